#!/usr/bin/python3
"""Plot a conservation-ledger CSV (coupling/conservation_ledger.h) like Codina2019 figures 2.3-2.14.

    plot_ledger.py ledger.csv [-o ledger.png] [-c mass enthalpy mom_y]

One row per component: the totals (continuum, whole system; Codina2019 fig. 2.3/2.7/2.11), the
continuum's sources against its change per step (fig. 2.4/2.9/2.12) and the relative balance
errors (eq. 2.20/2.26/2.36, fig. 2.6/2.10/2.14; absolute value on a log axis). Prints the worst
errors per component.
"""
import argparse
import sys

import numpy as np


def load(path):
    data = np.genfromtxt(path, delimiter=",", names=True)
    if data.ndim == 0:
        data = data.reshape(1)
    return data


def continuum_sources(d, c):
    return d[c + "_exchange"] + d[c + "_boundary_in"] - d[c + "_boundary_out"] + d[c + "_continuum_source"]


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("csv")
    ap.add_argument("-o", "--output", default=None, help="PNG (default: CSV name with .png)")
    ap.add_argument("-c", "--components", nargs="+", default=["mass", "enthalpy", "mom_y"])
    a = ap.parse_args(argv)
    d = load(a.csv)
    for c in a.components:
        if c + "_total" not in d.dtype.names:
            sys.exit(f"plot_ledger: no component '{c}' in {a.csv}")
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    t = d["time"]
    units = {"mass": "kg", "enthalpy": "J", "mom_x": "kg m/s", "mom_y": "kg m/s", "mom_z": "kg m/s"}
    fig, ax = plt.subplots(len(a.components), 3, figsize=(15, 3.6 * len(a.components)), squeeze=False)
    for i, c in enumerate(a.components):
        u = units.get(c, "")
        ax[i, 0].plot(t, d[c + "_continuum"], label="continuum")
        ax[i, 0].plot(t, d[c + "_total"], "--", label="system (particles + continuum + pending)")
        ax[i, 0].set_ylabel(f"{c} [{u}]")
        ax[i, 0].set_title(f"{c}: totals")
        diff = np.diff(d[c + "_continuum"], prepend=np.nan)
        ax[i, 1].plot(t[1:], continuum_sources(d, c)[1:], label="sources (exchange + in - out + ext.)")
        ax[i, 1].plot(t[1:], diff[1:], "--", label="new - old")
        ax[i, 1].set_title(f"{c}: continuum balance terms per step")
        for col, lab in ((c + "_continuum_error", "continuum (thesis)"), (c + "_system_error", "system"),
                         (c + "_cumulative_system_error", "system, cumulative")):
            y = np.abs(d[col][1:])
            ax[i, 2].semilogy(t[1:], np.where(y > 0, y, np.nan), label=lab)
        ax[i, 2].set_title(f"{c}: |relative balance error|")
        for k in range(3):
            ax[i, k].set_xlabel("time [s]")
            ax[i, k].legend(fontsize=7)
        print(f"{c}: worst |continuum error| {np.nanmax(np.abs(d[c + '_continuum_error'])):.3e}, "
              f"worst |system error| {np.nanmax(np.abs(d[c + '_system_error'])):.3e}, "
              f"final cumulative system error {d[c + '_cumulative_system_error'][-1]:.3e}")
    fig.tight_layout()
    out = a.output or (a.csv.rsplit(".", 1)[0] + ".png")
    fig.savefig(out, dpi=90)
    print("wrote", out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
