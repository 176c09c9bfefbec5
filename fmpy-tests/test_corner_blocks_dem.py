"""The DEM tilting test in LMGC90 (rocking.corner_blocks.dem) on cases with closed forms,
within 2 % (docs/corner-blocks.md). Each run is a fresh process of about 5 s."""

import math

import pytest

from rocking.corner_blocks import dem
from rocking.corner_blocks.specimen import Specimen

pytest.importorskip("compas_lmgc90")

STEP = 0.0025  # the load step: lambda_c is the first level that fails, so it lies within STEP above


def _boxes(blocks):
    return [[list(b[0]), list(b[1])] for b in blocks]


def _lam(boxes, mu, alpha, start):
    r = dem.run_isolated({"boxes": boxes, "mu": mu}, alpha, dem.Protocol(start=start, step=STEP), timeout=300)
    assert r["collapsed"], r["history"]
    assert r["history"][0][1], "the first level must stand: start lower"
    return r["lam"]


def test_single_block_rocks_at_b_over_h():
    assert _lam(_boxes([((0, 0, 0), (0.1, 0.2, 0.3))]), 0.66, 0.0, 0.32) == pytest.approx(1 / 3, rel=0.02)


def test_single_block_slides_at_mu():
    assert _lam(_boxes([((0, 0, 0), (0.1, 0.2, 0.3))]), 0.2, 0.0, 0.19) == pytest.approx(0.2, rel=0.02)


def test_two_block_stack():
    """As test_corner_blocks.test_two_block_stack: the stack overturns as one."""
    b1, h1, b2, h2 = 0.2, 0.1, 0.15, 0.1
    boxes = _boxes([((0, 0, 0), (b1, 0.2, h1)), (((b1 - b2) / 2, 0, h1), ((b1 + b2) / 2, 0.2, h1 + h2))])
    w1, w2 = b1 * h1, b2 * h2
    closed = (w1 + w2) * b1 / 2 / (w1 * h1 / 2 + w2 * (h1 + h2 / 2))
    assert _lam(boxes, 2.0, 0.0, round(closed - 0.03, 3)) == pytest.approx(closed, rel=0.02)


def test_dry_stack_wall_overturns_at_t_over_h():
    """Two courses of running bond (the paper's blocks), out of plane: t/H."""
    from test_corner_blocks import running_bond_wall

    s = Specimen()
    wall = running_bond_wall(s.t, s.l, s.h, 2, 3)
    exact = s.t / (2 * s.h)
    lam = _lam(_boxes([(b.lo, b.hi) for b in wall]), 0.66, math.pi / 2, round(exact - 0.02, 3))
    assert lam == pytest.approx(exact, rel=0.02)
