"""Two horizontal components as one ground motion (issue 36, item 3): the pair's time base,
its axes and the compass, exact rotation, the planar components, and RotDnn intensity
measures.

References independent of the code: the shipped files' own components (read one by one),
compass geometry written out here (the unit vector of bearing b is (sin b, cos b) in
(east, north)), closed forms (circular motion, a unidirectional motion, the median of
|cos| over a uniform angle being cos 45 degrees), and brute force (dense sweeps of the
rotated components, each one's peak or oscillator response computed directly).
"""

import math

import numpy as np
import pytest

from rocking import groundmotion as gm
from rocking.fragility import intensity, rotd
from rocking.groundmotion import HorizontalPair, Record, pair_of

G = 9.80665
DATA = gm.DATA_DIR

# file, expected (x label, y label, compass bearing of x): y 90 degrees counterclockwise of
# x seen from above, from the labels' bearings worked out by hand
SHIPPED = [
    ("csmip-coalinga-1983/ce36456p_CE36456.V2", "90", "0", 90.0),
    ("geonet-darfield-2010/3366146_DFHS_HN_20.000", "090", "000", 90.0),
    ("geonet-kaikoura-2016/20161113_110259_WTMC_20.V2A", "N28W", "S62W", 332.0),
    ("usgs-lomaprieta-1989/0111a.smc", "360", "270", 0.0),
]
KAIKOURA = DATA / SHIPPED[2][0]


def random_pair(n=600, dt=0.01, seed=1, **kw):
    rng = np.random.default_rng(seed)
    x = Record.from_samples(rng.normal(size=n), dt, component="x", **kw)
    y = Record.from_samples(rng.normal(size=n), dt, component="y", **kw)
    return HorizontalPair.from_records(x, y)


def compass_pair(bx, by, east, north, dt=0.01):
    """The pair recorded by instruments along bearings bx, by of a motion given by its east
    and north accelerations: each component is the projection on (sin b, cos b)."""
    def comp(b):
        r = math.radians(b)
        return east * math.sin(r) + north * math.cos(r)
    return HorizontalPair.from_records(Record.from_samples(comp(bx), dt, component=f"{bx:g}"),
                                       Record.from_samples(comp(by), dt, component=f"{by:g}"))


# ---------------------------------------------------------------------------
# The pair: which component is x, the time base, what is refused

@pytest.mark.parametrize("rel,xl,yl,bx", SHIPPED)
def test_shipped_pair_axes_and_time_base(rel, xl, yl, bx):
    pair = pair_of(DATA / rel)
    own = {r.component: r for r in gm.components(DATA / rel)}
    assert (pair.x.component, pair.y.component, pair.bearing_x) == (xl, yl, bx)
    n = max(r.npts for r in own.values())
    assert pair.npts == n and pair.vertical is not None and pair.vertical.npts == n
    for rec in (pair.x, pair.y, pair.vertical):
        src = own[rec.component]
        assert rec.dt == src.dt
        np.testing.assert_array_equal(rec.time, np.arange(n) * src.dt)
        np.testing.assert_array_equal(rec.acc[:src.npts], src.acc)   # samples kept, zeros after
        assert not np.any(rec.acc[src.npts:])
        assert (f"[{rec.component}] padded with {n - src.npts} zero" in pair.notes) == (src.npts < n)


def test_a_record_gives_the_pair_of_its_set():
    rec = gm.read(KAIKOURA, component="S62W")
    pair = pair_of(rec)
    np.testing.assert_array_equal(pair.y.acc, rec.acc)


def test_different_steps_are_resampled_to_the_smallest_with_a_note():
    t_fine, t_coarse = np.arange(101) * 0.01, np.arange(41) * 0.025
    fine = Record.from_samples(np.sin(3 * t_fine), 0.01, component="a")
    coarse = Record.from_samples(2 * t_coarse, 0.025, component="b")     # linear: interpolation is exact
    pair = HorizontalPair.from_records(fine, coarse)
    assert pair.dt == 0.01 and pair.npts == 101
    np.testing.assert_allclose(pair.y.acc, 2 * t_fine, rtol=0, atol=1e-14)
    assert "[b] resampled from dt = 0.025 s to 0.01 s" in pair.notes
    assert "whether y is counterclockwise of x is not known" in pair.notes   # labels a, b: no bearing


def test_what_a_pair_refuses():
    a = Record.from_samples(np.ones(10), 0.01, component="N10E")
    b = Record.from_samples(np.ones(10), 0.01, component="N85W")          # 95 degrees apart
    with pytest.raises(ValueError, match="bearings 10 and 275 degrees are not perpendicular"):
        HorizontalPair.from_records(a, b)
    assert HorizontalPair.from_records(a, b, bearings=None).x is not None  # as given, on request
    up = Record.from_samples(np.ones(10), 0.01, component="UP", orientation=gm.VERTICAL)
    with pytest.raises(ValueError, match="HorizontalPair.y .* is a vertical component"):
        HorizontalPair.from_records(a, up, bearings=None)
    late = Record(time=np.arange(10) * 0.01 + 1.0, acc=np.ones(10), dt=0.01, component="E")
    with pytest.raises(ValueError, match="time starts at 1 s"):
        HorizontalPair.from_records(a, late, bearings=None)
    with pytest.raises(ValueError, match="not on x's time base"):
        HorizontalPair(a, Record.from_samples(np.ones(11), 0.01, component="E"))
    with pytest.raises(ValueError, match="holds 1 horizontal component"):
        pair_of(gm.STANDIN_PATH)


@pytest.mark.parametrize("label,expected", [
    ("360", 0.0), ("000", 0.0), ("90", 90.0), ("270", 270.0), ("N28W", 332.0), ("S62W", 242.0),
    ("N10E", 10.0), ("S10E", 170.0), ("NS", 0.0), ("ew", 90.0), ("HNE", 90.0), ("HNN", 0.0),
    ("HN1", None), ("UP", None), ("", None), ("N95E", None), ("400", None)])
def test_bearing_of_a_label(label, expected):
    assert gm.bearing(label) == expected


# ---------------------------------------------------------------------------
# Rotation: exact, and the compass

@pytest.mark.parametrize("a,b", [(30.0, 45.0), (-17.3, 200.1), (123.456, 0.0), (89.0, 1.0), (330.0, 60.0)])
def test_rotation_by_a_then_b_is_rotation_by_a_plus_b(a, b):
    pair = random_pair()
    two, one = pair.rotated(a).rotated(b), pair.rotated(a + b)
    scale = np.max(np.abs(pair.x.acc)) + np.max(np.abs(pair.y.acc))
    assert np.max(np.abs(two.x.acc - one.x.acc)) <= 4e-16 * scale * 4
    assert np.max(np.abs(two.y.acc - one.y.acc)) <= 4e-16 * scale * 4


def test_rotation_by_90_degrees_swaps_with_a_sign():
    pair = random_pair()
    q = pair.rotated(90.0)
    np.testing.assert_array_equal(q.x.acc, pair.y.acc)
    np.testing.assert_array_equal(q.y.acc, -pair.x.acc)
    np.testing.assert_array_equal(pair.rotated(-270.0).x.acc, pair.y.acc)
    np.testing.assert_array_equal(pair.rotated(180.0).y.acc, -pair.y.acc)


@pytest.mark.parametrize("a", [0.1, 37.0, 145.5, 271.0])
def test_rotation_keeps_the_norm_of_each_sample(a):
    pair = random_pair()
    q = pair.rotated(a)
    norm, qnorm = np.hypot(pair.x.acc, pair.y.acc), np.hypot(q.x.acc, q.y.acc)
    assert np.max(np.abs(qnorm - norm) / norm) < 1e-15 * 4


def test_azimuth_and_compass_against_projections():
    """A motion due north (sin t) recorded along N28W and S62W, as the Kaikoura set: the
    component along the azimuth of bearing 0 is the whole motion, across it nothing, and the
    labels of the rotated pair are the new bearings."""
    t = np.arange(500) * 0.01
    pair = compass_pair(332.0, 242.0, east=0 * t, north=np.sin(t))
    assert pair.azimuth_of_bearing(0.0) == 332.0
    turned = pair.rotated(pair.azimuth_of_bearing(0.0))
    np.testing.assert_allclose(turned.x.acc, np.sin(t), rtol=0, atol=1e-15)
    np.testing.assert_allclose(turned.y.acc, 0.0, rtol=0, atol=1e-15)
    assert (turned.x.component, turned.y.component, turned.bearing_x) == ("000", "270", 0.0)
    # due east (cos t), the same instruments: bearing 90 is azimuth 242 from x
    pair = compass_pair(332.0, 242.0, east=np.cos(t), north=0 * t)
    rec = pair.along(pair.azimuth_of_bearing(90.0))
    np.testing.assert_allclose(rec.acc, np.cos(t), rtol=0, atol=1e-15)
    assert gm.bearing(rec.component) == 90.0


def test_the_frame_is_right_handed_whatever_the_file_order():
    """N then E (Darfield's order) or E then N: x = E, y = N either way, and a motion along
    bearing 45 (north-east) is along azimuth 45 from x (counterclockwise from east)."""
    t = np.arange(300) * 0.01
    ne = np.sin(2 * t)                       # along bearing 45
    east, north = ne * math.sin(math.radians(45)), ne * math.cos(math.radians(45))
    for order in [(0.0, 90.0), (90.0, 0.0)]:
        pair = compass_pair(*order, east=east, north=north)
        assert (pair.bearing_x, gm.bearing(pair.y.component)) == (90.0, 0.0)
        np.testing.assert_allclose(pair.along(45.0).acc, ne, rtol=0, atol=1e-15)


def test_planar_records_and_the_peak_azimuth():
    pair = pair_of(KAIKOURA)
    (lx, rx), (ly, ry), (la, ra) = pair.planar_records(with_vertical=True)
    np.testing.assert_array_equal(rx.acc, pair.x.acc)
    np.testing.assert_array_equal(ry.acc, pair.y.acc)
    assert rx.av_record is pair.vertical and ra.av_record is pair.vertical
    assert (lx, ly) == ("x [N28W]", "y [S62W]") and la.startswith("azimuth ")
    sweep = [pair.along(a).pga for a in np.arange(0, 180, 0.05)]
    assert ra.pga == pytest.approx(pair.pga, rel=1e-14)            # the peak azimuth gives the peak
    assert max(sweep) <= ra.pga * (1 + 1e-14)
    assert max(sweep) >= ra.pga * math.cos(math.radians(0.025))
    assert pair.along(30.0).av_record is None


# ---------------------------------------------------------------------------
# RotDnn: closed forms

def test_circular_motion_rotd_is_the_amplitude():
    """x = A cos wt, y = A sin wt, sampled at every whole degree of phase: every azimuth's
    peak is A."""
    amp, dt = 2.5, 1.0 / 360.0
    phase = 2 * np.pi * np.arange(721) * dt
    pair = HorizontalPair.from_records(Record.from_samples(amp * np.cos(phase), dt, component="a"),
                                       Record.from_samples(amp * np.sin(phase), dt, component="b"))
    for pct in (0, 50, 100):
        assert rotd.rotd_pga(pair, pct) == pytest.approx(amp, rel=1e-14)
    assert intensity.parse("RotD50").of(pair) == pytest.approx(amp / G, rel=1e-14)


def test_unidirectional_motion_at_30_degrees():
    """f(t) along azimuth 30: the component along a is f cos(a - 30), so RotD100 is max|f| and
    RotD50 is max|f| times the median of |cos| over a uniform angle, cos 45 degrees."""
    f = np.random.default_rng(7).normal(size=800)
    c, s = math.cos(math.radians(30)), math.sin(math.radians(30))
    pair = HorizontalPair.from_records(Record.from_samples(f * c, 0.01, component="a"),
                                       Record.from_samples(f * s, 0.01, component="b"))
    pga = np.max(np.abs(f))
    assert rotd.rotd_pga(pair, 100) == pytest.approx(pga, rel=1e-15 * 4)
    assert rotd.rotd_pga(pair, 50) == pytest.approx(pga / math.sqrt(2), rel=1e-14)
    assert rotd.rotd_pga(pair, 0) == pytest.approx(0.0, abs=1e-14 * pga)      # across it: nothing
    assert pair.peak_azimuth() == pytest.approx(30.0, abs=1e-12)


# ---------------------------------------------------------------------------
# RotDnn: brute force on a real pair, invariants, the intensity measure

def test_rotd_pga_against_a_sweep_of_rotated_components():
    pair = pair_of(KAIKOURA)
    peaks = np.array([pair.rotated(a).x.pga for a in range(180)])
    assert rotd.rotd_pga(pair, 50) == pytest.approx(np.median(peaks), rel=1e-14)
    assert rotd.rotd_pga(pair, 0) == pytest.approx(peaks.min(), rel=1e-14)
    dense = max(pair.rotated(a).x.pga for a in np.arange(0, 180, 0.02))
    assert dense <= rotd.rotd_pga(pair, 100) <= dense / math.cos(math.radians(0.01))
    assert rotd.rotd_pga(pair, 100) >= max(pair.x.pga, pair.y.pga)


@pytest.mark.parametrize("period", [0.2, 1.0])
def test_rotd_sa_against_the_oscillator_under_each_rotated_component(period):
    pair = pair_of(KAIKOURA)
    sweep = np.array([intensity.spectral_acceleration(pair.rotated(a).x.acc, pair.dt, period)
                      for a in np.arange(0, 180, 0.5)])
    sa = sweep[::2]                                  # the whole degrees
    assert rotd.rotd_sa(pair, period, 50) == pytest.approx(np.median(sa), rel=1e-10)
    top, dense = rotd.rotd_sa(pair, period, 100), sweep.max()
    assert dense * (1 - 1e-10) <= top <= dense / math.cos(math.radians(0.25)) * (1 + 1e-10)
    # one azimuth of RotD: the SA of that component
    assert rotd.rotd_sa(pair, period, 50, step_deg=180.0) == pytest.approx(sa[0], rel=1e-10)


def test_rotd_does_not_depend_on_the_pair_s_axes():
    pair = pair_of(KAIKOURA)
    turned = pair.rotated(37.0)     # a whole number of the 1-degree azimuths: the same set
    for pct in (50, 100):
        assert rotd.rotd_pga(turned, pct) == pytest.approx(rotd.rotd_pga(pair, pct), rel=1e-13)
        assert rotd.rotd_sa(turned, 1.0, pct) == pytest.approx(rotd.rotd_sa(pair, 1.0, pct), rel=1e-10)
    assert rotd.rotd_pga(pair.rotated(12.345), 100) == pytest.approx(rotd.rotd_pga(pair, 100), rel=1e-14)


def test_rotd_intensity_measure_of_a_suite_component():
    im = intensity.parse("RotD50(SA(1.0))")
    assert (im.name, im.unit) == ("RotD50(SA(1))", "g")
    pair = pair_of(KAIKOURA)
    by_pair = im.of(pair)
    assert by_pair == pytest.approx(rotd.rotd_sa(pair, 1.0, 50) / G, rel=1e-15)
    for comp in ("N28W", "S62W"):                  # each component of the set: the set's value
        assert im.of(gm.read(KAIKOURA, component=comp)) == by_pair
    assert im.of(pair.scaled(2.0)) == pytest.approx(2 * by_pair, rel=1e-13)   # proportional
    with pytest.raises(ValueError, match=r"\[N28W\]: RotD needs the record as read"):
        im.of(gm.read(KAIKOURA, component="N28W").scaled(2.0))
    with pytest.raises(ValueError, match="KATNP_NS_standin.csv: its record set holds 1 horizontal"):
        im.of(gm.katnp())
    assert intensity.parse("rotd100").name == "RotD100(PGA)"
    for bad in ("RotD150", "RotD50(PGV)", "RotD50(AvgSA(0.5-2))"):
        with pytest.raises(ValueError, match="RotDnn"):
            intensity.parse(bad)
