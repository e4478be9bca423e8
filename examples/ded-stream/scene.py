#!/usr/bin/env python3
"""Directed energy deposition (Fuchs2022 §4.4, tables 1-3): five 16 um steel powder
particles fly at 10 m/s along a 45 degree axis into a laser melt pool on a 20 um substrate.
Coupled meltdemFoam (substrate, melt pool, gas) + LAMMPS (the particles).

    scene.py build CASE [--ci | --full] [--switch-off] [--dx DX] [--end T] [--refine L] [--vapour-jet] ...
    scene.py run CASE [--np N]
    scene.py analyse CASE
    scene.py all CASE [--ci | --full] [--switch-off] [--np N]

Geometry (z up): box 260 x 260 x 240 um, substrate z < 20 um, substrate centre C = (130, 130,
20) um. Particle k (k = 1..5) starts with its centre h_k = 40, 60, 80, 100, 120 um above the
substrate on the 45 degree axis through C (x = 130 um - h_k, y = 130 um, z = 20 um + h_k) and
moves at 10 m/s towards C. Laser 312 W, absorptivity 0.5, effective diameter d_w = 140 um:
Fuchs2022's d_w = 2 r_w with r_w the 1/e^2 radius (sigma = r_w/2), i.e. laser { radius 70e-6; }.
Variant --switch-off: the laser goes off at t = 0.012 ms (Fuchs2022's second variant).
"""
import argparse
import functools
import json
import math
import os
import re
import time

import numpy as np

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import evaporation
from meltdem.case import foam as fc
from meltdem.case import laser
from meltdem.io import dumps
from meltdem.scene import Scene

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = paths.source_dir()
paths.set_tool_environment()

M, G = fc.METAL, fc.GAS
LX, LY, LZ = 260e-6, 260e-6, 240e-6
SUB = 20e-6                          # substrate thickness
CX, CY = LX / 2, LY / 2              # substrate centre (beam axis)
D_P = 16e-6                          # powder diameter
HEIGHTS = [40e-6, 60e-6, 80e-6, 100e-6, 120e-6]   # centres above the substrate
SPEED = 10.0
P_LASER, ETA, R_W = 312.0, 0.5, 70e-6             # d_w = 2 r_w = 140 um
T_OFF = 1.2e-5                       # switch-off variant
T0, T_MELT, DT_MUSHY = 500.0, 1700.0, 10.0
# fix powder/melt needs latent > 0 and the coupling needs the continuum's L equal to it;
# Fuchs2022 has no latent heat of fusion (mjt-droplets uses L 0): 1 J/kg is 6e-7 of cp Tm
L_FUS = 1.0
E_STEEL, NU_STEEL, RESTITUTION = 2e11, 0.3, 0.5
E_STAR_WALL = E_STEEL / (2 * (1 - NU_STEEL ** 2))  # sphere on a flat of the same steel
DEM_DT = 2e-9                        # Hertz contact time at 10-20 m/s is ~3e-8 s: >= 15 steps
PAPER = dict(pool_diameter_um=130.0, pool_time_ms=0.018, first_in_beam_ms=0.004,
             first_enters_pool_ms=0.006, second_hits_first_ms=0.007, third_immerses_ms=0.009,
             last_flies_ms=0.026)

# end times: laser on to just past Fuchs2022's 0.018 ms pool; the switch-off variant to
# Fuchs2022's 0.026 ms. step_cells_off: the fluid step in cells of particle travel
VARIANTS = {"ci": dict(dx=10e-6, end=2.0e-5, end_off=2.6e-5, write=1e-6, step_cells=0.25, step_cells_off=0.25),
            "full": dict(dx=5e-6, end=2.6e-5, end_off=2.6e-5, write=1e-6, step_cells=0.25, step_cells_off=0.02)}


def particle_starts():
    """(position, velocity) of the five particles."""
    u = np.array([1.0, 0.0, -1.0]) / math.sqrt(2.0)
    return [(np.array([CX - h, CY, SUB + h]), SPEED * u) for h in HEIGHTS]


def kinematic_arrival(h):
    """Time for a particle on a straight line at 10 m/s to touch the substrate's top (centre
    R above it): vertical distance h - R at 10/sqrt(2) m/s."""
    return (h - D_P / 2) / (SPEED / math.sqrt(2.0))


def mesh_counts(dx):
    n = tuple(int(round(L / dx)) for L in (LX, LY, LZ))
    for L, k in zip((LX, LY, LZ, SUB), n + (int(round(SUB / dx)),)):
        if abs(k * dx - L) > 1e-3 * dx:
            raise SystemExit(f"dx = {dx:g} m does not divide {L:g} m (260, 240 and 20 um must be multiples)")
    return n


def centres(n, dx):
    """Cell centres in blockMesh order (x fastest, then y, then z)."""
    xc = (np.arange(n[0]) + 0.5) * dx
    yc = (np.arange(n[1]) + 0.5) * dx
    zc = (np.arange(n[2]) + 0.5) * dx
    Z, Y, X = np.meshgrid(zc, yc, xc, indexing="ij")
    return X.ravel(), Y.ravel(), Z.ravel()


def refinement_dict(levels, interval=1):
    """refinement{} of a --refine run: the finest cells in the pool and the metal about to melt,
    under the beam and around every grain; coarse cells in the gas and the deep substrate."""
    return fc.refinement_dict(levels, interval, [("meltPool", "belowSolidus 300;"), ("laser", "radii 1.2;"),
                                                 ("grains", "type particles; diameters 1; near (anywhere);")])


def build(a):
    case = a.case
    os.makedirs(case, exist_ok=True)
    h = a.dx * 2 ** a.refine           # the base mesh (refined to dx where needed)
    n = mesh_counts(h)
    # closed walls as in Fuchs2022, except the top: open to the atmosphere, so that the gas the
    # molten powder displaces (the coupling's volume source) can leave a box of incompressible
    # phases
    cc.box_mesh(case, (0, 0, 0), (LX, LY, LZ), n,
                {"walls": ("wall", ["xmin", "xmax", "ymin", "ymax", "zmin"]), "top": ("patch", ["zmax"])})
    X, Y, Z = centres(n, h)
    alpha = np.where(Z < SUB, 1.0, 0.0)
    cc.uniform_field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha,
                     {"walls": "type zeroGradient;",
                      "top": "type inletOutlet; inletValue uniform 0; value uniform 0;"})
    cc.uniform_field(case, "T", "[0 0 0 1 0 0 0]", T0,
                     {"walls": f"type fixedValue; value uniform {T0!r};",
                      "top": f"type inletOutlet; inletValue uniform {T0!r}; value uniform {T0!r};"})
    cc.uniform_field(case, "U", "[0 1 -1 0 0 0 0]", (0.0, 0.0, 0.0),
                     {"walls": "type noSlip;",
                      "top": "type pressureInletOutletVelocity; value uniform (0 0 0);"}, vector=True)
    cc.uniform_field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", 0.0,
                     {"walls": "type fixedFluxPressure; value uniform 0;",
                      "top": "type totalPressure; p0 uniform 0; value uniform 0;"})
    fc.transport(case, M["rho"], M["mu"] / M["rho"], G["rho"], G["mu"] / G["rho"], M["sigma0"])
    fc.gravity(case, (0.0, 0.0, -9.81))
    rho_avg = 0.5 * (M["rho"] + G["rho"])
    dt_cap = math.sqrt(rho_avg * a.dx ** 3 / (2 * math.pi * M["sigma0"]))
    # a particle crosses at most a quarter cell per fluid step (it samples the fluid once a step)
    max_dt = min(dt_cap, a.step_cells * a.dx / SPEED)
    # (not far below max_dt: the coupling rounds the fluid step down to whole DEM steps, so a
    # first step of a few DEM steps could only grow by the 1.2 factor rounded down, i.e. never)
    fc.control_dict(case, "meltdemFoam", a.end, max_dt / 2, a.write, max_co=a.max_co, max_alpha_co=a.max_co,
                    max_dt=max_dt, extra=fc.CELL_GEOMETRY_FUNCTIONS if a.refine else "")
    fc.fv_schemes(case)
    fc.fv_solution(case, n_correctors=3)
    cc.exact_solves(case, T=1e-14, relaxation=True)   # the metal mass and enthalpy balances
    t_off = f"    tOff {T_OFF!r};\n" if a.switch_off else ""
    extra = f"""metal
{{
    Tsolidus    {T_MELT - DT_MUSHY / 2!r};
    Tliquidus   {T_MELT + DT_MUSHY / 2!r};
    L           {L_FUS!r};
    cp          {M['cp']!r};
    k           {M['k']!r};
}}
gas {{ cp {G['cp']!r}; k {G['k']!r}; }}
darcy {{ C 1e10; b 1e-3; }}
energyControls {{ nCorrectors 30; tolerance 1e-10; }}
laser
{{
    power        {P_LASER!r};
{laser.absorptivity_entries(a, ETA, T_MELT + DT_MUSHY / 2)}    radius       {R_W!r};
    direction    (0 0 -1);
    position     ({CX!r} {CY!r} {LZ - a.dx / 2!r});
    tOn          0;
{t_off}}}
{evaporation.steel_dict(M['cp'], a.vapour_jet)}particles
{{
    lammpsInput     in.particles;
    distribution    {a.distribution};
    demStepsPerFluidStep auto;
}}
{refinement_dict(a.refine, a.refine_interval) if a.refine else ""}"""
    physics = {"energy": "on", "darcy": "on", "marangoni": "on", "laser": "on", "particles": "on",
               "evaporation": "on" if a.evaporation else "off", "recoil": "on" if a.recoil else "off"}
    fc.meltdem_properties(case, physics=physics, surface={"nSmooth": a.nsmooth}, extra=extra)
    m = 20e-6
    atoms = "".join(f"create_atoms 1 single {p[0]!r} {p[1]!r} {p[2]!r}\n" for p, _ in particle_starts())
    v = particle_starts()[0][1]
    dump_every = max(1, int(round(a.dump_dt / DEM_DT)))
    with open(os.path.join(case, "in.particles"), "w") as f:
        f.write(f"""# SPH paper 4.4: five 16 um steel particles, 45 degree stream at 10 m/s (written by scene.py)
units si
atom_style sphere 1
dimension 3
boundary f f f
region box block {-m!r} {LX + m!r} {-m!r} {LY + m!r} {-m!r} {LZ + m!r}
create_box 1 box
{atoms}set type 1 diameter {D_P!r} density {M['rho']!r}
velocity all set {v[0]!r} {v[1]!r} {v[2]!r}
comm_modify vel yes cutoff {2 * D_P!r}
neighbor 4e-6 bin
neigh_modify every 1 delay 0
pair_style granular/powder
pair_coeff * * hertz/material {E_STEEL!r} {RESTITUTION!r} {NU_STEEL!r} damping tsuji tangential linear_nohistory 0 0
timestep {DEM_DT!r}
fix integrate all nve/sphere
fix gravity all gravity 9.81 vector 0 0 -1
fix melt all powder/melt cp {M['cp']!r} Tmelt {T_MELT!r} latent {L_FUS!r} temp {T0!r} solid_metal {E_STAR_WALL!r} {RESTITUTION!r}
dump track all custom {dump_every} particles.dump id x y z vx vy vz radius f_melt[1] f_melt[2]
dump_modify track sort id format float %.10g
thermo_style custom step time atoms f_melt[1] f_melt[6]
thermo 1000
""")  # noqa: E501  (a long line of the LAMMPS input written verbatim)
    with open(os.path.join(case, "scene.json"), "w") as f:
        json.dump(dict(vars(a), n=n, scene="ded-stream"), f, indent=1)
    print(f"built {case}: {n[0]} x {n[1]} x {n[2]} cells of {h * 1e6:g} um"
          f"{f' refined to {a.dx * 1e6:g} um' if a.refine else ''} "
          f"({D_P / a.dx:.2f} cells per particle diameter), to t = {a.end * 1e3:g} ms, "
          f"laser {'off at 0.012 ms' if a.switch_off else 'on throughout'}")


def run(case, np_=1):
    fc.run(["blockMesh"], case, "log.blockMesh")
    t0 = time.time()
    if np_ > 1:
        cc.decompose(case, np_, (np_, 1, 1))
    cc.run_solver(case, np_)
    wall = time.time() - t0
    with open(os.path.join(case, "wall_seconds"), "w") as f:
        f.write(f"{wall:.1f} {np_}\n")
    print(f"solver wall time {wall:.1f} s on {np_} rank(s)")


# ---------------------------------------------------------------- analysis
DUMP_DT = 1e-7


def read_tracks(case):
    """{id: array of rows (t, x, y, z, vx, vy, vz, r, T, fmelt)}; the time is step * DEM_DT."""
    return dumps.tracks(os.path.join(case, "particles.dump"), DEM_DT)


def results_dirs(case):
    dirs = [d for d in fc.time_dirs(case) if float(d) > 0 and os.path.exists(os.path.join(case, d, "T"))]
    if not dirs and os.path.isdir(os.path.join(case, "processor0")):
        raise SystemExit("analyse reads the reconstructed case: run reconstructPar first")
    return dirs


def pool_stats(case, dx, n):
    """Per written time: (t, pool diameter [m] = 2 sqrt(A/pi) of the area A of the columns with a
    molten metal cell (alpha >= 0.5, T >= Tm), depth of the molten metal below the substrate top
    [m], peak T, molten metal volume [m3]). n: cells of dx (the finest cells of a refined run, whose
    fields are mapped onto them)."""
    X, Y, Z = centres(n, dx)
    rows = []
    for d in results_dirs(case):
        T = fc.lattice_field(case, d, "T", n, dx).ravel()
        a = fc.lattice_field(case, d, "alpha.metal", n, dx).ravel()
        molten = (a >= 0.5) & (T >= T_MELT)
        cols = molten.reshape(n[2], n[1] * n[0]).any(axis=0)
        area = cols.sum() * dx * dx
        depth = SUB - (Z[molten].min() - dx / 2) if molten.any() else 0.0
        vol = np.sum(a * (T >= T_MELT)) * dx ** 3
        rows.append((float(d), 2 * math.sqrt(area / math.pi), max(depth, 0.0), float(T.max()), vol))
    return np.array(rows)


@functools.lru_cache(maxsize=2)
def _read_text(path, mtime_ns, size):
    with open(path) as f:
        return f.read()


def solver_log(case):
    """The case's solver log, read once while it does not change (the analysis reads it twice)."""
    path = os.path.join(case, "log.meltdemFoam")
    st = os.stat(path)
    return _read_text(path, st.st_mtime_ns, st.st_size)


def laser_budget(case):
    """Per fluid step: time, continuum absorbed power (solver log), particles' absorbed power."""
    log = solver_log(case)
    cont = np.array([float(x) for x in re.findall(r"Laser: absorbed power (\S+) W", log)])
    p = cc.particles_csv(case)
    k = min(len(cont), len(p))
    return p["time"][:k], p["dt"][:k], cont[:k], p["laser_heat"][:k] / p["dt"][:k]


def laser_absorptivity(case, eta0):
    """Per absorbed-power line of the solver log (laser_budget's rows are its first ones): the
    absorptivity the step used (the linear model's)."""
    return laser.step_absorptivity(solver_log(case), eta0)[2]


def particle_events(tracks, t_end):
    """Per particle: arrival = first dump time its bottom reaches the substrate top, it is
    deflected (velocity off the initial by > 20 %), or it melts away within 5 um of the
    substrate top; its molten fraction and its fate. A particle missing from the last dumps
    melted completely (fix powder/melt deletes it; one that left the mesh would be booked as
    lost and stop the run's ledger showing it)."""
    out = []
    for k, h in enumerate(HEIGHTS, start=1):
        tr = tracks.get(k)
        ev = dict(id=k, start_height_um=h * 1e6, kinematic_arrival_ms=kinematic_arrival(h) * 1e3)
        if tr is None or not len(tr):
            out.append(ev)
            continue
        last = tr[-1]
        gone = last[0] < t_end - 2 * DUMP_DT
        bottom = last[3] - last[7]
        v0 = np.array(particle_starts()[k - 1][1])
        dv = np.linalg.norm(tr[:, 4:7] - v0, axis=1) / SPEED
        touch = tr[:, 3] - tr[:, 7] <= SUB
        hit = np.nonzero(touch | (dv > 0.2))[0]
        if len(hit):
            ev["arrival_ms"] = float(tr[hit[0], 0] * 1e3)
            ev["arrival_by"] = "substrate level" if touch[hit[0]] else "deflected"
        elif gone and bottom <= SUB + 5e-6:
            ev["arrival_ms"], ev["arrival_by"] = float(last[0] * 1e3), "melted at the surface"
        else:
            ev["arrival_ms"], ev["arrival_by"] = None, None
        # molten fraction from the shrinking radius (fix powder/melt keeps the density)
        ev["molten_fraction"] = 1.0 if gone else float(max(last[9], 1 - (last[7] / (D_P / 2)) ** 3))
        ev["last_seen_ms"] = float(last[0] * 1e3)
        ev["last_bottom_above_substrate_um"] = float((bottom - SUB) * 1e6)
        ev["peak_T_K"] = T_MELT if gone else float(tr[:, 8].max())
        ev["final_z_um"] = float(last[3] * 1e6)
        ev["final_vz"] = float(last[6])
        ev["bounced"] = bool(np.any(tr[:, 6] > 0))
        if gone:
            where = "at the pool surface" if bottom <= SUB + 5e-6 else "in flight"
            ev["fate"] = f"melted {where}" + (" after bouncing" if ev["bounced"] else "")
        elif bottom > SUB + 1e-6 and ev["bounced"]:
            ev["fate"] = "bounced, above the substrate"
        elif ev["arrival_ms"] is None:
            ev["fate"] = "in flight"
        else:
            ev["fate"] = "in the pool / on the substrate"
        out.append(ev)
    return out


def analyse(case):
    a = json.load(open(os.path.join(case, "scene.json")))
    dx, f = a["dx"], 2 ** a.get("refine", 0)
    n = tuple(k * f for k in a["n"])         # the finest cells
    pool = pool_stats(case, dx, n)
    tracks = read_tracks(case)
    t, dt, cont, part = laser_budget(case)
    events = particle_events(tracks, float(t[-1]))
    lit = (t - dt >= 0) & (t <= (T_OFF if a["switch_off"] else 1e9))
    if a["switch_off"]:
        lit &= t <= T_OFF - 1e-15
    eta0 = ETA if a.get("absorptivity") is None else a["absorptivity"]
    eta_p = laser_absorptivity(case, eta0)[:len(t)] * P_LASER
    err = (np.abs(cont + part - eta_p) / eta_p)[lit]
    dark = ~lit & (t - dt >= T_OFF - 1e-15) if a["switch_off"] else np.zeros_like(lit)
    d = cc.ledger(case)
    steps = d[1:]
    s = {}
    s["cells"] = int(np.prod(n))
    s["cell_um"] = dx * 1e6
    s["cells_per_particle_diameter"] = D_P / dx
    s["switch_off"] = bool(a["switch_off"])
    s["end_time_ms"] = float(t[-1] * 1e3) if len(t) else 0.0
    s["fluid_steps"] = int(len(t))
    if os.path.exists(os.path.join(case, "wall_seconds")):
        w = open(os.path.join(case, "wall_seconds")).read().split()
        s["wall_s"], s["ranks"] = float(w[0]), int(w[1])
    s["solver_cpu_s"] = fc.execution_time(case)
    s["pool_time_ms"] = [float(x) for x in pool[:, 0] * 1e3]
    s["pool_diameter_um"] = [float(x) for x in pool[:, 1] * 1e6]
    s["pool_depth_um"] = [float(x) for x in pool[:, 2] * 1e6]
    s["peak_T_K"] = [float(x) for x in pool[:, 3]]
    s["molten_volume_um3"] = [float(x) for x in pool[:, 4] * 1e18]
    at = np.argmin(np.abs(pool[:, 0] - PAPER["pool_time_ms"] * 1e-3))
    s["pool_diameter_at_0.018ms_um"] = float(pool[at, 1] * 1e6) if abs(pool[at, 0] - 1.8e-5) < 1e-7 else None
    s["pool_diameter_final_um"] = float(pool[-1, 1] * 1e6)
    s["max_pool_diameter_um"] = float(pool[:, 1].max() * 1e6)
    s["laser_lit_steps"] = int(lit.sum())
    s["laser_worst_rel_error_lit"] = float(err.max()) if len(err) else None
    s["laser_absorbed_by_particles_J"] = float(np.sum(part * dt))
    s["laser_absorbed_by_continuum_J"] = float(np.sum(cont * dt))
    lost = np.sum(((eta_p - cont - part) * dt)[lit])
    s["laser_energy_short_of_eta_P_J"] = float(lost)
    s["laser_energy_short_of_eta_P_fraction"] = float(lost / np.sum((eta_p * dt)[lit]))
    s["laser_absorptivity_mean_lit"] = float(np.sum((eta_p * dt)[lit]) / np.sum(dt[lit]) / P_LASER)
    s["laser_max_after_off_W"] = float(np.max(cont[dark] + part[dark])) if np.any(dark) else None
    s["worst_mass_continuum_error"] = float(np.max(np.abs(steps["mass_continuum_error"])))
    s["worst_enthalpy_continuum_error"] = float(np.max(np.abs(steps["enthalpy_continuum_error"])))
    s["worst_mass_system_error"] = float(np.max(np.abs(steps["mass_system_error"])))
    s["worst_enthalpy_system_error"] = float(np.max(np.abs(steps["enthalpy_system_error"])))
    s["particles"] = events
    s["paper"] = PAPER
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(s, f, indent=1)
    print_summary(s)
    return s


def print_summary(s):
    print(f"DED stream, {s['cells']} cells of {s['cell_um']:g} um ({s['cells_per_particle_diameter']:.2f} per "
          f"particle diameter), laser {'off at 0.012 ms' if s['switch_off'] else 'on'}, to "
          f"{s['end_time_ms']:.4f} ms in {s['fluid_steps']} fluid steps"
          + (f", {s['wall_s']:.0f} s wall on {s['ranks']} rank(s)" if "wall_s" in s else "")
          + (f", solver CPU {s['solver_cpu_s']:.0f} s" if s.get("solver_cpu_s") else ""))
    print("   t [ms]  pool diameter [um]  depth [um]  peak T [K]")
    for t, dd, dp, T in zip(s["pool_time_ms"], s["pool_diameter_um"], s["pool_depth_um"], s["peak_T_K"]):
        print(f"  {t:7.4f}  {dd:18.1f}  {dp:10.1f}  {T:10.0f}")
    print(f"pool diameter at 0.018 ms: {s['pool_diameter_at_0.018ms_um']} um (paper ~130 um)")
    print(" id  h0[um]  arrival[ms] (by)                 kinematic[ms]  molten  peak T[K]  fate")
    for e in s["particles"]:
        arr = e.get("arrival_ms")
        arr_s = f"{arr:.4f} ({e.get('arrival_by')})" if arr is not None else "-"
        print(f"  {e['id']}  {e['start_height_um']:6.0f}  {arr_s:32s} {e['kinematic_arrival_ms']:.4f}"
              f"         {e.get('molten_fraction', float('nan')):.3f}  {e.get('peak_T_K', float('nan')):8.0f}"
              f"  {e.get('fate', '-')}")
    print(f"laser: worst |continuum + particles - eta P|/eta P on {s['laser_lit_steps']} lit steps "
          f"{s['laser_worst_rel_error_lit']:.2e}; particles absorbed {s['laser_absorbed_by_particles_J']:.3e} J, "
          f"continuum {s['laser_absorbed_by_continuum_J']:.3e} J; short of eta P t by "
          f"{s['laser_energy_short_of_eta_P_fraction']:.2e} (light on particles that melted away)")
    print(f"ledger: worst per-step continuum errors mass {s['worst_mass_continuum_error']:.2e}, enthalpy "
          f"{s['worst_enthalpy_continuum_error']:.2e}; system mass {s['worst_mass_system_error']:.2e}, "
          f"enthalpy {s['worst_enthalpy_system_error']:.2e}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--ci", dest="variant", action="store_const", const="ci")
    g.add_argument("--full", dest="variant", action="store_const", const="full")
    ap.add_argument("--switch-off", action="store_true", help="laser off at 0.012 ms (paper's 2nd variant)")
    ap.add_argument("--dx", type=float, help="cell size [m] (ci 10e-6, full 5e-6)")
    ap.add_argument("--end", type=float, help="end time [s] (ci 2.0e-5, switch-off and full 2.6e-5)")
    ap.add_argument("--write", type=float, help="write interval [s] (1e-6)")
    ap.add_argument("--dump-dt", type=float, default=DUMP_DT, help="particle dump interval [s]")
    ap.add_argument("--distribution", default="overlap", choices=["centre", "neighbours", "overlap"])
    ap.add_argument("--nsmooth", type=int, default=2)
    ap.add_argument("--max-co", type=float, default=0.25, help="maxCo and maxAlphaCo")
    ap.add_argument("--step-cells", type=float,
                    help="largest fluid step as the fraction of a cell a 10 m/s particle crosses "
                         "(0.25; full switch-off 0.02)")
    ap.add_argument("--no-recoil", dest="recoil", action="store_false")
    ap.add_argument("--no-evaporation", dest="evaporation", action="store_false")
    ap.add_argument("--vapour-jet", action="store_true", help=evaporation.VAPOUR_JET_HELP)
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--refine", type=int, default=0, metavar="L",
                    help="adaptive refinement: base cells 2^L x --dx, refined to --dx in the pool, under the beam "
                    "and around the grains (refinement{})")
    ap.add_argument("--refine-interval", type=int, default=1, metavar="N", help="fluid steps between mesh updates")
    laser.add_absorptivity_arguments(ap, ETA)
    a = ap.parse_args(argv)
    laser.check_absorptivity_arguments(ap, a, ETA)
    if a.vapour_jet and not a.evaporation:
        ap.error("--vapour-jet needs evaporation (drop --no-evaporation)")
    v = VARIANTS[a.variant or "ci"]
    a.dx = a.dx or v["dx"]
    a.end = a.end or (v["end_off"] if a.switch_off else v["end"])
    a.write = a.write or v["write"]
    a.step_cells = a.step_cells or (v["step_cells_off"] if a.switch_off else v["step_cells"])
    if a.action in ("build", "all"):
        build(a)
    if a.action in ("run", "all"):
        run(a.case, a.np)
        if a.np > 1:
            fc.reconstruct(a.case)
    if a.action in ("analyse", "all"):
        analyse(a.case)


SCENE = Scene(name="ded-stream", kind="coupled",
              title="Directed energy deposition: a powder stream into a laser melt pool (Fuchs2022 §4.4)",
              ci_time='15 s (idle machine)', full_time='23 min (5 um cells, to 0.020 ms)',
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]))


if __name__ == "__main__":
    main()
