"""Continuum fields for ParaView: foamToVTK (Debian OpenFOAM v1912) into CASE/VTK/fields/ and
CASE/VTK/fields.pvd over its outputs.

foamToVTK v1912 writes, per time, an XML multiblock <case>_<index>.vtm (internal.vtu + the
boundary patches as .vtp, inline base64 binary) and a <case>.vtm.series (JSON, the times); the
.pvd lists the .vtm files with their times. Decomposed cases whose processor folders hold times
the case folder lacks are converted in place with 'mpirun -np N foamToVTK -parallel' (v1912
gathers the pieces into one file per time): the case is not reconstructed or changed, only
VTK/ is written."""
import glob
import json
import os
import re
import shutil
import subprocess

import numpy as np

from . import vtkxml


def _is_time(name):
    try:
        float(name)
        return True
    except ValueError:
        return False


def time_dirs(folder):
    """Time folders holding fields (names parse as numbers), in time order."""
    if not os.path.isdir(folder):
        return []
    out = [d for d in os.listdir(folder) if _is_time(d) and os.path.isdir(os.path.join(folder, d))]
    return sorted(out, key=float)


def processor_dirs(case):
    return sorted(glob.glob(os.path.join(case, "processor[0-9]*")),
                  key=lambda p: int(re.sub(r"\D", "", os.path.basename(p))))


def layout(case):
    """'serial' (time folders in the case) or ('parallel', N) when the processor folders hold
    later times than the case folder (an unreconstructed parallel run)."""
    procs = processor_dirs(case)
    root = [t for t in time_dirs(case)]
    if procs:
        pt = time_dirs(procs[0])
        if pt and (not root or float(pt[-1]) > float(root[-1])):
            return "parallel", len(procs)
    return "serial", 1


def foam_env():
    env = dict(os.environ)
    env.setdefault("WM_PROJECT_DIR", "/usr/share/openfoam")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT", "1")
    env.setdefault("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM", "1")
    return env


def run_foam_to_vtk(case, out_name="VTK/fields", log="log.foamToVTK"):
    """Run foamToVTK; returns (its output folder, the command). Raises RuntimeError naming the log."""
    exe = shutil.which("foamToVTK")
    if not exe:
        raise RuntimeError("foamToVTK not found on PATH (Debian package openfoam)")
    kind, n = layout(case)
    out = os.path.join(case, out_name)
    if os.path.isdir(out):
        shutil.rmtree(out)
    cmd = [exe, "-case", case, "-name", out_name]
    if kind == "parallel":
        cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(n)] + cmd + ["-parallel"]
    with open(os.path.join(case, log), "w") as f:
        r = subprocess.run(cmd, cwd=case, stdout=f, stderr=subprocess.STDOUT, env=foam_env())
    if r.returncode != 0:
        raise RuntimeError(f"foamToVTK failed (rc {r.returncode}): see {os.path.join(case, log)}")
    return out, cmd


def series_entries(out_dir):
    """[(time, .vtm path relative to out_dir)] from foamToVTK's .vtm.series (or its .vtm files)."""
    series = glob.glob(os.path.join(out_dir, "*.vtm.series"))
    entries = []
    if series:
        data = json.load(open(series[0]))
        entries = [(float(e["time"]), e["name"]) for e in data.get("files", [])]
    else:
        for p in glob.glob(os.path.join(out_dir, "*.vtm")):
            m = re.search(r"time='([^']+)'", open(p).read(400))
            if m:
                entries.append((float(m.group(1)), os.path.basename(p)))
    return sorted(entries)


def convert(case, out_dir=None):
    """foamToVTK + VTK/fields.pvd. Returns dict pvd, entries [(time, vtm)], layout, command,
    or None when the case has no mesh."""
    case = os.path.abspath(case)
    if not (os.path.exists(os.path.join(case, "constant", "polyMesh", "owner"))
            or glob.glob(os.path.join(case, "processor*", "constant", "polyMesh", "owner"))):
        return None
    vtk = out_dir or os.path.join(case, "VTK")
    os.makedirs(vtk, exist_ok=True)
    rel = os.path.relpath(os.path.join(vtk, "fields"), case)
    out, cmd = run_foam_to_vtk(case, rel)
    entries = series_entries(out)
    # a time folder without a field (a write cut short, a folder made by hand) is no written time
    kind, _ = layout(case)
    folder = processor_dirs(case)[0] if kind == "parallel" else case
    empty = {float(t) for t in time_dirs(folder) if not any(
        os.path.isfile(os.path.join(folder, t, f)) for f in os.listdir(os.path.join(folder, t)))}
    pvd_entries = [(t, f"fields/{name}") for t, name in entries if t not in empty]
    pvd = os.path.join(vtk, "fields.pvd")
    vtkxml.write_pvd(pvd, pvd_entries)
    return {"pvd": pvd, "entries": pvd_entries, "layout": kind, "command": " ".join(cmd),
            "empty_times": sorted(empty)}


def internal_piece(vtm_path):
    """Path of the internal mesh (.vtu) a foamToVTK .vtm names."""
    import xml.etree.ElementTree as ET
    root = ET.parse(vtm_path).getroot()
    base = os.path.dirname(vtm_path)
    for ds in root.iter("DataSet"):
        if ds.get("file", "").endswith(".vtu"):
            return os.path.join(base, ds.get("file"))
    return None


def read_internal(vtm_path):
    """(cell centres (n, 3), {field: cell values}, piece) of the internal mesh of one written time;
    centres = mean of each cell's points (exact for the hexahedra of blockMesh)."""
    piece = vtkxml.read_piece(internal_piece(vtm_path))
    conn = piece["cells"][("Cells", "connectivity")].astype(np.int64)
    offs = piece["cells"][("Cells", "offsets")].astype(np.int64)
    pts = piece["points"].astype(float)
    counts = np.diff(np.concatenate([[0], offs]))
    cell_of = np.repeat(np.arange(len(offs)), counts)
    centres = np.zeros((len(offs), 3))
    np.add.at(centres, cell_of, pts[conn])
    centres /= counts[:, None]
    return centres, piece["cell_data"], piece
