"""Non-associative limit analysis of block assemblies (rocking.corner_blocks.nonassoc,
docs/corner-nonassociative.md) against closed forms derived by hand statics, beside the
associative LP (lp.py): the non-associative multiplier never exceeds the associative one."""

import math

import numpy as np
import pytest

from rocking.corner_blocks import lp, nonassoc
from rocking.corner_blocks.assembly import Assembly, box, on_table

B, D, H = 0.1, 0.2, 0.3  # a block's x, y, z sizes (m)


def both(assembly, alpha=0.0, **options):
    """(non-associative result, lp.py's associative multiplier on the same 8-facet pyramid)."""
    r = nonassoc.solve(assembly, alpha, facets=8, **options)
    assert r.converged, r.status
    return r, lp.solve(assembly, alpha, facets=8).lam


def test_block_slides_before_it_rocks():
    """mu = 0.2 < b/h = 1/3: the block slides on the table at lambda = mu (horizontal
    force lambda W against friction mu W); sliding on a table lifts nothing but the block,
    so both flow rules agree."""
    r, lam_lp = both(on_table([box((0, 0, 0), (B, D, H))], mu=0.2))
    assert r.lam == pytest.approx(0.2, rel=1e-6)
    assert lam_lp == pytest.approx(0.2, rel=1e-6)
    assert r.lam <= lam_lp + 1e-9


def test_block_rocks_before_it_slides():
    """mu = 0.6 > b/h: the block overturns about its toe at lambda = b/h (moments about the
    toe: lambda W h/2 = W b/2), in x and in y."""
    for alpha, lever in ((0.0, B), (math.pi / 2, D)):
        r, lam_lp = both(on_table([box((0, 0, 0), (B, D, H))], mu=0.6 if lever == B else 0.9), alpha)
        assert r.lam == pytest.approx(lever / H, rel=1e-6)
        assert r.lam <= lam_lp + 1e-9
        assert r.opening_max_pressed <= 1e-9 * np.abs(r.velocity).max()


@pytest.mark.parametrize("mu, closed", [
    # overturning as one about the base's toe: (W1 + W2) b1/2 = lambda (W1 h1/2 + W2 (h1 + h2/2))
    (2.0, None),
    # both interfaces carry lambda times the weight above them against mu times it: slides at mu
    (0.5, 0.5),
])
def test_two_block_stack(mu, closed):
    """A wide base block (b1 x h1) and a stocky top block (b2 x h2) centred on it. With
    high friction the stack overturns as one, below the top block's own b2/h2 = 1.5; with
    mu = 0.5 below that, it slides at mu."""
    b1, h1, b2, h2 = 0.2, 0.1, 0.15, 0.1
    a = on_table([box((0, 0, 0), (b1, D, h1)), box(((b1 - b2) / 2, 0, h1), ((b1 + b2) / 2, D, h1 + h2))], mu=mu)
    if closed is None:
        w1, w2 = b1 * h1, b2 * h2
        closed = (w1 + w2) * b1 / 2 / (w1 * h1 / 2 + w2 * (h1 + h2 / 2))
        assert closed < mu and closed < b2 / h2
    r, lam_lp = both(a)
    assert r.lam == pytest.approx(closed, rel=1e-6)
    assert r.lam <= lam_lp + 1e-9


def block_against_a_wall(mu):
    """A block b x d x h on the table, its +x face against a fixed wall; the load (alpha = 0,
    along -x) pulls it away from the wall."""
    a = on_table([box((0, 0, 0), (B, D, H))], mu=mu)
    a.blocks.append(box((B, -0.5, -0.1), (B + 0.2, D + 0.5, H + 0.5)))
    a.fixed.append(True)
    a.roller.append(None)
    return a


def test_block_against_a_wall_where_the_flow_rules_differ():
    """Non-associative: nothing presses the block against the wall, so the wall carries
    nothing and the block rocks away from it about its toe at b/h, its heel sliding up the
    wall face without opening (mu > b/h, so the toe does not slide).

    Associative: the heel cannot slide up the wall without moving away from it by mu per
    unit slip, so the LP may press the heel against the wall with n (at z = 0, no moment
    about the toe) and hang friction mu n on it downwards (restoring). Moments about the
    toe: lambda W h/2 = W b/2 + mu n b; horizontally the table's friction carries
    lambda W + n <= mu (W + mu n). Both at their limits, with n' = n / W:
    n' = (mu - b/h) / (1 - mu^2 + 2 mu b/h), lambda = b/h (1 + 2 mu n'): 0.4359 at
    mu = 0.6, b/h = 1/3, 31 % above the frictional answer."""
    mu = 0.6
    bh = B / H
    n = (mu - bh) / (1 - mu ** 2 + 2 * mu * bh)
    lam_assoc = bh * (1 + 2 * mu * n)
    r, lam_lp = both(block_against_a_wall(mu))
    assert lam_lp == pytest.approx(lam_assoc, rel=1e-6)
    assert r.lam_associative == pytest.approx(lam_assoc, rel=1e-6)  # its own iteration 0 is the same LP
    assert r.lam == pytest.approx(bh, rel=1e-6)
    assert r.lam < lam_lp - 0.1
    assert r.iterations > 1 and r.history[0][0] == pytest.approx(lam_assoc, rel=1e-9)


def test_no_convergence_is_reported_not_returned():
    """The wall case needs about 25 relaxed iterations: stopped at 3 it raises, with the
    history; asked to, it returns the unconverged state flagged."""
    a = block_against_a_wall(0.6)
    with pytest.raises(nonassoc.NotConverged, match="not converged in 3 iterations") as info:
        nonassoc.solve(a, 0.0, max_iter=3)
    assert len(info.value.result.history) == 4 and not info.value.result.converged
    r = nonassoc.solve(a, 0.0, max_iter=3, raise_on_failure=False)
    assert not r.converged and "not converged" in r.status
    with pytest.raises(ValueError, match="relaxation"):
        nonassoc.solve(a, 0.0, relaxation=0.0)


def test_relaxation_changes_the_path_not_the_answer_here():
    """Full update (relaxation 1) reaches the wall case's b/h in fewer iterations."""
    a = block_against_a_wall(0.6)
    full = nonassoc.solve(a, 0.0, relaxation=1.0)
    half = nonassoc.solve(a, 0.0, relaxation=0.5)
    assert full.lam == pytest.approx(B / H, rel=1e-6) and half.lam == pytest.approx(B / H, rel=1e-6)
    assert full.iterations < half.iterations


def _support(s, facets):
    """max t . s over the unit pyramid section {t: cos(phi_k) t1 + sin(phi_k) t2 <= 1}: its
    vertices lie at radius 1/cos(pi/facets), half-way between the planes' normals."""
    angles = 2 * math.pi * (np.arange(facets) + 0.5) / facets
    vertices = np.stack([np.cos(angles), np.sin(angles)], axis=1) / math.cos(math.pi / facets)
    return float((vertices @ s).max())


@pytest.mark.parametrize("ends", ["free", "fixed"])
def test_small_corner_converges_below_the_lp_and_does_work_by_friction_alone(ends):
    """The 3-course, 3-block corner at pi/2 (docs/corner-nonassociative.md): converged, at or
    below the associative LP, and virtual work on its mechanism: the load's and the
    weights' power equal the friction's dissipation mu n |slip| (the pyramid's support
    function) at the corners, with no opening where a corner is pressed; the associative
    mechanism dissipates nothing."""
    from rocking.corner_blocks.assembly import Assembly, interfaces
    from rocking.corner_blocks.specimen import Specimen

    a = Assembly.from_specimen(Specimen(courses=3, blocks=3, ends=ends))
    r = nonassoc.solve(a, math.pi / 2, facets=8)
    assert r.converged, r.status
    assert r.lam <= lp.solve(a, math.pi / 2, facets=8).lam + 1e-9
    v = r.velocity
    weights = np.array([a.weight(i) for i in range(len(a.blocks))])
    power_dead = float(-(weights * v[:, 2]).sum())

    def dissipation(normal):
        out, k = 0.0, 0
        for f in interfaces(a):
            e = [ax for ax in range(3) if ax != f.axis]
            for p in f.corners:
                dv = (lp.point_velocity(v[f.j], a.blocks[f.j].centroid, p)
                      - lp.point_velocity(v[f.i], a.blocks[f.i].centroid, p))
                out += a.mu * normal[k] * _support(dv[e], 8)
                k += 1
        assert k == len(normal)
        return out

    assert dissipation(r.normal) > 0.01 * r.lam  # it slides somewhere
    assert r.lam + power_dead == pytest.approx(dissipation(r.normal), rel=1e-6)
    assert r.opening_max_pressed <= 1e-9 * np.abs(v).max()
    # the converged state is a collapse state, so complementarity.certify (an LP over all
    # force fields complementary to the mechanism) must find its lambda among its own; the
    # fields at both ends of that range obey the same virtual work
    from rocking.corner_blocks import complementarity

    p = nonassoc._Problem(a, math.pi / 2, 8)
    fields = []
    lo, hi = complementarity._certify(p, v, fields=fields)
    assert lo - 1e-6 <= r.lam <= hi + 1e-6
    for x, lam in zip(fields, (lo, hi)):
        assert x[p.lam_col] == lam
        assert lam + power_dead == pytest.approx(dissipation(x[p.n_cols]), abs=1e-6 * lam)


def test_committed_cases_lie_at_or_below_their_lp():
    """data/corner-blocks/nonassoc (`python -m rocking.corner_blocks.nonassoc`): every
    committed case that converged lies at or below its own associative iteration 0; one
    that did not says so and keeps its history (an unconverged iterate is no answer: the
    paper's corner at pi/2 went above its LP at iteration 1). Iteration 0 is the committed
    study's LP of the same case (data/corner-blocks/lp_*) where there is one."""
    import json
    from pathlib import Path

    folder = Path(__file__).resolve().parents[1] / "data" / "corner-blocks"
    cases = 0
    for path in sorted((folder / "nonassoc").glob("nonassoc_*.json")):
        r = json.loads(path.read_text())
        if r["converged"]:
            assert r["lam"] <= r["lam_associative"] + 1e-9, path.name
        else:
            assert r["status"].startswith("not converged in"), (path.name, r["status"])
            assert len(r["history"]) == r["iterations"] + 1
        lp_path = folder / path.name.replace("nonassoc_", "lp_")
        if lp_path.is_file():
            assert r["lam_associative"] == pytest.approx(json.loads(lp_path.read_text())["lam"], rel=1e-6)
        cases += 1
    assert cases >= 4


def test_a_clamp_of_zero_is_the_free_end():
    """The bounded roller (Specimen.clamp, in end-block weights) enters the non-associative
    LPs as it does the associative one: at 0 the 3-course corner converges to the free
    end's collapse state, and lies at or below its own associative LP."""
    from rocking.corner_blocks.specimen import Specimen

    def lam(**kw):
        r = nonassoc.solve(Assembly.from_specimen(Specimen(courses=3, blocks=3, **kw)), math.pi / 2, tol=1e-4)
        assert r.converged and r.lam <= r.lam_associative + 1e-9
        return r.lam

    assert lam(ends="outOfPlane", clamp=0.0) == pytest.approx(lam(ends="free"), rel=1e-4)


@pytest.mark.parametrize("relaxation", [0.5, 0.25])
def test_diagnose_follows_the_wall_case_by_hand(relaxation):
    """nonassoc.diagnose on the block against a wall (test above), by hand: iteration 1
    keeps the associative capacity mu n0 at the heel (n0 / W = (mu - b/h) / (1 - mu^2 +
    2 mu b/h)), so lambda_1 is the associative 0.4359, and the least-normal-force choice
    takes the wall's normal force to 0: the wall interface changes by n0. Relaxed, the
    heel's capacity is mu n0 (1 - r)^(k-1) at iteration k, and the moment about the toe,
    lambda W h/2 = W b/2 + mu n_hat b, gives lambda_k - b/h = (lambda_1 - b/h)(1 - r)^(k-1);
    at iteration 2 the wall interface changes by (1 - r) n0, more than the table's
    (mu r n0). Every iteration's mechanism is the rocking one, whose collapse states span
    b/h to lambda_1 (test_certify_gives_the_wall_cases_range_of_collapse_states)."""
    mu, bh = 0.6, B / H
    n0 = (mu - bh) / (1 - mu ** 2 + 2 * mu * bh)
    lam1 = bh * (1 + 2 * mu * n0)
    rows = nonassoc.diagnose(block_against_a_wall(mu), 0.0, relaxation=relaxation, iterations=6, tol=1e-9,
                             certify=True)
    assert [r["iteration"] for r in rows] == list(range(1, 7))
    for r in rows:
        assert r["lam"] == pytest.approx(bh + (lam1 - bh) * (1 - relaxation) ** (r["iteration"] - 1), rel=1e-6)
    assert rows[0]["interface"] == pytest.approx(n0, rel=1e-6)
    assert rows[1]["interface"] == pytest.approx((1 - relaxation) * n0, rel=1e-6)
    assert math.isnan(rows[0]["against_k_minus_2"])
    assert rows[1]["against_k_minus_2"] == pytest.approx(rows[0]["corner"], rel=1e-6)  # n_2 = 0 at the heel, as n_1
    for r in rows:
        assert r["certified"] == pytest.approx([bh, lam1], rel=1e-6)


def test_certify_gives_the_wall_cases_range_of_collapse_states():
    """complementarity.certify on the rocking mechanism of the block against a wall (the
    first fixed-capacity iteration's: about the toe, the heel sliding up the wall): with the
    heel pressed by any n from 0 to the associative n0, friction mu n hanging on it
    downwards, lambda = b/h (1 + 2 mu n / W) (test above); the table's friction allows
    n0 at most, so the collapse states with this mechanism span b/h to the associative
    0.4359. solve(certify=True) stops at iteration 1, whose lambda (0.4359) lies in its
    mechanism's range: a collapse state, the prestressed one, where the default iteration
    goes on to b/h, the least."""
    from rocking.corner_blocks import complementarity

    mu, bh = 0.6, B / H
    n0 = (mu - bh) / (1 - mu ** 2 + 2 * mu * bh)
    a = block_against_a_wall(mu)
    r = nonassoc.solve(a, 0.0, certify=True)
    assert r.converged and r.iterations == 1 and r.status.startswith("certified at iteration 1")
    assert r.lam == pytest.approx(bh * (1 + 2 * mu * n0), rel=1e-6)
    lo, hi = complementarity.certify(a, 0.0, r.velocity)
    assert lo == pytest.approx(bh, rel=1e-6) and hi == pytest.approx(bh * (1 + 2 * mu * n0), rel=1e-6)
    assert r.certified_range == pytest.approx((lo, hi), rel=1e-9)
    default = nonassoc.solve(a, 0.0)
    assert default.lam == pytest.approx(bh, rel=1e-6) and not default.certified


def test_certify_refuses_a_mechanism_that_penetrates_or_is_not_normalised():
    """A block on the table pushed into it (v_z < 0) is no mechanism: (nan, nan); sliding
    along the load (mu = 0.2 < b/h) is one at lambda = mu only; one whose load power is not
    1 is an error naming it."""
    from rocking.corner_blocks import complementarity

    a = on_table([box((0, 0, 0), (B, D, H))], mu=0.2)
    w = a.weight(a.free()[0])
    from rocking.corner_blocks.specimen import load_direction

    v = np.zeros((len(a.blocks), 6))
    i = a.free()[0]
    v[i, :3] = load_direction(0.0) / w
    v[i, 2] = -0.1 / w
    assert all(math.isnan(x) for x in complementarity.certify(a, 0.0, v))
    v[i, 2] = 0.0
    lo, hi = complementarity.certify(a, 0.0, v)  # sliding along the load: only lambda = mu
    assert lo == pytest.approx(0.2, rel=1e-9) and hi == pytest.approx(0.2, rel=1e-9)
    with pytest.raises(ValueError, match="load power"):
        complementarity.certify(a, 0.0, 2 * v)


@pytest.mark.parametrize("mu, closed", [(0.2, 0.2), (0.6, B / H)])
def test_least_by_milp_on_a_block_on_a_table(mu, closed):
    """complementarity.least (the MILP) on a block that slides (mu) or rocks (b/h) first:
    HiGHS proves the optimum, lower = upper = the closed form, within the big-M bounds."""
    from rocking.corner_blocks import complementarity

    r = complementarity.least(on_table([box((0, 0, 0), (B, D, H))], mu=mu), 0.0, time_limit=30)
    assert r.lower == pytest.approx(closed, rel=1e-6) and r.upper == pytest.approx(closed, rel=1e-6)
    assert not r.bound_active
