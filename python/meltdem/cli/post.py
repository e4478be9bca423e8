"""Post-processing of a finished (or stopped) run: `meltdem post CASE`, and the last step of
`meltdem run`.

    postprocess(case_dir, example=None) -> dict

writes, under the case:
    VTK/fields.pvd, VTK/fields/      continuum fields per OpenFOAM write time (foamToVTK)
    VTK/particles.pvd, VTK/particles/ the particles per dump frame (.vtp points)
    ledger.csv                        copy of postProcessing/particleLedger/ledger.csv
    plots/balances.png, melted_mass.png, absorbed_power.png, bead_profile.png (moving laser)
    summary.json, summary.md          the per-run numbers (summary.py)
and returns the summary dict. Every part is optional: what the case lacks is skipped and named
in summary.json's meltdem_post.notes; a part that fails is named there too (the others still run).
"""
import json
import math
import os
import shutil
import sys
import time

import numpy as np

from . import plots, summary

from ..analysis import section_lattice
from ..io import casedata, vtk_fields, vtk_particles


def _clean(v):
    if isinstance(v, dict):
        return {k: _clean(x) for k, x in v.items()}
    if isinstance(v, (list, tuple)):
        return [_clean(x) for x in v]
    if isinstance(v, np.integer):
        return int(v)
    if isinstance(v, np.floating):
        v = float(v)
    if isinstance(v, np.ndarray):
        return _clean(v.tolist())
    return v


def _put(s, sources, values, source):
    for k, v in values.items():
        if isinstance(v, float) and not math.isfinite(v):
            continue
        s[k] = v
        sources[k] = source


def postprocess(case_dir, example=None, fields=True, quiet=True, analyse=True):
    """analyse: run the scene's analysis when the case has no summary.json of it (meltdem run
    --no-analyse passes False)."""
    t_start = time.time()
    case = os.path.abspath(case_dir)
    if not os.path.isdir(case):
        raise FileNotFoundError(f"meltdem post: no case folder {case}")
    example = example or summary.detect_example(case)
    notes, sources, files, s = [], {}, {}, {}

    # the scene's own numbers first: its analysis writes summary.json, which this step rewrites
    scene, err = summary.scene_summary(case, example, analyse)
    if err:
        notes.append(err)

    # ParaView output
    fseries = None
    if fields:
        try:
            fseries = vtk_fields.convert(case)
            if fseries:
                files["fields_pvd"] = os.path.relpath(fseries["pvd"], case)
                s["field_write_times"] = len(fseries["entries"])
                if fseries["empty_times"]:
                    notes.append("time folder(s) without fields left out of fields.pvd (a write cut short?): "
                                 + ", ".join(f"{t:g}" for t in fseries["empty_times"]))
            else:
                notes.append("no OpenFOAM mesh: no fields.pvd")
        except Exception as e:
            notes.append(f"fields: {type(e).__name__}: {e}")
    try:
        pseries = vtk_particles.convert(case)
        if pseries:
            files["particles_pvd"] = os.path.relpath(pseries[0]["pvd"], case)
            files["particles_source"] = pseries[0]["source"]
            files["particles_time_source"] = pseries[0]["time_source"]
            for extra in pseries[1:]:
                files.setdefault("other_particle_pvds", []).append(os.path.relpath(extra["pvd"], case))
        else:
            notes.append("no particle dump (CASE/particles/*.dump, *.dump, dump.*): no particles.pvd")
    except Exception as e:
        pseries = []
        notes.append(f"particles: {type(e).__name__}: {e}")

    # ledger, balance rows, particle tally
    led = casedata.ledger(case)
    pcsv = casedata.particles_csv(case)
    bal_name, bal = casedata.balance_rows(case)
    if led is not None:
        shutil.copyfile(casedata.ledger_path(case), os.path.join(case, "ledger.csv"))
        files["ledger_csv"] = "ledger.csv"
    las = casedata.laser(case)

    # the moving laser's track and the written fields for its cross-section
    t_last_field = fseries["entries"][-1][0] if fseries and fseries["entries"] else None
    trk = casedata.track(case, t_last_field) if t_last_field is not None else None
    fields_series = []
    if trk is not None and fseries:
        try:
            for t, rel in fseries["entries"]:
                fields_series.append((t, *vtk_fields.read_internal(os.path.join(case, "VTK", rel))))
            # a refined run's cells differ between times: its section sampled on one lattice
            if section_lattice.needs_lattice(fields_series):
                fields_series = section_lattice.sample(fields_series, trk)
            else:
                fields_series = [(t, c, f) for t, c, f, _ in fields_series]
        except Exception as e:
            notes.append(f"reading the written fields: {type(e).__name__}: {e}")
            fields_series = []

    # plots
    pdir = os.path.join(case, "plots")
    os.makedirs(pdir, exist_ok=True)
    eta_p = (las["power"] * las["absorptivity"]) if las and las.get("power") is not None and las.get(
        "absorptivity") is not None else None
    for name, fn in (("balances", lambda p: plots.balances(p, led, bal)),
                     ("melted_mass", lambda p: plots.melted_mass(p, led, pcsv)),
                     ("absorbed_power", lambda p: plots.absorbed_power(p, bal, pcsv, eta_p))):
        try:
            if fn(os.path.join(pdir, name + ".png")):
                files[name + "_png"] = f"plots/{name}.png"
        except Exception as e:
            notes.append(f"plot {name}: {type(e).__name__}: {e}")
    if fields_series:
        try:
            lfmax = summary.fused_max(fields_series)
            t, c, f = fields_series[-1]
            lf_sec = plots.cross_section(c, dict(f, **{"alpha.metal": lfmax}), trk)[2] if lfmax is not None else None
            if plots.bead_profile(os.path.join(pdir, "bead_profile.png"), c, f, trk, t, lf_sec):
                files["bead_profile_png"] = "plots/bead_profile.png"
        except Exception as e:
            notes.append(f"plot bead_profile: {type(e).__name__}: {e}")

    # the numbers
    s["case"] = case
    if example:
        s["example"] = example
    if led is not None:
        try:
            nums = summary.ledger_numbers(led)
            unbooked = summary.momentum_unbooked(case)
            if unbooked:
                # ledger.csv has the columns; a balance that cannot close is not a result
                for k in [k for k in nums if k.endswith("_momentum_error")]:
                    del nums[k]
                notes.append("momentum balance not shown: the ledger does not book the impulse of "
                             + "; ".join(unbooked))
            _put(s, sources, nums, "ledger.csv")
        except Exception as e:   # a ledger of another layout: name it, keep the rest
            notes.append(f"ledger numbers: {type(e).__name__}: {e}")
    try:
        vals, srcs = summary.laser_numbers(bal, pcsv, bal_name)
        for k, v in vals.items():
            _put(s, sources, {k: v}, srcs[k])
    except Exception as e:
        notes.append(f"laser numbers: {type(e).__name__}: {e}")
    if "simulated_time_s" not in s:
        t_candidates = []
        if t_last_field is not None:
            t_candidates.append((t_last_field, "last OpenFOAM write time"))
        if pseries and pseries[0]["times"] and pseries[0]["time_source"] != "step":
            t_candidates.append((pseries[0]["times"][-1], f"last particle frame ({pseries[0]['time_source']})"))
        if t_candidates:
            t, src = max(t_candidates)
            _put(s, sources, {"simulated_time_s": float(t)}, src)
    if las and las.get("power") is not None:
        _put(s, sources, {"laser_power_W": las["power"]}, "constant/meltdemProperties laser")
        if las.get("absorptivity") is not None:
            _put(s, sources, {"laser_absorptivity": las["absorptivity"]}, "constant/meltdemProperties laser")
    et = summary.end_time(case)
    if et is not None:
        _put(s, sources, {"end_time_s": et}, "system/controlDict")
    w, wsrc = casedata.wall_time(case)
    if w is not None:
        _put(s, sources, {"wall_time_s": w}, wsrc)
    try:
        pst, frames = summary.particle_stats(case, pseries)
        _put(s, sources, pst, f"particle frames ({files.get('particles_source', '')})")
        if "particles_ejected" in pst:
            sources["particles_ejected"] += ": centre above the first frame's bed top, moving up"
    except Exception as e:
        frames = None
        notes.append(f"particle numbers: {type(e).__name__}: {e}")
    if fseries is None and frames and "packing_fraction" not in scene:
        try:
            pk = summary.packing(case, frames)
            if pk:
                _put(s, sources, pk, "meltdem.analysis.beds on the last frame")
        except Exception as e:
            notes.append(f"packing: {type(e).__name__}: {e}")
    if trk is not None and fields_series:
        try:
            _put(s, sources, summary.bead_geometry(fields_series, trk),
                 "fields, cross-section at mid-track")
        except Exception as e:
            notes.append(f"bead geometry: {type(e).__name__}: {e}")
    # the scene's numbers replace the generic ones (same names too: the scene defines them)
    for k, v in scene.items():
        if k in s and k not in ("case", "example"):
            s[k] = v
            sources[k] = f"the example's analysis (summary.json {k})"
    for key, cands in summary.SCENE_KEYS.items():
        for skey, factor in cands:
            v = scene.get(skey)
            if isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v):
                s[key] = type(factor)(v * factor) if isinstance(factor, int) else v * factor
                sources[key] = f"the example's analysis (summary.json {skey})"
                break

    labelled = {k for k, _, _ in summary.LABELS}
    for k in scene:
        if k in labelled and k not in sources:
            sources[k] = f"the example's analysis (summary.json {k})"
    s["postprocess_seconds"] = round(time.time() - t_start, 2)
    out = dict(_clean(scene))
    out.update(_clean(s))
    out[summary.MARK] = _clean({"scene_keys": sorted(scene), "sources": sources,
                                "files": files, "notes": notes})
    with open(os.path.join(case, "summary.json.tmp"), "w") as f:
        json.dump(out, f, indent=1)
    os.replace(os.path.join(case, "summary.json.tmp"), os.path.join(case, "summary.json"))
    summary.write_markdown(os.path.join(case, "summary.md"), out)
    if not quiet:
        print(open(os.path.join(case, "summary.md")).read())
    return out


def main(argv=None):
    import argparse
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("case")
    ap.add_argument("--example", default=None)
    a = ap.parse_args(argv)
    postprocess(a.case, a.example, quiet=False)
    return 0


if __name__ == "__main__":   # python3 -m meltdem.cli.post CASE
    sys.exit(main())
