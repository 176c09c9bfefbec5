"""RockingBlock as an FMI 3.0 FMU (target/fmu/fmi3/RockingBlock.fmu, the same
binary as the 2.0 archive): fmpy's FMI 3.0 XSD and validation, the same
variables as 2.0, trajectories bit for bit equal to 2.0's under the same host
loop (co-simulation and Model Exchange), FMU states round-tripped, calls
refused in the wrong state, and early return at the impacts of a rigid
block against Housner's closed form (test_model_exchange.Exact)."""

import math
import pathlib
import re
import subprocess
import sys

import numpy as np
import pytest
from fmpy import extract, read_model_description, simulate_fmu
from fmpy.fmi1 import FMICallException
from fmpy.fmi2 import FMU2Slave
from fmpy.fmi3 import FMU3Slave
from fmpy.validation import validate_fmu

from conftest import FMU
from fmu_helpers import start_values
from test_model_exchange import Exact, rigid_block

FMU3 = FMU.parent / "fmi3" / "RockingBlock.fmu"


@pytest.fixture(scope="module")
def fmu3_path():
    if not FMU3.is_file():
        pytest.fail(f"{FMU3} not found: run `cargo xtask fmu` first", pytrace=False)
    return str(FMU3)


def test_the_archive_validates_and_declares_the_2_0_variables(fmu_path, fmu3_path):
    assert validate_fmu(fmu3_path) == []
    cli = subprocess.run([sys.executable, "-m", "fmpy.cli", "validate", fmu3_path],
                         capture_output=True, text=True)
    assert cli.returncode == 0, cli.stdout + cli.stderr
    md2, md3 = read_model_description(fmu_path), read_model_description(fmu3_path, validate=True)
    assert md3.fmiVersion == "3.0" and md3.instantiationToken == md2.guid
    cs = md3.coSimulation
    assert cs.hasEventMode and cs.mightReturnEarlyFromDoStep and cs.canGetAndSetFMUstate
    assert md3.modelExchange is not None and md3.numberOfEventIndicators == md2.numberOfEventIndicators

    def table(md, skip=()):
        return {v.name: (v.valueReference, v.causality, v.variability, v.unit, v.start)
                for v in md.modelVariables if v.name not in skip}

    rates = {f"der({v.name})": v for v in md2.modelVariables
             if v.causality == "input" and v.variability == "continuous" and v.type == "Real"}
    assert set(rates) == {"der(ag)", "der(av)"}
    added = {"time"} | {f"eventIndicator{i + 1}" for i in range(md2.numberOfEventIndicators)} | set(rates)
    assert table(md3, added) == table(md2)
    # each input's first derivative: an input of its own, declared with `derivative`
    for name, x in rates.items():
        v = next(v for v in md3.modelVariables if v.name == name)
        assert (v.causality, v.variability, float(v.start)) == ("input", "continuous", 0.0)
        derivative = v.derivative if isinstance(v.derivative, str) else v.derivative.valueReference
        assert int(derivative) == x.valueReference
    # the same binaries under 3.0's platform names: the 2.0 archive's checks
    # (glibc 2.17 baseline, the win64 host under wine) hold for them
    two, three = _binaries(fmu_path), _binaries(fmu3_path)
    assert "x86_64-linux" in three and set(three) <= {"x86_64-linux", "x86_64-windows"}
    assert {NAMES[p]: b for p, b in two.items()} == three


NAMES = {"linux64": "x86_64-linux", "win64": "x86_64-windows"}


def _binaries(path):
    """Platform folder -> the bytes of the archive's binary there."""
    import zipfile

    with zipfile.ZipFile(path) as z:
        return {pathlib.PurePath(n).parts[1]: z.read(n) for n in z.namelist() if n.startswith("binaries/")}


def _ground(t):
    """A decaying 2 Hz pulse (m/s2): rocking with impacts on the crushing joint."""
    return 4.0 * math.sin(2 * math.pi * 2.0 * t) * math.exp(-0.5 * t)


CASE = dict(B=0.4, H=1.6, theta=0.0, omega=0.0)
OUT = ["theta", "omega", "af", "Fx"]


def _vr(md, names):
    v = {x.name: x.valueReference for x in md.modelVariables}
    return [v[n] for n in names]


def _initialized(path, slave_class, name):
    """A co-simulation instance of CASE out of initialization, either standard:
    (slave, model description, its setter and getter of Float64/Real)."""
    md = read_model_description(path)
    two = md.fmiVersion == "2.0"
    s = slave_class(guid=md.guid if two else md.instantiationToken, unzipDirectory=extract(path),
                    modelIdentifier="RockingBlock", instanceName=name)
    s.instantiate()
    real, get = (s.setReal, s.getReal) if two else (s.setFloat64, s.getFloat64)
    if two:
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
    else:
        s.enterInitializationMode(startTime=0.0)
    real(_vr(md, CASE), list(CASE.values()))
    s.exitInitializationMode()
    return s, md, real, get


def _co_simulate(path, slave_class, n=300, h=0.01):
    """One host loop for both standards: inputs held over each step."""
    s, md, real, get = _initialized(path, slave_class, "cs")
    ag, out = _vr(md, ["ag"]), _vr(md, OUT)
    rows = []
    for k in range(n):
        t = k * h
        real(ag, [_ground(t)])
        s.doStep(t, h)
        rows.append(get(out))
    s.terminate()
    s.freeInstance()
    return np.array(rows)


def _support_forces(path, slave_class, n=150, h=0.01):
    """Fx, Fz, FxSupport, FzSupport and their output derivatives of order 1 and
    2 after each step, a block rocking on the crushing joint (no av: the
    flexible laws give output derivatives without it only)."""
    s, md, real, get = _initialized(path, slave_class, "forces")
    rates = s.getRealOutputDerivatives if md.fmiVersion == "2.0" else s.getOutputDerivatives
    ag, out = _vr(md, ["ag"]), _vr(md, ["Fx", "Fz", "FxSupport", "FzSupport"])
    rows = []
    for k in range(n):
        t = k * h
        real(ag, [_ground(t)])
        s.doStep(t, h)
        rows.append(get(out) + rates(out, [1] * 4) + rates(out, [2] * 4))
    s.terminate()
    s.freeInstance()
    return np.array(rows)


def test_support_forces_are_exactly_the_opposite_of_fx_fz(fmu_path, fmu3_path):
    """FxSupport = -Fx and FzSupport = -Fz bit for bit along a run, values and
    output derivatives, in 2.0 and 3.0 co-simulation and in 2.0 Model Exchange."""
    for path, slave in [(fmu_path, FMU2Slave), (fmu3_path, FMU3Slave)]:
        r = _support_forces(path, slave)
        assert np.abs(r[:, 0]).max() > 1e3  # the block rocks and pushes
        for j in (0, 4, 8):  # value, first and second derivative
            assert (-r[:, j:j + 2]).tobytes() == r[:, j + 2:j + 4].tobytes(), (path, j)
    me = simulate_fmu(fmu_path, fmi_type="ModelExchange", stop_time=1.0, output_interval=0.01,
                      start_values=dict(CASE), input=np.array([(0.0, 4.0), (1.0, -4.0)],
                                                               dtype=[("time", float), ("ag", float)]),
                      output=["Fx", "Fz", "FxSupport", "FzSupport"])
    assert np.abs(me["Fx"]).max() > 1e3
    assert (-me["Fx"]).tobytes() == me["FxSupport"].tobytes()
    assert (-me["Fz"]).tobytes() == me["FzSupport"].tobytes()


def _ramps(path, slave_class, rates, n=120, h=0.01):
    """theta, omega, Fx, Fz after each step under ag and av given at the
    communication points with their slopes over the step (`rates`: "2.0" by
    fmi2SetRealInputDerivatives after the values, "3.0" by the der(x) inputs
    set before the values in the same fmi3SetFloat64 call, None: held)."""
    s, md, real, get = _initialized(path, slave_class, "ramps")
    inputs, out = _vr(md, ["ag", "av"]), _vr(md, ["theta", "omega", "Fx", "Fz"])
    ground = lambda t: [_ground(t), 0.3 * _ground(t + 0.1)]
    rows = []
    for k in range(n):
        t = k * h
        x0, x1 = ground(t), ground(t + h)
        slope = [(b - a) / h for a, b in zip(x0, x1)]
        if rates == "3.0":
            real(_vr(md, ["der(ag)", "der(av)"]) + inputs, slope + x0)
            assert get(_vr(md, ["der(ag)", "der(av)"])) == slope
        else:
            real(inputs, x0)
            if rates == "2.0":
                s.setRealInputDerivatives(inputs, [1, 1], slope)
        s.doStep(t, h)
        rows.append(get(out))
    s.terminate()
    s.freeInstance()
    return np.array(rows)


def test_input_derivatives_in_3_0_are_the_2_0_ones(fmu_path, fmu3_path):
    """The der(ag), der(av) inputs of 3.0 co-simulation interpolate the inputs
    over a step as 2.0's fmi2SetRealInputDerivatives of order 1 does: the same
    trajectory bit for bit (and not the one with the inputs held)."""
    two, three = _ramps(fmu_path, FMU2Slave, "2.0"), _ramps(fmu3_path, FMU3Slave, "3.0")
    held = _ramps(fmu3_path, FMU3Slave, None)
    assert np.abs(two[:, 0]).max() > 1e-3  # it rocks
    assert two.tobytes() == three.tobytes()
    assert np.abs(three[:, 0] - held[:, 0]).max() > 1e-6


def test_setting_an_input_alone_resets_its_der_input(fmu3_path):
    """Setting ag without der(ag) in the same call resets der(ag) to 0 (2.0's rule: a
    host that knows nothing of der(x) gets its input held, never a slope left from an
    earlier step); in the same call, in either order, the slope stands; der(av) in a
    call does not keep ag's."""
    s, md, real, get = _initialized(fmu3_path, FMU3Slave, "reset")
    ag, dag, dav = _vr(md, ["ag"]), _vr(md, ["der(ag)"]), _vr(md, ["der(av)"])
    real(dag + ag, [2.5, 1.0])
    assert get(dag) == [2.5]
    real(ag, [1.5])
    assert get(dag) == [0.0]
    real(ag + dag, [1.0, -3.0])
    assert get(dag) == [-3.0]
    real(ag + dav, [2.0, 4.0])
    assert get(dag) == [0.0] and get(dav) == [4.0]
    real(dag, [7.0])  # der(x) alone: x stays
    assert get(dag) == [7.0] and get(ag) == [2.0]
    s.terminate()
    s.freeInstance()


def test_co_simulation_is_bit_for_bit_the_2_0_trajectory(fmu_path, fmu3_path):
    a, b = _co_simulate(fmu_path, FMU2Slave), _co_simulate(fmu3_path, FMU3Slave)
    assert np.abs(a[:, 0]).max() > 1e-3  # it rocks
    assert a.tobytes() == b.tobytes()


def test_model_exchange_is_bit_for_bit_the_2_0_trajectory(fmu_path, fmu3_path):
    params = rigid_block()
    kw = dict(fmi_type="ModelExchange", solver="CVode", relative_tolerance=1e-8, stop_time=2.0,
              output_interval=0.01, start_values=start_values(params),
              output=["theta", "omega", "impacts"])
    a, b = simulate_fmu(fmu_path, **kw), simulate_fmu(fmu3_path, **kw)
    assert a["impacts"][-1] >= 3
    for name in ["time", "theta", "omega", "impacts"]:
        assert a[name].tobytes() == b[name].tobytes(), name


def _slave3(path, **flags):
    md = read_model_description(path)
    s = FMU3Slave(guid=md.instantiationToken, unzipDirectory=extract(path),
                  modelIdentifier="RockingBlock", instanceName="s3")
    messages = []
    s.instantiate(logMessage=lambda env, status, category, message: messages.append(message.decode()),
                  **flags)
    return s, md, messages


def test_fmu_state_round_trips_and_output_derivatives(fmu3_path):
    s, md, _ = _slave3(fmu3_path)
    s.enterInitializationMode(startTime=0.0)
    s.setFloat64(_vr(md, CASE), list(CASE.values()))
    s.exitInitializationMode()
    ag, out = _vr(md, ["ag"]), _vr(md, OUT)

    def run(t0, n):
        rows = []
        for k in range(n):
            s.setFloat64(ag, [_ground(t0 + k * 0.01)])
            s.doStep(t0 + k * 0.01, 0.01)
            rows.append(s.getFloat64(out))
        return rows

    run(0.0, 50)
    # output derivatives as in 2.0: d theta / dt is omega
    theta, omega = _vr(md, ["theta", "omega"])
    assert s.getOutputDerivatives([theta], [1]) == s.getFloat64([omega])
    bytes_ = s.serializeFMUState(s.getFMUState())
    first = run(0.5, 50)
    state = s.deserializeFMUState(bytes_)
    s.setFMUState(state)
    s.freeFMUState(state)
    again = run(0.5, 50)
    assert np.array(first).tobytes() == np.array(again).tobytes()
    s.terminate()
    s.freeInstance()


def test_instantiation_is_traced_with_the_instance_name(fmu3_path):
    """With logging on, the instantiation's trace names the instance as the
    host gave it: the quoted string, as FMI 2.0's does."""
    s, _, messages = _slave3(fmu3_path, loggingOn=True)
    s.freeInstance()
    assert any(m.startswith('fmi3InstantiateCoSimulation: instance "s3", token ') for m in messages), messages


def test_bad_calls_are_refused_through_the_logger(fmu3_path):
    """Each bad call on a fresh instance: refused with fmi3Error and a
    message naming the function and what is wrong."""

    def refused(call, expect):
        s, md, messages = _slave3(fmu3_path)
        with pytest.raises(FMICallException):
            call(s, md)
        s.freeInstance()
        assert any(expect in m for m in messages), messages

    refused(lambda s, md: s.doStep(0.0, 0.01), "fmi3DoStep: not allowed in state instantiated")
    # an enumeration is an Int64 in FMI 3.0, not an Int32
    refused(lambda s, md: s.setInt32(_vr(md, ["shape"]), [1]), "is no Int32 variable")
    refused(lambda s, md: s.setInt64(_vr(md, ["shape"]), [2**40]), "is no item")
    refused(lambda s, md: s.setFloat64(_vr(md, ["time"]), [1.0]), "cannot be set")
    refused(lambda s, md: s.setFloat64(_vr(md, ["der(ag)"]), [math.inf]), "must be finite")
    refused(lambda s, md: s.enterStepMode(), "eventModeUsed = false")

    def bad_width(s, md):
        s.enterInitializationMode(startTime=0.0)
        s.setFloat64(_vr(md, ["B"]), [-1.0])
        s.exitInitializationMode()

    refused(bad_width, "invalid parameters")
    s, md, _ = _slave3(fmu3_path)
    s.setInt64(_vr(md, ["shape"]), [1])  # the Int64 of an enumeration is accepted
    s.freeInstance()


def test_early_return_stops_at_each_impact_of_a_rigid_block(fmu3_path):
    """Free rocking of a rigid block from 0.5 alpha, 0.05 s steps: each step
    that holds an impact returns early at it, and the returned times are
    Housner's closed-form impact times."""
    ex = Exact(0.25, 1.0)
    exact = ex.impact_times(0.5 * ex.alpha, 6)
    s, md, _ = _slave3(fmu3_path, eventModeUsed=True, earlyReturnAllowed=True)
    params = start_values(rigid_block())
    s.enterInitializationMode(startTime=0.0)
    for name, value in params.items():
        (s.setInt64 if isinstance(value, int) else s.setFloat64)(_vr(md, [name]), [value])
    s.exitInitializationMode()
    s.updateDiscreteStates()
    s.enterStepMode()
    t, h, returns = 0.0, 0.05, []
    impacts = _vr(md, ["impacts"])
    while t < exact[-1] + 0.01:
        event, terminate, early, last = s.doStep(t, min(h, exact[-1] + 0.01 - t))
        assert not terminate
        if early:
            assert event and t < last < t + h
            returns.append((last, s.getInt32(impacts)[0]))
            s.enterEventMode()
            s.updateDiscreteStates()
            s.enterStepMode()
        t = last
    s.terminate()
    s.freeInstance()
    at_impact = [t for t, _ in returns]
    # every impact is an early return, and the impact count rises at each
    assert [n for _, n in returns][:len(exact)] == list(range(1, len(exact) + 1))
    err = np.abs(np.array(at_impact[:len(exact)]) - exact) / np.array(exact)
    print(f"\nearly returns at {len(exact)} impacts: worst relative error {err.max():.1e} against Housner")
    assert err.max() < 1e-7


def _overturn_2_0(fmu_path, params, ag, h):
    """fmi2LastSuccessfulTime of the step that discards at overturning."""
    from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated

    md = read_model_description(fmu_path)
    s = FMU2Slave(guid=md.guid, unzipDirectory=extract(fmu_path), modelIdentifier="RockingBlock",
                  instanceName="ov2")
    s.instantiate()
    s.setupExperiment(startTime=0.0)
    s.enterInitializationMode()
    for name, value in params.items():
        (s.setInteger if isinstance(value, int) else s.setReal)(_vr(md, [name]), [value])
    s.exitInitializationMode()
    s.setReal(_vr(md, ["ag"]), [ag])
    t = 0.0
    while True:
        try:
            s.doStep(t, h)
        except FMICallException:
            break
        t += h
    assert s.getBooleanStatus(fmi2Terminated)
    t_ov = s.getRealStatus(fmi2LastSuccessfulTime)
    s.terminate()
    s.freeInstance()
    return t_ov


@pytest.mark.parametrize("early", [False, True])
def test_overturning_ends_the_run_at_the_2_0_time(fmu_path, fmu3_path, early):
    """A rigid block under a constant ag of twice g tan(alpha) overturns;
    3.0 ends the run with terminateSimulation at the time 2.0 discards at
    (bit for bit without early return, where the steps are the same)."""
    params = start_values(rigid_block(theta_over_alpha=0.0))
    ag, h = 2 * 9.81 * 0.25, 0.05
    t_ov2 = _overturn_2_0(fmu_path, params, ag, h)
    s, md, messages = _slave3(fmu3_path, eventModeUsed=early, earlyReturnAllowed=early)
    s.enterInitializationMode(startTime=0.0)
    for name, value in params.items():
        (s.setInt64 if isinstance(value, int) else s.setFloat64)(_vr(md, [name]), [value])
    s.exitInitializationMode()
    if early:
        s.updateDiscreteStates()
        s.enterStepMode()
    s.setFloat64(_vr(md, ["ag"]), [ag])
    t, returns = 0.0, []
    while True:
        event, terminate, early_return, last = s.doStep(t, h)
        if terminate:
            break
        if early_return:  # uplift at the start
            returns.append(last)
            s.enterEventMode()
            s.updateDiscreteStates()
            s.enterStepMode()
        t = last
    assert s.getBoolean(_vr(md, ["overturned"]))[0]
    s.terminate()
    s.freeInstance()
    if early:
        assert abs(last - t_ov2) < 1e-9 * t_ov2
    else:
        assert last == t_ov2 and returns == []


SHEAR2, SHEAR3 = FMU.parent / "ShearFrame.fmu", FMU.parent / "fmi3" / "ShearFrame.fmu"
PER_FLOOR = ("m", "k", "Fx", "Fz", "u", "v", "a", "drift", "period")


def _by_name(md):
    return {v.name: v for v in md.modelVariables}


def test_shear_frame_3_0_declares_arrays_sized_by_n():
    """3.0: n is a UInt64 structural parameter; each per-floor variable of
    2.0 (Fx[1] ... Fx[20]) is one array (Fx) whose Dimension is n, with the
    value reference, causality, unit and start of its 2.0 element 1."""
    assert validate_fmu(str(SHEAR3)) == []
    cli = subprocess.run([sys.executable, "-m", "fmpy.cli", "validate", str(SHEAR3)],
                         capture_output=True, text=True)
    assert cli.returncode == 0, cli.stdout + cli.stderr
    two, three = (_by_name(read_model_description(str(p), validate=True)) for p in (SHEAR2, SHEAR3))
    n = three["n"]
    assert (n.type, n.causality, n.variability, int(n.start)) == ("UInt64", "structuralParameter", "fixed", 3)
    assert n.valueReference == two["n"].valueReference
    # 3.0 has no elements past n: n's description says it sizes the arrays
    assert "past n" in two["n"].description and "past n" not in n.description
    assert "length of every per-floor array" in n.description
    import zipfile

    with zipfile.ZipFile(SHEAR3) as z:  # fmpy 0.3.32 reads no min/max of a UInt64
        xml = z.read("modelDescription.xml").decode()
    assert re.search(r'<UInt64 name="n"[^>]* min="1" max="20"', xml)
    for name in PER_FLOOR:
        v, first = three[name], two[f"{name}[1]"]
        assert [int(d.valueReference) for d in v.dimensions] == [n.valueReference] and v.shape == (3,)
        assert (v.valueReference, v.causality, v.variability, v.unit, v.start) == \
               (first.valueReference, first.causality, first.variability, first.unit, first.start), name
    for name in ("Fx", "Fz"):
        der = three[f"der({name})"]
        derivative = der.derivative if isinstance(der.derivative, str) else der.derivative.valueReference
        assert int(derivative) == three[name].valueReference and der.shape == (3,)
    assert not [x for x in three if "[" in x]
    assert set(three) == {"time", "n", "damping", "zeta", "rayleighAlpha", "rayleighBeta", "ag", "der(ag)",
                          *PER_FLOOR, "der(Fx)", "der(Fz)"}


def test_shear_frame_3_0_is_bit_for_bit_its_2_0(fmu_path):
    """A 3-storey frame under a step of ag (fmpy's simulate_fmu; n left at
    its start 3: fmpy sets start values in the instantiated state, where 3.0
    forbids setting a structural parameter): the 3.0 arrays u, v, a are the
    2.0 scalars u[i], v[i], a[i] bit for bit."""
    start = {"ag": 1.5, "zeta": 0.05}
    out = [f"{x}[{i}]" for x in ("u", "v", "a") for i in (1, 2, 3)]
    a = simulate_fmu(str(SHEAR2), start_values={"n": 3, **start}, stop_time=2.0, output_interval=0.01,
                     output=out)
    b = simulate_fmu(str(SHEAR3), start_values=start, stop_time=2.0, output_interval=0.01,
                     output=["u", "v", "a"])
    assert np.abs(a["u[3]"]).max() > 0 and b["a"].shape == (201, 3)
    assert a["time"].tobytes() == b["time"].tobytes()
    for x in ("u", "v", "a"):
        two = np.stack([a[f"{x}[{i}]"] for i in (1, 2, 3)], axis=1)
        assert two.tobytes() == np.ascontiguousarray(b[x]).tobytes(), x


def _shear_frame_ramps(path, slave_class, storeys=3, floors=None, n=100, h=0.01):
    """ShearFrame of `storeys` storeys (masses and stiffnesses `floors`, if
    given) under ag and Fx[3] ramps given with their slopes (2.0:
    fmi2SetRealInputDerivatives of scalars; 3.0: n in configuration mode,
    the arrays Fx, der(Fx), m, k whole): a[1..storeys] after each step."""
    md = read_model_description(path)
    two = md.fmiVersion == "2.0"
    s = slave_class(guid=md.guid if two else md.instantiationToken, unzipDirectory=extract(path),
                    modelIdentifier="ShearFrame", instanceName="frame")
    s.instantiate()
    per_floor = range(1, storeys + 1)
    if two:
        s.setupExperiment(startTime=0.0)
        s.enterInitializationMode()
        s.setInteger(_vr(md, ["n"]), [storeys])
        real, get = s.setReal, s.getReal
        inputs, out = _vr(md, ["ag", "Fx[3]"]), _vr(md, [f"a[{i}]" for i in per_floor])
        m, k = (_vr(md, [f"{x}[{i}]" for i in per_floor]) for x in "mk")
    else:
        s.enterConfigurationMode()
        s.setUInt64(_vr(md, ["n"]), [storeys])
        s.exitConfigurationMode()
        s.enterInitializationMode(startTime=0.0)
        real, get = s.setFloat64, (lambda vrs: s.getFloat64(vrs, nValues=storeys))
        inputs, out, m, k = _vr(md, ["ag", "Fx"]), _vr(md, ["a"]), _vr(md, ["m"]), _vr(md, ["k"])
    if floors is not None:
        real(m, floors[0])
        real(k, floors[1])
    s.exitInitializationMode()

    def values(ag, fx3):  # 3.0: Fx whole, its element 3 set
        return [ag, fx3] if two else [ag] + [fx3 if i == 3 else 0.0 for i in per_floor]

    rows = []
    for step in range(n):
        x0, x1 = ([_ground(t), 1e4 * _ground(t + 0.2)] for t in (step * h, (step + 1) * h))
        slope = [(b - a) / h for a, b in zip(x0, x1)]
        real(inputs, values(*x0))
        if two:
            s.setRealInputDerivatives(inputs, [1, 1], slope)
        else:
            real(_vr(md, ["der(ag)", "der(Fx)"]), values(*slope))
        s.doStep(step * h, h)
        rows.append(get(out))
    s.terminate()
    s.freeInstance()
    return np.array(rows)


def test_shear_frame_input_derivatives_in_3_0_are_the_2_0_ones():
    two = _shear_frame_ramps(str(SHEAR2), FMU2Slave)
    three = _shear_frame_ramps(str(SHEAR3), FMU3Slave)
    assert three.shape == (100, 3) and np.abs(two).max() > 0.1
    assert two.tobytes() == three.tobytes()


def test_shear_frame_3_0_at_another_n_is_its_2_0():
    """n = 5 set in configuration mode, with masses and stiffnesses that
    differ floor by floor (the arrays m, k set whole): the 2.0 run with
    n = 5 and the scalars m[i], k[i], bit for bit."""
    floors = ([2.0e5, 1.8e5, 1.5e5, 1.2e5, 0.9e5], [3.0e8, 2.6e8, 2.2e8, 1.6e8, 1.0e8])
    two = _shear_frame_ramps(str(SHEAR2), FMU2Slave, storeys=5, floors=floors)
    three = _shear_frame_ramps(str(SHEAR3), FMU3Slave, storeys=5, floors=floors)
    assert three.shape == (100, 5) and np.abs(two[:, 4]).max() > 0.1
    assert two.tobytes() == three.tobytes()
    assert two.tobytes() != _shear_frame_ramps(str(SHEAR2), FMU2Slave, storeys=5).tobytes()


def test_shear_frame_3_0_refuses_a_wrong_count_through_the_logger():
    """nValues must count an array's n elements: fmpy's default (one value per
    value reference) for `a` is refused with a logged line naming it."""
    md = read_model_description(str(SHEAR3))
    s = FMU3Slave(guid=md.instantiationToken, unzipDirectory=extract(str(SHEAR3)), modelIdentifier="ShearFrame",
                  instanceName="frame")
    messages = []
    s.instantiate(logMessage=lambda env, status, category, message: messages.append(message.decode()))
    s.enterInitializationMode(startTime=0.0)
    s.exitInitializationMode()
    with pytest.raises(FMICallException):
        s.getFloat64(_vr(md, ["a"]))
    assert any("nValues = 1" in m and "a has 3 elements" in m for m in messages), messages
    s.freeInstance()


def test_co_simulation_reads_every_float64_as_a_recording_host_does(fmu3_path):
    """fmusim reads every Float64 variable of a co-simulation instance to record it; the
    event indicators answer there too: indicator 2 is thetaOv - |theta| (no av)."""
    s, md, messages = _slave3(fmu3_path)
    floats = [v for v in md.modelVariables if v.type == "Float64"]
    vrs = [v.valueReference for v in floats]
    s.enterInitializationMode(startTime=0.0)
    s.setFloat64(_vr(md, CASE), list(CASE.values()))
    s.exitInitializationMode()
    for k in range(30):
        s.setFloat64(_vr(md, ["ag"]), [_ground(k * 0.01)])
        s.doStep(k * 0.01, 0.01)
        values = dict(zip((v.name for v in floats), s.getFloat64(vrs)))
        assert values["eventIndicator2"] == values["thetaOv"] - abs(values["theta"]), messages
    s.terminate()
    s.freeInstance()
