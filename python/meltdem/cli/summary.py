"""The per-run summary: CASE/summary.json and a short CASE/summary.md table.

Only what the case has: the ledger's melted mass, balance errors and powder feed (coupled runs),
the absorbed laser energy (meltdemBalance + particles.csv), the simulated and wall time, the
particles (ejected: centre above the initial bed top and moving up, in any frame), the packing
fraction of a DEM bed (meltdem.analysis.beds on the last frame), the bead of a track.
Where the example's own analysis (scene.py analyse / pbf.summary, which write CASE/summary.json
themselves) has a number, that number is taken as it is and its key named as the source; it is
run first when the example is known and its summary is missing. The scene's keys stay in
summary.json beside the common ones (a later post-processing keeps them)."""
import contextlib
import glob
import io
import json
import math
import os
import re

import numpy as np

from .. import scene
from ..analysis import beds, profiles
from ..io import dumps, vtk_particles

MARK = "meltdem_post"
FAST = 1.0   # m/s: a grain this fast in any frame counts as thrown (spatter), whatever its direction

# common key <- (scene key, factor to SI), first present wins
SCENE_KEYS = {
    "bead_width_m": (("track_width_m", 1.0), ("bead_width_mm", 1e-3), ("melt_pool_width_moving_um", 1e-6)),
    "bead_height_m": (("bead_height_m", 1.0), ("bead_height_mm", 1e-3)),
    "penetration_m": (("track_depth_m", 1.0), ("penetration_mm", 1e-3), ("melt_pool_depth_moving_um", 1e-6)),
    # a fixed beam (pbf-point) has a melt pool, no bead
    "melt_pool_width_max_m": (("melt_pool_width_max_um", 1e-6),),
    "melt_pool_depth_max_m": (("melt_pool_depth_max_um", 1e-6),),
    "deposition_efficiency": (("deposition_efficiency_pct", 1e-2),),
    "packing_fraction": (("packing_fraction", 1.0),),
    "particles_ejected": (("particles_ejected", 1), ("grains_ejected", 1)),
}


def detect_example(case):
    """The scene a case was built from: the name its build wrote into CASE/scene.json (or None)."""
    p = os.path.join(case, "scene.json")
    if not os.path.exists(p):
        return None
    try:
        m = json.load(open(p))
    except (OSError, ValueError):
        return None
    name = m.get("scene") if isinstance(m, dict) else None
    return name if isinstance(name, str) and name in scene.names() else None


def run_scene_analysis(case, example):
    """Run the scene's own summary analysis (it writes CASE/summary.json); returns an error text or None."""
    try:
        fn = scene.get(example).summary
        if fn is None:
            return None
        with contextlib.redirect_stdout(io.StringIO()):
            fn(case)
    except Exception as e:  # the scene's analysis needs a complete run; report, keep going
        return f"{example} analysis: {type(e).__name__}: {str(e)[:200]}"
    return None


def scene_summary(case, example, analyse=True):
    """(the scene's own summary dict, error or None): summary.json as the scene wrote it, or as a
    previous post-processing kept it (its scene keys); without one, the scene's analysis is run
    when analyse is true."""
    p = os.path.join(case, "summary.json")
    err = None
    if not os.path.exists(p) and example and analyse:
        err = run_scene_analysis(case, example)
    if not os.path.exists(p):
        return {}, err
    try:
        s = json.load(open(p))
    except (OSError, ValueError):
        return {}, err
    if not isinstance(s, dict):
        return {}, err
    if MARK in s:
        keys = s[MARK].get("scene_keys", [])
        return {k: s[k] for k in keys if k in s}, err
    # a scene summary with an earlier post-processing nested into it (meltdem run merges so)
    return {k: v for k, v in s.items() if not (isinstance(v, dict) and MARK in v)}, err


def _finite(v):
    return isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)


def end_time(case):
    p = os.path.join(case, "system", "controlDict")
    if os.path.exists(p):
        m = re.search(r"^\s*endTime\s+([0-9eE.+-]+)\s*;", open(p).read(), re.M)
        if m:
            return float(m.group(1))
    return None


def gravity_axis(case):
    """(axis index, sign) of gravity in the LAMMPS input (fix gravity ... vector a b c), or None."""
    m = re.search(r"^\s*fix\s+\S+\s+\S+\s+gravity\s+\S+\s+vector\s+(\S+)\s+(\S+)\s+(\S+)",
                  vtk_particles.lammps_inputs(case), re.M)
    if not m:
        return None
    try:
        g = np.array([float(v) for v in m.groups()])
    except ValueError:
        return None
    k = int(np.argmax(np.abs(g)))
    return k, float(np.sign(g[k]))


def particle_stats(case, series):
    """Counts and ejection from the particle frames of the main series (VTK/particles.pvd)."""
    kind, paths = vtk_particles.find_dumps(case)
    if not paths:
        return {}, None
    if kind == "series":
        frames = [f[-1] for f in (dumps.read_frames(p) for p in paths) if f]
    else:
        src = series[0]["source"] if series else paths[0]
        frames = dumps.read_frames(os.path.join(case, src))
    if not frames:
        return {}, None
    out = {"particles_first_frame": int(len(frames[0]["data"])), "particles_last_frame": int(len(frames[-1]["data"])),
           "particle_frames": len(frames)}
    g = gravity_axis(case)
    cols0 = frames[0]["columns"]
    need = ("id", "x", "y", "z", "vx", "vy", "vz")
    if g is None or not all(c in cols0 for c in need) or len(frames) < 2:
        return out, frames
    k, sign = g
    upc, vupc = "xyz"[k], "v" + "xyz"[k]

    def col(fr, c):
        return fr["data"][:, fr["columns"].index(c)]
    start = next((j for j, fr in enumerate(frames) if len(fr["data"])), None)
    if start is None or start == len(frames) - 1:
        return out, frames
    frames_used = frames[start:]
    f0 = frames_used[0]
    r0 = col(f0, "radius") if "radius" in cols0 else np.zeros(len(f0["data"]))
    up0 = -sign * col(f0, upc)
    top0 = float(np.max(up0 + r0))
    first_ids = set(col(f0, "id").astype(int))
    ejected, fast, vmax = set(), set(), 0.0
    for j, fr in enumerate(frames_used):
        ids = col(fr, "id").astype(int)
        up = -sign * col(fr, upc)
        vup = -sign * col(fr, vupc)
        sp = np.sqrt(col(fr, "vx") ** 2 + col(fr, "vy") ** 2 + col(fr, "vz") ** 2)
        vmax = max(vmax, float(sp.max()) if len(sp) else 0.0)
        fast.update(int(i) for i in ids[sp > FAST])
        if j:
            ejected.update(int(i) for i in ids[(up > top0) & (vup > 0)] if i in first_ids)
    out["particles_ejected"] = len(ejected)
    out[f"particles_faster_than_{FAST:g}_m_per_s"] = len(fast)
    out["particle_speed_max_m_per_s"] = vmax
    return out, frames


def packing(case, frames):
    """Packing fraction of a DEM bed (no mesh): meltdem.analysis.beds.bed_stats on the last frame,
    the floor the box's lower bound against gravity."""
    g = gravity_axis(case)
    if g is None or not frames or g[1] > 0:
        return None
    fr = frames[-1]
    if not all(c in fr["columns"] for c in ("x", "y", "z", "radius")):
        return None
    tmp = os.path.join(case, "VTK", ".last_frame.dump")
    with open(tmp, "w") as f:
        n = len(fr["data"])
        f.write(f"ITEM: TIMESTEP\n{fr['step']}\nITEM: NUMBER OF ATOMS\n{n}\nITEM: BOX BOUNDS ff ff ff\n")
        for lo, hi in fr["box"]:
            f.write(f"{lo!r} {hi!r}\n")
        f.write("ITEM: ATOMS " + " ".join(fr["columns"]) + "\n")
        np.savetxt(f, fr["data"], fmt="%.17g")
    try:
        walls = not re.search(r"^\s*boundary\s+p\s+p", vtk_particles.lammps_inputs(case), re.M)
        s = beds.bed_stats(tmp, up="xyz"[g[0]], walls=walls)
    finally:
        os.remove(tmp)
    return {"packing_fraction": float(s["packing_layer"]), "bed_thickness_m": float(s["thickness"]),
            "bed_rms_speed_m_per_s": float(s["rms_speed"])}


def ledger_numbers(led):
    s = {"fluid_steps": int(len(led)), "simulated_time_s": float(led["time"][-1]),
         "melted_mass_kg": float(np.sum(led["mass_exchange"])),
         "particle_metal_start_kg": float(led["mass_particles"][0]),
         "particle_metal_end_kg": float(led["mass_particles"][-1]),
         "continuum_metal_gain_kg": float(led["mass_continuum"][-1] - led["mass_continuum"][0]),
         "particles_lost": int(np.sum(led["lost_particles"])),
         "particle_metal_lost_kg": float(led["mass_cumulative_lost"][-1])}
    steps = led[1:]
    for comp, key in (("mass", "mass"), ("enthalpy", "energy"), ("mom", "momentum")):
        for kind in ("system", "continuum"):
            if comp == "mom":
                per = [steps[f"mom_{c}_{kind}_error"] for c in "xyz"]
                cum = [led[f"mom_{c}_cumulative_{kind}_error"][-1] for c in "xyz"]
                w = float(max(np.max(np.abs(p)) for p in per)) if len(steps) else 0.0
                c = float(max(abs(v) for v in cum))
            else:
                w = float(np.max(np.abs(steps[f"{comp}_{kind}_error"]))) if len(steps) else 0.0
                c = float(abs(led[f"{comp}_cumulative_{kind}_error"][-1]))
            s[f"worst_step_{kind}_{key}_error"] = w
            s[f"cumulative_{kind}_{key}_error"] = c
    fed = float(np.sum(led["mass_feed"]))
    if fed > 0:
        dep, lost = s["melted_mass_kg"], s["particle_metal_lost_kg"]
        s.update(powder_fed_kg=fed, powder_pending_end_kg=float(led["mass_pending"][-1]),
                 powder_deposited_kg=dep, powder_lost_kg=lost,
                 deposition_efficiency=dep / (dep + lost) if dep + lost > 0 else float("nan"),
                 deposition_efficiency_of_fed=dep / fed)
    return s


# fixes that move particles without a force the ledger books, or only book what they add
_MOMENTUM_NEUTRAL_FIXES = ("nve", "nve/sphere", "nve/limit", "powder/insert", "powder/dt", "print", "halt",
                           "balance", "ave/time", "ave/chunk", "ave/histo", "ave/correlate", "ave/atom")


def momentum_unbooked(case):
    """Why the ledger's momentum balance does not close by construction (impulses it does not book:
    gravity on the particles, walls, the solid-metal contact, force fixes, the continuum's Darcy,
    surface, recoil and buoyancy forces); [] when it books every impulse."""
    from ..io.lammps_input import LammpsInput
    from ..io import foamdict as fd
    why = []
    ins = sorted(glob.glob(os.path.join(case, "in.*")))
    for p in ins:
        try:
            lmp = LammpsInput(p)
        except OSError:
            continue
        name = os.path.basename(p)
        for _, w in lmp.find("fix"):
            if len(w) < 4:
                continue
            style = w[3]
            if style == "gravity":
                why.append(f"gravity on the particles ({name}: fix {w[1]} gravity)")
            elif style.startswith("wall"):
                why.append(f"walls ({name}: fix {w[1]} {style})")
            elif style == "powder/melt":
                if "solid_metal" in w[4:]:
                    why.append(f"the solid-metal contact ({name}: fix {w[1]} powder/melt solid_metal)")
            elif not style.startswith(_MOMENTUM_NEUTRAL_FIXES):
                why.append(f"forces of {name}: fix {w[1]} {style}")
    # the physics terms acting on momentum (the solver's table): forces the balance does not book
    from .check import solver_terms
    table = solver_terms()
    try:
        md = fd.read(os.path.join(case, "constant", "meltdemProperties"))
        ph = md.get("physics") if isinstance(md.get("physics"), dict) else {}
        on = [k for k, t in (table["terms"] if table else {}).items() if "momentum" in t["acts"] and fd.switch(ph, k)]
        if on:
            why.append(f"the continuum's {', '.join(on)} force(s) (constant/meltdemProperties physics)")
    except (OSError, fd.FoamDictError):
        pass
    return why


def laser_numbers(bal, pcsv, bal_name="meltdemBalance"):
    """(values, sources): laser energy absorbed by the continuum (meltdemBalance laserEnergy_cum)
    and the particles (particles.csv laser_heat), the particles' molten mass (particles.csv)."""
    s = {}
    if bal is not None and "laserEnergy_cum" in bal.dtype.names:
        s["laser_energy_continuum_J"] = float(bal["laserEnergy_cum"][-1])
    if pcsv is not None and "laser_heat" in pcsv.dtype.names:
        s["laser_energy_particles_J"] = float(np.sum(pcsv["laser_heat"]))
    if s:
        s["laser_energy_absorbed_J"] = s.get("laser_energy_continuum_J", 0.0) + s.get("laser_energy_particles_J", 0.0)
    if pcsv is not None and "mass_melted" in pcsv.dtype.names:
        s["particle_molten_mass_kg"] = float(np.sum(pcsv["mass_melted"]))
    src = {k: "particles.csv" for k in s}
    src["laser_energy_continuum_J"] = f"postProcessing/{bal_name} laserEnergy_cum"
    src["laser_energy_absorbed_J"] = " + ".join(
        x for x, k in ((f"postProcessing/{bal_name}", "laser_energy_continuum_J"),
                       ("particles.csv", "laser_energy_particles_J")) if k in s)
    return s, src


def fused_max(fields_series):
    """Per cell the largest liquid fraction reached while the cell was metal (alpha >= 1/2) over
    the written times, or None without a liquidFraction field."""
    out = None
    for _, _, f in fields_series:
        if "liquidFraction" not in f or "alpha.metal" not in f:
            continue
        v = np.where(f["alpha.metal"] >= 0.5, f["liquidFraction"], 0.0)
        if out is not None and len(v) != len(out):
            raise ValueError("the mesh changed between written times (adaptive refinement): the per-cell "
                             "maximum over time needs one mesh; a scene's own analysis measures its track")
        out = v if out is None else np.maximum(out, v)
    return out


def bead_geometry(fields_series, trk):
    """Bead of a moving laser from the written fields, on the cross-section at the middle of the
    track: fused = liquid fraction reached 1/2 while metal at some written time (its 1/2
    crossings interpolated linearly between cell centres); width = widest fused extent across,
    penetration = initial metal surface (median column sum of alpha dv) minus the lowest fused
    point, height = highest metal column at the last written time minus that surface.
    fields_series: [(time, centres, fields)]."""
    from .plots import cross_section
    if trk is None or len(fields_series) < 2:
        return {}
    t0, c0, f0 = fields_series[0]
    if "alpha.metal" not in f0:
        return {}
    lfmax = fused_max(fields_series)
    if lfmax is None:
        return {}
    u, v, a0, _, _ = cross_section(c0, f0, trk)
    tl, cl, fl = fields_series[-1]
    u1, v1, a1, _, _ = cross_section(cl, fl, trk)
    _, _, lfs, _, _ = cross_section(cl, dict(fl, **{"alpha.metal": lfmax}), trk)
    uu, vv = np.unique(np.round(u, 9)), np.unique(np.round(v, 9))
    if len(uu) * len(vv) != len(u) or len(u1) != len(u):
        return {}
    faces = np.concatenate([[vv[0] - (vv[1] - vv[0]) / 2], (vv[1:] + vv[:-1]) / 2, [vv[-1] + (vv[-1] - vv[-2]) / 2]])
    dv = np.diff(faces)
    iu, iv = np.searchsorted(uu, np.round(u, 9)), np.searchsorted(vv, np.round(v, 9))

    def grid(x):
        g = np.zeros((len(vv), len(uu)))
        g[iv, iu] = x
        return g
    A0, A1, L = grid(a0), grid(a1), grid(lfs)
    h0 = faces[0] + dv @ A0            # metal surface height per column, start
    h1 = faces[0] + dv @ A1
    surface0 = float(np.median(h0))
    out = {"bead_height_m": float(max(0.0, np.max(h1 - surface0)))}
    # fused extent: the liquid fraction's 1/2 crossings, linear between cell centres (a fused
    # cell at the section's edge counts to its outer face)
    width, low = 0.0, None
    for j in range(len(vv)):
        cr = profiles.level_span(L[j, :], uu, 0.5)
        if cr:
            width = max(width, cr[1] - cr[0])
    for i in range(len(uu)):
        cr = profiles.level_span(L[:, i], vv, 0.5)
        if cr:
            low = cr[0] if low is None else min(low, cr[0])
    out["bead_width_m"] = float(width)
    out["penetration_m"] = float(max(0.0, surface0 - low)) if low is not None else 0.0
    out["bead_section_time_s"] = float(tl)
    return out


LABELS = [
    ("simulated_time_s", "simulated time", "s"), ("end_time_s", "end time (controlDict)", "s"),
    ("wall_time_s", "wall time", "s"), ("fluid_steps", "fluid steps", ""),
    ("bead_width_m", "bead width", "m"), ("bead_height_m", "bead height", "m"),
    ("penetration_m", "penetration", "m"),
    ("melt_pool_width_max_m", "melt pool width (largest)", "m"),
    ("melt_pool_depth_max_m", "melt pool depth (largest)", "m"),
    ("deposition_efficiency", "deposition efficiency", ""),
    ("powder_fed_kg", "powder fed", "kg"), ("powder_deposited_kg", "powder deposited", "kg"),
    ("packing_fraction", "packing fraction", ""), ("bed_thickness_m", "bed thickness", "m"),
    ("bed_rms_speed_m_per_s", "bed rms speed (settled: ~0)", "m/s"),
    ("particles_first_frame", "particles (first frame)", ""), ("particles_last_frame", "particles (last frame)", ""),
    ("particles_ejected", "particles ejected", ""),
    (f"particles_faster_than_{FAST:g}_m_per_s", f"particles faster than {FAST:g} m/s (any frame)", ""),
    ("particle_speed_max_m_per_s", "largest particle speed", "m/s"),
    ("melted_mass_kg", "metal handed from particles to continuum", "kg"),
    ("particle_molten_mass_kg", "molten particle mass (fix powder/melt)", "kg"),
    ("laser_energy_absorbed_J", "laser energy absorbed", "J"),
    ("laser_energy_continuum_J", "  by the continuum", "J"), ("laser_energy_particles_J", "  by the particles", "J"),
    ("particles_lost", "particles lost (left the mesh, or inserted outside it)", ""),
    ("particle_metal_lost_kg", "  their metal", "kg"),
    ("worst_step_system_mass_error", "worst per-step system mass error", ""),
    ("worst_step_system_energy_error", "worst per-step system energy error", ""),
    ("worst_step_system_momentum_error", "worst per-step system momentum error", ""),
    ("cumulative_system_mass_error", "cumulative system mass error", ""),
    ("cumulative_system_energy_error", "cumulative system energy error", ""),
    ("cumulative_system_momentum_error", "cumulative system momentum error", ""),
]


def write_markdown(path, s):
    rows = []
    for key, label, unit in LABELS:
        if key not in s:
            continue
        v = s[key]
        txt = (f"{v:.4g}" if isinstance(v, float) else str(v))
        src = s[MARK]["sources"].get(key, "")
        rows.append(f"| {label} | {txt} | {unit} | {src} |")
    head = f"# Run summary: {os.path.basename(os.path.abspath(os.path.dirname(path)))}\n\n"
    if s.get("example"):
        head += f"Example: {s['example']}.  "
    fl = s[MARK].get("files", {})
    pv = [fl[k] for k in ("fields_pvd", "particles_pvd") if k in fl]
    if pv:
        head += f"ParaView: open {' and '.join(pv)}" + (" together" if len(pv) > 1 else "") + (
            " (particles as spheres: Glyph, type Sphere, scale array diameter, factor 1). " if "particles_pvd" in fl
            else ". ")
    pngs = [v for k, v in fl.items() if k.endswith("_png")]
    if pngs:
        head += "Plots: " + ", ".join(pngs) + ". "
    if "ledger_csv" in fl:
        head += "Ledger: ledger.csv."
    head += "\n\n"
    notes = "".join(f"\n- {n}" for n in s[MARK].get("notes", []))
    with open(path, "w") as f:
        f.write(head + "| quantity | value | unit | source |\n|---|---|---|---|\n" + "\n".join(rows) + "\n"
                + (f"\nNotes:{notes}\n" if notes else ""))
