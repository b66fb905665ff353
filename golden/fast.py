"""FAST-9/16 segment test and corner scores, bit-exact with OpenCV's cv::FAST TYPE_9_16.

Everything is vectorised over the image: the 16 circle pixels of every interior pixel are
stacked into one (16, H-6, W-6) array, the brighter/darker tests are packed into 16-bit masks
and a 65536-entry table says whether a mask holds 9 cyclically contiguous ones. Scores are
only computed at corners (they are 0 elsewhere by definition).
"""

from __future__ import annotations

from functools import cache

import numpy as np

# OpenCV's offsets16 (fast_score.cpp, makeOffsets) as (dx, dy); pixel k is img[y + dy, x + dx].
# The cyclic order matters: arcs are runs of consecutive entries, wrapping from 15 to 0.
CIRCLE_OFFSETS: tuple[tuple[int, int], ...] = (
    (0, 3),
    (1, 3),
    (2, 2),
    (3, 1),
    (3, 0),
    (3, -1),
    (2, -2),
    (1, -3),
    (0, -3),
    (-1, -3),
    (-2, -2),
    (-3, -1),
    (-3, 0),
    (-3, 1),
    (-2, 2),
    (-1, 3),
)

RADIUS = 3  # corners need the whole circle inside the image
ARC = 9  # the "9" of FAST-9/16
N_CIRCLE = len(CIRCLE_OFFSETS)
SCORE_MODES = ("opencv", "sad")
SAD_MAX = N_CIRCLE * 255  # 4080: every circle pixel 255 away from the centre, threshold 0


def validate_image(img: object) -> np.ndarray:
    """Return img if it is a 2-D uint8 ndarray, else raise ValueError."""
    if not isinstance(img, np.ndarray):
        raise ValueError(f"image must be a numpy array, got {type(img).__name__}")
    if img.ndim != 2:
        raise ValueError(f"image must be 2-D (greyscale), got shape {img.shape}")
    if img.dtype != np.uint8:
        raise ValueError(f"image must be uint8, got dtype {img.dtype}")
    return img


def validate_threshold(threshold: object) -> int:
    """Return threshold as int if it is an integer in 0..255, else raise ValueError."""
    # bool is an int subclass but True/False as a threshold is almost certainly a bug.
    if isinstance(threshold, bool) or not isinstance(threshold, int | np.integer):
        raise ValueError(f"threshold must be an integer in 0..255, got {threshold!r}")
    if not 0 <= threshold <= 255:
        raise ValueError(f"threshold must be an integer in 0..255, got {threshold}")
    return int(threshold)


def validate_score(score: object) -> str:
    if score not in SCORE_MODES:
        raise ValueError(f"score must be one of {', '.join(SCORE_MODES)}; got {score!r}")
    return str(score)


@cache
def _contiguous_table() -> np.ndarray:
    """bool[65536]: does the 16-bit cyclic mask contain >= 9 consecutive set bits."""
    bits = ((np.arange(1 << N_CIRCLE)[:, None] >> np.arange(N_CIRCLE)) & 1).astype(bool)
    run = bits  # run[:, k]: bits k .. k+n-1 all set (cyclically), n = 1, 2, 4, 8, then 9
    for n in (1, 2, 4):
        run = run & np.roll(run, -n, axis=1)
    run = run & np.roll(bits, -(ARC - 1), axis=1)  # n = 9
    table = run.any(axis=1)
    table.flags.writeable = False
    return table


def _circle_stack(img: np.ndarray) -> np.ndarray:
    """uint8 (16, H-6, W-6): circle pixel k of every interior centre."""
    h, w = img.shape
    return np.stack(
        [
            img[RADIUS + dy : h - RADIUS + dy, RADIUS + dx : w - RADIUS + dx]
            for dx, dy in CIRCLE_OFFSETS
        ]
    )


def _pack16(flags: np.ndarray) -> np.ndarray:
    """bool (16, ...) -> uint16 (...) with bit k = flags[k]."""
    packed = np.packbits(flags, axis=0, bitorder="little")  # (2, ...) uint8
    return packed[0].astype(np.uint16) | (packed[1].astype(np.uint16) << 8)


def _arc_extrema(d: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """For d (16, N): per column, max over the 16 arcs of 9 of the arc minimum, and
    min over the arcs of the arc maximum. Window minima/maxima are built by doubling
    (2, 4, 8, then 9) so partial results are shared between neighbouring arcs."""
    lo = hi = d
    for n in (1, 2, 4):
        lo = np.minimum(lo, np.roll(lo, -n, axis=0))
        hi = np.maximum(hi, np.roll(hi, -n, axis=0))
    shifted = np.roll(d, -(ARC - 1), axis=0)
    lo = np.minimum(lo, shifted)  # lo[k] = min(d[k .. k+8]) cyclically
    hi = np.maximum(hi, shifted)
    return lo.max(axis=0), hi.min(axis=0)


def opencv_scores(centre: np.ndarray, circle: np.ndarray) -> np.ndarray:
    """OpenCV's cornerScore<16> for corners: max(A, B) - 1 (int32).

    centre: (N,) values, circle: (16, N) values. With d_k = v - c_k, A is the best arc
    minimum of d (darker arcs) and B the best arc minimum of -d (brighter arcs); the
    latter equals minus the smallest arc maximum of d.
    """
    d = centre.astype(np.int16)[None, :] - circle.astype(np.int16)
    best_min, least_max = _arc_extrema(d)
    return (np.maximum(best_min, -least_max) - 1).astype(np.int32)


def sad_scores(centre: np.ndarray, circle: np.ndarray, threshold: int) -> np.ndarray:
    """The paper's eq. 1 with the threshold taken off each term (int32):
    max(sum over brighter of (c - v - t), sum over darker of (v - c - t))."""
    diff = circle.astype(np.int32) - centre.astype(np.int32)[None, :]
    brighter = np.where(diff > threshold, diff - threshold, 0).sum(axis=0)
    darker = np.where(-diff > threshold, -diff - threshold, 0).sum(axis=0)
    return np.maximum(brighter, darker).astype(np.int32)


def fast_maps(
    img: np.ndarray, threshold: int, score: str = "opencv"
) -> tuple[np.ndarray, np.ndarray]:
    """Run the FAST-9/16 segment test on every pixel.

    Returns (corner, score): corner is bool HxW, score int32 HxW and 0 wherever corner is
    False. Only pixels with 3 <= x <= W-4 and 3 <= y <= H-4 can be corners.
    """
    img = validate_image(img)
    t = validate_threshold(threshold)
    score = validate_score(score)
    h, w = img.shape
    corner = np.zeros((h, w), dtype=bool)
    scores = np.zeros((h, w), dtype=np.int32)
    if h < 2 * RADIUS + 1 or w < 2 * RADIUS + 1:
        return corner, scores

    centre = img[RADIUS : h - RADIUS, RADIUS : w - RADIUS]
    circle = _circle_stack(img)
    # Saturating v +/- t is exact: c > min(v + t, 255) <=> c > v + t for c <= 255, and the
    # same for the lower bound; the sums themselves are done in int16 so nothing wraps.
    wide = centre.astype(np.int16)
    upper = np.minimum(wide + t, 255).astype(np.uint8)
    lower = np.maximum(wide - t, 0).astype(np.uint8)
    table = _contiguous_table()
    inner = table[_pack16(circle > upper)] | table[_pack16(circle < lower)]

    ys, xs = np.nonzero(inner)
    c_centre = centre[ys, xs]
    c_circle = circle[:, ys, xs]
    if score == "opencv":
        values = opencv_scores(c_centre, c_circle)
    else:
        values = sad_scores(c_centre, c_circle, t)
    corner[ys + RADIUS, xs + RADIUS] = True
    scores[ys + RADIUS, xs + RADIUS] = values
    return corner, scores
