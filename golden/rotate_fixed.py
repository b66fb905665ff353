"""The rotated pattern points in fixed point: the bit-true model of fastnms_orb_rotate,
equal to float32.rotate (cvRound of ORB's float32 rotation) for every cos/sin pair of the
domain (golden/tests/test_rotate_fixed.py compares them).

ORB's point is `cvRound(fl(fl(px*a) - fl(py*b)))` (and `fl(fl(px*b) + fl(py*a))` for y), with
px, py in -13..12 and a, b the float32 cos and sin (float32.py, *rotate*). The hardware needs
it for 512 points per keypoint, several per clock, so it must not spend a float adder per
point. It does this instead:

1. **Table of products, once per keypoint.** The float products `fl(k*c)`, c in {a, b},
   k in -13..12, as fixed-point words with FRACTION_BITS fraction bits: the 24-bit
   significand times |k| (28 bits), rounded to 24 significant bits (nearest even), shifted to
   the word's scale. A product of at least 2**-3 is exact on that grid (its ulp is at least
   2**-26). A smaller one is truncated (floor, two's complement) and a sticky bit says that
   bits were dropped. Each entry carries + 1/4, so that two entries add up to `x + 1/2`.
   Tables: PA[k] = fl(k*a) + 1/4, PB[k] = fl(k*b) + 1/4, NB[k] = -fl(k*b) + 1/4.
2. **Per point, one add per coordinate.** T = PA[px] + NB[py] = x + 1/2 (y: PB[px] +
   PA[py]), the sticky bits ORed. n = floor(T) and g = T - n (FRACTION_BITS bits).
3. **The float rounding, only where it matters.** cvRound(fl(x)) differs from cvRound(x)
   only when x lies within half a float ulp of a half-integer h: then fl(x) = h (h is a
   float, its last significand bit is 0, so a tie goes to h) and cvRound gives the even
   neighbour of h. With delta = 2**(e - 24), e the exponent of |h| (h is never a power of
   two other than +-1/2, so x and h share their binade):
   - near below the integer (h = n - 1/2): g <= delta;
   - near above (h = n + 1/2): g >= 1 - delta;
   the result is n, minus one if near below and n is odd, plus one if near above and n is
   odd. Elsewhere it is n = floor(x + 1/2).

Why truncating small products is exact: if both products are below 2**-3 in magnitude, |x| <
1/4 and the result is 0 whatever the low bits are (T stays in [0, 1)). If one is at least
2**-3, it is exact on the grid, the sum's dropped bits are those of the small product only,
the truncated T is floor(T) on the grid and the sticky bit tells g <= delta from g < delta
at equality; g >= 1 - delta is decided by the truncated value alone (1 - delta is on the
grid). The smallest delta, 2**-25 (|h| = 1/2), is 2 units of the grid.

Word widths: FRACTION_BITS = 26; |T| <= 26.5, so a signed word of 1 + 5 + 26 = 32 bits
plus the sticky bit. The product: 24 x 4 bits, 28-bit result, the scale shift right by
0..27 bits with sticky (c's exponent is -27..0: |c| >= 1.19e-8 or c = 0) or left by 3.
"""

from __future__ import annotations

import numpy as np

from .orb import PATTERN

FRACTION_BITS = 26
WORD_BITS = 32  # signed two's complement, |T| < 32
K_MIN, K_MAX = -13, 12  # the pattern's coordinates
QUARTER = 1 << (FRACTION_BITS - 2)
ONE = 1 << FRACTION_BITS


def product_entries(c_bits: np.ndarray, k: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """fl(k * c) as (floor(v * 2**26), sticky) int64 arrays; c float32 bits (|c| <= 1,
    0 or normal), k integers in -13..12. Broadcasts c against k."""
    c = np.asarray(c_bits, dtype=np.int64)
    k = np.asarray(k, dtype=np.int64)
    sign = (c >> 31) ^ (k < 0)
    e_field = (c >> 23) & 0xFF
    mant = np.where(e_field > 0, (c & 0x7FFFFF) | 0x800000, 0)
    p = np.abs(k) * mant  # < 2**28
    # Round to 24 significant bits: drop 0..4 bits (p < 2**24 is exact).
    drop = np.zeros_like(p)
    for bit in (24, 25, 26, 27):
        drop = np.where(p >= (1 << bit), bit - 23, drop)
    half = np.where(drop > 0, np.int64(1) << np.maximum(drop - 1, 0), 0)
    low = p & ((np.int64(1) << drop) - 1)
    kept = p >> drop
    up = (low > half) | ((low == half) & (drop > 0) & ((kept & 1) == 1))
    rounded = (kept + up) << drop  # <= 2**28
    # value = rounded * 2**(e - 127 - 23); on the grid: rounded * 2**(e - 150 + 26).
    shift = e_field - 150 + FRACTION_BITS  # -24 - ... : right shifts of up to 27
    right = np.maximum(-shift, 0)
    mag = np.where(shift >= 0, rounded << np.maximum(shift, 0), rounded >> right)
    sticky = (shift < 0) & ((rounded & ((np.int64(1) << right) - 1)) != 0)
    # Negative: floor(-m) = -(m_trunc + sticky).
    value = np.where(sign == 1, -(mag + sticky), mag)
    return np.where(mant == 0, 0, value), np.where(mant == 0, False, sticky)


def tables(a_bits: object, b_bits: object) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """PA, PB, NB of each keypoint: (value, sticky), each (N, 26) indexed by k - K_MIN."""
    k = np.arange(K_MIN, K_MAX + 1, dtype=np.int64)
    a = np.asarray(a_bits, dtype=np.int64).reshape(-1, 1)
    b = np.asarray(b_bits, dtype=np.int64).reshape(-1, 1)
    va, sa = product_entries(a, k)
    vb, sb = product_entries(b, k)
    # -floor(v) = floor(-v) + sticky: NB is floor(-v) with the same sticky bit.
    return {
        "PA": (va + QUARTER, sa),
        "PB": (vb + QUARTER, sb),
        "NB": (-vb - sb + QUARTER, sb),
    }


def _exponent_of_half(n2: np.ndarray) -> np.ndarray:
    """e = floor(log2 |h|) for h = n2 / 2, n2 odd (|h| >= 1/2): bit length of |n2| - 2."""
    m = np.abs(n2)
    e = np.full(m.shape, -1, dtype=np.int64)
    for bit in range(1, 7):
        e = np.where(m >= (1 << bit), bit - 1, e)
    return e


def round_point(t: np.ndarray, sticky: np.ndarray) -> np.ndarray:
    """cvRound(fl(x)) from t = floor((x + 1/2) * 2**26) and sticky (x's bits below)."""
    n = t >> FRACTION_BITS
    g = t & (ONE - 1)
    odd = (n & 1) == 1
    # near below: h = n - 1/2, delta = 2**(e - 24) = 2**p grid units, p = e - 24 + 26.
    p_low = _exponent_of_half(2 * n - 1) + FRACTION_BITS - 24
    d_low = np.int64(1) << p_low
    near_low = (g < d_low) | ((g == d_low) & ~sticky)
    p_high = _exponent_of_half(2 * n + 1) + FRACTION_BITS - 24
    near_high = g >= ONE - (np.int64(1) << p_high)
    return n - (near_low & odd) + (near_high & odd)


def rotate(a_bits: object, b_bits: object) -> tuple[np.ndarray, np.ndarray]:
    """(dx, dy) int64 (N, 512): ORB's rotated pattern points for N cos/sin pairs (float32
    bits), point 2i and 2i + 1 the two ends of descriptor bit i, as fastnms_orb_rotate
    computes them."""
    t = tables(a_bits, b_bits)
    ix = PATTERN[:, 0] - K_MIN
    iy = PATTERN[:, 1] - K_MIN
    pa, pa_s = t["PA"]
    pb, pb_s = t["PB"]
    nb, nb_s = t["NB"]
    x = round_point(pa[:, ix] + nb[:, iy], pa_s[:, ix] | nb_s[:, iy])
    y = round_point(pb[:, ix] + pa[:, iy], pb_s[:, ix] | pa_s[:, iy])
    return x, y
