#!/usr/bin/env python3
"""SLM single track over a generated powder bed (Codina2019 §4.2.2, tables 4.5 / 4.6),
coupled meltdemFoam + LAMMPS.

    scene.py build CASE [--ci | --full] [--cell H] [--bed DUMP] [--track L] [--distribution M]
                   [--gas-cp CP] [--gas-mu MU] [--fluid-dt DT] [--no-surface] [--vapour-jet]
    scene.py run CASE [--np N]
    scene.py analyse CASE
    scene.py all CASE [--ci | --full] [--np N] [build options]

build pours the powder bed with examples/powder-bed/in.powder-bed (closed box, the Codina2019
table 4.3 settings) unless --bed gives its dump, turns the dump into a LAMMPS data file
(the coupled run's initial particle state) and writes the OpenFOAM case: a box of uniform
hexahedra over the bed's floor, a solid SS304 substrate below the floor (y < 0), argon above,
a Gaussian laser (100 W, 0.1 mm spot, 0.5 m/s, absorptivity 0.5) moving along x over the
middle of the bed. See README.md for the choices and the definitions of the measured numbers.
"""
import argparse
import json
import os
import re
import subprocess
import sys
import time

import numpy as np

from meltdem import paths
from meltdem.analysis import profiles
from meltdem.case import coupled as cc
from meltdem.case import evaporation
from meltdem.case import foam as fc
from meltdem.case import laser as beam
from meltdem.io import dumps
from meltdem.scene import Scene

HERE = os.path.dirname(os.path.abspath(__file__))
SRC = paths.source_dir()
paths.set_tool_environment()

# --- Codina2019 tables 4.5 / 4.6 ---------------------------------------------------------
POWER, SPOT, SPEED, ETA = 100.0, 0.1e-3, 0.5, 0.5   # W, spot diameter (1/e^2) m, m/s, absorptivity
ALPHA_P, ALPHA_W = 0.5, 0.5                         # damping alpha particle-particle / wall (table 4.6)
# --- SS304 (representative values averaged over 300-1700 K; one set for powder and substrate) ---
RHO, CP, K, LATENT = 7900.0, 600.0, 25.0, 2.7e5
TSOL, TLIQ, TMELT = 1673.0, 1723.0, 1700.0          # the particles melt at TMELT (inside the range)
MU_MELT, SIGMA0, DSIGMA = 6e-3, 1.8, -4e-4          # Pa s, N/m, N/m/K
E_YOUNG, NU, MU_FRICTION = 200e9, 0.3, 0.1          # as examples/powder-bed
# --- argon at 300 K ---
GAS = dict(rho=1.6, mu=2.2e-5, cp=520.0, k=0.018)
# the gas of the case: argon (--gas-cp for the numerical gas of the mesh benchmark)
GAS_CP_CASE, GAS_MU_CASE = GAS["cp"], GAS["mu"]
T0 = 300.0
DEM_DT = 5e-9                                      # s: 1/10 of the Hertz time of two 15 um grains at 1 m/s
VMAX_DEM = 10.0                                    # m/s: speed limit of the DEM integration (see in.particles)
FLUID_DT = 5e-7                                    # s: fluid step (fixed, see README)
SURFACE = True                                     # surface tension and Marangoni (see README)
FINE_COURANT = 0.3                                 # the flow's step on cells finer than the variant's (README)
G = 9.81                                            # the bed was poured at 10 g; the scan runs at 1 g

VARIANTS = {
    # floor Lx x Lz, gas top, substrate thickness, cell, track start/end (x), cool-down, write interval
    "ci": dict(lx=0.3e-3, lz=0.3e-3, top=150e-6, sub=90e-6, cell=30e-6, x0=50e-6, x1=250e-6,
               cool=40e-6, write=10e-6),
    "full": dict(lx=0.9e-3, lz=0.9e-3, top=210e-6, sub=90e-6, cell=30e-6, x0=100e-6, x1=800e-6,
                 cool=100e-6, write=20e-6),
}


def e_of_alpha(a):
    """Restitution of the Tsuji-damped Hertz contact x'' = -x^1.5 - a x^0.25 x' (Codina2019 eq. 3.5):
    e depends on alpha alone (doc/pair_granular_powder.rst)."""
    from scipy.integrate import solve_ivp

    def f(t, y):
        x = max(y[0], 0.0)
        return [y[1], -x ** 1.5 - a * x ** 0.25 * y[1]]
    ev = lambda t, y: y[0]  # noqa: E731
    ev.terminal, ev.direction = True, -1
    s = solve_ivp(f, [0, 100], [1e-12, 1.0], events=ev, rtol=1e-11, atol=1e-14, max_step=0.01)
    return float(-s.y_events[0][0][1])


def mpi_env():
    return {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


# ------------------------------------------------------------------------------------------ build
def pour_bed(case, v):
    """Run examples/powder-bed for this floor (closed box, Codina2019 table 4.3) into CASE/bed/;
    v["seed"], where given, pours another bed (the input's own seed otherwise)."""
    bed = os.path.join(case, "bed")
    os.makedirs(bed, exist_ok=True)
    cmd = [paths.binary("meltdem-lmp"), "-in", os.path.join(SRC, "examples", "powder-bed", "in.powder-bed"),
           "-var", "Lx", repr(v["lx"]), "-var", "Lz", repr(v["lz"]), "-var", "sides", "wall",
           "-var", "every", "2000", "-var", "dump", "bed.dump", "-log", "log.powder-bed"]
    if v.get("seed"):
        cmd += ["-var", "seed", str(int(v["seed"]))]
    if v.get("np", 1) > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(v["np"])] + cmd
    t = time.time()
    with open(os.path.join(bed, "out.powder-bed"), "w") as f:
        subprocess.run(cmd, cwd=bed, stdout=f, stderr=subprocess.STDOUT, check=True, env=dict(os.environ, **mpi_env()))
    print(f"powder bed poured in {time.time() - t:.0f} s -> {bed}/bed.dump")
    return os.path.join(bed, "bed.dump")


def spread_bed(case, v):
    """Spread the bed with examples/powder-spread (blade, 2 d90 gap, its defaults) into CASE/spread/
    over this floor; returns its layer dump (the plate's middle lx x lz)."""
    from meltdem.scene import module
    t = time.time()
    dump, n = module("powder-spread").spread_bed(os.path.join(case, "spread"), v["lx"], v["lz"])
    print(f"powder bed spread in {time.time() - t:.0f} s: {n} grains -> {dump}")
    return dump


def write_data(case, dump, v):
    """LAMMPS data file of the bed (atom_style sphere: id type diameter density x y z), at rest;
    the box is the mesh plus a margin (the coupling books particles leaving the mesh)."""
    d = dumps.columns(dumps.read_frames(dump)[0])
    order = np.argsort(d["id"])
    r, m = d["radius"][order], d["mass"][order]
    dens = m / (4.0 / 3.0 * np.pi * r ** 3)
    x, y, z = d["x"][order], d["y"][order], d["z"][order]
    margin = 5e-5
    with open(os.path.join(case, "bed.data"), "w") as f:
        f.write(f"SLM track: powder bed from {os.path.basename(dump)}\n\n{len(r)} atoms\n1 atom types\n\n")
        f.write(f"{-margin!r} {v['lx'] + margin!r} xlo xhi\n{-v['sub'] - margin!r} {v['top'] + margin!r} ylo yhi\n"
                f"{-margin!r} {v['lz'] + margin!r} zlo zhi\n\nAtoms # sphere\n\n")
        for i in range(len(r)):
            f.write(f"{i + 1} 1 {2 * r[i]!r} {dens[i]!r} {x[i]!r} {y[i]!r} {z[i]!r}\n")
    return len(r)


def lammps_input(case, v, dump_every):
    e_wall = e_of_alpha(ALPHA_W)
    w = (f"hertz/material {E_YOUNG!r} 0.5 {NU!r} damping tsuji/alpha {ALPHA_W!r} "
         f"tangential mindlin NULL 1.0 {MU_FRICTION!r}")
    with open(os.path.join(case, "in.particles"), "w") as f:
        f.write(f"""# SLM track (thesis 4.2.2, table 4.6): the generated powder bed, coupled to meltdemFoam
units           si
atom_style      sphere 1
atom_modify     map array
boundary        f f f
newton          off
comm_modify     vel yes
read_data       bed.data
neighbor        1e-5 bin
neigh_modify    delay 0
pair_style      granular/powder 4.5e-5
# table 4.6: alpha 0.5 between particles and with walls (tsuji/alpha takes alpha directly)
pair_coeff      * * hertz/material {E_YOUNG!r} 0.5 {NU!r} damping tsuji/alpha {ALPHA_P!r} &
                tangential mindlin NULL 1.0 {MU_FRICTION!r}
# nve/limit: a melting grain's remnant shrinks towards zero radius and its Hertz time with it; a
# contact of such a remnant can throw it far within one fluid step (LAMMPS then loses it). The
# limit {VMAX_DEM:g} m/s is over 10 x the fastest grain measured (0.5-0.6 m/s); f_integrate counts the limited updates
# (reported). It integrates no rotation: the grains keep their angular velocity (zero).
fix             integrate all nve/limit {VMAX_DEM * DEM_DT!r}
fix             gravity all gravity {G!r} vector 0 -1 0
# side walls of the powder box (the mesh's side walls) and the substrate top y = 0 as a granular
# wall of the same steel (alpha {ALPHA_W}, e = {e_wall:.4f}); see README for why not solid_metal
fix             sidex all wall/gran/powder granular {w} xplane 0.0 {v['lx']!r}
fix             sidez all wall/gran/powder granular {w} zplane 0.0 {v['lz']!r}
fix             floor all wall/gran/powder granular {w} yplane 0.0 NULL
# fixed DEM step (not fix powder/dt): a melting grain shrinks and its Hertz time with it, and
# the coupled sub-cycle count is fixed from the step at the start of a fluid step (see README)
fix             melt all powder/melt cp {CP!r} Tmelt {TMELT!r} latent {LATENT!r} temp {T0!r}
compute         ov all powder/overlap threshold 0.01
compute         vmax all reduce max vy
variable        t equal time
thermo_style    custom step v_t dt atoms c_ov[1] c_ov[2] c_ov[3] c_vmax f_melt[1] f_melt[2] f_integrate
thermo_modify   lost warn norm no flush yes
thermo          {dump_every}
timestep        {DEM_DT!r}
dump            traj all custom {dump_every} particles.dump id radius x y z vx vy vz
dump_modify     traj time yes sort id format float %.9g
run             0
""")


def refinement_dict(levels, interval=1, grain_reach=1.0):
    """refinement{} of a --refine run: the finest cells in the melt pool and the metal about to melt,
    under the beam and where it will be over the next half spot of travel (at least until the next
    update), and within grain_reach diameters of the grains near either; coarse cells elsewhere."""
    ahead = f"lookAhead {interval}; lookAheadTime {0.5 * SPOT / SPEED!r};"
    grains = f"type particles; diameters {grain_reach:g}; near (pool beam);"
    return fc.refinement_dict(levels, interval, [("meltPool", "belowSolidus 300;"),
                                                 ("laser", f"radii 1.5; {ahead}"),
                                                 ("grains", grains)])


def build(case, variant, cell=None, bed=None, track=None, distribution="overlap", np_=1, gas_cp=None, fluid_dt=None,
          gas_mu=None, surface=None, refine=0, refine_interval=1, courant=None, laser_args=None, vapour_jet=False,
          grain_reach=1.0):
    v = dict(VARIANTS[variant])
    surface = SURFACE if surface is None else surface
    gas_cp = gas_cp or GAS_CP_CASE
    gas_mu = gas_mu or GAS_MU_CASE
    if cell:
        v["cell"] = cell
    if track:
        v["x1"] = v["x0"] + track
    v["np"] = np_
    h_fine = v["cell"]
    h = h_fine * 2 ** refine                     # the base mesh (refined to h_fine where needed)
    if courant is None and fluid_dt is None and surface and h_fine < VARIANTS[variant]["cell"]:
        # the fixed step outruns the flow's Courant limit on finer cells once surface forces drive
        # the pool (README): the flow's own step unless a step is given
        courant = FINE_COURANT
    v["sub"] = max(h, round(v["sub"] / h) * h)   # substrate top (y = 0) on a cell face
    v["top"] = max(h, round(v["top"] / h) * h)
    n = (int(round(v["lx"] / h)), int(round((v["sub"] + v["top"]) / h)), int(round(v["lz"] / h)))
    os.makedirs(case, exist_ok=True)
    dump = spread_bed(case, v) if bed == "spread" else bed or pour_bed(case, v)
    nparticles = write_data(case, dump, v)
    t_scan = (v["x1"] - v["x0"]) / SPEED
    t_end = t_scan + v["cool"]
    zc = v["lz"] / 2
    # capillary limit dt <= sqrt(rho_mean h^3 / (2 pi sigma)), with a margin
    dt_cap = 0.5 * np.sqrt(0.5 * (RHO + GAS["rho"]) * h_fine ** 3 / (2 * np.pi * SIGMA0))
    # fixed sub-cycles (see README): the fluid step is n_sub DEM steps (FLUID_DT; below the
    # capillary limit when surface tension is on)
    fluid_dt = fluid_dt or FLUID_DT
    fluid_dt = min(fluid_dt, dt_cap) if surface else fluid_dt
    n_sub = max(1, int(round(fluid_dt / DEM_DT)))
    # courant: the step the flow allows (Courant number <= courant, at most fluid_dt), the DEM
    # sub-cycles recomputed every step; else the fixed step of n_sub DEM steps
    sub_cycles = "auto" if courant else n_sub
    cc.box_mesh(case, (0.0, -v["sub"], 0.0), (v["lx"], v["top"], v["lz"]), n,
                {"substrate": ("wall", ["ymin"]), "atmosphere": ("patch", ["ymax"]),
                 "sides": ("wall", ["xmin", "xmax", "zmin", "zmax"])})
    yc = -v["sub"] + (np.arange(n[1]) + 0.5) * h
    ycell = np.broadcast_to(yc[None, :, None], (n[2], n[1], n[0])).ravel()
    alpha = np.where(ycell < 0.0, 1.0, 0.0)
    cc.uniform_field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha,
                     {"substrate": "type zeroGradient;", "sides": "type zeroGradient;",
                      "atmosphere": "type inletOutlet; inletValue uniform 0; value uniform 0;"})
    cc.uniform_field(case, "T", "[0 0 0 1 0 0 0]", T0,
                     {"substrate": f"type fixedValue; value uniform {T0!r};", "sides": "type zeroGradient;",
                      "atmosphere": f"type inletOutlet; inletValue uniform {T0!r}; value uniform {T0!r};"})
    cc.uniform_field(case, "U", "[0 1 -1 0 0 0 0]", (0.0, 0.0, 0.0),
                     {"substrate": "type noSlip;", "sides": "type noSlip;",
                      "atmosphere": "type pressureInletOutletVelocity; value uniform (0 0 0);"}, vector=True)
    cc.uniform_field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", 0.0,
                     {"substrate": "type fixedFluxPressure; value uniform 0;",
                      "sides": "type fixedFluxPressure; value uniform 0;",
                      "atmosphere": "type totalPressure; p0 uniform 0; value uniform 0;"})
    fc.transport(case, RHO, MU_MELT / RHO, GAS["rho"], gas_mu / GAS["rho"], SIGMA0)
    fc.gravity(case, (0.0, -G, 0.0))
    cell_fields = fc.CELL_GEOMETRY_FUNCTIONS if refine else ""
    max_co, max_dt = (courant, n_sub * DEM_DT) if courant else (0.3, dt_cap)
    fc.control_dict(case, "meltdemFoam", t_end, max_dt / 4, v["write"], max_co=max_co, max_alpha_co=max_co,
                    max_dt=max_dt, extra=cell_fields)
    fc.fv_schemes(case)
    fc.fv_solution(case, n_correctors=3)
    cc.exact_solves(case, p_rgh=1e-12, T=1e-14)   # the ledger balances (as tests/coupling)
    laser = f"""laser
{{
    power        {POWER!r};
{beam.absorptivity_entries(laser_args, ETA, TLIQ)}    radius       {SPOT / 2!r};      // 1/e^2 radius of the 0.1 mm spot
    direction    (0 -1 0);
    position     ({v['x0']!r} {v['top']!r} {zc!r});
    velocity     ({SPEED!r} 0 0);
    tOn          0;
    tOff         {t_scan!r};
    tStop        {t_scan!r};
}}
"""
    fc.meltdem_properties(case, physics=dict(flow="on", energy="on", darcy="on",
                                             surfaceTension="on" if surface else "off",
                                             marangoni="on" if surface else "off", laser="on", particles="on",
                                             evaporation="on" if vapour_jet else "off",
                                             recoil="on" if vapour_jet else "off"),
                          surface=dict(sigma0=SIGMA0, dSigmadT=DSIGMA, Tsigma0=TMELT, sigmaMin=0.2),
                          extra=f"""metal {{ cp {CP!r}; k {K!r}; L {LATENT!r}; Tsolidus {TSOL!r}; Tliquidus {TLIQ!r}; }}
gas {{ cp {gas_cp!r}; k {GAS['k']!r}; }}
darcy {{ C 1e10; b 1e-3; }}
energyControls {{ nCorrectors 50; tolerance 1e-13; }}
{laser}
{evaporation.steel_dict(CP, vapour_jet=True) if vapour_jet else ""}particles
{{
    lammpsInput     in.particles;
    distribution    {distribution};
    demStepsPerFluidStep {sub_cycles};
}}
{refinement_dict(refine, refine_interval, grain_reach) if refine else ""}""")
    dump_every = 1000  # DEM steps (5 us between snapshots)
    lammps_input(case, v, dump_every)
    meta = dict(scene="slm-track", variant=variant, n_cells=list(n), particles=nparticles, t_scan_s=t_scan,
                t_end_s=t_end, laser_x0_m=v["x0"], laser_x1_m=v["x1"], track_z_m=zc, dt_capillary_s=dt_cap,
                distribution=distribution, bed_dump=os.path.abspath(dump), gas_cp=gas_cp, gas_mu=gas_mu,
                vapour_jet=vapour_jet,
                fluid_dt_s=n_sub * DEM_DT, courant=courant, refine=refine, base_cell=h,
                **beam.absorptivity_meta(laser_args, ETA),
                **{k: v[k] for k in ("lx", "lz", "top", "sub", "cell", "cool", "write")})
    json.dump(meta, open(os.path.join(case, "scene.json"), "w"), indent=1)
    print(f"case {case}: {variant}, {n[0]}x{n[1]}x{n[2]} cells of {h * 1e6:g} um"
          f"{f' refined to {h_fine * 1e6:g} um' if refine else ''}, {nparticles} particles, "
          f"track x {v['x0'] * 1e3:g}-{v['x1'] * 1e3:g} mm ({t_scan * 1e3:g} ms) + {v['cool'] * 1e6:g} us cooling, "
          + (f"the flow's step (Courant <= {courant:g}, at most {n_sub * DEM_DT * 1e6:g} us)" if courant else
             f"fixed fluid step {n_sub * DEM_DT * 1e6:g} us"))


# -------------------------------------------------------------------------------------------- run
def run(case, np_=1):
    t = time.time()
    fc.run(["blockMesh"], case, "log.blockMesh")
    if np_ > 1:
        cc.decompose(case, np_, (1, 1, np_))
    cc.run_solver(case, np_)
    wall = time.time() - t
    if np_ > 1:
        fc.run(["reconstructPar", "-fields", "(T alpha.metal liquidFraction)"], case, "log.reconstructPar")
    meta = json.load(open(os.path.join(case, "scene.json")))
    meta["wall_s"] = wall
    meta["np"] = np_
    json.dump(meta, open(os.path.join(case, "scene.json"), "w"), indent=1)
    print(f"meltdemFoam + LAMMPS: {wall:.0f} s wall on {np_} rank(s)")


# ---------------------------------------------------------------------------------------- analyse


def lattice_field(case, time, name, meta):
    """A written field on the lattice of the finest cells, (nz, ny, nx) (fc.lattice_field: on a
    refined mesh (--refine) each cell's value fills the finest cells it covers)."""
    f = 2 ** meta.get("refine", 0)
    return fc.lattice_field(case, time, name, tuple(k * f for k in meta["n_cells"]), meta["cell"],
                            (0.0, -meta["sub"], 0.0))


def track_geometry(case, meta):
    """Melted region = metal cells (alpha >= 1/2) whose temperature reached T_half (liquid fraction
    1/2, the middle of the melting range) at some written time; its boundary is interpolated
    linearly between cell centres on the peak temperature. Width = z extent (widest cell row),
    depth = below the substrate top on the track axis, height = final metal above the substrate
    top (column sum of alpha); surface width = the melted width on the substrate's top plane (the
    peak temperature there extrapolated linearly from the two top substrate cell rows: the width a
    cross-section or a top view of the bare track measures, without the molten grains above it);
    medians over the x-slices of the middle of the track (one spot diameter away from its start
    and end). The width's mean over the slices and the slices' widths are returned too: molten
    grains above the plate make the widest span jump from slice to slice, and a median of few such
    slices can fall into a gap between them."""
    f = 2 ** meta.get("refine", 0)
    nx, ny, nz = (k * f for k in meta["n_cells"])
    h = meta["cell"]
    t_half = 0.5 * (TSOL + TLIQ)
    times = [d for d in fc.time_dirs(case) if float(d) > 0]
    tmax = fc.peak_metal_temperature(case, times, (nx, ny, nz), h, (0.0, -meta["sub"], 0.0), T0)
    alpha_end = lattice_field(case, times[-1], "alpha.metal", meta)
    xc = (np.arange(nx) + 0.5) * h
    yc = -meta["sub"] + (np.arange(ny) + 0.5) * h
    zc = (np.arange(nz) + 0.5) * h
    mid = (xc >= meta["laser_x0_m"] + SPOT) & (xc <= meta["laser_x1_m"] - SPOT)
    if not mid.any():
        mid = (xc >= meta["laser_x0_m"]) & (xc <= meta["laser_x1_m"])
    above = yc > 0
    widths, depths, heights, surface_widths = [], [], [], []
    axis = np.interp(meta["track_z_m"], zc, np.arange(nz))  # fractional index of the track axis
    k0 = int(np.floor(axis))
    j_top = int(np.nonzero(~above)[0][-1])                   # the substrate's top cell row
    for i in np.nonzero(mid)[0]:
        w = 0.0
        for j in range(ny):
            cr = profiles.level_span(tmax[:, j, i], zc, t_half, h)
            if cr:
                w = max(w, cr[1] - cr[0])
        widths.append(w)
        # peak T on the substrate's top plane, extrapolated from its two top cell rows
        plane = 1.5 * tmax[:, j_top, i] - 0.5 * tmax[:, j_top - 1, i]
        cr = profiles.level_span(plane, zc, t_half, h)
        surface_widths.append(cr[1] - cr[0] if cr else 0.0)
        col = tmax[k0, :, i] * (1 - (axis - k0)) + tmax[min(k0 + 1, nz - 1), :, i] * (axis - k0)
        cr = profiles.level_span(np.where(above, np.max(col), col), yc, t_half, h)  # from below up to the top
        depths.append(max(-cr[0], 0.0) if cr else 0.0)
        heights.append(np.max(np.sum(alpha_end[:, above, i], axis=1) * h))
    return dict(track_width_m=float(np.median(widths)), track_depth_m=float(np.median(depths)),
                track_width_mean_m=float(np.mean(widths)), track_width_slices_m=[float(w) for w in widths],
                track_width_surface_m=float(np.median(surface_widths)),
                bead_height_m=float(np.median(heights)), melted_cells=int(np.sum(tmax >= t_half)),
                peak_temperature_K=float(np.max(tmax)), snapshots=len(times), slices=int(mid.sum()))


def particle_motion(case, meta):
    """Ejection and denudation from the particle snapshots (particles.dump)."""
    snaps = [(fr["time"], dumps.columns(fr)) for fr in dumps.read_frames(os.path.join(case, "particles.dump"))]
    t0, first = snaps[0]
    tend, last = snaps[-1]
    ids0 = first["id"].astype(int)
    top0 = float(np.max(first["y"] + first["radius"]))       # highest point of the bed at the start
    vmax, ejected, ejected_speed = {}, set(), {}
    for t, s in snaps:
        speed = np.sqrt(s["vx"] ** 2 + s["vy"] ** 2 + s["vz"] ** 2)
        for i, sp, y, vy in zip(s["id"].astype(int), speed, s["y"], s["vy"]):
            vmax[i] = max(vmax.get(i, 0.0), sp)
            # ejected: the centre above the bed's highest point, moving up
            if y > top0 and vy > 0:
                ejected.add(i)
                ejected_speed[i] = max(ejected_speed.get(i, 0.0), sp)
    # particles that left the mesh (booked as outflow): their last snapshot speed counts
    present_end = set(last["id"].astype(int))
    d = cc.ledger(case)
    lost = int(np.sum(d["lost_particles"]))
    p = cc.particles_csv(case)
    # denudation: in the middle of the track, initial particles cleared (melted, lost, or moved
    # by more than their radius) vs the distance of their initial centre from the track axis
    idx_end = {i: k for k, i in enumerate(last["id"].astype(int))}
    x0, x1 = meta["laser_x0_m"] + SPOT / 2, meta["laser_x1_m"] - SPOT / 2
    sel = (first["x"] >= x0) & (first["x"] <= x1)
    dz = np.abs(first["z"] - meta["track_z_m"])
    cleared = np.zeros(len(ids0), bool)
    melted = np.zeros(len(ids0), bool)
    r_end = np.array([last["radius"][idx_end[i]] if i in idx_end else 0.0 for i in ids0])
    melted_volume = 4.0 / 3.0 * np.pi * float(np.sum(first["radius"] ** 3 - r_end ** 3))  # grains gone or shrunk
    for k, i in enumerate(ids0):
        if i not in idx_end:
            cleared[k] = melted[k] = True
            continue
        e = idx_end[i]
        moved = np.sqrt((last["x"][e] - first["x"][k]) ** 2 + (last["y"][e] - first["y"][k]) ** 2 +
                        (last["z"][e] - first["z"][k]) ** 2)
        cleared[k] = moved > first["radius"][k]
    bw = 15e-6
    edges = np.arange(0, meta["lz"] / 2 + bw, bw)
    frac = []
    for a, b in zip(edges[:-1], edges[1:]):
        m = sel & (dz >= a) & (dz < b)
        frac.append(np.mean(cleared[m]) if m.any() else np.nan)
    frac = np.array(frac)
    # half width: the first bin whose cleared fraction falls below 1/2 (linear in between)
    half = 0.0
    centres = 0.5 * (edges[:-1] + edges[1:])
    for k, f in enumerate(frac):
        if np.isnan(f):
            continue
        if f < 0.5:
            if k == 0:
                half = centres[0] * f / 0.5
            else:
                fp = frac[k - 1]
                half = centres[k - 1] + (fp - 0.5) / (fp - f) * bw
            break
    else:
        half = centres[-1]
    # farthest cleared particle that was not melted: how far the laser's influence reaches
    moved_only = cleared & ~melted & sel
    speeds = np.array([ejected_speed[i] for i in sorted(ejected)])
    return dict(particles_start=len(ids0), particles_end=len(present_end), particles_melted=int(np.sum(melted)),
                powder_melted_volume_m3=melted_volume,
                particles_lost=lost, particles_ejected=len(ejected),
                ejection_speed_median_m_per_s=float(np.median(speeds)) if len(speeds) else 0.0,
                ejection_speed_max_m_per_s=float(np.max(speeds)) if len(speeds) else 0.0,
                particle_speed_max_m_per_s=float(max(vmax.values())),
                particles_faster_than_0p5_m_per_s=int(sum(1 for s in vmax.values() if s > 0.5)),
                bed_top_m=top0, denudation_width_m=2 * half,
                denudation_moved_farthest_m=float(np.max(dz[moved_only])) if moved_only.any() else 0.0,
                denudation_profile=[None if np.isnan(f) else float(f) for f in frac],
                laser_heat_particles_J=float(np.sum(p["laser_heat"])),
                dump_times_s=[t0, tend], n_snapshots=len(snaps))


def laser_power(case, meta):
    """Per fluid step: continuum's absorbed laser power (solver log) + the particles' (particles.csv)
    vs eta P, over the steps that lie wholly inside the scan."""
    log = open(os.path.join(case, "log.meltdemFoam")).read()
    cont = np.array([float(x) for x in re.findall(r"Laser: absorbed power (\S+) W", log)])
    eta = beam.step_absorptivity(log, meta.get("absorptivity", ETA))[2]
    p = cc.particles_csv(case)
    n = min(len(cont), len(p))
    t = p["time"][:n]
    total = cont[:n] + p["laser_heat"][:n] / p["dt"][:n]
    inside = t <= meta["t_scan_s"] * (1 - 1e-12)
    energy = float(np.sum(total * p["dt"][:n]))
    eta_p = eta[:n] * POWER
    eta_mean = float(np.sum((eta[:n] * p["dt"][:n])[inside]) / np.sum(p["dt"][:n][inside]))
    return dict(laser_power_worst_rel_error=float(np.max(np.abs(total - eta_p)[inside] / eta_p[inside])),
                laser_energy_absorbed_J=energy, laser_energy_eta_P_t_J=eta_mean * POWER * meta["t_scan_s"],
                laser_absorptivity_mean=eta_mean,
                laser_power_particles_mean_W=float(np.sum(p["laser_heat"][:n]) / meta["t_scan_s"]),
                fluid_steps=int(len(p)))


def references(meta):
    """Conduction-only melt width of the same eta P, v on a semi-infinite SS304 substrate: Rosenthal
    (point source) and the Gaussian surface source of the 0.1 mm spot (quasi-steady, t = 1 ms),
    both at Tm; no latent heat, no powder (meltdem.analysis.rosenthal)."""
    from meltdem.analysis.rosenthal import rosenthal, width_at_depth, gaussian_transient
    a = K / (RHO * CP)
    q = ETA * POWER
    w_ros = width_at_depth(lambda xi, y, z: rosenthal(xi, y, z, q, K, a, SPEED, T0), TMELT, -1e-7,
                           (-600e-6, 100e-6), 400e-6, n=1400)
    t = 1e-3
    best = 0.0
    for xi in np.linspace(-200e-6, 50e-6, 51):
        def g(y):
            return gaussian_transient(SPEED * t + xi, y, -1e-7, t, q, K, a, RHO * CP, T0, SPOT / 2, 0.0,
                                      SPEED, nt=2000)
        if g(0.0) < TMELT:
            continue
        lo, hi = 0.0, 300e-6
        for _ in range(30):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if g(mid) >= TMELT else (lo, mid)
        best = max(best, lo)
    return dict(rosenthal_width_m=float(w_ros), gaussian_width_m=float(2 * best))


def limited_updates(case):
    """Last value of f_integrate (fix nve/limit: updates capped at VMAX_DEM) in log.lammps."""
    last = 0
    for line in open(os.path.join(case, "log.lammps")):
        w = line.split()
        if len(w) == 11 and w[0].isdigit():
            try:
                last = int(float(w[-1]))
            except ValueError:
                pass
    return last


def analyse(case):
    meta = json.load(open(os.path.join(case, "scene.json")))
    s = {}
    s.update(track_geometry(case, meta))
    s.update(particle_motion(case, meta))
    s.update(laser_power(case, meta))
    s.update(references(meta))
    d = cc.ledger(case)[1:]
    for c in ("mass", "enthalpy"):
        s[f"worst_{c}_continuum_error"] = float(np.max(np.abs(d[f"{c}_continuum_error"])))
        s[f"worst_{c}_system_error"] = float(np.max(np.abs(d[f"{c}_system_error"])))
    s["worst_momentum_continuum_error"] = float(max(np.max(np.abs(d[f"mom_{c}_continuum_error"])) for c in "xyz"))
    s["dem_updates_speed_limited"] = limited_updates(case)
    cpu = fc.execution_time(case)
    s["cpu_s"] = float("nan") if cpu is None else cpu  # solver CPU time of rank 0 (LAMMPS included)
    s["wall_s"] = meta.get("wall_s", float("nan"))
    s["cells"] = int(np.prod(meta["n_cells"]))
    s["cell_m"] = meta["cell"]
    json.dump(s, open(os.path.join(case, "summary.json"), "w"), indent=1)
    um = lambda x: f"{x * 1e6:.1f} um"  # noqa: E731
    rows = [
        ("track width (peak T >= T(f_l = 1/2))", um(s["track_width_m"]),
         f"Rosenthal {um(s['rosenthal_width_m'])}, Gaussian {um(s['gaussian_width_m'])}"),
        ("track width, mean over the track's slices", um(s["track_width_mean_m"]), f"{s['slices']} slices"),
        ("track width on the substrate's top plane", um(s["track_width_surface_m"]), ""),
        ("track depth below the substrate top", um(s["track_depth_m"]), ""),
        ("bead height above the substrate top", um(s["bead_height_m"]), "thesis expectation 30 um"),
        ("particles ejected (centre above bed top, moving up)", s["particles_ejected"], ""),
        ("ejection speed median / max", f"{s['ejection_speed_median_m_per_s']:.3f} / "
         f"{s['ejection_speed_max_m_per_s']:.3f} m/s", "thesis ~1 m/s"),
        ("largest particle speed", f"{s['particle_speed_max_m_per_s']:.3f} m/s", ""),
        ("particles melted / lost / start", f"{s['particles_melted']} / {s['particles_lost']} / "
         f"{s['particles_start']}", ""),
        ("powder melted (grains gone or shrunk), volume", f"{s['powder_melted_volume_m3'] * 1e18:.0f} um^3", ""),
        ("denudation width (cleared fraction >= 1/2)", um(s["denudation_width_m"]), ""),
        ("absorbed laser power, worst step", f"{s['laser_power_worst_rel_error']:.2e} rel.", "eta P = 50 W"),
        ("laser energy absorbed / eta P t_scan", f"{s['laser_energy_absorbed_J']:.6e} / "
         f"{s['laser_energy_eta_P_t_J']:.6e} J", ""),
        ("worst continuum mass / energy / momentum error", f"{s['worst_mass_continuum_error']:.1e} / "
         f"{s['worst_enthalpy_continuum_error']:.1e} / {s['worst_momentum_continuum_error']:.1e}", ""),
        ("DEM updates capped at the speed limit", s["dem_updates_speed_limited"], f"{VMAX_DEM:g} m/s"),
        ("cells / wall time / CPU time", f"{s['cells']} / {s['wall_s']:.0f} s / {s['cpu_s']:.0f} s", ""),
    ]
    for r in rows:
        print(f"{r[0]:<52} {str(r[1]):<28} {r[2]}")
    return s


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    g = ap.add_mutually_exclusive_group()
    g.add_argument("--ci", action="store_true", help="0.3 x 0.3 mm floor, 0.2 mm track (default)")
    g.add_argument("--full", action="store_true", help="thesis size 0.9 x 0.21 x 0.9 mm, 0.7 mm track")
    ap.add_argument("--np", type=int, default=1)
    ap.add_argument("--cell", type=float, help="cell size [m] (default the variant's: 30e-6)")
    ap.add_argument("--bed", help="powder-bed dump to use instead of pouring one, or 'spread': a layer spread "
                    "by examples/powder-spread's blade")
    ap.add_argument("--track", type=float, help="track length [m]")
    ap.add_argument("--distribution", default="overlap", choices=["centre", "neighbours", "overlap"])
    ap.add_argument("--gas-cp", type=float, help="gas heat capacity [J/kg/K] (default argon's 520)")
    ap.add_argument("--fluid-dt", type=float, help=f"fluid step [s] (default {FLUID_DT:g}; with --courant the "
                    "largest)")
    ap.add_argument("--courant", type=float, metavar="CO",
                    help="adaptive fluid step: the largest with cell and interface Courant numbers <= CO (at most "
                    "--fluid-dt), DEM sub-cycles recomputed every step (demStepsPerFluidStep auto); the default "
                    f"on cells finer than the variant's with surface forces on ({FINE_COURANT:g}) unless --fluid-dt "
                    "is given")
    ap.add_argument("--surface", dest="surface", action="store_true", default=SURFACE,
                    help="surface tension and Marangoni on (the default)")
    ap.add_argument("--no-surface", dest="surface", action="store_false",
                    help="surface tension and Marangoni off (the scene's default before 2026-12-04)")
    ap.add_argument("--gas-mu", type=float, help="gas viscosity [Pa s] (default argon's 2.2e-5)")
    ap.add_argument("--refine", type=int, default=0, metavar="L",
                    help="adaptive refinement: base cells 2^L x --cell, refined to --cell in the pool, under "
                    "the beam and its path ahead and around the grains near them (refinement{})")
    ap.add_argument("--refine-interval", type=int, default=1, metavar="N", help="fluid steps between mesh updates")
    ap.add_argument("--vapour-jet", action="store_true",
                    help="evaporation (Fuchs2022's steel data) and recoil on, and " + evaporation.VAPOUR_JET_HELP)
    beam.add_absorptivity_arguments(ap, ETA)
    a = ap.parse_args(argv)
    beam.check_absorptivity_arguments(ap, a, ETA)
    case = os.path.abspath(a.case)
    variant = "full" if a.full else "ci"
    if a.command in ("build", "all"):
        bed = a.bed if a.bed in (None, "spread") else os.path.abspath(a.bed)
        build(case, variant, a.cell, bed, a.track, a.distribution, a.np, a.gas_cp,
              a.fluid_dt, a.gas_mu, a.surface, a.refine, a.refine_interval, a.courant, laser_args=a,
              vapour_jet=a.vapour_jet)
    if a.command in ("run", "all"):
        run(case, a.np)
    if a.command in ("analyse", "all"):
        analyse(case)
    return 0


SCENE = Scene(name="slm-track", kind="coupled",
              title="SLM track over a generated powder bed (Codina2019 §4.2.2, tables 4.5 / 4.6)",
              ci_time='166 s wall', full_time=None,
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]),
              summary=analyse)


if __name__ == "__main__":
    sys.exit(main())
