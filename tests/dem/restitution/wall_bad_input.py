#!/usr/bin/python3
"""fix wall/gran/powder and wall/gran/region/powder must refuse bad input with a LAMMPS
error naming the problem (never a crash)."""
import sys
from meltdem.testing.lammps_run import check_errors

T = "dem.restitution.wall_bad_input"
HEAD = """units {units}
atom_style {atom_style}
boundary p p f
comm_modify vel yes
region box block -1e-4 1e-4 -1e-4 1e-4 0 1e-4
create_box 1 box
region cup cylinder z 0 0 8e-5 0 1e-4 side in
create_atoms 1 single 0 0 5e-5
"""
HM = "hertz/material 200e9 0.5 0.3"
TAN = "tangential linear_nohistory 1.0 0.0"
W = "fix w all wall/gran/powder granular"
WR = "fix w all wall/gran/region/powder granular"
cases = [
    ("non-SI units", "metal", f"{W} {HM} damping tsuji {TAN} zplane 0 NULL", "requires units si"),
    ("atom style not sphere", "si", f"{W} {HM} damping tsuji {TAN} zplane 0 NULL", "requires atom style sphere",
     "atomic"),
    ("too few arguments", "si", f"{W}", "too few arguments"),
    ("tsuji with limit_damping", "si", f"{W} {HM} damping tsuji {TAN} limit_damping zplane 0 NULL",
     "cannot be combined with limit_damping"),
    ("impact_speed <= 0", "si", f"{W} {HM} damping tsuji impact_speed 0 {TAN} zplane 0 NULL",
     "impact_speed must be > 0"),
    ("impact_speed missing", "si", f"{W} {HM} damping tsuji impact_speed", "impact_speed needs 1 value"),
    ("hooke interaction style", "si", "fix w all wall/gran/powder hooke 1e5 NULL 0 NULL 0.5 0 zplane 0 NULL",
     "supports only the 'granular' interaction style"),
    ("e > 1", "si", f"{W} hertz/material 200e9 1.2 0.3 damping tsuji {TAN} zplane 0 NULL",
     "restitution e must lie in (0,1]"),
    ("e = 0", "si", f"{W} hertz/material 200e9 0 0.3 damping tsuji {TAN} zplane 0 NULL",
     "restitution e must lie in (0,1]"),
    ("alpha < 0", "si", f"{W} {HM} damping tsuji/alpha -1 {TAN} zplane 0 NULL", "tsuji/alpha must be >= 0"),
    ("alpha missing", "si", f"{W} {HM} damping tsuji/alpha", "damping tsuji/alpha needs 1 value"),
    ("alpha not a number", "si", f"{W} {HM} damping tsuji/alpha x {TAN} zplane 0 NULL",
     "Expected floating point parameter"),
    ("E <= 0", "si", f"{W} hertz/material -2e9 0.5 0.3 damping tsuji {TAN} zplane 0 NULL", "E must be > 0"),
    ("Poisson ratio > 0.5", "si", f"{W} hertz/material 200e9 0.5 0.7 damping tsuji {TAN} zplane 0 NULL",
     "Poisson's ratio must lie in (-1,0.5]"),
    ("hertz/material values missing", "si", f"{W} hertz/material 200e9", "hertz/material needs 3 value"),
    ("tsuji with hooke normal model", "si", f"{W} hooke 1e5 0.5 damping tsuji {TAN} zplane 0 NULL",
     "damping tsuji needs normal model hertz/material, hertz, dmt or jkr"),
    ("wall_material E <= 0", "si", f"{W} {HM} damping tsuji wall_material 0 0.3 {TAN} zplane 0 NULL",
     "wall_material E must be > 0"),
    ("wall_material nu out of range", "si", f"{W} {HM} damping tsuji wall_material 70e9 0.6 {TAN} zplane 0 NULL",
     "wall_material Poisson's ratio must lie in (-1,0.5]"),
    ("wall_material missing values", "si", f"{W} {HM} damping tsuji wall_material", "wall_material needs 1 value"),
    ("wall_material without material model", "si", f"{W} hertz 1e5 0.5 wall_material rigid {TAN} zplane 0 NULL",
     "wall_material needs normal model hertz/material"),
    ("no wall style", "si", f"{W} {HM} damping tsuji {TAN}", "missing wall style"),
    ("region wall in wall/gran/powder", "si", f"{W} {HM} damping tsuji {TAN} region cup",
     "region walls need fix wall/gran/region/powder"),
    ("plane wall in wall/gran/region/powder", "si", f"{WR} {HM} damping tsuji {TAN} zplane 0 NULL",
     "the wall style must be 'region ID'"),
    ("unknown region", "si", f"{WR} {HM} damping tsuji {TAN} region nowhere",
     ("Region ID for fix wall/gran/region does not exist", "Region nowhere for fix wall/gran/region does not exist")),
    ("unknown keyword", "si", f"{W} {HM} damping tsuji {TAN} bogus 1 zplane 0 NULL",
     ("Illegal fix wall/gran command", "Unknown fix wall/gran keyword bogus")),
    ("wall in periodic dimension", "si", f"{W} {HM} damping tsuji {TAN} xplane 0 NULL",
     "Cannot use wall in periodic dimension"),
]
inputs = []
for case in cases:
    what, units, line, expect = case[:4]
    atom_style = case[4] if len(case) > 4 else "sphere"
    inputs.append((what, HEAD.format(units=units, atom_style=atom_style) + line + "\nrun 0\n", expect))
sys.exit(0 if check_errors(T, inputs) else 1)
