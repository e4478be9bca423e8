#!/usr/bin/env python3
"""meltdem post (python/meltdem/cli/post.py) on real runs, checked against the files the run wrote:

(a) coupled: the CI pbf-point scene (examples/pbf-point) cut to 8 us (grains start melting at
    7.2 us), serial: VTK/fields.pvd and VTK/particles.pvd parse, every file they name exists
    and parses; one field entry per OpenFOAM write time with the mesh's cell count and the
    written alpha.metal values; one particle entry per CASE/particles/<time>.dump with its
    particle count, positions and temperatures; the plots are PNG files; summary.json's melted
    mass equals the ledger's (sum of mass_exchange), its absorbed laser energy the balance rows'
    + the particles', its balance errors the ledger's worst;
(b) decomposed: the same case decomposed at its last time with only time 0 in the case folder:
    fields.pvd from the processor folders (mpirun foamToVTK -parallel), same cells and metal;
(c) DEM only: examples/powder-pour/in.pour with a dump without ITEM: TIME (its own removed) for 0.2 ms: one
    .vtp per frame with the frame's particles, times step x timestep, a packing fraction; run as
    two runs with the timestep doubled between them: each frame's time from its run's timestep.
"""
import glob
import os
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import numpy as np

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.cli import post
from meltdem.io import vtkxml
from meltdem.loader import load_module
from meltdem.paths import examples_dir
from meltdem.testing.report import check_absolute, check_at_least, check_at_most, check_relative, report

SRC = paths.source_dir()

pbf = load_module(os.path.join(examples_dir(), "pbf-point", "pbf.py"))

TEST = "cli.postprocess"
END, WRITE = 8e-6, 2e-6


def referenced_files(pvd):
    """Every file a .pvd names, and for .vtm blocks the files they name, recursively; each parsed
    with xml.etree (raises on a broken file). Returns (paths, missing)."""
    seen, missing = [], []
    todo = [p for _, p in vtkxml.read_pvd(pvd)]
    while todo:
        p = todo.pop(0)
        if not os.path.exists(p):
            missing.append(p)
            continue
        root = ET.parse(p).getroot()
        seen.append(p)
        if root.get("type") == "vtkMultiBlockDataSet":
            base = os.path.dirname(p)
            todo += [os.path.join(base, d.get("file")) for d in root.iter("DataSet") if d.get("file")]
    return seen, missing


def check_pvd(name, pvd):
    ok = report(TEST, f"{name}: {os.path.basename(pvd)} exists", os.path.exists(pvd), True, "exact",
                os.path.exists(pvd))
    if not ok:
        return False, []
    entries = vtkxml.read_pvd(pvd)
    files, missing = referenced_files(pvd)
    ok &= check_absolute(TEST, f"{name}: files named by {os.path.basename(pvd)} (and its .vtm) missing",
                         len(missing), 0, 0)
    ok &= check_at_least(TEST, f"{name}: files named and parsed as XML", len(files), len(entries))
    return ok, entries


def n_cells(case):
    head = open(os.path.join(case, "constant", "polyMesh", "owner")).read(2000)
    return int(re.search(r"nCells:\s*(\d+)", head).group(1))


def is_png(path):
    return os.path.exists(path) and open(path, "rb").read(8) == b"\x89PNG\r\n\x1a\n"


def dump_frame(path):
    """(time, columns, data) of a one-frame dump, read here independently of the tool."""
    lines = open(path).read().splitlines()
    t = float(lines[lines.index("ITEM: TIME") + 1]) if "ITEM: TIME" in lines else None
    k = next(i for i, line in enumerate(lines) if line.startswith("ITEM: NUMBER OF ATOMS"))
    n = int(lines[k + 1])
    a = next(i for i, line in enumerate(lines) if line.startswith("ITEM: ATOMS"))
    cols = lines[a].split()[2:]
    data = np.array([r.split() for r in lines[a + 1:a + 1 + n]], float).reshape(n, len(cols))
    return t, cols, data


def coupled(work):
    case = os.path.join(work, "pbf")
    pbf.build(case, "point-ci")
    cd = os.path.join(case, "system", "controlDict")
    txt = open(cd).read()
    txt = re.sub(r"^endTime .*;", f"endTime {END!r};", txt, flags=re.M)
    txt = re.sub(r"^writeInterval .*;", f"writeInterval {WRITE!r};", txt, flags=re.M)
    open(cd, "w").write(txt)
    pbf.run(case, 1, 240)
    s = post.postprocess(case)
    print(f"post-processing took {s['postprocess_seconds']} s")
    ok = True

    # continuum fields
    good, entries = check_pvd("coupled", os.path.join(case, "VTK", "fields.pvd"))
    ok &= good
    tds = fc.time_dirs(case)
    ok &= check_absolute(TEST, "coupled: fields.pvd entries vs OpenFOAM write times", len(entries), len(tds), 0)
    ok &= check_absolute(TEST, "coupled: last field time [s] vs last write time", entries[-1][0], float(tds[-1]), 1e-12)
    from meltdem.io import vtk_fields
    _, f, piece = vtk_fields.read_internal(entries[-1][1])
    nc = n_cells(case)
    ok &= check_absolute(TEST, "coupled: cells of the last internal .vtu vs the mesh's (polyMesh/owner)",
                         int(piece["attrib"]["NumberOfCells"]), nc, 0)
    a_foam = fc.read_internal(os.path.join(case, tds[-1], "alpha.metal")) * np.ones(nc)
    ok &= check_at_most(TEST, "coupled: max |alpha.metal in the .vtu - in the time folder| (Float32)",
                        float(np.max(np.abs(f["alpha.metal"] - a_foam))), 1e-6)

    # particles
    good, pentries = check_pvd("coupled", os.path.join(case, "VTK", "particles.pvd"))
    ok &= good
    dumps = sorted(glob.glob(os.path.join(case, "particles", "*.dump")), key=lambda p: float(os.path.basename(p)[:-5]))
    ok &= check_absolute(TEST, "coupled: particles.pvd entries vs CASE/particles/*.dump", len(pentries), len(dumps), 0)
    for k in (0, len(dumps) - 1):
        t, cols, data = dump_frame(dumps[k])
        p = vtkxml.read_piece(pentries[k][1])
        ok &= check_absolute(TEST, f"coupled: particles in .vtp {k} vs its dump", int(p["attrib"]["NumberOfPoints"]),
                             len(data), 0)
        ok &= check_relative(TEST, f"coupled: time of particle entry {k} [s] vs the dump's ITEM: TIME", pentries[k][0],
                             t, 1e-12)
        xyz = data[:, [cols.index("x"), cols.index("y"), cols.index("z")]]
        ok &= check_at_most(TEST, f"coupled: max |position in .vtp {k} - dump| [m]",
                            float(np.max(np.abs(p["points"] - xyz))), 0.0)
        ok &= check_at_most(TEST, f"coupled: max |temperature in .vtp {k} - dump f_melt[1]| [K]",
                            float(np.max(np.abs(p["point_data"]["temperature"] - data[:, cols.index("f_melt[1]")]))),
                            0.0)
        ok &= check_at_most(TEST, f"coupled: max |diameter - 2 radius| in .vtp {k} [m]",
                            float(np.max(np.abs(p["point_data"]["diameter"] - 2 * data[:, cols.index("radius")]))), 0.0)

    # plots
    for name in ("balances", "melted_mass", "absorbed_power"):
        path = os.path.join(case, "plots", name + ".png")
        ok &= report(TEST, f"coupled: plots/{name}.png is a PNG", is_png(path), True, "exact", is_png(path))

    # summary against the run's own files
    led = np.genfromtxt(os.path.join(case, "postProcessing", "particleLedger", "ledger.csv"), delimiter=",", names=True)
    pcsv = np.genfromtxt(os.path.join(case, "postProcessing", "particleLedger", "particles.csv"), delimiter=",",
                         names=True)
    bal = np.genfromtxt(os.path.join(case, "postProcessing", "particleBalance", "0", "balance.csv"), delimiter=",",
                        names=True)
    melted = float(np.sum(led["mass_exchange"]))
    ok &= check_at_least(TEST, "coupled: metal handed over by 8 us [kg] (grains melt from 7.2 us)", melted, 1e-12)
    ok &= check_relative(TEST, "coupled: summary melted mass [kg] vs ledger sum(mass_exchange)",
                         s["melted_mass_kg"], melted, 1e-12)
    e_ref = float(bal["laserEnergy_cum"][-1] + np.sum(pcsv["laser_heat"]))
    ok &= check_relative(TEST, "coupled: summary absorbed laser energy [J] vs balance + particles.csv",
                         s["laser_energy_absorbed_J"], e_ref, 1e-12)
    ok &= check_relative(TEST, "coupled: summary worst per-step system mass error vs ledger",
                         s["worst_step_system_mass_error"], float(np.max(np.abs(led["mass_system_error"][1:]))), 1e-12)
    ok &= check_relative(TEST, "coupled: summary simulated time [s] vs end time", s["simulated_time_s"], END, 0.01)
    keys = ("simulated_time_s", "wall_time_s", "melted_mass_kg", "laser_energy_absorbed_J",
            "worst_step_system_mass_error", "worst_step_system_energy_error", "cumulative_system_mass_error",
            "cumulative_system_energy_error", "particles_first_frame")
    bad = [k for k in keys if not (isinstance(s.get(k), (int, float)) and np.isfinite(s[k]))]
    ok &= report(TEST, "coupled: summary.json keys missing or not finite", ",".join(bad) or "none", "none", "exact",
                 not bad)
    md = os.path.exists(os.path.join(case, "summary.md"))
    ok &= report(TEST, "coupled: summary.md written", md, True, "exact", md)
    return ok, case, a_foam, nc


def decomposed(work, case, a_foam, nc):
    dcase = os.path.join(work, "pbf-decomposed")
    os.makedirs(dcase)
    last = fc.time_dirs(case)[-1]
    for d in ("system", "constant", "0", last):
        shutil.copytree(os.path.join(case, d), os.path.join(dcase, d))
    fc.dictionary(dcase, "system/decomposeParDict", "numberOfSubdomains 2;\nmethod simple;\ncoeffs { n (2 1 1); }\n")
    fc.run(["decomposePar", "-force", "-latestTime"], dcase, "log.decomposePar")
    shutil.rmtree(os.path.join(dcase, last))
    s = post.postprocess(dcase)
    good, entries = check_pvd("decomposed", os.path.join(dcase, "VTK", "fields.pvd"))
    ok = good
    ok &= check_absolute(TEST, "decomposed: last field time [s] vs the processors' last time", entries[-1][0],
                         float(last), 1e-12)
    from meltdem.io import vtk_fields
    _, f, piece = vtk_fields.read_internal(entries[-1][1])
    ok &= check_absolute(TEST, "decomposed: cells of the gathered .vtu vs the mesh's",
                         int(piece["attrib"]["NumberOfCells"]), nc, 0)
    ok &= check_relative(TEST, "decomposed: sum of alpha.metal over the cells vs the serial time folder",
                         float(np.sum(f["alpha.metal"])), float(np.sum(a_foam)), 1e-6)
    errs = [n for n in s["meltdem_post"]["notes"] if n.startswith("fields")]
    ok &= report(TEST, "decomposed: errors converting the fields", "; ".join(errs) or "none", "none", "exact", not errs)
    return ok


def moving_laser(work, case):
    """The coupled case's fields with its laser dictionary given a velocity (the fields stay those
    of the fixed beam): the track branch (cross-section at mid-track, bead profile, bead numbers)
    runs on real fields; the numbers are checked for presence and range only."""
    tcase = os.path.join(work, "pbf-track")
    shutil.copytree(case, tcase, ignore=shutil.ignore_patterns("VTK", "plots", "summary.*", "pbf.json"))
    mp = os.path.join(tcase, "constant", "meltdemProperties")
    txt = open(mp).read()
    txt = re.sub(r"(\n\s*position\s*\()([^ ]+)", r"\n    velocity (5 0 0);\n    tStart 2e-6;\1 4e-05", txt, count=1)
    open(mp, "w").write(txt)
    s = post.postprocess(tcase)
    png = os.path.join(tcase, "plots", "bead_profile.png")
    ok = report(TEST, "moving laser: plots/bead_profile.png is a PNG", is_png(png), True, "exact", is_png(png))
    bad = [k for k in ("bead_width_m", "bead_height_m", "penetration_m")
           if not (isinstance(s.get(k), float) and 0.0 <= s[k] <= 140e-6)]
    ok &= report(TEST, "moving laser: bead numbers missing or outside [0, domain height]", ",".join(bad) or "none",
                 "none", "exact", not bad)
    return ok


def dem_only(work):
    case = os.path.join(work, "pour")
    os.makedirs(case)
    txt = open(os.path.join(SRC, "examples", "powder-pour", "in.pour")).read()
    # in.pour's own dump carries ITEM: TIME; this one has none (frame times from the log's steps)
    txt = re.sub(r"^dump(_modify)?\s+pour\b.*\n", "", txt, flags=re.M)
    txt = re.sub(r"^run ", "dump            d all custom 2000 pour.dump id type x y z vx vy vz radius mass\nrun ",
                 txt, flags=re.M)
    open(os.path.join(case, "in.pour"), "w").write(txt)
    subprocess.run([paths.binary("meltdem-lmp"), "-in", "in.pour", "-var", "nsteps", "20000",
                    "-log", "log.lammps", "-screen", "none"], cwd=case, check=True)
    s = post.postprocess(case)
    good, entries = check_pvd("dem", os.path.join(case, "VTK", "particles.pvd"))
    ok = good
    text = open(os.path.join(case, "pour.dump")).read()
    steps = [int(v) for v in re.findall(r"ITEM: TIMESTEP\n(\d+)", text)]
    counts = [int(v) for v in re.findall(r"ITEM: NUMBER OF ATOMS\n(\d+)", text)]
    ok &= check_absolute(TEST, "dem: particles.pvd entries vs dump frames", len(entries), len(steps), 0)
    got = [int(vtkxml.read_piece(p)["attrib"]["NumberOfPoints"]) for _, p in entries]
    ok &= check_absolute(TEST, "dem: frames whose .vtp particle count differs from the dump's",
                         sum(a != b for a, b in zip(got, counts)), 0, 0)
    ok &= check_at_least(TEST, "dem: particles in the last frame (poured)", got[-1], 1)
    ok &= check_relative(TEST, "dem: last entry time [s] vs step x timestep 1e-8 (the dump has no ITEM: TIME)",
                         entries[-1][0], steps[-1] * 1e-8, 1e-12)
    nofields = not os.path.exists(os.path.join(case, "VTK", "fields.pvd"))
    ok &= report(TEST, "dem: no fields.pvd (no mesh)", nofields, True, "exact", nofields)
    pf = s.get("packing_fraction", float("nan"))
    ok &= report(TEST, "dem: packing fraction of the last frame in (0, 0.74]", pf, "(0, 0.74]", "range",
                 bool(0 < pf <= 0.74))
    ok &= check_absolute(TEST, "dem: summary particles in the last frame vs the dump", s["particles_last_frame"],
                         counts[-1], 0)

    # the same input run as 10000 steps of 1e-8 s, then `timestep 2e-8` and 10000 more: each frame's time
    # from the timestep of its run (was step x the last timestep: 4e-4 instead of 3e-4 s at the end)
    two = os.path.join(work, "pour-two-steps")
    os.makedirs(two)
    open(os.path.join(two, "in.pour"), "w").write(
        re.sub(r"^run\s+\$\{nsteps\}", "run 10000\ntimestep 2e-8\nrun 10000", txt, count=1, flags=re.M))
    subprocess.run([paths.binary("meltdem-lmp"), "-in", "in.pour", "-log", "log.lammps", "-screen", "none"],
                   cwd=two, check=True)
    s2 = post.postprocess(two)
    good, entries = check_pvd("dem, two timesteps", os.path.join(two, "VTK", "particles.pvd"))
    ok &= good
    text = open(os.path.join(two, "pour.dump")).read()
    steps = [int(v) for v in re.findall(r"ITEM: TIMESTEP\n(\d+)", text)]
    want = [k * 1e-8 if k <= 10000 else 1e-4 + (k - 10000) * 2e-8 for k in steps]
    worst = max(abs(t - w) for (t, _), w in zip(entries, want)) if len(entries) == len(steps) else float("inf")
    ok &= check_at_most(TEST, f"dem, timestep 1e-8 then 2e-8: frames' largest time error [s] ({len(steps)} frames)",
                        worst, 1e-15)
    ok &= check_relative(TEST, "dem, timestep 1e-8 then 2e-8: simulated time [s] (1e4 x 1e-8 + 1e4 x 2e-8)",
                         s2.get("simulated_time_s", float("nan")), 3e-4, 1e-12)
    return ok


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-post-")
    ok, case, a_foam, nc = coupled(work)
    ok &= decomposed(work, case, a_foam, nc)
    ok &= moving_laser(work, case)
    ok &= dem_only(work)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
