"""The same coupled case in every host, against the monolithic reference (docs/cosimulation-hosts.md).

    python -m rocking.cosim.hosts [--out docs/img] [--steps 0.01 0.005 ...]

Hosts, all Jacobi with inputs held over the communication step:

- `master`: rocking.cosim's master (fmpy), `scheme="jacobi", inputs="constant"`;
- `container`: the system written as an SSP file (ssp.py: the block's
  FxSupport, FzSupport connected to the frame's loads as they are), the
  container FMU generated from it by fmu-manipulation-toolbox (its runtime
  couples the two FMUs), stepped by fmpy;
- `c-host`: fmu-rocking/tests/c_host/coupled.c, compiled here with `cc`;
- `opensees`: the frame built in OpenSees (opensees.shear_building, modal
  damping) under RockingBlock.fmu, with the loop of hostloop.py;
- `fmpy-ssp`: fmpy's own simulate_ssp on the same SSP file (the bindings
  passed by hand: see run_fmpy_ssp).

Writes cosim_hosts.png (error against the reference as a function of the
step) to --out and prints the table of docs/cosimulation-hosts.md. ~1 min.
"""

import argparse
import shutil
import subprocess
import tempfile
from pathlib import Path
from types import SimpleNamespace

import fmpy
import numpy as np

from .. import paths
from . import opensees as osa
from . import ssp
from .hostloop import couple, open_block, shear_frame_fmu
from .master import CoupledFMUs
from .reference import Reference
from .study import convergence_case, errors

HOSTS = ("master", "container", "c-host", "opensees", "fmpy-ssp")
STEPS = (0.01, 0.005, 0.0025, 0.00125)


def enumerated(fmu, params):
    """params with enumeration items given by name replaced by their values (for SSP and C)."""
    md = fmpy.read_model_description(str(fmu))
    out = {}
    for v in md.modelVariables:
        if v.name in params:
            value = params[v.name]
            if v.type == "Enumeration" and isinstance(value, str):
                value = next(int(i.value) for i in v.declaredType.items if i.name == value)
            elif v.type in ("Integer", "Enumeration"):
                value = int(value)
            else:
                value = float(value)
            out[v.name] = value
    missing = set(params) - set(out)
    if missing:
        raise KeyError(f"{sorted(missing)}: not variables of {fmu}")
    return out


def _samples(case, h):
    t = np.arange(int(round(case["stop_time"] / h)) + 1) * h
    return t, np.asarray(case["ground"](t), float)


def run_master(case, h, fmus):
    return fmus.run(**case, step=h, scheme="jacobi", inputs="constant", reject=False)


def run_container(case, h, work):
    """The SSP system in the container FMU, inputs sampled at the communication points.

    The loop is slave.Slave (fmpy's FMU2Slave) stepped here rather than fmpy.simulate_fmu,
    which raises at the step where the block overturns and returns nothing: the
    container runtime turns the block's fmi2Discard into fmi2Error. That error,
    after a message of status Discard (the block's overturning, passed on by the
    container), ends the run at the last communication point (`overturned`);
    any other error raises.
    """
    from .. import fmu as _fmu
    from .slave import Slave

    work = Path(tempfile.mkdtemp(dir=work))
    frame = enumerated(shear_frame_fmu(), case["frame"])
    block = enumerated(paths.default_fmu(), case["block"])
    path = ssp.write_ssp(work / "BlockOnFrame.ssp", shear_frame_fmu(), paths.default_fmu(), frame, block,
                         case["floor"], h)
    container, _ = ssp.container_from_ssp(path, work, h)
    t, ag = _samples(case, h)
    fmu = Slave(container)
    rows, overturned = [], False
    try:
        fmu.instantiate({}, 0.0, case["stop_time"])
        fmu.exit_init()
        r_ag, r_out = fmu.refs(["ag"]), fmu.refs(["theta", "aFloor"])
        for k, tk in enumerate(t):
            rows.append([tk, *fmu.get(r_out)])
            if k + 1 == len(t):
                break
            fmu.set(r_ag, [float(ag[k])])
            try:
                fmu.do_step(tk, h)
            except _fmu.FMUError as error:
                # the container logs through printf-style "%s" messages this logger does
                # not format; the embedded block's message keeps its status, Discard
                if "[DISCARD]" not in str(error):
                    raise
                overturned = True
                break
    finally:
        fmu.close()
    out = np.array(rows)
    return SimpleNamespace(time=out[:, 0], theta=out[:, 1], a_floor=out[:, 2], overturned=overturned)


def run_fmpy_ssp(case, h, work):
    """fmpy's simulate_ssp on the SSP file, the bindings passed as its
    parameter_set (it does not read ParameterBindings). Its rows: the row labelled t holds the outputs after
    the step from t, i.e. at t + h; an external input reaches the FMUs one step
    late (connections are applied after the step)."""
    from fmpy.ssp.simulation import simulate_ssp

    work = Path(tempfile.mkdtemp(dir=work))
    frame = enumerated(shear_frame_fmu(), case["frame"])
    block = enumerated(paths.default_fmu(), case["block"])
    path = ssp.write_ssp(work / "BlockOnFrame.ssp", shear_frame_fmu(), paths.default_fmu(), frame, block,
                         case["floor"], h)
    n = int(round(case["stop_time"] / h))
    got = simulate_ssp(str(path), stop_time=(n - 0.5) * h, step_size=h,
                       parameter_set=ssp.fmpy_parameter_set(path), input={"ag": lambda t: float(case["ground"](t))})
    time = np.arange(len(got) + 1) * h  # its own times add h step by step (they drift)
    theta = np.concatenate([[0.0], got["block.theta"]])
    a_floor = np.concatenate([[0.0], got[f"frame.a[{case['floor']}]"]])
    return SimpleNamespace(time=time, theta=theta, a_floor=a_floor)


def build_c_host(work):
    if shutil.which("cc") is None:
        raise RuntimeError("the C host needs a C compiler (cc)")
    exe = Path(work) / "coupled"
    source = paths.repo() / "fmu-rocking" / "tests" / "c_host" / "coupled.c"
    subprocess.run(["cc", "-O2", "-std=c99", "-Wall", "-Wextra", "-Werror", "-o", str(exe), str(source),
                    "-ldl"], check=True)
    return exe


def run_c_host(case, h, work, exe, force_sign=-1.0, tolerance=1e-9):
    """The C host on the case; its ground is ag(t_k) held over each step."""
    work = Path(tempfile.mkdtemp(dir=work))
    fmus = {"block": paths.default_fmu(), "frame": shear_frame_fmu()}
    lines, vr = [], {}
    for name in ("block", "frame"):  # instance 0 steps first: the block, as in hostloop.couple
        md = fmpy.read_model_description(str(fmus[name]))
        unzipped = Path(fmpy.extract(str(fmus[name]), unzipdir=str(work / name)))
        lib = unzipped / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so"
        lines.append(f"fmu {lib} {md.guid} {unzipped.joinpath('resources').as_uri()}")
        vr[name] = {v.name: (v.valueReference, v.type) for v in md.modelVariables}
    lines.append(f"tolerance 0 {tolerance!r}")
    t, ag = _samples(case, h)
    lines.append(f"step {h!r} {len(t) - 1}")
    for i, name in enumerate(("block", "frame")):
        for key, value in enumerated(fmus[name], case[name]).items():
            ref, kind = vr[name][key]
            lines.append(f"{'real' if kind == 'Real' else 'integer'} {i} {ref} {value!r}")
    j = case["floor"]
    lines.append(f"link 1 {vr['frame'][f'a[{j}]'][0]} 0 {vr['block']['ag'][0]} 1")
    lines.append(f"link 0 {vr['block']['Fx'][0]} 1 {vr['frame'][f'Fx[{j}]'][0]} {force_sign!r}")
    lines.append(f"link 0 {vr['block']['Fz'][0]} 1 {vr['frame'][f'Fz[{j}]'][0]} {force_sign!r}")
    lines.append(f"ground 1 {vr['frame']['ag'][0]}")
    lines.append(f"out 0 {vr['block']['theta'][0]}")
    lines.append(f"out 1 {vr['frame'][f'a[{j}]'][0]}")
    (work / "config").write_text("\n".join(lines) + "\n")
    (work / "ground").write_text("\n".join(repr(float(a)) for a in ag) + "\n")
    r = subprocess.run([str(exe), str(work / "config"), str(work / "ground")], capture_output=True, text=True,
                       timeout=300)
    if r.returncode != 0:
        raise RuntimeError(f"the C host failed: {r.stderr}")
    rows = [row.split() for row in r.stdout.splitlines() if not row.startswith("discard")]
    out = np.array(rows, dtype=float)
    return SimpleNamespace(time=out[:, 0], theta=out[:, 1], a_floor=out[:, 2])


def run_opensees(case, h, substeps=10, hold="constant"):
    """The frame in OpenSees (modal damping) under the block, hostloop's Jacobi loop
    (`hold`: "constant" or "linear", see hostloop.couple)."""
    frame = case["frame"]
    n = int(frame["n"])
    m = [frame[f"m[{i}]"] for i in range(1, n + 1)]
    k = [frame[f"k[{i}]"] for i in range(1, n + 1)]
    t, ag = _samples(case, h)
    structure = osa.OpenSeesStructure(osa.shear_building(m, k, zeta=frame["zeta"]), case["floor"], t, ag,
                                      substeps=substeps)
    block = open_block(case["block"])
    try:
        res = couple(structure, block, t, ag, h, case["stop_time"], hold=hold)
    finally:
        block.close(), structure.close()
    return SimpleNamespace(time=res.t, theta=res.theta, a_floor=res.a_floor)


def compare(steps=STEPS, hosts=HOSTS, progress=print):
    """{host: [errors(...) at each step]} for the convergence case of study.py."""
    case = convergence_case()
    ref = Reference(**case)
    rows = {host: [] for host in hosts}
    with tempfile.TemporaryDirectory() as work, CoupledFMUs() as fmus:
        exe = build_c_host(work) if "c-host" in hosts else None
        for h in steps:
            for host in hosts:
                if host == "master":
                    res = run_master(case, h, fmus)
                elif host == "container":
                    res = run_container(case, h, work)
                elif host == "c-host":
                    res = run_c_host(case, h, work, exe)
                elif host == "fmpy-ssp":
                    res = run_fmpy_ssp(case, h, work)
                else:
                    res = run_opensees(case, h)
                rows[host].append(errors(res, ref))
                progress(f"{host:9s} h = {h:g} s: " + ", ".join(f"{k} {v:.2e}" for k, v in rows[host][-1].items()))
    return rows


def plot(rows, steps, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(10, 4))
    for ax, key, title in zip(axes, ("theta", "a_floor"), ("block rotation theta", "floor acceleration a[3]")):
        for host, marker in zip(rows, "osdv^"):
            ax.loglog(steps, [r[key] for r in rows[host]], marker=marker, label=host)
        ax.loglog(steps, [rows["master"][0][key] * h / steps[0] for h in steps], "k:", lw=0.8, label="order 1")
        ax.set_xticks(steps, [f"{h:g}" for h in steps])
        ax.minorticks_off()
        ax.set_xlabel("communication step h (s)")
        ax.set_ylabel("max error / reference peak")
        ax.set_title(title)
        ax.grid(True, which="both", lw=0.3)
    axes[0].legend()
    fig.suptitle("Jacobi, inputs held: each host against the monolithic reference")
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    parser = argparse.ArgumentParser(description="the coupled case in every host against the reference")
    parser.add_argument("--out", default="docs/img", help="folder of cosim_hosts.png")
    parser.add_argument("--steps", type=float, nargs="+", default=list(STEPS))
    args = parser.parse_args(argv)
    rows = compare(args.steps)
    print("\nmax error of theta / of a[3], over the reference's peak")
    print("\n| host | " + " | ".join(f"h = {h:g} s" for h in args.steps) + " |")
    print("|---|" + "---:|" * len(args.steps))
    for host, errs in rows.items():
        print(f"| {host} | " + " | ".join(f"{e['theta']:.2e} / {e['a_floor']:.2e}" for e in errs) + " |")
    print("\nerror of the peaks, theta / a[3]")
    print("\n| host | " + " | ".join(f"h = {h:g} s" for h in args.steps) + " |")
    print("|---|" + "---:|" * len(args.steps))
    for host, errs in rows.items():
        print(f"| {host} | " + " | ".join(f"{e['peak_theta']:.1e} / {e['peak_a_floor']:.1e}" for e in errs) + " |")
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    plot(rows, args.steps, out / "cosim_hosts.png")


if __name__ == "__main__":
    main()
