#!/usr/bin/python3
"""Benchmark: MeltDEM against OpenFOAM's own lagrangian DEM on OpenFOAM's hopper tutorial
(icoUncoupledKinematicParcelFoam/hopper/hopperInitialState, OpenFOAM v1912): speed
(particle-steps per second) and the heap both codes make of the same grains.

    /usr/bin/python3 bench/hopper_vs_openfoam.py [--end-time 0.1] [--repeat 1] [--skip-openfoam]
        [--one-way] [--bin build/bin] [--out bench] [--keep]

OpenFOAM side. The tutorial is not installed with OpenFOAM; it is in Debian's
openfoam-examples package (1912.200626-1). The script fetches it without root
(`apt-get download` into $MELTDEM_CACHE, default ~/.cache/meltdem, once), unpacks it there
(`dpkg-deb -x`) and copies hopperInitialState into a scratch folder (its .gz files
gunzipped); nothing of the tutorial is kept in the repository. It then runs blockMesh and
icoUncoupledKinematicParcelFoam serially with endTime = --end-time and reads from the log
the parcels and the DEM sub-steps of each fluid step (the solver prints "N move-collide
subCycles" for every fluid step it subdivides, N = ceil(deltaT / (t_contact / 12)) from the
fastest parcel, PairSpringSliderDashpot::nSubCycles; a step without the line is one
sub-step). Wall time = own timer around the solver (start-up included); particle-steps =
sum over fluid steps of parcels x sub-steps. The final positions come from
`foamToVTK -latestTime` (the cloud as VTK points; v1912's positions file is barycentric).
Results are cached as JSON next to the package (--skip-openfoam reuses them).

MeltDEM side: the same 3300 grains (kinematicCloudPositions), d, rho, E, nu, friction,
Tsuji damping alpha literally (`damping tsuji/alpha`), walls with their own E, nu and
friction (`wall_material`), gravity of constant/g, the funnel of blockMeshDict (two inclined
plane regions, the vertical sides, the closed outlet floor, the front/back plates), and the
same number of DEM steps as OpenFOAM took (a fixed step: endTime / that count, rounded to
whole fluid steps of 5e-5 s). Runs:
  * coupled: meltdemFoam + LAMMPS in one job (fix powder/melt, physics energy off: isothermal
    grains), on a box mesh of 20 mm cells (3.3 d) over the hopper with the gas (the tutorial's air)
    at rest; wall time of the whole solver and LAMMPS's own clock (particles.csv);
  * one-way (--one-way): meltdemFoam on the tutorial's own blockMesh mesh with
    physics { flow off; energy off; particles on; } (the row says so if the solver refuses it);
  * meltdem-lmp: the same LAMMPS input standalone (fix powder/melt with the same air as an
    `ambient` fluid at rest);
  * lmp: stock /usr/bin/lmp, `pair_style granular` with `hertz` stiffness 4/3 E* and `mindlin`
    8 G* written out (stock walls cannot take a wall material) and `damping tsuji` with the
    restitution whose Tsuji polynomial gives the same alpha; no fluid drag.
Heap comparison after --end-time: centre of mass, free surface (mean height of the three top
grains in 20 mm bins of x), grains inside the funnel, mean speed; each with its tolerance.
Writes hopper_vs_openfoam.md and hopper_vs_openfoam.png into --out.

Run time: OpenFOAM needs about 17 ms per DEM sub-step for these 3300 parcels on one core;
the tutorial's full 0.25 s (72983 sub-steps) took 20.4 minutes (23 minutes in all with the
MeltDEM rows), so the default end time is 0.1 s (8-9 minutes for OpenFOAM, 9-10 in all).
"""
import argparse
import glob
import gzip
import json
import math
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from scipy.optimize import brentq  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
sys.path.insert(0, os.path.join(ROOT, "python"))
os.environ.setdefault("MELTDEM_SOURCE_DIR", ROOT)
os.environ.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")

from meltdem.case import coupled as cc  # noqa: E402
from meltdem.case import foam as fc  # noqa: E402
from meltdem.io import dumps, foamdict, vtkxml  # noqa: E402

from build_stamp import build_stamp, stamp_line  # noqa: E402

PACKAGE, VERSION = "openfoam-examples", "1912.200626-1"
TUTORIAL = ("usr/share/doc/openfoam-examples/examples/lagrangian/icoUncoupledKinematicParcelFoam/"
            "hopper/hopperInitialState")
CELL = 0.02          # cells of the coupled run's box mesh [m]: 3.3 d, the usual unresolved CFD-DEM size
BIN = 0.02           # x bins of the free-surface profile [m]
TOP = 3              # grains per bin averaged for the free surface
# (physics energy off: cp, Tmelt, latent not used); drag coefficients held over sub-steps within 1 %
ISOTHERMAL = "cp 1000 Tmelt 5000 latent 1e5 temp 300 coefficient_tolerance 0.01"


# ------------------------------------------------------------------------------ the tutorial
def cache_dir():
    d = os.environ.get("MELTDEM_CACHE") or os.path.join(os.path.expanduser("~"), ".cache", "meltdem")
    os.makedirs(d, exist_ok=True)
    return d


def fetch_tutorial(cache):
    """The tutorial folder unpacked from the Debian package in the cache (downloaded once)."""
    tree = os.path.join(cache, f"{PACKAGE}_{VERSION}")
    tut = os.path.join(tree, TUTORIAL)
    if os.path.isdir(tut):
        return tut
    debs = sorted(glob.glob(os.path.join(cache, f"{PACKAGE}_{VERSION}_*.deb")))
    if not debs:
        r = subprocess.run(["apt-get", "download", f"{PACKAGE}={VERSION}"], cwd=cache,
                           stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
        debs = sorted(glob.glob(os.path.join(cache, f"{PACKAGE}_{VERSION}_*.deb")))
        if r.returncode != 0 or not debs:
            raise SystemExit(f"apt-get download {PACKAGE}={VERSION} failed in {cache}:\n{r.stdout[-2000:]}")
    subprocess.run(["dpkg-deb", "-x", debs[-1], tree], check=True)
    if not os.path.isdir(tut):
        raise SystemExit(f"{debs[-1]} has no {TUTORIAL}")
    return tut


def copy_case(tut, dest):
    """The tutorial case in dest, every .gz file unpacked."""
    shutil.copytree(tut, dest)
    for gz in glob.glob(os.path.join(dest, "**", "*.gz"), recursive=True):
        with gzip.open(gz, "rb") as f, open(gz[:-3], "wb") as g:
            shutil.copyfileobj(f, g)
        os.remove(gz)
    return dest


def read_positions(path):
    text = open(path).read()
    rows = re.findall(r"^\([ \t]*(\S+)[ \t]+(\S+)[ \t]+([^\s)]+)[ \t]*\)[ \t]*$", text, re.M)
    return np.array(rows, dtype=float)


def sub(d, *keys):
    for k in keys:
        d = d[k]
    return d


def num(d, *keys):
    v = foamdict.number(sub(d, *keys[:-1]), keys[-1])
    if v is None:
        raise SystemExit(f"tutorial: entry {'/'.join(keys)} missing or not a number")
    return v


def tutorial_setup(case):
    """Grains, materials, walls, gravity and time step of the tutorial case (unpacked)."""
    cloud = foamdict.read(os.path.join(case, "constant", "kinematicCloudProperties"))
    pair = sub(cloud, "subModels", "pairCollisionCoeffs", "pairSpringSliderDashpotCoeffs")
    walls = sub(cloud, "subModels", "pairCollisionCoeffs", "wallLocalSpringSliderDashpotCoeffs")
    inj = sub(cloud, "subModels", "injectionModels", "model1")
    s = dict(rho=num(cloud, "constantProperties", "rho0"), E=num(cloud, "constantProperties", "youngsModulus"),
             nu=num(cloud, "constantProperties", "poissonsRatio"),
             d=num(inj, "sizeDistribution", "fixedValueDistribution", "value"),
             alpha=num(pair, "alpha"), mu=num(pair, "mu"), S=num(pair, "collisionResolutionSteps"),
             walls={w: dict(E=num(walls, w, "youngsModulus"), nu=num(walls, w, "poissonsRatio"),
                            alpha=num(walls, w, "alpha"), mu=num(walls, w, "mu"))
                    for w in ("walls", "frontAndBack")})
    if num(pair, "b") != 1.5 or any(num(walls, w, "b") != 1.5 for w in ("walls", "frontAndBack")):
        raise SystemExit("tutorial: the contact exponent b is not 1.5 (Hertz)")
    g = foamdict.vector(foamdict.value(foamdict.read(os.path.join(case, "constant", "g")), "value")[0])
    tr = foamdict.read(os.path.join(case, "constant", "transportProperties"))
    s.update(g=g, rho_air=num(tr, "rhoInf"), nu_air=num(tr, "nu"),
             dt=num(foamdict.read(os.path.join(case, "system", "controlDict")), "deltaT"))
    s["pos"] = read_positions(os.path.join(case, "constant", foamdict.word(inj, "positionsFile")))
    # the hopper: blockMeshDict's vertices (scaled)
    bm = foamdict.read(os.path.join(case, "system", "blockMeshDict"))
    scale = foamdict.number(bm, "scale") or foamdict.number(bm, "convertToMeters") or 1.0
    v = np.array([foamdict.vector(p) for p in bm["vertices"][0]]) * scale
    x0, x1, y0, y1 = v[:, 0].min(), v[:, 0].max(), v[:, 1].min(), v[:, 1].max()
    yf = v[(v[:, 0] == x0) & (v[:, 1] < y1), 1].max()          # where the funnel meets the sides
    xo = np.sort(np.unique(v[v[:, 1] == y0, 0]))                # the outlet (closed here)
    s["box"] = dict(x0=x0, x1=x1, y0=y0, y1=y1, z0=v[:, 2].min(), z1=v[:, 2].max(), yf=yf, xo0=xo[0], xo1=xo[-1])
    return s


# ------------------------------------------------------------------------------ OpenFOAM run
def parse_openfoam_log(path):
    """Per fluid step (time, DEM sub-steps, parcels) and the last ExecutionTime/ClockTime."""
    text = open(path).read()
    steps = []
    for block in re.split(r"\nTime = ", text)[1:]:
        t = float(block.split()[0])
        n = re.search(r"^\s*(\d+) move-collide subCycles", block, re.M)
        p = re.search(r"Current number of parcels\s*=\s*(\d+)", block)
        steps.append((t, int(n.group(1)) if n else 1, int(p.group(1)) if p else 0))
    ex = re.findall(r"ExecutionTime = (\S+) s\s+ClockTime = (\S+) s", text)
    return np.array(steps), (float(ex[-1][0]), float(ex[-1][1])) if ex else (None, None)


def run_openfoam(tut, work, end_time):
    case = copy_case(tut, os.path.join(work, "openfoam"))
    foamdict.set_entries(os.path.join(case, "system", "controlDict"),
                         {"endTime": repr(end_time), "writeInterval": repr(end_time)})
    fc.run(["blockMesh"], case, "log.blockMesh")
    print(f"OpenFOAM: icoUncoupledKinematicParcelFoam to {end_time:g} s (serial) ...", flush=True)
    t0 = time.perf_counter()
    fc.run(["icoUncoupledKinematicParcelFoam"], case, "log.icoUncoupledKinematicParcelFoam")
    wall = time.perf_counter() - t0
    steps, (cpu, clock) = parse_openfoam_log(os.path.join(case, "log.icoUncoupledKinematicParcelFoam"))
    fc.run(["foamToVTK", "-latestTime", "-no-internal", "-no-boundary", "-ascii"], case, "log.foamToVTK")
    vtp = sorted(glob.glob(os.path.join(case, "VTK", "lagrangian", "kinematicCloud", "kinematicCloud_*.vtp")),
                 key=lambda p: int(re.search(r"_(\d+)\.vtp$", p).group(1)))
    piece = vtkxml.read_piece(vtp[-1])
    order = np.argsort(piece["point_data"]["origId"])
    res = dict(end_time=end_time, deltaT=float(np.diff(steps[:, 0]).mean()) if len(steps) > 1 else None,
               fluid_steps=len(steps), dem_steps=int(steps[:, 1].sum()), parcels=int(steps[-1, 2]),
               psteps=float((steps[:, 1] * steps[:, 2]).sum()), wall=wall, cpu=cpu, clock=clock,
               subcycles=steps[:, 1].astype(int).tolist(), times=steps[:, 0].tolist(),
               x=piece["points"][order].astype(float).tolist(),
               v=piece["point_data"]["U"][order].astype(float).tolist(),
               date=time.strftime("%Y-%m-%d %H:%M"))
    print(f"OpenFOAM: {res['fluid_steps']} fluid steps, {res['dem_steps']} DEM sub-steps, {res['parcels']} parcels, "
          f"wall {wall:.1f} s, {res['psteps'] / wall:.4g} particle-steps/s", flush=True)
    return res


# ------------------------------------------------------------------------------ MeltDEM runs
def tsuji_restitution(alpha):
    """The restitution whose Tsuji polynomial (stock LAMMPS damping tsuji) is alpha."""
    poly = np.polynomial.Polynomial([1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218])
    return brentq(lambda e: poly(e) - alpha, 0.0, 1.0, xtol=1e-15)


def wall_moduli(s, w):
    E, nu, Ew, nuw = s["E"], s["nu"], s["walls"][w]["E"], s["walls"][w]["nu"]
    Es = 1.0 / ((1 - nu ** 2) / E + (1 - nuw ** 2) / Ew)
    Gs = 1.0 / (2 * ((2 - nu) * (1 + nu) / E + (2 - nuw) * (1 + nuw) / Ew))
    return Es, Gs


def jittered(pos, amplitude, seed=4242):
    """pos with x and y moved by uniform random offsets in [-amplitude, amplitude]: the tutorial's grains
    sit on a lattice one diameter apart, so whether a neighbour pair touches is decided by round-off"""
    p = np.array(pos, dtype=float)
    p[:, :2] += np.random.default_rng(seed).uniform(-amplitude, amplitude, (len(p), 2))
    return p


def write_data(path, s):
    b = s["box"]
    m = 0.01
    with open(path, "w") as f:
        f.write(f"hopper tutorial grains (OpenFOAM kinematicCloudPositions)\n\n{len(s['pos'])} atoms\n1 atom types\n\n"
                f"{b['x0'] - m!r} {b['x1'] + m!r} xlo xhi\n{b['y0'] - m!r} {b['y1'] + m!r} ylo yhi\n"
                f"{b['z0'] - 0.001!r} {b['z1'] + 0.001!r} zlo zhi\n\nAtoms # sphere\n\n")
        for i, (x, y, z) in enumerate(s["pos"]):
            f.write(f"{i + 1} 1 {s['d']!r} {s['rho']!r} {x!r} {y!r} {z!r}\n")


def lammps_input(s, dt, stock=False, ambient=False, steps=None, thermo=2000):
    """The LAMMPS input of the hopper: MeltDEM styles, or stock ones (stock=True)."""
    b = s["box"]
    nrm = np.array([b["yf"] - b["y0"], b["xo0"] - b["x0"]])      # normal of the left funnel wall
    nx, ny = nrm / np.linalg.norm(nrm)
    if stock:
        Es, Gs = s["E"] / (2 * (1 - s["nu"] ** 2)), s["E"] / (4 * (2 - s["nu"]) * (1 + s["nu"]))
        pair = (f"hertz {4 / 3 * Es!r} {tsuji_restitution(s['alpha'])!r} damping tsuji "
                f"tangential mindlin {8 * Gs!r} 1.0 {s['mu']!r}")

        def wall(w):
            Ew, Gw = wall_moduli(s, w)
            return (f"hertz {4 / 3 * Ew!r} {tsuji_restitution(s['walls'][w]['alpha'])!r} damping tsuji "
                    f"tangential mindlin {8 * Gw!r} 1.0 {s['walls'][w]['mu']!r}")
    else:
        pair = (f"hertz/material {s['E']!r} 0.5 {s['nu']!r} damping tsuji/alpha {s['alpha']!r} "
                f"tangential mindlin NULL 1.0 {s['mu']!r}")

        def wall(w):
            ww = s["walls"][w]
            return (f"hertz/material {s['E']!r} 0.5 {s['nu']!r} damping tsuji/alpha {ww['alpha']!r} "
                    f"wall_material {ww['E']!r} {ww['nu']!r} tangential mindlin NULL 1.0 {ww['mu']!r}")
    sfx = "" if stock else "/powder"
    g = np.array(s["g"])
    gm = float(np.linalg.norm(g))
    melt = "" if stock else f"fix melt all powder/melt {ISOTHERMAL}"
    if ambient:
        melt += f" ambient 300 0.026 {s['rho_air']!r} {s['rho_air'] * s['nu_air']!r} 1005 0 0 0"
    styles = "stock styles" if stock else "MeltDEM styles"
    text = f"""# OpenFOAM's hopper tutorial (hopperInitialState) in LAMMPS ({styles})
units si
atom_style sphere{'' if stock else ' 1'}
atom_modify map array
boundary f f f
newton off
comm_modify vel yes
read_data hopper.data
neighbor {s['d'] / 6!r} bin
neigh_modify delay 0 every 1 check yes
pair_style granular{sfx}
pair_coeff * * {pair}
fix integrate all nve/sphere
fix gravity all gravity {gm!r} vector {g[0] / gm!r} {g[1] / gm!r} {g[2] / gm!r}
# the tutorial's patch 'walls': sides, top, closed outlet floor and the two funnel walls
fix sides all wall/gran{sfx} granular {wall('walls')} xplane {b['x0']!r} {b['x1']!r}
fix floor all wall/gran{sfx} granular {wall('walls')} yplane {b['y0']!r} {b['y1']!r}
region funnelL plane {b['x0']!r} {b['yf']!r} 0.0 {nx!r} {ny!r} 0.0 side in
region funnelR plane {b['x1']!r} {b['yf']!r} 0.0 {-nx!r} {ny!r} 0.0 side in
fix funnelL all wall/gran/region{sfx} granular {wall('walls')} region funnelL
fix funnelR all wall/gran/region{sfx} granular {wall('walls')} region funnelR
# patch 'frontAndBack'
fix plates all wall/gran{sfx} granular {wall('frontAndBack')} zplane {b['z0']!r} {b['z1']!r}
{melt}
timestep {dt!r}
thermo_style custom step time atoms ke
thermo_modify format float %.10g
thermo {thermo}
"""
    if steps is not None:
        text += f"run {steps}\nwrite_dump all custom final.dump id x y z vx vy vz modify sort id format float %.12g\n"
    return text


def final_dump(path):
    c = dumps.columns(dumps.read_frames(path)[-1])
    order = np.argsort(c["id"])
    return (np.column_stack([c["x"], c["y"], c["z"]])[order], np.column_stack([c["vx"], c["vy"], c["vz"]])[order])


def run_lammps(work, name, binary, s, dt, steps, stock):
    d = os.path.join(work, name)
    os.makedirs(d, exist_ok=True)
    write_data(os.path.join(d, "hopper.data"), s)
    with open(os.path.join(d, "in.hopper"), "w") as f:
        f.write(lammps_input(s, dt, stock=stock, ambient=not stock, steps=steps))
    t0 = time.perf_counter()
    r = subprocess.run([binary, "-in", "in.hopper", "-log", "log.lammps", "-echo", "none", "-screen", "none"],
                       cwd=d, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    wall = time.perf_counter() - t0
    log = open(os.path.join(d, "log.lammps")).read() if os.path.exists(os.path.join(d, "log.lammps")) else ""
    if r.returncode != 0:
        err = re.search(r"ERROR[^\n]*", log + r.stdout)
        return dict(error=err.group(0) if err else f"exit code {r.returncode}", wall=wall)
    m = re.search(r"Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", log)
    x, v = final_dump(os.path.join(d, "final.dump"))
    n_atoms = int(m.group(3))
    return dict(wall=wall, loop=float(m.group(1)), dem_steps=int(m.group(2)), parcels=n_atoms,
                psteps=float(int(m.group(2)) * len(s["pos"])), x=x, v=v)


def write_meltdem_case(case, s, dt_dem, n_sub, end_time, one_way, tut=None):
    """The coupled case: a box mesh over the hopper (gas at rest), or the tutorial's own mesh
    with flow off (one_way)."""
    b = s["box"]
    os.makedirs(case, exist_ok=True)
    if one_way:
        os.makedirs(os.path.join(case, "system"), exist_ok=True)
        shutil.copy(os.path.join(tut, "system", "blockMeshDict"), os.path.join(case, "system", "blockMeshDict"))
        patches = {"walls": "wall", "frontAndBack": "wall"}
    else:
        n = (round((b["x1"] - b["x0"]) / CELL), round((b["y1"] - b["y0"]) / CELL), 1)
        cc.box_mesh(case, (b["x0"], b["y0"], b["z0"]), (b["x1"], b["y1"], b["z1"]), n,
                    {"walls": ("wall", ["xmin", "xmax", "ymin", "ymax"]), "frontAndBack": ("wall", ["zmin", "zmax"])})
        patches = {"walls": "wall", "frontAndBack": "wall"}
    cc.uniform_field(case, "alpha.metal", "[0 0 0 0 0 0 0]", 0.0, {p: "type zeroGradient;" for p in patches})
    cc.uniform_field(case, "U", "[0 1 -1 0 0 0 0]", (0.0, 0.0, 0.0), {p: "type noSlip;" for p in patches},
                     vector=True)
    cc.uniform_field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", 0.0,
                     {p: "type fixedFluxPressure; value uniform 0;" for p in patches})
    # phase 'metal' absent (alpha 0): the grains' density; the gas is the tutorial's air
    fc.transport(case, s["rho"], 1e-3 / s["rho"], s["rho_air"], s["nu_air"], 0.0)
    fc.gravity(case, s["g"])
    fluid_dt = n_sub * dt_dem
    fc.control_dict(case, "meltdemFoam", end_time, fluid_dt, end_time, max_co=0.5, max_alpha_co=0.5,
                    max_dt=fluid_dt, adjustable=False)
    fc.fv_schemes(case)
    fc.fv_solution(case, n_correctors=2, p_ref_cell=0)   # closed
    physics = dict(flow="off" if one_way else "on", energy="off", surfaceTension="off", particles="on")
    fc.meltdem_properties(case, physics=physics, extra=f"""
particles
{{
    lammpsInput     in.particles;
    distribution    neighbours;
    demStepsPerFluidStep {n_sub};
}}
""")
    write_data(os.path.join(case, "hopper.data"), s)
    with open(os.path.join(case, "in.particles"), "w") as f:
        f.write(lammps_input(s, dt_dem))
    fc.run(["blockMesh"], case, "log.blockMesh")


def fatal_message(log):
    text = open(log, errors="replace").read() if os.path.exists(log) else ""
    m = re.search(r"FOAM FATAL (?:IO )?ERROR[^\n]*\n(.*?)(?:\n\s*\n|\Z)", text, re.S)
    if m:
        return " ".join(m.group(1).split())
    m = re.search(r"ERROR[^\n]*", text)
    return m.group(0) if m else (text.strip().splitlines() or ["no output"])[-1]


def run_meltdem(work, name, s, dt_dem, n_sub, end_time, one_way=False, tut=None):
    case = os.path.join(work, name)
    write_meltdem_case(case, s, dt_dem, n_sub, end_time, one_way, tut)
    t0 = time.perf_counter()
    rc = cc.run_solver(case, check=False)
    wall = time.perf_counter() - t0
    if rc != 0:
        return dict(error=fatal_message(os.path.join(case, "log.meltdemFoam")), wall=wall, case=case)
    pc = cc.particles_csv(case)
    dumpfile = sorted(glob.glob(os.path.join(case, "particles", "*.dump")), key=lambda p: float(
        os.path.basename(p)[:-5]))[-1]
    x, v = final_dump(dumpfile)
    return dict(wall=wall, loop=float(pc["lammps_seconds"][-1]), exchange=float(pc["exchange_seconds"][-1]),
                cpu=fc.execution_time(case), dem_steps=int(pc["dem_steps"].sum()), parcels=int(pc["particles"][-1]),
                psteps=float((pc["particles"] * pc["dem_steps"]).sum()), fluid_steps=len(pc), x=x, v=v, case=case)


def build_text(bin_dir, at_start=None):
    """build_stamp (at_start None) or stamp_line; a meltdemFoam being relinked must not stop the bench"""
    try:
        return stamp_line(ROOT, bin_dir, at_start) if at_start else build_stamp(ROOT, bin_dir)
    except OSError as e:
        return at_start if at_start and "not readable" in at_start else f"meltdemFoam not readable ({e.strerror})"


# ------------------------------------------------------------------------------ heap numbers
def surface(x, b):
    """Mean height of the TOP highest grains in each BIN-wide x bin (nan where empty)."""
    nb = round((b["x1"] - b["x0"]) / BIN)
    # the initial lattice has grains on bin edges: round-off must not move them across (2 um slack)
    idx = np.clip(np.floor((x[:, 0] - b["x0"]) / BIN + 1e-4).astype(int), 0, nb - 1)
    out = []
    for k in range(nb):
        y = np.sort(x[idx == k, 1])
        out.append(y[-TOP:].mean() if len(y) else np.nan)
    return b["x0"] + (np.arange(nb) + 0.5) * BIN, np.array(out)


def heap(x, v, s):
    b = s["box"]
    _, prof = surface(x, b)
    return dict(ycom=x[:, 1].mean(), xcom=x[:, 0].mean(), funnel=int((x[:, 1] < b["yf"]).sum()),
                speed=float(np.linalg.norm(v, axis=1).mean()), ymax=x[:, 1].max(), profile=prof)


# ------------------------------------------------------------------------------ main
def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--end-time", type=float, default=0.1, help="simulated time of both codes [s] (tutorial: 0.25)")
    ap.add_argument("--repeat", type=int, default=1, help="runs of each MeltDEM row, fastest kept (OpenFOAM: once)")
    ap.add_argument("--skip-openfoam", action="store_true", help="reuse the cached OpenFOAM results of --end-time")
    ap.add_argument("--one-way", action="store_true", help="also run meltdemFoam with flow off on the tutorial mesh")
    ap.add_argument("--interval-factor", type=int, default=4,
                    help="also run coupled with a fluid step this many times the tutorial's (1: not)")
    ap.add_argument("--jitter", type=float, default=1e-9,
                    help="also run coupled, meltdem-lmp and stock lmp with every grain moved at random by up to this "
                         "in x and y [m] (0: not)")
    ap.add_argument("--bin", default=os.environ.get("MELTDEM_BIN") or os.path.join(ROOT, "build", "bin"))
    ap.add_argument("--out", default=HERE)
    ap.add_argument("--keep", action="store_true", help="keep the scratch cases (printed)")
    a = ap.parse_args()
    a.bin = os.path.abspath(a.bin)
    os.environ["MELTDEM_BIN"] = a.bin
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    os.environ.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    start = time.time()

    cache = cache_dir()
    tut = fetch_tutorial(cache)
    work = tempfile.mkdtemp(prefix="meltdem-hopper-")
    s = tutorial_setup(copy_case(tut, os.path.join(work, "tutorial")))
    b = s["box"]
    print(f"tutorial: {len(s['pos'])} grains, d {s['d']:g} m, fluid step {s['dt']:g} s; cache {cache}; work {work}")

    ofjson = os.path.join(cache, f"hopper_openfoam_t{a.end_time:g}.json")
    if a.skip_openfoam:
        if not os.path.exists(ofjson):
            raise SystemExit(f"--skip-openfoam: no cached OpenFOAM results {ofjson}: run once without it")
        of = json.load(open(ofjson))
        print(f"OpenFOAM: cached results of {of['date']} ({ofjson})")
    else:
        of = run_openfoam(tut, work, a.end_time)
        with open(ofjson, "w") as f:
            json.dump(of, f)

    # the same DEM step count, as whole fluid steps of the tutorial's length
    n_fluid = round(a.end_time / s["dt"])
    n_sub = max(1, round(of["dem_steps"] / n_fluid))
    steps = n_sub * n_fluid
    dt_dem = a.end_time / steps
    print(f"MeltDEM: {steps} DEM steps of {dt_dem:.6g} s ({n_sub} per fluid step of {s['dt']:g} s; "
          f"OpenFOAM took {of['dem_steps']})", flush=True)

    stamp = build_text(a.bin)             # the build the MeltDEM rows run (OpenFOAM's run does not use it)
    rows = {"coupled": f"MeltDEM coupled (meltdemFoam + LAMMPS, box mesh of {CELL * 1e3:g} mm cells, gas at rest)"}
    if a.interval_factor > 1:
        rows["coupled-long"] = (f"MeltDEM coupled, fluid step {a.interval_factor}x the tutorial's "
                                f"({a.interval_factor * n_sub} DEM steps each)")
    if a.one_way:
        rows["one-way"] = "MeltDEM one-way (meltdemFoam, tutorial mesh, flow off)"
    rows["meltdem-lmp"] = "meltdem-lmp standalone (same input, ambient air)"
    rows["lmp"] = "stock /usr/bin/lmp (pair granular, no drag)"
    sj = dict(s, pos=jittered(s["pos"], a.jitter)) if a.jitter > 0 else s
    if a.jitter > 0:
        for k in ("coupled", "meltdem-lmp", "lmp"):
            rows[k + "-jitter"] = f"{k}, lattice jittered by {a.jitter:g} m"
    runs = {k: [] for k in rows}
    for rep in range(a.repeat):
        for k in rows:
            name = f"{k}-{rep}"
            t0 = time.perf_counter()
            try:
                if k == "coupled":
                    r = run_meltdem(work, name, s, dt_dem, n_sub, a.end_time)
                elif k == "coupled-jitter":
                    r = run_meltdem(work, name, sj, dt_dem, n_sub, a.end_time)
                elif k == "meltdem-lmp-jitter":
                    r = run_lammps(work, name, os.path.join(a.bin, "meltdem-lmp"), sj, dt_dem, steps, stock=False)
                elif k == "lmp-jitter":
                    r = run_lammps(work, name, "/usr/bin/lmp", sj, dt_dem, steps, stock=True)
                elif k == "coupled-long":
                    r = run_meltdem(work, name, s, dt_dem, a.interval_factor * n_sub, a.end_time)
                elif k == "one-way":
                    r = run_meltdem(work, name, s, dt_dem, n_sub, a.end_time, one_way=True, tut=tut)
                elif k == "meltdem-lmp":
                    r = run_lammps(work, name, os.path.join(a.bin, "meltdem-lmp"), s, dt_dem, steps, stock=False)
                else:
                    r = run_lammps(work, name, "/usr/bin/lmp", s, dt_dem, steps, stock=True)
            except (OSError, RuntimeError, ValueError, IndexError) as e:   # a binary being rebuilt, a broken output
                r = dict(error=" ".join(f"{type(e).__name__}: {e}".split())[:300], wall=time.perf_counter() - t0)
            runs[k].append(r)
            if "error" in r:
                print(f"{rows[k]}: FAILED after {r['wall']:.1f} s: {r['error']}", flush=True)
            else:
                print(f"{rows[k]}: wall {r['wall']:.1f} s, LAMMPS loop {r['loop']:.1f} s, {r['dem_steps']} DEM steps, "
                      f"{r['psteps'] / r['wall']:.4g} particle-steps/s (wall)", flush=True)
    res = {}
    for k, rs in runs.items():
        ok = [r for r in rs if "error" not in r]
        res[k] = min(ok, key=lambda r: r["wall"]) if ok else rs[-1]

    # ---------------------------------------------------------------- tables
    of_rate = of["psteps"] / of["wall"]
    ofx, ofv = np.array(of["x"]), np.array(of["v"])
    lines = ["# MeltDEM vs OpenFOAM's DEM: the hopper tutorial", "",
             f"OpenFOAM's `icoUncoupledKinematicParcelFoam/hopper/hopperInitialState` (Debian {PACKAGE} {VERSION}, "
             f"fetched and run by `bench/hopper_vs_openfoam.py`): {len(s['pos'])} grains d = {s['d'] * 1e3:g} mm, "
             f"rho {s['rho']:g}, E {s['E']:g}, nu {s['nu']:g}, friction {s['mu']:g}, Tsuji alpha {s['alpha']:g}; walls "
             f"E {s['walls']['walls']['E']:g}, nu {s['walls']['walls']['nu']:g}, friction "
             f"{s['walls']['walls']['mu']:g} (front/back {s['walls']['frontAndBack']['mu']:g}); gravity "
             f"{tuple(s['g'])}; fluid step {s['dt']:g} s; outlet closed. Simulated time **{a.end_time:g} s** "
             + ("(the tutorial's own endTime)." if a.end_time >= 0.25 else
                "(the tutorial runs 0.25 s, which took OpenFOAM alone 20 min on one core: the default is shorter, "
                "for both codes alike)."),
             "", f"Serial, one core each, shared 2-core machine; OpenFOAM run once ({of['date']}), MeltDEM rows "
             f"fastest of {a.repeat}. Build of the MeltDEM rows: " + build_text(a.bin, stamp) + ".", "",
             f"DEM steps: OpenFOAM sub-cycles each fluid step (`N move-collide subCycles` in its log, N from the "
             f"fastest parcel's Hertz contact time / {s['S']:g}); it took {of['dem_steps']} sub-steps in "
             f"{of['fluid_steps']} fluid steps ({min(of['subcycles'])}-{max(of['subcycles'])} per step). MeltDEM runs "
             f"the same count at a fixed step: {steps} steps of {dt_dem:.4g} s ({n_sub} per fluid step). OpenFOAM's "
             f"wall time is the script's clock around the solver; its log says ExecutionTime (CPU) {of['cpu']:g} s, "
             f"ClockTime {of['clock']:g} s.", "",
             "| run | particles | DEM steps | particle-steps | wall (s) | LAMMPS loop (s) | particle-steps/s (wall) | "
             "particle-steps/s (LAMMPS) | vs OpenFOAM (wall) |", "|---|---|---|---|---|---|---|---|---|",
             f"| OpenFOAM icoUncoupledKinematicParcelFoam (pairCollision) | {of['parcels']} | {of['dem_steps']} | "
             f"{of['psteps']:.4g} | {of['wall']:.1f} | - | {of_rate:.4g} | - | 1 |"]
    for k, label in rows.items():
        r = res[k]
        if "error" in r:
            lines.append(f"| {label} | FAILED: {r['error'].replace('|', '/')} | | | {r['wall']:.1f} | | | | |")
            continue
        rate = r["psteps"] / r["wall"]
        lines.append(f"| {label} | {r['parcels']} | {r['dem_steps']} | {r['psteps']:.4g} | {r['wall']:.1f} | "
                     f"{r['loop']:.1f} | "
                     f"{rate:.4g} | {r['psteps'] / r['loop']:.4g} | {rate / of_rate:.3g} |")
    cp = res["coupled"]
    ratio = cp["psteps"] / cp["wall"] / of_rate if "error" not in cp else float("nan")
    lines += ["", f"**Coupled MeltDEM / OpenFOAM particle-steps per second: {ratio:.3g}** (whole solver wall time "
              f"each; target >= 30: {'met' if ratio >= 30 else 'NOT met'}).", ""]
    long = res.get("coupled-long", {"error": ""})
    if "error" not in long:
        lines += [f"Coupled with the fluid step {a.interval_factor}x the tutorial's (the gas is at rest; the coupling "
                  f"interval is a user's choice, `bench/coupling_interval.md`): "
                  f"**{long['psteps'] / long['wall'] / of_rate:.3g}x** OpenFOAM.", ""]
    for k in ("coupled", "coupled-long", "one-way"):
        r = res.get(k, {"error": ""})
        if "error" not in r:
            lines.append(f"- {k} run: {r['fluid_steps']} fluid steps, LAMMPS {r['loop']:.1f} s, exchange "
                         f"{r['exchange']:.1f} s (`particles.csv`'s `lammps_seconds`, `exchange_seconds`), the fluid "
                         f"and the rest {r['wall'] - r['loop'] - r['exchange']:.1f} s of {r['wall']:.1f} s.")

    loops = {k: res[k]["loop"] for k in rows if "error" not in res[k]}
    if all(k in loops for k in ("coupled", "lmp", "coupled-jitter", "lmp-jitter", "meltdem-lmp-jitter")):
        lines += ["", f"The LAMMPS part against stock lmp (loop times, same steps; the coupled run's include the "
                  f"exchange records LAMMPS builds): coupled {loops['lmp'] / loops['coupled']:.3g}x of stock on the "
                  f"tutorial's lattice; with the lattice jittered by {a.jitter:g} m in all three runs, coupled "
                  f"{loops['lmp-jitter'] / loops['coupled-jitter']:.3g}x and meltdem-lmp "
                  f"{loops['lmp-jitter'] / loops['meltdem-lmp-jitter']:.3g}x of stock (target 0.9x); stock lmp's "
                  f"loop takes {loops['lmp-jitter'] / loops['lmp']:.3g} times as long jittered as on the lattice. "
                  "The tutorial's grains start one diameter apart, so whether a neighbour pair touches is decided by "
                  "round-off: stock lmp keeps the lattice exact, the coupled run's gas moves grains sideways by "
                  "round-off amounts, and more pairs touch (overlaps of round-off size) until the lattice breaks up "
                  "in the funnel: work of the pair style, not of the coupling."]

    # heap
    ref = heap(ofx, ofv, s)
    cols = [k for k in rows if "error" not in res[k]]
    hs = {k: heap(res[k]["x"], res[k]["v"], s) for k in cols}
    d = s["d"]
    xc, _ = surface(ofx, b)

    def prof_err(h):
        e = h["profile"] - ref["profile"]
        e = e[np.isfinite(e)]
        return math.sqrt(float(np.mean(e ** 2))), float(np.max(np.abs(e)))

    vscale = 0.05 * math.sqrt(float(np.linalg.norm(s["g"])) * d)   # a settled heap: both speeds ~0
    checks = [("centre of mass height y [mm]", lambda h: h["ycom"] * 1e3, ref["ycom"] * 1e3, 0.5 * d * 1e3,
               "0.5 d"),
              ("centre of mass x [mm]", lambda h: h["xcom"] * 1e3, ref["xcom"] * 1e3, 0.5 * d * 1e3, "0.5 d"),
              ("highest grain y [mm]", lambda h: h["ymax"] * 1e3, ref["ymax"] * 1e3, d * 1e3, "1 d"),
              (f"grains inside the funnel (y < {b['yf'] * 1e3:.1f} mm)", lambda h: h["funnel"], ref["funnel"],
               max(0.05 * ref["funnel"], 10), "5 % (at least 10)"),
              ("mean grain speed [m/s]", lambda h: h["speed"], ref["speed"], max(0.2 * ref["speed"], vscale),
               "20 %, at least 0.05 sqrt(g d)")]
    lines += ["", f"## Heap at t = {a.end_time:g} s", "",
              f"Free surface: mean height of the {TOP} highest grains in each {BIN * 1e3:g} mm bin of x "
              f"({len(xc)} bins); its difference to OpenFOAM's as RMS and worst bin.", "",
              "| quantity | OpenFOAM | " + " | ".join(rows[k].split(" (")[0] for k in cols) + " | tolerance | "
              "coupled within |", "|---|---|" + "---|" * len(cols) + "---|---|"]
    summary = []
    for name, f, refv, tol, tols in checks:
        vals = [f(hs[k]) for k in cols]
        fmt = (lambda v: f"{v}") if isinstance(refv, int) else (lambda v: f"{v:.4g}")
        within = abs(f(hs["coupled"]) - refv) <= tol if "coupled" in hs else None
        lines.append(f"| {name} | {fmt(refv)} | " + " | ".join(fmt(v) for v in vals) +
                     f" | {tols} ({tol:.3g}) | {'yes' if within else 'NO' if within is not None else '-'} |")
        summary.append((name, f(hs["coupled"]) if "coupled" in hs else None, refv, tol, within))
    for label, idx, tol in (("free surface, RMS difference [mm]", 0, d), ("free surface, worst bin [mm]", 1, 2 * d)):
        vals = [prof_err(hs[k])[idx] * 1e3 for k in cols]
        within = prof_err(hs["coupled"])[idx] <= tol if "coupled" in hs else None
        verdict = "yes" if within else "NO" if within is not None else "-"
        lines.append(f"| {label} | 0 | " + " | ".join(f"{v:.3g}" for v in vals) +
                     f" | {tol / d:g} d ({tol * 1e3:.3g}) | {verdict} |")
        summary.append((label, prof_err(hs["coupled"])[idx] * 1e3 if "coupled" in hs else None, 0.0, tol * 1e3,
                        within))
    if len(cols) > 1:
        pairs = [(i, j) for n_, i in enumerate(cols) for j in cols[n_ + 1:]]
        rms = [math.sqrt(float(np.nanmean((hs[i]["profile"] - hs[j]["profile"]) ** 2))) * 1e3 for i, j in pairs]
        yc = [hs[k]["ycom"] * 1e3 for k in cols]
        lines += ["", f"Spread among the LAMMPS runs themselves (same contact model; round-off, drag and style "
                  f"differences grow chaotically in a heap): free surface RMS {min(rms):.3g}-{max(rms):.3g} mm between "
                  f"pairs, centre of mass height {min(yc):.4g}-{max(yc):.4g} mm. A difference to OpenFOAM beyond this "
                  "spread is a difference of the models."]
    lines += ["", "Differences in the models (not in the numbers): OpenFOAM sets its DEM step per fluid step from the "
              "fastest parcel (MeltDEM: one fixed step, the same count); at the friction limit OpenFOAM zeroes the "
              "tangential spring, LAMMPS's `mindlin` keeps it at the limit; OpenFOAM's walls are the mesh faces "
              "(corners and edges from its wall-site search), LAMMPS's are infinite planes cut by nothing (the "
              "funnel planes and the outlet floor meet the grains only where the tutorial's faces are). Drag: "
              "OpenFOAM's `sphereDrag` and MeltDEM's default (`thesis`) are the same Cd; the coupled run's gas "
              "moves a little under the grains' drag, the one-way and `ambient` runs keep it at rest, stock lmp has "
              "none (air drag is under 1 % of the weight below 1 m/s)."]
    lines += ["", f"Command: `/usr/bin/python3 bench/hopper_vs_openfoam.py {' '.join(sys.argv[1:])}`; total run time "
              f"{(time.time() - start) / 60:.1f} min."]
    with open(os.path.join(a.out, "hopper_vs_openfoam.md"), "w") as f:
        f.write("\n".join(lines) + "\n")
    print("\n".join(lines))
    print(f"\ncoupled / OpenFOAM particle-steps per second: {ratio:.3g}")
    for name, mv, ov, tol, within in summary:
        if mv is not None:
            print(f"{name}: MeltDEM {mv:.4g}, OpenFOAM {ov:.4g}, tolerance {tol:.3g}: {'ok' if within else 'OUTSIDE'}")

    # ---------------------------------------------------------------- plot
    fig, ax = plt.subplots(1, 3, figsize=(15, 6), gridspec_kw=dict(width_ratios=[1, 1, 1.2]))
    outline = np.array([[b["x0"], b["y1"]], [b["x0"], b["yf"]], [b["xo0"], b["y0"]], [b["xo1"], b["y0"]],
                        [b["x1"], b["yf"]], [b["x1"], b["y1"]]])
    panels = [("OpenFOAM", ofx, ref)] + ([("MeltDEM coupled", cp["x"], hs["coupled"])] if "coupled" in hs else [])
    ylim = b["y1"] + 0.07          # room for the legend above the hopper
    for axi, (title, x, h) in zip(ax[:2], panels):
        axi.plot(outline[:, 0] * 1e3, outline[:, 1] * 1e3, "k-", lw=1.5)
        axi.scatter(x[:, 0] * 1e3, x[:, 1] * 1e3, s=3, c="tab:blue" if title == "OpenFOAM" else "tab:orange")
        axi.plot(xc * 1e3, ref["profile"] * 1e3, "b--", lw=1, label="free surface, OpenFOAM")
        if title != "OpenFOAM":
            axi.plot(xc * 1e3, h["profile"] * 1e3, "r-", lw=1, label="free surface, MeltDEM")
        axi.axhline(h["ycom"] * 1e3, color="gray", lw=0.8, ls=":", label="centre of mass")
        axi.set_aspect("equal")
        axi.set_ylim(-5, ylim * 1e3)
        axi.set_xlabel("x [mm]")
        axi.set_ylabel("y [mm]")
        axi.set_title(f"{title}, t = {a.end_time:g} s", fontsize=10)
        axi.legend(fontsize=7, loc="upper right")
    names, rates, colors = ["OpenFOAM"], [of_rate], ["tab:blue"]
    for k, c in zip(rows, ["tab:orange", "tab:red", "tab:green", "tab:gray", "tab:purple", "tab:brown", "tab:pink",
                           "tab:olive", "tab:cyan"]):
        if "error" not in res[k]:
            names.append(k)
            rates.append(res[k]["psteps"] / res[k]["wall"])
            colors.append(c)
    ax[2].bar(range(len(names)), rates, color=colors)
    for i, r in enumerate(rates):
        ax[2].text(i, r * 1.1, f"{r:.3g}\n({r / of_rate:.3g}x)", ha="center", fontsize=8)
    ax[2].set_yscale("log")
    ax[2].set_ylim(min(rates) / 3, max(rates) * 5)
    ax[2].set_xticks(range(len(names)))
    ax[2].set_xticklabels(names, fontsize=7, rotation=30, ha="right")
    ax[2].set_ylabel("particle-steps per second (whole run's wall time)")
    ax[2].set_title(f"coupled / OpenFOAM = {ratio:.3g} (target >= 30)", fontsize=10)
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "hopper_vs_openfoam.png"), dpi=110)
    fc.finish(True, work, a.keep)


if __name__ == "__main__":
    main()
