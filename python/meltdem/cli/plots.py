"""PNG plots of a run (matplotlib, Agg): balances, melted mass, absorbed laser power and, for a
moving laser, the bead cross-section. Each function returns the path written, or None when the
case has nothing to plot for it."""
import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

FLOOR = 1e-18   # lowest |relative error| shown: below double round-off
COMPONENTS = (("mass", "mass", "C0"), ("enthalpy", "energy (enthalpy)", "C3"), ("mom", "momentum", "C2"))


def _save(fig, path):
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def _time_plot(fig, ax, path, time_unit, ylabel):
    """Label, grid, legend and save a single plot over time."""
    ax.set_xlabel(f"time [{time_unit}]")
    ax.set_ylabel(ylabel)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    return _save(fig, path)


def _time_unit(t):
    """(factor, unit) for a time axis reaching t [s]."""
    t = float(np.max(t)) if np.size(t) else 0.0
    if t >= 0.1:
        return 1.0, "s"
    if t >= 1e-4:
        return 1e3, "ms"
    return 1e6, "us"


def _abs_log(v):
    v = np.abs(np.asarray(v, float))
    return np.where(v > 0, v, np.nan)


def _component(led, comp, kind):
    """|error| series of one ledger component; momentum: the largest of x, y, z."""
    if comp == "mom":
        cols = [f"mom_{c}_{kind}" for c in "xyz" if f"mom_{c}_{kind}" in led.dtype.names]
        if not cols:
            return None
        return np.max(np.abs(np.column_stack([led[c] for c in cols])), axis=1)
    c = f"{comp}_{kind}"
    return np.abs(led[c]) if c in led.dtype.names else None


def balances(path, led=None, bal=None):
    """Per-step and cumulative relative balance errors (log |error|): the ledger's system
    (particles + continuum + pending) and continuum errors, else meltdemBalance's relative ones."""
    if led is None and bal is None:
        return None
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharex=True)
    tf, tu = _time_unit(led["time"] if led is not None else bal["time"])
    if led is not None and len(led) > 1:
        t = led["time"][1:] * tf
        for comp, label, colour in COMPONENTS:
            for kind, style, tag in (("system_error", "-", "system"), ("continuum_error", "--", "continuum")):
                v = _component(led[1:], comp, kind)
                if v is not None:
                    axes[0].plot(t, _abs_log(v), style, color=colour, lw=1, label=f"{label}, {tag}")
                v = _component(led[1:], comp, "cumulative_" + kind)
                if v is not None:
                    axes[1].plot(t, _abs_log(v), style, color=colour, lw=1, label=f"{label}, {tag}")
        axes[0].set_title("per step: |(sources - change) / total| (ledger)")
        axes[1].set_title("cumulative since the start (ledger)")
    elif bal is not None:
        t = bal["time"] * tf
        names = bal.dtype.names
        for col, label, colour in (("massErrorRel", "mass", "C0"), ("enthalpyErrorRel", "energy (enthalpy)", "C3"),
                                   ("momentumErrorRel", "momentum", "C2")):
            if col in names:
                axes[1].plot(t, _abs_log(bal[col]), color=colour, lw=1, label=label)
                axes[0].plot(t[1:], _abs_log(np.diff(bal[col])), color=colour, lw=1, label=label)
        axes[0].set_title("per step: change of the relative error (meltdemBalance)")
        axes[1].set_title("cumulative relative error (meltdemBalance)")
    for ax in axes:
        ax.set_yscale("log")
        lo, hi = ax.get_ylim()
        if lo < FLOOR < hi:       # round-off zeros (1e-50) would squeeze the scale
            ax.set_ylim(bottom=FLOOR)
        ax.set_xlabel(f"time [{tu}]")
        ax.set_ylabel("|relative error|")
        ax.grid(True, which="both", alpha=0.3)
        if ax.lines:
            ax.legend(fontsize=7)
    return _save(fig, path)


def melted_mass(path, led=None, pcsv=None):
    """Metal handed over by the particles (ledger exchange, cumulative), the molten mass fix
    powder/melt reports (particles.csv), particle and continuum metal, feed and losses."""
    if led is None and pcsv is None:
        return None
    fig, ax = plt.subplots(figsize=(7, 4.2))
    tf, tu = _time_unit(led["time"] if led is not None else pcsv["time"])
    if led is not None:
        t = led["time"] * tf
        ax.plot(t, np.cumsum(led["mass_exchange"]), "C3", lw=2, label="metal handed to the continuum (ledger)")
        ax.plot(t, led["mass_particles"], "C0", lw=1, label="metal in particles")
        ax.plot(t, led["mass_continuum"] - led["mass_continuum"][0], "C1", lw=1, label="continuum metal gained")
        if np.any(led["mass_feed"]):
            ax.plot(t, np.cumsum(led["mass_feed"]), "C2", lw=1, label="powder fed")
        if np.any(led["mass_cumulative_lost"]):
            ax.plot(t, led["mass_cumulative_lost"], "C7", lw=1, label="left the mesh (lost)")
    if pcsv is not None and "mass_melted" in pcsv.dtype.names:
        ax.plot(pcsv["time"] * tf, np.cumsum(pcsv["mass_melted"]), "k:", lw=1.5, label="molten (fix powder/melt)")
    return _time_plot(fig, ax, path, tu, "mass [kg]")


def absorbed_power(path, bal=None, pcsv=None, eta_p=None):
    """Laser power absorbed by the continuum (meltdemBalance laserPower) and the particles
    (particles.csv laser_heat / dt) vs time; eta P as a reference line."""
    has_c = bal is not None and "laserPower" in bal.dtype.names
    has_p = pcsv is not None and "laser_heat" in pcsv.dtype.names
    if not (has_c or has_p):
        return None
    fig, ax = plt.subplots(figsize=(7, 4.2))
    tf, tu = _time_unit(bal["time"] if has_c else pcsv["time"])
    if has_c:
        ax.plot(bal["time"] * tf, bal["laserPower"], "C1", lw=1, label="continuum")
    if has_p:
        ax.plot(pcsv["time"] * tf, pcsv["laser_heat"] / pcsv["dt"], "C0", lw=1, label="particles")
    if has_c and has_p:
        t = pcsv["time"]
        ax.plot(t * tf, np.interp(t, bal["time"], bal["laserPower"]) + pcsv["laser_heat"] / pcsv["dt"], "k", lw=1.5,
                label="total")
    if eta_p:
        ax.axhline(eta_p, color="0.5", ls="--", lw=1, label="absorptivity x power")
    return _time_plot(fig, ax, path, tu, "absorbed laser power [W]")


def cross_section(centres, fields, trk):
    """Cells of the slice across the track at its middle: (u across, v up, their alpha.metal,
    liquid fraction or None, the slice's along-track position). Cells: the layer of cell
    centres nearest to the track's middle."""
    axis, up = trk["axis"], trk["up"]
    across = np.cross(axis, up)
    across /= np.linalg.norm(across)
    if across[np.argmax(np.abs(across))] < 0:   # along a world axis: its positive direction
        across = -across
    mid = 0.5 * (trk["start"] + trk["end"])
    s = (centres - mid) @ axis
    layers = np.unique(np.round(s, 9))          # 1 nm: cell centres of one layer agree to that
    s0 = layers[np.argmin(np.abs(layers))]
    sel = np.abs(s - s0) <= 1e-9
    u = centres[sel] @ across
    v = centres[sel] @ up
    a = fields["alpha.metal"][sel]
    lf = fields["liquidFraction"][sel] if "liquidFraction" in fields else None
    return u, v, a, lf, float(mid @ axis + s0)


def _length_unit(extent):
    return (1e3, "mm") if extent > 2e-3 else (1e6, "um")


def _time_text(t):
    if t >= 1e-2:
        return f"{t:.4g} s"
    if t >= 1e-5:
        return f"{t * 1e3:.4g} ms"
    return f"{t * 1e6:.4g} us"


def bead_profile(path, centres, fields, trk, time, tmax_lf=None):
    """Metal fraction on the cross-section of the track at its middle, last written time; the
    alpha = 1/2 contour (surface) and, when given, the fused zone (tmax_lf: per cell of the
    section the largest liquid fraction the cell reached while metal, contour 1/2). Zoomed to the
    bead: the cells fused or partly metal, with a margin of their own size."""
    if trk is None or "alpha.metal" not in fields:
        return None
    u, v, a, lf, pos = cross_section(centres, fields, trk)
    if len(u) < 4:
        return None
    uu, vv = np.unique(np.round(u, 9)), np.unique(np.round(v, 9))
    # the section's outer cell faces (centres +- half the end cells)
    ulo = u.min() - (uu[1] - uu[0]) / 2 if len(uu) > 1 else u.min()
    uhi = u.max() + (uu[-1] - uu[-2]) / 2 if len(uu) > 1 else u.max()
    vlo = v.min() - (vv[1] - vv[0]) / 2 if len(vv) > 1 else v.min()
    vhi = v.max() + (vv[-1] - vv[-2]) / 2 if len(vv) > 1 else v.max()
    busy = (a > 0.01) & (a < 0.99)
    if tmax_lf is not None:
        busy |= tmax_lf >= 0.5
    if busy.any():
        box = [u[busy].min(), u[busy].max(), v[busy].min(), v[busy].max()]
        m = max(box[1] - box[0], box[3] - box[2], 1e-12)
        box = [max(box[0] - m, ulo), min(box[1] + m, uhi), max(box[2] - m, vlo), min(box[3] + m, vhi)]
    else:
        box = [ulo, uhi, vlo, vhi]
    f, unit = _length_unit(max(box[1] - box[0], box[3] - box[2]))
    fig, ax = plt.subplots(figsize=(7, 4.6))
    drawn_fused = False
    if len(uu) * len(vv) == len(u):
        iu = np.searchsorted(uu, np.round(u, 9))
        iv = np.searchsorted(vv, np.round(v, 9))
        A = np.full((len(vv), len(uu)), np.nan)
        A[iv, iu] = a
        im = ax.pcolormesh(uu * f, vv * f, A, shading="nearest", cmap="viridis", vmin=0, vmax=1)
        ax.contour(uu * f, vv * f, A, levels=[0.5], colors="w", linewidths=1.5)
        if tmax_lf is not None:
            L = np.full((len(vv), len(uu)), np.nan)
            L[iv, iu] = tmax_lf
            if np.nanmax(L) >= 0.5:
                ax.contour(uu * f, vv * f, L, levels=[0.5], colors="r", linewidths=1.2, linestyles="--")
                drawn_fused = True
    else:
        im = ax.tricontourf(u * f, v * f, a, levels=np.linspace(0, 1, 11), cmap="viridis")
    fig.colorbar(im, ax=ax, label="metal fraction alpha.metal")
    ax.set_xlim(box[0] * f, box[1] * f)
    ax.set_ylim(box[2] * f, box[3] * f)
    ax.set_aspect("equal")
    ax.set_xlabel(f"across the track [{unit}]")
    ax.set_ylabel(f"up (against the beam) [{unit}]")
    ax.set_title(f"bead cross-section at {pos * f:.4g} {unit} along the track, t = {_time_text(time)}"
                 + ("\n(white: surface alpha = 1/2; red dashed: fused, liquid fraction reached 1/2)"
                    if drawn_fused else "\n(white: surface alpha = 1/2)"), fontsize=9)
    return _save(fig, path)
