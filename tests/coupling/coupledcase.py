"""Writer for the coupled (meltdemFoam + LAMMPS) test cases: a 3D box mesh of hexahedra
(blockMesh), uniform initial fields, the LAMMPS input of the particles, and the runners
(serial, or decomposed with mpirun -np N). The 2D writers of tests/support/foamcase.py do
the dictionaries they share."""
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.environ["MELTDEM_SOURCE_DIR"], "tests", "support"))
import foamcase as fc  # noqa: E402

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
    bd = "".join(
        f"    {name}\n    {{\n        type {typ};\n        faces\n        (\n"
        + "".join(f"            {FACES[f]}\n" for f in fs) + "        );\n    }\n"
        for name, (typ, fs) in patches.items())
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
    """A field with a uniform internal value (no frontAndBack: the mesh is 3D)."""
    if vector:
        internal = f"uniform ({value[0]!r} {value[1]!r} {value[2]!r})"
    else:
        internal = f"uniform {value!r}"
    bf = "".join(f"    {k}\n    {{\n        {v}\n    }}\n" for k, v in boundary.items())
    fc.write(case, f"0/{name}", "volVectorField" if vector else "volScalarField", name,
             f"dimensions {dims};\ninternalField {internal};\nboundaryField\n{{\n{bf}}}\n")


def decompose(case, np_, direction=(1, 2, 1)):
    fc.dictionary(case, "system/decomposeParDict", f"""numberOfSubdomains {np_};
method simple;
coeffs {{ n ({direction[0]} {direction[1]} {direction[2]}); }}
""")
    fc.run(["decomposePar", "-force"], case, "log.decomposePar")


def run_solver(case, np_=1, log="log.meltdemFoam", check=True):
    solver = fc.solver()
    if np_ == 1:
        return fc.run([solver], case, log, check=check)
    mpirun = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_)]
    env = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}
    return fc.run(mpirun + [solver, "-parallel"], case, log, env=env, check=check)


def ledger(case):
    path = os.path.join(case, "postProcessing", "particleLedger", "ledger.csv")
    d = np.genfromtxt(path, delimiter=",", names=True)
    return d.reshape(1) if d.ndim == 0 else d


def particles_csv(case):
    path = os.path.join(case, "postProcessing", "particleLedger", "particles.csv")
    d = np.genfromtxt(path, delimiter=",", names=True)
    return d.reshape(1) if d.ndim == 0 else d
