#!/usr/bin/python3
"""fix powder/melt refuses bad input with a LAMMPS error that names the problem."""
import sys

from meltdem.testing.lammps_run import check_errors, run
from meltdem.testing.report import report
from melt_common import HEADER

TEST = "dem.melt.bad_input"
OK_ARGS = "cp 48.35 Tmelt 1000 latent 2.7e5"
AMB = "ambient 1500 100 1.6 2e-5 520 0 0 0"
ATOM = "create_atoms 1 single 0 0 0\n"


def fix(args, header=HEADER):
    return header + ATOM + f"fix m all powder/melt {args}\nrun 0\n"


cases = [
    ("missing cp", fix("Tmelt 1000 latent 2.7e5"), "requires keyword cp"),
    ("two fix powder/melt", fix(OK_ARGS).replace("\nrun 0\n", f"\nfix m2 all powder/melt {OK_ARGS}\nrun 0\n"),
     "both act on the particles"),
    ("negative cp", fix("cp -1 Tmelt 1000 latent 2.7e5"), "cp must be > 0"),
    ("cp without value", fix("Tmelt 1000 latent 2.7e5 cp"), "keyword cp needs 1 value"),
    ("missing Tmelt", fix("cp 48.35 latent 2.7e5"), "requires keyword Tmelt"),
    ("negative Tmelt", fix("cp 48.35 Tmelt -5 latent 2.7e5"), "Tmelt must be > 0"),
    ("missing latent", fix("cp 48.35 Tmelt 1000"), "requires keyword latent"),
    ("negative latent", fix("cp 48.35 Tmelt 1000 latent -2"), "latent must be > 0"),
    ("non-numeric cp", fix("cp abc Tmelt 1000 latent 2.7e5"), "Expected floating point parameter"),
    ("wrong drag keyword", fix(OK_ARGS + " drag stokes"), "drag model stokes unknown"),
    ("ambient with 5 values", fix(OK_ARGS + " ambient 1500 100 1.6 2e-5 520"), "ambient needs 8 values"),
    ("ambient cut short by a keyword", fix(OK_ARGS + " ambient 1500 100 1.6 2e-5 520 0 0 drag thesis"),
     "ambient needs 8 values"),
    ("ambient zero viscosity", fix(OK_ARGS + " ambient 1500 100 1.6 0 520 0 0 0"), "viscosity MUF must be > 0"),
    ("ambient zero conductivity", fix(OK_ARGS + " ambient 1500 0 1.6 2e-5 520 0 0 0"),
     "conductivity KF must be > 0"),
    ("temp above Tmelt", fix(OK_ARGS + " temp 1200 " + AMB), "temp 1200 outside [0, Tmelt"),
    ("negative handover diameter", fix(OK_ARGS + " handover -1e-6"), "handover diameter must be >= 0 m"),
    ("handover without value", fix(OK_ARGS + " handover"), "keyword handover needs 1 value"),
    ("unknown keyword", fix(OK_ARGS + " colour red"), "unknown keyword colour"),
    ("atom_style sphere without radius variation",
     fix(OK_ARGS, HEADER.replace("atom_style sphere 1", "atom_style sphere")), "requires atom_style sphere 1"),
    ("atom_style atomic", fix(OK_ARGS, HEADER.replace("atom_style sphere 1", "atom_style atomic")),
     "requires atom_style sphere 1"),
    ("units metal", fix(OK_ARGS, HEADER.replace("units si", "units metal")), "requires units si"),
]

ok = check_errors(TEST, cases)

# and the valid command runs
rc, out = run(fix(OK_ARGS + " temp 300 drag schiller-naumann " + AMB), check=False)
ok &= report(TEST, "valid command", f"exit code {rc}", "exit code 0", "exact", rc == 0)
sys.exit(0 if ok else 1)
