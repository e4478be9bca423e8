#!/usr/bin/python3
"""meltdemplugin.so: MeltDEM's styles as a LAMMPS plugin.

lammps.plugin: the plugin loaded as "plugin load" loads it (meltdem-plugin-loader, a stock
driver that links LAMMPS only) exports lammpsplugin_init, registers every project style and
runs the head-on restitution input with results identical to meltdem-lmp's; it does not
carry meltdem-lmp's post_create hook. lammps.plugin_load: "plugin load" in the installed
lmp (MELTDEM_PLUGIN_LMP, default lmp), skipped (exit 77) when that lmp lacks PLUGIN."""
import glob
import os
import re
import subprocess
import sys

from meltdem import paths
from meltdem.testing.lammps_run import run
from meltdem.testing.report import check_relative, report

MODE = sys.argv[1] if len(sys.argv) > 1 else "loader"
T = "lammps.plugin" if MODE == "loader" else "lammps.plugin_load"
PLUGIN = os.path.join(paths.bin_dir(), "..", "lib", "meltdemplugin.so")
HEAD_ON = os.path.join(paths.source_dir(), "tests", "dem", "restitution", "in.head_on")
VARS = dict(v=1, style="granular/powder", e=0.5, damp="tsuji", dt=1e-10, n=3000)


INSERT = open(os.path.join(paths.source_dir(), "tests", "lammps", "in.project_styles")).read()


def head_on(cmd, prefix=""):
    return run(prefix + open(HEAD_ON).read(), check=False, variables=VARS, exe=cmd)


def inserted(cmd, prefix=""):
    rc, out = run(prefix + INSERT, check=False, exe=cmd)
    hits = [w.split()[1] for w in out.splitlines() if w.startswith("INSERTED ")]
    if rc != 0 or not hits:
        print(out[-2000:])
    return hits[0] if rc == 0 and hits else None


def result(out):
    lines = [w.split()[1] for w in out.splitlines() if w.startswith("RESULT ")]
    return lines[0] if lines else None


lmp_cmd = [paths.binary("meltdem-lmp")]
rc, out = head_on(lmp_cmd)
reference = result(out)
if rc != 0 or reference is None:
    print(out[-3000:])
    sys.exit("meltdem-lmp failed on the head-on input")

if MODE == "stock":
    lmp = os.environ.get("MELTDEM_PLUGIN_LMP", "lmp")
    help_text = subprocess.run([lmp, "-h"], stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True).stdout
    packages = help_text.split("Installed packages:")[-1].split("List of")[0].split()
    if "PLUGIN" not in packages:
        print(f"SKIP: {lmp} was built without the PLUGIN package: 'plugin load' is not available "
              "(Debian's LAMMPS on bookworm and trixie); lammps.plugin tests the plugin with a loader")
        sys.exit(77)
    prefix = f"plugin load {os.path.abspath(PLUGIN)}\n"
    cmd = [lmp]
    rc, out = head_on(cmd, prefix)
else:
    symbols = subprocess.run(["nm", "-D", "--defined-only", PLUGIN], stdout=subprocess.PIPE, text=True,
                             check=True).stdout.split()
    ok_symbols = "lammpsplugin_init" in symbols and "_ZN9LAMMPS_NS6LAMMPS11post_createEv" not in symbols
    report(T, "exports lammpsplugin_init, defines no LAMMPS::post_create", ok_symbols, True, "exact",
           ok_symbols)
    if not ok_symbols:
        sys.exit(1)
    prefix = ""
    cmd = [os.path.join(paths.bin_dir(), "..", "tests", "bin", "meltdem-plugin-loader"), PLUGIN]
    rc, out = head_on(cmd)
    registered = [int(w.split()[1]) for w in out.splitlines() if w.startswith("PLUGIN_STYLES ")]
    headers = glob.glob(os.path.join(paths.source_dir(), "lammps-src", "*.h"))
    styles = sum(1 for h in headers for line in open(h) if re.match(r"(Fix|Compute|Pair)Style\(", line))
    n = registered[0] if registered else 0
    report(T, "styles registered through lammpsplugin_init (as the style headers declare)", n, styles, "exact",
           n == styles)
    if n != styles:
        print(out[-3000:])
        sys.exit(1)
measured = result(out)
if rc != 0 or measured is None:
    print(out[-3000:])
    report(T, "head-on input with the plugin's granular/powder", "failed", "runs", "exact", False)
    sys.exit(1)
ok = measured == reference
report(T, "e (prescribed 0.5) with the plugin's styles against meltdem-lmp (all digits)", measured, reference,
       "exact", ok)
ok &= check_relative(T, "e with the plugin's granular/powder at 2 m/s", float(measured), 0.5, 0.01)
n_plugin, n_lmp = inserted(cmd, prefix), inserted(lmp_cmd)
ok_insert = n_plugin is not None and n_plugin == n_lmp == "10"
report(T, "grains inserted by the plugin's fix powder/insert (with compute powder/overlap, fix powder/dt)",
       n_plugin, n_lmp, "exact", ok_insert)
ok &= ok_insert
sys.exit(0 if ok else 1)
