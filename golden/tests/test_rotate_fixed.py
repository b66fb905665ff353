"""The fixed-point rotation (golden/rotate_fixed.py, the model of fastnms_orb_rotate)
against float32.rotate, ORB's float32 steps, on every pattern point of many angles: whole
and tenth degrees, random angles, the angles of random moments, and the rare angles where
the float rounding of the rotated point changes its cvRound (found by a float64 criterion
that does not use either model)."""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import pytest
from fastnms.golden import float32, rotate_fixed
from fastnms.golden.orb import MOMENT_MAX, PATTERN
from fastnms.testing.orb_angles import cos_sin_of_degrees, near_half_integer_angles


def assert_equal_to_float32(a: np.ndarray, b: np.ndarray) -> None:
    x, y = rotate_fixed.rotate(a, b)
    gx, gy = float32.rotate(PATTERN[None, :, 0], PATTERN[None, :, 1], a[:, None], b[:, None])
    bad = np.argwhere((x != gx) | (y != gy))
    if len(bad):
        k, p = bad[0]
        pytest.fail(
            f"{len(bad)} points differ; first: cos {a[k]:08x} sin {b[k]:08x} point {p} "
            f"{tuple(PATTERN[p])}: ({x[k, p]}, {y[k, p]}), float32.rotate ({gx[k, p]}, {gy[k, p]})"
        )


def test_whole_and_tenth_degrees():
    assert_equal_to_float32(*cos_sin_of_degrees(np.arange(3600, dtype=np.float32) / 10))


def test_random_degrees():
    rng = np.random.default_rng(7)
    deg = (rng.random(5000) * 360).astype(np.float32)
    assert_equal_to_float32(*cos_sin_of_degrees(deg[deg < 360]))


def test_angles_of_moments():
    rng = np.random.default_rng(8)
    big = rng.integers(-MOMENT_MAX, MOMENT_MAX + 1, size=(2, 4000))
    small = rng.integers(-40, 41, size=(2, 2000))
    m = np.concatenate([big, small, [[0, 0, 1, -1, 0], [1, -1, 0, 0, 0]]], axis=1)
    deg = float32.fast_atan2(m[0], m[1]).view(np.float32)
    assert_equal_to_float32(*cos_sin_of_degrees(deg))


def test_angles_where_the_float_rounding_matters():
    """About one angle in 5000 has a point whose float32 rotation lands on a half-integer
    (or within half an ulp of one) so that cvRound differs from rounding the exact value;
    the correction of the fixed-point model is exercised only there."""
    a, b = near_half_integer_angles(np.random.default_rng(9), 8)
    px, py = PATTERN[None, :, 0], PATTERN[None, :, 1]
    gx, gy = float32.rotate(px, py, a[:, None], b[:, None])
    fa = a.astype(np.uint32).view(np.float32).astype(np.float64)[:, None]
    fb = b.astype(np.uint32).view(np.float32).astype(np.float64)[:, None]
    changed = (gx != np.rint(px * fa - py * fb)) | (gy != np.rint(px * fb + py * fa))
    assert changed.any(axis=1).sum() >= 20, "too few angles where the float rounding matters"
    assert_equal_to_float32(a, b)


def test_product_entries_are_the_float_products_on_the_grid():
    """Each table entry is floor(fl(k*c) * 2**26) with a sticky bit for the dropped bits,
    checked in exact rational arithmetic against float32.mul."""
    rng = np.random.default_rng(10)
    exps = rng.integers(100, 127, size=3000)  # |c| from 2**-27 to below 1
    c = (rng.integers(0, 2, size=3000) << 31) | (exps << 23) | rng.integers(0, 1 << 23, 3000)
    c = np.concatenate([c, [0, 0x3F800000, 0xBF800000, 0x3F000000, 0x32000000, 0x3E000000]])
    k = np.arange(rotate_fixed.K_MIN, rotate_fixed.K_MAX + 1)
    value, sticky = rotate_fixed.product_entries(c[:, None], k[None, :])
    exact = float32.mul(float32.from_int(k)[None, :], c[:, None])
    for i in range(len(c)):
        for j in range(len(k)):
            f = Fraction(float(np.uint32(exact[i, j]).view(np.float32))) * 2**26
            floor = f.numerator // f.denominator
            assert (value[i, j], sticky[i, j]) == (floor, floor != f), (hex(c[i]), k[j])


def test_pairs_off_the_circle_at_half_integers():
    """The method holds for any a, b of the domain (|c| <= 1, c = 0 or |c| >= 2**-27), not
    only cos/sin pairs. With a a multiple of 1/8, px*a lands on half-integers, and b tiny
    puts the rotated point just beside one: the cases where the sticky bit of a truncated
    product decides the rounding."""
    halves = [s * v for s in (1, -1) for v in (0.5, 0.25, 0.75, 1.0, 0.125, 0.375)]
    tiny = {
        s * (2.0**-j + t * 2.0**-m) / p
        for s in (1, -1)
        for j in range(21, 27)
        for m in range(j + 1, j + 24, 3)
        for t in (-1, 0, 1)
        for p in (1, 2, 4, 8)
    }
    tiny = [v for v in tiny if abs(v) >= 2.0**-27]
    bits = np.array([np.float32(v).view(np.uint32) for v in halves + tiny], dtype=np.int64)
    assert all(float(np.uint32(b).view(np.float32)) in halves + tiny for b in bits)
    h, t = bits[: len(halves)], bits[len(halves) :]
    a = np.concatenate([np.repeat(h, len(t)), np.tile(t, len(h))])
    b = np.concatenate([np.tile(t, len(h)), np.repeat(h, len(t))])
    assert_equal_to_float32(a, b)
