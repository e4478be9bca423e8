#!/usr/bin/python3
"""granular/powder must refuse bad input with a LAMMPS error naming the problem. jkr without a
history model is refused where LAMMPS has no slot for its contact flag (29 Sep 2021) and runs where
LAMMPS keeps it itself (the 2023+ GRANULAR API)."""
import sys
import os
from meltdem.testing.lammps_run import check_errors, lammps_version, printed_value, run
from meltdem.testing.report import check_relative, report

T = "dem.restitution.bad_input"
HEAD = """units {units}
atom_style sphere
comm_modify vel yes
region box block -1e-4 1e-4 -1e-4 1e-4 -1e-4 1e-4
create_box 2 box
create_atoms 1 single 0 0 0
pair_style granular/powder
"""
GOOD = "pair_coeff 1 1 hertz/material 200e9 0.5 0.3 damping tsuji tangential linear_nohistory 1.0 0.0\n"
cases = [
    ("e > 1", "si", "pair_coeff * * hertz/material 200e9 1.2 0.3 damping tsuji tangential linear_nohistory 1.0 0.0\n",
     "restitution e must lie in (0,1]"),
    ("e = 0", "si", "pair_coeff * * hertz/material 200e9 0 0.3 damping tsuji tangential linear_nohistory 1.0 0.0\n",
     "restitution e must lie in (0,1]"),
    ("alpha < 0", "si",
     "pair_coeff * * hertz/material 200e9 0.5 0.3 damping tsuji/alpha -1 tangential linear_nohistory 1.0 0.0\n",
     "tsuji/alpha must be >= 0"),
    ("alpha missing", "si", "pair_coeff * * hertz/material 200e9 0.5 0.3 damping tsuji/alpha\n",
     "damping tsuji/alpha needs a value"),
    ("tsuji/alpha twice", "si",
     "pair_coeff * * hertz/material 200e9 0.5 0.3 damping tsuji/alpha 1 damping tsuji/alpha 2\n",
     "damping given twice"),
    ("tsuji with hooke", "si",
     "pair_coeff * * hooke 1e5 0.5 damping tsuji tangential linear_nohistory 1.0 0.0\n",
     "damping tsuji needs normal model hertz/material, hertz, dmt"),
    ("unset mixed pair", "si",
     GOOD + "pair_coeff 2 2 hertz/material 100e9 0.5 0.3 damping tsuji tangential linear_nohistory 1.0 0.0\nrun 0\n",
     "pair_coeff 1 2 not set"),
    ("tsuji with limit_damping", "si",
     "pair_coeff * * hertz/material 200e9 0.5 0.3 damping tsuji tangential linear_nohistory 1.0 0.0 limit_damping\n",
     "cannot be combined with limit_damping"),
    ("impact_speed <= 0", "si", "pair_style granular/powder impact_speed -2\n", "impact_speed must be > 0"),
    ("impact_speed missing", "si", "pair_style granular/powder impact_speed\n", "impact_speed needs a value"),
    ("impact_speed not a number", "si", "pair_style granular/powder impact_speed fast\n",
     "Expected floating point parameter"),
    ("two cutoffs", "si", "pair_style granular/powder 1e-5 2e-5\n", "expected [cutoff] [impact_speed V]"),
    ("non-SI units", "metal",
     "pair_coeff * * hertz/material 200e9 0.5 0.3 damping tsuji tangential linear_nohistory 1.0 0.0\nrun 0\n",
     "requires units si"),
]
JKR = "pair_coeff * * jkr 200e9 0.5 0.3 0.1 damping tsuji tangential linear_nohistory 1.0 0.0\n"
NEW_GRANULAR_API = lammps_version() > 20210929
if not NEW_GRANULAR_API:
    cases.append(("jkr without a history model", "si", JKR,
                  "jkr needs a tangential, rolling or twisting model with history"))
ok = check_errors(T, [(what, HEAD.format(units=units) + tail, expect) for what, units, tail, expect in cases])
if NEW_GRANULAR_API:
    text = HEAD.format(units="si") + JKR + "set group all diameter 2e-5\nfix 1 all nve/sphere\nrun 10\n"
    rc, out = run(text, check=False)
    ran = rc == 0 and "Loop time" in out and not any(line.startswith("ERROR") for line in out.splitlines())
    if not ran:
        print(out[-2000:])
    ok &= report(T, "jkr without a history model (LAMMPS >= 2023 keeps the contact flag itself): 10 steps",
                 "runs" if ran else f"exit code {rc}", "runs", "exact", ran)

# the words of pair_coeff in the orders LAMMPS takes: tsuji/alpha's value before the normal model is
# the same alpha (coupling::restitution_for_alpha(1.5) = 0.05833, the head-on collision of
# restitution.py) where the stock parser takes that order (29 Sep 2021); the 2023+ parser wants the
# normal model first and stops with its own error
with open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "in.head_on")) as f:
    HEAD_ON = f.read()
ORDERS = (("normal model first", "hertz/material 200e9 0.5 0.3 damping tsuji/alpha 1.5 tangential"),
          ("tsuji/alpha first", "damping tsuji/alpha 1.5 hertz/material 200e9 0.5 0.3 tangential"))
HEAD_ON_VARS = dict(v=10, style="granular/powder", dt=1e-10, n=3000)
for what, words in ORDERS:
    text = HEAD_ON.replace("hertz/material 200e9 ${e} 0.3 damping ${damp} tangential", words)
    if what == "tsuji/alpha first" and NEW_GRANULAR_API:
        for k, v in HEAD_ON_VARS.items():
            text = text.replace("${%s}" % k, str(v))
        ok &= check_errors(T, [(f"{what} (LAMMPS >= 2023: the normal model comes first)", text,
                                "Illegal model type damping")])
        continue
    _, out = run(text, variables=HEAD_ON_VARS)
    ok &= check_relative(T, f"e for tsuji/alpha 1.5 at 20 m/s, {what}", printed_value(out, "RESULT"), 0.0583279, 0.01)
sys.exit(0 if ok else 1)
