#!/usr/bin/python3
"""Binder jetting: an 80 um binder droplet falling into a 500-particle powder bed (Fuchs2022
§4.2, configuration of §4.1, tables 2-4), isothermal (no energy equation).

    scene.py build    CASE [--ci | --full] [--speeds 1,10,50] [--dx DX] [--particles on|off]
                           [--end T1,T2,T3] [--distribution overlap|neighbours|centre]
    scene.py run      CASE [--np N]
    scene.py analyse  CASE
    scene.py all      CASE [--ci | --full] [--np N] [build options]
    scene.py plot     CASE      (CASE/sections.png: vertical sections through the droplet axis)

CASE holds bed/ (the DEM pre-processing step: in.bed, settled into bed.data) and one OpenFOAM
case per droplet speed (v1/, v10/, v50/). meltdemFoam's two VOF phases are "metal" (here the
liquid binder, table 4: rho 1000, mu 1e-3, sigma 0.5, contact angle 60 deg) and gas (table 3:
rho 7.43, mu 6e-4); the powder (table 2: steel, rho 7430) is LAMMPS's, coupled by drag and
buoyancy only (physics energy off). The substrate's top (z = 20 um) is the mesh's no-slip floor
and the LAMMPS floor wall.

Binaries: $MELTDEM_BIN (default <repo>/build/bin); WM_PROJECT_DIR defaults to /usr/share/openfoam.
"""
import argparse
import json
import math
import os
import shutil
import subprocess
import time

import numpy as np

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.io import dumps
from meltdem.scene import Scene

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = paths.source_dir()
paths.set_tool_environment()

# Fuchs2022 tables 2-4
BINDER = dict(rho=1000.0, mu=1.0e-3, sigma=0.5, theta=60.0)
GAS = dict(rho=7.43, mu=6.0e-4)
POWDER = dict(rho=7430.0, E=200e9, nu=0.3, median=22.6e-6, sigln=0.2, dlo=16e-6, dhi=32e-6)
G = 9.81
# Fuchs2022 §4.2 geometry
DROP_D = 80e-6
DROP_ABOVE = 100e-6        # droplet centre above the substrate
ZFLOOR = 20e-6             # substrate thickness: its top is the floor of the mesh
END = {1.0: 1.0e-4, 10.0: 5.0e-5, 50.0: 2.0e-5}   # Fuchs2022's times (1, 10 m/s); 50 m/s ours

VARIANTS = {
    # Fuchs2022 size: 320 x 320 x 200 um, 500 particles
    "full": dict(L=320e-6, ztop=200e-6, N=500, dx=20e-6 / 3, speeds=[1.0, 10.0, 50.0],
                 distribution="neighbours"),
    # CI: 200 x 200 um floor (same powder per area: 195 particles), 10 um cells
    "ci": dict(L=200e-6, ztop=200e-6, N=195, dx=10e-6, speeds=[1.0, 10.0, 50.0],
               distribution="neighbours"),
}


def speed_dir(v):
    return f"v{v:g}"


# ----------------------------------------------------------------------------------- build
def build(case, variant="ci", speeds=None, dx=None, particles="on", end=None, distribution=None):
    p = dict(VARIANTS[variant])
    if speeds:
        p["speeds"] = speeds
    if dx:
        p["dx"] = dx
    if distribution:
        p["distribution"] = distribution
    ends = {v: END.get(v, 5e-5) for v in p["speeds"]}
    if end:
        ends = dict(zip(p["speeds"], end))
    p.update(variant=variant, particles=particles, end={str(v): ends[v] for v in p["speeds"]})
    os.makedirs(case, exist_ok=True)
    bed = os.path.join(case, "bed")
    os.makedirs(bed, exist_ok=True)
    shutil.copy(os.path.join(HERE, "in.bed"), os.path.join(bed, "in.bed"))
    with open(os.path.join(case, "scene.json"), "w") as f:
        json.dump(dict(p, scene="bjt-droplet"), f, indent=1)
    for v in p["speeds"]:
        write_foam_case(os.path.join(case, speed_dir(v)), p, v, ends[v])
    print(f"built {case}: {variant}, speeds {p['speeds']} m/s, dx {p['dx'] * 1e6:.3g} um, particles {particles}")


def mesh_counts(p):
    n = round(p["L"] / p["dx"])
    nz = round((p["ztop"] - ZFLOOR) / p["dx"])
    return n, n, nz


def cell_centres(p):
    nx, ny, nz = mesh_counts(p)
    h = (p["L"] / nx, p["L"] / ny, (p["ztop"] - ZFLOOR) / nz)
    x = (np.arange(nx) + 0.5) * h[0]
    y = (np.arange(ny) + 0.5) * h[1]
    z = ZFLOOR + (np.arange(nz) + 0.5) * h[2]
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")   # blockMesh order: x fastest, then y, z
    return X.ravel(), Y.ravel(), Z.ravel(), h


def sphere_fraction(X, Y, Z, h, c, r, nsub=6):
    """volume fraction of the sphere (centre c, radius r) in each cell, by sub-sampling"""
    s = (np.arange(nsub) + 0.5) / nsub - 0.5
    a = np.zeros(X.size)
    near = (np.abs(X - c[0]) < r + h[0]) & (np.abs(Y - c[1]) < r + h[1]) & (np.abs(Z - c[2]) < r + h[2])
    xs, ys, zs = X[near], Y[near], Z[near]
    acc = np.zeros(xs.size)
    for sx in s:
        for sy in s:
            for sz in s:
                acc += ((xs + sx * h[0] - c[0]) ** 2 + (ys + sy * h[1] - c[1]) ** 2
                        + (zs + sz * h[2] - c[2]) ** 2 <= r * r)
    a[near] = acc / nsub ** 3
    return a


def write_foam_case(case, p, v, t_end):
    os.makedirs(case, exist_ok=True)
    L, ztop, dx = p["L"], p["ztop"], p["dx"]
    n = mesh_counts(p)
    cc.box_mesh(case, (0.0, 0.0, ZFLOOR), (L, L, ztop), n,
                {"substrate": ("wall", ["zmin"]), "walls": ("wall", ["xmin", "xmax", "ymin", "ymax", "zmax"])})
    X, Y, Z, h = cell_centres(p)
    centre = (L / 2, L / 2, ZFLOOR + DROP_ABOVE)
    alpha = sphere_fraction(X, Y, Z, h, centre, DROP_D / 2)
    U = np.zeros((X.size, 3))
    U[:, 2] = -v * (alpha > 0)   # the droplet's cells, interface cells included, move with it
    theta = BINDER["theta"]
    wall_alpha = (f"type constantAlphaContactAngle; theta0 {theta!r}; limit gradient; value uniform 0;")
    cc.uniform_field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha,
                     {"substrate": wall_alpha, "walls": wall_alpha})
    cc.uniform_field(case, "U", "[0 1 -1 0 0 0 0]", U,
                     {"substrate": "type noSlip;", "walls": "type noSlip;"}, vector=True)
    cc.uniform_field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", 0.0,
                     {"substrate": "type fixedFluxPressure; value uniform 0;",
                      "walls": "type fixedFluxPressure; value uniform 0;"})
    fc.transport(case, BINDER["rho"], BINDER["mu"] / BINDER["rho"], GAS["rho"], GAS["mu"] / GAS["rho"],
                 BINDER["sigma"])
    fc.gravity(case, (0.0, 0.0, -G))
    # capillary limit sqrt(rho_mean dx^3 / (2 pi sigma)) (interFoam's Courant control lacks it)
    rho_mean = 0.5 * (BINDER["rho"] + GAS["rho"])
    dt_cap = math.sqrt(rho_mean * dx ** 3 / (2 * math.pi * BINDER["sigma"]))
    write = t_end / 20
    # start at the Courant/capillary limit: the coupling's auto sub-cycling (floor(dt_fluid/dt_DEM)
    # DEM steps, the fluid step then n dt_DEM) cannot grow out of n <= 4 under the 1.2x growth cap
    fc.control_dict(case, "meltdemFoam", t_end, min(dt_cap, 0.3 * dx / v), write, max_co=0.3,
                    max_alpha_co=0.3, max_dt=dt_cap, extra="functions { balance { type meltdemBalance; } }")
    txt = open(os.path.join(case, "system", "controlDict")).read().replace("writePrecision 12", "writePrecision 17")
    open(os.path.join(case, "system", "controlDict"), "w").write(txt)
    fc.fv_schemes(case)
    # closed box: pressure reference; tight alpha solve (binder volume conserved to round-off)
    fc.fv_solution(case, n_correctors=3, p_ref_cell=n[0] * n[1] * (n[2] - 1), alpha_tolerance=1e-14)
    sol = os.path.join(case, "system", "fvSolution")
    txt = open(sol).read()
    txt = txt.replace('relaxationFactors { equations { ".*" 1; } }', "")
    # the reference as a point (a cell index would be the master's local one in parallel)
    txt = txt.replace(f"pRefCell {n[0] * n[1] * (n[2] - 1)};",
                      f"pRefPoint ({dx / 2!r} {dx / 2!r} {ztop - dx / 2!r});")
    open(sol, "w").write(txt)
    physics = dict(energy="off", surfaceTension="off", particles=p["particles"])
    extra = ""
    if p["particles"] == "on":
        extra = f"""
particles
{{
    lammpsInput     in.particles;
    distribution    {p["distribution"]};
    demStepsPerFluidStep auto;
}}
"""
        write_lammps(case, p)
    fc.meltdem_properties(case, physics=physics, extra=extra)


def write_lammps(case, p):
    L, ztop = p["L"], p["ztop"]
    E, nu = POWDER["E"], POWDER["nu"]
    wall = f"hertz/material {E!r} 0.5 {nu!r} damping tsuji/alpha 1.0 tangential mindlin NULL 1.0 0.1"
    with open(os.path.join(case, "in.particles"), "w") as f:
        f.write(f"""# the settled bed of bed/ (scene.py run copies bed.data here), coupled by drag and buoyancy
units si
atom_style sphere 1
atom_modify map array
boundary f f f
newton off
comm_modify vel yes
read_data bed.data
reset_timestep 0
neighbor 8e-6 bin
neigh_modify delay 0
pair_style granular/powder 3.2e-5
pair_coeff * * hertz/material {E!r} 0.5 {nu!r} damping tsuji/alpha 1.5 tangential mindlin NULL 1.0 0.1
fix integrate all nve/sphere
fix gravity all gravity {G!r} vector 0 0 -1
fix floor all wall/gran/powder granular {wall} zplane {ZFLOOR!r} {ztop!r}
fix sidex all wall/gran/powder granular {wall} xplane 0.0 {L!r}
fix sidey all wall/gran/powder granular {wall} yplane 0.0 {L!r}
fix dt all powder/dt steps 10 max 2e-8
# isothermal coupling (physics energy off): the fix's thermal data are not used
fix melt all powder/melt cp 500 Tmelt 5000 latent 2.7e5 temp 300 drag schiller-naumann
compute sp all property/atom vx vy vz
variable speed atom sqrt(vx*vx+vy*vy+vz*vz)
compute vmax all reduce max v_speed
thermo_style custom step time dt atoms c_vmax
thermo_modify format float %.12g flush yes
thermo 50
dump traj all custom 50 traj.dump id radius x y z vx vy vz
dump_modify traj sort id format float %.10g
""")


# ------------------------------------------------------------------------------------- run
def mpirun(np_):
    if np_ == 1:
        return []
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_)]


def run(case, np_=1):
    p = json.load(open(os.path.join(case, "scene.json")))
    env = dict(os.environ, OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    timing = {}
    bed = os.path.join(case, "bed")
    if p["particles"] == "on" and not os.path.exists(os.path.join(bed, "bed.data")):
        t0 = time.time()
        cmd = mpirun(np_) + [paths.binary("meltdem-lmp"), "-in", "in.bed", "-log", "log.bed",
                             "-var", "L", repr(p["L"]), "-var", "N", str(p["N"]),
                             "-var", "zfloor", repr(ZFLOOR), "-var", "ztop", repr(p["ztop"])]
        with open(os.path.join(bed, "out.bed"), "w") as f:
            r = subprocess.run(cmd, cwd=bed, stdout=f, stderr=subprocess.STDOUT, env=env)
        if r.returncode != 0:
            raise RuntimeError(f"bed generation failed, see {bed}/out.bed")
        timing["bed_s"] = time.time() - t0
        print(f"bed: {p['N']} particles settled in {timing['bed_s']:.0f} s")
    for v in p["speeds"]:
        c = os.path.join(case, speed_dir(v))
        if p["particles"] == "on":
            shutil.copy(os.path.join(bed, "bed.data"), os.path.join(c, "bed.data"))
        # a re-run starts clean: no time folders, ledgers or trajectories of an earlier run
        for d in fc.time_dirs(c):
            if float(d) > 0:
                shutil.rmtree(os.path.join(c, d))
        for d in ["postProcessing", "traj.dump"] + [d for d in os.listdir(c) if d.startswith("processor")]:
            path = os.path.join(c, d)
            if os.path.isdir(path):
                shutil.rmtree(path)
            elif os.path.exists(path):
                os.remove(path)
        t0 = time.time()
        fc.run(["blockMesh"], c, "log.blockMesh")
        if np_ > 1:
            cc.decompose(c, np_, direction=(2, 1, 1) if np_ == 2 else (np_, 1, 1))
        cc.run_solver(c, np_)
        timing[f"v{v:g}_s"] = time.time() - t0
        print(f"v = {v:g} m/s: {time.time() - t0:.0f} s")
        if np_ > 1:
            fc.run(["reconstructPar", "-newTimes"], c, "log.reconstructPar")
    with open(os.path.join(case, "timing.json"), "w") as f:
        json.dump(dict(timing, np=np_), f, indent=1)


# --------------------------------------------------------------------------------- analyse


def trajectory(c):
    """all frames of c/traj.dump: list of (time step, dict column -> array)"""
    return [(fr["step"], dumps.columns(fr)) for fr in dumps.read_frames(os.path.join(c, "traj.dump"))]


def read_data_atoms(path):
    """id, radius, x, y, z of a LAMMPS data file (atom_style sphere)"""
    lines = open(path).read().splitlines()
    k = next(i for i, line in enumerate(lines) if line.startswith("Atoms"))
    rows = []
    for line in lines[k + 2:]:
        w = line.split()
        if not w:
            break
        rows.append([float(t) for t in w[:7]])
    a = np.array(sorted(rows))
    return dict(id=a[:, 0], radius=a[:, 2] / 2, x=a[:, 4], y=a[:, 5], z=a[:, 6])


def bed_surface(atoms, L):
    """bed top: mean over 40 um columns (about two mean diameters) of the highest particle top
    above the substrate, inner columns only (away from the walls)"""
    top = atoms["z"] + atoms["radius"] - ZFLOOR
    w = 40e-6
    nc = max(1, int(L // w))
    tops = []
    for i in range(nc):
        for j in range(nc):
            sel = ((atoms["x"] >= i * w) & (atoms["x"] < (i + 1) * w)
                   & (atoms["y"] >= j * w) & (atoms["y"] < (j + 1) * w))
            if sel.any():
                tops.append(top[sel].max())
    solid = (4.0 / 3.0 * math.pi * atoms["radius"] ** 3).sum() / L ** 2
    return float(np.mean(tops)), float(solid)


def lammps_times(log):
    """step -> time from the thermo lines of the coupled LAMMPS log"""
    st = {}
    for line in open(log):
        w = line.split()
        if len(w) == 5 and w[0].isdigit():
            try:
                st[int(w[0])] = (float(w[1]), float(w[4]))
            except ValueError:
                pass
    return st


def analyse_speed(case, p, v):
    c = os.path.join(case, speed_dir(v))
    nx, ny, nz = mesh_counts(p)
    X, Y, Z, h = cell_centres(p)
    vol = h[0] * h[1] * h[2]
    xc = yc = p["L"] / 2
    times = fc.time_dirs(c)
    res = {}
    alpha0 = fc.read_internal(os.path.join(c, times[0], "alpha.metal"))
    V0 = float(np.sum(alpha0) * vol)
    # droplet free fall: centroid velocity (volume-weighted) at the write times before contact
    fall = []
    ztop_bed = None
    if p["particles"] == "on":
        atoms0 = read_data_atoms(os.path.join(c, "bed.data"))
        ztop_bed, solid = bed_surface(atoms0, p["L"])
        res["bed_top_um"] = ztop_bed * 1e6
        res["bed_solid_layer_um"] = solid * 1e6
    # footprint on the bed: the binder (alpha >= 0.5) inside the bed layer (below the bed top;
    # without particles the lowest cell layer), projected, as an equivalent radius [m]
    layer = (Z.reshape(nz, ny, nx)[:, 0, 0] - ZFLOOR) < (ztop_bed if ztop_bed is not None else h[2])

    def footprint(a3):
        return math.sqrt((a3[layer] >= 0.5).any(axis=0).sum() * h[0] * h[1] / math.pi)

    def wetted(a3):
        # columns holding at least 1 um of binder (a film thinner than a cell has alpha < 0.5)
        return math.sqrt((a3.sum(axis=0) * h[2] >= 1e-6).sum() * h[0] * h[1] / math.pi)
    lowest_start = DROP_ABOVE - DROP_D / 2     # droplet bottom above the substrate at t = 0
    last = times[-1]
    a = fc.read_internal(os.path.join(c, last, "alpha.metal"))
    res["time_ms"] = float(last) * 1e3
    res["binder_volume_rel_error"] = float((np.sum(a) * vol - V0) / V0)
    for t in times:
        at = fc.read_internal(os.path.join(c, t, "alpha.metal"))
        Ut = fc.read_internal(os.path.join(c, t, "U"))
        if Ut.ndim == 1:
            Ut = np.tile(Ut, (at.size, 1))
        m = np.sum(at)
        zlow = Z[at >= 0.5].min() - h[2] / 2 - ZFLOOR if (at >= 0.5).any() else 0.0
        fall.append((float(t), float(np.sum(at * Z) / m), float(np.sum(at * Ut[:, 2]) / m), zlow,
                     footprint(at.reshape(nz, ny, nx)), wetted(at.reshape(nz, ny, nx))))
    fall = np.array(fall)
    # reference: the droplet's centroid falls with v0 + g t, slowed by the gas drag
    # (Schiller-Naumann on the 80 um sphere, gas table 3), before its bottom reaches an obstacle
    obstacle = (ztop_bed if ztop_bed is not None else 0.0)
    gap = lowest_start - obstacle
    t_contact = max(gap, 0.0) / v
    sel = (fall[:, 0] > 0) & (fall[:, 0] <= 0.7 * t_contact)
    if sel.any():
        k = np.nonzero(sel)[0][-1]
        tk = fall[k, 0]
        w = -v
        dt = tk / 2000
        for _ in range(2000):
            re = GAS["rho"] * abs(w) * DROP_D / GAS["mu"]
            cd = 24 / re * (1 + 0.15 * re ** 0.687)
            w += dt * (-G + 0.75 * cd * GAS["rho"] / BINDER["rho"] * w * abs(w) / DROP_D * -1)
        res["fall_check_time_ms"] = tk * 1e3
        res["fall_velocity_m_s"] = -fall[k, 2]
        res["fall_velocity_reference_m_s"] = -w
    # spread: projected binder area (columns holding alpha >= 0.5) as an equivalent radius
    a3 = a.reshape(nz, ny, nx)
    wet = (a3 >= 0.5).any(axis=0)
    res["spread_radius_um"] = math.sqrt(wet.sum() * h[0] * h[1] / math.pi) * 1e6
    Xc, Yc = X.reshape(nz, ny, nx)[0], Y.reshape(nz, ny, nx)[0]
    rr = np.hypot(Xc - xc, Yc - yc)
    res["spread_max_radius_um"] = float((rr[wet].max() + h[0] / 2) * 1e6) if wet.any() else 0.0
    res["footprint_radius_um"] = footprint(a3) * 1e6
    res["footprint_radius_largest_um"] = float(fall[:, 4].max() * 1e6)
    res["footprint_radius_largest_time_ms"] = float(fall[np.argmax(fall[:, 4]), 0] * 1e3)
    res["wetted_radius_um"] = wetted(a3) * 1e6
    res["wetted_radius_largest_um"] = float(fall[:, 5].max() * 1e6)
    res["wetted_radius_largest_time_ms"] = float(fall[np.argmax(fall[:, 5]), 0] * 1e3)
    # penetration history: when the binder front reached the substrate
    reached = fall[fall[:, 3] <= 0.0, 0]
    res["binder_reaches_substrate_ms"] = float(reached[0] * 1e3) if reached.size else float("nan")
    zlow = Z[a >= 0.5].min() - h[2] / 2 - ZFLOOR if (a >= 0.5).any() else float("nan")
    res["binder_lowest_um"] = zlow * 1e6
    if ztop_bed is not None:
        res["penetration_um"] = (ztop_bed - zlow) * 1e6
        below = (Z - ZFLOOR) < ztop_bed
        res["binder_in_bed_fraction"] = float(np.sum(a[below]) / np.sum(a))
        # particles: displaced (moved more than their radius) and largest speed
        snaps = trajectory(c)
        st = lammps_times(os.path.join(c, "log.lammps"))
        s0 = snaps[0][1]
        s1 = snaps[-1][1]
        ids = np.intersect1d(s0["id"], s1["id"])
        i0 = np.searchsorted(s0["id"], ids)
        i1 = np.searchsorted(s1["id"], ids)
        d = np.sqrt(sum((s1[k][i1] - s0[k][i0]) ** 2 for k in "xyz"))
        res["particles"] = int(len(s1["id"]))
        res["displaced_particles"] = int(np.sum(d > s0["radius"][i0]))
        res["displaced_max_um"] = float(d.max() * 1e6)
        res["snapshot_time_ms"] = st.get(snaps[-1][0], (float("nan"),))[0] * 1e3
        res["max_particle_speed_m_s"] = float(max(np.sqrt(s[1]["vx"] ** 2 + s[1]["vy"] ** 2 + s[1]["vz"] ** 2).max()
                                                  for s in snaps))
        res["max_particle_speed_thermo_m_s"] = max((vm for _, vm in st.values()), default=float("nan"))

        # compression beneath the droplet: solid in the cylinder r < R_drop below the bed top
        def solid_under(s):
            r = np.hypot(s["x"] - xc, s["y"] - yc)
            return float(np.sum(4.0 / 3.0 * math.pi * s["radius"] ** 3 * (r < DROP_D / 2)))
        res["solid_under_droplet_change"] = solid_under(s1) / max(solid_under(s0), 1e-300) - 1.0
        led = os.path.join(c, "postProcessing", "particleLedger", "ledger.csv")
        if os.path.exists(led):
            rows = cc.ledger(c)[1:]
            res["ledger_mass_continuum_error_max"] = float(np.max(np.abs(rows["mass_continuum_error"])))
            res["ledger_momentum_continuum_error_max"] = float(max(np.max(np.abs(rows[f"mom_{k}_continuum_error"]))
                                                                   for k in "xyz"))
    np.savetxt(os.path.join(c, "fall.txt"), fall,
               header="time centroid_z centroid_w lowest_binder_above_substrate footprint_radius wetted_radius")
    return res


def analyse(case):
    p = json.load(open(os.path.join(case, "scene.json")))
    out = {}
    for v in p["speeds"]:
        r = analyse_speed(case, p, v)
        for k, val in r.items():
            out[f"{speed_dir(v)}_{k}"] = val
    tpath = os.path.join(case, "timing.json")
    if os.path.exists(tpath):
        out.update({f"wall_{k}": val for k, val in json.load(open(tpath)).items()})
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(out, f, indent=1, sort_keys=True)
    keys = sorted({k.split("_", 1)[1] for k in out if k.startswith("v") and not k.startswith("wall")})
    print(f"{'quantity':42s}" + "".join(f"{speed_dir(v) + ' m/s':>14s}" for v in p["speeds"]))
    for k in keys:
        vals = [out.get(f"{speed_dir(v)}_{k}") for v in p["speeds"]]
        print(f"{k:42s}" + "".join(f"{x:14.5g}" if isinstance(x, (int, float)) else f"{'-':>14s}" for x in vals))
    return out


def plot(case, out=None):
    """vertical section through the droplet axis (y = L/2) at the start and the end of each speed:
    binder fraction and the grains cut by the plane"""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.patches import Circle
    p = json.load(open(os.path.join(case, "scene.json")))
    nx, ny, nz = mesh_counts(p)
    X, Y, Z, h = cell_centres(p)
    j = ny // 2
    fig, axes = plt.subplots(len(p["speeds"]), 2, figsize=(9, 2.9 * len(p["speeds"])), squeeze=False)
    for row, v in enumerate(p["speeds"]):
        c = os.path.join(case, speed_dir(v))
        times = fc.time_dirs(c)
        snaps = trajectory(c) if p["particles"] == "on" else []
        for col, (t, snap) in enumerate([(times[0], snaps[0] if snaps else None),
                                         (times[-1], snaps[-1] if snaps else None)]):
            ax = axes[row][col]
            a = fc.read_internal(os.path.join(c, t, "alpha.metal")).reshape(nz, ny, nx)[:, j, :]
            ax.imshow(a, origin="lower", cmap="Blues", vmin=0, vmax=1,
                      extent=(0, p["L"] * 1e6, ZFLOOR * 1e6, p["ztop"] * 1e6))
            if snap is not None:
                s = snap[1]
                dy = np.abs(s["y"] - p["L"] / 2)
                for x, z, r, d in zip(s["x"], s["z"], s["radius"], dy):
                    if d < r:
                        ax.add_patch(Circle((x * 1e6, z * 1e6), math.sqrt(r * r - d * d) * 1e6,
                                            color="0.35", alpha=0.8))
            ax.axhline(ZFLOOR * 1e6, color="k", lw=1)
            ax.set_title(f"{v:g} m/s, t = {float(t) * 1e3:.3f} ms", fontsize=9)
            ax.set_xlabel("x [um]")
            ax.set_ylabel("z [um]")
    fig.tight_layout()
    out = out or os.path.join(case, "sections.png")
    fig.savefig(out, dpi=110)
    print("wrote", out)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["build", "run", "analyse", "all", "plot"])
    ap.add_argument("case")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--ci", action="store_true")
    g.add_argument("--full", action="store_true")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--speeds", help="comma-separated droplet speeds [m/s] (default 1,10,50)")
    ap.add_argument("--end", help="comma-separated end times [s], one per speed")
    ap.add_argument("--dx", type=float, help="cell size [m]")
    ap.add_argument("--particles", choices=["on", "off"], default="on")
    ap.add_argument("--distribution", choices=["overlap", "neighbours", "centre"])
    a = ap.parse_args(argv)
    case = os.path.abspath(a.case)
    if a.command in ("build", "all"):
        build(case, "full" if a.full else "ci",
              speeds=[float(s) for s in a.speeds.split(",")] if a.speeds else None,
              dx=a.dx, particles=a.particles,
              end=[float(s) for s in a.end.split(",")] if a.end else None, distribution=a.distribution)
    if a.command in ("run", "all"):
        run(case, a.np)
    if a.command in ("analyse", "all"):
        analyse(case)
    if a.command == "plot":
        plot(case)


SCENE = Scene(name="bjt-droplet", kind="coupled",
              title="Binder jetting: a binder droplet into a powder bed (Fuchs2022 §4.2, tables 2–4)",
              ci_time='1 min 39 s to 3 min 2 s wall', full_time=None,
              build=lambda case, size: main(["build", case, f"--{size}"]),
              run=lambda case, np_: main(["run", case, "--np", str(np_)]),
              analyse=lambda case: main(["analyse", case]))


if __name__ == "__main__":
    main()
