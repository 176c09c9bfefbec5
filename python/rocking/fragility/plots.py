"""Plots of a study: IDA curves (peak |theta| / alpha against the intensity, one line per
record, flat at its collapse intensity) and the fitted fragility with the empirical points."""

import math

import numpy as np


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def _plain_log(axis, lo, hi):
    """Plain numbers on a log axis (0.5, 1, 2 rather than 5x10^-1); every minor tick labelled
    over a range under 30, those at 2 and 5 of each decade over a wider one."""
    from matplotlib.ticker import FuncFormatter
    fmt = FuncFormatter(lambda v, _: f"{v:g}")
    axis.set_major_formatter(fmt)
    if hi / lo < 30:
        axis.set_minor_formatter(fmt)
    else:  # 2 and 5 of each decade only
        lead = lambda v: round(v / 10 ** math.floor(math.log10(v) + 1e-9), 6)  # noqa: E731
        axis.set_minor_formatter(FuncFormatter(lambda v, _: f"{v:g}" if v > 0 and lead(v) in (2, 5) else ""))


def short_name(record):
    """A record's name for a legend: its file and component, without the folders."""
    return record.rsplit("/", 1)[-1]


def plot_ida(path, rows, analysis, im, title):
    """IDA curves of one body: `rows` its runs (DataFrame), `analysis` its entry of
    Study.analyse. Records whose search the run budget left unresolved are drawn dotted
    and marked in the legend."""
    plt = _pyplot()
    fig, ax = plt.subplots(figsize=(9.5, 5))
    ok = rows[rows["error"] == ""]
    tops = []  # each record's first collapse, or its highest run if censored: the axis ends above them
    for i, (rname, r) in enumerate(ok.groupby("record")):
        color = f"C{i % 10}"
        cap = analysis["records"].get(rname, {})
        unresolved = bool(cap.get("unresolved"))
        r = r.sort_values("im")
        stand = r[~r["overturned"].astype(bool)]
        if math.isfinite(cap.get("capacity", math.nan)) and not cap.get("censored", True):
            stand = stand[stand["im"] < cap["capacity"]]
        label = short_name(rname) + (" (UNRESOLVED)" if unresolved else "")
        ax.plot(stand["peak_theta_over_alpha"], stand["im"], "o" + (":" if unresolved else "-"), ms=3, lw=1,
                color=color, label=label)
        if not cap.get("censored", True):
            x0 = stand["peak_theta_over_alpha"].max() if len(stand) else 0.0
            ax.plot([x0, 1.6], [cap["capacity"]] * 2, lw=1, ls="--", color=color)
            ax.plot([1.6], [cap["capacity"]], "x", color=color)
        fails = r[r["overturned"].astype(bool)]
        ax.plot(np.full(len(fails), 1.7), fails["im"], "|", color=color, ms=6)
        tops.append(cap["capacity"] if math.isfinite(cap.get("capacity", math.nan)) else r["im"].max())
    ax.axvline(1.0, color="0.5", lw=0.6, ls=":")
    ax.set_xlim(0, 1.8)
    ax.set_yscale("log")
    if tops and len(ok):
        ax.set_ylim(ok["im"].min() / 1.2, max(tops) * 1.4)
    _plain_log(ax.yaxis, *ax.get_ylim())
    ax.set_xlabel("peak |theta| / alpha")
    ax.set_ylabel(im.label)
    ax.set_title(title, fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.text(0.01, -0.13, "dashed: first collapse intensity (x); ticks at 1.7: runs that overturned",
            transform=ax.transAxes, fontsize=7, color="0.3")
    ax.legend(fontsize=6.5, loc="upper left", bbox_to_anchor=(1.01, 1.0), borderaxespad=0.0)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_fragility(path, fits, im, title, method, states=None):
    """Fitted lognormal fragilities {body: (Fragility or None, empirical)}, one panel each, on
    a log intensity axis, with the bootstrap's confidence band on the curve; empirical: IDA
    (collapse intensities, count censored), plotted at (i - 0.5) / n; stripes (intensities,
    fraction collapsed, runs). states {body: {damage state: Fragility or None}}: their curves
    too."""
    plt = _pyplot()
    n = len(fits)
    cols = min(n, 3)
    rows = math.ceil(n / cols)
    fig, axes = plt.subplots(rows, cols, figsize=(4.8 * cols, 5.6 * rows), squeeze=False)
    for ax, (label, (frag, emp)) in zip(axes.flat, fits.items()):
        xs = []
        if method == "ida":
            caps = np.sort(np.asarray(emp[0], dtype=float))
            total = len(caps) + emp[1]
            ax.plot(caps, (np.arange(1, len(caps) + 1) - 0.5) / total, "o", color="C1", ms=4,
                    label=f"collapse intensities ({emp[1]} of {total} censored)" if emp[1] else "collapse intensities")
            xs += list(caps)
        else:
            stripes, frac, counts = emp
            ax.plot(stripes, frac, "s", color="C1", ms=4, label="fraction overturned at each stripe")
            xs += list(stripes)
        extra = (states or {}).get(label, {})
        for f in [frag] + [g for g in extra.values() if g is not None]:
            if f is not None:
                xs += [f.median * math.exp(-2.5 * f.beta_total), f.median * math.exp(2.5 * f.beta_total)]
        xs = [x for x in xs if x > 0 and math.isfinite(x)]
        lo, hi = (min(xs) / 1.3, max(xs) * 1.3) if xs else (0.1, 10.0)
        x = np.geomspace(lo, hi, 400)
        for k, (name, f) in enumerate(extra.items()):
            if f is not None:
                ax.plot(x, f.probability(x), color=f"C{k + 2}", lw=1.1, ls="--",
                        label=f"{name}: median {f.median:.3g}, beta {f.beta_total:.2f}")
        if frag is not None:
            band = frag.band(x)
            if np.isfinite(band[0]).any():
                ax.fill_between(x, *band, color="C0", alpha=0.15, lw=0,
                                label=f"{frag.level:.0%} bootstrap band")
            ax.plot(x, frag.probability(x), color="C0", lw=1.6,
                    label=f"overturning: median {frag.median:.3g}, beta {frag.beta_total:.2f}")
        else:
            ax.text(0.5, 0.5, "no fit", transform=ax.transAxes, ha="center")
        ax.set_xscale("log")
        ax.set_xlim(lo, hi)
        _plain_log(ax.xaxis, lo, hi)
        ax.tick_params(axis="x", which="minor", labelsize=7)
        ax.set_ylim(-0.02, 1.02)
        ax.set_xlabel(im.label)
        ax.set_ylabel("P(exceedance)" if extra else "P(overturning)")
        ax.set_title(label, fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=6.5, loc="upper center", bbox_to_anchor=(0.5, -0.16), frameon=False)  # off the curves
    for ax in list(axes.flat)[n:]:
        ax.set_visible(False)
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
