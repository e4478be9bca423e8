"""Writer for the coupled (meltdemFoam + LAMMPS) test cases: a 3D box mesh of hexahedra
(blockMesh), uniform initial fields, the LAMMPS input of the particles, and the runners
(serial, or decomposed with mpirun -np N). The 2D writers of meltdem.case.foam do
the dictionaries they share."""
import os
import re

import numpy as np

from meltdem.case import foam as fc

FACES = {"xmin": "(0 4 7 3)", "xmax": "(1 2 6 5)", "ymin": "(0 1 5 4)", "ymax": "(3 7 6 2)",
         "zmin": "(0 3 2 1)", "zmax": "(4 5 6 7)"}


def box_mesh(case, lo, hi, n, patches):
    """One hex block [lo, hi] with n cells; patches: name -> (type, [box faces]) covering all six
    faces (xmin, xmax, ymin, ymax, zmin, zmax)."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    verts = [(x0, y0, z0), (x1, y0, z0), (x1, y1, z0), (x0, y1, z0),
             (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1)]
    used = sorted(f for _, fs in patches.values() for f in fs)
    assert used == sorted(FACES), f"patches must cover the six faces once, got {used}"
    vs = "\n".join(f"    ({a!r} {b!r} {c!r})" for a, b, c in verts)
    bd = fc.patch_entries({side: (name, typ) for name, (typ, sides) in patches.items() for side in sides}, FACES)
    fc.dictionary(case, "system/blockMeshDict", f"""scale 1;
vertices
(
{vs}
);
blocks ( hex (0 1 2 3 4 5 6 7) ({n[0]} {n[1]} {n[2]}) simpleGrading (1 1 1) );
edges ();
boundary
(
{bd});
""")


def uniform_field(case, name, dims, value, boundary, vector=False):
    """A field with a uniform internal value, or per cell for a numpy array (no frontAndBack:
    the mesh is 3D)."""
    if isinstance(value, np.ndarray):
        internal = fc._internal(value, vector)
    elif vector:
        internal = f"uniform ({value[0]!r} {value[1]!r} {value[2]!r})"
    else:
        internal = f"uniform {value!r}"
    bf = "".join(f"    {k}\n    {{\n        {v}\n    }}\n" for k, v in boundary.items())
    fc.write(case, f"0/{name}", "volVectorField" if vector else "volScalarField", name,
             f"dimensions {dims};\ninternalField {internal};\nboundaryField\n{{\n{bf}}}\n")


# (decomposePar and the solver launch live in meltdem.case.foam; the names stay here for callers)
decompose = fc.decompose
run_solver = fc.run_solver


def build_and_run(case, build, np_=1):
    """build(case), decomposed for np_ > 1, run; the particle ledger and particles.csv of the run."""
    build(case)
    if np_ > 1:
        decompose(case, np_)
    run_solver(case, np_)
    return ledger(case), particles_csv(case)


def ledger(case):
    path = os.path.join(case, "postProcessing", "particleLedger", "ledger.csv")
    d = np.genfromtxt(path, delimiter=",", names=True)
    return d.reshape(1) if d.ndim == 0 else d


def particles_csv(case):
    path = os.path.join(case, "postProcessing", "particleLedger", "particles.csv")
    d = np.genfromtxt(path, delimiter=",", names=True)
    return d.reshape(1) if d.ndim == 0 else d


# Codina2019 §2.3 channel (tables 2.1-2.3): hot artificial argon flowing down a square channel.
GAS = dict(rho=1.6115, cp=5210.928, k=100.0, mu=2.1e-5, T=1500.0)
CHANNEL = dict(lx=2.1e-3, ly=18.2e-3, lz=2.1e-3, h=0.7e-3, u=-2.0)


def cell_centres_y(n, lo, hi):
    """y of the cell centres of a one-block mesh in blockMesh order (x fastest, then y, z)."""
    h = (hi[1] - lo[1]) / n[1]
    yc = lo[1] + (np.arange(n[1]) + 0.5) * h
    return np.broadcast_to(yc[None, :, None], (n[2], n[1], n[0])).ravel()


def exact_solves(case, alpha=1e-14, p_rgh=None, U=None, T=None, relaxation=False):
    """Tighten the linear solves of fc.fv_solution's system/fvSolution: the ledger's balances are
    only as exact as these solves (alpha to 1e-14 for the metal mass; p_rgh, U, T to the given
    tolerance with relTol 0, None keeps fv_solution's). Drops relaxationFactors (relax() breaks
    exact conservation) unless relaxation."""
    sol = os.path.join(case, "system", "fvSolution")
    txt = open(sol).read()
    txt = txt.replace("tolerance 1e-10; relTol 0;\n    }", f"tolerance {alpha!r}; relTol 0;\n    }}", 1)
    if p_rgh is not None:
        txt = txt.replace("p_rgh { solver PCG; preconditioner DIC; tolerance 1e-9; relTol 0.01; }",
                          f"p_rgh {{ solver PCG; preconditioner DIC; tolerance {p_rgh!r}; relTol 0; }}")
    if U is not None:
        txt = txt.replace('"U.*" { solver smoothSolver; smoother symGaussSeidel; tolerance 1e-9; relTol 0; }',
                          f'"U.*" {{ solver smoothSolver; smoother symGaussSeidel; tolerance {U!r}; relTol 0; }}')
    if T is not None:
        txt = txt.replace('"T.*" { solver PBiCGStab; preconditioner DILU; tolerance 1e-10; relTol 0; }',
                          f'"T.*" {{ solver PBiCGStab; preconditioner DILU; tolerance {T!r}; relTol 0; }}')
    if not relaxation:
        txt = txt.replace('relaxationFactors { equations { ".*" 1; } }', "")
    open(sol, "w").write(txt)


def channel_case(case, model, particle, channel=None, gas=None, t_end=8.5e-3, fluid_dt=1e-5,
                 dem_dt=1e-6, max_co=0.5, metal_k=30.0, extra_lammps="", g=(0.0, 0.0, 0.0),
                 floor=None, melt_keywords="", physics=None, extra_properties="", particles_script=None):
    """A box channel along y (inlet ymax with U = (0, u, 0), outlet ymin, slip walls), gas at
    rest or flowing, one particle from LAMMPS. particle: dict d, rho, cp, Tm, L, T0, x, y, z,
    v (velocity vector) and held (no time integration: the particle stays where it is).
    The fluid step is fluid_dt at most (Courant max_co); solver tolerances are tight, since the
    balances are only as exact as the linear solves."""
    ch = dict(CHANNEL, **(channel or {}))
    gs = dict(GAS, **(gas or {}))
    p = particle
    n = (round(ch["lx"] / ch["h"]), round(ch["ly"] / ch["h"]), round(ch["lz"] / ch["h"]))
    u, T = ch["u"], gs["T"]
    box_mesh(case, (0, 0, 0), (ch["lx"], ch["ly"], ch["lz"]), n,
             {"inlet": ("patch", ["ymax"]), "outlet": ("patch", ["ymin"]),
              "walls": ("wall", ["xmin", "xmax", "zmin", "zmax"])})
    # optional metal floor: floor = (top y, temperature) of a metal layer at the outlet end
    alpha0, T0 = 0.0, T
    if floor:
        y = cell_centres_y(n, (0, 0, 0), (ch["lx"], ch["ly"], ch["lz"]))
        alpha0 = np.where(y < floor[0], 1.0, 0.0)
        T0 = np.where(y < floor[0], floor[1], T)
    uniform_field(case, "alpha.metal", "[0 0 0 0 0 0 0]", alpha0,
                  {"inlet": "type fixedValue; value uniform 0;",
                   "outlet": "type zeroGradient;", "walls": "type zeroGradient;"})
    uniform_field(case, "T", "[0 0 0 1 0 0 0]", T0,
                  {"inlet": f"type fixedValue; value uniform {T!r};",
                   "outlet": f"type inletOutlet; inletValue uniform {T!r}; value uniform {T!r};",
                   "walls": "type zeroGradient;"})
    uniform_field(case, "U", "[0 1 -1 0 0 0 0]", (0.0, u, 0.0),
                  {"inlet": f"type fixedValue; value uniform (0 {u!r} 0);",
                   "outlet": "type zeroGradient;", "walls": "type slip;"}, vector=True)
    uniform_field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", 0.0,
                  {"inlet": "type fixedFluxPressure; value uniform 0;",
                   "outlet": "type fixedValue; value uniform 0;",
                   "walls": "type fixedFluxPressure; value uniform 0;"})
    fc.transport(case, p["rho"], 6e-3 / p["rho"], gs["rho"], gs["mu"] / gs["rho"], 0.0)
    fc.gravity(case, g)
    fc.control_dict(case, "meltdemFoam", t_end, fluid_dt, t_end / 4, max_co=max_co, max_alpha_co=max_co,
                    max_dt=fluid_dt)
    fc.fv_schemes(case)
    fc.fv_solution(case, n_correctors=3)
    exact_solves(case, p_rgh=1e-14, U=1e-15, T=1e-15)
    fc.meltdem_properties(case, physics=dict(dict(energy="on", surfaceTension="off", particles="on"),
                                             **(physics or {})), extra=extra_properties + f"""
metal {{ cp {p["cp"]!r}; k {metal_k!r}; L {p["L"]!r}; Tsolidus {p["Tm"] - 1!r}; Tliquidus {p["Tm"]!r}; }}
gas {{ cp {gs["cp"]!r}; k {gs["k"]!r}; }}
energyControls {{ nCorrectors 50; tolerance 1e-13; }}
particles
{{
    lammpsInput     in.particles;
    distribution    {model};
    demStepsPerFluidStep auto;
}}
""")
    fc.run(["blockMesh"], case, "log.blockMesh")
    m = 1e-4
    v = p.get("v", (0.0, u, 0.0))
    integrate = "" if p.get("held") else "fix integrate all nve/sphere"
    gravity = "" if not any(g) else (f"fix gravity all gravity {float(np.linalg.norm(g))!r} vector "
                                     f"{g[0]!r} {g[1]!r} {g[2]!r}")
    with open(os.path.join(case, "in.particles"), "w") as f:
        f.write(f"""# one particle in the channel, coupled
units si
atom_style sphere 1
dimension 3
boundary f f f
region box block {-m!r} {ch["lx"] + m!r} {-m!r} {ch["ly"] + m!r} {-m!r} {ch["lz"] + m!r}
create_box 1 box
create_atoms 1 single {p.get("x", ch["lx"] / 2)!r} {p["y"]!r} {p.get("z", ch["lz"] / 2)!r}
set atom 1 diameter {p["d"]!r} density {p["rho"]!r}
velocity all set {v[0]!r} {v[1]!r} {v[2]!r}
comm_modify cutoff {2 * p["d"]!r}
neighbor 1e-5 bin
timestep {dem_dt!r}
{integrate}
{gravity}
fix melt all powder/melt cp {p["cp"]!r} Tmelt {p["Tm"]!r} latent {p["L"]!r} temp {p.get("T0", 0.0)!r} {melt_keywords}
thermo_style custom step time atoms f_melt[1] f_melt[2] f_melt[6]
thermo_modify format float %.12g
thermo 200
{extra_lammps}
""")


def track_commands(every=50):
    """LAMMPS lines that print the (single) particle's y and vy in the thermo output."""
    return f"""compute py all property/atom y vy
compute ys all reduce sum c_py[1] c_py[2]
thermo_style custom step time atoms c_ys[1] c_ys[2]
thermo_modify format float %.12g
thermo {every}
"""


def track(log):
    """(time, y, vy) of the single particle from a LAMMPS log with track_commands()."""
    rows = []
    for line in open(log):
        w = line.split()
        if len(w) == 5 and re.fullmatch(r"\d+", w[0]) and w[2] == "1":
            try:
                rows.append((float(w[1]), float(w[3]), float(w[4])))
            except ValueError:
                pass
    return np.array(sorted(set(rows)))


def check_evaporation_booked(test, case, ledger_bound):
    """The metal evaporated in a coupled run (particleBalance's evaporatedMass_cum) against 1e-7 of the
    continuum's metal at the start, so that a ledger holding ledger_bound sees it if it went unbooked;
    returns (ok, evaporated, metal at the start)."""
    from meltdem.testing.report import check_at_least
    bal = np.genfromtxt(os.path.join(case, "postProcessing", "particleBalance", "0", "balance.csv"),
                        delimiter=",", names=True)
    evaporated, metal = float(bal["evaporatedMass_cum"][-1]), float(bal["metalMass"][0])
    ok = check_at_least(test, f"metal evaporated and booked [kg] (> 1e-7 of the continuum's metal, so the "
                        f"ledger's {ledger_bound:g} sees it)", evaporated, 1e-7 * metal)
    return ok, evaporated, metal


def check_balances(test, ledger_rows, mass=1e-13, energy=1e-6, momentum=None, xfail=None, momentum_xfail=None,
                   momentum_miss_within=None):
    """The worst per-step continuum errors of a ledger (Codina2019 eq. 2.20, 2.26, 2.36) against
    their bounds (momentum only when given); returns whether all held. momentum_xfail: a known
    miss of the momentum bound, momentum_miss_within its own bound (report.py's miss_within)."""
    from meltdem.testing.report import check_at_most
    steps = ledger_rows[1:]  # the first step has no previous one
    ok = check_at_most(test, "worst per-step continuum mass error (eq. 2.20)",
                       np.max(np.abs(steps["mass_continuum_error"])), mass, xfail=xfail)
    ok &= check_at_most(test, "worst per-step continuum energy error (eq. 2.26)",
                        np.max(np.abs(steps["enthalpy_continuum_error"])), energy, xfail=xfail)
    if momentum is not None:
        worst = max(np.max(np.abs(steps[f"mom_{c}_continuum_error"])) for c in "xyz")
        ok &= check_at_most(test, "worst per-step continuum momentum error (eq. 2.36)", worst, momentum,
                            xfail=xfail or momentum_xfail, miss_within=None if xfail else momentum_miss_within)
    return ok


def ledger_totals_difference(run, reference):
    """The largest difference between two runs' ledger totals (particles, continuum, exchange of mass,
    enthalpy and momentum) over their steps, relative to the reference's largest total (a momentum
    component against the momentum magnitude): np N against serial, step by step."""
    if len(run) != len(reference):
        raise ValueError(f"the ledgers have {len(run)} and {len(reference)} steps")
    worst = 0.0
    momentum = np.max(np.sqrt(sum(reference[f"mom_{k}_total"] ** 2 for k in "xyz")))
    for c in ("mass", "enthalpy", "mom_x", "mom_y", "mom_z"):
        scale = momentum if c.startswith("mom") else np.max(np.abs(reference[f"{c}_total"]))
        for cat in ("particles", "continuum", "exchange"):
            worst = max(worst, np.max(np.abs(run[f"{c}_{cat}"] - reference[f"{c}_{cat}"])) / scale)
    return float(worst)
