#!/usr/bin/python3
"""Laser metal deposition, single pass: Codina2019 §4.1, table 4.1 conditions, compared with
table 4.2 (bead width, height, penetration, powder deposition efficiency).

meltdemFoam (substrate, melt pool, argon) hosts LAMMPS (the powder stream) in one MPI job. A 1 kW
Gaussian beam (2.5 mm 1/e^2 spot) moves at 100 mm/min over a steel plate; a coaxial powder
stream (40-200 um, 1.6 g/min) is inserted during the run by fix powder/insert (massrate) in a
slab above the pool that moves with the beam, aimed down at the pool. Grains that land in the
melt are captured and melt into the continuum (deposited); grains that land on solid metal
bounce off it (fix powder/melt solid_metal) and leave the mesh (booked as lost).

Half model: the plane y = 0 through the beam axis is a symmetry plane (OpenFOAM symmetryPlane,
LAMMPS fix wall/reflect); laser power and powder feed are halved accordingly.

    scene.py build CASE [--ci | --full] [--track MM --dx MM --np N ...]
    scene.py run CASE [--np N]
    scene.py analyse CASE
    scene.py all CASE [--ci | --full] [--np N]

See README.md next to this file for the model, what it leaves out and the results.
"""
import argparse
import copy
import json
import math
import os
import shutil
import sys

import numpy as np

from meltdem import paths
from meltdem.analysis import profiles
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.case import laser
from meltdem.scene import Scene

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = paths.source_dir()
paths.set_tool_environment()

# ---------------------------------------------------------------------------------------------
# Codina2019 table 4.1 (process) and table 4.2 (references)
PROCESS = dict(power=1000.0,            # W
               spot_diameter=2.5e-3,    # m, Gaussian, taken as the 1/e^2 diameter
               speed=100e-3 / 60.0,     # m/s (100 mm/min)
               feed=1.6e-3 / 60.0,      # kg/s (1.6 g/min)
               dmin=40e-6, dmax=200e-6,  # m, powder size range
               substrate_thickness=5e-3)
EXPERIMENT = dict(width_mm=3.46, height_mm=0.82, penetration_mm=0.61, efficiency_pct=85.8)
THESIS_SIM = dict(width_mm=3.3, height_mm=0.75, penetration_mm=0.75, efficiency_pct=86.5)

# One metal (the coupling requires particles and continuum to share cp, L and Tmelt): AISI 304,
# the substrate, which holds nearly all of the heat and the whole melt pool (the powder is 2.5 %
# of the absorbed power). Values averaged over 300 K - Tm (Mills, Recommended values of
# thermophysical properties for selected commercial alloys, 2002); the grains keep Inconel 718's
# density, so the fed mass is the table's 1.6 g/min of IN718.
METAL = dict(rho=7900.0, mu=6.0e-3, cp=600.0, k=25.0, L=2.6e5, Tsolidus=1670.0, Tliquidus=1727.0,
             sigma0=1.75, dSigmadT=-4.0e-4, Tsigma0=1700.0, sigmaMin=0.2)
T_MELT_PARTICLE = 1700.0          # in [Tsolidus, Tliquidus] (checked by the coupling)
RHO_POWDER = 8190.0               # Inconel 718
DUMMY_ID = 1000000
DUMMY_D = 1e-5
ARGON = dict(rho=1.6, mu=2.2e-5, cp=520.0, k=0.018)
T0 = 300.0
G = 9.81

VARIANTS = {
    # CI: 0.5 mm cells, 1.2 mm of track (0.72 s); the measured section then lies just before the
    # start and misses part of its powder: the CI geometry is a smoke check
    "ci": dict(dx=0.5e-3, track=1.2e-3, write=0.06, absorptivity=0.35),
    # full: Codina2019's 0.25 mm cells, a shortened track (3 mm, 1.8 s; see README)
    "full": dict(dx=0.25e-3, track=3.0e-3, write=0.1, absorptivity=0.35),
}


# ---------------------------------------------------------------------------------------------
# mesh: one block, multi-section grading; fine (dx) around the track, geometric growth outside
def graded(length, h, growth=1.2, hmax=None):
    """(n, expansion last/first) of a section of `length` starting with cells of size h and
    growing by at most `growth` per cell (coarsest cell at most hmax)."""
    n = 1
    while True:
        r = min(growth, ((hmax or 1e9) / h) ** (1.0 / max(n - 1, 1)))
        s = h * (r ** n - 1) / (r - 1) if abs(r - 1) > 1e-12 else h * n
        if s >= length:
            break
        n += 1
    # choose the ratio r so that n cells starting at h fill the length exactly
    lo, hi = 1.0, growth * 1.5
    for _ in range(200):
        r = 0.5 * (lo + hi)
        s = h * (r ** n - 1) / (r - 1) if abs(r - 1) > 1e-12 else h * n
        lo, hi = (r, hi) if s < length else (lo, r)
    return n, r ** (n - 1)


def section_faces(x0, sections):
    """Face coordinates of consecutive sections [(length, n, expansion)], OpenFOAM's geometric
    division (first cell L (1-q)/(1-q^n), q = expansion^(1/(n-1)))."""
    faces = [x0]
    for length, n, e in sections:
        q = e ** (1.0 / (n - 1)) if n > 1 else 1.0
        w = np.ones(n) if abs(q - 1) < 1e-14 else q ** np.arange(n)
        faces.extend(faces[-1] + length * np.cumsum(w) / np.sum(w))
    return np.array(faces)


class Geometry:
    """Half model, z = 0 the plate surface, y = 0 the symmetry plane through the track, the beam
    moving along +x from x_start to x_end."""

    def __init__(self, dx, track, margin_behind=2.5e-3, margin_ahead=2.5e-3, coarse_x=4e-3,
                 y_fine=3.0e-3, width=8e-3, z_fine=1.5e-3, gas=1.75e-3):
        self.dx, self.track = dx, track

        def snap(v):
            return math.ceil(v / dx - 1e-9) * dx     # fine zones hold whole cells (z = 0 a face)
        y_fine, z_fine, gas = snap(y_fine), snap(z_fine), snap(gas)
        self.x_start = coarse_x + margin_behind
        self.x_end = self.x_start + track
        fine_x = margin_behind + track + margin_ahead
        fine_x = math.ceil(fine_x / dx - 1e-9) * dx
        nfx = int(round(fine_x / dx))
        ncx, ecx = graded(coarse_x, dx, hmax=8 * dx)
        self.xsec = [(coarse_x, ncx, 1.0 / ecx), (fine_x, nfx, 1.0), (coarse_x, ncx, ecx)]
        nfy = int(round(y_fine / dx))
        ncy, ecy = graded(width - y_fine, dx, hmax=8 * dx)
        self.ysec = [(y_fine, nfy, 1.0), (width - y_fine, ncy, ecy)]
        sub = PROCESS["substrate_thickness"]
        ncz, ecz = graded(sub - z_fine, dx, hmax=8 * dx)
        nfz = int(round((z_fine + gas) / dx))
        self.zsec = [(sub - z_fine, ncz, 1.0 / ecz), (z_fine + gas, nfz, 1.0)]
        self.xf = section_faces(0.0, self.xsec)
        self.yf = section_faces(0.0, self.ysec)
        self.zf = section_faces(-sub, self.zsec)
        self.lo = (self.xf[0], self.yf[0], self.zf[0])
        self.hi = (self.xf[-1], self.yf[-1], self.zf[-1])
        self.gas = gas
        self.n = (len(self.xf) - 1, len(self.yf) - 1, len(self.zf) - 1)

    def centres(self):
        c = [0.5 * (f[1:] + f[:-1]) for f in (self.xf, self.yf, self.zf)]
        return c

    def split(self, levels):
        """The lattice of the finest cells of a mesh refined `levels` times from this one: every
        cell cut into 2^levels per axis at equal spacing (hexRef8 splits at the midpoints)."""
        g = copy.copy(self)
        k = 2 ** levels
        g.xf, g.yf, g.zf = (np.append(f[:-1, None] + np.outer(np.diff(f), np.arange(k) / k), f[-1])
                            for f in (self.xf, self.yf, self.zf))
        g.dx = self.dx / k
        g.n = tuple(k * n for n in self.n)
        return g

    def cells(self):
        return self.n[0] * self.n[1] * self.n[2]


def grading_text(secs):
    return "(" + " ".join(f"({length * 1e3!r} {n} {e!r})" for length, n, e in secs) + ")"


def write_mesh(case, g):
    x0, y0, z0 = g.lo
    x1, y1, z1 = g.hi
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    vs = "\n".join(f"    ({a!r} {b!r} {c!r})" for a, b, c in verts)
    fc.dictionary(case, "system/blockMeshDict", f"""scale 1;
vertices
(
{vs}
);
blocks
(
    hex (0 1 2 3 4 5 6 7) ({g.n[0]} {g.n[1]} {g.n[2]})
    simpleGrading ({grading_text(g.xsec)} {grading_text(g.ysec)} {grading_text(g.zsec)})
);
edges ();
boundary
(
    symmetry {{ type symmetryPlane; faces ((0 1 5 4)); }}
    sides    {{ type wall; faces ((0 4 7 3) (1 2 6 5) (3 7 6 2)); }}
    bottom   {{ type wall; faces ((0 3 2 1)); }}
    top      {{ type patch; faces ((4 5 6 7)); }}
);
""")


# ---------------------------------------------------------------------------------------------
def powder_rings(w, nrings=4, rmax_w=2.0):
    """Gaussian powder spot (1/e^2 radius w) as nrings uniform annuli out to rmax_w w: radii and
    the mass fraction of each ring (normalised to the truncated Gaussian)."""
    radii = np.linspace(0.0, rmax_w * w, nrings + 1)
    cdf = 1.0 - np.exp(-2.0 * radii ** 2 / w ** 2)
    frac = np.diff(cdf) / cdf[-1]
    return radii, frac


def dem_step(estar, dmin, v):
    """A tenth of the Hertz contact time (Codina2019 eq. 3.1) of the smallest grain hitting the
    solid metal (or another grain) at speed v."""
    m = RHO_POWDER * math.pi * dmin ** 3 / 6.0
    tc = 2.87 * (m ** 2 / (0.5 * dmin * estar ** 2 * v)) ** 0.2
    return tc / 10.0


def rosenthal(g, absorbed, X, Y, Z, images=6):
    """Quasi-steady temperature of a point source `absorbed` [W] moving along +x at the scan speed
    on the plate surface (Rosenthal's thick-plate solution, plate thickness by image sources for
    adiabatic top and bottom), the source at x_start, capped below the solidus: the plate as the
    beam finds it in the steady section of a long track (no pool yet)."""
    alpha_th = METAL["k"] / (METAL["rho"] * METAL["cp"])
    v, H = PROCESS["speed"], PROCESS["substrate_thickness"]
    xi = X - g.x_start
    T = np.zeros_like(X)
    for n in range(-images, images + 1):
        R = np.sqrt(xi ** 2 + Y ** 2 + (Z - 2 * n * H) ** 2)
        R = np.maximum(R, 1e-6)
        T += np.exp(-v * (xi + R) / (2 * alpha_th)) / R
    T = T0 + absorbed / (2 * math.pi * METAL["k"]) * T
    return np.minimum(T, METAL["Tsolidus"] - 50.0)


def write_lammps(case, g, a):
    w = 0.5 * PROCESS["spot_diameter"] * a.powder_spot
    radii, frac = powder_rings(w)
    feed = 0.5 * PROCESS["feed"]                         # half model
    margin = 1e-3
    # nozzle slab: inside the mesh, under the top; spans the whole track so that its (static)
    # bounding box holds the moving rings
    z1 = g.hi[2] - 0.1e-3
    z0 = z1 - 0.4e-3
    xa, xb = g.x_start - radii[-1] - 0.1e-3, g.x_end + radii[-1] + 0.1e-3
    m_mean = RHO_POWDER * math.pi / 6 * (PROCESS["dmax"] ** 4 - PROCESS["dmin"] ** 4) / (
        4 * (PROCESS["dmax"] - PROCESS["dmin"]))
    n_expected = feed * a.end / m_mean
    dt = dem_step(a.estar, PROCESS["dmin"], max(2.0, a.powder_speed * 1.5))
    # a held dummy grain with a large ID: fix powder/insert numbers new grains after the largest
    # current ID, and without it a grain that melts away would hand its ID to the next one (the
    # coupling keeps per-ID state)
    dummy = (g.lo[0] + 0.3e-3, g.hi[1] - 0.3e-3, g.hi[2] - 0.3e-3)
    with open(os.path.join(case, "lmd.data"), "w") as f:
        f.write(f"""LMD powder stream: one held dummy grain (scene.py)

1 atoms
1 atom types

{g.lo[0] - margin!r} {g.hi[0] + margin!r} xlo xhi
{-margin!r} {g.hi[1] + margin!r} ylo yhi
{g.lo[2] - margin!r} {g.hi[2] + margin!r} zlo zhi

Atoms # sphere

{DUMMY_ID} 1 {DUMMY_D!r} {RHO_POWDER!r} {dummy[0]!r} {dummy[1]!r} {dummy[2]!r}
""")
    lines = [f"""# LMD powder stream (thesis 4.1, table 4.1), half model: written by examples/lmd-track/scene.py
units           si
atom_style      sphere 1
dimension       3
boundary        f f f
atom_modify     map hash
comm_modify     vel yes
read_data       lmd.data
group           grains empty
neighbor        5e-5 bin
neigh_modify    binsize 1e-3
neigh_modify    every 1 delay 0 check yes
# grains are soft (E* {a.estar:g} Pa): collisions in the sparse stream are rare (thesis 4.1) and the
# DEM step follows the Hertz contact time of the smallest grain (overlap at impact < 10 % R)
pair_style      granular/powder
pair_coeff      * * hertz/material {2 * (1 - 0.3 ** 2) * a.estar!r} {a.restitution!r} 0.3 damping tsuji tangential linear_nohistory 0 0
timestep        {dt!r}
fix             integrate grains nve/sphere
fix             gravity grains gravity {G!r} vector 0 0 -1
fix             symmetry grains wall/reflect ylo 0.0
# a grain melted below half the smallest inserted one would have fewer than 5 steps per contact
# at this step: what is left of it goes to the melt (fix powder/melt handover)
fix             melt all powder/melt cp {METAL['cp']!r} Tmelt {T_MELT_PARTICLE!r} latent {METAL['L']!r} temp {T0!r} solid_metal {a.estar!r} {a.restitution!r} handover {0.5 * PROCESS['dmin']!r}
# the nozzle moves with the beam: ring centres follow x_beam(t)
variable        xb equal {g.x_start!r}+{PROCESS['speed']!r}*time
region          slab block {xa!r} {xb!r} 0.0 {radii[-1] + 0.1e-3!r} {z0!r} {z1!r}
"""]  # noqa: E501  (long lines of the LAMMPS input written verbatim)
    ins = []
    for k in range(len(frac)):
        ro, ri = radii[k + 1], radii[k]
        lines.append(f"region          out{k} cylinder z v_xb 0.0 {ro!r} INF INF side out\n"
                     f"region          in{k} union 2 out{k} out{k} side out\n")
        if k == 0:
            lines.append(f"region          ring{k} intersect 2 slab in{k}\n")
        else:
            lines.append(f"region          hole{k} cylinder z v_xb 0.0 {ri!r} INF INF side out\n"
                         f"region          ring{k} intersect 3 slab in{k} hole{k}\n")
        n_k = int(max(50, 3 * n_expected * frac[k] + 50))
        lines.append(f"fix             ins{k} grains powder/insert {n_k} {4711 + 97 * k} region ring{k} "
                     f"diam uniform {PROCESS['dmin']!r} {PROCESS['dmax']!r} dens {RHO_POWDER!r} "
                     f"massrate {feed * frac[k]!r} vel 0 0 {-a.powder_speed!r} temp {T0!r} attempts 2000\n")
        ins.append(k)
    nins = "+".join(f"f_ins{k}[1]" for k in ins)
    mins = "+".join(f"f_ins{k}[4]" for k in ins)
    mpend = "+".join(f"f_ins{k}[5]" for k in ins)
    every = max(1, int(round(a.log_every / dt)))
    lines.append(f"""variable        t equal time
variable        nins equal {nins}
variable        mins equal {mins}
variable        mpend equal {mpend}
variable        mmelt equal f_melt[1]
variable        np equal atoms
fix             feedlog all ave/time {every} 1 {every} v_t v_np v_nins v_mins v_mpend v_mmelt file feed.dat format " %.15g"
dump            grains all custom {every * 20} dump.grains id x y z vx vy vz diameter f_melt[1]
dump_modify     grains sort id
thermo_style    custom step time atoms v_nins v_mins v_mmelt
thermo_modify   format float %.15g
thermo          {every * 20}
""")  # noqa: E501  (a long line of the LAMMPS input written verbatim)
    with open(os.path.join(case, "in.particles"), "w") as f:
        f.write("".join(lines))
    return dt


# ---------------------------------------------------------------------------------------------
def field(case, name, dims, internal, bf, vector=False):
    if isinstance(internal, np.ndarray):
        txt = fc._internal(internal, vector)
    else:
        txt = internal
    b = "".join(f"    {k}\n    {{\n        {v}\n    }}\n" for k, v in bf.items())
    fc.write(case, f"0/{name}", "volVectorField" if vector else "volScalarField", name,
             f"dimensions {dims};\ninternalField {txt};\nboundaryField\n{{\n{b}}}\n")


def build(a):
    case = a.case
    if os.path.exists(case):
        # (.meltdem.lock: the lock `meltdem run` holds on the case while it builds it)
        if set(os.listdir(case)) - {".meltdem.lock"} and not os.path.exists(os.path.join(case, "scene.json")):
            raise SystemExit(f"lmd-track: {case} exists and is not a scene case; not overwriting it")
        shutil.rmtree(case)
    os.makedirs(case)
    g = Geometry(a.dx * 2 ** a.refine, a.track)        # the base mesh (refined to a.dx where needed)
    a.end = a.track / PROCESS["speed"]
    write_mesh(case, g)
    xc, yc, zc = g.centres()
    Z = np.broadcast_to(zc[:, None, None], (g.n[2], g.n[1], g.n[0])).ravel()
    alpha = np.where(Z < 0.0, 1.0, 0.0)
    Y = np.broadcast_to(yc[None, :, None], (g.n[2], g.n[1], g.n[0])).ravel()
    X = np.broadcast_to(xc[None, None, :], (g.n[2], g.n[1], g.n[0])).ravel()
    if a.cold_start:
        Tinit = f"uniform {T0!r}"
    else:
        Tinit = np.where(Z < 0.0, rosenthal(g, a.absorptivity * PROCESS["power"], X, Y, Z), T0)
    sym = "type symmetryPlane;"
    field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha,
          {"symmetry": sym, "sides": "type zeroGradient;", "bottom": "type zeroGradient;",
           "top": "type inletOutlet; inletValue uniform 0; value uniform 0;"})
    field(case, "T", "[0 0 0 1 0 0 0]", Tinit,
          {"symmetry": sym, "sides": "type zeroGradient;", "bottom": "type zeroGradient;",
           "top": f"type inletOutlet; inletValue uniform {T0!r}; value uniform {T0!r};"})
    field(case, "U", "[0 1 -1 0 0 0 0]", "uniform (0 0 0)",
          {"symmetry": sym, "sides": "type noSlip;", "bottom": "type noSlip;",
           "top": "type pressureInletOutletVelocity; value uniform (0 0 0);"}, vector=True)
    field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", "uniform 0",
          {"symmetry": sym, "sides": "type fixedFluxPressure; value uniform 0;",
           "bottom": "type fixedFluxPressure; value uniform 0;",
           "top": "type totalPressure; p0 uniform 0; value uniform 0;"})
    fc.transport(case, METAL["rho"], METAL["mu"] / METAL["rho"], ARGON["rho"], ARGON["mu"] / ARGON["rho"],
                 METAL["sigma0"])
    fc.gravity(case, (0.0, 0.0, -G))
    rho_avg = 0.5 * (METAL["rho"] + ARGON["rho"])
    dt_cap = math.sqrt(rho_avg * a.dx ** 3 / (2 * math.pi * METAL["sigma0"]))
    # a grain sees the fluid of its cell at the start of the fluid step (explicit coupling) and the
    # solid metal is located once per step: a grain crossing more than a fraction of a cell per
    # step samples the wrong phase (melt heat charged to gas cells, deep wall overlaps)
    dt_grain = a.cells_per_step * a.dx / a.powder_speed
    a.max_dt = min(dt_cap, dt_grain) if a.particles else dt_cap
    fc.control_dict(case, "meltdemFoam", a.end, min(1e-5, a.max_dt), a.write, max_co=0.4, max_alpha_co=0.4,
                    max_dt=a.max_dt, extra=fc.CELL_GEOMETRY_FUNCTIONS if a.refine else "")
    fc.fv_schemes(case)
    fc.fv_solution(case, n_correctors=2)
    cc.exact_solves(case)   # metal mass to round-off needs a tight alpha solve
    laser_power = 0.5 * PROCESS["power"]          # half model
    fc.meltdem_properties(case, physics=dict(energy="on", darcy="on", surfaceTension="on",
                                             marangoni="on" if a.marangoni else "off",
                                             laser="on", particles="on" if a.particles else "off"),
                          # Marangoni density-scaled: on the metal side, so the argon moves by the melt's drag
                          surface=dict({k: METAL[k] for k in ("sigma0", "dSigmadT", "Tsigma0", "sigmaMin")},
                                       **({"marangoniDensityScaled": 1}
                                          if a.marangoni and a.marangoni_scaling == "density" else {})),
                          extra=f"""
metal {{ cp {METAL['cp']!r}; k {METAL['k']!r}; L {METAL['L']!r}; Tsolidus {METAL['Tsolidus']!r}; Tliquidus {METAL['Tliquidus']!r}; }}
gas {{ cp {ARGON['cp']!r}; k {ARGON['k']!r}; }}
darcy {{ C 1e8; b 1e-3; }}
energyControls {{ nCorrectors 20; tolerance 1e-10; }}
laser
{{
    power           {laser_power!r};   // half model: P/2
{laser.absorptivity_entries(a, a.absorptivity, METAL['Tliquidus'])}    radius          {0.5 * PROCESS['spot_diameter']!r};   // 1/e^2 radius of the 2.5 mm spot
    direction       (0 0 -1);
    position        ({g.x_start!r} 0 0);
    velocity        ({PROCESS['speed']!r} 0 0);
    tStart          0;
    tStop           {a.end!r};
}}
particles
{{
    lammpsInput     in.particles;
    distribution    {a.distribution};
    demStepsPerFluidStep auto;
    laserShadow     {"on" if a.laser_shadow else "off"};   // powder absorption is negligible in LMD (thesis 4.1)
}}
{refinement_dict(a) if a.refine else ""}""")  # noqa: E501  (a long line of the dictionary written verbatim)
    dem_dt = write_lammps(case, g, a)
    meta = dict(vars(a), scene="lmd-track", cells=g.cells(), n=g.n, x_start=g.x_start, x_end=g.x_end, dem_dt=dem_dt,
                dt_capillary=dt_cap)
    with open(os.path.join(case, "scene.json"), "w") as f:
        json.dump(meta, f, indent=1)
    print(f"lmd-track: case {case}: {g.n[0]}x{g.n[1]}x{g.n[2]} = {g.cells()} cells "
          f"({f'base {g.dx * 1e3:g} mm refined to ' if a.refine else 'fine '}{a.dx * 1e3:g} mm), "
          f"track {a.track * 1e3:g} mm = {a.end:.3g} s, DEM step {dem_dt:.3g} s, capillary step {dt_cap:.3g} s")
    return case


def refinement_dict(a):
    """refinement{} of a --refine run: the finest cells in the melt pool and the metal within 300 K
    of melting, under the beam (1.2 radii, 0.5 mm deep) and where it will be over the next half beam
    radius of travel, and around the grains near either (with powder); the base mesh elsewhere."""
    ahead = 0.25 * PROCESS["spot_diameter"] / PROCESS["speed"]
    grains = [("grains", "type particles; diameters 1; near (pool beam);")] if a.particles else []
    return fc.refinement_dict(a.refine, a.refine_interval,
                              [("meltPool", "belowSolidus 300;"),
                               ("laser", f"radii 1.2; depth 5e-4; lookAhead {a.refine_interval}; "
                                         f"lookAheadTime {ahead!r};")] + grains)


# ---------------------------------------------------------------------------------------------
def run(case, np_=1):
    return fc.run_scene_case(case, np_, "lmd-track")


# ---------------------------------------------------------------------------------------------
def times(case):
    return [d for d in fc.time_dirs(case) if float(d) > 0]


def analyse(case, quiet=False):
    meta = json.load(open(os.path.join(case, "scene.json")))
    levels = meta.get("refine", 0)
    base = Geometry(meta["dx"] * 2 ** levels, meta["track"])
    g = base.split(levels)

    def read_field(time, name):          # on the finest cells' lattice (a refined cell fills those it covers)
        return fc.graded_lattice_field(case, time, name, (base.xf, base.yf, base.zf), levels).ravel()
    xc, yc, zc = g.centres()
    nx, ny, nz = g.n
    tds = times(case)
    if not tds:
        raise RuntimeError(f"no written time in {case}")
    # max liquid fraction over the written times: the fused zone
    fmax = np.zeros(g.cells())
    f_last = np.zeros(g.cells())         # the last time's: where the pool is at the end
    for d in tds:
        p = os.path.join(case, d, "liquidFraction")
        if os.path.exists(p):
            f = read_field(d, "liquidFraction")
            if f.size > 1:
                fmax = np.maximum(fmax, f)
                f_last = f if d == tds[-1] else f_last
    fmax = fmax.reshape(nz, ny, nx)
    last = tds[-1]
    alpha = read_field(last, "alpha.metal").reshape(nz, ny, nx)
    dz = np.diff(g.zf)
    # metal column height above the original surface, h(x, y) = sum alpha dz - substrate
    h = np.einsum("kji,k->ji", alpha, dz) - PROCESS["substrate_thickness"]
    sig = 0.25 * PROCESS["spot_diameter"] * meta.get("powder_spot", 1.0)
    liquid_last = f_last.reshape(nz, ny, nx).max(axis=(0, 1))
    cols, section_kind = measured_section(xc, liquid_last, g.x_start, g.x_end, sig, meta["dx"])
    ksurf = np.searchsorted(zc, 0.0) - 1          # top row of substrate cells (centre below z = 0)
    rows = []
    for i in cols:
        prof = h[:, i]
        height = float(np.max(prof))
        # fused width at the plate surface: liquid fraction 0.5 crossing along y in the top row
        fr = fmax[ksurf, :, i]
        width = 2.0 * profiles.first_fall(yc, fr, 0.5)
        # penetration: liquid fraction 0.5 crossing along -z in the column at y = 0
        col = fmax[:ksurf + 1, 0, i][::-1]          # from the surface down
        depth = profiles.first_fall(-zc[:ksurf + 1][::-1], col, 0.5)
        # the deposit's cross-section (net metal volume per length, exact on any mesh) and its
        # width where its top falls to 10 % of its height (the outer edge of the bead's run)
        area = 2.0 * float(np.dot(prof, np.diff(g.yf)))
        top_width = 2.0 * profiles.level_span(prof, yc, 0.1 * height)[1] if height > 0 else 0.0
        rows.append((xc[i], width, height, depth, area, top_width))
    rows = np.array(rows)
    have_ledger = os.path.exists(os.path.join(case, "postProcessing", "particleLedger", "ledger.csv"))
    if have_ledger:
        # powder (particle ledger): fed = drawn by fix powder/insert, deposited = molten into the
        # continuum, lost = left the mesh (bounced off solid metal), aloft = still grains at the end
        led = ledger(case)
        fed = float(np.sum(led["mass_feed"]))
        dep_c = np.cumsum(led["mass_exchange"])
        lost_c = np.cumsum(led["mass_lost"])
        melted, lost = float(dep_c[-1]), float(lost_c[-1])
        # the held dummy grain is no powder: not fed, never deposited or lost
        dummy = RHO_POWDER * math.pi / 6 * DUMMY_D ** 3
        aloft, pending = float(led["mass_particles"][-1]) - dummy, float(led["mass_pending"][-1])
        eff = melted / (melted + lost) if melted + lost > 0 else float("nan")
        # the same over the second half of the run (closer to the steady pool)
        j = int(np.searchsorted(led["time"], 0.5 * float(led["time"][-1])))
        dd, dl = melted - float(dep_c[j]), lost - float(lost_c[j])
        eff2 = dd / (dd + dl) if dd + dl > 0 else float("nan")
        feed = np.loadtxt(os.path.join(case, "feed.dat"), comments="#", ndmin=2)   # step t np nins mins mpend mmelt
        cont0, cont1 = float(led["mass_continuum"][0]), float(led["mass_continuum"][-1])
    summary = {
        "bead_width_mm": 1e3 * float(np.mean(rows[:, 1])),
        "bead_height_mm": 1e3 * float(np.mean(rows[:, 2])),
        "penetration_mm": 1e3 * float(np.mean(rows[:, 3])),
        "bead_width_spread_mm": 1e3 * float(np.ptp(rows[:, 1])),
        "bead_height_spread_mm": 1e3 * float(np.ptp(rows[:, 2])),
        "penetration_spread_mm": 1e3 * float(np.ptp(rows[:, 3])),
        "bead_area_mm2": 1e6 * float(np.mean(rows[:, 4])),
        "deposit_top_width_mm": 1e3 * float(np.mean(rows[:, 5])),
        "section_x_mm": [1e3 * float(rows[0, 0]), 1e3 * float(rows[-1, 0])],
        "section": section_kind,
        # the bead's height along the track at the end (largest over y), from the start to 1 mm
        # past the end: a rising profile at the section says the bead is not yet steady there
        "height_profile_mm": [[1e3 * float(xc[i]), 1e3 * float(np.max(h[:, i]))] for i in range(nx)
                              if g.x_start <= xc[i] <= g.x_end + 1e-3],
        "time_s": float(tds[-1]) if not have_ledger else float(led["time"][-1]),
        "cells": int(g.cells()), "dx_mm": 1e3 * meta["dx"], "track_mm": 1e3 * meta["track"],
        "refine_levels": levels, "base_cells": int(base.cells()), "most_cells": fc.most_cells(case, base.cells()),
        "cpu_seconds": fc.execution_time(case),
        "absorptivity": meta["absorptivity"], "powder_spot_over_laser_spot": meta.get("powder_spot", 1.0),
        "wall_seconds": meta.get("wall_seconds"),
    }
    if not have_ledger:
        summary.update(geometric_capture(g, meta, tds, read_field))
        # the bead a parabolic cross-section of the fused width would have with that capture:
        # area = eta feed / (rho v), height = 1.5 area / width
        area = summary["geometric_capture_pct"] / 100 * PROCESS["feed"] / (METAL["rho"] * PROCESS["speed"])
        if summary["bead_width_mm"] > 0:
            summary["implied_bead_height_mm"] = 1.5 * area / (summary["bead_width_mm"] * 1e-3) * 1e3
    if have_ledger:
        summary.update({
            "deposition_efficiency_pct": 100.0 * eff,
            "deposition_efficiency_second_half_pct": 100.0 * eff2,
            "powder_fed_kg": fed, "powder_deposited_kg": melted, "powder_lost_kg": lost,
            "powder_aloft_kg": aloft, "powder_pending_kg": pending, "continuum_metal_gain_kg": cont1 - cont0,
            "powder_melted_lammps_kg": lammps_molten(case),
            "particles_inserted": int(feed[-1, 3]), "fluid_steps": int(len(led)),
        })
        for c in ("mass", "enthalpy"):
            for kind in ("continuum", "system"):
                k = f"{c}_{kind}_error"
                if len(led) > 1:
                    summary[f"worst_step_{k}"] = float(np.max(np.abs(led[k][1:])))
            summary[f"cumulative_{c}_system_error"] = float(led[f"{c}_cumulative_system_error"][-1])
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(summary, f, indent=1)
    if not quiet:
        print_table(summary)
    return summary


def measured_section(xc, liquid_last, x_start, x_end, sig, dx, width=0.5e-3):
    """Cell columns of the measured section and which rule chose them. 'solid': where the
    experiment cuts its bead, the 0.5 mm (at least two cells) of solid bead just behind the
    pool's tail at the end, when it lies at least 2.8 sigma of the powder spot past the start
    (the spot passed it, the deposit froze). 'pool': tracks too short to leave such a bead (CI,
    the 3 mm full track) keep 1.25-1.75 mm behind the final beam position (2-2.8 sigma, sigma =
    w/2): >= 97.7 % of the powder that section gets has arrived, the widest pool has passed."""
    on_track = (xc >= x_start) & (xc <= x_end)
    molten = np.where(on_track & (liquid_last > 0.0))[0]
    if len(molten):
        tail = xc[molten[0]] - 0.5 * dx                  # the pool's trailing face
        w = max(width, 2.0 * dx)
        cols = np.where((xc >= tail - w) & (xc < tail))[0]
        if len(cols) and xc[cols[0]] - 0.5 * dx >= x_start + 2.8 * sig:
            return cols, "solid"
    cols = np.where((xc >= x_end - 2.8 * sig) & (xc <= x_end - 2.0 * sig))[0]
    if len(cols) == 0:           # coarse meshes: the cell column nearest to 2.4 sigma behind
        cols = np.array([int(np.argmin(np.abs(xc - (x_end - 2.4 * sig))))])
    return cols, "pool"


def geometric_capture(g, meta, tds, read_field, n_last=3):
    """Bare track (no powder): the share of the powder spot (its rings, each uniform) that falls
    on the pool surface (top metal cells with liquid fraction >= 0.5, the pool at the surface),
    averaged over the last written times: Codina2019's 'geometrical matching of the powder
    stream and the meltpool surface', an estimate of the deposition efficiency without the
    coupled grains. Also the bead height a parabolic bead of the fused width would get from it."""
    xc, yc, zc = g.centres()
    nx, ny, nz = g.n
    ksurf = np.searchsorted(zc, 0.0) - 1
    w = 0.5 * PROCESS["spot_diameter"] * meta.get("powder_spot", 1.0)
    radii, frac = powder_rings(w)
    dxs, dys = np.diff(g.xf), np.diff(g.yf)
    # sub-sample each surface cell (8 x 8 points) against the rings
    sub = (np.arange(8) + 0.5) / 8
    out = []
    for d in tds[-n_last:]:
        fl = read_field(d, "liquidFraction").reshape(nz, ny, nx)[ksurf]
        xbeam = g.x_start + PROCESS["speed"] * float(d)
        got = 0.0
        for j in range(ny):
            for i in range(nx):
                if fl[j, i] < 0.5:
                    continue
                px = g.xf[i] + sub * dxs[i] - xbeam
                py = g.yf[j] + sub * dys[j]
                r = np.hypot(px[:, None], py[None, :]).ravel()
                k = np.searchsorted(radii, r, side="right") - 1
                ok = (k >= 0) & (k < len(frac))
                dens = frac[k[ok]] / (0.5 * np.pi * (radii[k[ok] + 1] ** 2 - radii[k[ok]] ** 2))  # half rings
                got += np.sum(dens) * dxs[i] * dys[j] / sub.size ** 2
        out.append(got)
    eta = float(np.mean(out))
    return {"geometric_capture_pct": 100.0 * eta, "geometric_capture_spread_pct": 100.0 * float(np.ptp(out))}


def lammps_molten(case):
    """Molten mass fix powder/melt reports (v_mmelt) on the last thermo line of log.lammps, i.e.
    at the end of the last coupled step."""
    val, cols = float("nan"), None
    for line in open(os.path.join(case, "log.lammps")):
        w = line.split()
        if w[:2] == ["Step", "Time"]:
            cols = w
        elif cols and len(w) == len(cols) and w[0].isdigit():
            try:
                val = float(w[cols.index("v_mmelt")])
            except ValueError:
                pass
    return val


def ledger(case):
    path = os.path.join(case, "postProcessing", "particleLedger", "ledger.csv")
    d = np.genfromtxt(path, delimiter=",", names=True)
    return d.reshape(1) if d.ndim == 0 else d


def print_table(s):
    print(f"lmd-track: {s['cells']} cells ({s['dx_mm']:g} mm), track {s['track_mm']:g} mm, t = {s['time_s']:.3g} s, "
          f"{s.get('fluid_steps', '-')} steps, section x = {s['section_x_mm'][0]:.2f}-{s['section_x_mm'][1]:.2f} mm "
          f"({'solid bead behind the pool' if s.get('section') == 'solid' else 'behind the final beam, in the pool'})")
    print(f"{'quantity':32s} {'measured':>9s} {'experiment':>10s} {'error':>8s} {'thesis sim':>10s}")
    for key, ref in (("bead_width_mm", "width_mm"), ("bead_height_mm", "height_mm"),
                     ("penetration_mm", "penetration_mm"), ("deposition_efficiency_pct", "efficiency_pct")):
        if key not in s:
            continue
        m, e, t = s[key], EXPERIMENT[ref], THESIS_SIM[ref]
        print(f"{key:32s} {m:9.3f} {e:10.3f} {m - e:+8.3f} {t:10.3f}")
    if "bead_area_mm2" in s and "powder_fed_kg" in s:
        e_area = 2.0 / 3.0 * EXPERIMENT["width_mm"] * EXPERIMENT["height_mm"]
        print(f"bead cross-section {s['bead_area_mm2']:.3f} mm2 (experiment's width and height as a parabola: "
              f"{e_area:.3f} mm2); the deposit's top falls to 10 % of its height at "
              f"{s['deposit_top_width_mm']:.2f} mm width")
    if "geometric_capture_pct" in s:
        print(f"bare track (no powder): share of the powder spot on the pool surface "
              f"{s['geometric_capture_pct']:.1f} % "
              f"(spread {s['geometric_capture_spread_pct']:.1f}) -- the geometric estimate of the deposition "
              "efficiency; "
              f"implied parabolic bead height {s.get('implied_bead_height_mm', float('nan')):.3f} mm")
    if "powder_fed_kg" not in s:
        return
    print(f"powder fed {s['powder_fed_kg']:.4g} kg, deposited {s['powder_deposited_kg']:.4g} kg, "
          f"lost {s['powder_lost_kg']:.4g} kg, aloft {s['powder_aloft_kg']:.4g} kg, pending "
          f"{s['powder_pending_kg']:.3g} kg; continuum metal gain {s['continuum_metal_gain_kg']:.4g} kg")
    print(f"efficiency over the second half {s['deposition_efficiency_second_half_pct']:.1f} %; worst per-step "
          f"errors: continuum mass {s.get('worst_step_mass_continuum_error', 0):.2g}, energy "
          f"{s.get('worst_step_enthalpy_continuum_error', 0):.2g}; system mass "
          f"{s.get('worst_step_mass_system_error', 0):.2g}, energy {s.get('worst_step_enthalpy_system_error', 0):.2g}")


# ---------------------------------------------------------------------------------------------
def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    v = ap.add_mutually_exclusive_group()
    v.add_argument("--ci", action="store_const", dest="variant", const="ci")
    v.add_argument("--full", action="store_const", dest="variant", const="full")
    ap.add_argument("--dx", type=float, help="fine cell size [mm]")
    ap.add_argument("--track", type=float, help="track length [mm]")
    ap.add_argument("--write", type=float, help="write interval [s]")
    laser.add_absorptivity_arguments(ap, VARIANTS["ci"]["absorptivity"])
    ap.add_argument("--powder-spot", type=float, default=1.0,
                    help="powder spot 1/e^2 diameter / laser spot diameter (default 1: coaxial focus)")
    ap.add_argument("--powder-speed", type=float, default=1.0, help="grain speed at the nozzle exit [m/s]")
    ap.add_argument("--cells-per-step", type=float, default=0.25,
                    help="largest grain travel per fluid step in fine cells (sets maxDeltaT)")
    ap.add_argument("--estar", type=float, default=5.5e7, help="grain contact modulus E* [Pa]")
    ap.add_argument("--restitution", type=float, default=0.6)
    ap.add_argument("--distribution", default="centre",
                    help="particle->cell model (default centre: grains are smaller than the cells)")
    ap.add_argument("--marangoni", dest="marangoni", action="store_true", default=True,
                    help="Marangoni force on, density-scaled (the default)")
    ap.add_argument("--no-marangoni", dest="marangoni", action="store_false",
                    help="Marangoni force off (the conduction-shaped pool of the earlier releases)")
    ap.add_argument("--marangoni-scaling", choices=["density", "none"], default="density",
                    help="density: the force on the metal side of the interface (default); none: spread over "
                    "the interface cells, which also drives the argon over the pool")
    ap.add_argument("--laser-shadow", action="store_true",
                    help="grains in the beam absorb and shadow (off by default: negligible in LMD, thesis 4.1)")
    ap.add_argument("--cold-start", action="store_true",
                    help="plate at 300 K (default: the quasi-steady Rosenthal field of the moving source)")
    ap.add_argument("--no-particles", dest="particles", action="store_false",
                    help="laser only (no powder): the bare melt track")
    ap.add_argument("--log-every", type=float, default=2e-3, help="powder log interval [s]")
    ap.add_argument("--refine", type=int, default=0, metavar="L",
                    help="adaptive refinement: base cells 2^L x --dx, refined to --dx in the pool, under the beam "
                    "and its path ahead and around the grains near them (refinement{})")
    ap.add_argument("--refine-interval", type=int, default=1, metavar="N", help="fluid steps between mesh updates")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args(argv)
    laser.check_absorptivity_arguments(ap, a, VARIANTS["ci"]["absorptivity"])
    a.case = os.path.abspath(a.case)
    if a.action in ("build", "all"):
        var = dict(VARIANTS[a.variant or "ci"])
        for k in ("dx", "track"):
            if getattr(a, k) is not None:
                var[k] = getattr(a, k) * 1e-3
        for k in ("write", "absorptivity"):
            if getattr(a, k) is not None:
                var[k] = getattr(a, k)
        for k, val in var.items():
            setattr(a, k, val)
        a.variant = a.variant or "ci"
        build(a)
    if a.action in ("run", "all"):
        run(a.case, a.np)
    if a.action in ("analyse", "all"):
        analyse(a.case)
    return 0


SCENE = Scene(name="lmd-track", kind="coupled",
              title="Laser metal deposition, single pass (Codina2019 4.1, tables 4.1 / 4.2)",
              ci_time='2 min 5 s wall', full_time='14 min (medium: 1/3 mm cells, 3 mm of track)',
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]),
              summary=lambda case: analyse(case, quiet=True))


if __name__ == "__main__":
    sys.exit(main())
