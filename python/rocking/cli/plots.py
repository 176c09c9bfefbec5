"""The plots of `rocking simulate` and `rocking cosim`: theta over alpha on an axis
scaled to the response, overturning marked, legends and labels off the curves."""

import math
from pathlib import Path

G = 9.80665  # m/s² per g


def _pyplot():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    return plt


def legend_above(ax, handles=None, labels=None):
    """The panel's legend in one row above it, where no curve is."""
    if handles is None:
        handles, labels = ax.get_legend_handles_labels()
    ax.legend(handles, labels, loc="lower left", bbox_to_anchor=(0.0, 1.0), ncol=len(labels), fontsize=8,
              frameon=False, borderaxespad=0.2, handlelength=2.5)


def theta_panel(ax, t, theta_over_alpha, alpha, theta_ov, color="C0"):
    """theta / alpha against t. The axis follows the response: ±1.1 once it reaches half of
    alpha, else 1.3 times its peak (a 0.008 alpha response is not drawn flat on ±1.1); the
    lines theta = ±alpha and ±thetaOv are drawn when inside, else the legend says where."""
    import numpy as np
    from matplotlib.lines import Line2D

    peak = float(np.max(np.abs(theta_over_alpha))) if len(theta_over_alpha) else 0.0
    lim = 1.1 if peak >= 0.5 or peak == 0 else 1.3 * peak
    ax.plot(t, theta_over_alpha, lw=0.9, color=color, label="theta / alpha")
    ax.axhline(0, color="0.6", lw=0.5)
    ov = theta_ov / alpha if alpha and theta_ov and math.isfinite(theta_ov) else None
    off = []
    for level, style, name in ((1.0, dict(color="C1", ls="--"), "theta = ±alpha"),
                               (ov, dict(color="C3", ls=":"), f"overturning ±thetaOv = ±{ov or 0:.3g} alpha")):
        if level is None:
            continue
        if level <= lim:
            for sign in (1, -1):
                ax.axhline(sign * level, lw=0.8, label=name if sign > 0 else None, **style)
        else:
            off.append(name)
    handles, labels = ax.get_legend_handles_labels()
    if off:
        handles.append(Line2D([], [], lw=0))
        labels.append(f"{', '.join(off)}: off this scale (peak {peak:.3g})")
    ax.set_ylim(-lim, lim)
    ax.set_ylabel("theta / alpha" + (f"\n(alpha = {alpha:.4g} rad)" if alpha else ""))
    legend_above(ax, handles, labels)


def mark_overturning(axes, t_overturn):
    """A vertical line at the overturning time on every panel, its label above the top one."""
    from matplotlib.transforms import blended_transform_factory
    for ax in axes:
        ax.axvline(t_overturn, color="C3", lw=1.2)
    top = axes[0]
    top.text(t_overturn, 1.02, f"overturned {t_overturn:.2f} s", color="C3", fontsize=9, ha="right",
             va="bottom", transform=blended_transform_factory(top.transData, top.transAxes))


def _title(s, rec, args):
    title = s["preset"] or f"RockingBlock ({s['parameters'].get('shape', 'default shape')})"
    if rec is not None:
        comp = f" [{rec.component}]" if rec.component else ""
        title += f" under {rec.name or Path(args.record).name}{comp} x {args.scale:g}"
        if s["record"]["synthetic_stand_in"]:
            title += " (synthetic stand-in)"
    if s.get("vertical"):
        title += f" with av {s['vertical']['component']}"
    outcome = (f"out of range: {s['terminal'].split(':')[0]}" if s.get("terminal")
               else f"overturned at {s['t_overturn_s']:.2f} s" if s["overturned"]
               else f"stands; peak |theta|/alpha = {s['peak_theta_over_alpha']:.3g}")
    return f"{title}\n{outcome}"


def _regime_panel(ax, t, regime, regimes, t_overturn):
    """The regime as steps; it ends on "overturned" when the run did (the FMU's last row is
    its state at the last successful time, before the regime changes)."""
    import numpy as np
    t, regime = np.asarray(t), np.asarray(regime)
    ax.step(t, regime, where="post", lw=0.9, color="C4")
    overturned = next((v for v, name in regimes.items() if name.lower() == "overturned"), None)
    if t_overturn is not None and overturned is not None:
        ax.plot([t[-1], t_overturn], [regime[-1], overturned], lw=0.9, color="C4")
        ax.plot([t_overturn], [overturned], "o", ms=5, color="C4", zorder=4)
    values = sorted(regimes) or sorted(set(regime.tolist()))
    ax.set_yticks(values, [regimes.get(v, str(v)) for v in values], fontsize=7)
    ax.set_ylim(min(values) - 0.5, max(values) + 0.5)
    ax.set_ylabel("regime")


def plot_simulation(path, table, s, regimes, rec, args):
    """`rocking simulate`'s plot.png: ground motion, theta / alpha, |MR|, regime."""
    from matplotlib.ticker import EngFormatter

    plt = _pyplot()
    t = table["time"].to_numpy()
    fig, axes = plt.subplots(4, 1, sharex=True, figsize=(10, 9.5), height_ratios=(1.1, 1.6, 1.1, 0.8))
    fig.suptitle(_title(s, rec, args), fontsize=11)

    ax = axes[0]
    if rec is not None:
        t_rec = rec.time[rec.time <= t[-1] + rec.dt]
        ax.plot(t_rec, args.scale * rec.acc[:len(t_rec)] / G, lw=0.6, color="0.3")
    else:
        ax.plot(t, table["ag"] / G, lw=0.6, color="0.3")
    if "av" in table:
        axes[0].lines[-1].set_label("ag")
        ax.plot(t, table["av"] / G, lw=0.6, color="C9", label="av (vertical, up)")
        legend_above(ax)
    ax.set_ylabel("ground acc. (g)" if "av" in table else "ground acc. ag (g)")

    theta_panel(axes[1], t, table["thetaOverAlpha"].to_numpy(), s["calculated"].get("alpha"),
                s["calculated"].get("thetaOv"))

    ax = axes[2]
    ax.plot(t, table["MR"], lw=0.9, color="C2")
    ax.yaxis.set_major_formatter(EngFormatter(unit="N·m"))
    ax.set_ylabel("restoring moment |MR|\n(against theta)")

    if "regime" in table:
        _regime_panel(axes[3], t, table["regime"], regimes, s["t_overturn_s"] if s["overturned"] else None)
    axes[3].set_xlabel("time (s)")

    if s["overturned"]:
        mark_overturning(axes, s["t_overturn_s"])
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def plot_cosim(path, res, alpha, theta_ov):
    """`rocking cosim`'s plot.png: ground and floor acceleration, theta / alpha, Fx."""
    plt = _pyplot()
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=(10, 8))
    o = res.options
    fig.suptitle(f"Block on floor {o['floor']}: {o['scheme']}, {o['inputs']}, {o['coupling']}, h = {o['step']:g} s\n"
                 + (f"overturned at {res.t_overturn:.3f} s" if res.overturned
                    else f"stands; peak |theta|/alpha = {max(abs(res.theta)) / alpha:.3g}"), fontsize=10)
    axes[0].plot(res.time, res.ag, lw=0.7, color="0.4", label="ground ag")
    axes[0].plot(res.time, res.a_floor, lw=0.9, color="C0", label=f"floor a[{o['floor']}]")
    axes[0].set_ylabel("acceleration (m/s2)")
    legend_above(axes[0])
    theta_panel(axes[1], res.time, res.theta / alpha, alpha, theta_ov, color="C1")
    axes[2].plot(res.time, res.Fx / 1e3, lw=0.9, color="C2")
    axes[2].set_ylabel("support force Fx (kN)")
    axes[2].set_xlabel("time (s)")
    if res.overturned:
        mark_overturning(axes, res.t_overturn)
    for ax in axes:
        ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
