"""Absorptivity options shared by the melt-pool scenes: the command-line flags and the laser entries they set.

A scene keeps its own constant absorptivity as the default; --dabsorptivity-dt selects meltdemFoam's
`absorptivityModel linear` (foam-src/meltdemModels/terms/laser/README.md), eta at the scene's reference
temperature (its liquidus) plus the slope times the beam-weighted surface temperature's distance from it.
"""
import re

import numpy as np

_STEP_OR_ETA = re.compile(r"^Time = (\S+)$|Laser: surface temperature \S+ K, absorptivity (\S+)"
                          r"|Laser: absorbed power \S+ W", re.M)


def _get(a, key, default):
    """Entry `key` of parsed arguments, a dict of them (a scene's json), or None (all defaults)."""
    value = a.get(key) if isinstance(a, dict) else getattr(a, key, None)
    return default if value is None else value


def add_absorptivity_arguments(ap, default):
    """Add --absorptivity, --dabsorptivity-dt and --absorptivity-max to the argparse parser `ap`."""
    ap.add_argument("--absorptivity", type=float, default=None, metavar="ETA",
                    help=f"absorbed fraction of the beam (default {default:g})")
    ap.add_argument("--dabsorptivity-dt", type=float, default=None, metavar="PER_K",
                    help="absorptivity linear in the surface temperature under the beam: this slope [1/K], "
                    "--absorptivity at the liquidus (default: constant)")
    ap.add_argument("--absorptivity-min", type=float, default=0.0, metavar="ETA",
                    help="lower bound of the linear absorptivity (default 0)")
    ap.add_argument("--absorptivity-max", type=float, default=1.0, metavar="ETA",
                    help="upper bound of the linear absorptivity (default 1)")


def absorptivity(a, default):
    """The constant (or reference) absorptivity of parsed arguments `a`; raises ValueError outside [0, 1]."""
    eta = _get(a, "absorptivity", default)
    lo, hi = _get(a, "absorptivity_min", 0.0), _get(a, "absorptivity_max", 1.0)
    if not 0.0 <= eta <= 1.0:
        raise ValueError(f"--absorptivity {eta:g} must be in [0, 1]")
    if not 0.0 <= lo <= hi <= 1.0:
        raise ValueError(f"--absorptivity-min {lo:g} and --absorptivity-max {hi:g} need 0 <= min <= max <= 1")
    return eta


def absorptivity_entries(a, default, t_reference, indent="    "):
    """Laser-dictionary lines for the absorptivity of parsed arguments `a`: `absorptivity` and, with
    --dabsorptivity-dt, the linear model referenced at t_reference [K]."""
    eta = absorptivity(a, default)
    lines = [f"absorptivity {eta!r};"]
    if _get(a, "dabsorptivity_dt", None) is not None:
        lines += ["absorptivityModel linear;", f"dAbsorptivitydT {_get(a, 'dabsorptivity_dt', 0.0)!r};",
                  f"Tabsorptivity {float(t_reference)!r};", f"absorptivityMin {_get(a, 'absorptivity_min', 0.0)!r};",
                  f"absorptivityMax {_get(a, 'absorptivity_max', 1.0)!r};"]
    return "".join(f"{indent}{s}\n" for s in lines)


def absorptivity_meta(a, default):
    """The absorptivity settings of `a` for a scene's json (which the functions here read back as `a`)."""
    return dict(absorptivity=absorptivity(a, default), dabsorptivity_dt=_get(a, "dabsorptivity_dt", None),
                absorptivity_min=_get(a, "absorptivity_min", 0.0), absorptivity_max=_get(a, "absorptivity_max", 1.0))


def check_absorptivity_arguments(ap, a, default):
    """Stop with the parser's usage error when the absorptivity flags of `a` are out of range."""
    try:
        absorptivity(a, default)
    except ValueError as e:
        ap.error(str(e))


def step_absorptivity(log_text, eta0):
    """The absorptivity each fluid step of a meltdemFoam log used: (step end times, eta per step, eta per
    'Laser: absorbed power' line). The linear model prints its eta before the step's heat source; a step
    without a print keeps the previous eta, the first ones eta0."""
    times, etas, per_line = [], [], []
    eta = eta0
    for m in _STEP_OR_ETA.finditer(log_text):
        if m.group(1) is not None:
            times.append(float(m.group(1)))
            etas.append(eta)
        elif m.group(2) is not None:
            eta = float(m.group(2))
            if etas:
                etas[-1] = eta
        else:
            per_line.append(eta)
    return np.array(times), np.array(etas), np.array(per_line)


def absorbed_fraction_integral(log_text, eta0, lit_time):
    """Integral of eta over the beam's on-time up to the log's last step: sum over steps of eta times the
    lit time in the step; lit_time(t) is the cumulative on-time [s]."""
    t, eta, _ = step_absorptivity(log_text, eta0)
    if not len(t):
        return 0.0
    edges = np.concatenate(([0.0], t))
    lit = np.array([lit_time(x) for x in edges])
    return float(np.sum(eta * np.diff(lit)))
