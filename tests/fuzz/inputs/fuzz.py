#!/usr/bin/env python3
"""Fuzzing the inputs a user writes: random mutations of valid DEM inputs and coupled
cases, each run the way a user runs it, under a time limit. Every mutation must end either

  ran      exit code 0 (coupled: the ledger's per-step system mass and energy errors below
           1e-8 in summary.json, i.e. closed balances), or
  named    a non-zero exit code with a message that names the problem: LAMMPS's 'ERROR: ...'
           line, or meltdem's 'meltdem: ERROR: ...' line (which carries meltdem check's
           'file: entry' lines or the solver's first error line),

and never with a crash (a signal, an abort, 'terminate called', a Python traceback), a hang (the
time limit), or unclosed balances after exit code 0.

Seeds: the DEM input tests/cli/kill_resume/in.bed cut to 3000 steps (run by meltdem-lmp), the
Codina2019 §2.3 channel with one particle cut to 5e-4 s and ded-stream's CI case cut to 0.4 us (both
run by `meltdem run CASE --no-analyse`: check, solver, post-processing). Mutations: a number
made out of range (0, negative, 1e300, 1e-300), nan or inf, a number replaced by a word, a token
deleted, a keyword misspelt, a line deleted or duplicated, a file truncated.

usage: fuzz.py N_DEM N_COUPLED SEED [--show]   (CI: 40 24 17; the long variant: label long)
--show prints every mutation with the line it ended with.
Counts of mutations tried and of each outcome are reported as validation rows; every failing
mutation is printed with its seed, file and edit, so that it can be replayed."""
import glob
import json
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile

from meltdem import paths
from meltdem.testing.cli import meltdem_command
from meltdem.testing.report import check_absolute, report_info
from meltdem.testing.thesis_case import thesis_particle

SRC = paths.source_dir()
BIN = paths.bin_dir()

N_DEM, N_COUPLED, SEED = (int(x) for x in sys.argv[1:4])
LONG = "--long" in sys.argv
SHOW = "--show" in sys.argv   # print each mutation with the message it ended with
TEST = "fuzz.long" if LONG else "fuzz"
TIMEOUT = {"dem": 60, "coupled": 240}
CRASH = ("Traceback (most recent call last)", "terminate called", "Signal: Segmentation", "Signal: Aborted",
         "Floating point exception", "*** Process received signal", "core dumped")
NUMBER = re.compile(r"(?<![\w.$\[{-])[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?(?![\w.])")


def mutate_text(text, rng):
    """(new text, what was done) for one random mutation of a LAMMPS input or a dictionary."""
    lines = text.split("\n")
    body = [i for i, ln in enumerate(lines) if ln.strip() and not ln.lstrip().startswith(("#", "//", "FoamFile"))]
    kind = rng.choice(["number", "number", "number", "nonfinite", "word", "drop_token", "typo", "drop_line",
                       "dup_line", "truncate"])
    if kind == "truncate":
        cut = rng.randrange(0, max(1, len(text)))
        return text[:cut], f"truncated at byte {cut} of {len(text)}"
    i = rng.choice(body)
    ln = lines[i]
    if kind in ("number", "nonfinite", "word"):
        nums = list(NUMBER.finditer(ln))
        if not nums:
            kind = "typo"
        else:
            m = rng.choice(nums)
            new = (rng.choice(["0", "-1", "-0.5", "1e300", "1e-300", "-1e300", "2", "1e6"]) if kind == "number"
                   else rng.choice(["nan", "inf", "-inf", "NaN"]) if kind == "nonfinite"
                   else rng.choice(["abc", "on", "yes", "none", "x1"]))
            lines[i] = ln[:m.start()] + new + ln[m.end():]
            return "\n".join(lines), f"line {i + 1}: {m.group(0)} -> {new}: {lines[i].strip()[:120]}"
    if kind == "drop_token":
        toks = ln.split()
        if len(toks) > 1:
            k = rng.randrange(1, len(toks))
            lines[i] = " ".join(toks[:k] + toks[k + 1:])
            return "\n".join(lines), f"line {i + 1}: token '{toks[k]}' deleted: {lines[i].strip()[:120]}"
        kind = "typo"
    if kind == "typo":
        words = [m for m in re.finditer(r"[A-Za-z_/]{3,}", ln)]
        if words:
            m = rng.choice(words)
            w = m.group(0)
            j = rng.randrange(len(w) - 1)
            t = w[:j] + w[j + 1] + w[j] + w[j + 2:] if w[j] != w[j + 1] else w + "x"
            lines[i] = ln[:m.start()] + t + ln[m.end():]
            return "\n".join(lines), f"line {i + 1}: '{w}' -> '{t}'"
        kind = "drop_line"
    if kind == "dup_line":
        lines.insert(i, ln)
        return "\n".join(lines), f"line {i + 1} duplicated: {ln.strip()[:120]}"
    del lines[i]
    return "\n".join(lines), f"line {i + 1} deleted: {ln.strip()[:120]}"


def outcome(rc, out, closed=True):
    if rc is None:
        return "hang"
    if any(c in out for c in CRASH) or rc < 0 or rc >= 128:
        return "crash"
    if rc == 0:
        return "ran" if closed else "unclosed"
    named = re.search(r"^(ERROR|meltdem: ERROR:|  ERROR )\S*.*\S", out, re.M) is not None
    return "named" if named else "unnamed"


def message(out):
    """the line that names the problem (LAMMPS ERROR, meltdem ERROR), '' if none"""
    m = re.findall(r"^(?:ERROR.*|meltdem: ERROR:.*|  ERROR .*)$", out, re.M)
    return m[0][:220] if m else ""


def show(label, what, o, out):
    if SHOW:
        print(f"{label}: {what}\n    -> {o}: {message(out) if o != 'ran' else 'exit 0'}")


def run(cmd, cwd, limit):
    try:
        p = subprocess.run(cmd, cwd=cwd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                           errors="replace", timeout=limit, start_new_session=True)
        return p.returncode, p.stdout
    except subprocess.TimeoutExpired as e:
        out = e.stdout.decode(errors="replace") if isinstance(e.stdout, bytes) else (e.stdout or "")
        return None, out


def dem_seed(work):
    d = os.path.join(work, "dem_seed")
    os.makedirs(d)
    text = open(os.path.join(SRC, "tests", "cli", "kill_resume", "in.bed")).read()
    text = re.sub(r"^run\s+\d+", "run             3000", text, flags=re.M)
    text = text.replace("ave/time 5000 1 5000", "ave/time 500 1 500").replace("custom 20000", "custom 1000")
    open(os.path.join(d, "in.bed"), "w").write(text)
    return d


def coupled_seeds(work):
    tp = thesis_particle()
    from meltdem.case import coupled as cc
    channel = os.path.join(work, "channel_seed")
    cc.channel_case(channel, "centre", dict(d=tp.D, rho=tp.RHO_P, cp=tp.CP_P, Tm=tp.TM, L=tp.L, T0=0.0, y=17.6e-3),
                    t_end=5e-4)
    ded = os.path.join(work, "ded_seed")
    subprocess.run(["/usr/bin/python3", os.path.join(SRC, "examples", "ded-stream", "scene.py"), "build", ded, "--ci"],
                   check=True, stdout=subprocess.DEVNULL)
    p = os.path.join(ded, "system", "controlDict")
    text = re.sub(r"^endTime .*$", "endTime 4e-07;", open(p).read(), flags=re.M)
    open(p, "w").write(text)
    return [channel, ded]


def case_files(case):
    """the files a user edits: dictionaries, field headers, the LAMMPS input"""
    out = [f for f in glob.glob(os.path.join(case, "system", "*")) + glob.glob(os.path.join(case, "constant", "*"))
           if os.path.isfile(f)]
    out += [f for f in glob.glob(os.path.join(case, "0", "*")) if os.path.getsize(f) < 200_000]
    out += glob.glob(os.path.join(case, "in.*"))
    return sorted(out)


def closed_balances(case):
    try:
        s = json.load(open(os.path.join(case, "summary.json")))
    except (OSError, ValueError):
        return False
    errs = [s.get(k) for k in ("worst_step_system_mass_error", "worst_step_system_energy_error")]
    return all(isinstance(e, (int, float)) and abs(e) < 1e-8 for e in errs)


def main():
    rng = random.Random(SEED)
    work = tempfile.mkdtemp(prefix="meltdem-fuzz-")
    counts = {"dem": {}, "coupled": {}}
    failures = []

    dseed = dem_seed(work)
    rc, out = run([os.path.join(BIN, "meltdem-lmp"), "-in", "in.bed", "-log", "none"], dseed, TIMEOUT["dem"])
    seeds_ok = check_absolute(TEST, "DEM seed input runs unmutated (exit code)", rc if rc is not None else -1, 0, 0)
    for n in range(N_DEM):
        case = os.path.join(work, f"dem_{n}")
        shutil.copytree(dseed, case)
        p = os.path.join(case, "in.bed")
        text, what = mutate_text(open(p).read(), rng)
        open(p, "w").write(text)
        rc, out = run([os.path.join(BIN, "meltdem-lmp"), "-in", "in.bed", "-log", "none"], case, TIMEOUT["dem"])
        o = outcome(rc, out)
        show(f"dem_{n}", what, o, out)
        counts["dem"][o] = counts["dem"].get(o, 0) + 1
        if o in ("ran", "named"):
            shutil.rmtree(case, ignore_errors=True)
        else:
            failures.append((f"dem_{n}", "in.bed", what, o, out[-1500:]))

    cseeds = coupled_seeds(work)
    for s in cseeds:
        c = s + "_run"
        shutil.copytree(s, c)
        rc, out = run(meltdem_command() + ["run", c, "--no-analyse"], work, TIMEOUT["coupled"])
        seeds_ok &= check_absolute(TEST, f"coupled seed {os.path.basename(s)} runs unmutated (exit code)",
                                   rc if rc is not None else -1, 0, 0)
        seeds_ok &= check_absolute(TEST, f"coupled seed {os.path.basename(s)}: closed balances",
                                   int(closed_balances(c)), 1, 0)
    for n in range(N_COUPLED):
        seed = cseeds[n % len(cseeds)]
        case = os.path.join(work, f"coupled_{n}")
        shutil.copytree(seed, case)
        f = rng.choice(case_files(case))
        text, what = mutate_text(open(f, errors="replace").read(), rng)
        open(f, "w").write(text)
        rel = os.path.relpath(f, case)
        rc, out = run(meltdem_command() + ["run", case, "--no-analyse"], work, TIMEOUT["coupled"])
        o = outcome(rc, out, closed_balances(case))
        show(f"coupled_{n} {os.path.basename(seed)} {rel}", what, o, out)
        counts["coupled"][o] = counts["coupled"].get(o, 0) + 1
        if o in ("ran", "named"):
            shutil.rmtree(case, ignore_errors=True)
        else:
            failures.append((f"coupled_{n} ({os.path.basename(seed)})", rel, what, o, out[-2000:]))

    for label, who, what, o, out in failures:
        print(f"=== {o}: {label}, {who}: {what}\n{out}\n")
    ok = seeds_ok
    for kind, n in (("dem", N_DEM), ("coupled", N_COUPLED)):
        c = counts[kind]
        print(f"{kind}: {n} mutations (seed {SEED}): " + ", ".join(f"{k} {v}" for k, v in sorted(c.items())))
        ok &= check_absolute(TEST, f"{kind} mutations tried", sum(c.values()), n, 0)
        for good in ("ran", "named"):
            result = "ran with closed balances" if good == "ran" else "stopped with a named error"
            ok &= report_info(TEST, f"{kind} mutations that {result} (count, info)", c.get(good, 0))
        for bad in ("crash", "hang", "unclosed", "unnamed"):
            ok &= check_absolute(TEST, f"{kind} mutations ending in a {bad}", c.get(bad, 0), 0, 0)
    from meltdem.case import foam as fc
    return fc.finish(ok, work)


if __name__ == "__main__":
    sys.exit(main())
