#!/usr/bin/env python3
"""foam.laser_power: meltdem::laserHeatSource and evaporationModel evaluated by meltdemLaserCheck
on written alpha fields of a 3D box (no solver).

- absorbed power = eta P to 1e-6 (flat surface, off-centre beam partly outside the box; curved
  spherical cap; serial and np 2), integrated here from the written field (V = dx dy dz);
- the beam convention (1/e^2 radius, I0 = 2P/(pi r^2)): un-normalised hit fraction on a flat
  surface under the whole beam = 1;
- zero when off and when no metal is under the beam; moving linear and polyline paths; hatched
  tracks with the beam off while it returns (power by the lit part of each step);
- p_v(T_v) = 0.54 p_a (Fuchs2022 eq. 10), p_v and the eq. 18 flux at 2500 K by hand, heat-loss
  integral over a flat surface = flux * area;
- bad input stops with a FatalIOError naming the entry.
"""
import math
import os
import re
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_relative, check_absolute, report_info

SRC = paths.source_dir()

TEST = "foam.laser_power"
APP = paths.binary("meltdemLaserCheck")
LX, LY, LZ = 200e-6, 200e-6, 100e-6
NX, NY, NZ = 20, 20, 10
DX, DY, DZ = LX / NX, LY / NY, LZ / NZ
P, ETA, R = 200.0, 0.4, 30e-6
EVAP = dict(pAmbient=1e5, CT=5e4, Tboil=3000.0, hv=6.583e6, cp=965.0, Th0=663.731, CM=1.1095e-3,
            stickingCoefficient=1.0)

ix, iy, iz = np.meshgrid(np.arange(NX), np.arange(NY), np.arange(NZ), indexing="ij")
# blockMesh order: x fastest, then y, then z
XC = ((ix + 0.5) * DX).transpose(2, 1, 0).ravel()
YC = ((iy + 0.5) * DY).transpose(2, 1, 0).ravel()
ZC = ((iz + 0.5) * DZ).transpose(2, 1, 0).ravel()


def block_mesh(case):
    fc.dictionary(case, "system/blockMeshDict", f"""convertToMeters 1;
vertices ( (0 0 0) ({LX!r} 0 0) ({LX!r} {LY!r} 0) (0 {LY!r} 0)
           (0 0 {LZ!r}) ({LX!r} 0 {LZ!r}) ({LX!r} {LY!r} {LZ!r}) (0 {LY!r} {LZ!r}) );
blocks ( hex (0 1 2 3 4 5 6 7) ({NX} {NY} {NZ}) simpleGrading (1 1 1) );
edges ();
boundary ( walls {{ type wall; faces ((0 4 7 3) (1 2 6 5) (0 1 5 4) (3 7 6 2) (0 3 2 1) (4 5 6 7)); }} );
mergePatchPairs ();
""")
    fc.dictionary(case, "system/decomposeParDict", "numberOfSubdomains 2;\nmethod simple;\n"
                  "coeffs { n (2 1 1); }\n")


def make_case(root, name, alpha, laser, evap=None):
    case = os.path.join(root, name)
    os.makedirs(case)
    block_mesh(case)
    fc.control_dict(case, "meltdemLaserCheck", 1.0, 1e-6, 1.0)
    fc.fv_schemes(case)
    fc.fv_solution(case)
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha, {"walls": "type zeroGradient;"})
    body = "laser\n{\n" + "".join(f"    {k} {v};\n" for k, v in laser.items()) + "}\n"
    ev = dict(EVAP)
    ev.update(evap or {})
    body += "evaporation\n{\n" + "".join(f"    {k} {v!r};\n" for k, v in ev.items()) + "}\n"
    fc.dictionary(case, "constant/meltdemProperties", body)
    fc.run(["blockMesh"], case, "log.blockMesh")
    return case


def vec(p):
    return "(" + " ".join(repr(float(c)) for c in p) + ")"


def check_app(case, args, np_=1, check=True):
    cmd = [APP] + args
    if np_ > 1:
        fc.run(["decomposePar", "-force"], case, "log.decomposePar")
        cmd = ["mpirun", "-np", str(np_), "--oversubscribe"] + cmd + ["-parallel"]
    env = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    rc = fc.run(cmd, case, "log.check", env=env, check=check)
    with open(os.path.join(case, "log.check")) as f:
        return rc, f.read()


def laser_lines(log):
    out = []
    for line in log.splitlines():
        if line.startswith("laser t "):
            t = line.split()
            d = {t[i]: t[i + 1:i + 4] if t[i] == "position" else t[i + 1]
                 for i in range(0, len(t) - 1) if t[i] in ("t", "on", "position", "absorbed",
                                                           "hitFraction", "integral", "min")}
            out.append(dict(t=float(d["t"]), on=int(d["on"]), pos=np.array([float(v) for v in d["position"]]),
                            absorbed=float(d["absorbed"]), hit=float(d["hitFraction"]),
                            integral=float(d["integral"]), qmin=float(d["min"])))
    return out


def field_integral(case, time):
    q = fc.read_internal(os.path.join(case, time, "laserHeatSource"))
    q = np.broadcast_to(q, XC.shape)
    return float(np.sum(q) * DX * DY * DZ), q


def sub_sampled_sphere(xc, yc, zc, rad, nsub=6):
    s = (np.arange(nsub) + 0.5) / nsub - 0.5
    a = np.zeros(XC.size)
    for sx in s:
        for sy in s:
            for sz in s:
                a += ((XC + sx * DX - xc) ** 2 + (YC + sy * DY - yc) ** 2 + (ZC + sz * DZ - zc) ** 2
                      <= rad * rad)
    return a / nsub ** 3


def main():
    if not os.path.exists(APP):
        print(f"missing {APP}")
        return 1
    ok = True
    root = tempfile.mkdtemp(prefix="laser_power_")
    z_top = LZ
    flat = (ZC < 50e-6).astype(float)  # interface on the face z = 50 um
    # tOn < 0: the step (-dt, 0] evaluated at t = 0 is lit (timeAveraged)
    base = dict(power=P, absorptivity=ETA, radius=R, direction="(0 0 -1)", tOn=-1)

    # 1. flat surface, centred beam: convention (hit fraction 1) and eta P
    lz = dict(base, position=vec((100e-6, 100e-6, z_top)))
    case = make_case(root, "flat_centre", flat, lz)
    _, log = check_app(case, ["-times", "(0)", "-write"])
    r = laser_lines(log)[0]
    ok &= check_relative(TEST, "flat, centred beam: hit fraction (1/e^2 radius, I0 = 2P/(pi r^2))",
                         r["hit"], 1.0, 1e-3)
    integ, q = field_integral(case, "0")
    ok &= check_relative(TEST, "flat, centred: integral of the written field [W]", integ, ETA * P, 1e-6)
    cx = float(np.sum(q * XC) / np.sum(q))
    ok &= check_absolute(TEST, "flat, centred: source centroid x [m]", cx, 100e-6, 1e-7)
    ok &= check_absolute(TEST, "flat, alphaWeighted (default): power in gas cells [W]",
                         float(np.sum(q[flat == 0])) * DX * DY * DZ, 0.0, 0.0)

    # tilted beam (45 deg): the footprint grows by 1/cos, the facing factor is cos: hit fraction 1
    ltilt = dict(base, position=vec((100e-6, 100e-6, 50e-6)), direction="(1 0 -1)")
    case = make_case(root, "flat_tilted", flat, ltilt)
    _, log = check_app(case, ["-times", "(0)", "-write"])
    r = laser_lines(log)[0]
    ok &= check_relative(TEST, "flat, beam tilted 45 deg: hit fraction", r["hit"], 1.0, 2e-3)
    integ, q = field_integral(case, "0")
    ok &= check_relative(TEST, "flat, beam tilted 45 deg: integral [W]", integ, ETA * P, 1e-6)
    # beam along -x onto the face of a metal block (x > 120 um): a vertical wall absorbs eta P
    wall = (XC > 120e-6).astype(float)
    case = make_case(root, "wall", wall, dict(base, position=vec((LX, 100e-6, 50e-6)), direction="(1 0 0)"))
    _, log = check_app(case, ["-times", "(0)"])
    rw = laser_lines(log)[0]
    ok &= check_relative(TEST, "beam (1 0 0) onto the x = 120 um face of a block: integral [W]",
                         rw["integral"], ETA * P, 1e-6)
    # beam pointing up from inside the metal: no surface faces it
    case = make_case(root, "upward", flat, dict(base, position=vec((100e-6, 100e-6, 0.0)), direction="(0 0 1)"))
    _, log = check_app(case, ["-times", "(0)"])
    ok &= check_absolute(TEST, "beam (0 0 1) from below the surface: absorbed [W]",
                         abs(laser_lines(log)[0]["integral"]), 0.0, 0.0)

    # 2. flat surface, beam off-centre and partly outside the box: still eta P (serial, np 2)
    loff = dict(base, position=vec((175e-6, 80e-6, z_top)), distribution="gradAlpha")
    case = make_case(root, "flat_off", flat, loff)
    _, log = check_app(case, ["-times", "(0)", "-write"])
    r = laser_lines(log)[0]
    integ, q = field_integral(case, "0")
    ok &= check_relative(TEST, "flat, off-centre beam partly off the box (gradAlpha): written-field integral [W]",
                         integ, ETA * P, 1e-6)
    ok &= check_relative(TEST, "flat, off-centre: model absorbedPower [W]", r["absorbed"], ETA * P, 1e-6)
    ok &= check_relative(TEST, "flat, off-centre, distribution gradAlpha: share in the gas cells",
                         float(np.sum(q[flat == 0]) / np.sum(q)), 0.5, 1e-9)
    expect_hit = 0.5 * (1 + math.erf(math.sqrt(2) * (LX - 175e-6) / R))  # x-truncated Gaussian
    # the same Gaussian summed here over the interface cells (x < 200 um: the box edge truncates it)
    xs = (np.arange(NX) + 0.5) * DX
    ys = (np.arange(NY) + 0.5) * DY
    g = np.exp(-2 * ((xs[:, None] - 175e-6) ** 2 + (ys[None, :] - 80e-6) ** 2) / R ** 2)
    hit_sum = 2 * float(np.sum(g)) * DX * DY / (math.pi * R ** 2)
    ok &= check_relative(TEST, "flat, off-centre: hit fraction vs the cell-centre Gaussian sum", r["hit"],
                         hit_sum, 1e-9)
    ok &= check_relative(TEST, "flat, off-centre: hit fraction vs erf truncation (midpoint rule, r = 3 dx)",
                         r["hit"], expect_hit, 5e-3)
    _, log2 = check_app(case, ["-times", "(0)"], np_=2)
    r2 = laser_lines(log2)[0]
    ok &= check_relative(TEST, "flat, off-centre, np 2: integral (gSum) [W]", r2["integral"], ETA * P, 1e-6)
    ok &= check_relative(TEST, "flat, off-centre, np 2 vs serial hit fraction", r2["hit"], r["hit"], 1e-9)

    # 3. curved surface: spherical cap (radius 80 um, centre 10 um below the box), beam off-centre
    cap = sub_sampled_sphere(100e-6, 100e-6, -10e-6, 80e-6)
    lcap = dict(base, position=vec((130e-6, 85e-6, z_top)))
    case = make_case(root, "cap", cap, lcap)
    _, log = check_app(case, ["-times", "(0)", "-write"])
    r = laser_lines(log)[0]
    integ, q = field_integral(case, "0")
    ok &= check_relative(TEST, "curved cap, off-centre beam: written-field integral [W]", integ, ETA * P, 1e-6)
    ok &= check_absolute(TEST, "curved cap: min source (>= 0) [W/m3]", min(0.0, float(q.min())), 0.0, 0.0)
    ok &= report_info(TEST, "curved cap: un-normalised hit fraction (info)", r["hit"])
    _, log2 = check_app(case, ["-times", "(0)"], np_=2)
    ok &= check_relative(TEST, "curved cap, np 2: integral (gSum) [W]", laser_lines(log2)[0]["integral"],
                         ETA * P, 1e-6)

    # 4. off / no metal: zero
    lonoff = dict(base, position=vec((100e-6, 100e-6, z_top)), tOn=1e-4, tOff=2e-4)
    case = make_case(root, "onoff", flat, lonoff)
    # steps (t - dt, t] with dt = 1e-6 (controlDict): power scaled by the lit part (timeAveraged)
    _, log = check_app(case, ["-times", "(0 1e-4 1.005e-4 1.5e-4 2e-4 2.005e-4 3e-4)"])
    rs = laser_lines(log)
    ok &= check_absolute(TEST, "steps ending at 0 and at tOn (dark): absorbed [W]",
                         abs(rs[0]["integral"]) + abs(rs[1]["integral"]), 0.0, 0.0)
    ok &= check_relative(TEST, "step half after tOn: absorbed [W] = eta P / 2", rs[2]["integral"], ETA * P / 2, 1e-6)
    ok &= check_relative(TEST, "between tOn and tOff: absorbed [W]", rs[3]["integral"], ETA * P, 1e-6)
    ok &= check_relative(TEST, "step ending at tOff: absorbed [W]", rs[4]["integral"], ETA * P, 1e-6)
    ok &= check_relative(TEST, "step half past tOff: absorbed [W] = eta P / 2", rs[5]["integral"], ETA * P / 2, 1e-6)
    ok &= check_absolute(TEST, "after tOff: absorbed [W]", abs(rs[6]["integral"]), 0.0, 0.0)
    case = make_case(root, "onoff_instant", flat, dict(lonoff, timeAveraged="no"))
    _, log = check_app(case, ["-times", "(1e-4 1.005e-4 2e-4)"])
    rs = laser_lines(log)
    ok &= check_relative(TEST, "timeAveraged no: at tOn eta P, at tOff 0 [W]",
                         rs[0]["integral"] + rs[1]["integral"] + rs[2]["integral"], 2 * ETA * P, 1e-6)
    case = make_case(root, "nometal", np.zeros(XC.size), dict(base, position=vec((100e-6, 100e-6, z_top))))
    _, log = check_app(case, ["-times", "(0)"])
    ok &= check_absolute(TEST, "no metal under the beam: absorbed [W]", abs(laser_lines(log)[0]["integral"]),
                         0.0, 0.0)
    # beam over a region with no metal surface (metal only in x < 50 um): misses
    side = ((XC < 50e-6) & (ZC < 50e-6)).astype(float)
    case = make_case(root, "miss", side, dict(base, position=vec((170e-6, 100e-6, z_top)), radius=10e-6))
    _, log = check_app(case, ["-times", "(0)"])
    ok &= check_absolute(TEST, "beam 12 radii away from the metal: absorbed [W]",
                         abs(laser_lines(log)[0]["integral"]), 0.0, 0.0)

    # grazing beam (metal slab x < 50 um, beam axis 30 um beyond its edge): exact eta P by default,
    # eta P * hitFraction with scaleByHitFraction
    graze = dict(base, position=vec((80e-6, 100e-6, z_top)))
    case = make_case(root, "graze", side, graze)
    _, log = check_app(case, ["-times", "(0)"])
    rg = laser_lines(log)[0]
    ok &= check_relative(TEST, "grazing beam, default: absorbed [W] = eta P", rg["integral"], ETA * P, 1e-6)
    case = make_case(root, "graze_scaled", side, dict(graze, scaleByHitFraction="yes"))
    _, log = check_app(case, ["-times", "(0)"])
    rs = laser_lines(log)[0]
    ok &= check_relative(TEST, f"grazing beam, scaleByHitFraction: absorbed [W] = eta P hitFraction "
                         f"({rg['hit']:.4g})", rs["integral"], ETA * P * rg["hit"], 1e-6)

    # 5. moving paths
    x0, v, ts, te = 50e-6, 0.5, 1e-5, 2.1e-4
    lmove = dict(base, position=vec((x0, 100e-6, z_top)), velocity="(0.5 0 0)", tStart=ts, tStop=te, tOff=1.0)
    case = make_case(root, "linear", flat, lmove)
    times = [0.0, 1e-4, 1.5e-4, 3e-4]
    _, log = check_app(case, ["-times", "(" + " ".join(map(repr, times)) + ")", "-write"])
    rs = laser_lines(log)
    err = max(abs(rr["pos"][0] - (x0 + v * min(max(t - ts, 0), te - ts))) for rr, t in zip(rs, times))
    ok &= check_absolute(TEST, "linear path: max |x(t) - x0 - v (t - tStart)| [m] (clamped at tStop)", err, 0.0, 1e-12)
    _, q = field_integral(case, "0.0001")
    cx = float(np.sum(q * XC) / np.sum(q))
    ok &= check_absolute(TEST, "linear path: source centroid at t = 1e-4 [m]", cx, x0 + v * (1e-4 - ts), 2e-7)
    lpoly = dict(base, path="((50e-6 50e-6 1e-4) (150e-6 50e-6 1e-4) (150e-6 150e-6 1e-4))", speed=1.0, tStart=0)
    case = make_case(root, "polyline", flat, lpoly)
    _, log = check_app(case, ["-times", "(5e-5 1.5e-4 1e-3)"])
    rs = laser_lines(log)
    ref = [(100e-6, 50e-6), (150e-6, 100e-6), (150e-6, 150e-6)]
    err = max(math.hypot(rr["pos"][0] - a, rr["pos"][1] - b) for rr, (a, b) in zip(rs, ref))
    ok &= check_absolute(TEST, "polyline path: max position error at 3 times [m]", err, 0.0, 1e-12)
    # hatched tracks (serpentine, along x at y = 50 and 150 um) at 1 m/s from tStart 1e-5, the beam off
    # for returnTime 5e-5 between them: on in [1e-5, 1.3e-4) and [1.8e-4, 3e-4)
    tracks = "(((40e-6 50e-6 1e-4) (160e-6 50e-6 1e-4)) ((160e-6 150e-6 1e-4) (40e-6 150e-6 1e-4)))"
    case = make_case(root, "tracks", flat, dict(base, tracks=tracks, speed=1.0, returnTime=5e-5, tStart=1e-5))
    times = [7e-5, 1.305e-4, 1.5e-4, 1.805e-4, 2.4e-4, 1e-3]
    _, log = check_app(case, ["-times", "(" + " ".join(map(repr, times)) + ")"])
    rs = laser_lines(log)
    ref = [(100e-6, 50e-6), (160e-6, 50e-6 + 1e-4 * 0.5e-6 / 5e-5), (160e-6, 90e-6), (159.5e-6, 150e-6),
           (100e-6, 150e-6), (40e-6, 150e-6)]
    err = max(math.hypot(rr["pos"][0] - a, rr["pos"][1] - b) for rr, (a, b) in zip(rs, ref))
    ok &= check_absolute(TEST, "tracks: max position error at 6 times (on a track, jumping back, after) [m]",
                         err, 0.0, 1e-12)
    lit = [1.0, 0.5, 0.0, 0.5, 1.0, 0.0]
    err = max(abs(rr["integral"] - f * ETA * P) for rr, f in zip(rs, lit))
    ok &= check_absolute(TEST, "tracks: max |absorbed - eta P x lit part of the step| / eta P (on, half, returning, "
                         "half, on, after)", err / (ETA * P), 0.0, 1e-6)

    # 6. evaporation (Fuchs2022 eq. 10, 18)
    case = make_case(root, "evap", flat, dict(base, position=vec((100e-6, 100e-6, z_top))))
    _, log = check_app(case, ["-T", "(2500 3000)"])
    ev = {}
    for line in log.splitlines():
        t = line.split()
        if line.startswith("evaporation T"):
            ev[float(t[2])] = (float(t[4]), float(t[6]), float(t[8]))
        if line.startswith("evaporationField"):
            field_loss, gas_loss = float(t[4]), float(t[6])
    ok &= check_relative(TEST, "p_v(T_boil) [Pa] = 0.54 p_a", ev[3000.0][0], 0.54 * 1e5, 1e-12)
    pv_hand = 5.4e4 * math.exp(-5e4 * (1 / 2500 - 1 / 3000))  # 1926.4 Pa
    ok &= check_relative(TEST, "p_v(2500 K) [Pa] by hand", ev[2500.0][0], pv_hand, 1e-12)
    flux_hand = 0.82 * pv_hand * math.sqrt(1.1095e-3 / 2500) * (6.583e6 + 965 * (2500 - 663.731))
    ok &= check_relative(TEST, "eq. 18 heat flux at 2500 K [W/m2] by hand", ev[2500.0][1], flux_hand, 1e-12)

    def fl(T):
        return (0.82 * 5.4e4 * math.exp(-5e4 * (1 / T - 1 / 3000)) * math.sqrt(1.1095e-3 / T)
                * (6.583e6 + 965 * (T - 663.731)))
    ok &= check_relative(TEST, "d flux/dT at 2500 K [W/m2/K] vs central difference (dT 1e-3 K)",
                         ev[2500.0][2], (fl(2500 + 1e-3) - fl(2500 - 1e-3)) / 2e-3, 1e-6)
    ok &= check_relative(TEST, "heat-loss field integral, flat surface, 2500 K [W] = flux * area",
                         field_loss, flux_hand * LX * LY, 1e-9)
    ok &= check_absolute(TEST, "heat loss in gas cells (2 alpha weight) [W]", gas_loss, 0.0, 0.0)
    # smeared interface (alpha 1, 2/3, 1/3, 0 over the rows z = 35..65 um): the weight keeps the area
    smear = np.interp(ZC, [35e-6, 65e-6], [1.0, 0.0])
    case = make_case(root, "evap_smear", smear, dict(base, position=vec((100e-6, 100e-6, z_top))))
    _, log = check_app(case, ["-T", "(2500)"])
    loss = [float(line.split()[4]) for line in log.splitlines() if line.startswith("evaporationField")][0]
    ok &= check_relative(TEST, "heat-loss integral, smeared interface (3 cells), 2500 K [W] = flux * area",
                         loss, flux_hand * LX * LY, 1e-9)

    # 7. bad input: FatalIOError naming the entry, no signal
    bad = [("power", dict(base, position=vec((1e-4, 1e-4, z_top)), power=-1), "laser"),
           ("absorptivity", dict(base, position=vec((1e-4, 1e-4, z_top)), absorptivity=1.5), "laser"),
           ("radius", dict(base, position=vec((1e-4, 1e-4, z_top)), radius=0), "laser"),
           ("position", dict(base, position=vec((1e-4, 3e-4, z_top))), "laser"),
           ("tOff", dict(base, position=vec((1e-4, 1e-4, z_top)), tOn=1e-4, tOff=0), "laser"),
           ("velocity", dict(base, position=vec((1e-4, 1e-4, z_top)), velocity="(1 0 0)", tStop=1e-3), "laser"),
           ("path", dict(base, path="((1e-4 1e-4 1e-4) (5e-4 1e-4 1e-4))", speed=1), "laser"),
           ("returnTime", dict(base, tracks="(((5e-5 5e-5 1e-4) (1e-4 5e-5 1e-4)))", speed=1, returnTime=-1),
            "laser"),
           ("tracks", dict(base, tracks="(((5e-5 5e-5 1e-4) (1e-4 5e-5 1e-4)))", speed=1, returnTime=0,
                           position=vec((1e-4, 1e-4, z_top))), "laser"),
           ("tracks", dict(base, tracks="(((5e-5 5e-5 1e-4) (5e-4 5e-5 1e-4)))", speed=1, returnTime=0), "laser"),
           ("distribution", dict(base, position=vec((1e-4, 1e-4, z_top)), distribution="sharp"), "laser"),
           ("CT", dict(base, position=vec((1e-4, 1e-4, z_top))), "evap")]
    nbad = 0
    for i, (entry, ld, kind) in enumerate(bad):
        case = make_case(root, f"bad{i}", flat, ld, evap={"CT": -1.0} if kind == "evap" else None)
        rc, log = check_app(case, ["-T", "(3000)"] if kind == "evap" else ["-times", "(0)"], check=False)
        good = (rc not in (0,) and rc < 128 and "FOAM FATAL IO ERROR" in log
                and re.search(r"\b" + entry + r"\b", log.split("FOAM FATAL IO ERROR", 1)[-1]) is not None)
        if not good:
            print(f"bad input {entry}: rc {rc}\n{log[-1500:]}")
        nbad += good
    ok &= check_absolute(TEST, f"bad inputs stopped with a FatalIOError naming the entry (of {len(bad)})",
                         nbad, len(bad), 0)

    return fc.finish(ok, root)


if __name__ == "__main__":
    sys.exit(main())
