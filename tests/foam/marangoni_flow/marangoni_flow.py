#!/usr/bin/env python3
"""Marangoni-driven surface flow: a flat metal layer (20 um) under gas (80 um), no gravity,
T imposed linear along the surface (1800 K left -> 1600 K right, fixed on the end walls).
With dSigmadT < 0 the surface must flow from hot to cold (+x). Magnitude reference: the
start-up of two semi-infinite fluids under a constant surface shear tau = |dsigma/dT| dT/dx,
    u_s(t) = 2 tau sqrt(t/pi) / (sqrt(rho_l mu_l) + sqrt(rho_g mu_g)),
valid while both diffusion lengths stay inside their layers (here t <= 10 us:
sqrt(nu_l t) = 2.8 um, sqrt(nu_g t) = 28 um) and away from the end walls (middle half).
The same layer solid (solidus above the range, Darcy on) must stay at rest, gas included: the
surface forces act on liquid metal only (weighted by its liquid fraction). With
marangoniDensityScaled the force sits on the metal side of the interface, half a cell below it here:
first order in the cell size (an expected miss at these 1 um cells, shown). The momentum balance
(meltdemBalance) books the Marangoni impulse: tau L dz t over the surface (1e-3), the balance
closing to 5e-3 of the exchanged impulse.
"""
import os
import shutil
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_relative, check_absolute, check_at_most

src = paths.source_dir()

TEST = "foam.marangoni_flow"
M, G = fc.METAL, fc.GAS
L, h, H, nx, dy, DZ = 200e-6, 20e-6, 80e-6, 25, 1e-6, 4e-6
TL, TR = 1800.0, 1600.0
t_end = 1.0e-5

work = tempfile.mkdtemp(prefix="marangoni_flow.")
ny = int(round((h + H) / dy))


def make_and_run(case, marangoni, solid=False, density_scaled=False):
    g = fc.Grid2D(L, h + H, nx, ny, dz=DZ)
    g.block_mesh(case, {"left": ("left", "wall"), "right": ("right", "wall")})
    fc.control_dict(case, "meltdemFoam", t_end, 1e-9, t_end / 4, max_co=0.2, max_alpha_co=0.2, max_dt=5e-8,
                    extra="functions\n{\n    balance { type meltdemBalance; }\n}\n")
    fc.fv_schemes(case)
    fc.fv_solution(case, p_ref_cell=0)
    fc.transport(case, M["rho"], M["mu"] / M["rho"], G["rho"], G["mu"] / G["rho"], M["sigma0"])
    fc.gravity(case)
    # marangoni needs the energy equation: the linear T profile is its steady solution (fixed
    # ends, adiabatic top and bottom); solidus/liquidus below the range keep the layer liquid
    melt = "Tsolidus 2000; Tliquidus 2100;" if solid else "Tsolidus 1000; Tliquidus 1100;"
    physics = {"energy": "on", "marangoni": marangoni, "darcy": "on" if solid else "off"}
    fc.meltdem_properties(case, physics=physics, surface={"marangoniDensityScaled": 1} if density_scaled else None,
                          extra=f"metal {{ cp {M['cp']!r}; k {M['k']!r}; L 0; {melt} }}\n"
                                f"gas {{ cp {G['cp']!r}; k {G['k']!r}; }}\n"
                                + ("darcy { C 1e12; b 1e-3; }\n" if solid else ""))
    sides = {"left": "type zeroGradient;", "right": "type zeroGradient;", "walls": "type zeroGradient;"}
    fc.field(case, "alpha.metal", "[0 0 0 0 0 0 0]", (g.y < h).astype(float), sides)
    # linear in x with fixed end values: also the steady conduction solution if energy is solved
    fc.field(case, "T", "[0 0 0 1 0 0 0]", TL + (TR - TL) * g.x / L,
             {"left": f"type fixedValue; value uniform {TL!r};", "right": f"type fixedValue; value uniform {TR!r};",
              "walls": "type zeroGradient;"})
    fc.field(case, "U", "[0 1 -1 0 0 0 0]", np.zeros((g.x.size, 3)),
             {k: "type noSlip;" for k in sides}, vector=True)
    fc.field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", np.zeros(g.x.size),
             {k: "type fixedFluxPressure; value uniform 0;" for k in sides})
    fc.run(["blockMesh"], case, "log.blockMesh")
    fc.run([fc.solver()], case, "log.solver")


case = os.path.join(work, "layer")
make_and_run(case, "on")
tau = abs(M["dSigmadT"]) * (TL - TR) / L
ok = True
times = fc.time_dirs(case)[1:]
ok &= len(times) == 4 and abs(float(times[-1]) - t_end) < 1e-12
j, mid = int(round(h / dy)), slice(nx // 4, 3 * nx // 4)
for d in times:
    t = float(d)
    U = fc.read_internal(os.path.join(case, d, "U")).reshape(ny, nx, 3)
    us = 0.5 * (U[j - 1, mid, 0] + U[j, mid, 0])      # the two cell rows either side of the surface
    ref = 2 * tau * np.sqrt(t / np.pi) / (np.sqrt(M["rho"] * M["mu"]) + np.sqrt(G["rho"] * G["mu"]))
    print(f"t = {t:.3g} s: surface u_x mean {us.mean():.4g} (min {us.min():.4g}) m/s, reference {ref:.4g} m/s")
ok &= check_absolute(TEST, "sign of the surface velocity u_x (hot x=0 -> cold x=L), cells of the middle half not > 0",
                     int(np.sum(us <= 0)), 0, 0)
ok &= check_relative(TEST, f"surface velocity at t={t:g} s [m/s] vs two-fluid start-up 2 tau sqrt(t/pi)/(e_l+e_g)",
                     us.mean(), ref, 0.10)
# the momentum balance books the Marangoni force (meltdemFoam's physicsForce): its impulse is the
# surface shear over the surface, tau L dz t; the rest of the balance (walls' shear, PISO's velocity
# correction) closes to the exchanged impulse's 5e-3
bal = np.genfromtxt(os.path.join(case, "postProcessing", "balance", "0", "balance.csv"), delimiter=",", names=True)
ok &= check_relative(TEST, "Marangoni impulse booked by the momentum balance [N s] vs tau L dz t_end",
                     float(bal["physicsForceImpulse_cum_x"][-1]), tau * L * DZ * t_end, 1e-3)
ok &= check_at_most(TEST, "momentum balance error at t_end / exchanged impulse", float(bal["momentumErrorRel"][-1]),
                    5e-3)
# the switch: with marangoni off the same layer must stay (nearly) at rest
off = os.path.join(work, "off")
make_and_run(off, "off")
U = fc.read_internal(os.path.join(off, fc.time_dirs(off)[-1], "U")).reshape(ny, nx, 3)
ok &= check_at_most(TEST, "marangoni off: max surface |u_x| / reference", np.abs(U[j - 1:j + 1, mid, 0]).max() / ref,
                    0.01)
# a solid layer (solidus 2000 K above the 1600-1800 K surface, Darcy holding the metal): no
# Marangoni or capillary force on it, so neither the metal nor the gas over it moves
solid = os.path.join(work, "solid")
make_and_run(solid, "on", solid=True)
U = np.broadcast_to(fc.read_internal(os.path.join(solid, fc.time_dirs(solid)[-1], "U")), (ny * nx, 3))
ok &= check_at_most(TEST, "solid layer, marangoni on: max |u| anywhere (gas included) / liquid surface reference",
                    float(np.abs(U).max()) / ref, 0.01)
# density-scaled: the same start-up, the force on the metal side of the interface
scaled = os.path.join(work, "scaled")
make_and_run(scaled, "on", density_scaled=True)
U = fc.read_internal(os.path.join(scaled, fc.time_dirs(scaled)[-1], "U")).reshape(ny, nx, 3)
ok &= check_relative(TEST, f"marangoniDensityScaled: surface velocity at t={t_end:g} s [m/s] vs the two-fluid start-up",
                     float(np.mean(0.5 * (U[j - 1, mid, 0] + U[j, mid, 0]))), ref, 0.10, miss_within=0.25,
                     xfail="density scaling puts the force half a cell below a sharp interface: first order in the "
                     "cell size (-15.5 % at these 1 um cells, -8.4 % at 0.5 um)")
if ok:
    shutil.rmtree(work)
else:
    print("case kept in", case)
sys.exit(0 if ok else 1)
