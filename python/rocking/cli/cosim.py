"""`rocking cosim CASE.toml --out DIR`: one coupled run, block on a frame, from a file.

CASE.toml (or .json, the same tables):

    [frame]                  # ShearFrame.fmu: masses/stiffnesses per storey (kg, N/m),
    masses = [1e4, 1e4, 1e4] # floor 1 first, or any parameter by name ("m[1]" = 1e4)
    stiffnesses = [4e6, 4e6, 4e6]
    zeta = 0.02

    [block]                  # RockingBlock.fmu parameters by name (docs/model.md §5)
    interface = "elastic"
    kn = 1e8

    [ground]                 # either a record file (path relative to CASE.toml) ...
    record = "../data/ground-motions/some.AT2"
    component = "090"        # optional
    scale = 1.0              # optional
    vertical = true          # optional: the record set's vertical component as the block's av
                             # (or "FILE[:COMPONENT]"), scaled alike; the frame has no vertical DOF
    # ... or a sine: amplitude = 4.0 (m/s2), frequency = 2.0 (Hz), cycles = 3

    [coupling]               # all optional but floor
    floor = 3
    step = 0.001             # communication step (s)
    stop_time = 3.0          # default: the record's end, or the sine's end + 2 s
    scheme = "jacobi"        # or "gauss-seidel"
    inputs = "extrapolate"   # or "constant", or "midpoint" (each input held at its mean over the step)
    coupling = "two-way"     # or "one-way"
    reject = true            # step rejection at impacts and contact changes (default)
    rtol = 1e-10             # the block's integrator tolerance
    early_return = false     # with --fmi 3: end the communication step at each of the block's
                             # impacts, uplifts and rests (fmi3DoStep's early return)
    ground_input = "chord"   # the frame's ag over a step: "chord" (value and slope, the default),
                             # "midpoint" (the chord's mean) or "held" (the step start's value)

Writes DIR/timehistory.csv (time, ag, theta, omega, a_floor, Fx, Fz, u[1..n]),
DIR/summary.json and DIR/plot.png, and prints a summary.
"""

import argparse
import json
import textwrap
import tomllib
from pathlib import Path

from .. import jsonfile
from .common import CLIError, horizontal_record

SECTIONS = {"frame", "block", "ground", "coupling"}
COUPLING_KEYS = {"floor", "step", "stop_time", "scheme", "inputs", "coupling", "reject", "substeps", "rtol",
                 "early_return", "ground_input"}


def register(sub, common):
    """Add the subcommand to the `rocking` parser (cli.main.build_parser)."""
    p = sub.add_parser("cosim", parents=[common], help="a block on a floor of a shear frame, co-simulated",
                       description=textwrap.fill(
                           "Couple RockingBlock.fmu to floor j of ShearFrame.fmu (docs/cosimulation.md) as "
                           "CASE describes and write DIR/timehistory.csv, DIR/summary.json and DIR/plot.png.", 100),
                       epilog=__doc__.split("\n\n", 1)[1].split("\nWrites")[0],
                       formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("case", metavar="CASE.toml", help="the coupled case (.toml or .json)")
    p.add_argument("--out", required=True, metavar="DIR", help="output folder")
    p.add_argument("--reference", action="store_true",
                   help="also solve the monolithic coupled equations (elastic solid rectangle only) and "
                        "report the co-simulation's error against them")
    p.add_argument("--fmi", type=int, choices=(2, 3), default=2,
                   help="the FMI standard of both FMUs (default 2; 3: the 3.0 archives, fmi3/ beside the "
                        "2.0 ones; input rates through their der(x) inputs, [coupling] early_return available)")
    p.add_argument("--frame-fmu", metavar="PATH", help="default: the ShearFrame.fmu an installed wheel carries; "
                                                       "in a clone target/fmu/ShearFrame.fmu (--fmi 3: "
                                                       "target/fmu/fmi3/ShearFrame.fmu)")
    p.add_argument("--block-fmu", metavar="PATH", help="default: the RockingBlock.fmu an installed wheel carries; "
                                                       "in a clone target/fmu/RockingBlock.fmu (--fmi 3: "
                                                       "target/fmu/fmi3/RockingBlock.fmu)")
    p.set_defaults(func=cmd_cosim)


def _error(message):
    return CLIError(message)


def load_case(path):
    """The case file as a dict of its four tables; one-line errors naming the file and key."""
    path = Path(path)
    if not path.is_file():
        raise _error(f"{path}: no such case file")
    try:
        case = json.loads(path.read_text()) if path.suffix == ".json" else tomllib.loads(path.read_text())
    except (ValueError, tomllib.TOMLDecodeError) as exc:
        raise _error(f"{path}: {exc}") from exc
    unknown = set(case) - SECTIONS
    if unknown:
        raise _error(f"{path}: unknown table(s) {sorted(unknown)}; expected {sorted(SECTIONS)}")
    for key in ("frame", "ground", "coupling"):
        if key not in case:
            raise _error(f"{path}: missing table [{key}]")
    bad = set(case["coupling"]) - COUPLING_KEYS
    if bad:
        raise _error(f"{path}: [coupling] unknown key(s) {sorted(bad)}; expected {sorted(COUPLING_KEYS)}")
    if "floor" not in case["coupling"]:
        raise _error(f"{path}: [coupling] floor is required (the floor carrying the block, 1..n)")
    return case


def frame_from(table, where):
    from ..cosim.master import frame_params
    table = dict(table)
    masses, stiff = table.pop("masses", None), table.pop("stiffnesses", None)
    if (masses is None) != (stiff is None):
        raise _error(f"{where}: [frame] masses and stiffnesses go together")
    params = {}
    if masses is not None:
        if len(masses) != len(stiff) or not 1 <= len(masses) <= 20:
            raise _error(f"{where}: [frame] masses and stiffnesses need one value per storey, 1 to 20")
        params = frame_params(masses, stiff, zeta=table.pop("zeta", 0.05))
    params.update(table)
    return params


def ground_from(table, case_path):
    """(ag callable, default stop time, facts for the summary)."""
    from ..cosim.master import record_ground, sine_ground
    table = dict(table)
    if "record" in table:
        path = Path(table["record"])
        if not path.is_absolute():
            path = case_path.parent / path
        rec, fmt = horizontal_record(path, table.get("component"))
        scale = float(table.get("scale", 1.0))
        facts = {"record": str(path), "format": fmt, "component": rec.component, "scale": scale,
                 "dt_s": rec.dt, "pga_m_s2": rec.pga * scale, "vertical": None}
        av = None
        if table.get("vertical", False) is not False:
            vert = _vertical(table["vertical"], rec, case_path)
            av = record_ground(vert.time, scale * vert.acc)
            facts["vertical"] = {"record": str(vert.source), "component": vert.component,
                                 "pga_m_s2": vert.pga * abs(scale)}
        return record_ground(rec.time, scale * rec.acc), float(rec.time[-1]), facts, av
    try:
        amp, freq = float(table["amplitude"]), float(table["frequency"])
    except KeyError as exc:
        raise _error(f"{case_path}: [ground] needs `record = FILE` or `amplitude` and `frequency` "
                     f"(missing {exc.args[0]})") from exc
    cycles = table.get("cycles")
    end = (float(cycles) / freq + 2.0) if cycles is not None else 10.0
    if "vertical" in table:
        raise _error(f"{case_path}: [ground] vertical: goes with a record (its set's vertical component)")
    return sine_ground(amp, freq, cycles=cycles), end, {"sine": table}, None


def _vertical(value, rec, case_path):
    """The vertical Record that [ground] vertical names: true (the record set's), or "FILE[:C]"."""
    from .common import vertical_record
    if value is True:
        return vertical_record("auto", rec)[0]
    if isinstance(value, str):
        path, _, comp = value.partition(":") if not (case_path.parent / value).exists() else (value, "", "")
        path = Path(path) if Path(path).is_absolute() else case_path.parent / path
        return vertical_record(f"{path}:{comp}" if comp else str(path), rec)[0]
    raise _error(f"{case_path}: [ground] vertical: expected true or \"FILE[:COMPONENT]\", found {value!r}")


def cmd_cosim(args, _params):
    import numpy as np
    import pandas as pd

    from .. import paths
    from ..cosim.master import CoupledFMUs
    from ..fmu import RockingFMU
    from .plots import plot_cosim

    case_path = Path(args.case)
    case = load_case(case_path)
    frame = frame_from(case["frame"], case_path)
    block = dict(case.get("block", {}))
    ground, end, ground_facts, av = ground_from(case["ground"], case_path)
    opts = dict(case["coupling"])
    opts.setdefault("stop_time", end)
    opts.setdefault("step", 1e-3)
    fmu_dir = paths.target_dir() / "fmu" if paths.REPO is not None else Path(".")
    std_dir = fmu_dir / "fmi3" if args.fmi == 3 else fmu_dir
    frame_fmu = Path(args.frame_fmu) if args.frame_fmu else std_dir / "ShearFrame.fmu"
    block_fmu = Path(args.block_fmu) if args.block_fmu else std_dir / "RockingBlock.fmu"
    # alpha and thetaOv for the summary come from the FMI 2.0 block (the same binary)
    block_fmu2 = block_fmu if args.fmi == 2 else fmu_dir / "RockingBlock.fmu"
    for f in (frame_fmu, block_fmu, block_fmu2):
        if not f.is_file():
            build = ("this wheel does not carry it" if paths.BUNDLE is not None
                     else "in a clone `cargo xtask fmu` writes it")
            raise _error(f"{f}: no such FMU ({build}; or pass --frame-fmu/--block-fmu)")
    with CoupledFMUs(frame_fmu, block_fmu, fmi=args.fmi) as fmus:
        try:
            res = fmus.run(frame, block, ground=ground, vertical=av, **opts)
        except TypeError as exc:
            raise _error(f"{case_path}: [coupling] {exc}") from exc
    check = None
    if args.reference and av is not None:
        raise _error(f"{case_path}: --reference: the reference solution has no vertical input; leave out "
                     "[ground] vertical")
    if args.reference:
        from ..cosim.reference import Reference
        from ..cosim.study import errors
        try:
            ref = Reference(frame, block, opts["floor"], ground, res.time[-1],
                            coupling=opts.get("coupling", "two-way"))
        except ValueError as exc:
            raise _error(f"{case_path}: --reference: {exc}") from exc
        check = errors(res, ref)
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    n = res.u.shape[1]
    table = pd.DataFrame({"time": res.time, "ag": res.ag, "theta": res.theta, "omega": res.omega,
                          "a_floor": res.a_floor, "Fx": res.Fx, "Fz": res.Fz,
                          **{f"u[{i + 1}]": res.u[:, i] for i in range(n)}})
    table.to_csv(out / "timehistory.csv", index=False)
    k_th, k_a = int(np.argmax(np.abs(res.theta))), int(np.argmax(np.abs(res.a_floor)))
    with RockingFMU(block_fmu2) as rocking_fmu:  # alpha and thetaOv, for theta / alpha
        calc = rocking_fmu.calculated(block)
    summary = {"case": str(case_path), "ground": ground_facts, "frame": frame, "block": block,
               "options": res.options, "overturned": res.overturned,
               "t_overturn_s": res.t_overturn if res.overturned else None,
               "t_end_s": float(res.time[-1]), "peak_theta_rad": float(abs(res.theta[k_th])),
               "t_peak_theta_s": float(res.time[k_th]), "alpha_rad": calc["alpha"], "thetaOv_rad": calc["thetaOv"],
               "peak_theta_over_alpha": float(abs(res.theta[k_th])) / calc["alpha"],
               "peak_a_floor_m_s2": float(abs(res.a_floor[k_a])), "t_peak_a_floor_s": float(res.time[k_a]),
               "peak_roof_displacement_m": float(np.max(np.abs(res.u[:, -1]))),
               "steps": res.steps, "rejected_steps": res.rejected, "early_returns_s": res.early_returns,
               "wall_s": res.wall,
               "error_against_reference": check,
               "files": {"timehistory": "timehistory.csv", "plot": "plot.png"}}
    jsonfile.write(out / "summary.json", summary)
    plot_cosim(out / "plot.png", res, calc["alpha"], calc["thetaOv"])
    outcome = (f"OVERTURNED at t = {res.t_overturn:.4f} s (the frame's state kept at that time)"
               if res.overturned else f"stands until t = {res.time[-1]:g} s")
    print(f"coupling    FMI {res.options['fmi']}.0, {res.options['scheme']}, {res.options['inputs']} inputs, "
          f"{res.options['coupling']}"
          + (f", {len(res.early_returns)} early returns" if res.options["early_return"] else "") + ", "
          f"h = {res.options['step']:g} s, block on floor {res.options['floor']} of {n}\n"
          f"result      {outcome}\n"
          f"peak        |theta| = {summary['peak_theta_rad']:.6g} rad at t = {summary['t_peak_theta_s']:.4f} s, "
          f"|a[{res.options['floor']}]| = {summary['peak_a_floor_m_s2']:.6g} m/s2 at t = "
          f"{summary['t_peak_a_floor_s']:.4f} s\n"
          + (f"reference   relative error: theta {check['theta']:.2e}, a[j] {check['a_floor']:.2e} (histories), "
             f"peaks {check['peak_theta']:.2e}, {check['peak_a_floor']:.2e}\n" if check else "")
          + f"wrote       {out / 'timehistory.csv'}, {out / 'summary.json'}, {out / 'plot.png'}  "
          f"({len(res.time)} rows, {res.steps} steps, {res.rejected} rejected, {res.wall:.2f} s)")
    return 0
