"""Powder bed fusion scenes of Fuchs2022 (§4.5, tables 1-3), shared by
examples/pbf-point and examples/pbf-line: the bed generator (DEM with meltdem-lmp), the coupled
case writer (meltdemFoam hosting LAMMPS), the runner and the analysis.

Axes: x along the track, y up (gravity -y, laser -y), z across. The substrate (continuum
metal) fills y < SUB; the powder (DEM particles, fix powder/melt with solid_metal) rests on it;
gas above, an open atmosphere at the top (the melt of the particles adds metal volume: the gas
it displaces must leave), no-slip walls at 500 K elsewhere (Fuchs2022 §4.1).
"""
import json
import math
import os
import re
import shutil
import subprocess
import time

import numpy as np

from meltdem import paths
from meltdem.case import coupled as cc
from meltdem.case import evaporation
from meltdem.case import foam as fc
from meltdem.case import laser
from meltdem.io import dumps

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = paths.source_dir()
paths.set_tool_environment()

# Fuchs2022 tables 1-3 (stainless steel near Tm = 1700 K; gas scaled rho 1/100, mu 1/10)
M, G = fc.METAL, fc.GAS
T_MELT, DT_MUSHY, T0 = 1700.0, 10.0, 500.0
# Fuchs2022 has no latent heat of fusion (mjt-droplets uses L 0). Here the grains are lumped
# (one temperature each): with L ~ 0 a grain at its melting point melts within one fluid step,
# its whole volume appears in the continuum at once and the gas it displaces leaves at ~100 m/s
# (Courant ~1 in the step, grains thrown at 50 m/s). Steel's latent heat (2.7e5 J/kg, the
# Codina2019 SS304 value; fix powder/melt and the continuum must share it) spreads the melting
# of a grain in the beam over ~2 us, as the conduction through a real grain does.
LATENT = 2.7e5
ETA, T_BOIL = 0.5, 3000.0
# DEM contact: Fuchs2022's contact is soft (k_c = 1 kg/s^2); E = 2 GPa keeps overlaps < 1e-3 R
# at rest and ~ 0.08 R head-on at 10 m/s, and a DEM step 16x longer than 200 GPa's.
E_DEM, NU_DEM, E_REST = 2.0e9, 0.3, 0.3
RHO_P = M["rho"]
DT_DEM = 2.0e-8
MAX_DT_EXCHANGE = 6.0e-8
# Gas heat capacity. Fuchs2022's gas (table 3: rho 7.43, cp 10) holds 1e-5 of the metal's heat
# per volume. The coupling hands a grain's convective heat to its cells with the volume weights
# of the distribution, while the grain's heat flux uses the weight-averaged T and k: a grain half
# in the melt and half in gas then takes half of its heat from the gas cells, which go to -1e3 K
# within a step (and the recoil pressure p_v(T < 0) explodes). A gas cell's drop per step is
# about 6 Nu k dT dt / (d^2 rho cp_gas) = 1.3e8 / (rho cp_gas) K for the worst grain (16 um,
# k 18, dT 1500 K, dt 1e-7 s): cp_gas 1e5 (rho cp = 0.1 of the metal's) keeps it below 200 K.
# The gas conducts as in Fuchs2022 (k 0.026), so its heat capacity barely matters elsewhere.
GAS_CP_STABLE = 1.0e5   # only with --gas-cp; the default is Fuchs2022's 10

VARIANTS = {
    # Fuchs2022 §4.5 point melting: 320 x 320 x 240 um, 80 um substrate, 500 particles
    "point-full": dict(lx=320e-6, ly=240e-6, lz=320e-6, sub=80e-6, n=500, dx=10e-6, power=312.0,
                       rw=70e-6, x0=160e-6, v=0.0, t_move=None, t_off=1.0e-4, t_end=2.5e-4,
                       write=5e-6, dist="overlap"),
    # CI: same physics, 10 um cells, a 160 x 160 um floor with 100 grains, 140 um high, 40 um
    # substrate, laser on 30 us, off until 40 us
    "point-ci": dict(lx=160e-6, ly=140e-6, lz=160e-6, sub=40e-6, n=100, dx=10e-6, power=312.0,
                     rw=70e-6, x0=80e-6, v=0.0, t_move=None, t_off=3.0e-5, t_end=4.0e-5,
                     write=2.5e-6, dist="overlap"),
    # Fuchs2022 line melting: 960 x 320 x 240 um, 1500 particles, on at 160 um, at rest to 0.05 ms,
    # 2 m/s over 640 um, off at 0.37 ms (Fuchs2022's videos run to 0.49 ms)
    "line-full": dict(lx=960e-6, ly=240e-6, lz=320e-6, sub=80e-6, n=1500, dx=10e-6, power=312.0,
                      rw=70e-6, x0=160e-6, v=2.0, t_move=5.0e-5, t_off=3.7e-4, t_end=4.2e-4,
                      write=1e-5, dist="overlap"),
    # CI: a 280 x 160 um floor, 160 grains, on at x = 80 um, at rest 10 us, 2 m/s over 60 um,
    # off at 40 us, end 45 us
    "line-ci": dict(lx=280e-6, ly=140e-6, lz=160e-6, sub=40e-6, n=160, dx=10e-6, power=312.0,
                    rw=70e-6, x0=80e-6, v=2.0, t_move=1.0e-5, t_off=4.0e-5, t_end=4.5e-5,
                    write=2.5e-6, dist="overlap"),
}

D_LO, D_HI, D_MED, D_SIG = 16e-6, 32e-6, 23e-6, 0.2   # log-normal, truncated to 16-32 um


# ----------------------------------------------------------------------------------------------
# bed


def bed_input(cfg, seed):
    """LAMMPS input that pours cfg['n'] log-normal grains onto the substrate top and lets them
    settle (gravity x10 to settle faster; friction 0.1 so that the bed does not flow flat)."""
    lx, ly, lz, sub, n = cfg["lx"], cfg["ly"], cfg["lz"], cfg["sub"], cfg["n"]
    return f"""# PBF powder bed: {n} grains, d log-normal (median {D_MED:g}, sigma_ln {D_SIG:g}) in
# [{D_LO:g}, {D_HI:g}] m, poured onto the substrate top y = {sub:g} m and settled
units           si
atom_style      sphere
atom_modify     map array
boundary        f f f
region          box block 0 {lx!r} {sub!r} {ly!r} 0 {lz!r} units box
create_box      1 box
neighbor        4e-6 bin
neigh_modify    delay 0
comm_modify     vel yes
pair_style      granular/powder {D_HI!r}
pair_coeff      * * hertz/material {E_DEM!r} {E_REST!r} {NU_DEM!r} damping tsuji tangential mindlin NULL 1.0 0.1
fix             integrate all nve/sphere
fix             gravity all gravity {10 * 9.81!r} vector 0 -1 0
fix             walls all wall/gran/powder granular hertz/material {E_DEM!r} {E_REST!r} {NU_DEM!r} damping tsuji tangential mindlin NULL 1.0 0.1 yplane {sub!r} {ly!r}
fix             wx all wall/gran/powder granular hertz/material {E_DEM!r} {E_REST!r} {NU_DEM!r} damping tsuji tangential mindlin NULL 1.0 0.1 xplane 0 {lx!r}
fix             wz all wall/gran/powder granular hertz/material {E_DEM!r} {E_REST!r} {NU_DEM!r} damping tsuji tangential mindlin NULL 1.0 0.1 zplane 0 {lz!r}
region          feed block 0 {lx!r} {sub + 2e-6!r} {ly - 2e-6!r} 0 {lz!r} units box
fix             feed all powder/insert {n} {seed} region feed diam lognormal {D_MED!r} {D_SIG!r} {D_LO!r} {D_HI!r} dens {RHO_P!r} rate {n / 2e-5!r} vel 0 -0.5 0
fix             dt all powder/dt steps 10 max 5e-8
compute         ke all ke
variable        t equal time
variable        vrms equal sqrt(2*c_ke/(mass(all)+1e-30))
variable        done equal "v_t > 4e-3 || (f_feed[1] == {n} && v_t > 2e-4 && v_vrms < 2e-3)"
fix             stop all halt 1000 v_done > 0.5 error continue
thermo_style    custom step time dt atoms f_feed[1] v_vrms
thermo_modify   norm no flush yes
thermo          2000
timestep        1e-9
run             100000000
write_dump      all custom bed.dump id radius x y z modify sort id
"""  # noqa: E501  (long lines of the LAMMPS input written verbatim)


def make_bed(bed_dir, cfg, seed=4711):
    """Run the pour (once: reused when bed.dump exists for the same parameters); returns the
    (n, 4) array x, y, z, d."""
    os.makedirs(bed_dir, exist_ok=True)
    inp = bed_input(cfg, seed)
    dump = os.path.join(bed_dir, "bed.dump")
    path = os.path.join(bed_dir, "in.bed")
    if not (os.path.exists(dump) and os.path.exists(path) and open(path).read() == inp):
        with open(path, "w") as f:
            f.write(inp)
        t0 = time.time()
        with open(os.path.join(bed_dir, "log.bed"), "w") as log:
            subprocess.run([paths.binary("meltdem-lmp"), "-in", "in.bed", "-log", "log.lammps"], cwd=bed_dir,
                           stdout=log, stderr=subprocess.STDOUT, check=True)
        print(f"bed: {cfg['n']} grains poured and settled in {time.time() - t0:.0f} s")
    a = dumps.read_frames(dump)[-1]["data"]
    return np.column_stack([a[:, 2], a[:, 3], a[:, 4], 2 * a[:, 1]])


# ----------------------------------------------------------------------------------------------
# case


def ncells(cfg):
    return tuple(int(round(cfg[k] / cfg["dx"])) for k in ("lx", "ly", "lz"))


def centres(cfg):
    n = ncells(cfg)
    h = cfg["dx"]
    x = (np.arange(n[0]) + 0.5) * h
    y = (np.arange(n[1]) + 0.5) * h
    z = (np.arange(n[2]) + 0.5) * h
    Z, Y, X = np.meshgrid(z, y, x, indexing="ij")   # blockMesh order: x fastest, then y, z
    return X.ravel(), Y.ravel(), Z.ravel()


def laser_dict(cfg):
    lines = [f"power {cfg['power']!r};", *laser.absorptivity_entries(cfg.get("laser_args"), ETA,
                                                                     T_MELT + DT_MUSHY / 2, "").splitlines(),
             f"radius {cfg['rw']!r};", "direction (0 -1 0);"]
    y = cfg["ly"] - cfg["dx"] / 2
    if cfg.get("tracks"):
        # hatched tracks (examples/pbf-layer): scanned in order, the beam off while it returns
        tracks = " ".join(f"(({a[0]!r} {y!r} {a[1]!r}) ({b[0]!r} {y!r} {b[1]!r}))" for a, b in cfg["tracks"])
        lines += [f"tracks ({tracks});", f"speed {cfg['v']!r};", f"returnTime {cfg['return_time']!r};",
                  f"tStart {cfg['t_start']!r};"]
        return "laser\n{\n" + "".join(f"    {s}\n" for s in lines) + "}\n"
    lines += ["tOn 0;", f"tOff {cfg['t_off']!r};", f"position ({cfg['x0']!r} {y!r} {cfg['lz'] / 2!r});"]
    if cfg["v"]:
        lines += [f"velocity ({cfg['v']!r} 0 0);", f"tStart {cfg['t_move']!r};", f"tStop {cfg['t_off']!r};"]
    return "laser\n{\n" + "".join(f"    {s}\n" for s in lines) + "}\n"


def track_intervals(cfg):
    """[(t_begin, t_end, (x0, z0), (x1, z1))] of each scanned track (cfg['tracks'])."""
    out, t = [], cfg["t_start"]
    for a, b in cfg["tracks"]:
        dur = math.hypot(b[0] - a[0], b[1] - a[1]) / cfg["v"]
        out.append((t, t + dur, a, b))
        t += dur + cfg["return_time"]
    return out


def lit_time(cfg, t_end):
    """Time [s] the beam was on up to t_end."""
    if cfg.get("tracks"):
        return sum(max(min(t_end, t1) - t0, 0.0) for t0, t1, _, _ in track_intervals(cfg))
    return min(t_end, cfg["t_off"])


def beam_xz(cfg, t):
    """Beam axis (x, z) at time t (the laser's path, as meltdem::laserHeatSource walks it)."""
    if cfg.get("tracks"):
        knots = [(t0, a) for t0, t1, a, b in track_intervals(cfg) for t0, a in ((t0, a), (t1, b))]
        if t <= knots[0][0]:
            return knots[0][1]
        for (ta, pa), (tb, pb) in zip(knots[:-1], knots[1:]):
            if t <= tb:
                w = (t - ta) / (tb - ta) if tb > ta else 1.0
                return pa[0] + w * (pb[0] - pa[0]), pa[1] + w * (pb[1] - pa[1])
        return knots[-1][1]
    return beam_x(cfg, t), cfg["lz"] / 2


def particles_input(cfg, bed):
    lx, ly, lz = cfg["lx"], cfg["ly"], cfg["lz"]
    estar_wall = E_DEM / (2 * (1 - NU_DEM ** 2))
    return f"""# PBF powder, coupled (meltdemFoam hosts this input): {len(bed)} grains read from bed.data
units           si
atom_style      sphere 1
atom_modify     map array
boundary        f f f
read_data       bed.data
neighbor        4e-6 bin
neigh_modify    delay 0
comm_modify     vel yes cutoff {2 * D_HI + 4e-6!r}
pair_style      granular/powder {D_HI!r}
pair_coeff      * * hertz/material {E_DEM!r} {E_REST!r} {NU_DEM!r} damping tsuji tangential linear_nohistory 0 0
fix             integrate all nve/sphere
fix             gravity all gravity 9.81 vector 0 -1 0
# the domain walls (paper: rigid walls; ejected grains bounce off them); no friction (paper)
fix             wx all wall/gran/powder granular hertz/material {E_DEM!r} {E_REST!r} {NU_DEM!r} damping tsuji tangential linear_nohistory 0 0 xplane 0 {lx!r}
fix             wz all wall/gran/powder granular hertz/material {E_DEM!r} {E_REST!r} {NU_DEM!r} damping tsuji tangential linear_nohistory 0 0 zplane 0 {lz!r}
fix             wy all wall/gran/powder granular hertz/material {E_DEM!r} {E_REST!r} {NU_DEM!r} damping tsuji tangential linear_nohistory 0 0 yplane 0 {ly!r}
# fixed DEM step: 1/10 of the Hertz contact time of two 16 um grains at 10 m/s (1.9e-7 s);
# fix powder/dt would follow the melting grains' shrinking radii down to 1e-10 s
timestep        {DT_DEM!r}
{balance_line(cfg)}# the substrate and the solidified track are continuum metal: solid_metal makes them a wall
fix             melt all powder/melt cp {M['cp']!r} Tmelt {T_MELT + DT_MUSHY / 2!r} latent {LATENT!r} temp {T0!r} solid_metal {estar_wall!r} {E_REST!r}
compute         ke all ke
thermo_style    custom step time dt atoms f_melt[1] f_melt[6] c_ke
thermo_modify   norm no flush yes format float %.10g
thermo          1000
dump            traj all custom 200 traj.dump id x y z vx vy vz radius f_melt[1] f_melt[2]
dump_modify     traj time yes sort id
"""  # noqa: E501  (long lines of the LAMMPS input written verbatim)


def balance_line(cfg):
    """LAMMPS's fix balance by particle count (every cfg['balance'] DEM steps, shifting the
    sub-domain planes in x and z), or nothing."""
    if not cfg.get("balance"):
        return ""
    return f"fix             balance all balance {cfg['balance']} 1.05 shift xz 10 1.05\n"


def write_bed_data(path, cfg, bed):
    # a wide margin: a melting remnant whose explicit drag goes unstable (response time below
    # the DEM step) can cross a wall in one step; it must leave the mesh (booked as outflow)
    # before it could leave the LAMMPS box (a fatal error)
    m = 1e-3
    with open(path, "w") as f:
        f.write(f"PBF powder bed\n\n{len(bed)} atoms\n1 atom types\n\n"
                f"{-m!r} {cfg['lx'] + m!r} xlo xhi\n{-m!r} {cfg['ly'] + m!r} ylo yhi\n"
                f"{-m!r} {cfg['lz'] + m!r} zlo zhi\n\nAtoms # sphere\n\n")
        for i, (x, y, z, d) in enumerate(bed, 1):
            f.write(f"{i} 1 {d!r} {RHO_P!r} {x!r} {y!r} {z!r}\n")


def lognormal_mean_volume():
    """mean grain volume of the truncated log-normal diameters (numerical, on 2000 points)"""
    d = np.linspace(D_LO, D_HI, 2000)
    w = np.exp(-0.5 * (np.log(d / D_MED) / D_SIG) ** 2) / d
    return float(np.sum(w * math.pi / 6 * d ** 3) / np.sum(w))


def spread_bed(bed_dir, cfg):
    """The bed spread by examples/powder-spread's blade (2 d90 gap, its defaults) with this
    scene's grains over its floor: the (n, 4) array x, y, z, d on the substrate top."""
    from meltdem.scene import module
    t0 = time.time()
    dump, n = module("powder-spread").spread_bed(
        bed_dir, cfg["lx"], cfg["lz"], dlo=D_LO, dhi=D_HI, diam=f"lognormal {D_MED!r} {D_SIG!r} {D_LO!r} {D_HI!r}",
        mean_volume=lognormal_mean_volume(), gap=2 * (D_LO + 0.9 * (D_HI - D_LO)), E=E_DEM)
    print(f"bed: {n} grains spread in {time.time() - t0:.0f} s")
    a = dumps.columns(dumps.read_frames(dump)[-1])
    return np.column_stack([a["x"], a["y"] + cfg["sub"], a["z"], 2 * a["radius"]])


def refinement_dict(cfg, levels, interval):
    """refinement{} of a --refine run: the finest cells in the pool and the metal about to melt, under
    the beam and where it will be over the next half beam radius of travel, and around the grains
    near either; coarse cells in the gas and the deep substrate."""
    ahead = f"lookAhead {interval}; lookAheadTime {0.5 * cfg['rw'] / cfg['v']!r};" if cfg["v"] else ""
    return fc.refinement_dict(levels, interval, [("meltPool", "belowSolidus 300;"),
                                                 ("laser", f"radii 1.2; {ahead}"),
                                                 ("grains", "type particles; diameters 1; near (pool beam);")])


def build(case, variant, dx=None, dist=None, n=None, bed_dir=None, seed=4711, gas_cp=G["cp"], shadow=True,
          bed_process="pour", refine=0, refine_interval=1, laser_args=None, vapour_jet=False):
    """variant: a name in VARIANTS or the configuration itself (examples/pbf-layer's, with its
    'variant' and 'scene')."""
    cfg = dict(VARIANTS[variant]) if isinstance(variant, str) else dict(variant)
    variant = cfg.get("variant", variant)
    cfg["gas_cp"] = gas_cp
    cfg["shadow"] = shadow
    cfg["refine"] = refine
    cfg["vapour_jet"] = vapour_jet
    cfg["laser_args"] = laser.absorptivity_meta(laser_args, ETA)
    if dx:
        cfg["dx"] = dx
    if dist:
        cfg["dist"] = dist
    if n:
        cfg["n"] = n
    cfg["variant"] = variant
    if os.path.exists(case):
        shutil.rmtree(case)
    os.makedirs(case)
    if bed_process == "spread":
        bed = spread_bed(bed_dir or os.path.join(case, "spread"), cfg)
        cfg["n"] = len(bed)
    else:
        bed = make_bed(bed_dir or os.path.join(case, "bed"), cfg, seed)
    cfg["bed_top"] = float(np.max(bed[:, 1] + bed[:, 3] / 2))
    # the base mesh of 2^refine dx (refined to dx where refinement{} asks)
    base = dict(cfg, dx=cfg["dx"] * 2 ** refine)
    nc = ncells(base)
    lo, hi = (0.0, 0.0, 0.0), (nc[0] * base["dx"], nc[1] * base["dx"], nc[2] * base["dx"])
    cc.box_mesh(case, lo, hi, nc, {"walls": ("wall", ["xmin", "xmax", "ymin", "zmin", "zmax"]),
                                   "atmosphere": ("patch", ["ymax"])})
    X, Y, Z = centres(base)
    alpha = np.clip((cfg["sub"] - (Y - base["dx"] / 2)) / base["dx"], 0.0, 1.0)  # exact cell fraction
    h = cfg["dx"]
    walls = {"walls": "type zeroGradient;", "atmosphere": "type inletOutlet; inletValue uniform 0; value uniform 0;"}
    cc.uniform_field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha, walls)
    cc.uniform_field(case, "T", "[0 0 0 1 0 0 0]", T0,
                     {"walls": f"type fixedValue; value uniform {T0!r};",
                      "atmosphere": f"type inletOutlet; inletValue uniform {T0!r}; value uniform {T0!r};"})
    cc.uniform_field(case, "U", "[0 1 -1 0 0 0 0]", (0.0, 0.0, 0.0),
                     {"walls": "type noSlip;",
                      "atmosphere": "type pressureInletOutletVelocity; value uniform (0 0 0);"}, vector=True)
    cc.uniform_field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", 0.0,
                     {"walls": "type fixedFluxPressure; value uniform 0;",
                      "atmosphere": "type totalPressure; p0 uniform 0; value uniform 0;"})
    fc.transport(case, M["rho"], M["mu"] / M["rho"], G["rho"], G["mu"] / G["rho"], M["sigma0"])
    fc.gravity(case, (0.0, -9.81, 0.0))
    rho_avg = 0.5 * (M["rho"] + G["rho"])
    dt_cap = math.sqrt(rho_avg * h ** 3 / (2 * math.pi * M["sigma0"]))
    # the grains' heat exchange is explicit (fluid frozen over the step): the step must stay
    # below the worst cell's heat capacity over its grains' conductance, ~7e-8 s for a grain
    # on the substrate (meltdemFoam stops naming it otherwise)
    fc.control_dict(case, "meltdemFoam", cfg["t_end"], DT_DEM, cfg["write"], max_co=0.25, max_alpha_co=0.25,
                    max_dt=min(dt_cap, MAX_DT_EXCHANGE), extra=fc.CELL_GEOMETRY_FUNCTIONS if refine else "")
    fc.fv_schemes(case)
    # metal mass conserved to round-off needs the alpha solve converged (doc/foam_meltdemFoam.rst)
    fc.fv_solution(case, n_correctors=3, alpha_tolerance=1e-14)
    extra = f"""metal
{{
    Tsolidus    {T_MELT - DT_MUSHY / 2!r};
    Tliquidus   {T_MELT + DT_MUSHY / 2!r};
    L           {LATENT!r};
    cp          {M['cp']!r};
    k           {M['k']!r};
}}
gas {{ cp {cfg['gas_cp']!r}; k {G['k']!r}; }}
darcy {{ C 1e10; b 1e-3; }}
energyControls {{ nCorrectors 20; tolerance 1e-10; }}
{laser_dict(cfg)}{evaporation.steel_dict(965.0, cfg.get('vapour_jet', False))}particles
{{
    lammpsInput     in.particles;
    distribution    {cfg['dist']};
    demStepsPerFluidStep auto;
    laserShadow     {'on' if cfg['shadow'] else 'off'};
}}
{refinement_dict(cfg, refine, refine_interval) if refine else ""}"""
    fc.meltdem_properties(case, physics={"energy": "on", "darcy": "on", "marangoni": "on", "recoil": "on",
                                         "laser": "on", "evaporation": "on", "particles": "on"},
                          surface={"nSmooth": 2}, extra=extra)
    write_bed_data(os.path.join(case, "bed.data"), cfg, bed)
    with open(os.path.join(case, "in.particles"), "w") as f:
        f.write(particles_input(cfg, bed))
    with open(os.path.join(case, "pbf.json"), "w") as f:
        json.dump(cfg, f, indent=1)
    with open(os.path.join(case, "scene.json"), "w") as f:
        json.dump({"scene": cfg.get("scene") or ("pbf-line" if variant.startswith("line") else "pbf-point")}, f)
    print(f"{case}: {variant}, {nc[0]} x {nc[1]} x {nc[2]} cells of {base['dx'] * 1e6:g} um"
          f"{f' refined to {h * 1e6:g} um' if refine else ''} "
          f"({D_LO / h:.1f}-{D_HI / h:.1f} cells per grain diameter, distribution {cfg['dist']}), "
          f"{len(bed)} grains, bed top {cfg['bed_top'] * 1e6:.1f} um")
    return cfg


def run(case, np_=1, timeout=None):
    """blockMesh (+ decomposePar) + meltdemFoam; timeout [s] of wall time stops the solver
    (the case keeps what it wrote) and raises RuntimeError like a solver failure."""
    t0 = time.time()
    fc.run(["blockMesh"], case, "log.blockMesh")
    if np_ > 1:
        # ranks side by side across the scan (z): each holds its share of the beam, the pool and
        # the refined cells while the beam moves along x (a split along x leaves them on one rank)
        cc.decompose(case, np_, (1, 1, np_))
    cmd = fc.solver_command(np_)
    env = dict(os.environ, **fc.MPIRUN_ENV, PWD=os.path.abspath(case))
    with open(os.path.join(case, "log.meltdemFoam"), "w") as log:
        p = subprocess.Popen(cmd, cwd=case, stdout=log, stderr=subprocess.STDOUT, env=env)
        try:
            rc = p.wait(timeout=timeout)
        except subprocess.TimeoutExpired:
            p.terminate()
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
                p.wait()
            rc = "timeout"
    wall = time.time() - t0
    if np_ > 1:
        # the analysis reads the fields of the case folder (also after a stop or a timeout), and
        # on a refined run the cell centres and volumes
        fc.reconstruct(case, ["T", "alpha.metal", "U", "liquidFraction", "C", "V"], check=False)
    with open(os.path.join(case, "wall_seconds"), "w") as f:
        f.write(f"{wall:.1f} {np_}\n")
    print(f"{case}: ran {wall:.0f} s on {np_} rank(s)" + ("" if rc == 0 else f" (stopped: {rc})"))
    if rc == "timeout":
        with open(os.path.join(case, "log.meltdemFoam"), "a") as log:
            log.write(f"\nERROR: wall-clock limit of {timeout} s reached (scene runner)\n")
        raise RuntimeError(f"meltdemFoam stopped after the wall-clock limit of {timeout} s in {case}")
    if rc != 0:
        raise RuntimeError(f"meltdemFoam failed (rc {rc}) in {case}")
    return wall


# ----------------------------------------------------------------------------------------------
# analysis


def grains(case, cfg):
    """Ejected grains: a grain whose centre rose more than its own diameter above where it
    started (it left the bed upwards); their peak speeds (max |v| over the frames after they
    started rising). Also the bed-top rise and the largest speed of any grain."""
    path = os.path.join(case, "traj.dump")
    if not os.path.exists(path):
        return {}
    frames = [(fr["time"], fr["data"]) for fr in dumps.read_frames(path) if len(fr["data"])]
    if not frames:
        return {}
    t0, f0 = frames[0]
    y0 = {int(r[0]): r[2] for r in f0}
    d0 = {int(r[0]): 2 * r[7] for r in f0}
    rise, vmax = {}, {}
    for t, a in frames:
        for r in a:
            i = int(r[0])
            rise[i] = max(rise.get(i, -1.0), r[2] - y0[i])
            vmax[i] = max(vmax.get(i, 0.0), float(np.linalg.norm(r[4:7])))
    ej = [i for i in rise if rise[i] > d0[i]]
    speeds = np.array([vmax[i] for i in ej]) if ej else np.zeros(0)
    return {"grains_ejected": len(ej),
            "ejected_speed_mean_m_per_s": float(speeds.mean()) if len(ej) else 0.0,
            "ejected_speed_max_m_per_s": float(speeds.max()) if len(ej) else 0.0,
            "grain_speed_max_m_per_s": float(max(vmax.values())),
            "grains_left_at_end": int(len(frames[-1][1])),
            "trajectory_frames": len(frames), "trajectory_end_s": frames[-1][0]}


def isotherm_extent(T, molten, axis, h):
    """The longest extent along AXIS of molten metal over the lattice's lines, each end where T
    crosses T_MELT between the last molten cell's centre and the next cell's (linear), at the next
    cell's centre when that cell is not colder (hot gas or mushy metal beside the pool: the limit of
    the crossing as that cell's T rises to T_MELT, so that the reading never jumps with a hundredth
    of a kelvin), or at the domain's face when the line ends molten."""
    Tl, ml = np.moveaxis(T, axis, -1), np.moveaxis(molten, axis, -1)
    best = 0.0
    for line in np.argwhere(ml.any(axis=-1)):
        t, cells = Tl[tuple(line)], np.nonzero(ml[tuple(line)])[0]
        lo, hi = cells.min(), cells.max()
        x0 = lo * h if lo == 0 else (lo - 0.5 + crossing(t[lo], t[lo - 1])) * h
        x1 = (hi + 1) * h if hi == len(t) - 1 else (hi + 0.5 + 1.0 - crossing(t[hi], t[hi + 1])) * h
        best = max(best, x1 - x0)
    return best


def crossing(t_in, t_out):
    """Where between a molten cell's centre (T t_in >= T_MELT) and its neighbour's (t_out) T
    crosses T_MELT, as the fraction of the way from the neighbour: 0 at the neighbour's centre
    when it is not colder."""
    return 0.0 if t_out >= T_MELT else (T_MELT - t_out) / (t_in - t_out)


def melt_pool(case, cfg):
    """From the written fields: melt pool depth (deepest point below the initial substrate
    surface y = SUB of metal with T >= T_MELT, interpolated along the column), width
    (extent across the track, z, of molten metal) and length (x), both interpolated to the T_MELT
    crossings along their lines as the depth is, and the keyhole depth (SUB minus
    the lowest metal surface height within rw/2 of the beam axis), each the maximum over the
    written times with its time."""
    nx, ny, nz = ncells(cfg)
    h = cfg["dx"]
    yc = (np.arange(ny) + 0.5) * h
    xc = (np.arange(nx) + 0.5) * h
    zc = (np.arange(nz) + 0.5) * h
    sub = cfg["sub"]
    out = dict(depth=(0.0, 0.0), width=(0.0, 0.0), length=(0.0, 0.0), keyhole=(0.0, 0.0),
               peak_T=(0.0, 0.0), pool_volume=(0.0, 0.0))
    series = []
    depth_x = np.zeros(nx)          # deepest molten point per x (over z and time)
    surface_x = None                # metal surface height on the track centre line, last time
    for d in fc.time_dirs(case):
        fT, fa = os.path.join(case, d, "T"), os.path.join(case, d, "alpha.metal")
        if not (os.path.exists(fT) and os.path.exists(fa)) or float(d) == 0.0:
            continue
        t = float(d)
        T = fc.lattice_field(case, d, "T", (nx, ny, nz), h)
        a = fc.lattice_field(case, d, "alpha.metal", (nx, ny, nz), h)
        molten = (a >= 0.5) & (T >= T_MELT)
        # depth: lowest molten point, interpolated to the T_MELT crossing below it
        depth = 0.0
        cols = np.argwhere(molten.any(axis=1))
        for k, i in cols:
            js = np.nonzero(molten[k, :, i])[0]
            j = js.min()
            y = yc[j]
            if j > 0 and T[k, j - 1, i] < T_MELT:
                y = yc[j - 1] + (T_MELT - T[k, j - 1, i]) / (T[k, j, i] - T[k, j - 1, i]) * h
            depth = max(depth, sub - y)
            depth_x[i] = max(depth_x[i], sub - y)
        # width (z) and length (x) of the molten region, to the T_MELT crossings
        width = isotherm_extent(T, molten, 0, h)
        length = isotherm_extent(T, molten, 2, h)
        # keyhole: metal surface height in the columns near the beam axis (first alpha < 0.5
        # going up from the bottom, interpolated)
        xb, zb = beam_xz(cfg, t)
        near = (np.hypot(xc[None, :] - xb, zc[:, None] - zb) <= cfg["rw"] / 2)
        low = np.inf
        for k, i in np.argwhere(near):
            col = a[k, :, i]
            js = np.nonzero(col < 0.5)[0]
            if not len(js):
                continue
            j = js[0]
            y = 0.0 if j == 0 else yc[j - 1] + (col[j - 1] - 0.5) / (col[j - 1] - col[j]) * h
            low = min(low, y)
        keyhole = sub - low if np.isfinite(low) else 0.0
        kc = nz // 2
        surface_x = []
        for i in range(nx):
            col = 0.5 * (a[kc, :, i] + a[kc - 1, :, i]) if nz % 2 == 0 else a[kc, :, i]
            js = np.nonzero(col < 0.5)[0]
            j = js[0] if len(js) else ny
            surface_x.append(0.0 if j == 0 else (yc[j - 1] + (col[j - 1] - 0.5) / (col[j - 1] - col[j]) * h
                                                 if j < ny else ny * h))
        vol = float(np.sum(a * (T >= T_MELT))) * h ** 3
        peak = float(np.max(np.where(a >= 0.5, T, 0.0)))
        series.append(dict(time_s=t, depth_m=depth, width_m=width, length_m=length, keyhole_m=keyhole,
                           peak_metal_T_K=peak, pool_volume_m3=vol))
        for key, val in (("depth", depth), ("width", width), ("length", length), ("keyhole", keyhole),
                         ("peak_T", peak), ("pool_volume", vol)):
            if val > out[key][0]:
                out[key] = (val, t)
    out["depth_x"] = depth_x
    out["surface_x"] = np.array(surface_x) if surface_x is not None else np.zeros(nx)
    out["x"] = xc
    return out, series


def beam_x(cfg, t):
    if not cfg["v"] or t <= cfg["t_move"]:
        return cfg["x0"]
    return cfg["x0"] + cfg["v"] * (min(t, cfg["t_off"]) - cfg["t_move"])


def laser_energy(case, cfg):
    """(absorbed by the continuum, by the grains, eta P t_on) [J]."""
    bal = os.path.join(case, "postProcessing", "particleBalance", "0", "balance.csv")
    cont = 0.0
    if os.path.exists(bal):
        b = np.genfromtxt(bal, delimiter=",", names=True)
        b = b.reshape(1) if b.ndim == 0 else b
        cont = float(b["laserEnergy_cum"][-1])
        evap = float(b["evaporationEnergy_cum"][-1])
    else:
        evap = 0.0
    p = cc.particles_csv(case)
    grains_ = float(np.sum(p["laser_heat"]))
    t_end = float(p["time"][-1])
    eta0 = cfg.get("laser_args", {}).get("absorptivity", ETA)
    if cfg.get("laser_args", {}).get("dabsorptivity_dt") is None:
        return cont, grains_, eta0 * cfg["power"] * lit_time(cfg, t_end), evap, t_end
    # the linear model: eta P integrated over the steps' lit time
    log = open(os.path.join(case, "log.meltdemFoam")).read()
    eta_t = laser.absorbed_fraction_integral(log, eta0, lambda t: lit_time(cfg, min(t, t_end)))
    return cont, grains_, cfg["power"] * eta_t, evap, t_end


def summary(case):
    cfg = json.load(open(os.path.join(case, "pbf.json")))
    s = {"variant": cfg["variant"], "cells": "x".join(str(c) for c in ncells(cfg)),
         "cell_size_um": cfg["dx"] * 1e6, "cells_per_grain_diameter_min": D_LO / cfg["dx"],
         "cells_per_grain_diameter_max": D_HI / cfg["dx"], "distribution": cfg["dist"],
         "grains": cfg["n"], "bed_top_um": cfg["bed_top"] * 1e6}
    led = cc.ledger(case)
    p = cc.particles_csv(case)
    s["simulated_time_s"] = float(led["time"][-1])
    s["end_time_s"] = cfg["t_end"]
    s["completed"] = bool(led["time"][-1] >= cfg["t_end"] - led["dt"][-1])   # OpenFOAM stops within dt/2
    s["fluid_steps"] = int(len(led))
    s["dem_steps"] = int(np.sum(p["dem_steps"]))
    ws = os.path.join(case, "wall_seconds")
    if os.path.exists(ws):
        w = open(ws).read().split()
        s["wall_seconds"], s["ranks"] = float(w[0]), int(w[1])
    pool, series = melt_pool(case, cfg)
    for k, unit, scale in (("depth", "um", 1e6), ("width", "um", 1e6), ("length", "um", 1e6),
                           ("keyhole", "um", 1e6), ("peak_T", "K", 1.0), ("pool_volume", "um3", 1e18)):
        s[f"melt_pool_{k}_max_{unit}" if k not in ("keyhole", "peak_T") else
          (f"keyhole_depth_max_{unit}" if k == "keyhole" else "peak_metal_T_K")] = pool[k][0] * scale
        s[f"{k}_time_s"] = pool[k][1]
    s.update(grains(case, cfg))
    if cfg["v"] and not cfg.get("tracks"):
        # the moving pool: widest written pool in the second half of the travel (Eagar-Tsai is
        # the quasi-steady pool), and the profile along the track
        late = [r for r in series
                if cfg["t_move"] + 0.5 * (cfg["t_off"] - cfg["t_move"]) <= r["time_s"] <= cfg["t_off"]]
        s["melt_pool_width_moving_um"] = max((r["width_m"] for r in late), default=0.0) * 1e6
        s["melt_pool_depth_moving_um"] = max((r["depth_m"] for r in late), default=0.0) * 1e6
        s["eagar_tsai_width_um"] = eagar_tsai_width(ETA * cfg["power"], cfg["v"], cfg["rw"] / 2) * 1e6
        x_end = beam_x(cfg, cfg["t_off"])
        i0 = int(np.argmin(abs(pool["x"] - cfg["x0"])))
        i1 = int(np.argmin(abs(pool["x"] - x_end)))
        s["depth_at_start_um"] = float(pool["depth_x"][i0]) * 1e6
        s["depth_at_end_um"] = float(pool["depth_x"][i1]) * 1e6
        s["final_surface_at_start_um"] = float(pool["surface_x"][i0] - cfg["sub"]) * 1e6
        s["final_surface_at_end_um"] = float(pool["surface_x"][i1] - cfg["sub"]) * 1e6
    m0 = float(led["mass_particles"][0] + p["mass_melted"][0]) if len(p) else 0.0
    s["grain_mass_initial_kg"] = m0
    s["grain_mass_molten_kg"] = float(np.sum(p["mass_melted"]))
    s["grain_mass_remaining_kg"] = float(led["mass_particles"][-1])
    s["grain_mass_lost_kg"] = float(led["mass_cumulative_lost"][-1])
    # the melt the continuum received (the ledger's exchange): a grain that leaves the mesh takes
    # its last step's melt with it, booked as lost, while particles.csv counts it as molten
    deposited = float(np.sum(led["mass_exchange"]))
    s["grain_mass_balance_rel"] = ((s["grain_mass_remaining_kg"] + deposited + s["grain_mass_lost_kg"] - m0) / m0
                                   if m0 else 0.0)
    cont, gl, ref, evap, t_end = laser_energy(case, cfg)
    s["laser_energy_continuum_J"], s["laser_energy_grains_J"] = cont, gl
    s["laser_energy_absorbed_J"], s["laser_energy_eta_P_t_J"] = cont + gl, ref
    s["laser_energy_rel_error"] = (cont + gl - ref) / ref if ref else 0.0
    s["evaporation_energy_J"] = evap
    steps = led[1:]
    for comp, key in (("mass", "mass"), ("enthalpy", "energy")):
        s[f"worst_step_continuum_{key}_error"] = (float(np.max(np.abs(steps[f"{comp}_continuum_error"])))
                                                  if len(steps) else 0.0)
        s[f"worst_step_system_{key}_error"] = (float(np.max(np.abs(steps[f"{comp}_system_error"])))
                                               if len(steps) else 0.0)
    s["cumulative_system_mass_error"] = float(led["mass_cumulative_system_error"][-1])
    s["T_min_K"], s["T_max_K"] = log_T_range(case)
    s["solver_stop"] = stop_reason(case) or ""
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(s, f, indent=1)
    with open(os.path.join(case, "melt_pool_series.json"), "w") as f:
        json.dump({"series": series, "x_m": pool["x"].tolist(), "max_depth_along_x_m": pool["depth_x"].tolist(),
                   "final_surface_height_along_x_m": pool["surface_x"].tolist()}, f, indent=1)
    return s


def log_T_range(case):
    lo, hi = np.inf, -np.inf
    logs = [f for f in os.listdir(case) if f.startswith("log.meltdemFoam")]
    for name in logs:
        for m in re.finditer(r"T min/max = (\S+), (\S+)", open(os.path.join(case, name)).read()):
            lo, hi = min(lo, float(m.group(1))), max(hi, float(m.group(2)))
    return (float(lo) if np.isfinite(lo) else 0.0), (float(hi) if np.isfinite(hi) else 0.0)


def print_summary(s):
    w = max(len(k) for k in s)
    for k, v in s.items():
        print(f"  {k:<{w}}  {v:.6g}" if isinstance(v, float) else f"  {k:<{w}}  {v}")


# ----------------------------------------------------------------------------------------------
# analytic reference: Eagar-Tsai (Gaussian source moving over a half space, conduction only)


def eagar_tsai_width(q, v, sigma, k=M["k"], rho=M["rho"], cp=M["cp"], T0=T0, Tm=T_MELT):
    """Melt-pool width (2 x the largest half-width of the Tm isotherm on the surface) of a
    Gaussian surface source of absorbed power q, standard deviation sigma (= r_w/2), moving at v
    over a half space (Eagar & Tsai 1983):
    T - T0 = q/(pi rho cp sqrt(4 pi a)) int_0^inf exp(-((x + v t)^2 + y^2)/(4 a t + 2 s^2)
             - z^2/(4 a t)) / (sqrt(t) (2 a t + s^2)) dt   (z = 0 on the surface)."""
    from scipy.integrate import quad
    from scipy.optimize import brentq
    a = k / (rho * cp)

    def temp(x, y):
        def f(u):
            return (np.exp(-((x + v * u * u) ** 2 + y ** 2) / (4 * a * u * u + 2 * sigma ** 2))
                    / (2 * a * u * u + sigma ** 2)) * 2.0   # t = u^2: dt/sqrt(t) = 2 du
        val, _ = quad(f, 0, np.inf, limit=400)
        return T0 + q / (np.pi * rho * cp * np.sqrt(4 * np.pi * a)) * val

    def half_width(x):
        if temp(x, 0.0) < Tm:
            return 0.0
        return brentq(lambda y: temp(x, y) - Tm, 0.0, 2e-3)

    from scipy.optimize import minimize_scalar
    r = minimize_scalar(lambda x: -half_width(x), bounds=(-6 * sigma - 2e-4, 2 * sigma), method="bounded")
    return 2 * half_width(r.x)


def stop_reason(case):
    """The first line of a FOAM FATAL ERROR or a LAMMPS ERROR in the solver log, if any."""
    path = os.path.join(case, "log.meltdemFoam")
    if not os.path.exists(path):
        return None
    lines = open(path).read().splitlines()
    for i, line in enumerate(lines):
        if "FOAM FATAL" in line and i + 1 < len(lines):
            return lines[i + 1].strip()[:400]
        if line.startswith("ERROR"):
            return line.strip()[:400]
    return None
