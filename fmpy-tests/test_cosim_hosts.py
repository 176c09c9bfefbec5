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

import fmpy
import numpy as np
import pytest

from rocking.cosim import hosts, ssp
from rocking.cosim import opensees as osa
from rocking.cosim.hostloop import ShearFrameFMU, couple, open_block, shear_frame_fmu
from rocking.cosim.master import CoupledFMUs, sine_ground
from rocking.cosim.reference import Reference
from rocking.cosim.study import convergence_case, errors

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
    return open_block(parameters, fmu=fmu)


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


def test_the_documented_opensees_table_at_scale_one_is_what_the_example_gives(fmu_path):
    """docs/cosimulation-hosts.md §2: at scale 1.0 the documented command (--t-end 20) overturns
    the block, two-way and one-way, at the times the table gives (they were once shown standing,
    with the peaks up to 8-10 s)."""
    table = (ROOT / "docs" / "cosimulation-hosts.md").read_text()
    example = _example()
    for two_way, label in [(True, "two-way"), (False, "one-way")]:
        result, _, _ = example.run(scale=1.0, t_end=20.0, two_way=two_way, fmu=fmu_path)
        assert result.overturned, label
        row = next(line for line in table.splitlines() if line.startswith(f"| 1.0 | {label} |"))
        assert row.endswith(f"| at {result.t_end:.2f} s |"), (row, result.t_end)


@pytest.fixture(scope="module")
def ssp_system(fmus, tmp_path_factory):
    frame, block = fmus
    params = {"n": 3, "damping": 2, "rayleighAlpha": RAYLEIGH[0], "rayleighBeta": RAYLEIGH[1]}
    for i in range(3):
        params[f"m[{i + 1}]"], params[f"k[{i + 1}]"] = M[i], K[i]
    work = tmp_path_factory.mktemp("ssp")
    path = ssp.write_ssp(work / "BlockOnFrame.ssp", frame, block, params, {"B": 0.5, "H": 2.5}, FLOOR, H)
    return path, params, work


def test_the_ssp_file_reads_back_with_its_parameters_and_connections(ssp_system, fmus, tmp_path):
    path, params, _ = ssp_system
    components, connections, parameters = ssp.read_ssp(path)
    assert components == {"frame": "resources/ShearFrame.fmu", "block": "resources/RockingBlock.fmu"}
    assert parameters["frame"] == params and parameters["block"] == {"B": 0.5, "H": 2.5}
    factors = {(s, sc, e, ec): f for s, sc, e, ec, f in connections}
    # the force on the support as it is: no connection needs a factor
    assert factors[("block", "FxSupport", "frame", "Fx[3]")] == 1.0
    assert factors[("block", "FzSupport", "frame", "Fz[3]")] == 1.0
    assert set(factors.values()) == {1.0}
    negated = ssp.write_ssp(tmp_path / "n.ssp", *fmus, params, {}, FLOOR, H, forces="negated")
    factors = {(s, sc, e, ec): f for s, sc, e, ec, f in ssp.read_ssp(negated)[1]}
    assert factors[("block", "Fx", "frame", "Fx[3]")] == -1.0
    assert factors[("frame", "a[3]", "block", "ag")] == 1.0


def test_the_ssp_file_names_omsimulators_master_in_its_vendor_annotation(ssp_system, fmus, tmp_path):
    """OMSimulator imports a system only if its own annotation (type "org.openmodelica")
    names the master (docs/cosimulation-hosts.md, section 3): the fixed-step "oms-ma" at
    the file's step. The annotation stays within the standard: fmpy's reader validates
    the file against the SSP 1.0 schema and reads the system as before."""
    import xml.etree.ElementTree as ET

    from fmpy.ssp.ssd import read_ssd

    ns = {"ssd": ssp.SSD_NS, "ssc": ssp.SSC_NS,
          "oms": "https://raw.githubusercontent.com/OpenModelica/OMSimulator/master/schema/oms.xsd"}
    for path, step in [(ssp_system[0], H),
                       (ssp.write_ssp(tmp_path / "n.ssp", *fmus, {"n": 3}, {}, FLOOR, 0.0025, forces="negated"),
                        0.0025)]:
        root = ET.fromstring(ssp.ssd_text(path))
        annotations = root.findall("ssd:System/ssd:Annotations/ssc:Annotation", ns)
        assert [a.get("type") for a in annotations] == ["org.openmodelica"], path
        masters = annotations[0].findall("oms:Annotations/oms:SimulationInformation/oms:FixedStepMaster", ns)
        assert len(masters) == 1, path
        assert masters[0].get("description") == "oms-ma"
        assert float(masters[0].get("stepSize")) == step
        assert 0.0 < float(masters[0].get("relativeTolerance")) <= 1e-6
        ssd = read_ssd(str(path), validate=True)  # raises on a schema violation
        assert [e.name for e in ssd.system.elements] == ["frame", "block"]
        assert len(ssd.system.connections) == 6


def test_the_container_refuses_a_sign_it_cannot_apply_unless_told_how(fmus, tmp_path):
    negated = ssp.write_ssp(tmp_path / "n.ssp", *fmus, {"n": 3}, {}, FLOOR, H, forces="negated")
    with pytest.raises(ValueError, match="factor -1.0"):
        ssp.container_from_ssp(negated, tmp_path, H)
    _, dropped = ssp.container_from_ssp(negated, tmp_path, H, signs="drop")
    assert [d[1] for d in dropped] == ["Fx", "Fz"]


def test_the_container_fmu_is_the_jacobi_loop_bit_for_bit(ssp_system, fmus):
    """The container couples the block's support forces as they are: its run is
    hostloop's Jacobi loop (the frame fed the block's -Fx, -Fz of the same
    communication point), with no extra step of force lag."""
    path, _, work = ssp_system
    container, dropped = ssp.container_from_ssp(path, work, H)
    assert dropped == []
    record = np.array(list(zip(RECORD_T, RECORD_AG)), dtype=[("time", float), ("ag", float)])
    got = fmpy.simulate_fmu(str(container), stop_time=T_END, output_interval=H, input=record,
                            output=["theta", "aFloor"])
    ref = _fmu_coupled(fmus, ground_mode="constant")
    assert np.abs(ref.theta).max() > 0.05
    assert np.array_equal(got["time"], ref.t)
    assert np.array_equal(got["theta"], ref.theta)
    assert np.array_equal(got["aFloor"], ref.a_floor)


def test_the_c_host_reproduces_the_same_scheme_bit_for_bit(fmus, tmp_path):
    case = _case_of_this_file()
    got = hosts.run_c_host(case, H, tmp_path, hosts.build_c_host(tmp_path))
    ref = _fmu_coupled(fmus, ground_mode="constant")
    assert np.abs(ref.theta).max() > 0.05
    assert np.array_equal(got.time, ref.t)
    assert np.abs(got.theta - ref.theta).max() <= 1e-12
    assert np.abs(got.a_floor - ref.a_floor).max() <= 1e-9


def _case_of_this_file():
    params = {"n": 3, "damping": "rayleigh", "rayleighAlpha": RAYLEIGH[0], "rayleighBeta": RAYLEIGH[1]}
    for i in range(3):
        params[f"m[{i + 1}]"], params[f"k[{i + 1}]"] = M[i], K[i]
    return dict(frame=params, block={}, floor=FLOOR, stop_time=T_END,
                ground=lambda t: np.interp(t, RECORD_T, RECORD_AG))


# -- every host on the convergence case of rocking.cosim.study, against its reference --

@pytest.fixture(scope="module")
def reference():
    return Reference(**convergence_case())


@pytest.fixture(scope="module")
def hosts_vs_reference(fmus, tmp_path_factory, reference):
    work = tmp_path_factory.mktemp("hosts")
    case = convergence_case()
    ref = reference
    exe = hosts.build_c_host(work)
    out = {}
    with CoupledFMUs(*fmus) as pair:
        for h in (0.005, 0.0025):
            runs = {"master": hosts.run_master(case, h, pair), "container": hosts.run_container(case, h, work),
                    "c-host": hosts.run_c_host(case, h, work, exe), "opensees": hosts.run_opensees(case, h),
                    "fmpy-ssp": hosts.run_fmpy_ssp(case, h, work)}
            out[h] = {name: (res, errors(res, ref)) for name, res in runs.items()}
    return out


@pytest.mark.parametrize("host", ["master", "container", "c-host", "opensees", "fmpy-ssp"])
def test_every_host_converges_to_the_reference_at_order_one(hosts_vs_reference, host):
    coarse, fine = hosts_vs_reference[0.005][host][1], hosts_vs_reference[0.0025][host][1]
    print(f"{host}: theta error {coarse['theta']:.2e} -> {fine['theta']:.2e}, peak theta "
          f"{coarse['peak_theta']:.1e} -> {fine['peak_theta']:.1e}, peak a[3] {coarse['peak_a_floor']:.1e} -> "
          f"{fine['peak_a_floor']:.1e}")
    assert 1.6 < coarse["theta"] / fine["theta"] < 2.6
    assert fine["peak_theta"] < 3e-3 and fine["peak_a_floor"] < 3e-3


@pytest.mark.parametrize("host", ["container", "c-host", "opensees", "fmpy-ssp"])
def test_every_host_agrees_with_the_master_within_the_coupling_error(hosts_vs_reference, host):
    for h, runs in hosts_vs_reference.items():
        master, got = runs["master"][0], runs[host][0]
        n = min(len(master.time), len(got.time))
        assert np.array_equal(master.time[:n], got.time[:n])
        diff = np.abs(master.theta[:n] - got.theta[:n]).max() / np.abs(master.theta).max()
        coupling = max(runs["master"][1]["theta"], runs[host][1]["theta"])  # each against the reference
        print(f"{host}, h = {h}: theta differs from the master's by {diff:.2e} of its peak; the larger "
              f"coupling error of the two {coupling:.2e}")
        assert diff <= 1.5 * coupling


def test_fmpy_ssp_is_the_jacobi_loop_with_the_ground_one_step_late(hosts_vs_reference, tmp_path):
    """fmpy's simulate_ssp on the SSP file with the support forces: the C host's
    loop (the frame fed -Fx, -Fz of the same point, no extra force lag) given
    the ground of the previous communication point. Not bit for bit only because
    fmpy evaluates the input at its own times, which add h step by step."""
    h = 0.005
    case = convergence_case()
    ground = case["ground"]
    late = dict(case, ground=lambda t: np.where(np.asarray(t) >= h / 2, ground(np.asarray(t) - h), 0.0))
    loop = hosts.run_c_host(late, h, tmp_path, hosts.build_c_host(tmp_path))
    got = hosts_vs_reference[h]["fmpy-ssp"][0]
    assert np.array_equal(loop.time, got.time)
    assert np.abs(loop.theta).max() > 0.1
    assert np.abs(loop.theta - got.theta).max() <= 1e-12
    assert np.abs(loop.a_floor - got.a_floor).max() <= 1e-10


def test_opensees_with_extrapolated_inputs_converges_faster(reference, hosts_vs_reference):
    """hostloop's hold="linear": the block's force passed with its output derivative,
    the floor acceleration with its last difference."""
    peaks = {}
    for h in (0.005, 0.0025):
        res = hosts.run_opensees(convergence_case(), h, hold="linear")
        peaks[h] = errors(res, reference)["peak_theta"]
    held = hosts_vs_reference[0.0025]["opensees"][1]["peak_theta"]
    print(f"OpenSees, extrapolated inputs: peak theta error {peaks[0.005]:.1e} -> {peaks[0.0025]:.1e} "
          f"(held: {held:.1e} at 2.5 ms)")
    assert peaks[0.005] / peaks[0.0025] > 3.0  # order 2 where holding gives 1
    assert peaks[0.0025] < 0.2 * held


def test_the_container_ends_cleanly_where_the_block_overturns(fmus, tmp_path):
    case = dict(convergence_case(), ground=sine_ground(9.0, 2.0, cycles=3))
    with CoupledFMUs(*fmus) as pair:
        master = hosts.run_master(case, H, pair)
    got = hosts.run_container(case, H, tmp_path)
    assert master.overturned and got.overturned
    # the container stops at the communication point before the overturning
    assert master.t_overturn - H <= got.time[-1] < master.t_overturn


def test_fmpy_simulate_ssp_ignores_bindings_and_factors_as_documented(fmus, tmp_path):
    """What docs/cosimulation-hosts.md says of fmpy's SSP support, measured."""
    from fmpy.ssp.simulation import simulate_ssp

    frame, block = fmus
    path = ssp.write_ssp(tmp_path / "s.ssp", frame, block, {"n": 3}, {"B": 0.4}, FLOOR, H, forces="negated")
    plain = simulate_ssp(str(path), stop_time=0.2, step_size=H, input={"ag": lambda t: 3.0})
    bound = simulate_ssp(str(path), stop_time=0.2, step_size=H, input={"ag": lambda t: 3.0},
                         parameter_set=ssp.fmpy_parameter_set(path))
    weight = lambda b: 1800 * 9.81 * b * 1.0 * 2.5  # the default prism, rho g B L H
    assert plain["block.Fz"][0] == pytest.approx(weight(0.5), rel=1e-12)  # B = 0.4 not applied
    assert bound["block.Fz"][0] == pytest.approx(weight(0.4), rel=1e-12)
    # the -1 factor is not applied: the frame receives the block's Fx itself
    assert np.abs(bound["block.Fx"]).max() > 0
    assert np.array_equal(bound["frame.Fx[3]"], bound["block.Fx"])
