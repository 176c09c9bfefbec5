"""`rocking record`: what the readers of rocking.groundmotion see in a ground-motion file."""

from pathlib import Path

from .common import CLIError, add_record_options, read_components, read_record, record_facts


def cmd_record(args, _params):
    path = Path(args.file)
    if not path.exists():
        raise CLIError(f"{path}: no such record file")
    if args.component is not None:
        rec, fmt = read_record(path, args.component, args.units, args.fmt)
        records = [rec]
    else:
        records, fmt = read_components(path, args.units, args.fmt)
    print(f"file        {path}")
    print(f"format      {fmt}")
    print(f"components  {len(records)}: {', '.join(r.component for r in records)}")
    for rec in records:
        f = record_facts(rec)
        print(f"\n[{rec.component}] {rec.name}")
        print(f"  orientation    {rec.orientation} (from the file's header)")
        print(f"  units in file  {rec.units_in_file}")
        print(f"  npts           {f['npts']}")
        print(f"  dt             {f['dt_s']:g} s")
        print(f"  duration       {f['duration_s']:g} s")
        print(f"  PGA            {f['pga_g']:.4f} g = {f['pga_m_s2']:.4f} m/s2 at t = {f['t_pga_s']:g} s")
        print(f"  PGV            {f['pgv_cm_s']:.2f} cm/s (trapezoidal integral of acc from rest, no baseline correction)")
        if rec.notes:
            note = rec.notes.splitlines()[0]
            print(f"  notes          {note[:160]}{'...' if len(note) > 160 else ''}")
    if args.plot:
        plot_records(Path(args.plot), records, path)
        print(f"\nwrote {args.plot}")
    return 0


def plot_records(path, records, source):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    g = 9.80665
    fig, axes = plt.subplots(len(records), 2, figsize=(11, 2.4 * len(records) + 0.8), squeeze=False,
                             sharex=True)
    for (ax_a, ax_v), rec in zip(axes, records):
        f = record_facts(rec)
        ax_a.plot(rec.time, rec.acc / g, lw=0.5, color="0.25")
        ax_a.plot(f["t_pga_s"], rec.acc[int(abs(rec.acc).argmax())] / g, "o", color="C3", ms=4)
        ax_a.set_ylabel(f"[{rec.component}] acc (g)")
        ax_a.set_title(f"PGA {f['pga_g']:.3f} g at {f['t_pga_s']:.2f} s", fontsize=9)
        vel = rec.velocity * 100
        ax_v.plot(rec.time, vel, lw=0.7, color="C0")
        ax_v.set_ylabel("vel. (cm/s)")
        ax_v.set_title(f"PGV {f['pgv_cm_s']:.1f} cm/s (integrated from rest)", fontsize=9)
        for ax in (ax_a, ax_v):
            ax.grid(alpha=0.3)
    for ax in axes[-1]:
        ax.set_xlabel("time (s)")
    name = records[0].name or source.name
    fig.suptitle(f"{source.name}: {name}\n{records[0].npts} points, dt = {records[0].dt:g} s", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def register(sub, common):
    """Add the subcommand to `sub` (argparse subparsers); `common` is the parent parser of --debug."""
    p = sub.add_parser("record", parents=[common], help="what the reader sees in a ground-motion file",
                       description="Format, components, npts, dt, duration, PGA, PGV of a ground-motion file "
                                   "as the readers of rocking.groundmotion see it.")
    p.add_argument("file", metavar="FILE")
    p.add_argument("--component", help="only this component (label or index)")
    p.add_argument("--plot", metavar="PNG", help="plot acceleration and velocity of each component")
    add_record_options(p)
    p.set_defaults(func=cmd_record)
