"""The exchange benchmarks' case: a closed cube of quiescent argon-like gas at 1500 K with a
simple cubic lattice of steel particles that heat, feel drag and buoyancy and fall, but never
melt, so every particle samples the fluid and deposits heat and momentum every fluid step
(bench/coupling_exchange_share.py, bench/scaling.py).

    build(case, model, scenario, per_axis, cells, steps, edge=1e-3)
    timed_solver(case, np_)  -> (stamps, wall): wall-clock time of each step's end, run time

Scenarios: 'granular' (pair_style granular/powder, DEM step 1e-8 s, 100 sub-cycles per fluid
step, no contact forms) and 'ballistic' (no pair style, DEM step = fluid step: LAMMPS costs
almost nothing, the largest exchange share). The lattice fills [0.05, 0.95] of the cube
(spacing (0.9 edge) / per_axis, origin 0.4 spacings so that no centre lies on a cell face);
diameters uniform 20-40 um (fixed seed); LAMMPS box 0.1 edge beyond the mesh.
"""
import os
import subprocess
import time

from meltdem.case import coupled as cc
from meltdem.case import foam as fc

DT = 1e-6                     # fluid step [s]
T_GAS, RHO_G, MU_G, CP_G, K_G = 1500.0, 0.32, 5.6e-5, 520.0, 0.06
RHO_P, CP_P, TM, LAT, T0 = 7900.0, 500.0, 1700.0, 2.7e5, 300.0
D_LO, D_HI = 20e-6, 40e-6
SCENARIO_DEM = {"granular": 1e-8, "ballistic": DT}


def fill(edge):
    """The cube the lattice fills (lo, hi) [m]."""
    return 0.05 * edge, 0.95 * edge


def build(case, model, scenario, per_axis, cells, steps, edge=1e-3, particles=True):
    n = cells
    cc.box_mesh(case, (0, 0, 0), (edge, edge, edge), (n, n, n),
                {"walls": ("wall", ["xmin", "xmax", "ymin", "ymax", "zmin", "zmax"])})
    cc.uniform_field(case, "alpha.metal", "[0 0 0 0 0 0 0]", 0.0, {"walls": "type zeroGradient;"})
    cc.uniform_field(case, "T", "[0 0 0 1 0 0 0]", T_GAS, {"walls": "type zeroGradient;"})
    cc.uniform_field(case, "U", "[0 1 -1 0 0 0 0]", (0.0, 0.0, 0.0), {"walls": "type noSlip;"}, vector=True)
    cc.uniform_field(case, "p_rgh", "[1 -1 -2 0 0 0 0]", 0.0,
                     {"walls": "type fixedFluxPressure; value uniform 0;"})
    fc.transport(case, RHO_P, 6e-3 / RHO_P, RHO_G, MU_G / RHO_G, 0.0)
    fc.gravity(case, (0.0, 0.0, -9.81))  # the same gravity as fix gravity (checked by the coupling)
    end = steps * DT
    fc.control_dict(case, "meltdemFoam", end, DT, end, max_co=0.5, max_alpha_co=0.5, max_dt=DT)
    fc.fv_schemes(case)
    fc.fv_solution(case, n_correctors=2, p_ref_cell=0)
    part = f"""particles
{{
    lammpsInput     in.particles;
    distribution    {model};
    demStepsPerFluidStep auto;
}}
""" if particles else ""
    fc.meltdem_properties(case, physics=dict(energy="on", surfaceTension="off",
                                             particles="on" if particles else "off"), extra=f"""
metal {{ cp {CP_P!r}; k 30; L {LAT!r}; Tsolidus {TM - 1!r}; Tliquidus {TM!r}; }}
gas {{ cp {CP_G!r}; k {K_G!r}; }}
{part}""")
    fc.run(["blockMesh"], case, "log.blockMesh")
    if not particles:
        return
    if scenario == "granular":
        pair = f"""pair_style      granular/powder {D_HI!r}
pair_coeff      * * hertz/material 200e9 0.5 0.3 damping tsuji/alpha 1.5 tangential mindlin NULL 1.0 0.1
"""
    else:
        pair = "pair_style      none\n"
    lo, hi = fill(edge)
    b0, b1 = -0.1 * edge, 1.1 * edge  # the LAMMPS box
    spacing = (hi - lo) / per_axis
    with open(os.path.join(case, "in.particles"), "w") as f:
        f.write(f"""# meltdem.case.exchange_box: {per_axis}^3 particles, scenario {scenario}
units           si
atom_style      sphere 1
atom_modify     map array
dimension       3
boundary        f f f
newton          off
comm_modify     vel yes
region          box block {b0!r} {b1!r} {b0!r} {b1!r} {b0!r} {b1!r} units box
create_box      1 box
lattice         sc {spacing!r} origin 0.4 0.4 0.4
region          cloud block {lo!r} {hi!r} {lo!r} {hi!r} {lo!r} {hi!r} units box
create_atoms    1 region cloud
variable        d atom random({D_LO!r},{D_HI!r},4242)
set             group all diameter v_d
set             group all density {RHO_P!r}
{pair}neighbor        1e-5 bin
neigh_modify    delay 0
comm_modify     cutoff {2 * D_HI!r}
timestep        {SCENARIO_DEM[scenario]!r}
fix             integrate all nve/sphere
fix             gravity all gravity 9.81 vector 0 0 -1
fix             melt all powder/melt cp {CP_P!r} Tmelt {TM!r} latent {LAT!r} temp {T0!r}
thermo          1000
""")


def timed_solver(case, np_):
    """Runs the solver as meltdem.case.coupled.run_solver does, writing log.meltdemFoam, and returns
    the wall-clock time since the launch at which each step's ExecutionTime line arrived
    (the solver flushes it at the end of every step) and the run's total wall time."""
    cmd = [fc.solver()]
    env = dict(os.environ, WM_PROJECT_DIR=os.environ.get("WM_PROJECT_DIR", "/usr/share/openfoam"),
               PWD=os.path.abspath(case))
    if np_ > 1:
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_)] + cmd + ["-parallel"]
        env.update(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1")
    stamps = []
    t0 = time.perf_counter()
    with open(os.path.join(case, "log.meltdemFoam"), "w") as log:
        p = subprocess.Popen(cmd, cwd=case, env=env, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             text=True, bufsize=1)
        for line in p.stdout:
            if line.startswith("ExecutionTime ="):
                stamps.append(time.perf_counter() - t0)
            log.write(line)
        rc = p.wait()
    wall = time.perf_counter() - t0
    if rc != 0:
        raise SystemExit(f"{' '.join(cmd)} failed (rc {rc}) in {case}: see log.meltdemFoam")
    return stamps, wall
