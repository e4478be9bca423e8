#!/usr/bin/python3
"""Insertion into a region already at 40 % solids (Codina2019 §3.2.2 "overlaps in
injection", ch. 5 "deferred insertion"). DEM only, meltdem-lmp.

The region (a cube of 9 lattice spacings) holds 729 steel spheres of d = 30 um on a simple
cubic lattice of spacing a = d (pi / (6 * 0.4))^(1/3) = 1.094 d, each jittered by up to
0.3 (a - d) / 2 per axis: 40.0 % solids by volume, overlap-free. Its largest holes (the cube
centres, 0.947 d from the corners) take spheres up to ~0.94 d, never one of the same size.
fix powder/insert must then either place particles without any overlap or let them wait,
and say so (naming the knobs) when it cannot make progress -- never force an overlap
(pop-corn, measured with compute powder/overlap and the largest particle speed).

  full:    30 more d = 30 um spheres, stall 20 warn: none fits, all 30 wait, the warning appears
           once after 20 tries naming region / attempts / gap / rate; no overlap, nothing moves.
  stop:    the same with stall 20 error: the run stops at that try with the same message.
  holes:   100 spheres of d = 15 um: all placed in the first try (they fit the holes), no
           overlap anywhere, solids 40 % -> 40.7 %, nothing moves over 200 steps.
  waiting: the 40 % block falls out of the region at 5 m/s (no gravity, no walls); 300 spheres of
           d = 30 um due at once, moving with it: they wait while the region is full and are
           all placed as room frees up, none overlapping (the largest speed stays 5 m/s), none
           before the block has moved far enough for a sphere nested in the hollow of four top
           spheres: 0.5 d + sqrt(d^2 - a^2/2) - a/2 - 2 jitter = 0.56 d.
usage: insertion_40pct.py [--np N]   (N ranks: every rank takes the same decisions)
"""
import math
import re
import sys

import numpy as np

from meltdem.testing.report import check_absolute, check_at_most, check_relative
from meltdem.testing.lammps_run import run, thermo_rows

NP = int(sys.argv[sys.argv.index("--np") + 1]) if "--np" in sys.argv else 1
T = "extremes.insertion_40pct" + (f".np{NP}" if NP > 1 else "")
D, RHO, PHI, N_SIDE = 30e-6, 7800.0, 0.40, 9
A = D * (math.pi / (6 * PHI)) ** (1 / 3)
L = N_SIDE * A
JITTER = 0.3 * (A - D) / 2


def lattice():
    rng = np.random.default_rng(7)
    i = np.arange(N_SIDE)
    g = np.stack(np.meshgrid(i, i, i, indexing="ij"), -1).reshape(-1, 3)
    return (g + 0.5) * A + rng.uniform(-JITTER, JITTER, g.shape)


def text(insert, steps, v0=0.0, box_below=0.0, every=1):
    """The lattice at rest (or moving down at v0) in region fill = [0, L]^3, then insert."""
    atoms = "\n".join(f"create_atoms 1 single {float(x)!r} {float(y)!r} {float(z)!r} units box"
                      for x, y, z in lattice())
    return f"""units si
atom_style sphere
atom_modify map array
boundary f f f
comm_modify vel yes
region box block {-A!r} {L + A!r} {-A!r} {L + A!r} {-box_below - A!r} {L + A!r}
create_box 1 box
region fill block 0 {L!r} 0 {L!r} 0 {L!r}
{atoms}
set group all diameter {D!r}
set group all density {RHO!r}
velocity all set 0 0 {-v0!r}
pair_style granular/powder {D!r}
pair_coeff * * hertz/material 2e11 0.5 0.3 damping tsuji tangential linear_nohistory 1.0 0.0
neighbor 3e-6 bin
timestep 1e-8
fix 1 all nve/sphere
{insert}
compute ov all powder/overlap warn no
compute rad all property/atom radius
variable s atom sqrt(vx*vx+vy*vy+vz*vz)
compute vmax all reduce max v_s
variable vol atom 4.0/3.0*PI*c_rad^3*(x>0)*(x<{L!r})*(y>0)*(y<{L!r})*(z>0)*(z<{L!r})
compute vs all reduce sum v_vol
variable phi equal c_vs/{L**3!r}
thermo_style custom step atoms f_ins[1] f_ins[2] f_ins[3] f_ins[7] c_ov[1] c_ov[2] c_vmax v_phi
thermo_modify format float %.10g
thermo {every}
run {steps}
"""


def rows_of(out):
    return thermo_rows(out)


def stall_message(out):
    m = re.search(r"(WARNING|ERROR): Fix powder/insert ins: no particle placed in (\d+) insertion tries.*", out)
    return m


def knobs_named(msg):
    return all(k in msg for k in ("enlarge region fill", "attempts", "gap", "rate/massrate"))


def main():
    ok = True
    phi0 = len(lattice()) * math.pi / 6 * D**3 / L**3
    ok &= check_relative(T, "solids volume fraction of the filled region", phi0, PHI, 1e-12)

    # full: same-size particles cannot fit; they wait, with a warning after 20 tries
    rc, out = run(text(f"fix ins all powder/insert 30 4711 region fill diam one {D!r} dens {RHO!r} "
                       "attempts 200 stall 20 warn", 40), check=False, np=NP)
    r = rows_of(out)
    ok &= check_absolute(T, "full: exit code", rc, 0, 0)
    ok &= check_absolute(T, "full: particles inserted into the 40 % region", r[-1]["f_ins[1]"], 0, 0)
    ok &= check_absolute(T, "full: particles pending", r[-1]["f_ins[2]"], 30, 0)
    ok &= check_absolute(T, "full: insertion tries in a row without progress", r[-1]["f_ins[7]"], 40, 0)
    m = stall_message(out)
    ok &= check_absolute(T, "full: stall warnings (once, after 20 tries)",
                         len(re.findall("no particle placed in", out)), 1, 0)
    ok &= check_absolute(T, "full: the warning names region, attempts, gap, rate",
                         int(bool(m) and knobs_named(m.group(0))), 1, 0)
    if m:
        print(m.group(0))
    ok &= check_absolute(T, "full: largest overlap / R (no contact at all)", max(x["c_ov[1]"] for x in r), 0, 0)
    ok &= check_absolute(T, "full: largest particle speed [m/s] (no pop-corn)", max(x["c_vmax"] for x in r), 0, 0)

    # stop: the same, but the stall stops the run at the 20th try
    rc, out = run(text(f"fix ins all powder/insert 30 4711 region fill diam one {D!r} dens {RHO!r} "
                       "attempts 200 stall 20 error", 40), check=False, np=NP)
    m = stall_message(out)
    ok &= check_absolute(T, "stop: exit code is nonzero", int(rc != 0), 1, 0)
    ok &= check_absolute(T, "stop: an ERROR naming region, attempts, gap, rate",
                         int(bool(m) and m.group(1) == "ERROR" and knobs_named(m.group(0))), 1, 0)
    ok &= check_absolute(T, "stop: tries when it stopped", int(m.group(2)) if m else -1, 20, 0)
    r = rows_of(out)
    ok &= check_at_most(T, "stop: last thermo step before the stop", r[-1]["Step"] if r else 0, 20)

    # the keyword's own bad input
    for bad, msg in (("stall 0 warn", "stall tries must be > 0"), ("stall 5 maybe", "stall action maybe"),
                     ("stall 5", "missing value for stall")):
        rc, out = run(text(f"fix ins all powder/insert 1 4711 region fill diam one {D!r} dens {RHO!r} {bad}", 1),
                      check=False, np=NP)
        ok &= check_absolute(T, f"bad input '{bad}': stops with '{msg}'", int(rc != 0 and msg in out), 1, 0)

    # holes: 15 um spheres fit the cube centres: placed at once, no contact anywhere
    n_small, d_small = 100, D / 2
    rc, out = run(text(f"fix ins all powder/insert {n_small} 4711 region fill diam one {d_small!r} dens {RHO!r} "
                       "attempts 500 stall 20 warn", 200), check=False, np=NP)
    r = rows_of(out)
    ok &= check_absolute(T, "holes: exit code", rc, 0, 0)
    first = next((x["Step"] for x in r if x["f_ins[1]"] == n_small), math.inf)
    ok &= check_absolute(T, "holes: step by which all 100 are placed", first, 1, 0)
    ok &= check_absolute(T, "holes: largest overlap / R", max(x["c_ov[1]"] for x in r), 0, 0)
    ok &= check_absolute(T, "holes: largest particle speed [m/s] (no pop-corn)", max(x["c_vmax"] for x in r), 0, 0)
    phi1 = PHI + n_small * math.pi / 6 * d_small**3 / L**3
    ok &= check_relative(T, "holes: solids fraction after insertion", r[-1]["v_phi"], phi1, 1e-9)
    ok &= check_absolute(T, "holes: stall warnings", len(re.findall("no particle placed in", out)), 0, 0)

    # waiting: the block leaves the region at 1 m/s; the pending particles follow as room frees up
    n_wait, v0 = 300, 5.0
    steps = int(round(1.2 * L / v0 / 1e-8))
    rc, out = run(text(f"fix ins all powder/insert {n_wait} 4711 region fill diam one {D!r} dens {RHO!r} "
                       f"vel 0 0 {-v0!r} attempts 100 every 10 stall 1000000 warn", steps, v0=v0, box_below=1.3 * L,
                       every=10),
                  check=False, np=NP)
    r = rows_of(out)
    ok &= check_absolute(T, "waiting: exit code", rc, 0, 0)
    placed = [x["f_ins[1]"] for x in r]
    first = next((x["Step"] for x in r if x["f_ins[1]"] > 0), math.inf)
    done = next((x["Step"] for x in r if x["f_ins[1]"] == n_wait), math.inf)
    print(f"{T}: waiting: first particle placed at step {first:g}, all {n_wait} by step {done:g} "
          f"(of {steps}; the block clears a diameter every {D / v0 / 1e-8:g} steps)")
    ok &= check_absolute(T, "waiting: particles placed by the end", placed[-1], n_wait, 0)
    ok &= check_absolute(T, "waiting: particles pending at the end", r[-1]["f_ins[2]"], 0, 0)
    nest = 0.5 * D + math.sqrt(D**2 - A**2 / 2) - A / 2 - 2 * JITTER
    ok &= check_at_most(T, "waiting: -(first step with a particle placed) vs -(block moved 0.56 d, nested sphere)",
                        -min(first, 1e9), -nest / v0 / 1e-8)
    ok &= check_absolute(T, "waiting: largest overlap / R", max(x["c_ov[1]"] for x in r), 0, 0)
    ok &= check_relative(T, "waiting: largest particle speed [m/s] (no pop-corn)", max(x["c_vmax"] for x in r), v0,
                         1e-12)
    ok &= check_absolute(T, "waiting: particles (lattice + inserted)", r[-1]["Atoms"], len(lattice()) + n_wait, 0)
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
