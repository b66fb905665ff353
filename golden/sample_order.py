"""The order in which the RTL rotates and samples ORB's 256 point pairs, and the square each
lane can reach: the method model of fastnms_orb_rotate's output order and of
fastnms_orb_sample's patch copies (docs/orb_rtl.md, *The comparisons*). The descriptor does
not depend on it: bit i is pair i's comparison whatever the order it is computed in.

The sampler reads LANES points per clock at data-dependent places, so each lane has its own
copy of the keypoint's blurred patch, cut to the square its points can reach at any angle:

- **Reach.** A point (px, py) rotated by any angle stays within rho = hypot(px, py), so
  |cvRound(x)| and |cvRound(y)| are at most its reach: the smallest R with
  (2R + 1)**2 > 4 rho**2, that is R + 1/2 > rho. The float32 steps stretch the rotated
  value by at most a factor 1 + 2**-21 (two rounded products and a rounded sum, each 1 +
  2**-24, with cos**2 + sin**2 <= (1 + 2**-24)**2 for correctly rounded cos and sin): at most
  18.4 * 2**-21 < 10**-5 here. And R + 1/2 never lies that close above rho: rho**2 is an
  integer and (R + 1/2)**2 = R**2 + R + 1/4 is not, so (R + 1/2) - rho >= 1/4 / (rho +
  R + 1/2) >= 1/148. So |x| < R + 1/2 and |cvRound(x)| <= R, for every angle.
- **Order.** The pairs sorted by their reach (the larger of their two points'), a stable
  sort; pair-lane j (rotate lanes 2j and 2j + 1, the two ends of a bit) takes the j-th block
  of STEPS = 512 / LANES of them, one per step. The near pairs share lanes, whose copies
  are then small: at LANES 8 the four pair-lanes reach 10, 13, 14 and 18 pixels.
- LANES = 1 keeps the pattern's own order (one point per step, no pair-lanes).
"""

from __future__ import annotations

import numpy as np

from .orb import PATTERN

POINTS = len(PATTERN)  # 512
PAIRS = POINTS // 2


def point_reach() -> np.ndarray:
    """int64 (512,): each point's reach, the smallest R with (2R + 1)**2 > 4 (px**2 + py**2)."""
    rho2 = PATTERN[:, 0] ** 2 + PATTERN[:, 1] ** 2
    reach = np.zeros(POINTS, dtype=np.int64)
    while True:
        short = (2 * reach + 1) ** 2 <= 4 * rho2
        if not short.any():
            return reach
        reach[short] += 1


def pair_reach() -> np.ndarray:
    """int64 (256,): the larger reach of each pair's two points."""
    r = point_reach()
    return np.maximum(r[0::2], r[1::2])


def pairs_by_reach() -> np.ndarray:
    """int64 (256,): the pair indices sorted by reach, ties in pattern order."""
    return np.argsort(pair_reach(), kind="stable")


def steps(lanes: int) -> int:
    if lanes not in (1, 2, 4, 8, 16):
        raise ValueError(f"LANES must be 1, 2, 4, 8 or 16, not {lanes}")
    return POINTS // lanes


def point_order(lanes: int) -> np.ndarray:
    """int64 (STEPS, LANES): the pattern point in each lane at each step."""
    n = steps(lanes)
    if lanes == 1:
        return np.arange(POINTS).reshape(n, 1)
    # pair-lane j, step s: pair pairs_by_reach[j * n + s]; its two ends in lanes 2j, 2j + 1.
    pairs = pairs_by_reach().reshape(lanes // 2, n).T
    return np.stack([2 * pairs, 2 * pairs + 1], axis=2).reshape(n, lanes)


def lane_reach(lanes: int) -> np.ndarray:
    """int64 (LANES,): the largest reach among each lane's points (lanes 2j, 2j + 1 equal)."""
    return point_reach()[point_order(lanes)].max(axis=0)
