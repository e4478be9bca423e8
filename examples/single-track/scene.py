#!/usr/bin/env python3
"""Bare-plate laser single tracks on IN625: the NIST AM Bench 2018 series AMB2018-02 (Lane et al.
2020), continuum only (meltdemFoam, no particles).

    scene.py build CASE [--ci | --full] [--track-case AMMT-A|..|CBM-C] [--dx UM] [--refine L] [--track MM]
                   [--absorptivity ETA] [--dabsorptivity-dt K [--absorptivity-min A] [--absorptivity-max B]]
                   [--dsigma-dt D] [--no-marangoni]
                   [--no-surface-tension] [--no-recoil]
    scene.py run CASE [--np N]
    scene.py analyse CASE
    scene.py all CASE [build options] [--np N]

A Gaussian beam (the measured D4sigma spot as its 1/e^2 diameter) scans a bare IN625 plate under
argon along x; half model (the plane z = 0 through the beam axis is a symmetryPlane, the power
halved). Surface tension, Marangoni (density-scaled), Darcy, evaporation and recoil are on by
default. The fused zone is the metal whose temperature reached the middle of the melting range at a
written time (liquid fraction 1/2, interpolated between cell centres); its width
(at the plate surface) and depth (below it) are averaged over the cross sections of the steady
part of the track and compared with the measured mean and scatter. See README.md.
"""
import argparse
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

paths.set_tool_environment()

# AMB2018-02 (Lane et al. 2020): bare IN625 plates, two machines. AMMT: NIST's testbed, 170 um
# D4sigma spot, the applied powers (commanded 150 / 195 W, README "Data"); CBM: the commercial build
# machine, 100 um D4sigma spot. width / depth: the class means of table 4 [um]; *_sd: the standard
# deviation between the tracks' means (AMMT: NIST's cross-section results, table 2; CBM: of table 3).
TRACKS = {
    "AMMT-A": dict(power=137.9, speed=0.4, spot=170e-6, width=147.9, width_sd=3.7, depth=42.5, depth_sd=1.7,
                   tracks=3, mode="conduction"),
    "AMMT-B": dict(power=179.2, speed=0.8, spot=170e-6, width=123.5, width_sd=6.5, depth=36.0, depth_sd=1.9,
                   tracks=3, mode="conduction"),
    "AMMT-C": dict(power=179.2, speed=1.2, spot=170e-6, width=106.0, width_sd=1.4, depth=29.6, depth_sd=0.6,
                   tracks=4, mode="conduction"),
    "CBM-A": dict(power=150.0, speed=0.4, spot=100e-6, width=171.0, width_sd=2.5, depth=151.0, depth_sd=20.5,
                  tracks=3, mode="keyhole"),
    "CBM-B": dict(power=195.0, speed=0.8, spot=100e-6, width=133.0, width_sd=1.7, depth=91.0, depth_sd=1.8,
                  tracks=3, mode="transition"),
    "CBM-C": dict(power=195.0, speed=1.2, spot=100e-6, width=100.0, width_sd=1.8, depth=60.0, depth_sd=0.5,
                  tracks=4, mode="transition"),
}

# IN625 (README "Material"): solidus / liquidus 1563 / 1623 K (Pawel & Williams 1985, the fusion
# boundary convention of Lane et al.); rho, L, mu, absorptivity as ORNL's Myna material file; cp and k
# its linear solid cp(T) and k(T) averaged over 300 K..solidus (cp: the mean that gives the
# sensible enthalpy to the solidus exactly, k: the Kirchhoff mean); surface tension 1.8 N/m, dsigma/dT
# as AdditiveFOAM's IN625
METAL = dict(rho=8440.0, mu=7.0e-3, cp=566.0, k=19.8, L=2.9e5, Tsolidus=1563.0, Tliquidus=1623.0,
             sigma0=1.8, dSigmadT=-1.1e-4, sigmaMin=0.2)
METAL["Tsigma0"] = METAL["Tliquidus"]
ARGON = dict(rho=1.6, mu=2.2e-5, cp=520.0, k=0.018)
# vapour as nickel (IN625 is 58-63 % Ni): boiling point, heat and molar mass of evaporation
VAPOUR = dict(Tboil=3186.0, hv=6.38e6, M=58.69e-3)
ABSORPTIVITY = 0.36
T0 = 300.0

VARIANTS = {
    # finest cell, refinement levels, track length, substrate depth, gas height, beam start (x), writes
    "ci": dict(dx=10e-6, refine=1, track=0.6e-3, sub=280e-6, gas=40e-6, x0=120e-6, write=10e-6),
    "full": dict(dx=5e-6, refine=2, track=1.0e-3, sub=320e-6, gas=40e-6, x0=120e-6, write=5e-6),
}


def cells(v, h):
    return tuple(int(round(v[k] / h)) for k in ("lx", "ly", "lz"))


def geometry(v, spot):
    """The box of the case (y = 0 is the plate surface, z = 0 the symmetry plane) rounded to whole
    base cells: the track and one spot diameter beyond its end along x, 1.5 spot diameters across."""
    base = v["dx"] * 2 ** v["refine"]
    g = dict(v, base=base)
    g["sub"] = base * math.ceil(v["sub"] / base - 1e-9)
    g["gas"] = base * math.ceil(v["gas"] / base - 1e-9)
    g["ly"] = g["sub"] + g["gas"]
    g["lx"] = base * math.ceil((v["x0"] + v["track"] + 1.5 * spot) / base - 1e-9)
    g["lz"] = base * math.ceil(max(240e-6, 1.5 * spot) / base - 1e-9)
    return g


def evaporation_dict():
    """Evaporation of the melt as nickel vapour: C_T = h_v M / R; what leaves carries h_v, the latent
    heat of melting and the sensible heat above T0 (h(T) = cp (T - T0) with h_v + L as the constant)."""
    R = 8.314462618
    hv, cp = VAPOUR["hv"], METAL["cp"]
    return (f"evaporation {{ pAmbient 1e5; CT {hv * VAPOUR['M'] / R!r}; Tboil {VAPOUR['Tboil']!r}; "
            f"hv {hv + METAL['L']!r}; cp {cp!r}; Th0 {T0!r}; CM {VAPOUR['M'] / (2 * math.pi * R)!r}; }}\n")


def refinement_dict(g, track):
    """The finest cells in the pool and the metal within 300 K of melting, under the beam (1.2
    radii, one radius deep) and where it will be over the next half radius of travel."""
    r = 0.5 * track["spot"]
    ahead = 0.5 * r / track["speed"]
    return fc.refinement_dict(g["refine"], g["refine_interval"],
                              [("meltPool", "belowSolidus 300;"),
                               ("laser", f"radii 1.2; depth {r!r}; lookAhead {g['refine_interval']}; "
                                         f"lookAheadTime {ahead!r};")])


def build(a):
    case = a.case
    if os.path.exists(case):
        if set(os.listdir(case)) - {".meltdem.lock"} and not os.path.exists(os.path.join(case, "scene.json")):
            raise SystemExit(f"single-track: {case} exists and is not a scene case; not overwriting it")
        shutil.rmtree(case)
    os.makedirs(case)
    v = dict(VARIANTS[a.variant])
    for k in ("dx", "refine", "track"):
        if getattr(a, k) is not None:
            v[k] = getattr(a, k)
    v["refine_interval"] = a.refine_interval
    track = TRACKS[a.track_case]
    g = geometry(v, track["spot"])
    eta = laser.absorptivity(a, ABSORPTIVITY)
    n = cells(g, g["base"])
    cc.box_mesh(case, (0.0, -g["sub"], 0.0), (g["lx"], g["gas"], g["lz"]), n,
                {"symmetry": ("symmetryPlane", ["zmin"]), "walls": ("wall", ["xmin", "xmax", "zmax"]),
                 "bottom": ("wall", ["ymin"]), "atmosphere": ("patch", ["ymax"])})
    yc = -g["sub"] + (np.arange(n[1]) + 0.5) * g["base"]
    alpha = np.broadcast_to((yc < 0.0).astype(float)[None, :, None], (n[2], n[1], n[0])).ravel()
    sym = "type symmetryPlane;"
    cc.uniform_field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha,
                     {"symmetry": sym, "walls": "type zeroGradient;", "bottom": "type zeroGradient;",
                      "atmosphere": "type inletOutlet; inletValue uniform 0; value uniform 0;"})
    cc.uniform_field(case, "T", "[0 0 0 1 0 0 0]", T0,
                     {"symmetry": sym, "walls": "type zeroGradient;",
                      "bottom": f"type fixedValue; value uniform {T0!r};",
                      "atmosphere": f"type inletOutlet; inletValue uniform {T0!r}; value uniform {T0!r};"})
    cc.uniform_field(case, "U", "[0 1 -1 0 0 0 0]", (0.0, 0.0, 0.0),
                     {"symmetry": sym, "walls": "type noSlip;", "bottom": "type noSlip;",
                      "atmosphere": "type pressureInletOutletVelocity; value uniform (0 0 0);"}, vector=True)
    cc.uniform_field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", 0.0,
                     {"symmetry": sym, "walls": "type fixedFluxPressure; value uniform 0;",
                      "bottom": "type fixedFluxPressure; value uniform 0;",
                      "atmosphere": "type totalPressure; p0 uniform 0; value uniform 0;"})
    fc.transport(case, METAL["rho"], METAL["mu"] / METAL["rho"], ARGON["rho"], ARGON["mu"] / ARGON["rho"],
                 METAL["sigma0"])
    fc.gravity(case, (0.0, -9.81, 0.0))
    end = (g["track"]) / track["speed"]
    # the beam moves at most a quarter of a finest cell per step; with surface tension also the
    # capillary limit (the solver keeps the step under it itself, maxCapillaryNo): here it bounds the
    # first step and the lookahead of the refinement
    rho_avg = 0.5 * (METAL["rho"] + ARGON["rho"])
    max_dt = 0.25 * g["dx"] / track["speed"]
    if a.surface_tension:
        max_dt = min(max_dt, math.sqrt(rho_avg * g["dx"] ** 3 / (2 * math.pi * METAL["sigma0"])))
    # the conservation ledger every step; on a refining run each write's cell centres and volumes
    functions = "    balance { type meltdemBalance; }\n"
    if g["refine"]:
        functions += fc.CELL_GEOMETRY_ENTRIES
    fc.control_dict(case, "meltdemFoam", end, 0.1 * max_dt, g["write"], max_co=0.3, max_alpha_co=0.3,
                    max_dt=max_dt, extra="functions\n{\n" + functions + "}\n")
    fc.fv_schemes(case)
    fc.fv_solution(case, n_correctors=3, alpha_tolerance=1e-14)
    y_beam = 0.5 * g["base"]
    physics = dict(energy="on", darcy="on", laser="on",
                   surfaceTension="on" if a.surface_tension else "off",
                   marangoni="on" if a.marangoni else "off",
                   recoil="on" if a.recoil else "off", evaporation="on" if a.recoil else "off")
    surface = {k: METAL[k] for k in ("sigma0", "dSigmadT", "Tsigma0", "sigmaMin")}
    if a.dsigma_dt is not None:
        surface["dSigmadT"] = a.dsigma_dt
    surface.update(nSmooth=2, **({"marangoniDensityScaled": 1} if a.marangoni else {}))
    extra = f"""metal {{ cp {METAL['cp']!r}; k {METAL['k']!r}; L {METAL['L']!r}; Tsolidus {METAL['Tsolidus']!r}; Tliquidus {METAL['Tliquidus']!r}; }}
gas {{ cp {ARGON['cp']!r}; k {ARGON['k']!r}; }}
darcy {{ C 1e10; b 1e-3; }}
energyControls {{ nCorrectors 20; tolerance 1e-10; }}
laser
{{
    power           {0.5 * track['power']!r};   // half model: P/2
{laser.absorptivity_entries(a, ABSORPTIVITY, METAL['Tliquidus'])}    radius          {0.5 * track['spot']!r};   // 1/e^2 radius = D4sigma / 2
    direction       (0 -1 0);
    position        ({g['x0']!r} {y_beam!r} 0);
    velocity        ({track['speed']!r} 0 0);
    tStart          0;
    tStop           {end!r};
}}
{evaporation_dict() if a.recoil else ""}{refinement_dict(g, track) if g['refine'] else ""}"""  # noqa: E501
    fc.meltdem_properties(case, physics=physics, surface=surface, extra=extra)
    keep = ("dx", "refine", "refine_interval", "track", "lx", "ly", "lz", "sub", "gas", "x0", "base", "write")
    meta = dict(scene="single-track", variant=a.variant, track_case=a.track_case,
                **laser.absorptivity_meta(a, ABSORPTIVITY), physics=physics, dsigma_dt=surface["dSigmadT"], end=end,
                max_dt=max_dt, **{k: g[k] for k in keep})
    with open(os.path.join(case, "scene.json"), "w") as f:
        json.dump(meta, f, indent=1)
    refined = f" refined to {g['dx'] * 1e6:g} um" if g["refine"] else ""
    print(f"single-track: case {case}: AMB2018-02 {a.track_case} ({track['power']:g} W, {track['speed']:g} m/s, "
          f"{track['spot'] * 1e6:g} um), {n[0]}x{n[1]}x{n[2]} base cells of {g['base'] * 1e6:g} um"
          f"{refined}, "
          f"track {g['track'] * 1e3:g} mm = {end * 1e3:.3g} ms, absorptivity {eta:g}")
    return case


def run(case, np_=1):
    return fc.run_scene_case(case, np_, "single-track")


def peak_metal_temperature(case, meta):
    """Max over the written times of T where the cell holds metal (alpha >= 1/2), on the finest
    cells' lattice (nz, ny, nx): the fused zone is where it reached the middle of the melting range."""
    h = meta["dx"]
    times = [d for d in fc.time_dirs(case) if float(d) > 0 and os.path.exists(os.path.join(case, d, "T"))]
    return fc.peak_metal_temperature(case, times, cells(meta, h), h, (0.0, -meta["sub"], 0.0), T0), times


def analyse(case, quiet=False):
    meta = json.load(open(os.path.join(case, "scene.json")))
    track = TRACKS[meta["track_case"]]
    h = meta["dx"]
    nx, ny, nz = cells(meta, h)
    tmax, times = peak_metal_temperature(case, meta)
    if not times:
        raise RuntimeError(f"single-track: no written time in {case}")
    t_fused = 0.5 * (METAL["Tsolidus"] + METAL["Tliquidus"])
    xc = (np.arange(nx) + 0.5) * h
    yc = -meta["sub"] + (np.arange(ny) + 0.5) * h
    zc = (np.arange(nz) + 0.5) * h
    # steady part: the sections from 0.4 of the track (the pool has built up) to one
    # spot diameter before its end (the pool there has not yet passed)
    x_end = meta["x0"] + track["speed"] * float(times[-1])
    xa = meta["x0"] + 0.4 * meta["track"]
    xb = min(x_end, meta["x0"] + meta["track"]) - track["spot"]
    cols = np.where((xc >= xa) & (xc <= xb))[0]
    if len(cols) == 0:
        raise RuntimeError(f"single-track: no steady section between x = {xa * 1e3:.3f} and {xb * 1e3:.3f} mm")
    jtop = int(np.searchsorted(yc, 0.0)) - 1          # top row of the plate (centre below y = 0)
    widths, depths = [], []
    for i in cols:
        # width at the plate surface y = 0: the fused half widths of the top two rows of the plate
        # (centres h/2 and 3h/2 below it) extrapolated linearly; half model: 2 x the half width
        w1, w2 = (profiles.first_fall(zc, tmax[:, j, i], t_fused) for j in (jtop, jtop - 1))
        widths.append(2.0 * (w1 + 0.5 * (w1 - w2) if w2 > 0 else w1))
        col = tmax[0, :jtop + 1, i][::-1]                                         # from the surface down
        depths.append(profiles.first_fall(-yc[:jtop + 1][::-1], col, t_fused))
    widths, depths = np.array(widths), np.array(depths)
    cpu = fc.execution_time(case)
    s = dict(track_case=meta["track_case"], mode=track["mode"], power_W=track["power"], speed_m_per_s=track["speed"],
             spot_um=track["spot"] * 1e6, absorptivity=meta["absorptivity"], physics=meta["physics"],
             dsigma_dt=meta.get("dsigma_dt"),
             dx_um=h * 1e6, refine_levels=meta["refine"], track_mm=meta["track"] * 1e3,
             time_s=float(times[-1]), end_s=meta["end"], completed=float(times[-1]) >= meta["end"] * (1 - 1e-6),
             sections=len(cols), section_x_mm=[float(xc[cols[0]] * 1e3), float(xc[cols[-1]] * 1e3)],
             width_um=float(widths.mean() * 1e6), width_spread_um=float(np.ptp(widths) * 1e6),
             depth_um=float(depths.mean() * 1e6), depth_spread_um=float(np.ptp(depths) * 1e6),
             measured_width_um=track["width"], measured_width_sd_um=track["width_sd"],
             measured_depth_um=track["depth"], measured_depth_sd_um=track["depth_sd"],
             cpu_seconds=cpu, wall_seconds=meta.get("wall_seconds"),
             most_cells=fc.most_cells(case, np.prod(cells(meta, meta["base"]))))
    s["fluid_steps"] = fc.fluid_steps(case)
    with open(os.path.join(case, "summary.json"), "w") as f:
        json.dump(s, f, indent=1)
    if not quiet:
        print_table(s)
    return s


def tolerance(measured, sd):
    """The measured scatter or 10 % of the mean, whichever is larger (issue 19)."""
    return max(sd or 0.0, 0.1 * measured)


def print_table(s):
    print(f"single-track AMB2018-02 {s['track_case']} ({s['mode']}): {s['power_W']:g} W, {s['speed_m_per_s']:g} m/s, "
          f"{s['dx_um']:g} um cells, {s['sections']} sections x = {s['section_x_mm'][0]:.2f}-"
          f"{s['section_x_mm'][1]:.2f} mm, {s['fluid_steps']} steps, CPU {s['cpu_seconds']:.0f} s")
    print(f"{'quantity':12s} {'simulated':>10s} {'spread':>8s} {'measured':>9s} {'scatter':>8s} {'tolerance':>9s}")
    for q in ("width", "depth"):
        m, sd = s[f"measured_{q}_um"], s[f"measured_{q}_sd_um"]
        tol = tolerance(m, sd) if m else float("nan")
        print(f"{q + ' [um]':12s} {s[f'{q}_um']:10.1f} {s[f'{q}_spread_um']:8.1f} {m if m else float('nan'):9.1f} "
              f"{sd if sd else float('nan'):8.1f} {tol:9.1f}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("action", choices=["build", "run", "analyse", "all"])
    ap.add_argument("case")
    v = ap.add_mutually_exclusive_group()
    v.add_argument("--ci", action="store_const", dest="variant", const="ci")
    v.add_argument("--full", action="store_const", dest="variant", const="full")
    ap.add_argument("--track-case", choices=sorted(TRACKS), default="AMMT-B", help="AMB2018-02 track (default AMMT-B)")
    ap.add_argument("--dx", type=lambda s: float(s) * 1e-6, help="finest cell size [um]")
    ap.add_argument("--refine", type=int, metavar="L", help="refinement levels: base cells 2^L x dx")
    ap.add_argument("--refine-interval", type=int, default=5, metavar="N", help="fluid steps between mesh updates")
    ap.add_argument("--track", type=lambda s: float(s) * 1e-3, help="track length [mm]")
    laser.add_absorptivity_arguments(ap, ABSORPTIVITY)
    ap.add_argument("--dsigma-dt", type=float, help=f"dsigma/dT [N/m/K] (default {METAL['dSigmadT']:g})")
    ap.add_argument("--no-marangoni", dest="marangoni", action="store_false")
    ap.add_argument("--no-surface-tension", dest="surface_tension", action="store_false")
    ap.add_argument("--no-recoil", dest="recoil", action="store_false", help="no evaporation and recoil pressure")
    ap.add_argument("--np", type=int, default=1)
    a = ap.parse_args(argv)
    a.case = os.path.abspath(a.case)
    a.variant = a.variant or "ci"
    laser.check_absorptivity_arguments(ap, a, ABSORPTIVITY)
    if a.marangoni and not a.surface_tension:
        ap.error("--no-surface-tension needs --no-marangoni (the Marangoni force is the surface tension's gradient)")
    if a.action in ("build", "all"):
        build(a)
    if a.action in ("run", "all"):
        run(a.case, a.np)
    if a.action in ("analyse", "all"):
        analyse(a.case)
    return 0


SCENE = Scene(name="single-track", kind="continuum",
              title="Bare-plate laser single tracks on IN625 (AM Bench 2018, AMB2018-02)",
              ci_time="1.5 min (AMMT-B)", full_time="29 min on 2 ranks (AMMT-B, 5 um, 1 mm track; measured)",
              build=lambda case, size: main(["build", case, f"--{size}"]),
              analyse=lambda case: main(["analyse", case]),
              summary=lambda case: analyse(case, quiet=True))


if __name__ == "__main__":
    sys.exit(main())
