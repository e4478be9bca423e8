#!/usr/bin/env python3
"""The new user's path (README "First run"): `meltdem list`, `meltdem run powder-pour` and
`meltdem check` in an empty folder, from a shell that has set nothing (no MELTDEM_* or
WM_PROJECT_DIR variables), then the outputs: the LAMMPS log, the ParaView series of the grains
(every frame a valid VTK file with all 300 poured grains at the end, resting on the plate inside
the box) and the summary (packing fraction of a poured bed of equal spheres, between random
loose 0.55 and random close 0.64, with a margin for the bed's rough top surface).
"""
import base64
import json
import os
import re
import struct
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

from meltdem import paths
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_least, check_at_most

SRC = paths.source_dir()
BIN = paths.bin_dir()

TEST = "cli.new_user"
GRAINS, END, BOX_XY, DIAMETER = 300, 1e-3, 3e-4, 30e-6   # examples/powder-pour/in.pour
NEW_USER_ENV = {"PATH": "/usr/local/bin:/usr/bin:/bin", "HOME": os.environ.get("HOME", "/root"),
                # mpirun as root (CI runs as root); a user account needs neither
                "OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1"}


def meltdem(work, *args):
    p = subprocess.run([os.path.join(BIN, "meltdem"), *args], cwd=work, env=NEW_USER_ENV,
                       stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    print(f"$ meltdem {' '.join(args)}\n{p.stdout}")
    return p.returncode, p.stdout


def points(vtp):
    """(number of points, z coordinates) of a .vtp with ascii or inline base64 Float32/64 points,
    decoded here from the VTK XML format itself (not with the writer's own reader)."""
    root = ET.parse(vtp).getroot()
    piece = root.find(".//Piece")
    n = int(piece.get("NumberOfPoints"))
    arr = piece.find("Points/DataArray")
    if arr.get("format") == "ascii":
        xyz = [float(v) for v in arr.text.split()]
    else:
        raw = base64.b64decode("".join(arr.text.split()))
        head = 8 if root.get("header_type", "UInt32") == "UInt64" else 4
        size = struct.unpack("<Q" if head == 8 else "<I", raw[:head])[0]
        code = {"Float32": "f", "Float64": "d"}[arr.get("type")]
        xyz = struct.unpack(f"<{size // struct.calcsize(code)}{code}", raw[head:head + size])
    if len(xyz) != 3 * n:
        raise ValueError(f"{vtp}: {len(xyz)} coordinates for {n} points")
    return n, list(xyz[2::3])


def main():
    keep = "--keep" in sys.argv
    work = tempfile.mkdtemp(prefix="meltdem-new-user-")
    ok = True

    rc, out = meltdem(work, "list")
    ok &= check_absolute(TEST, "`meltdem list` exit code", rc, 0, 0)
    examples = sorted(d for d in os.listdir(os.path.join(SRC, "examples"))
                      if os.path.isdir(os.path.join(SRC, "examples", d)) and not d.startswith("_"))
    listed = [e for e in examples if re.search(rf"^{re.escape(e)}\s", out, re.M)]
    ok &= check_absolute(TEST, "examples `meltdem list` shows, of those in examples/", len(listed), len(examples), 0)

    rc, out = meltdem(work, "run", "powder-pour")
    ok &= check_absolute(TEST, "`meltdem run powder-pour` exit code", rc, 0, 0)
    case = os.path.join(work, "powder-pour")
    ok &= check_absolute(TEST, "progress line reached 100 % (simulated time / end time, steps/s, ETA)",
                         int(bool(re.search(r"t = .* / .* s \(100 %\)\s+\S+ steps/s\s+ETA", out))), 1, 0)
    log = os.path.join(case, "log.lammps")
    ok &= check_absolute(TEST, "log.lammps written and complete (Total wall time)",
                         int(os.path.exists(log) and "Total wall time" in open(log).read()), 1, 0)

    # ParaView: the particle series
    pvd = os.path.join(case, "VTK", "particles.pvd")
    ok &= check_absolute(TEST, "VTK/particles.pvd written", int(os.path.exists(pvd)), 1, 0)
    if os.path.exists(pvd):
        sets = ET.parse(pvd).getroot().findall(".//DataSet")
        ok &= check_absolute(TEST, "particle frames in particles.pvd (a dump every 0.1 ms over 1 ms)", len(sets), 11, 0)
        bad, last = 0, None
        for d in sets:
            f = os.path.join(os.path.dirname(pvd), d.get("file"))
            try:
                last = (float(d.get("timestep")),) + points(f)
            except (OSError, ET.ParseError, AttributeError, TypeError, ValueError):
                bad += 1
        ok &= check_absolute(TEST, "frames whose .vtp is missing or not valid VTK XML", bad, 0, 0)
        if last:
            ok &= check_absolute(TEST, "time of the last frame [s]", last[0], END, 1e-12)
            ok &= check_absolute(TEST, "grains in the last frame (all poured)", last[1], GRAINS, 0)
            ok &= check_at_least(TEST, "lowest grain centre in the last frame [m] (on the plate: >= r)",
                                 min(last[2]), 0.5 * DIAMETER * 0.99)

    summary = os.path.join(case, "summary.json")
    ok &= check_absolute(TEST, "summary.json written", int(os.path.exists(summary)), 1, 0)
    if os.path.exists(summary):
        s = json.load(open(summary))
        ok &= check_absolute(TEST, "summary: grains at the end", s.get("particles_last_frame", -1), GRAINS, 0)
        phi = s.get("packing_fraction", float("nan"))
        ok &= check_at_least(TEST, "summary: packing fraction of the poured bed (>= 0.45)", phi, 0.45)
        ok &= check_at_most(TEST, "summary: packing fraction of the poured bed (<= random close 0.64)", phi, 0.64)
        ok &= check_at_least(TEST, "summary: wall time [s] (> 0)", s.get("wall_time_s", 0.0), 1e-3)
    ok &= check_absolute(TEST, "summary.md written", int(os.path.exists(os.path.join(case, "summary.md"))), 1, 0)

    rc, out = meltdem(work, "check", "powder-pour")
    ok &= check_absolute(TEST, "`meltdem check powder-pour` exit code after the run", rc, 0, 0)
    return fc.finish(ok, work, keep)


if __name__ == "__main__":
    sys.exit(main())
