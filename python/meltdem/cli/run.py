"""`meltdem run`: one case from an example name or a case folder to its post-processed output.

    example name -> the scene's build (CASE, ci|full; meltdem.scene)
    check (stop on errors) -> mesh (blockMesh when system/blockMeshDict and no polyMesh)
    -> decompose (--np > 1) -> ONE job: [mpirun -np N] meltdemFoam [-parallel] | meltdem-lmp -in IN
    -> reconstructPar (N > 1) -> the scene's analyse (examples) -> post-processing (cli/post.py)

--resume: coupled and continuum-only cases: the latest time T with CASE/meltdemRestart/T/complete
and the OpenFOAM time folder (CASE/T or processor0/T); system/controlDict gets startFrom startTime;
startTime T (foamDictionary), what the stopped run wrote after T is removed, and the solver is
relaunched without meshing or decomposing. DEM-only cases: meltdem-lmp -checkpoint writes
CASE/meltdemRestart/<step>/ during the run; -resume continues from the latest complete one.
One run per case: the case is locked while it runs (caselock.py).
"""
import ctypes
import json
import os
import shutil
import signal
import subprocess
import sys
import time

from .. import paths
from ..case import foam as fc
from . import caselock
from . import check as chk
from . import examples as ex
from ..io import foamdict as fd
from .examples import StepError
from .progress import FoamProgress, LammpsProgress, Reporter

RESTART_DIR = "meltdemRestart"


def say(msg):
    print(f"meltdem: {msg}", flush=True)


def bin_dir():
    return paths.bin_dir()


def env():
    e = paths.tool_env()
    e["MELTDEM_BIN"] = bin_dir()
    return e


def _die_with_parent():
    """The solver ends when meltdem is killed (mpirun forwards the signal to its ranks)."""
    try:
        ctypes.CDLL("libc.so.6").prctl(1, signal.SIGTERM)   # PR_SET_PDEATHSIG
    except Exception:
        pass


def tool(cmd, case, log):
    """A short OpenFOAM tool (blockMesh, decomposePar, ...), its output in CASE/log."""
    with open(os.path.join(case, log), "w") as f:
        r = subprocess.run(cmd, cwd=case, stdout=f, stderr=subprocess.STDOUT, env=dict(env(), PWD=case))
    if r.returncode != 0:
        why = failure_reason(case, log)
        raise StepError(f"{cmd[0]} failed (rc {r.returncode}){': ' + why if why else ''}; "
                        f"read {os.path.join(case, log)}")


WALL_FILE = "wall_seconds"


def wall_segments(case):
    """[(seconds, ranks, how)] of the runs of a case so far (CASE/wall_seconds: the total and the
    ranks on its first line, then one '# segment seconds ranks how' line per launch)."""
    out = []
    try:
        for ln in open(os.path.join(case, WALL_FILE)):
            w = ln.split()
            if len(w) >= 4 and w[0] == "#" and w[1] == "segment":
                out.append((float(w[2]), int(w[3]), " ".join(w[4:])))
    except (OSError, ValueError):
        return []
    return out


def write_wall(case, segments):
    """CASE/wall_seconds: the total over all segments (a resumed run's included) and the ranks."""
    total = sum(s for s, _, _ in segments)
    ranks = segments[-1][1] if segments else 1
    text = f"{total:.1f} {ranks}\n" + "".join(f"# segment {s:.1f} {n} {how}\n" for s, n, how in segments)
    tmp = os.path.join(case, WALL_FILE + ".tmp")
    with open(tmp, "w") as f:
        f.write(text)
    os.replace(tmp, os.path.join(case, WALL_FILE))


def launch(cmd, case, log, tracker, np_=1, earlier=(), how="run"):
    """Run the solver job with the progress line; returns (rc, wall seconds). CASE/wall_seconds
    is kept current while it runs (a killed run's time counts in the resumed run's total)."""
    t0 = time.time()
    rep = Reporter(tracker)
    earlier = list(earlier)
    last = 0.0
    with open(os.path.join(case, log), "w") as f:
        p = subprocess.Popen(cmd, cwd=case, stdout=f, stderr=subprocess.STDOUT, env=dict(env(), PWD=case),
                             preexec_fn=_die_with_parent)
        try:
            while p.poll() is None:
                rep.update()
                if time.time() - last > 5:
                    last = time.time()
                    write_wall(case, earlier + [(last - t0, np_, how)])
                time.sleep(0.5)
        except KeyboardInterrupt:
            p.send_signal(signal.SIGTERM)
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()
            raise
        rep.update(final=True)
    wall = time.time() - t0
    write_wall(case, earlier + [(wall, np_, how)])
    return p.returncode, wall


def mpirun(np_):
    return ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(np_)]


def failure_reason(case, log):
    """The first error line of a solver log (FOAM FATAL ... message, LAMMPS ERROR), '' if none."""
    try:
        lines = open(os.path.join(case, log), errors="replace").read().splitlines()
    except OSError:
        return ""
    for i, ln in enumerate(lines):
        if "FOAM FATAL" in ln:
            block = [x.strip() for x in lines[i + 1:i + 12]]
            rest = [x for x in block if x and not x.startswith(("From ", "in file", "file:", "at line"))]
            msg = rest[0] if rest else ln.strip()
            # a FatalIOError names the dictionary: "file: CASE/constant/x at line N."
            where = next((x for x in block if x.startswith("file:")), None)
            if where:
                loc = where[len("file:"):].strip().rstrip(".")
                msg = f"{loc.replace(case + os.sep, '')}: {msg}"
            return _clip(msg)
        if ln.startswith("ERROR") or " ERROR:" in ln:
            return _clip(ln.strip())
    return ""


def solver_warnings(case, log, limit=5):
    """The messages of the solver's warnings ('--> FOAM Warning' blocks), each once."""
    try:
        lines = open(os.path.join(case, log), errors="replace").read().splitlines()
    except OSError:
        return []
    out = []
    for i, ln in enumerate(lines):
        if "FOAM Warning" not in ln:
            continue
        body = []
        for x in lines[i + 1:i + 12]:
            x = x.strip()
            if x.startswith(("From ", "in file")):
                continue
            if not x:
                if body:
                    break
                continue
            body.append(x)
        msg = _clip(" ".join(body))
        if msg and msg not in out:
            out.append(msg)
    return out[:limit]


def _clip(text, n=320):
    return text if len(text) <= n else text[:n].rsplit(" ", 1)[0] + " ..."


# --------------------------------------------------------------------------------- OpenFOAM case
def processor_dirs(case):
    return sorted(d for d in os.listdir(case) if d.startswith("processor") and d[9:].isdigit())


def scan_axes(case):
    """The axes a moving laser of the case (constant/meltdemProperties laser{}) travels along or
    shines along: {0, 1, 2} indices; empty without a laser or when it cannot be read."""
    try:
        laser = fd.read(os.path.join(case, "constant", "meltdemProperties")).get("laser")
    except (OSError, fd.FoamDictError):
        return set()
    if not isinstance(laser, dict):
        return set()
    moves = []
    for key in ("velocity", "direction"):
        v = fd.value(laser, key)
        if v:
            moves.append(fd.vector(v[0]))
    tracks = fd.value(laser, "tracks")
    for track in (tracks[0] if tracks and isinstance(tracks[0], list) else []):
        if isinstance(track, list) and len(track) == 2:
            a, b = fd.vector(track[0]), fd.vector(track[1])
            if a and b:
                moves.append(tuple(y - x for x, y in zip(a, b)))
    return {k for v in moves if v for k in range(3) if v[k] != 0.0}


def decomposition_split(case, np_, mesh_box):
    """(nx, ny, nz) of the simple decomposition meltdem run writes: np_ slabs stacked along the
    mesh's longest side, except along the laser's scan and beam axes where another side is left
    (slabs across the scan each hold a share of the beam, the pool and its refined cells; slabs
    along it leave them on one rank, slabs along the beam put substrate and gas apart)."""
    axis = 0
    if mesh_box:
        span = [high - low for low, high in zip(*mesh_box)]
        avoid = scan_axes(case)
        free = [k for k in range(3) if k not in avoid] or [0, 1, 2]
        axis = max(free, key=lambda k: span[k])
    split = [1, 1, 1]
    split[axis] = np_
    return tuple(split)


def decompose(case, np_, mesh_box):
    rel = "system/decomposeParDict"
    p = os.path.join(case, rel)
    n = None
    if os.path.isfile(p):
        try:
            n = fd.number(fd.read(p), "numberOfSubdomains")
        except (OSError, fd.FoamDictError):
            n = None
    if n is None or int(n) != np_:
        split = decomposition_split(case, np_, mesh_box)
        with open(p, "w") as f:
            f.write("FoamFile { version 2.0; format ascii; class dictionary; object decomposeParDict; }\n"
                    f"// written by meltdem run --np {np_}\nnumberOfSubdomains {np_};\nmethod simple;\n"
                    f"coeffs {{ n ({split[0]} {split[1]} {split[2]}); }}\n"
                    f"simpleCoeffs {{ n ({split[0]} {split[1]} {split[2]}); delta 0.001; }}\n")
        say(f"wrote {rel} ({np_} subdomains along {'xyz'[split.index(np_)]})")
    tool(["decomposePar", "-force"], case, "log.decomposePar")


def latest_checkpoint(case, at=None):
    """(T name, where the OpenFOAM fields are) of the latest complete checkpoint (the one at time
    AT when given), or raises StepError naming what is missing."""
    rdir = os.path.join(case, RESTART_DIR)
    if not os.path.isdir(rdir):
        raise StepError(f"cannot resume: no checkpoint folder {rdir} (the solver writes "
                        f"{RESTART_DIR}/<time>/ at every write time)")
    complete = [t for t in fd.time_dirs(rdir) if os.path.isfile(os.path.join(rdir, t, "complete"))
                and (at is None or float(t) == at)]
    if not complete:
        raise StepError(f"cannot resume: no complete checkpoint in {rdir} (no <time>/complete: the run "
                        f"was stopped before its first write time finished)")
    proc = os.path.isdir(os.path.join(case, "processor0"))
    foam_times = fd.time_dirs(os.path.join(case, "processor0") if proc else case)
    have = {float(t): t for t in foam_times}
    for t in sorted(complete, key=float, reverse=True):
        if float(t) in have:
            return t, have[float(t)], proc
    where = "processor0/" if proc else ""
    raise StepError(f"cannot resume: checkpoints {', '.join(complete)} in {rdir} have no OpenFOAM time "
                    f"folder {where}<time> in {case}")


def start_as_written(case, cd):
    """The time a run starts from by system/controlDict's startFrom (startTime, firstTime or
    latestTime: the case's time folders, processor0's when the case has none), as meltdemFoam does."""
    how = fd.word(cd, "startFrom") or "startTime"
    if how not in ("firstTime", "latestTime"):
        return fd.number(cd, "startTime") or 0.0
    folder = chk.start_time_folder(case, cd)
    if folder is None:
        raise StepError(f"startFrom {how} in {os.path.join(case, 'system', 'controlDict')}: no time folder in {case}")
    return float(os.path.basename(folder))


def complete_checkpoint_at(case, t):
    """Whether the case holds a complete checkpoint at time t with its OpenFOAM time folder."""
    try:
        latest_checkpoint(case, at=t)
        return True
    except StepError:
        return False


START_FILE = os.path.join("system", "meltdemStartAsWritten.json")


def set_start_time(case, t):
    """startFrom startTime; startTime T in system/controlDict, by foamDictionary when available.
    The entries as written are kept in system/meltdemStartAsWritten.json (restored after the
    resumed run finishes, or before a fresh run)."""
    cd = os.path.join(case, "system", "controlDict")
    keep = os.path.join(case, START_FILE)
    if not os.path.isfile(keep):
        d = fd.read(cd)
        json.dump({"startFrom": fd.word(d, "startFrom") or "startTime",
                   "startTime": " ".join(map(str, fd.value(d, "startTime") or ["0"]))}, open(keep, "w"))
    _set_control(case, {"startFrom": "startTime", "startTime": t})


def restore_start_time(case):
    """Undo set_start_time (a finished resume, or a fresh run of a case resumed before)."""
    keep = os.path.join(case, START_FILE)
    if os.path.isfile(keep):
        orig = json.load(open(keep))
        _set_control(case, orig)
        os.remove(keep)
        say(f"system/controlDict: startFrom {orig['startFrom']}; startTime {orig['startTime']} (as written) restored")


def _set_control(case, entries):
    cd = os.path.join(case, "system", "controlDict")

    def as_set():
        d = fd.read(cd)
        return all(" ".join(map(str, fd.value(d, k) or [])) == str(v) for k, v in entries.items())

    try:
        for key, val in entries.items():
            subprocess.run(["foamDictionary", "-entry", key, "-set", str(val), cd], check=True,
                           stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, env=env(), cwd=case)
    except (OSError, subprocess.CalledProcessError):
        pass
    # foamDictionary writes numbers to 6 digits: a time named 1.1662673e-05 is set as written here
    if not as_set():
        fd.set_entries(cd, entries)
    if not as_set():
        raise StepError(f"could not set {entries} in {cd}")


def keep_log(case, log):
    """A resumed run's log is new: the one of the run it continues becomes log.X.1 (.2, ...)."""
    p = os.path.join(case, log)
    if not os.path.isfile(p):
        return
    n = 1
    while os.path.exists(f"{p}.{n}"):
        n += 1
    os.replace(p, f"{p}.{n}")
    say(f"the log of the run it continues: {log}.{n}")


def clear_after_checkpoint(case, t):
    """What a killed run wrote past the checkpoint it is resumed from (time folders, checkpoints,
    particle frames): the resumed run writes them again."""
    later = [os.path.join(case, d) for d in fd.time_dirs(case) if float(d) > t]
    for p in processor_dirs(case):
        later += [os.path.join(case, p, d) for d in fd.time_dirs(os.path.join(case, p)) if float(d) > t]
    rdir = os.path.join(case, RESTART_DIR)
    if os.path.isdir(rdir):
        later += [os.path.join(rdir, d) for d in fd.time_dirs(rdir) if float(d) > t]
    pdir = os.path.join(case, "particles")
    if os.path.isdir(pdir):
        for f in os.listdir(pdir):
            try:
                if f.endswith(".dump") and float(f[:-5]) > t:
                    later.append(os.path.join(pdir, f))
            except ValueError:
                pass
    if later:
        say(f"removing what the stopped run wrote after t = {t:g} s ({len(later)} folder(s)/file(s))")
    for p in later:
        if os.path.isdir(p):
            shutil.rmtree(p)
        else:
            os.remove(p)


def clear_earlier_output(case, start):
    """Time folders after startTime, checkpoints and processor folders of an earlier run (the new
    run rewrites them; stale ones would be read back by --resume and the post-processing)."""
    later = [t for t in fd.time_dirs(case) if float(t) > start]
    # the function objects' segments of resumed runs and the logs of the runs they continued
    pp = os.path.join(case, "postProcessing")
    for fo in (os.listdir(pp) if os.path.isdir(pp) else []):
        for seg in fd.time_dirs(os.path.join(pp, fo)):
            if float(seg) > start:
                shutil.rmtree(os.path.join(pp, fo, seg))
    for f in os.listdir(case):
        if f.startswith("log.") and f.rsplit(".", 1)[-1].isdigit():
            os.remove(os.path.join(case, f))
    rdir = os.path.join(case, RESTART_DIR)
    # processor folders are only output when the start fields are in the case itself
    has_start = any(float(t) == start for t in fd.time_dirs(case))
    procs = processor_dirs(case) if has_start else []
    if later or os.path.isdir(rdir) or procs:
        extra = ([RESTART_DIR + "/"] if os.path.isdir(rdir) else []) + (["processor*/"] if procs else [])
        say(f"earlier output in {case} ({len(later)} time folder(s) after {start:g}"
            f"{', ' + ', '.join(extra) if extra else ''}) is overwritten: starting from t = {start:g} s")
        for t in later:
            shutil.rmtree(os.path.join(case, t))
        shutil.rmtree(rdir, ignore_errors=True)
        for p in procs:
            shutil.rmtree(os.path.join(case, p))


def run_foam(case, np_, resume, rebuilt=False):
    """rebuilt: the case was just (re)built from an example, so an existing polyMesh is stale."""
    cd = fd.read(os.path.join(case, "system", "controlDict"))
    t_end = fd.number(cd, "endTime")
    mesh, _ = chk.mesh_box(case, chk.Report())
    procs = processor_dirs(case)
    resume_at = None
    if not resume:
        restore_start_time(case)
        cd = fd.read(os.path.join(case, "system", "controlDict"))
        t_written = start_as_written(case, cd)
        # a start time with a complete checkpoint continues from it, as meltdemFoam alone does
        if t_written > 0 and complete_checkpoint_at(case, t_written):
            how = fd.word(cd, "startFrom") or "startTime"
            say(f"system/controlDict starts from t = {t_written:g} s (startFrom {how}), which has a complete "
                f"checkpoint: the run continues from it, as --resume does")
            resume, resume_at = True, t_written
    if resume:
        t, _, decomposed = latest_checkpoint(case, at=resume_at)
        if decomposed:
            np_ = np_ if np_ > 1 else len(procs)
            if np_ != len(procs):
                raise StepError(f"cannot resume on {np_} rank(s): the case is decomposed into {len(procs)} "
                                f"processor folders (resume with --np {len(procs)})")
        elif np_ > 1:
            raise StepError(f"cannot resume on {np_} ranks: the checkpoint was written by a serial run "
                            f"(resume with --np 1)")
        set_start_time(case, t)
        say(f"resuming from the checkpoint at t = {t} s ({RESTART_DIR}/{t}; system/controlDict: "
            f"startFrom startTime; startTime {t})")
        t_start = float(t)
        clear_after_checkpoint(case, t_start)
        keep_log(case, "log.meltdemFoam")
    else:
        t_start = t_written
        clear_earlier_output(case, t_start)
        if rebuilt and os.path.isfile(os.path.join(case, "system", "blockMeshDict")):
            shutil.rmtree(os.path.join(case, "constant", "polyMesh"), ignore_errors=True)
        if os.path.isfile(os.path.join(case, "system", "blockMeshDict")) and \
                not os.path.isfile(os.path.join(case, "constant", "polyMesh", "points")):
            say("meshing: blockMesh (log.blockMesh)")
            tool(["blockMesh"], case, "log.blockMesh")
        if np_ > 1 and _wedge(case):
            say(f"the mesh has wedge (axisymmetric) patches: runs serial, --np {np_} not used")
            np_ = 1
        if np_ > 1:
            say(f"decomposing into {np_} subdomains (log.decomposePar)")
            decompose(case, np_, mesh)
    solver = os.path.join(bin_dir(), "meltdemFoam")
    if not os.access(solver, os.X_OK):
        raise StepError(f"{solver} not found: build MeltDEM first (scripts/build.sh)")
    cmd = [solver] if np_ == 1 else mpirun(np_) + [solver, "-parallel"]
    say(f"running {' '.join(cmd[-2:] if np_ > 1 else cmd[:1]).replace(bin_dir() + '/', '')} on {np_} rank(s), "
        f"t = {t_start:g} -> {t_end:g} s (log.meltdemFoam)")
    tracker = FoamProgress(os.path.join(case, "log.meltdemFoam"), t_end, t_start)
    earlier = wall_segments(case) if resume else []
    try:
        rc, wall = launch(cmd, case, "log.meltdemFoam", tracker, np_, earlier,
                          f"resumed at t = {t_start:g} s" if resume else "run")
    except KeyboardInterrupt:
        say(f"interrupted at t = {tracker.t:g} s; continue from the last checkpoint with: meltdem run {case} --resume")
        raise
    if rc != 0:
        why = failure_reason(case, "log.meltdemFoam")
        raise StepError(f"meltdemFoam failed (rc {rc}) at t = {tracker.t:g} s{': ' + why if why else ''}; read "
                        f"{os.path.join(case, 'log.meltdemFoam')}"
                        + (f" (resume: meltdem run {case} --resume)" if os.path.isdir(os.path.join(case, RESTART_DIR))
                           else ""))
    for w in solver_warnings(case, "log.meltdemFoam"):
        say(f"WARNING (log.meltdemFoam): {w}")
    say(f"meltdemFoam finished in {wall:.0f} s wall")
    if resume:
        restore_start_time(case)
    if np_ > 1:
        reconstruct(case)
    return wall


def reconstruct(case):
    """The decomposed times the case folder lacks, reconstructed (fc.reconstruct_commands: a refined
    run's meshes first)."""
    for cmd, log in fc.reconstruct_commands(case):
        say(f"reconstructing{' the refined mesh' if cmd[0] == 'reconstructParMesh' else ''} ({log})")
        tool(cmd, case, log)


def _wedge(case):
    p = os.path.join(case, "system", "blockMeshDict")
    try:
        return "wedge" in open(p).read()
    except OSError:
        return False


# ----------------------------------------------------------------------------------- DEM case
def dem_checkpoints(case):
    """Steps of the complete checkpoints of a DEM-only run (meltdem-lmp -checkpoint), ascending."""
    rdir = os.path.join(case, RESTART_DIR)
    out = []
    for d in os.listdir(rdir) if os.path.isdir(rdir) else []:
        if d.isdigit() and os.path.isfile(os.path.join(rdir, d, "complete")):
            out.append(int(d))
    return sorted(out)


CHECKPOINT_EVERY = 10000   # DEM steps between the checkpoints of a DEM-only run (default)


def run_dem(case, np_, resume, checkpoint_every=None):
    inp = chk.dem_input(case)
    if resume:
        steps = dem_checkpoints(case)
        if not steps:
            raise StepError(f"cannot resume: no complete checkpoint in {os.path.join(case, RESTART_DIR)} (the run "
                            f"was stopped before its first checkpoint, or was not started by meltdem run)")
        say(f"resuming from the checkpoint at step {steps[-1]} ({RESTART_DIR}/{steps[-1]})")
        if checkpoint_every is not None:
            say("--checkpoint-every is not used on --resume: the run keeps the interval it was started with")
        for log in ("log.lammps", "out.lammps"):
            keep_log(case, log)
    else:
        shutil.rmtree(os.path.join(case, RESTART_DIR), ignore_errors=True)
        for f in os.listdir(case):
            if f.startswith(("log.", "out.")) and f.rsplit(".", 1)[-1].isdigit():
                os.remove(os.path.join(case, f))
    from ..io.lammps_input import LammpsInput
    overrides = chk.scene_vars(case)
    lmp_in = LammpsInput(os.path.join(case, inp), overrides)
    lmp = os.path.join(bin_dir(), "meltdem-lmp")
    if not os.access(lmp, os.X_OK):
        raise StepError(f"{lmp} not found: build MeltDEM first (scripts/build.sh)")
    # the progress follows the screen output (out.lammps), line-buffered by stdbuf: LAMMPS writes
    # its log file through a full stdio buffer unless the input says thermo_modify flush yes
    cmd = (["stdbuf", "-oL"] if shutil.which("stdbuf") else []) + [lmp, "-in", inp, "-log", "log.lammps"]
    for k, v in overrides.items():
        cmd += ["-var", k, v]
    runs = lmp_in.runs()
    # checkpoints the run resumes from (`meltdem run CASE --resume`); a resumed run keeps the
    # interval it was started with (it is in the checkpoint)
    cmd += ["-checkpoint", RESTART_DIR, str(checkpoint_every or CHECKPOINT_EVERY)] + (["-resume"] if resume else [])
    if np_ > 1:
        cmd = mpirun(np_) + cmd
    halt = lmp_in.fixes("halt")
    say(f"running meltdem-lmp -in {inp} on {np_} rank(s)"
        + (f", {'at most ' if halt else ''}{sum(r for r in runs if r > 0)} steps" if runs and min(runs) >= 0 else "")
        + (f" (fix {halt[0][1][1]} halt ends it when its condition is met: the ETA is an upper bound)" if halt else "")
        + " (log.lammps)")
    rc, wall = launch(cmd, case, "out.lammps", LammpsProgress(os.path.join(case, "out.lammps"), lmp_in.timestep(),
                                                              runs, lmp_in.run_timesteps()),
                      np_, wall_segments(case) if resume else [], "resumed" if resume else "run")
    if rc != 0:
        why = failure_reason(case, "log.lammps") or failure_reason(case, "out.lammps")
        raise StepError(f"meltdem-lmp failed (rc {rc}){': ' + why if why else ''}; read "
                        f"{os.path.join(case, 'log.lammps')} (screen output: out.lammps)"
                        + (f" (resume: meltdem run {case} --resume)" if dem_checkpoints(case) else ""))
    say(f"meltdem-lmp finished in {wall:.1f} s wall")
    return wall


# ------------------------------------------------------------- scenes with a run step of their own
def run_scene(name, case, np_):
    """Examples whose built case is not one solver case (bjt-droplet: a bed, then one case per
    impact speed) run through their scene's run step; the progress follows the newest solver log."""
    subs = sorted(d for d in os.listdir(case) if chk.case_kind(os.path.join(case, d)) == "foam")
    say(f"{name} runs through its scene's run step (sub-cases {', '.join(subs) or 'none'}; log.run)")
    log = os.path.join(case, "log.run")
    p, f = ex.scene_run(name, case, np_, log)
    t0, current, rep = time.time(), None, None
    try:
        while p.poll() is None:
            logs = [os.path.join(case, s, "log.meltdemFoam") for s in subs]
            logs = [x for x in logs if os.path.exists(x)]
            if logs:
                newest = max(logs, key=os.path.getmtime)
                if newest != current:
                    if rep:
                        rep.update(final=True)
                    current = newest
                    sub = os.path.dirname(newest)
                    t_end = fd.number(fd.read(os.path.join(sub, "system", "controlDict")), "endTime")
                    say(f"{os.path.basename(sub)}:")
                    rep = Reporter(FoamProgress(newest, t_end))
                rep.update()
            time.sleep(0.5)
    finally:
        f.close()
    if rep:
        rep.update(final=True)
    if p.returncode != 0:
        raise StepError(f"{name} scene run failed (rc {p.returncode}): read {log}")
    return time.time() - t0, subs


# ------------------------------------------------------------------------------------- post
def postprocess(case, example=None, analyse=True):
    try:
        from . import post
    except ImportError as e:
        say(f"post-processing unavailable (meltdem.cli.post: {e})")
        return None
    say("post-processing (VTK series, plots, summary)")
    try:
        return post.postprocess(case, example=example, analyse=analyse)
    except Exception as e:  # post-processing must not hide a finished run
        raise StepError(f"post-processing failed ({type(e).__name__}: {e}); the run's output is in {case}; "
                        f"retry with: meltdem post {case}")


# ------------------------------------------------------------------------------------- main
def run(target, case=None, np_=1, resume=False, size="ci", check_first=True, analyse=True, checkpoint_every=None):
    """Returns 0; raises StepError with the one-line reason. The case is locked for the whole run
    (caselock.py): a second run of the same case stops before it touches anything."""
    name = target if target in ex.names() and not (os.sep in target or target.startswith(".")) else None
    if name is None and not os.path.isdir(target):
        raise StepError(f"'{target}' is neither an example ({', '.join(ex.names())}) nor a case folder")
    if name:
        case = os.path.abspath(case or os.path.join(os.getcwd(), name))
        if resume and not os.path.isdir(case):
            raise StepError(f"cannot resume {name}: no case folder {case} (run it first, or give --case DIR)")
    else:
        if case and os.path.abspath(case) != os.path.abspath(target):
            raise StepError(f"--case applies to example names only: '{target}' is a case folder and runs where it "
                            f"is; copy it to {case} and run that, or leave out --case")
        case = os.path.abspath(target)
    if any(c.isspace() for c in case):
        raise StepError(f"the case path '{case}' has white space, which OpenFOAM's file names cannot hold; "
                        f"move or rename the case folder")
    os.makedirs(case, exist_ok=True)
    lock = caselock.CaseLock(case, f"meltdem run {target}{' --resume' if resume else ''}")
    try:
        lock.acquire()
    except caselock.CaseLocked as e:
        raise StepError(str(e))
    try:
        # the ranks of a killed run outlive its launcher for a moment: a resume started at once
        # would share the output files with them
        try:
            waited = caselock.wait_for_solvers(case)
        except caselock.CaseLocked as e:
            raise StepError(str(e))
        if lock.stale:
            say(f"took over the case lock of a run that ended without releasing it ({lock.stale})")
        if waited:
            say("waited for the processes of an earlier run to end: " + ", ".join(f"pid {p} {n}" for p, n in waited))
        return _run(name, target, case, lock, np_, resume, size, check_first, analyse, checkpoint_every)
    finally:
        lock.release()


def _run(name, target, case, lock, np_, resume, size, check_first, analyse, checkpoint_every=None):
    if name:
        if resume:
            say(f"resuming {name} in {case} (not rebuilt)")
        else:
            say(f"building {name} ({size}) into {case} (log.build)")
            ex.build(name, case, size)
            lock.refresh()
    elif size == "full":
        say("--full applies to example names only: the case folder runs as it is")
    t_start = time.time()
    kind = chk.case_kind(case)
    if kind is None and name and ex.has_step(name, "run"):
        if resume:
            raise StepError(f"--resume is not supported for {name} "
                            "(it runs several sub-cases through its own run step)")
        _, subs = run_scene(name, case, np_)
        for s in subs:
            postprocess(os.path.join(case, s), example=name, analyse=analyse)
        if analyse:
            say(f"analysing: {name}'s analyse step (log.analyse)")
            ex.analyse(name, case)
    else:
        if check_first:
            rep, kind = chk.check(case)
            if rep.problems:
                chk.print_report(case, rep, kind, out=sys.stderr)
                raise StepError(f"{case} fails its checks ({len(rep.problems)} problem(s) above); fix them or "
                                f"see: meltdem check {case}")
            say(f"check: {len(rep.checked)} item(s) OK")
        if kind == "foam":
            if checkpoint_every is not None:
                say("--checkpoint-every applies to DEM-only cases: this case checkpoints at the write times "
                    "of its system/controlDict")
            run_foam(case, np_, resume, rebuilt=bool(name) and not resume)
        else:
            run_dem(case, np_, resume, checkpoint_every)
        # the scene's analysis first: post-processing then takes its numbers (bead, efficiency,
        # packing) from the summary.json it wrote instead of running the analysis a second time
        if name and analyse and ex.has_step(name, "analyse"):
            say(f"analysing: {name}'s analyse step (log.analyse)")
            ex.analyse(name, case)
        postprocess(case, example=name, analyse=analyse)
    say(f"done in {time.time() - t_start:.0f} s: {case}")
    for f in ("summary.md", "summary.json"):
        if os.path.isfile(os.path.join(case, f)):
            say(f"summary: {os.path.join(case, f)}")
            break
    return 0
