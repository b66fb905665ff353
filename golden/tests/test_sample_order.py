"""The sampling order and reach of golden/sample_order.py: every lane's points stay inside its
reach at every tested angle (float32.rotate: whole and tenth degrees, random angles, the
angles of random moments, the angles where the float rounding changes a point), and the order
is a permutation that keeps each bit's two ends on the same step."""

from __future__ import annotations

import numpy as np
import pytest
from fastnms.golden import float32, sample_order
from fastnms.golden.orb import MOMENT_MAX, PATTERN
from fastnms.testing.orb_angles import cos_sin_of_degrees, near_half_integer_angles

ALL_LANES = (1, 2, 4, 8, 16)


@pytest.mark.parametrize("lanes", ALL_LANES)
def test_order_is_a_permutation_with_both_ends_of_a_bit_on_one_step(lanes):
    order = sample_order.point_order(lanes)
    assert order.shape == (512 // lanes, lanes)
    assert sorted(order.ravel().tolist()) == list(range(512))
    if lanes > 1:
        assert (order[:, 1::2] == order[:, 0::2] + 1).all()
        assert (order[:, 0::2] % 2 == 0).all()


def test_lane_reach_at_lanes_8():
    assert sample_order.lane_reach(8).tolist() == [10, 10, 13, 13, 14, 14, 18, 18]


def test_reach_is_the_radius_rounded_up_past_a_half():
    rho = np.hypot(PATTERN[:, 0], PATTERN[:, 1])
    reach = sample_order.point_reach()
    assert (reach + 0.5 > rho).all()
    assert (reach - 0.5 <= rho).all()


def test_every_rotated_point_stays_inside_its_reach():
    rng = np.random.default_rng(20261128)
    deg = np.concatenate(
        [np.arange(0, 3600, dtype=np.float32) / np.float32(10), rng.random(20000) * 360]
    ).astype(np.float32)
    a, b = cos_sin_of_degrees(deg[deg < 360])
    m = rng.integers(-MOMENT_MAX, MOMENT_MAX + 1, size=(2, 5000))
    ma, mb = cos_sin_of_degrees(float32.fast_atan2(m[0], m[1]).view(np.float32))
    ha, hb = near_half_integer_angles(rng, 2)
    a, b = np.concatenate([a, ma, ha]), np.concatenate([b, mb, hb])
    reach = sample_order.point_reach()
    seen = np.zeros(512, dtype=np.int64)
    for s in range(0, len(a), 2000):
        x, y = float32.rotate(
            PATTERN[None, :, 0], PATTERN[None, :, 1], a[s : s + 2000, None], b[s : s + 2000, None]
        )
        seen = np.maximum(seen, np.maximum(np.abs(x), np.abs(y)).max(axis=0))
    assert (seen <= reach).all(), np.flatnonzero(seen > reach)
    # Not loose: every point comes within one pixel of its reach, most reach it.
    assert (seen >= reach - 1).all()
    assert (seen == reach).mean() > 0.9
    for lanes in ALL_LANES:
        lane = sample_order.lane_reach(lanes)
        assert (seen[sample_order.point_order(lanes)] <= lane).all()
