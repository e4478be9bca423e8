"""Small writer for the 2D OpenFOAM cases of the surface-force tests (capillary, Marangoni, MJT).

Cases are written from Python (no setFields / codeStream): a one-block 2D mesh with one cell in z
(front/back 'empty'), fields as nonuniform lists on the structured cell order of blockMesh
(x fastest, then y), and the dictionaries interFoam-type solvers read.
"""
import os
import subprocess

import numpy as np

from .. import paths

HEADER = """FoamFile
{{
    version     2.0;
    format      ascii;
    class       {cls};
    object      {obj};
}}
"""


def write(case, rel, cls, obj, body):
    path = os.path.join(case, rel)
    os.makedirs(os.path.dirname(path), exist_ok=True)
    with open(path, "w") as f:
        f.write(HEADER.format(cls=cls, obj=obj) + body)
    return path


def dictionary(case, rel, body):
    return write(case, rel, "dictionary", os.path.basename(rel), body)


def patch_entries(sides, faces):
    """blockMeshDict boundary entries: sides maps each block side to (patch name, type), faces
    each side to its vertex list; sides that share a patch name form one patch (in the order
    the names first appear)."""
    groups = {}
    for side, (name, typ) in sides.items():
        groups.setdefault(name, [typ, []])[1].append(faces[side])
    return "".join(f"    {name}\n    {{\n        type {typ};\n        faces ({' '.join(fl)});\n    }}\n"
                   for name, (typ, fl) in groups.items())


class Grid2D:
    """Uniform nx x ny grid on [x0, x0+lx] x [y0, y0+ly], one cell of thickness dz in z."""

    def __init__(self, lx, ly, nx, ny, x0=0.0, y0=0.0, dz=None):
        self.lx, self.ly, self.nx, self.ny, self.x0, self.y0 = lx, ly, nx, ny, x0, y0
        self.dx, self.dy = lx / nx, ly / ny
        self.dz = dz if dz is not None else self.dx
        xc = x0 + (np.arange(nx) + 0.5) * self.dx
        yc = y0 + (np.arange(ny) + 0.5) * self.dy
        # blockMesh order: x fastest
        self.X, self.Y = np.meshgrid(xc, yc)
        self.x, self.y = self.X.ravel(), self.Y.ravel()

    def wedge_mesh(self, case, patches=None, angle_deg=5.0):
        """Axisymmetric variant: x is the radius (x0 must be 0), y the axis; one wedge cell of
        angle_deg in the circumferential direction ('front'/'back' wedge, 'axis' collapsed).
        Cell volumes are then ~ x dx dy angle (see volumes())."""
        assert self.x0 == 0.0
        p = {"right": ("walls", "wall"), "bottom": ("walls", "wall"), "top": ("walls", "wall")}
        if patches:
            p.update(patches)
        import math
        th = math.radians(angle_deg) / 2
        r, y0, y1 = self.lx, self.y0, self.y0 + self.ly
        c, sn = r * math.cos(th), r * math.sin(th)
        faces = {"right": "(1 2 5 4)", "bottom": "(0 1 4 0)", "top": "(3 5 2 3)",
                 "front": "(0 4 5 3)", "back": "(0 3 2 1)", "axis": "(0 3 3 0)"}
        p.update(front=("front", "wedge"), back=("back", "wedge"), axis=("axis", "empty"))
        bnd = patch_entries(p, faces)
        body = f"""convertToMeters 1;
vertices
(
    (0 {y0!r} 0) ({c!r} {y0!r} {-sn!r}) ({c!r} {y1!r} {-sn!r}) (0 {y1!r} 0)
    ({c!r} {y0!r} {sn!r}) ({c!r} {y1!r} {sn!r})
);
blocks ( hex (0 1 2 3 0 4 5 3) ({self.nx} {self.ny} 1) simpleGrading (1 1 1) );
edges ();
boundary
(
{bnd});
mergePatchPairs ();
"""
        self.axisymmetric = True
        dictionary(case, "system/blockMeshDict", body)

    def block_mesh(self, case, patches=None, nz=1):
        """patches: dict side->(name, type) for sides left/right/bottom/top; default all 'walls' wall.
        nz > 1: a 3D box nz cells of dz deep, its front and back 'walls' too (fields then hold
        nz copies of the 2D values: np.tile(values, nz))."""
        p = {"left": ("walls", "wall"), "right": ("walls", "wall"),
             "bottom": ("walls", "wall"), "top": ("walls", "wall")}
        faces = {"left": "(0 4 7 3)", "right": "(1 2 6 5)", "bottom": "(0 1 5 4)", "top": "(3 7 6 2)",
                 "front": "(0 3 2 1)", "back": "(4 5 6 7)"}
        if nz > 1:
            p.update(front=("walls", "wall"), back=("walls", "wall"))
        else:
            p.update(front=("frontAndBack", "empty"), back=("frontAndBack", "empty"))
        if patches:
            p.update(patches)
        bnd = patch_entries(p, faces)
        x1, y1, z1 = self.x0 + self.lx, self.y0 + self.ly, nz * self.dz
        body = f"""convertToMeters 1;
vertices
(
    ({self.x0!r} {self.y0!r} 0) ({x1!r} {self.y0!r} 0) ({x1!r} {y1!r} 0) ({self.x0!r} {y1!r} 0)
    ({self.x0!r} {self.y0!r} {z1!r}) ({x1!r} {self.y0!r} {z1!r}) ({x1!r} {y1!r} {z1!r}) ({self.x0!r} {y1!r} {z1!r})
);
blocks ( hex (0 1 2 3 4 5 6 7) ({self.nx} {self.ny} {nz}) simpleGrading (1 1 1) );
edges ();
boundary
(
{bnd});
mergePatchPairs ();
"""  # noqa: E501  (a long line of the blockMeshDict written verbatim)
        dictionary(case, "system/blockMeshDict", body)


def _internal(values, vector=False):
    v = np.asarray(values, dtype=float)
    if vector:
        items = "\n".join(f"({a:.12g} {b:.12g} {c:.12g})" for a, b, c in v)
        return f"nonuniform List<vector>\n{len(v)}\n(\n{items}\n)"
    if np.all(v == v.flat[0]):
        return f"uniform {v.flat[0]:.12g}"
    items = "\n".join(f"{a:.12g}" for a in v.ravel())
    return f"nonuniform List<scalar>\n{v.size}\n(\n{items}\n)"


def field(case, name, dims, values, boundary, vector=False, time="0", wedge=False):
    """boundary: dict patch -> body text (e.g. 'type zeroGradient;'); frontAndBack empty is added
    (wedge=True: front/back wedge and axis empty)."""
    b = dict(boundary)
    if wedge:
        b.setdefault("front", "type wedge;")
        b.setdefault("back", "type wedge;")
        b.setdefault("axis", "type empty;")
    else:
        b.setdefault("frontAndBack", "type empty;")
    bf = "".join(f"    {k}\n    {{\n        {v}\n    }}\n" for k, v in b.items())
    body = (f"dimensions {dims};\ninternalField {_internal(values, vector)};\n"
            f"boundaryField\n{{\n{bf}}}\n")
    write(case, f"{time}/{name}", "volVectorField" if vector else "volScalarField", name, body)


def control_dict(case, app, end_time, dt, write_interval, extra="", max_co=0.2, max_alpha_co=0.2,
                 max_dt=1.0, adjustable=True):
    dictionary(case, "system/controlDict", f"""application {app};
startFrom startTime;
startTime 0;
stopAt endTime;
endTime {end_time!r};
deltaT {dt!r};
writeControl adjustableRunTime;
writeInterval {write_interval!r};
purgeWrite 0;
writeFormat ascii;
writePrecision 12;
writeCompression off;
timeFormat general;
timePrecision 8;
runTimeModifiable no;
adjustTimeStep {'yes' if adjustable else 'no'};
maxCo {max_co!r};
maxAlphaCo {max_alpha_co!r};
maxDeltaT {max_dt!r};
{extra}
""")


def fv_schemes(case, extra_div="", alpha="alpha.metal"):
    """snGrad(alpha) and snGrad(rho) uncorrected: the surface forces' and gravity's gradients (on
    refined meshes the corrected scheme's non-orthogonal part puts a force on a fluid at rest;
    on orthogonal meshes the two schemes are the same)."""
    dictionary(case, "system/fvSchemes", f"""ddtSchemes {{ default Euler; }}
gradSchemes {{ default Gauss linear; }}
divSchemes
{{
    default none;
    div(rhoPhi,U)  Gauss linearUpwind grad(U);
    div(phi,alpha)  Gauss vanLeer;
    div(phirb,alpha) Gauss linear;
    div(((rho*nuEff)*dev2(T(grad(U))))) Gauss linear;
    div(rhoCpPhi,T) Gauss vanLeer;
{extra_div}
}}
laplacianSchemes {{ default Gauss linear corrected; }}
interpolationSchemes {{ default linear; }}
snGradSchemes {{ default corrected; snGrad({alpha}) uncorrected; snGrad(rho) uncorrected; }}
""")


def fv_solution(case, alpha="alpha.metal", extra_solvers="", n_correctors=3, n_outer=1,
                momentum_predictor="no", p_ref_cell=None, alpha_tolerance=1e-10):
    """p_ref_cell: cell index of the pressure reference (closed domains), value 0.
    alpha_tolerance: 1e-14 conserves the metal mass to round-off (the MULESCorr predictor is
    only as conservative as its linear solve, doc/foam_meltdemFoam.rst)."""
    ref = "" if p_ref_cell is None else f"    pRefCell {p_ref_cell};\n    pRefValue 0;\n"
    dictionary(case, "system/fvSolution", f"""solvers
{{
    "{alpha}.*"
    {{
        nAlphaCorr 2; nAlphaSubCycles 1; cAlpha 1; MULESCorr yes; nLimiterIter 5;
        solver smoothSolver; smoother symGaussSeidel; tolerance {alpha_tolerance!r}; relTol 0;
    }}
    "pcorr.*" {{ solver PCG; preconditioner DIC; tolerance 1e-8; relTol 0; }}
    p_rgh {{ solver PCG; preconditioner DIC; tolerance 1e-9; relTol 0.01; }}
    p_rghFinal {{ $p_rgh; relTol 0; }}
    "U.*" {{ solver smoothSolver; smoother symGaussSeidel; tolerance 1e-9; relTol 0; }}
    "T.*" {{ solver PBiCGStab; preconditioner DILU; tolerance 1e-10; relTol 0; }}
{extra_solvers}
}}
PIMPLE
{{
    momentumPredictor {momentum_predictor};
    nOuterCorrectors {n_outer};
    nCorrectors {n_correctors};
    nNonOrthogonalCorrectors 0;
{ref}}}
relaxationFactors {{ equations {{ ".*" 1; }} }}
""")


def transport(case, rho_metal, nu_metal, rho_gas, nu_gas, sigma):
    dictionary(case, "constant/transportProperties", f"""phases (metal gas);
metal {{ transportModel Newtonian; nu {nu_metal!r}; rho {rho_metal!r}; }}
gas {{ transportModel Newtonian; nu {nu_gas!r}; rho {rho_gas!r}; }}
sigma {sigma!r};
""")
    dictionary(case, "constant/turbulenceProperties", "simulationType laminar;\n")


def gravity(case, g=(0.0, 0.0, 0.0)):
    write(case, "constant/g", "uniformDimensionedVectorField", "g",
          f"dimensions [0 1 -2 0 0 0 0];\nvalue ({g[0]!r} {g[1]!r} {g[2]!r});\n")


def run(cmd, case, log, env=None, check=True):
    e = dict(os.environ)
    e.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    e["PWD"] = os.path.abspath(case)
    if env:
        e.update(env)
    with open(os.path.join(case, log), "w") as f:
        r = subprocess.run(cmd, cwd=case, stdout=f, stderr=subprocess.STDOUT, env=e)
    if check and r.returncode != 0:
        with open(os.path.join(case, log)) as f:
            tail = f.read()[-3000:]
        raise RuntimeError(f"{' '.join(cmd)} failed (rc {r.returncode}) in {case}:\n{tail}")
    return r.returncode


def read_internal(path):
    """Internal field of an ascii OpenFOAM field file (scalar or vector) as a numpy array."""
    with open(path) as f:
        txt = f.read()
    i = txt.index("internalField")
    rest = txt[i + len("internalField"):].lstrip()
    if rest.startswith("uniform"):
        val = rest[len("uniform"):].split(";")[0].strip()
        if val.startswith("("):
            return np.array([float(t) for t in val.strip("()").split()])
        return np.array(float(val))
    # nonuniform List<type> N ( ... )
    j = rest.index("(")
    k = rest.index("\n)", j)
    body = rest[j + 1:k]
    if "List<vector>" in rest[:j]:
        return np.array([[float(t) for t in line.strip().strip("()").split()]
                         for line in body.strip().splitlines() if line.strip()])
    return np.array([float(t) for t in body.split()])


def time_dirs(case):
    out = []
    for d in os.listdir(case):
        try:
            out.append((float(d), d))
        except ValueError:
            pass
    return [d for _, d in sorted(out)]


def subsampled_fraction(grid, inside, nsub=8):
    """Fraction of each cell where inside(x, y) holds, from nsub^2 points per cell."""
    s = (np.arange(nsub) + 0.5) / nsub - 0.5
    a = np.zeros(grid.x.size)
    for sx in s:
        for sy in s:
            a += inside(grid.x + sx * grid.dx, grid.y + sy * grid.dy)
    return a / nsub ** 2


def smooth_alpha_disc(grid, xc, yc, r, width=None, nsub=8):
    """Volume fraction of a disc of radius r by sub-sampling each cell (nsub^2 points)."""
    return subsampled_fraction(grid, lambda px, py: (px - xc) ** 2 + (py - yc) ** 2 <= r * r, nsub)


def alpha_rect(grid, x0, x1, y0, y1, nsub=8):
    """Volume fraction of the rectangle [x0, x1] x [y0, y1] by sub-sampling each cell."""
    return subsampled_fraction(grid, lambda px, py: (px >= x0) & (px <= x1) & (py >= y0) & (py <= y1), nsub)


# Fuchs2022 tables 1-3 (stainless steel near Tm = 1700 K, atmospheric gas scaled as there)
METAL = dict(rho=7430.0, mu=6.0e-3, cp=965.0, k=35.95, sigma0=1.8, dSigmadT=-1.0e-3, Tsigma0=1700.0,
             sigmaMin=0.2, Tm=1700.0)
GAS = dict(rho=7.43, mu=6.0e-4, cp=10.0, k=0.026)

PHYSICS_OFF = dict(flow="on", energy="off", darcy="off", surfaceTension="on", marangoni="off",
                   recoil="off", laser="off", evaporation="off", buoyancy="off")


def meltdem_properties(case, physics=None, surface=None, extra=""):
    """constant/meltdemProperties as FOAM.md lays it out; physics overrides PHYSICS_OFF,
    surface overrides the surfaceTension entries of METAL (e.g. nSmooth)."""
    ph = dict(PHYSICS_OFF)
    ph.update(physics or {})
    st = {k: METAL[k] for k in ("sigma0", "dSigmadT", "Tsigma0", "sigmaMin")}
    st.update(surface or {})
    body = "physics\n{\n" + "".join(f"    {k} {v};\n" for k, v in ph.items()) + "}\n"
    body += "surfaceTension\n{\n" + "".join(f"    {k} {v!r};\n" for k, v in st.items()) + "}\n"
    body += extra
    dictionary(case, "constant/meltdemProperties", body)


def set_physics(case, **switches):
    """Set physics{} switches (e.g. marangoni="off") of a written CASE/constant/meltdemProperties;
    a switch the case does not list is an error (KeyError), not silently added."""
    import re
    path = os.path.join(case, "constant", "meltdemProperties")
    text = open(path).read()
    block = re.search(r"^physics\s*\{(.*?)^\}", text, re.S | re.M)
    body = block.group(1)
    for name, value in switches.items():
        body, n = re.subn(rf"^(\s*{name}\s+)\w+;", rf"\g<1>{value};", body, flags=re.M)
        if n != 1:
            raise KeyError(f"physics switch '{name}' not in {path}")
    open(path, "w").write(text[:block.start(1)] + body + text[block.end(1):])


def solver():
    """The solver under test: $MELTDEM_FOAM_SOLVER (to try a case with another build) or
    $MELTDEM_BIN/meltdemFoam."""
    return os.environ.get("MELTDEM_FOAM_SOLVER") or paths.binary("meltdemFoam")


def contour_radii(grid, alpha, xc, yc, level=0.5):
    """Distances from (xc, yc) of the points of the alpha = level contour (matplotlib)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cs = plt.contour(grid.X, grid.Y, alpha.reshape(grid.ny, grid.nx), [level])
    segs = [s for s in cs.allsegs[0] if len(s)]
    plt.close("all")
    pts = np.vstack(segs)
    return np.hypot(pts[:, 0] - xc, pts[:, 1] - yc)


def finish(ok, work, keep=False, shown=None):
    """End of a case-based test: remove the scratch folder when the test passed (and it is
    not to be kept), otherwise say where the cases are; returns the exit code."""
    import shutil
    if ok and not keep:
        shutil.rmtree(work)
    else:
        print("case(s) kept in", shown or work)
    return 0 if ok else 1


CELL_GEOMETRY_ENTRIES = """    centres { type writeCellCentres; libs (fieldFunctionObjects); writeControl writeTime; }
    volumes { type writeCellVolumes; libs (fieldFunctionObjects); writeControl writeTime; }
"""
CELL_GEOMETRY_FUNCTIONS = "functions\n{\n" + CELL_GEOMETRY_ENTRIES + "}\n"
"""controlDict functions of a refining run: each write time's cell centres C and volumes V, for
lattice_field (the entries alone: CELL_GEOMETRY_ENTRIES, to join other function objects)."""


def lattice_field(case, time, name, n_fine, h, origin=(0.0, 0.0, 0.0)):
    """A written field on the lattice of the finest cells (n_fine = (nx, ny, nz) cells of h from
    origin), as an (nz, ny, nx) array: as written on a uniform mesh; on a refined one (the time has
    the C and V of CELL_GEOMETRY_FUNCTIONS) each cell's value fills the finest cells it covers."""
    nx, ny, nz = n_fine
    values = np.asarray(read_internal(os.path.join(case, time, name)), dtype=float)
    if not os.path.exists(os.path.join(case, time, "C")):
        return (values * np.ones(nx * ny * nz)).reshape(nz, ny, nx)
    C = np.asarray(read_internal(os.path.join(case, time, "C")), dtype=float).reshape(-1, 3)
    V = np.asarray(read_internal(os.path.join(case, time, "V")), dtype=float) * np.ones(len(C))
    values = values * np.ones(len(C))
    span = np.rint(np.cbrt(V) / h).astype(int)            # finest cells per edge of each cell
    lo = np.rint((C - 0.5 * span[:, None] * h - np.asarray(origin)) / h).astype(int)
    return _fill_lattice((nz, ny, nx), lo.T, span, values)


def peak_metal_temperature(case, times, n_fine, h, origin, floor):
    """Max over the written times of T where the cell holds metal (alpha.metal >= 1/2), elsewhere
    `floor`, on the finest cells' lattice (lattice_field), as an (nz, ny, nx) array."""
    tmax = np.full(tuple(n_fine)[::-1], float(floor))
    for d in times:
        T, a = (np.nan_to_num(lattice_field(case, d, name, n_fine, h, origin), nan=floor)
                for name in ("T", "alpha.metal"))
        tmax = np.maximum(tmax, np.where(a >= 0.5, T, floor))
    return tmax


def _fill_lattice(shape, lo, span, values):
    """An array of `shape` (nz, ny, nx) where each cell's value fills the span^3 finest cells from
    its lowest one lo = (ix, iy, iz) (NaN where no cell is)."""
    out = np.full(shape, np.nan)
    for s in np.unique(span):
        sel = np.nonzero(span == s)[0]
        for dz in range(s):
            for dy in range(s):
                for dx in range(s):
                    out[lo[2][sel] + dz, lo[1][sel] + dy, lo[0][sel] + dx] = values[sel]
    return out


def graded_lattice_field(case, time, name, base_faces, levels):
    """A written field on the lattice of the finest cells of a graded block (base_faces = the x, y, z
    face coordinates of the base mesh, every base cell cut into 2^levels per axis), as an (nz, ny, nx)
    array: as written on the base mesh; on a refined one (the time has the C and V of
    CELL_GEOMETRY_FUNCTIONS) each cell fills the finest cells it covers, found from its base cell and
    its level (hexRef8 halves every edge)."""
    k = 2 ** levels
    n_base = [len(f) - 1 for f in base_faces]
    values = np.asarray(read_internal(os.path.join(case, time, name)), dtype=float)
    if not os.path.exists(os.path.join(case, time, "C")):
        values = (values * np.ones(int(np.prod(n_base)))).reshape(n_base[::-1])
        return values.repeat(k, axis=0).repeat(k, axis=1).repeat(k, axis=2)
    C = np.asarray(read_internal(os.path.join(case, time, "C")), dtype=float).reshape(-1, 3)
    V = np.asarray(read_internal(os.path.join(case, time, "V")), dtype=float) * np.ones(len(C))
    values = values * np.ones(len(C))
    base = [np.clip(np.searchsorted(f, C[:, d]) - 1, 0, len(f) - 2) for d, f in enumerate(base_faces)]
    widths = [np.diff(f)[i] for f, i in zip(base_faces, base)]
    level = np.rint(np.log2(widths[0] * widths[1] * widths[2] / V) / 3).astype(int)
    span = k >> level                                      # finest cells per edge of each cell
    lo = [i * k + np.floor((C[:, d] - f[i]) / w * (1 << level)).astype(int) * span
          for d, (f, i, w) in enumerate(zip(base_faces, base, widths))]
    return _fill_lattice([n * k for n in n_base[::-1]], lo, span, values)


def refinement_ledger(case):
    """The mesh changes of a refining run (postProcessing/refinement/<start>/refinement.csv of every
    start), one row each, and the worst |after/before - 1| of metal and enthalpy over them."""
    import glob
    rows = [np.atleast_1d(np.genfromtxt(f, delimiter=",", names=True))
            for f in sorted(glob.glob(os.path.join(case, "postProcessing", "refinement", "*", "refinement.csv")))]
    if not rows:
        raise FileNotFoundError(f"{case}: no postProcessing/refinement/*/refinement.csv (no mesh change booked)")
    ref = np.concatenate(rows)
    worst = max(float(np.max(np.abs(ref[f"{c}After"] / ref[f"{c}Before"] - 1))) for c in ("metal", "enthalpy"))
    return ref, worst


def refinement_dict(levels, interval, criteria, buffer_layers=1):
    """refinement{} of constant/meltdemProperties (doc/foam_refinement.rst): criteria = [(name, entries)],
    each asking for the finest level (`level <levels>;` is added before its entries)."""
    body = "".join(f"        {name:<8} {{ level {levels}; {entries} }}\n" for name, entries in criteria)
    return f"""refinement
{{
    maxLevel        {levels};
    refineInterval  {interval};
    nBufferLayers   {buffer_layers};
    criteria
    {{
{body}    }}
}}
"""


def fluid_steps(case, log="log.meltdemFoam"):
    """The number of time steps in CASE/log (its 'Time = ' lines)."""
    with open(os.path.join(case, log), errors="replace") as f:
        return sum(1 for line in f if line.startswith("Time = "))


def execution_time(case, log="log.meltdemFoam"):
    """The solver's last ExecutionTime in CASE/log [s] (CPU of the master rank); None if none."""
    import re
    path = os.path.join(case, log)
    cpu = re.findall(r"ExecutionTime = (\S+) s", open(path).read()) if os.path.exists(path) else []
    return float(cpu[-1]) if cpu else None


def temperature_range(case, log="log.solver"):
    """The coldest and hottest cell over a meltdemFoam run: the extremes of its log's 'T min/max'
    lines [K]."""
    import re
    pairs = re.findall(r"T min/max = (\S+), (\S+)", open(os.path.join(case, log)).read())
    return min(float(a) for a, _ in pairs), max(float(b) for _, b in pairs)


def reconstruct_commands(case, fields=None):
    """[(command, log)] that reconstruct the decomposed times the case folder lacks: where the mesh
    changed (adaptive refinement writes processorN/<time>/polyMesh) reconstructParMesh first, which
    also writes the addressing reconstructPar needs; then reconstructPar (of `fields` only, if given).
    Empty when there is nothing new."""
    proc0 = os.path.join(case, "processor0")
    new = [d for d in time_dirs(proc0) if not os.path.isdir(os.path.join(case, d))]
    if not new:
        return []
    changed = [d for d in new if os.path.isdir(os.path.join(proc0, d, "polyMesh"))]
    cmds = [(["reconstructParMesh", "-mergeTol", "1e-6", "-time", ",".join(changed)], "log.reconstructParMesh")]
    cmds = cmds if changed else []
    select = ["-fields", "(" + " ".join(fields) + ")"] if fields else []
    return cmds + [(["reconstructPar", "-time", ",".join(new)] + select, "log.reconstructPar")]


def reconstruct(case, fields=None, check=True):
    """Run reconstruct_commands(case, fields)."""
    for cmd, log in reconstruct_commands(case, fields):
        run(cmd, case, log, check=check)


def most_cells(case, base_cells):
    """The most cells the mesh had (the refinement ledger's cellsAfter; the base mesh without one)."""
    import glob
    if not glob.glob(os.path.join(case, "postProcessing", "refinement", "*", "refinement.csv")):
        return int(base_cells)
    rows, _ = refinement_ledger(case)
    return int(max([base_cells] + [int(r["cellsAfter"]) for r in rows]))


def decompose(case, np_, direction=(1, 2, 1)):
    """decomposePar -force into np_ subdomains, method simple with n = direction."""
    dictionary(case, "system/decomposeParDict", f"""numberOfSubdomains {np_};
method simple;
coeffs {{ n ({direction[0]} {direction[1]} {direction[2]}); }}
""")
    run(["decomposePar", "-force"], case, "log.decomposePar")


MPIRUN_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def solver_command(np_=1):
    """The solver's command line: serial, or on np_ ranks with mpirun -parallel (env: MPIRUN_ENV)."""
    if np_ == 1:
        return [solver()]
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_), solver(), "-parallel"]


def run_solver(case, np_=1, log="log.meltdemFoam", check=True):
    """The solver serial or on np_ ranks (solver_command); its return code."""
    return run(solver_command(np_), case, log, env=MPIRUN_ENV, check=check)


def run_scene_case(case, np_, name, decomposition=None):
    """blockMesh, then meltdemFoam serial or on np_ ranks (decomposePar `simple` along x unless
    decomposition (nx ny nz) is given; reconstructed after), the wall time and return code booked in
    CASE/scene.json; raises RuntimeError with the log's tail when the solver fails."""
    import json
    import time
    t0 = time.time()
    run(["blockMesh"], case, "log.blockMesh")
    if np_ > 1:
        decompose(case, np_, decomposition or (np_, 1, 1))
    rc = run_solver(case, np_, check=False)
    if np_ > 1 and rc == 0:
        reconstruct(case)          # reconstructParMesh first on the times a refinement changed
    wall = time.time() - t0
    path = os.path.join(case, "scene.json")
    meta = json.load(open(path))
    meta.update(wall_seconds=wall, np=np_, rc=rc)
    json.dump(meta, open(path, "w"), indent=1)
    if rc != 0:
        tail = open(os.path.join(case, "log.meltdemFoam")).read()[-3000:]
        raise RuntimeError(f"meltdemFoam failed (rc {rc}) in {case}:\n{tail}")
    print(f"{name}: ran in {wall:.0f} s")
    return wall
