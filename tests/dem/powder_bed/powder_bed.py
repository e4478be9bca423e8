#!/usr/bin/python3
"""CI-sized powder bed of Codina2019 table 4.3/4.4 (examples/powder-bed/in.powder-bed).

Same input, material (E = 200 GPa, no softening), damping (alpha 1.5 particle, 1 wall),
friction, gravity x10, injection at -2 m/s and powder amount per floor area as the
example, on a 0.30 x 0.30 mm floor, periodic sideways (so the small box has no side-wall
layering), instead of 0.90 x 0.90 mm with walls: 153 instead of 1375 particles.

Checks (definitions in python/meltdem/analysis/beds.py and README.md):
  * feed: inserted + pending = requested at every thermo step once all are due; pending 0 and inserted =
    requested at the end; all particles still in the box.
  * no pop-corn, sampled every 100 steps (compute powder/overlap): no contact above
    overlap/R = 0.01, no pop-corn warning. 0.01 is 1.6 times the elastic Hertz peak of
    the hardest impact this pour can have (two equal spheres approaching at 2 x 2.01 m/s,
    delta_max/R = (2.776 rho U^2/E*)^0.4 = 0.0063, independent of size); pop-corn
    (Codina2019 §3.2.1) is an overlap beyond what the impact speed allows.
  * no particle faster than 2 x the largest free-fall speed sqrt(v0^2 + 2 g Ly) (the most
    a collision can hand a light particle): energy is not created.
  * settled: the run stopped on its own (all in, rms speed < 1 mm/s) before tend; the
    largest overlap/R at the end is below 1e-4 (resting contacts under 10 g: ~1e-6).
  * thickness H (height where the solid fraction profile falls to half its bulk value)
    vs Codina2019's ~60 um, tolerance 15 um (half a mean diameter: the thickness of a
    layer two particles thick depends on where its rough top is put; the mean column
    top is printed too);
  * packing V/(A H) (solid layer over thickness: Codina2019's compaction factor) inside
    the range of random poured beds 0.55-0.64, and vs Codina2019's 0.5 (+-0.05, XFAIL:
    a poured low-friction bed is denser).
Codina2019's amount (60 um at 0.5 = a 30 um solid layer) is used, so H = 30 um / packing.
"""
import math
import os
import subprocess
import tempfile

from meltdem import paths
from meltdem.analysis.beds import bed_stats
from meltdem.testing.lammps_run import lmp, thermo_runs
from meltdem.testing.report import check_absolute, check_at_most, report

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = paths.source_dir()

TEST = "dem.powder_bed.ci"
VSETTLE, POPCORN, TEND, EVERY = 0.001, 0.01, 15e-3, 100
G, V0, LY = 10 * 9.81, 2.0, 2.1e-4
with tempfile.TemporaryDirectory() as d:
    cmd = [lmp(), "-in", os.path.join(SRC, "examples", "powder-bed", "in.powder-bed"), "-log", "none",
           "-echo", "none", "-var", "Lx", "3e-4", "-var", "Lz", "3e-4", "-var", "sides", "periodic",
           "-var", "tend", str(TEND), "-var", "vsettle", str(VSETTLE), "-var", "popcorn", str(POPCORN),
           "-var", "every", str(EVERY), "-var", "dump", "bed.dump"]
    p = subprocess.run(cmd, cwd=d, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, timeout=600)
    if p.returncode != 0:
        print(p.stdout[-4000:])
        raise SystemExit(f"meltdem-lmp failed with exit code {p.returncode}")
    s = bed_stats(os.path.join(d, "bed.dump"))
out = p.stdout
rows = thermo_runs(out)[0]
N = int(next(line.split()[2] for line in out.splitlines() if line.startswith("BED N")))
last = rows[-1]
FEED_TIME = 5e-5  # the input's rate feeds all N within 50 us; after that every one is inserted or pending
fed = [r for r in rows if r["Time"] > 1.05 * FEED_TIME]

ok = True
ok &= check_absolute(TEST, "max |inserted + pending - requested| after the feed time", max(
    abs(r["f_feed[1]"] + r["f_feed[2]"] - N) for r in fed), 0, 0)
ok &= check_absolute(TEST, "particles inserted at the end (requested N)", last["f_feed[1]"], N, 0)
ok &= check_absolute(TEST, "particles pending at the end", last["f_feed[2]"], 0, 0)
ok &= check_absolute(TEST, "particles in the box at the end (none lost)", s["particles"], N, 0)
ok &= check_at_most(TEST, f"largest overlap/R over the run (every {EVERY} steps; pop-corn)",
                    max(r["c_ov[1]"] for r in rows), POPCORN)
ok &= check_at_most(TEST, f"contacts above overlap/R {POPCORN}, largest count over the run",
                    max(r["c_ov[2]"] for r in rows), 0)
ok &= report(TEST, "no pop-corn warning", "pop-corn at step" in out, False, "exact", "pop-corn at step" not in out)
vbound = 2 * math.sqrt(V0 ** 2 + 2 * G * LY)
ok &= check_at_most(TEST, "largest particle speed over the run [m/s] (2 x free-fall bound)",
                    max(r["c_ov[3]"] for r in rows), vbound)
ok &= check_at_most(TEST, "simulated time [s] (stopped as settled before tend)", last["Time"], 0.999 * TEND)
ok &= check_at_most(TEST, "rms particle speed at the end [m/s] (settled)", s["rms_speed"], VSETTLE)
ok &= check_at_most(TEST, "largest overlap/R at the end (resting contacts)", last["c_ov[1]"], 1e-4)
ok &= check_absolute(TEST, "bed thickness H [m] (thesis table 4.4: ~60 um)", s["thickness"], 60e-6, 15e-6)
ok &= check_absolute(TEST, "packing V/(A H) in the random poured range 0.55-0.64", s["packing_layer"], 0.595, 0.045)
ok &= check_absolute(TEST, "packing V/(A H) (thesis table 4.4 compaction factor 0.5)", s["packing_layer"], 0.5, 0.05,
                     xfail="a poured low-friction bed packs at 0.55-0.64; with DMT cohesion of 0.1 and 1 mJ/m^2 "
                           "the CI bed packs at 0.611/0.596 (bench/reduced_modulus.md); thesis's 0.5 not reproduced")
ke_ratio = s["rms_speed"] ** 2 / (2 * G * s["d_mean"])
loop = [line for line in out.splitlines() if line.startswith("Loop time")]
print(f"INFO particles {s['particles']}, simulated {last['Time'] * 1e3:.3f} ms, {loop[-1] if loop else ''}")
print(f"INFO slab packing phi_b (0.25-0.75 H) {s['packing_slab']:.3f}, top thickness (mean column top) "
      f"{s['top_thickness'] * 1e6:.2f} um, solid layer {s['solid_layer'] * 1e6:.2f} um, "
      f"largest speed {s['max_speed']:.3g} m/s, KE/(M g d_mean) {ke_ratio:.2e}")
raise SystemExit(0 if ok else 1)
