"""The block-on-frame system in three hosts, and the OpenSees adapter (docs/cosimulation-hosts.md).

- OpenSees: a linear shear building built in OpenSees matches ShearFrame.fmu
  (exact for the piecewise-linear record) to second order in the OpenSees
  substep, alone and coupled to RockingBlock.fmu (there within a small
  fraction of the coupling error); the shipped nonlinear frame example runs
  coupled to the block's overturning and ends cleanly.
- SSP + container FMU: the system written once as an SSP file, turned into an
  fmu-manipulation-toolbox container and run by fmpy, reproduces our Jacobi
  master with the same connections bit for bit.
- The C host fmu-rocking/tests/c_host/coupled.c reproduces the master (the
  physical coupling) bit for bit.
"""

import importlib.util
import pathlib
import shutil
import subprocess

import fmpy
import numpy as np
import pytest

from rocking.cosim import opensees as osa
from rocking.cosim import ssp
from rocking.cosim.hostloop import ShearFrameFMU, Slave, couple, shear_frame_fmu

ROOT = pathlib.Path(__file__).resolve().parent.parent
M, K, FLOOR = [2e4] * 3, [2e7] * 3, 3
RAYLEIGH = (1.0, 0.002)
H, T_END = 0.005, 4.0
RECORD_T = np.arange(0.0, T_END + 1e-9, H)
RECORD_AG = np.where(RECORD_T < 1.5, 0.3 * 9.81 * np.sin(2 * np.pi * 2 * RECORD_T), 0.0)


@pytest.fixture(scope="module")
def fmus(fmu_path):
    frame = shear_frame_fmu()
    if not frame.is_file():
        pytest.fail(f"{frame} not found: run `cargo xtask fmu` first", pytrace=False)
    return frame, pathlib.Path(fmu_path)


def _block(fmu, **parameters):
    return Slave(fmu, "block", parameters, tolerance=1e-9)


def _fmu_coupled(fmus, h=H, **kw):
    frame, block_fmu = fmus
    block, structure = _block(block_fmu), ShearFrameFMU(M, K, FLOOR, rayleigh=RAYLEIGH, fmu=frame)
    try:
        return couple(structure, block, RECORD_T, RECORD_AG, h, T_END, **kw)
    finally:
        block.close(), structure.close()


def _opensees_alone_error(fmus, substeps):
    fr = ShearFrameFMU(M, K, FLOOR, rayleigh=RAYLEIGH, fmu=fmus[0])
    os_ = osa.OpenSeesStructure(osa.shear_building(M, K, RAYLEIGH), FLOOR, RECORD_T, RECORD_AG,
                                substeps=substeps)
    worst = peak = 0.0
    for k in range(int(round(T_END / H))):
        t = k * H
        g0, g1 = RECORD_AG[k], RECORD_AG[k + 1]
        for s in (fr, os_):
            s.step(t, H, g0, (g1 - g0) / H, 0.0, 0.0, 0.0, 0.0)
        a = fr.floors()
        worst = max(worst, max(abs(a[i - 1] - os_.node_response(i, 1)[1]) for i in range(1, 4)))
        peak = max(peak, np.abs(a).max())
    fr.close(), os_.close()
    return worst / peak


def test_opensees_shear_building_matches_shear_frame_fmu_to_second_order(fmus):
    coarse, fine = _opensees_alone_error(fmus, 10), _opensees_alone_error(fmus, 40)
    print(f"OpenSees vs ShearFrame.fmu, worst floor acceleration / peak: {coarse:.2e} (10 substeps), "
          f"{fine:.2e} (40 substeps)")
    assert fine < 1e-5
    assert coarse / fine > 10  # Newmark's average acceleration: 16 for 4x finer substeps


def test_opensees_coupled_matches_shear_frame_coupled_within_the_coupling_error(fmus):
    ref = _fmu_coupled(fmus)
    fine = _fmu_coupled(fmus, h=H / 4)
    block = _block(fmus[1])
    os_ = osa.OpenSeesStructure(osa.shear_building(M, K, RAYLEIGH), FLOOR, RECORD_T, RECORD_AG, substeps=10)
    got = couple(os_, block, RECORD_T, RECORD_AG, H, T_END)
    block.close(), os_.close()
    coupling = np.abs(fine.theta[::4] - ref.theta).max()
    hosts = np.abs(got.theta - ref.theta).max()
    print(f"theta: OpenSees vs ShearFrame.fmu coupled {hosts:.2e} rad; coupling error (h vs h/4) "
          f"{coupling:.2e} rad; peak {np.abs(ref.theta).max():.3f} rad")
    assert np.abs(ref.theta).max() > 0.05  # the block rocks
    assert hosts < 0.1 * coupling
    peak_os, peak_fmu = np.abs(got.a_floor).max(), np.abs(ref.a_floor).max()
    assert abs(peak_os - peak_fmu) < 0.01 * peak_fmu


def _example():
    spec = importlib.util.spec_from_file_location("opensees_frame", ROOT / "examples" / "opensees_frame.py")
    example = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(example)
    return example


def _bare_frame(example, scale, t_end=7.0, h=0.01):
    """The example's frame without the block: roof absolute acceleration, and whether a column yielded."""
    from rocking import groundmotion as gm

    rec = gm.katnp()
    keep = rec.time <= t_end + 1e-9
    frame = osa.OpenSeesStructure(example.build, example.ROOF_NODE, rec.time[keep], scale * rec.acc[keep],
                                  substeps=4)
    roof, yielded = [], False
    for k in range(int(round(t_end / h))):
        frame.step(k * h, h, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0)
        roof.append(frame.floor_acceleration())
        yielded = yielded or example.column_yielded(frame.ops)
    frame.close()
    return np.array(roof), yielded


def test_the_shipped_opensees_frame_is_linear_below_yield_and_not_past_it():
    example = _example()
    roof = {scale: _bare_frame(example, scale) for scale in (0.05, 0.1, 1.5, 3.0)}
    small = np.abs(roof[0.1][0] - 2 * roof[0.05][0]).max() / np.abs(roof[0.1][0]).max()
    large = np.abs(roof[3.0][0] - 2 * roof[1.5][0]).max() / np.abs(roof[3.0][0]).max()
    print(f"roof acceleration, response to twice the record minus twice the response: {small:.1e} "
          f"(elastic), {large:.1e} (yielding), of the peak")
    assert not roof[0.1][1] and roof[3.0][1]
    assert small < 1e-6  # a linear frame (Newton converges to 1e-10 m per iteration)
    assert large > 1e-2  # the fibres yield: the response is no longer proportional


def test_the_shipped_opensees_frame_runs_coupled_to_overturning(fmu_path):
    result, tracker, periods = _example().run(scale=3.0, t_end=8.0, fmu=fmu_path)
    assert 0.5 < periods[0] < 1.0
    assert tracker.yielded, "the columns stay elastic: the example does not show nonlinear columns"
    assert result.overturned and result.t_end < 8.0
    assert result.t[-1] <= result.t_end  # the structure's record stops at the last communication point


@pytest.fixture(scope="module")
def ssp_system(fmus, tmp_path_factory):
    frame, block = fmus
    params = {"n": 3, "damping": 2, "rayleighAlpha": RAYLEIGH[0], "rayleighBeta": RAYLEIGH[1]}
    for i in range(3):
        params[f"m[{i + 1}]"], params[f"k[{i + 1}]"] = M[i], K[i]
    work = tmp_path_factory.mktemp("ssp")
    path = ssp.write_ssp(work / "BlockOnFrame.ssp", frame, block, params, {"B": 0.5, "H": 2.5}, FLOOR, H)
    return path, params, work


def test_the_ssp_file_reads_back_with_its_parameters_and_signs(ssp_system):
    path, params, _ = ssp_system
    components, connections, parameters = ssp.read_ssp(path)
    assert components == {"frame": "resources/ShearFrame.fmu", "block": "resources/RockingBlock.fmu"}
    assert parameters["frame"] == params and parameters["block"] == {"B": 0.5, "H": 2.5}
    factors = {(s, sc, e, ec): f for s, sc, e, ec, f in connections}
    assert factors[("block", "Fx", "frame", "Fx[3]")] == -1.0
    assert factors[("frame", "a[3]", "block", "ag")] == 1.0


def test_the_container_refuses_a_sign_it_cannot_apply(ssp_system, tmp_path):
    with pytest.raises(ValueError, match="factor -1.0"):
        ssp.container_from_ssp(ssp_system[0], tmp_path, H)


def test_the_container_fmu_reproduces_the_master_with_the_same_connections(ssp_system, fmus):
    path, _, work = ssp_system
    container, dropped = ssp.container_from_ssp(path, work, H, signs="drop")
    assert [d[1] for d in dropped] == ["Fx", "Fz"]
    record = np.array(list(zip(RECORD_T, RECORD_AG)), dtype=[("time", float), ("ag", float)])
    got = fmpy.simulate_fmu(str(container), stop_time=T_END, output_interval=H, input=record,
                            output=["theta", "aFloor"])
    ref = _fmu_coupled(fmus, ground_mode="constant", force_sign=1.0)
    assert np.abs(ref.theta).max() > 0.05
    assert np.array_equal(got["time"], ref.t)
    assert np.abs(got["theta"] - ref.theta).max() <= 1e-12
    assert np.abs(got["aFloor"] - ref.a_floor).max() <= 1e-9


def _c_host(fmus, work, force_sign):
    if shutil.which("cc") is None:
        pytest.skip("no C compiler (cc) on this machine")
    exe = work / "coupled"
    subprocess.run(["cc", "-O2", "-std=c99", "-Wall", "-Wextra", "-Werror", "-o", str(exe),
                    str(ROOT / "fmu-rocking" / "tests" / "c_host" / "coupled.c"), "-ldl"], check=True)
    lines = []
    for name, fmu in (("block", fmus[1]), ("frame", fmus[0])):
        md = fmpy.read_model_description(str(fmu))
        unzipped = fmpy.extract(str(fmu), unzipdir=str(work / name))
        lib = pathlib.Path(unzipped) / "binaries" / "linux64" / f"{md.coSimulation.modelIdentifier}.so"
        lines.append(f"fmu {lib} {md.guid} file://{unzipped}/resources")
    vr = {n: {v.name: v.valueReference for v in fmpy.read_model_description(str(f)).modelVariables}
          for n, f in (("block", fmus[1]), ("frame", fmus[0]))}
    lines.append("tolerance 0 1e-9")
    lines.append(f"step {H!r} {int(round(T_END / H))}")
    lines.append(f"integer 1 {vr['frame']['n']} 3")
    lines.append(f"integer 1 {vr['frame']['damping']} 2")
    lines.append(f"real 1 {vr['frame']['rayleighAlpha']} {RAYLEIGH[0]!r}")
    lines.append(f"real 1 {vr['frame']['rayleighBeta']} {RAYLEIGH[1]!r}")
    for i in range(3):
        lines.append(f"real 1 {vr['frame'][f'm[{i + 1}]']} {M[i]!r}")
        lines.append(f"real 1 {vr['frame'][f'k[{i + 1}]']} {K[i]!r}")
    lines.append(f"link 1 {vr['frame'][f'a[{FLOOR}]']} 0 {vr['block']['ag']} 1")
    lines.append(f"link 0 {vr['block']['Fx']} 1 {vr['frame'][f'Fx[{FLOOR}]']} {force_sign!r}")
    lines.append(f"link 0 {vr['block']['Fz']} 1 {vr['frame'][f'Fz[{FLOOR}]']} {force_sign!r}")
    lines.append(f"ground 1 {vr['frame']['ag']}")
    lines.append(f"out 0 {vr['block']['theta']}")
    lines.append(f"out 1 {vr['frame'][f'a[{FLOOR}]']}")
    (work / "config").write_text("\n".join(lines) + "\n")
    (work / "ground").write_text("\n".join(repr(float(a)) for a in RECORD_AG) + "\n")
    r = subprocess.run([str(exe), str(work / "config"), str(work / "ground")], capture_output=True, text=True,
                       timeout=120)
    assert r.returncode == 0, r.stderr
    return np.array([[float(x) for x in row.split()] for row in r.stdout.splitlines()])


def test_the_c_host_reproduces_the_master(fmus, tmp_path):
    got = _c_host(fmus, tmp_path, -1.0)
    ref = _fmu_coupled(fmus, ground_mode="constant")
    assert np.abs(ref.theta).max() > 0.05
    assert np.array_equal(got[:, 0], ref.t)
    assert np.abs(got[:, 1] - ref.theta).max() <= 1e-12
    assert np.abs(got[:, 2] - ref.a_floor).max() <= 1e-9
