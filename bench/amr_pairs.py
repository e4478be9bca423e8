"""Table and plot of AMR-vs-uniform pairs for bench/amr.py and bench/amr_ded.py: rows are dicts with
cell_um (finest cell), levels (0: uniform), cells, cpu_s and the scene's measures."""
import os


def table(rows, columns):
    """Markdown lines: each uniform run, then the AMR runs of its finest cell with the change of every
    compared column and the CPU ratio. columns: [(key, header, format, compared)]."""
    compared = [c for c in columns if c[3]]
    head = ["finest cell [um]", "mesh", "most cells"] + [c[1] for c in columns] + ["CPU [s]"]
    head += [f"{c[1].split(' [')[0]} vs uniform" for c in compared] + ["CPU uniform / AMR"]
    lines = ["| " + " | ".join(head) + " |", "|" + "---|" * len(head)]
    for u in (r for r in rows if r["levels"] == 0):
        group = [u] + [r for r in rows if r["levels"] > 0 and r["cell_um"] == u["cell_um"]]
        for r in group:
            mesh = "uniform" if r is u else f"AMR, {r['levels']} level(s)"
            cells = [f"{r['cell_um']:g}", mesh, str(r["cells"])] + [fmt.format(r[k]) for k, _, fmt, _ in columns]
            cells.append(f"{r['cpu_s']:.0f}")
            if r is u:
                cells += [""] * (len(compared) + 1)
            else:
                cells += [f"{(r[k] / u[k] - 1) * 100:+.1f} %" for k, *_ in compared]
                cells.append(f"{u['cpu_s'] / r['cpu_s']:.2f}")
            lines.append("| " + " | ".join(cells) + " |")
    return lines


def plot(rows, key, ylabel, png, reference=None):
    """The measure `key` and the solver CPU against the finest cell, uniform and AMR."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(1, 2, figsize=(9, 3.6))
    for lv, mk in ((0, "o-"), (1, "s--"), (2, "^:")):
        sel = sorted((r for r in rows if r["levels"] == lv), key=lambda r: r["cell_um"])
        if sel:
            lab = "uniform" if lv == 0 else f"AMR {lv} level(s)"
            ax[0].plot([r["cell_um"] for r in sel], [r[key] for r in sel], mk, label=lab)
            ax[1].plot([r["cell_um"] for r in sel], [r["cpu_s"] for r in sel], mk, label=lab)
    if reference:
        ax[0].axhline(reference[0], color="k", lw=0.8, ls=":", label=reference[1])
    ax[0].set_xlabel("finest cell [um]")
    ax[0].set_ylabel(ylabel)
    ax[1].set_xlabel("finest cell [um]")
    ax[1].set_ylabel("solver CPU [s]")
    ax[0].legend()
    fig.tight_layout()
    fig.savefig(png, dpi=110)
    os.chmod(png, 0o644)
