"""Keypoint orientations for the tests of the rotated pattern (golden/rotate_fixed.py and
fastnms_orb_rotate): cos and sin as ORB computes them, and the rare angles where the float32
rounding of a rotated point changes its cvRound."""

from __future__ import annotations

import numpy as np
from fastnms.golden import float32, trig
from fastnms.golden.orb import PATTERN


def cos_sin_of_degrees(deg: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """int64 float32 bits of cos and sin of float32 degrees in [0, 360), as ORB computes
    them: (float)cos((double)(deg * (float)(CV_PI/180)))."""
    bits = np.asarray(deg, dtype=np.float32).view(np.uint32).astype(np.int64)
    a, b = trig.cos_sin(float32.to_radians(bits).astype(np.int64))
    return a.astype(np.int64), b.astype(np.int64)


def near_half_integer_angles(
    rng: np.random.Generator, batches: int, batch: int = 50000
) -> tuple[np.ndarray, np.ndarray]:
    """(cos, sin) bits of the random angles (batches x batch drawn) with a rotated point
    within 2**-18 of a half-integer, computed in float64 without either model: a superset
    of the angles where float32 rounding changes a point (about one angle in 5000)."""
    px, py = PATTERN[None, :, 0], PATTERN[None, :, 1]
    found_a, found_b = [], []
    for _ in range(batches):
        deg = (rng.random(batch) * 360).astype(np.float32)
        a, b = cos_sin_of_degrees(deg[deg < 360])
        fa = a.astype(np.uint32).view(np.float32).astype(np.float64)[:, None]
        fb = b.astype(np.uint32).view(np.float32).astype(np.float64)[:, None]
        near = np.zeros(len(a), dtype=bool)
        for v in (px * fa - py * fb, px * fb + py * fa):
            near |= (np.abs(v - np.floor(v) - 0.5) < 2.0**-18).any(axis=1)
        found_a.append(a[near])
        found_b.append(b[near])
    return np.concatenate(found_a), np.concatenate(found_b)
