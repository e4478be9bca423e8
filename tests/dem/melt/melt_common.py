"""Helpers of the fix powder/melt tests: run meltdem-lmp on an input text, read thermo."""
import tempfile

from meltdem.testing.lammps_run import run


# a single particle in a large periodic box, SI units, radius changes allowed
HEADER = """units si
atom_style sphere 1
atom_modify map array
boundary p p p
region box block -0.01 0.01 -0.01 0.01 -0.01 0.01
create_box 1 box
comm_modify vel yes
neighbor 1e-4 bin
"""

# the Codina2019 §2.3 particle (d, rho, cp, Tm, T0) melting in the table 2.2 gas (Tf, k), moving
# with it at 2 m/s down; latent heat: E_latent = 0.248611 J for m = 9.069e-7 kg
THESIS_MELTING = (600e-6, 8020.0, 48.35, 1000.0, 0.0, 1500.0, 100.0)
THESIS_LATENT = 0.248611 / 9.069e-7
THESIS_GAS = f"{THESIS_MELTING[5]} {THESIS_MELTING[6]} 1.6115 2.1e-5 5210.928 0 -2 0"

# per-step thermo of the fix's six ledger columns
LEDGER_OUTPUT = """fix nve all nve/sphere
thermo_style custom step atoms f_m[1] f_m[2] f_m[3] f_m[4] f_m[5] f_m[6]
thermo_modify format float %.17g
thermo 1
"""


def run_through_restart(text, procs, melt, dt, np, before, after):
    """Run text for `before` steps on np ranks, write_restart, and go on from the file in a new
    process for `after` steps (procs, melt: the processors and fix lines to give again); returns
    the output of both."""
    with tempfile.TemporaryDirectory() as wd:
        _, out = run(text + f"run {before}\nwrite_restart half.restart\n", np=np, cwd=wd)
        _, out2 = run(procs + "read_restart half.restart\ncomm_modify vel yes\nneighbor 1e-4 bin\n"
                      f"timestep {dt}\n" + melt + LEDGER_OUTPUT + f"run {after}\n", np=np, cwd=wd)
    return out + out2
