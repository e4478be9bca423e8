#!/usr/bin/python3
"""fix powder/insert refuses bad input with a LAMMPS error that names the problem; the
valid command (with temp through fix powder/melt) runs and sets the temperature."""
import os
import sys
import tempfile

from meltdem.testing.lammps_run import check_errors, run
from meltdem.testing.report import report
from insert_common import read_dump

TEST = "dem.insert.bad_input"
HEADER = """units si
atom_style sphere
boundary p p f
region box block 0 0.01 0 0.01 0 0.01
create_box 2 box
comm_modify vel yes
region ins block 0.001 0.009 0.001 0.009 0.001 0.009
pair_style granular 1.2e-3
pair_coeff * * hertz/material 5e6 0.5 0.3 damping tsuji tangential linear_nohistory 1.0 0.5
timestep 1e-6
"""
OK = "100 1 region ins diam uniform 0.8e-3 1.2e-3 dens 2500"


def fix(args, header=HEADER, extra=""):
    return header + extra + f"fix ins all powder/insert {args}\nrun 1\n"


cases = [
    ("unknown keyword", fix(OK + " colour red"), "unknown keyword colour"),
    ("keyword without value", fix(OK + " attempts"), "missing value for attempts"),
    ("vel with two values", fix(OK + " vel 0 0"), "missing value for vel"),
    ("missing region", fix("100 1 diam one 1e-3 dens 2500"), "region keyword is required"),
    ("missing diam", fix("100 1 region ins dens 2500"), "diam keyword is required"),
    ("missing dens", fix("100 1 region ins diam one 1e-3"), "dens keyword is required"),
    ("too few arguments", fix("100"), "expected N seed region"),
    ("N = 0", fix(OK.replace("100 1", "0 1")), "N must be > 0"),
    ("seed = 0", fix(OK.replace("100 1", "100 0")), "seed must be > 0"),
    ("diameter 0", fix("100 1 region ins diam one 0 dens 2500"), "diam one: diameter must be > 0"),
    ("negative dlo", fix("100 1 region ins diam uniform -1e-3 1e-3 dens 2500"), "dlo must be > 0"),
    ("dlo > dhi", fix("100 1 region ins diam uniform 1.2e-3 0.8e-3 dens 2500"), "dlo > dhi"),
    ("normal dlo > dhi", fix("100 1 region ins diam normal 1e-3 1e-4 1.2e-3 0.8e-3 dens 2500"), "dlo > dhi"),
    ("normal sd 0", fix("100 1 region ins diam normal 1e-3 0 0.8e-3 1.2e-3 dens 2500"), "sd must be > 0"),
    ("lognormal sigma negative", fix("100 1 region ins diam lognormal 1e-3 -0.2 0.8e-3 1.2e-3 dens 2500"),
     "sigma_ln must be > 0"),
    ("rosin-rammler n = 0", fix("100 1 region ins diam rosin-rammler 1e-3 0 0.8e-3 1.2e-3 dens 2500"),
     "n must be > 0"),
    ("rosin-rammler cut short", fix("100 1 region ins diam rosin-rammler 1e-3 4 0.8e-3"),
     "missing value for diam rosin-rammler"),
    ("unknown distribution", fix("100 1 region ins diam gamma 1 2 dens 2500"), "unknown diam style gamma"),
    ("table file missing", fix("100 1 region ins diam table nofile.txt dens 2500"),
     "cannot open diameter table file nofile.txt"),
    ("table line without weight", fix("100 1 region ins diam table bad_table.txt dens 2500"),
     "table line 2: missing weight"),
    ("negative density", fix("100 1 region ins diam one 1e-3 dens -5"), "dens must be > 0"),
    ("negative rate", fix(OK + " rate -1"), "rate must be > 0"),
    ("rate and massrate", fix(OK + " rate 10 massrate 1e-3"), "rate and massrate are exclusive"),
    ("attempts 0", fix(OK + " attempts 0"), "attempts must be > 0"),
    ("negative gap", fix(OK + " gap -1e-4"), "gap must be >= 0"),
    ("type out of range", fix(OK + " type 3"), "type 3 outside 1..2"),
    ("region does not exist", fix(OK.replace("region ins", "region nope")), "region ID nope does not exist"),
    ("region cannot hold the particles",
     fix(OK.replace("region ins", "region tiny"), extra="region tiny block 0.001 0.0015 0.001 0.009 0.001 0.009\n"),
     "region tiny cannot hold the particles"),
    ("region outside a fixed boundary",
     fix(OK.replace("region ins", "region high"), extra="region high block 0.001 0.009 0.001 0.009 0.005 0.02\n"),
     "region high extends outside the simulation box"),
    ("unbounded region",
     fix(OK.replace("region ins", "region outside"),
         extra="region outside block 0.001 0.009 0.001 0.009 0.001 0.009 side out\n"),
     "region outside is unbounded"),
    ("pair cutoff below the diameter", fix(OK, HEADER.replace("pair_style granular 1.2e-3", "pair_style granular")),
     "pair cutoff 0 is smaller than the largest inserted diameter"),
    ("temp without fix powder/melt", fix(OK + " temp 300"), "temp requires fix powder/melt"),
    # stopped before the first step (not at the first insertion): run 0 inserts nothing
    ("temp above fix powder/melt's Tmelt",
     HEADER.replace("atom_style sphere", "atom_style sphere 1")
     + "fix m all powder/melt cp 500 Tmelt 1700 latent 2.7e5\n"
     + f"fix ins all powder/insert {OK} temp 1800\nrun 0\n", "temp 1800 is above Tmelt 1700 of fix powder/melt m"),
    ("moving region", fix(OK.replace("region ins", "region mv"), extra="variable xm equal 0.1*time\n"
                                                                       "region mv block 0.001 0.009 0.001 0.009 "
                                                                       "0.001 0.009 move v_xm NULL NULL units box\n"),
     "region mv cannot be dynamic"),
    ("units metal", fix(OK, HEADER.replace("units si", "units metal")), "requires units si"),
    ("units cgs", fix(OK, HEADER.replace("units si", "units cgs")), "requires units si"),
    ("atom_style atomic", fix(OK, HEADER.replace("atom_style sphere", "atom_style atomic")),
     "requires atom style sphere"),
]

ok = True
with tempfile.TemporaryDirectory() as d:
    with open(os.path.join(d, "bad_table.txt"), "w") as f:
        f.write("1e-3 1\n1.1e-3\n")
    ok &= check_errors(TEST, cases, cwd=d)

    # the valid command, with temp applied through fix powder/melt
    melt = HEADER.replace("atom_style sphere", "atom_style sphere 1") + \
        "fix m all powder/melt cp 500 Tmelt 1700 latent 2.7e5 temp 250\n"
    text = melt + (f"fix ins all powder/insert {OK} temp 300 type 2 vel 0 0 -0.1\n"
                   "dump d all custom 1 dump.ins id radius x y z f_m[1] type vz\n"
                   "dump_modify d format float %.17g\nrun 1\n")
    rc, out = run(text, check=False, cwd=d)
    ok &= report(TEST, "valid command", f"exit code {rc}", "exit code 0", "exact", rc == 0)
    if rc == 0:
        fr = read_dump(os.path.join(d, "dump.ins"))[1]
        ok &= report(TEST, "particles inserted by the valid command", len(fr), 100, "exact", len(fr) == 100)
        ok &= report(TEST, "temperature of the new particles (temp 300, powder/melt temp 250)",
                     f"{fr[:, 5].min():g}..{fr[:, 5].max():g}", 300, "exact", (fr[:, 5] == 300).all())
        ok &= report(TEST, "type of the new particles (type 2)", f"{fr[:, 6].min():g}..{fr[:, 6].max():g}", 2,
                     "exact", (fr[:, 6] == 2).all())
    else:
        print(out[-2000:])
sys.exit(0 if ok else 1)
