#!/usr/bin/env python3
"""Bad input to the coupled solver: a clear message before the first step.

The Codina2019 §2.3 case (tests/coupling/thesis_particle, build()) with a short end time runs
cleanly; each variant breaks one thing (the LAMMPS input, the particles sub-dictionary, the
metal data, the switches) and runs meltdemFoam serially under a time limit. A variant passes
when the solver
  - exits with a non-zero code that is not a signal or a trap (no segfault, no hang: a run past
    the time limit fails),
  - takes no time step (no 'Time = ' line in its output), and
  - prints a message holding the expected fragments (an OpenFOAM FatalIOError naming the entry,
    or LAMMPS's own ERROR line where LAMMPS rejects the input while reading it or stops inside
    its sub-cycles: meltdemFoam passes LAMMPS's ERROR and WARNING lines to its output).
The clean case must run its few steps to the end, so a variant cannot pass by breaking
something else.
With --np N every case is decomposed (mesh split along the channel) and run with mpirun -np N:
the message must come the same way, and no rank may hang.
usage: bad_input.py [--np N] [--keep] [--only NAME ...]
"""
import os
import re
import signal
import subprocess
import sys
import tempfile

from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_at_most, report
from meltdem.testing.thesis_case import thesis_particle

tp = thesis_particle()

LX, LY, LZ = cc.CHANNEL["lx"], cc.CHANNEL["ly"], cc.CHANNEL["lz"]

TEST = "coupling.bad_input"
TIMEOUT = 90  # s per run; the clean case takes a few seconds
MARGIN = 1e-4  # the LAMMPS box of build() extends the mesh by this on every side
STEPS = 3  # fluid steps of the clean case


def edit(case, rel, old, new, count=1):
    """Replace old by new in a case file; the text must be there (the variant would otherwise
    test nothing)."""
    path = os.path.join(case, rel)
    txt = open(path).read()
    if isinstance(old, re.Pattern):
        txt, n = old.subn(new, txt, count=count)
    else:
        n = txt.count(old)
        txt = txt.replace(old, new, count)
    assert n >= 1, f"{rel}: {old!r} not found"
    open(path, "w").write(txt)


LMP, PROPS = "in.particles", "constant/meltdemProperties"
MELT_FIX = re.compile(r"^fix melt all powder/melt .*$", re.M)
BOX = re.compile(r"^region box block .*$", re.M)
PARTICLE = re.compile(r"^create_atoms 1 single .*$", re.M)
FIX_LINE = f"fix melt all powder/melt cp {tp.CP_P!r} Tmelt {tp.TM!r} latent {tp.L!r} temp 0.0"


def drop_lines(case, rel, pattern):
    edit(case, rel, re.compile(pattern, re.M), "", count=0)


# name -> (what is broken, edit(case), fragments the message must hold)
VARIANTS = {
    "units_metal": (
        "LAMMPS input in units metal",
        lambda c: edit(c, LMP, "units si", "units metal"),
        ["units si"]),
    "units_lj": (
        "LAMMPS input in units lj",
        lambda c: edit(c, LMP, "units si", "units lj"),
        ["units si"]),
    "particle_outside_mesh": (
        "particle centre above the mesh (inside the LAMMPS box)",
        lambda c: edit(c, LMP, PARTICLE,
                       f"create_atoms 1 single {LX / 2!r} {LY + MARGIN / 2!r} {LZ / 2!r}"),
        ["particle 1", "outside the mesh"]),
    "box_smaller_than_mesh": (
        "LAMMPS box 0.3 mm short of the mesh in x",
        lambda c: edit(c, LMP, BOX,
                       f"region box block {-MARGIN!r} {LX - 3e-4!r} {-MARGIN!r} {LY + MARGIN!r} "
                       f"{-MARGIN!r} {LZ + MARGIN!r}"),
        ["mismatched domains", "LAMMPS box in x"]),
    "periodic_box_not_mesh": (
        "LAMMPS box periodic in x but wider than the mesh",
        lambda c: edit(c, LMP, "boundary f f f", "boundary p f f"),
        ["mismatched domains", "periodic"]),
    "gravity_mismatch": (
        "fix gravity 9.81 m/s2 in LAMMPS, constant/g zero",
        lambda c: edit(c, LMP, "thermo 200", "thermo 200\nfix grav all gravity 9.81 vector 0 -1 0"),
        ["mismatched gravity", "(0 -9.81 0)", "constant/g is (0 0 0)"]),
    "missing_lammpsInput": (
        "no lammpsInput entry in particles",
        lambda c: drop_lines(c, PROPS, r"^\s*lammpsInput .*\n"),
        ["missing entry 'lammpsInput'"]),
    "lammpsInput_not_found": (
        "lammpsInput names a file that does not exist",
        lambda c: edit(c, PROPS, "lammpsInput     in.particles;", "lammpsInput     in.nothere;"),
        ["lammpsInput", "cannot open", "in.nothere"]),
    "lammpsInput_directory": (
        "lammpsInput names a folder (constant)",
        lambda c: edit(c, PROPS, "lammpsInput     in.particles;", "lammpsInput     constant;"),
        ["lammpsInput", "cannot open", "constant (missing, empty or not a file)"]),
    "lammpsInput_empty": (
        "lammpsInput is an empty file",
        lambda c: open(os.path.join(c, LMP), "w").close(),
        ["lammpsInput", "cannot open", "in.particles (missing, empty or not a file)"]),
    "unknown_distribution": (
        "distribution cells (unknown model)",
        lambda c: edit(c, PROPS, re.compile(r"distribution\s+\w+;"), "distribution    cells;"),
        ["distribution", "cells"]),
    "demStepsPerFluidStep_zero": (
        "demStepsPerFluidStep 0",
        lambda c: edit(c, PROPS, "demStepsPerFluidStep auto;", "demStepsPerFluidStep 0;"),
        ["demStepsPerFluidStep"]),
    "heatExchange_unknown": (
        "heatExchange explicit (unknown mode)",
        lambda c: edit(c, PROPS, "demStepsPerFluidStep auto;",
                       "demStepsPerFluidStep auto;\n    heatExchange explicit;"),
        ["heatExchange", "twoBody or implicit", "explicit"]),
    "particles_unknown_entry": (
        "heatexchange implicit (a misspelt entry of particles)",
        lambda c: edit(c, PROPS, "demStepsPerFluidStep auto;",
                       "demStepsPerFluidStep auto;\n    heatexchange implicit;"),
        ["unknown entry 'heatexchange'", "particles"]),
    "no_melt_fix": (
        "no fix powder/melt in the LAMMPS input",
        lambda c: (edit(c, LMP, MELT_FIX, ""), drop_lines(c, LMP, r"^thermo_style .*\n")),
        ["0 fix powder/melt", "exactly one"]),
    "two_melt_fixes": (
        "two fix powder/melt in the LAMMPS input",
        lambda c: edit(c, LMP, MELT_FIX, FIX_LINE + "\n" + FIX_LINE.replace("fix melt ", "fix melt2 ")),
        ["2 fix powder/melt", "exactly one"]),
    "cp_mismatch": (
        "metal cp 50 in meltdemProperties, fix powder/melt cp 48.35",
        lambda c: edit(c, PROPS, f"cp {tp.CP_P!r};", "cp 50;"),
        ["cp 50 differs from fix \"melt\" powder/melt cp"]),
    "latent_mismatch": (
        "metal L 2.7e5 in meltdemProperties, fix powder/melt latent 2.74e5",
        lambda c: edit(c, PROPS, f"L {tp.L!r};", "L 2.7e5;"),
        ["L 270000 differs from fix \"melt\" powder/melt latent"]),
    "Tmelt_outside_solidus_liquidus": (
        "fix powder/melt Tmelt 1100 outside [Tsolidus 999, Tliquidus 1000]",
        lambda c: edit(c, LMP, f"Tmelt {tp.TM!r}", "Tmelt 1100.0"),
        ["Tmelt", "outside [Tsolidus, Tliquidus]"]),
    "missing_metal_L": (
        "metal L missing (material data)",
        lambda c: edit(c, PROPS, f" L {tp.L!r};", ""),
        ["missing entry 'L'"]),
    "one_way_implicit_heat": (
        "one-way coupling (flow off) with heatExchange implicit, which it cannot feed back",
        lambda c: (edit(c, PROPS, "    flow on;", "    flow off;"),
                   edit(c, PROPS, "demStepsPerFluidStep auto;",
                        "demStepsPerFluidStep auto;\n    heatExchange implicit;")),
        ["heatExchange implicit", "one-way"]),
    "missing_particles_dict": (
        "physics particles on without the particles sub-dictionary",
        lambda c: edit(c, PROPS, re.compile(r"^particles\s*\{[^}]*\}\n", re.M), ""),
        ["sub-dictionary 'particles'"]),
    "solid_metal_without_energy": (
        "isothermal particles (energy off) with the solid_metal keyword",
        lambda c: (edit(c, PROPS, "    energy on;", "    energy off;"),
                   edit(c, LMP, MELT_FIX, FIX_LINE + " solid_metal 1e9 0.5")),
        ["solid_metal", "'energy on'"]),
    "lammps_error_in_run": (
        "a LAMMPS error inside the first DEM sub-cycles (fix print of 1/(step-3))",
        lambda c: edit(c, LMP, "thermo 200", 'thermo 200\nvariable bad equal 1/(step-3)\n'
                       'fix pr all print 3 "${bad}"'),
        ["ERROR on proc", "Divide by 0", "Last command: run"]),
    "alpha_above_one": (
        "0/alpha.metal internalField 1.5 (ran with rc 0)",
        lambda c: edit(c, "0/alpha.metal", "internalField uniform 0.0;", "internalField uniform 1.5;"),
        ["0/alpha.metal", "outside [0, 1]", "metal volume fraction"]),
    "alpha_negative": (
        "0/alpha.metal internalField -0.2 (stopped after step 1 blaming the particles' heat exchange)",
        lambda c: edit(c, "0/alpha.metal", "internalField uniform 0.0;", "internalField uniform -0.2;"),
        ["0/alpha.metal", "outside [0, 1]"]),
    "negative_density": (
        "metal rho -8020 in transportProperties (stopped after step 1 blaming the heat exchange)",
        lambda c: edit(c, "constant/transportProperties", "rho 8020.0;", "rho -8020.0;"),
        ["rho -8020", "must be positive", "transportProperties"]),
    "lammps_syntax_error": (
        "an unknown command in the LAMMPS input",
        lambda c: edit(c, LMP, "neighbor 1e-5 bin", "neighbour 1e-5 bin"),
        ["ERROR", "neighbour"]),
}


def build(case):
    tp.build(case, "centre")
    end = STEPS * 1e-5
    edit(case, "system/controlDict", re.compile(r"^endTime .*;$", re.M), f"endTime {end!r};")


def run(case, np_=1):
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    cmd = [fc.solver()]
    if np_ > 1:
        cc.decompose(case, np_)
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_)] + cmd + ["-parallel"]
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    # own process group: a hang is killed with every rank
    p = subprocess.Popen(cmd, cwd=case, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, env=env,
                         start_new_session=True)
    try:
        out, _ = p.communicate(timeout=TIMEOUT)
        rc, out = p.returncode, out.decode(errors="replace")
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        out, _ = p.communicate()
        rc, out = None, out.decode(errors="replace") + f"\n[killed after {TIMEOUT} s]\n"
    with open(os.path.join(case, "log.meltdemFoam"), "w") as f:
        f.write(out)
    return rc, out


def steps_taken(out):
    return len(re.findall(r"^Time = ", out, re.M))


def message(out):
    """The error text: OpenFOAM's fatal block, or LAMMPS's ERROR line(s)."""
    i = out.find("FOAM FATAL")
    if i >= 0:
        return out[i:]
    return "\n".join(line for line in out.splitlines() if "ERROR" in line or line.startswith("Last command"))


def main():
    keep = "--keep" in sys.argv
    only = sys.argv[sys.argv.index("--only") + 1:] if "--only" in sys.argv else None
    np_ = int(sys.argv[sys.argv.index("--np") + 1]) if "--np" in sys.argv else 1
    test = TEST + (f".np{np_}" if np_ > 1 else "")
    work = tempfile.mkdtemp(prefix="meltdem-coupling-bad-input-")
    ok = True

    clean = os.path.join(work, "clean")
    build(clean)
    rc, out = run(clean, np_)
    n = steps_taken(out)
    ok &= report(test, f"clean case runs its {STEPS} steps to the end (exit code, steps)", f"rc {rc}, {n} steps",
                 f"rc 0, {STEPS} steps", "exact", rc == 0 and n == STEPS and "\nEnd" in out)

    for name, (what, breakit, words) in VARIANTS.items():
        if only and name not in only:
            continue
        case = os.path.join(work, name)
        build(case)
        breakit(case)
        rc, out = run(case, np_)
        text = message(out)
        killed = (rc is None or rc < 0 or rc >= 128
                  or re.search(r"Foam::sigSegv|Foam::sigFpe|printStack|Segmentation fault", out))
        named = bool(text) and all(w in text for w in words)
        first = " ".join(line.strip() for line in text.splitlines()[:6] if line.strip())[:200] if text else out[-200:]
        print(f"{name}: rc {rc}; {first!r}")
        ok &= report(test, f"{what}: stops with a message holding {words}",
                     f"rc {rc}, {'signal/timeout' if killed else 'exit'}, "
                     f"{'names it' if named else 'does not name it'}",
                     "non-zero exit naming the problem", "exact", rc not in (0, None) and not killed and named)
        ok &= check_at_most(test, f"{what}: fluid steps taken before the message", steps_taken(out), 0)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
