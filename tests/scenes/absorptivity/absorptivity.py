#!/usr/bin/env python3
"""The melt-pool scenes' absorptivity options (meltdem.case.laser): --absorptivity, and
--dabsorptivity-dt with --absorptivity-min/-max selecting meltdemFoam's linear model.

Checks (measured | reference | tolerance):
- every melt-pool scene (single-track, slm-track, lmd-track, ded-stream, pbf-point, pbf-line,
  pbf-layer) writes the linear model's entries into constant/meltdemProperties laser{} as given,
  referenced at its metal's liquidus (exact);
- each refuses an absorptivity outside [0, 1] and min > max with a usage error naming the flag,
  before writing a case (exit status 2);
- ded-stream CI run with eta = 0.5 + 2e-4 (T_s - 1705 K), bounded to [0, 0.7]: every step's eta
  (solver log) is the model at the step's beam-weighted surface temperature (1e-9), continuum +
  particles absorb eta P on every lit step (1e-9), eta rises from the cold plate's 0.26 by at
  least 0.2 over the run (the model acts), and the ledger balances.
"""
import os
import re
import subprocess
import sys
import tempfile

import numpy as np

from meltdem import paths
from meltdem import scene as scenes
from meltdem.case import coupled as cc
from meltdem.case import foam as fc
from meltdem.testing.report import check_absolute, check_at_least, check_at_most

TEST = "scenes.absorptivity"
SRC = paths.source_dir()
LIQUIDUS = {"single-track": 1623.0, "slm-track": 1723.0, "lmd-track": 1727.0, "ded-stream": 1705.0,
            "pbf-point": 1705.0, "pbf-line": 1705.0, "pbf-layer": 1705.0}
LINEAR = ["--dabsorptivity-dt", "1.5e-4", "--absorptivity", "0.4", "--absorptivity-min", "0.2",
          "--absorptivity-max", "0.75"]


def script(name):
    return os.path.join(SRC, "examples", name, "scene.py")


def laser_entries(case):
    """laser{} of CASE/constant/meltdemProperties as {keyword: text}."""
    text = re.sub(r"//.*", "", open(os.path.join(case, "constant", "meltdemProperties")).read())
    body = re.search(r"^laser\s*\{(.*?)^\}", text, re.S | re.M).group(1)
    return {m.group(1): m.group(2).strip() for m in re.finditer(r"(\w+)\s+([^;]+);", body)}


def entries_and_usage(work):
    ok = True
    want = {"absorptivity": 0.4, "dAbsorptivitydT": 1.5e-4, "absorptivityMin": 0.2, "absorptivityMax": 0.75}
    for name, t_liq in LIQUIDUS.items():
        case = os.path.join(work, name)
        subprocess.run(["/usr/bin/python3", script(name), "build", case] + LINEAR, check=True,
                       stdout=subprocess.DEVNULL)
        got = laser_entries(case)
        wrong = [k for k, v in want.items() if float(got.get(k, "nan")) != v]
        wrong += [] if got.get("absorptivityModel") == "linear" else ["absorptivityModel"]
        wrong += [] if float(got.get("Tabsorptivity", "nan")) == t_liq else ["Tabsorptivity"]
        ok &= check_absolute(TEST, f"{name}: laser{{}} entries of the linear model not as given (count; "
                             f"wrong: {' '.join(wrong) or 'none'})", float(len(wrong)), 0.0, 0)
        for bad, flag in ((["--absorptivity", "1.5"], "--absorptivity 1.5"),
                          (["--dabsorptivity-dt", "1e-4", "--absorptivity-min", "0.6", "--absorptivity-max", "0.4"],
                           "--absorptivity-min 0.6")):
            stopped = os.path.join(work, name + "-bad")
            r = subprocess.run(["/usr/bin/python3", script(name), "build", stopped] + bad,
                               capture_output=True, text=True)
            named = r.returncode == 2 and flag in r.stderr and not os.path.exists(stopped)
            ok &= check_absolute(TEST, f"{name}: {' '.join(bad)} stops with a usage error naming {flag} and no case "
                                 f"(1 = yes; exit {r.returncode})", float(named), 1.0, 0)
    return ok


def ded_stream_run(work):
    ded = scenes.module("ded-stream")
    case = os.path.join(work, "ded-run")
    subprocess.run(["/usr/bin/python3", script("ded-stream"), "build", case, "--ci", "--dabsorptivity-dt", "2e-4",
                    "--absorptivity-max", "0.7"], check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["/usr/bin/python3", script("ded-stream"), "run", case], check=True, stdout=subprocess.DEVNULL)
    log = open(os.path.join(case, "log.meltdemFoam")).read()
    printed = np.array([(float(t), float(e)) for t, e in
                        re.findall(r"Laser: surface temperature (\S+) K, absorptivity (\S+)", log)])
    model = np.clip(0.5 + 2e-4 * (printed[:, 0] - 1705.0), 0.0, 0.7)
    ok = check_at_most(TEST, f"ded-stream: worst |eta - (0.5 + 2e-4 (T_s - 1705 K)) bounded to [0, 0.7]| over "
                       f"{len(printed)} steps", float(np.max(np.abs(printed[:, 1] - model))), 1e-9)
    ok &= check_at_least(TEST, "ded-stream: rise of eta over the run, from the cold plate's (the model acts)",
                         float(printed[:, 1].max() - printed[0, 1]), 0.2)
    t, dt, cont, part = ded.laser_budget(case)
    eta = ded.laser_absorptivity(case, 0.5)[:len(t)]
    lit = t - dt >= -1e-18
    err = np.abs(cont + part - eta * ded.P_LASER) / (eta * ded.P_LASER)
    ok &= check_at_most(TEST, f"ded-stream: worst |continuum + particles - eta P| / eta P on {int(lit.sum())} lit "
                        "steps, eta the step's", float(np.max(err[lit])), 1e-9)
    ok &= cc.check_balances(TEST, cc.ledger(case))
    return ok


def main():
    work = tempfile.mkdtemp(prefix="meltdem-absorptivity-")
    ok = entries_and_usage(work)
    ok &= ded_stream_run(work)
    return fc.finish(ok, work)


if __name__ == "__main__":
    sys.exit(main())
