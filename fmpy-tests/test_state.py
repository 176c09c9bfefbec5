"""FMU states: save/restore and serialize/deserialize reproduce the
continuation bit for bit; corrupted or foreign buffers are refused.

That fmi2FreeInstance frees the states still alive is invisible from here: it
is checked by valgrind's leak check of fmu-rocking/examples/c_api_loop.rs,
which leaves states alive for it (tools/memcheck.sh, run by tools/test.sh)."""

import struct
import zlib
from ctypes import byref, c_double, c_int, c_size_t, c_uint, c_void_p, create_string_buffer

import pytest
from fmpy.fmi2 import fmi2LastSuccessfulTime, fmi2Terminated

from fmu_helpers import DISCARD, ERROR, OK, Host

DT = 0.01


@pytest.fixture
def host(fmu_path, unzipped):
    h = Host(fmu_path, unzipped)
    yield h
    h.free()


def start(h, **values):
    h.fmu.setupExperiment(startTime=0.0)
    h.set(**values)
    h.fmu.enterInitializationMode()
    h.fmu.exitInitializationMode()


def steps(h, k0, n, ag=lambda t: 2.5 * (1 if int(t * 3) % 2 else -1)):
    """n steps from step k0 with a square-wave ground acceleration; the
    trajectory as exact floats."""
    out = []
    for k in range(k0, k0 + n):
        t = k * DT
        h.set(ag=ag(t))
        h.fmu.setRealInputDerivatives([h.vr["ag"]], [1], [0.3])
        h.fmu.doStep(t, DT)
        out.append((h.get("theta"), h.get("omega"), h.get("impacts"), h.get("Fx"), h.get("regime")))
    return out


CASES = [
    dict(interface="rigid", theta=0.05),
    dict(interface="elastic", theta=0.02),
    dict(interface="elastoPlastic", theta=0.02, shape="hollowCircle"),
]


@pytest.mark.parametrize("case", CASES, ids=[c["interface"] for c in CASES])
def test_get_set_state_reproduces_the_continuation(host, case):
    start(host, **case)
    steps(host, 0, 40)
    s = host.fmu.getFMUstate()
    first = steps(host, 40, 60)
    host.fmu.setFMUstate(s)
    again = steps(host, 40, 60)
    assert again == first  # bit for bit
    host.fmu.freeFMUstate(s)


@pytest.mark.parametrize("case", CASES, ids=[c["interface"] for c in CASES])
def test_serialized_state_continues_in_another_instance(fmu_path, unzipped, case):
    a = Host(fmu_path, unzipped, name="a")
    start(a, **case)
    steps(a, 0, 40)
    s = a.fmu.getFMUstate()
    data = a.fmu.serializeFMUstate(s)
    first = steps(a, 40, 60)
    b = Host(fmu_path, unzipped, name="b")  # fresh: parameters come with the state
    sb = b.fmu.deSerializeFMUstate(data)
    b.fmu.setFMUstate(sb)
    assert b.get("B") == a.get("B")
    again = steps(b, 40, 60)
    assert again == first
    assert b.fmu.serializeFMUstate(b.fmu.getFMUstate()) == a.fmu.serializeFMUstate(a.fmu.getFMUstate())
    a.free()
    b.free()


def test_get_state_reuses_the_given_state(host):
    start(host)
    s = host.fmu.getFMUstate()
    before = s.value
    host.fmu.doStep(0.0, 0.1)
    host.fmu.fmi2GetFMUstate(host.fmu.component, byref(s))
    assert s.value == before
    host.fmu.setFMUstate(s)
    assert host.fmu.getRealStatus(fmi2LastSuccessfulTime) == pytest.approx(0.1)


def test_state_restores_after_an_error(host):
    start(host, interface="rigid", theta=0.05)
    steps(host, 0, 10)
    s = host.fmu.getFMUstate()
    expected = steps(host, 10, 5)
    host.fmu.setFMUstate(s)
    assert host.raw("fmi2SetReal", (c_uint * 1)(host.vr["ag"]), 1, (c_double * 1)(float("nan"))) == ERROR
    host.fmu.setFMUstate(s)  # allowed in the error state: back to stepComplete
    assert steps(host, 10, 5) == expected


def test_state_restores_after_overturning(host):
    start(host, interface="rigid", theta=0.1, omega=0.6)
    s = host.fmu.getFMUstate()
    t = 0.0
    while True:
        st = host.raw("fmi2DoStep", c_double(t), c_double(DT), c_int(1))
        if st == DISCARD:
            break
        assert st == OK
        t += DT
    assert host.fmu.getBooleanStatus(fmi2Terminated)
    host.fmu.setFMUstate(s)
    assert not host.fmu.getBooleanStatus(fmi2Terminated)
    assert host.get("theta") == 0.1 and host.get("overturned") is False
    host.fmu.doStep(0.0, DT)


def test_states_of_other_instances_and_freed_states_are_refused(fmu_path, unzipped):
    a = Host(fmu_path, unzipped, name="a")
    b = Host(fmu_path, unzipped, name="b")
    start(a)
    start(b)
    s = a.fmu.getFMUstate()
    assert b.raw("fmi2SetFMUstate", s) == ERROR
    assert "not a live FMU state of this instance" in b.errors()[-1]
    a.fmu.freeFMUstate(s)
    assert s.value is None
    stale = c_void_p(12345678)
    assert a.raw("fmi2SetFMUstate", stale) == ERROR
    a.free()
    b.free()


# ----- the byte format ------------------------------------------------------

def envelope(data):
    """(guid, version, payload) of a serialized state."""
    assert data[:8] == b"FMI2STAT"
    version, n = struct.unpack_from("<II", data, 8)
    guid = data[16:16 + n]
    (plen,) = struct.unpack_from("<Q", data, 16 + n)
    payload = data[24 + n:24 + n + plen]
    (crc,) = struct.unpack_from("<I", data, 24 + n + plen)
    assert crc == zlib.crc32(data[:24 + n + plen])
    assert len(data) == 28 + n + plen
    return guid, version, payload


def seal(guid, version, payload):
    body = b"FMI2STAT" + struct.pack("<II", version, len(guid)) + guid + struct.pack("<Q", len(payload)) + payload
    return body + struct.pack("<I", zlib.crc32(body))


def deserialize_status(h, data):
    buf = create_string_buffer(bytes(data), len(data))
    state = c_void_p()
    return h.raw("fmi2DeSerializeFMUstate", buf, c_size_t(len(data)), byref(state))


@pytest.fixture
def serialized(host):
    start(host, interface="elastoPlastic", theta=0.02)
    steps(host, 0, 20)
    s = host.fmu.getFMUstate()
    return host.fmu.serializeFMUstate(s)


def test_envelope_layout(host, serialized):
    guid, version, payload = envelope(serialized)
    assert guid.decode() == host.md.guid
    assert version == 1
    assert deserialize_status(host, serialized) == OK


def test_every_corrupted_byte_is_detected(host, serialized):
    for i in range(0, len(serialized)):
        bad = bytearray(serialized)
        bad[i] ^= 0x5A
        assert deserialize_status(host, bad) == ERROR, i
        host.fmu.reset()
    assert "refused" in host.errors()[-1]


def test_truncated_and_empty_buffers_are_refused(host, serialized):
    for n in (0, 4, 8, 20, len(serialized) // 2, len(serialized) - 1):
        assert deserialize_status(host, serialized[:n]) == ERROR, n
        host.fmu.reset()


def test_zero_padding_is_accepted(host, serialized):
    # fmi2SerializeFMUstate into a larger buffer pads with zeros
    assert deserialize_status(host, serialized + bytes(16)) == OK


def test_foreign_buffers_are_refused(host, serialized):
    guid, version, payload = envelope(serialized)
    cases = {
        "another model": seal(b"{00000000-0000-0000-0000-000000000000}", version, payload),
        "format version": seal(guid, version + 1, payload),
        "trailing": seal(guid, version, payload + b"\0"),
        "truncated payload": seal(guid, version, payload[:-3]),
        "bad magic": b"XXXXXXXX" + serialized[8:],
        "random": bytes(range(256)) * 2,
    }
    for what, data in cases.items():
        assert deserialize_status(host, data) == ERROR, what
        host.fmu.reset()


def test_payload_fields_are_checked(host, serialized):
    guid, version, payload = envelope(serialized)
    # first byte: the state machine (0..5 valid, fatal refused, 7 and 8 the
    # Model Exchange states, refused by a co-simulation instance)
    for code in (6, 7, 200):
        bad = bytes([code]) + payload[1:]
        assert deserialize_status(host, seal(guid, version, bad)) == ERROR
        host.fmu.reset()
    # the model state must be there when one was saved (tag 1), intact
    assert deserialize_status(host, seal(guid, version, payload[:-1])) == ERROR


def test_serialize_into_a_small_buffer_is_refused(host):
    start(host)
    s = host.fmu.getFMUstate()
    size = c_size_t()
    host.fmu.fmi2SerializedFMUstateSize(host.fmu.component, s, byref(size))
    buf = create_string_buffer(size.value)
    assert host.raw("fmi2SerializeFMUstate", s, buf, c_size_t(size.value - 1)) == ERROR
    assert "too small" in host.errors()[-1]
