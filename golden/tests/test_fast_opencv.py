"""The golden FAST against OpenCV's cv2.FastFeatureDetector (TYPE_9_16), and both scores
against a direct per-pixel reimplementation."""

from __future__ import annotations

import functools
import itertools
from collections.abc import Callable
from pathlib import Path

import cv2
import numpy as np
import pytest
from fastnms.golden.fast import CIRCLE_OFFSETS, fast_maps
from fastnms.golden.image import load_grey
from fastnms.golden.model import NMS_MODES, SCORES, detect

THRESHOLDS_EDGE = (0, 1, 10, 20, 50, 254, 255)


def opencv_fast(img: np.ndarray, threshold: int, nonmax: bool) -> np.ndarray:
    """cv2 keypoints as int64 (N, 3) x, y, response sorted by y then x."""
    det = cv2.FastFeatureDetector_create(
        threshold=threshold, nonmaxSuppression=nonmax, type=cv2.FAST_FEATURE_DETECTOR_TYPE_9_16
    )
    kps = det.detect(img)
    raw = np.array([(k.pt[0], k.pt[1], k.response) for k in kps], dtype=np.float64).reshape(-1, 3)
    rec = raw.astype(np.int64)
    assert np.array_equal(rec, raw), "OpenCV returned non-integer keypoint coordinates/responses"
    return rec[np.lexsort((rec[:, 0], rec[:, 1]))]


def describe_difference(ours: np.ndarray, ref: np.ndarray) -> str:
    mine = {tuple(r) for r in ours.tolist()}
    theirs = {tuple(r) for r in ref.tolist()}
    extra = sorted(mine - theirs, key=lambda r: (r[1], r[0]))[:8]
    missing = sorted(theirs - mine, key=lambda r: (r[1], r[0]))[:8]
    return (
        f"golden {len(ours)} vs OpenCV {len(ref)}; only golden (x,y,s): {extra}; "
        f"only OpenCV: {missing}"
    )


def assert_matches_opencv(img: np.ndarray, threshold: int, context: str) -> int:
    """Check both OpenCV modes; returns the number of corners (no NMS) for sanity checks."""
    with_nms = detect(img, threshold, "opencv", "3x3")
    ref = opencv_fast(img, threshold, nonmax=True)
    assert np.array_equal(with_nms, ref), f"{context} t={threshold} nms=3x3: " + (
        describe_difference(with_nms, ref)
    )
    plain = detect(img, threshold, "opencv", "none")
    ref = opencv_fast(img, threshold, nonmax=False)
    assert np.array_equal(plain[:, :2], ref[:, :2]), f"{context} t={threshold} nms=none: " + (
        describe_difference(plain[:, :2], ref[:, :2])
    )
    return len(plain)


# ---- real photographs ------------------------------------------------------------------


@functools.lru_cache(maxsize=4)
def _shared(path: Path) -> np.ndarray:
    return load_grey(path)


@pytest.mark.parametrize("threshold", [10, 20, 50])
def test_shared_image_matches_opencv(shared_image: Path, threshold: int, cv_optimized: bool):
    img = _shared(shared_image)
    n = assert_matches_opencv(img, threshold, shared_image.name)
    assert n > 0, f"{shared_image.name}: no corners at all, the comparison would be empty"


# ---- generated images ------------------------------------------------------------------


def uniform_noise(rng: np.random.Generator) -> np.ndarray:
    return rng.integers(0, 256, (61, 83), dtype=np.uint8)


def blurred_noise(rng: np.random.Generator) -> np.ndarray:
    img = uniform_noise(rng)
    img = cv2.GaussianBlur(img, (0, 0), 1.2)
    return cv2.normalize(img, None, 0, 255, cv2.NORM_MINMAX)


def saturated_pixels(rng: np.random.Generator) -> np.ndarray:
    return (rng.integers(0, 2, (57, 70)) * 255).astype(np.uint8)


def saturated_blocks(rng: np.random.Generator) -> np.ndarray:
    """Random rectangles of 0 and 255: straight edges and right-angle corners."""
    img = np.full((64, 96), 255 * int(rng.integers(0, 2)), dtype=np.uint8)
    for _ in range(40):
        h, w = rng.integers(1, 12, size=2)
        y, x = rng.integers(0, 64), rng.integers(0, 96)
        img[y : y + h, x : x + w] = 255 * int(rng.integers(0, 2))
    return img


def two_levels(rng: np.random.Generator) -> np.ndarray:
    """Random pixels at two levels 40 apart: thresholds 39/40/41 hit the strict > and <."""
    low = int(rng.integers(0, 216))
    return np.where(rng.random((50, 66)) < 0.5, low, low + 40).astype(np.uint8)


def checkerboard(square: int) -> Callable[[np.random.Generator], np.ndarray]:
    """A 0/255 board on a grey background. Inside, a board has no FAST corners for even
    squares (an X-junction has no 9-pixel arc); its outer corners always have some."""

    def make(rng: np.random.Generator) -> np.ndarray:
        oy, ox = rng.integers(0, square, size=2)  # random phase
        yy, xx = np.mgrid[0:48, 0:70]
        board = ((yy + oy) // square + (xx + ox) // square) % 2 * 255
        img = np.full((48, 70), 128, dtype=np.uint8)
        y0, x0 = rng.integers(0, 8, size=2)
        img[y0 : 48 - 8 + y0, x0 : 70 - 8 + x0] = board[y0 : 48 - 8 + y0, x0 : 70 - 8 + x0]
        return img

    return make


def constant(value: int) -> Callable[[np.random.Generator], np.ndarray]:
    return lambda rng: np.full((32, 45), value, dtype=np.uint8)


GENERATED: dict[str, Callable[[np.random.Generator], np.ndarray]] = {
    "uniform_noise": uniform_noise,
    "blurred_noise": blurred_noise,
    "saturated_pixels": saturated_pixels,
    "saturated_blocks": saturated_blocks,
    "two_levels": two_levels,
    **{f"checker{s}": checkerboard(s) for s in (1, 2, 3, 4, 5, 8)},
    **{f"constant{v}": constant(v) for v in (0, 128, 255)},
}


@pytest.mark.parametrize("kind", sorted(GENERATED))
def test_generated_matches_opencv(kind: str, cv_optimized: bool, rng: np.random.Generator, seed):
    total = 0
    for rep in range(3):
        img = GENERATED[kind](rng)
        thresholds = set(THRESHOLDS_EDGE) | {39, 40, 41}
        for t in sorted(thresholds):
            total += assert_matches_opencv(img, t, f"{kind} #{rep} (seed {seed})")
    if kind.startswith("constant"):
        assert total == 0
    else:
        assert total > 0, f"{kind}: no corners at any threshold, the comparison says nothing"


def test_circle_is_opencv_offsets16():
    # The circle as OpenCV's makeOffsets lists it for patternSize 16 (fast_score.cpp).
    expected = [(0, 3), (1, 3), (2, 2), (3, 1), (3, 0), (3, -1), (2, -2), (1, -3)]
    expected += [(-dx, -dy) for dx, dy in expected]
    assert list(CIRCLE_OFFSETS) == expected
    # A closed ring: 16 distinct points at distance ~3, consecutive ones 8-adjacent.
    assert len(set(CIRCLE_OFFSETS)) == 16
    assert all(8 <= dx * dx + dy * dy <= 10 for dx, dy in CIRCLE_OFFSETS)
    ring = [*CIRCLE_OFFSETS, CIRCLE_OFFSETS[0]]
    assert all(max(abs(a - c), abs(b - d)) == 1 for (a, b), (c, d) in itertools.pairwise(ring))


SMALL = [(h, w) for h in range(1, 9) for w in range(1, 9)]


@pytest.mark.parametrize(("h", "w"), SMALL, ids=[f"{h}x{w}" for h, w in SMALL])
def test_small_images(h: int, w: int, cv_optimized: bool, rng: np.random.Generator, seed):
    for rep in range(4):
        img = (rng.integers(0, 2, (h, w)) * 255).astype(np.uint8)
        if rep == 3:
            img = rng.integers(0, 256, (h, w), dtype=np.uint8)
        for t in (0, 1, 20, 255):
            assert_matches_opencv(img, t, f"{h}x{w} #{rep} (seed {seed})")
            corner, score = fast_maps(img, t)
            assert corner.shape == score.shape == (h, w)
            if h < 7 or w < 7:
                assert not corner.any() and not score.any()


@pytest.mark.parametrize("shape", [(0, 0), (0, 9), (9, 0), (1, 1)])
def test_degenerate_images(shape: tuple[int, int]):
    img = np.zeros(shape, dtype=np.uint8)
    for score in SCORES:
        corner, scores = fast_maps(img, 0, score)
        assert corner.shape == shape and corner.dtype == bool and not corner.any()
        assert scores.shape == shape and scores.dtype == np.int32 and not scores.any()
        for nms in NMS_MODES:
            out = detect(img, 0, score, nms)
            assert out.shape == (0, 3) and out.dtype == np.int64
    assert opencv_fast(img, 0, True).shape == (0, 3)


@pytest.mark.parametrize("transpose", [False, True], ids=["7_high", "7_wide"])
def test_seven_pixel_strips(transpose: bool, cv_optimized: bool, rng: np.random.Generator, seed):
    """Exactly one row/column of possible centres, next to images of every other length."""
    total = 0
    for n in range(7, 48):
        img = (rng.integers(0, 2, (7, n)) * 255).astype(np.uint8)
        img = img.T.copy() if transpose else img
        for t in (0, 20):
            total += assert_matches_opencv(img, t, f"{img.shape} (seed {seed})")
    assert total > 0


def test_map_invariants(rng: np.random.Generator, seed):
    img = cv2.GaussianBlur(rng.integers(0, 256, (90, 120), dtype=np.uint8), (0, 0), 0.8)
    for t in (0, 5, 30):
        corner, score = fast_maps(img, t, "opencv")
        assert corner.dtype == bool and score.dtype == np.int32
        ys, xs = np.nonzero(corner)
        assert ys.size > 0, f"seed {seed}"
        assert ys.min() >= 3 and ys.max() <= img.shape[0] - 4
        assert xs.min() >= 3 and xs.max() <= img.shape[1] - 4
        assert not score[~corner].any()
        assert score[corner].min() >= t and score[corner].max() <= 254


# ---- scores against a direct per-pixel reimplementation ----------------------------------


def scalar_reference(img: np.ndarray, t: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """corner, opencv score, sad score, computed pixel by pixel from the definitions."""
    h, w = img.shape
    corner = np.zeros((h, w), bool)
    s_cv = np.zeros((h, w), np.int32)
    s_sad = np.zeros((h, w), np.int32)
    for y in range(3, h - 3):
        for x in range(3, w - 3):
            v = int(img[y, x])
            ring = [int(img[y + dy, x + dx]) for dx, dy in CIRCLE_OFFSETS]
            arcs = [[ring[(k + i) % 16] for i in range(9)] for k in range(16)]
            bright = any(all(c > v + t for c in arc) for arc in arcs)
            dark = any(all(c < v - t for c in arc) for arc in arcs)
            if not (bright or dark):
                continue
            corner[y, x] = True
            a = max(min(v - c for c in arc) for arc in arcs)
            b = max(min(c - v for c in arc) for arc in arcs)
            s_cv[y, x] = max(a, b) - 1
            s_sad[y, x] = max(
                sum(c - v - t for c in ring if c > v + t),
                sum(v - c - t for c in ring if c < v - t),
            )
    return corner, s_cv, s_sad


@pytest.mark.parametrize("kind", ["uniform_noise", "blurred_noise", "saturated_pixels"])
def test_scores_match_scalar_reference(kind: str, rng: np.random.Generator, seed):
    img = np.ascontiguousarray(GENERATED[kind](rng)[:40, :40])
    for t in (0, 7, 25, 60):
        ref_corner, ref_cv, ref_sad = scalar_reference(img, t)
        corner_cv, score_cv = fast_maps(img, t, "opencv")
        corner_sad, score_sad = fast_maps(img, t, "sad")
        msg = f"{kind} t={t} seed {seed}"
        assert ref_corner.any(), msg
        assert np.array_equal(corner_cv, ref_corner), msg
        assert np.array_equal(corner_sad, ref_corner), msg
        assert np.array_equal(score_cv, ref_cv), msg
        assert np.array_equal(score_sad, ref_sad), msg


def test_sad_invariants(rng: np.random.Generator, seed):
    for rep in range(4):
        img = saturated_pixels(rng) if rep % 2 else uniform_noise(rng)
        for t in (0, 1, 30, 100):
            corner_cv, _ = fast_maps(img, t, "opencv")
            corner, score = fast_maps(img, t, "sad")
            msg = f"#{rep} t={t} seed {seed}"
            assert np.array_equal(corner, corner_cv), msg
            assert not score[~corner].any(), msg
            assert score.min() >= 0 and score.max() <= 4080, msg


def test_score_extremes():
    """Centre 0 with the whole circle at 255: SAD reaches 16 * 255, OpenCV's score 254."""
    img = np.zeros((7, 7), np.uint8)
    for dx, dy in CIRCLE_OFFSETS:
        img[3 + dy, 3 + dx] = 255
    assert detect(img, 0, "sad", "none").tolist() == [[3, 3, 4080]]
    assert detect(img, 0, "opencv", "none").tolist() == [[3, 3, 254]]
    assert detect(img, 254, "sad", "none").tolist() == [[3, 3, 16]]
    assert detect(img, 254, "opencv", "none").tolist() == [[3, 3, 254]]
    assert detect(img, 255, "sad", "none").shape == (0, 3)
    assert opencv_fast(img, 254, True).tolist() == [[3, 3, 254]]


def test_exactly_nine_contiguous():
    """Nine brighter circle pixels make a corner wherever the arc starts (including arcs
    wrapping from pixel 15 to 0); eight do not; the score is the weakest arc pixel - 1."""
    for start in range(16):
        for length, is_corner in ((8, False), (9, True)):
            img = np.full((7, 7), 100, np.uint8)
            for i in range(length):
                dx, dy = CIRCLE_OFFSETS[(start + i) % 16]
                img[3 + dy, 3 + dx] = 160 if i else 131  # weakest difference 31
            got = detect(img, 30, "opencv", "none").tolist()
            assert got == ([[3, 3, 30]] if is_corner else []), (start, length)
            assert opencv_fast(img, 30, True).tolist() == got, (start, length)
            sad = detect(img, 30, "sad", "none").tolist()
            assert sad == ([[3, 3, 1 + 30 * (length - 1)]] if is_corner else []), (start, length)


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"threshold": -1}, "threshold"),
        ({"threshold": 256}, "threshold"),
        ({"threshold": 1.5}, "threshold"),
        ({"threshold": "20"}, "threshold"),
        ({"threshold": True}, "threshold"),
        ({"threshold": None}, "threshold"),
        ({"score": "harris"}, "score"),
        ({"nms": "5x5"}, "nms"),
        ({"img": np.zeros((9, 9, 3), np.uint8)}, "2-D"),
        ({"img": np.zeros((9, 9), np.float32)}, "uint8"),
        ({"img": np.zeros((9, 9), np.uint16)}, "uint8"),
        ({"img": [[0] * 9] * 9}, "numpy array"),
    ],
)
def test_detect_rejects_bad_arguments(kwargs: dict, match: str):
    img = kwargs.get("img", np.zeros((9, 9), np.uint8))
    args = {"threshold": 20, "score": "opencv", "nms": "3x3"}
    args.update((k, v) for k, v in kwargs.items() if k != "img")
    with pytest.raises(ValueError, match=match):
        detect(img, **args)
    if "nms" not in kwargs:
        with pytest.raises(ValueError, match=match):
            fast_maps(img, args["threshold"], args["score"])


def test_numpy_integer_threshold_accepted():
    img = saturated_pixels(np.random.default_rng(1))
    assert np.array_equal(detect(img, np.uint8(20)), detect(img, 20))


def test_zero_score_corner():
    """At t=0 a corner whose best arc differs by 1 scores 0: OpenCV lists it without NMS and
    never keeps it with NMS (0 is not > the 0 of its non-corner neighbours)."""
    img = np.full((15, 15), 100, np.uint8)
    for dx, dy in CIRCLE_OFFSETS[:9]:
        img[7 + dy, 7 + dx] = 101
    plain = detect(img, 0, "opencv", "none").tolist()
    assert [7, 7, 0] in plain
    assert [7, 7] not in detect(img, 0, "opencv", "3x3")[:, :2].tolist()
    assert_matches_opencv(img, 0, "zero-score corner")
