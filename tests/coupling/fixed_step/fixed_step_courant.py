#!/usr/bin/env python3
"""A fixed sub-cycle (demStepsPerFluidStep N) overrides the step adjustTimeStep chose
(doc/foam_particle_coupling.rst); where that runs the flow past maxCo the solver says so.

The Codina2019 §2.3 particle (thesis_particle.py) falling 2 m/s through gas at rest, 0.2 ms, with
maxCo 5e-3: the gas the particle drags moves (Courant number 0.03 at 10 us), so from the second
step on the step the Courant limit allows is about 6 times below the fixed 10 us. Checks (label
coupling):
  - demStepsPerFluidStep 10: one warning naming demStepsPerFluidStep 10 and the Courant limit
    (once per run, not per step) and the run completes;
  - demStepsPerFluidStep auto, same case: no such warning (the step follows the limit);
  - demStepsPerFluidStep 10 with adjustTimeStep no: no warning (the user fixed the step).
usage: fixed_step_courant.py [--keep]
"""
import os
import re
import sys
import tempfile

from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute
from meltdem.testing.thesis_case import thesis_particle

tp = thesis_particle()

TEST = "coupling.fixed_step_courant"
WARNING = "fixes the fluid step at"


def run(case, sub_cycles, adjustable=True):
    """Warnings about a fixed step past the limit in the log, and whether the run reached its end."""
    tp.build(case, "centre", fluid_dt=1e-5, max_co=5e-3)
    p = os.path.join(case, "constant", "meltdemProperties")
    properties = open(p).read().replace("demStepsPerFluidStep auto;", f"demStepsPerFluidStep {sub_cycles};")
    open(p, "w").write(properties)
    c = os.path.join(case, "system", "controlDict")
    control = re.sub(r"\nendTime [^;]*;", "\nendTime 2e-4;", open(c).read())
    if not adjustable:
        control = re.sub(r"\nadjustTimeStep [^;]*;", "\nadjustTimeStep no;", control)
    open(c, "w").write(control)
    cc.run_solver(case)
    log = open(os.path.join(case, "log.meltdemFoam"), errors="replace").read()
    said = [ln for ln in log.splitlines() if WARNING in ln]
    done = "End" in log.splitlines()[-3:] or "\nEnd\n" in log[-200:]
    if not done:
        print(f"{case}: log.meltdemFoam ends\n" + "\n".join(log.splitlines()[-30:]))
    return said, done


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-fixed-step-")
    said, done = run(os.path.join(work, "fixed"), 10)
    print("\n".join(said))
    ok = check_absolute(TEST, "demStepsPerFluidStep 10 past maxCo: warnings naming it (once per run)",
                        float(sum("demStepsPerFluidStep 10" in s and "Courant limit" in s for s in said)), 1.0, 0)
    ok &= check_absolute(TEST, "demStepsPerFluidStep 10 past maxCo: run completes (1 = yes)", float(done), 1.0, 0)
    said, done = run(os.path.join(work, "auto"), "auto")
    ok &= check_absolute(TEST, "demStepsPerFluidStep auto: fixed-step warnings", float(len(said)), 0.0, 0)
    said, done = run(os.path.join(work, "fixed_dt"), 10, adjustable=False)
    ok &= check_absolute(TEST, "demStepsPerFluidStep 10, adjustTimeStep no: fixed-step warnings",
                         float(len(said)), 0.0, 0)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
