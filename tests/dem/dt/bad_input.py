#!/usr/bin/python3
"""fix powder/dt and compute powder/overlap refuse bad input with a LAMMPS error naming
the problem."""
from meltdem.testing.lammps_run import check_errors
from meltdem.testing.dem import two_spheres

TEST = "dem.dt.bad_input"
BASE = two_spheres(-6e-5, 6e-5, 20e-6, 30e-6, 1.0, -1.0)


def fix(args, text=BASE):
    return text + f"fix dt all powder/dt {args}\nrun 0\n"


def comp(args):
    return BASE + f"compute ov all powder/overlap {args}\nthermo_style custom step c_ov[1]\nrun 0\n"


PAIR = "pair_coeff * * hertz/material 200000000000.0 0.0 0.3 damping velocity tangential linear_nohistory 0 0"
cases = [
    ("missing steps", fix("every 2"), "requires keyword steps"),
    ("no arguments", fix(""), "requires keyword steps"),
    ("steps 0", fix("steps 0"), "steps must be > 0"),
    ("steps negative", fix("steps -5"), "steps must be > 0"),
    ("steps without value", fix("steps"), "keyword steps needs 1 value"),
    ("steps not a number", fix("steps ten"), "Expected floating point parameter"),
    ("every 0", fix("steps 10 every 0"), "every must be > 0"),
    ("max negative", fix("steps 10 max -1e-9"), "max must be > 0"),
    ("interval 0", fix("steps 10 interval 0"), "interval must be > 0"),
    ("vmin 0", fix("steps 10 vmin 0"), "vmin must be > 0"),
    ("unknown keyword", fix("steps 10 colour red"), "unknown keyword colour"),
    ("units metal", fix("steps 10", BASE.replace("units si", "units metal")), "requires units si"),
    ("pair style without E (granular hertz)",
     fix("steps 10", BASE.replace(PAIR, "pair_coeff * * hertz 1e5 0.5 tangential linear_nohistory 0 0")),
     "must use hertz/material"),
    ("pair style not granular (gran/hertz/history)",
     fix("steps 10", BASE.replace("pair_style granular", "pair_style gran/hertz/history 1e5 NULL 0 0 0.5 0")
         .replace(PAIR, "pair_coeff * *")), "requires pair_style granular or granular/powder"),
    ("atom_style atomic", fix("steps 10", "units si\natom_style atomic\nregion b block 0 1 0 1 0 1\n"
                              "create_box 1 b\npair_style granular\n"), "requires atom_style sphere"),
    ("compute threshold 0", comp("threshold 0"), "threshold must be > 0"),
    ("compute threshold without value", comp("threshold"), "keyword threshold needs 1 value"),
    ("compute unknown keyword", comp("limit 3"), "unknown keyword limit"),
    ("compute warn 0", comp("warn 0"), "warn must be no or a number of steps > 0"),
]

ok = check_errors(TEST, cases)
raise SystemExit(0 if ok else 1)
