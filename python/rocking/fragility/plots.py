"""Plots of a study: IDA curves (peak |theta| / alpha against the intensity, one line per
record, flat at its collapse intensity) and the fitted fragility with the empirical points."""

import math

import numpy as np


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def plot_ida(path, rows, analysis, im, title):
    """IDA curves of one body: `rows` its runs (DataFrame), `analysis` its entry of
    Study.analyse."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(7, 5))
    ok = rows[rows["error"] == ""]
    for i, (rname, r) in enumerate(ok.groupby("record")):
        color = f"C{i % 10}"
        cap = analysis["records"].get(rname, {})
        r = r.sort_values("im")
        stand = r[~r["overturned"].astype(bool)]
        if math.isfinite(cap.get("capacity", math.nan)) and not cap.get("censored", True):
            stand = stand[stand["im"] < cap["capacity"]]
        ax.plot(stand["peak_theta_over_alpha"], stand["im"], "o-", ms=3, lw=1, color=color,
                label=rname if len(rname) < 48 else "..." + rname[-45:])
        if not cap.get("censored", True):
            x0 = stand["peak_theta_over_alpha"].max() if len(stand) else 0.0
            ax.plot([x0, 1.6], [cap["capacity"]] * 2, lw=1, ls="--", color=color)
            ax.plot([1.6], [cap["capacity"]], "x", color=color)
        fails = r[r["overturned"].astype(bool)]
        ax.plot(np.full(len(fails), 1.7), fails["im"], "|", color=color, ms=6)
    ax.axvline(1.0, color="0.5", lw=0.6, ls=":")
    ax.set_xlim(0, 1.8)
    ax.set_xlabel("peak |theta| / alpha   (flat line: collapse intensity; ticks at 1.7: runs that overturned)")
    ax.set_ylabel(im.label)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=6, loc="upper left")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_fragility(path, fits, im, title, method):
    """Fitted lognormal fragilities {body: (Fragility or None, empirical)}, one panel each;
    empirical: IDA (collapse intensities, count censored), plotted at (i - 0.5) / n; stripes
    (intensities, fraction collapsed, runs)."""
    plt = _pyplot()
    n = len(fits)
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.6 * cols, 3.9 * rows), squeeze=False)
    for ax, (label, (frag, emp)) in zip(axes.flat, fits.items()):
        xmax = None
        if method == "ida":
            caps = np.sort(np.asarray(emp[0], dtype=float))
            total = len(caps) + emp[1]
            ax.plot(caps, (np.arange(1, len(caps) + 1) - 0.5) / total, "o", color="C1", ms=4,
                    label=f"collapse intensities ({emp[1]} of {total} censored)" if emp[1] else "collapse intensities")
            xmax = caps.max() * 1.2 if len(caps) else None
        else:
            stripes, frac, counts = emp
            ax.plot(stripes, frac, "s", color="C1", ms=4, label="fraction overturned at each stripe")
            xmax = max(stripes) * 1.05 if len(stripes) else None
        if frag is not None:
            xmax = max(xmax or 0, frag.median * math.exp(2 * frag.beta))
            x = np.linspace(0, xmax, 400)[1:]
            ax.plot(x, frag.probability(x), color="C0", lw=1.6,
                    label=f"lognormal: median {frag.median:.3g}, beta {frag.beta:.2f}")
            if math.isfinite(frag.median_ci[0]):
                ax.axvspan(*frag.median_ci, color="C0", alpha=0.12,
                           label=f"{frag.level:.0%} bootstrap interval of the median")
        else:
            ax.text(0.5, 0.5, "no fit", transform=ax.transAxes, ha="center")
        ax.set_xlim(0, xmax or 1)
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlabel(im.label)
        ax.set_ylabel("P(overturning)")
        ax.set_title(label, fontsize=10)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=6.5, loc="lower right")
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
