"""The golden ORB against OpenCV's own cv2.ORB: keypoints, responses and float32 angles
identical; descriptors identical once the golden samples OpenCV's floating-point blur (the
one cv2.ORB uses), which proves the pattern, the rotation, the rounding and the bit layout;
the contract's bit-exact blur against cv2.GaussianBlur."""

from __future__ import annotations

import ctypes
import ctypes.util
import functools
import math
from pathlib import Path

import cv2
import numpy as np
import pytest
from fastnms.golden import orb
from fastnms.golden.image import load_grey
from fastnms.golden.model import NMS_MODES, SCORES, detect
from fastnms.testing import opencv_orb
from fastnms.testing.images import bundled_images

THRESHOLDS = (10, 20, 40)


def cv2_orb(img: np.ndarray, threshold: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """cv2.ORB's (x, y, response) int64, angles float32, descriptors uint8, by y then x."""
    return tuple(opencv_orb.features(img, threshold))


def golden_with_float_blur(img: np.ndarray, threshold: int) -> orb.OrbFeatures:
    """The golden's keypoints and angles, descriptors sampled from cv2.ORB's blur."""
    f = orb.orb_features(img, threshold)
    xs, ys = f.records[:, 0], f.records[:, 1]
    return f._replace(descriptors=orb.descriptors(orb.float_blur(img), xs, ys, f.angles))


def assert_equals_cv2_orb(img: np.ndarray, threshold: int, context: str) -> int:
    rec, angles, des = cv2_orb(img, threshold)
    f = golden_with_float_blur(img, threshold)
    assert np.array_equal(f.records, rec), (
        f"{context} t={threshold}: keypoints differ (golden {len(f.records)}, cv2.ORB {len(rec)})"
    )
    bad = np.nonzero(f.angles.view(np.uint32) != angles.view(np.uint32))[0]
    assert bad.size == 0, (
        f"{context} t={threshold}: {bad.size} angles differ, first at {f.records[bad[0]]}: "
        f"golden {f.angles[bad[0]]!r}, cv2.ORB {angles[bad[0]]!r}"
    )
    bad = np.nonzero((f.descriptors != des).any(axis=1))[0]
    assert bad.size == 0, (
        f"{context} t={threshold}: {bad.size} descriptors differ, first at {f.records[bad[0]]}"
    )
    return len(rec)


# ---- real photographs -------------------------------------------------------------------


@functools.lru_cache(maxsize=4)
def _grey(path: Path) -> np.ndarray:
    return load_grey(path)


@pytest.mark.parametrize(
    "threshold", [pytest.param(t, marks=pytest.mark.slow) if t != 20 else t for t in THRESHOLDS]
)
def test_shared_photograph_equals_cv2_orb(shared_image: Path, threshold: int, cv_optimized):
    n = assert_equals_cv2_orb(_grey(shared_image), threshold, shared_image.name)
    assert n > 0, f"{shared_image.name}: no keypoint, nothing was compared"


@pytest.mark.parametrize("path", bundled_images()[:3], ids=lambda p: p.name)
def test_bundled_photograph_equals_cv2_orb(path: Path):
    """Runs on a fresh clone too (scikit-image's photographs)."""
    assert assert_equals_cv2_orb(_grey(path), 20, path.name) > 0


# ---- generated images -------------------------------------------------------------------


def textured_patch(rng: np.random.Generator, size: int = 96) -> np.ndarray:
    blobs = cv2.GaussianBlur(rng.integers(0, 256, (size, size), dtype=np.uint8), (0, 0), 2.5)
    return cv2.normalize(blobs, None, 0, 255, cv2.NORM_MINMAX)


@pytest.mark.parametrize("angle", [0, 7.5, 30, 45, 60, 90, 135, 180, 225, 270, 315, 359])
def test_rotated_texture_equals_cv2_orb(angle: float, rng: np.random.Generator):
    """The same textured patch rotated: every orientation quadrant and the axes."""
    patch = textured_patch(rng, 160)
    turn = cv2.getRotationMatrix2D((79.5, 79.5), angle, 1.0)
    img = cv2.warpAffine(patch, turn, (160, 160), borderMode=cv2.BORDER_REFLECT_101)
    assert assert_equals_cv2_orb(img, 10, f"rotated {angle}") > 0


def test_noise_and_saturation_equal_cv2_orb(rng: np.random.Generator):
    """Noise at threshold 0 (a keypoint at most pixels), saturated areas (0 and 255
    plateaus, where many comparisons are between equal values), a checkerboard."""
    noise = rng.integers(0, 256, (96, 128), dtype=np.uint8)
    saturated = np.clip(noise.astype(np.int16) * 3 - 255, 0, 255).astype(np.uint8)
    cells = (np.indices((96, 128)) // 5).sum(axis=0) % 2
    board = np.where(cells == 1, 255, 0).astype(np.uint8)
    for name, img in (("noise", noise), ("saturated", saturated), ("checkerboard", board)):
        for t in (0, 20):
            assert_equals_cv2_orb(img, t, name)


def dot_image(offsets: list[tuple[int, int]], w: int = 80, h: int = 80) -> np.ndarray:
    """A dark dot at the centre of a flat field (a FAST corner whose patch is symmetric, so
    m01 = m10 = 0) plus bright pixels at the given offsets, outside the FAST circle."""
    img = np.full((h, w), 100, np.uint8)
    img[h // 2, w // 2] = 0
    for dx, dy in offsets:
        img[h // 2 + dy, w // 2 + dx] = 250
    return img


@pytest.mark.parametrize(
    ("offsets", "expected"),
    [
        ([], 0.0),  # flat patch: m01 = m10 = 0
        ([(9, 0)], 0.0),
        ([(0, 9)], 90.0),  # v grows downwards
        ([(-9, 0)], 180.0),
        ([(0, -9)], 270.0),
        ([(6, 6)], None),  # the diagonals: |m01| = |m10|, fastAtan2's value at c = 1
        ([(-6, 6)], None),
        ([(-6, -6)], None),
        ([(6, -6)], None),
        ([(9, 0), (0, 9), (-9, 0), (0, -9)], 0.0),  # symmetric again
    ],
)
def test_axis_and_diagonal_angles(offsets, expected):
    img = dot_image(offsets)
    f = orb.orb_features(img, 20)
    centre = np.nonzero((f.records[:, 0] == 40) & (f.records[:, 1] == 40))[0]
    assert centre.size == 1, f.records
    if expected is not None:
        assert f.angles[centre[0]] == np.float32(expected)
    assert_equals_cv2_orb(img, 20, f"dot {offsets}")


def test_diagonals_are_45_degree_multiples_of_each_other():
    angles = [orb.fast_atan2(np.array([y]), np.array([x]))[0] for x, y in [(5, 5), (-5, 5)]]
    assert np.float32(180) - angles[0] == angles[1]


def test_border_is_31_pixels_from_each_side():
    """Dots 30, 31, W-32 and W-31 from the left (and the same vertically), apart so that
    the NMS keeps each: the two inside are kept, the others dropped (cv2.ORB's
    edgeThreshold 31)."""
    w, h = 120, 100
    img = np.full((h, w), 100, np.uint8)
    xs, ys = (30, 31, w - 32, w - 31), (30, 31, h - 32, h - 31)
    spots = [(x, 40 + 6 * i) for i, x in enumerate(xs)] + [
        (45 + 8 * i, y) for i, y in enumerate(ys)
    ]
    for x, y in spots:
        img[y, x] = 0
    assert {tuple(r[:2]) for r in detect(img, 20).tolist()} == set(spots)
    f = orb.orb_features(img, 20)
    kept = {tuple(r[:2]) for r in f.records.tolist()}
    assert kept == {spots[1], spots[2], spots[5], spots[6]}
    assert_equals_cv2_orb(img, 20, "border dots")


@pytest.mark.parametrize("shape", [(62, 62), (62, 200), (200, 62), (7, 7), (3, 3)])
def test_small_images_have_no_descriptor(shape: tuple[int, int], rng: np.random.Generator):
    img = rng.integers(0, 256, shape, dtype=np.uint8)
    kps, des = orb.detect_and_compute(img, 0)
    assert kps == () and des.shape == (0, orb.DESCRIPTOR_BYTES) and des.dtype == np.uint8
    assert cv2_orb(img, 0)[0].shape[0] == 0
    if min(shape) > 7:
        assert len(detect(img, 0)) > 0  # there were corners: the border dropped them


# ---- every score and NMS ----------------------------------------------------------------


def opencv_ic_angle(img: np.ndarray, x: int, y: int) -> float:
    """OpenCV's IC_Angle transcribed loop for loop, with cv2.fastAtan2 (the scalar one)."""
    m01 = m10 = 0
    for u in range(-orb.HALF_PATCH, orb.HALF_PATCH + 1):
        m10 += u * int(img[y, x + u])
    for v in range(1, orb.HALF_PATCH + 1):
        v_sum = 0
        d = orb.UMAX[v]
        for u in range(-d, d + 1):
            plus, minus = int(img[y + v, x + u]), int(img[y - v, x + u])
            v_sum += plus - minus
            m10 += u * (plus + minus)
        m01 += v * v_sum
    return cv2.fastAtan2(float(m01), float(m10))


@pytest.mark.parametrize("score", SCORES)
@pytest.mark.parametrize("nms", NMS_MODES)
def test_every_score_and_nms(score: str, nms: str, rng: np.random.Generator):
    """Any NMS's keypoints: the border filter, then angles from OpenCV's IC_Angle loop and
    descriptors from cv2.ORB.compute at those keypoints and angles (float blur)."""
    img = textured_patch(rng, 112)
    kps, des = orb.detect_and_compute(img, 10, score, nms)
    records = detect(img, 10, score, nms)
    inside = records[orb.in_orb_border(records, img.shape)]
    assert len(kps) == len(inside) > 0
    assert [(k.pt, k.response) for k in kps] == [((x, y), s) for x, y, s in inside.tolist()]
    for k in kps[:: max(1, len(kps) // 40)]:
        assert np.float32(k.angle) == np.float32(opencv_ic_angle(img, *map(int, k.pt)))
    xs, ys = inside[:, 0], inside[:, 1]
    angles = np.array([k.angle for k in kps], np.float32)
    ours = orb.descriptors(orb.float_blur(img), xs, ys, angles)
    theirs = cv2.ORB_create(nlevels=1).compute(img, list(kps))
    assert len(theirs[0]) == len(kps)
    assert np.array_equal(ours, theirs[1])


# ---- rotation at chosen angles, and which cos OpenCV's build calls -----------------------


def cv2_descriptor_at(img: np.ndarray, x: int, y: int, angle: np.float32) -> np.ndarray:
    """cv2.ORB.compute keeps a given keypoint's angle: its descriptor at any angle."""
    kp = cv2.KeyPoint(float(x), float(y), float(orb.PATCH_SIZE), float(angle), 0.0, 0, -1)
    kps, des = cv2.ORB_create(nlevels=1).compute(img, [kp])
    assert len(kps) == 1 and np.float32(kps[0].angle) == angle
    return des[0]


def golden_descriptor_at(blurred: np.ndarray, x: int, y: int, angle: np.float32) -> np.ndarray:
    return orb.descriptors(blurred, np.array([x]), np.array([y]), np.array([angle]))[0]


@pytest.mark.parametrize("angle", [float(a) for a in range(0, 360, 45)] + [359.99997, 1e-5])
def test_descriptor_at_multiples_of_45_degrees(angle: float, rng: np.random.Generator):
    img = rng.integers(0, 256, (80, 80), dtype=np.uint8)
    a = np.float32(angle)
    want = cv2_descriptor_at(img, 40, 40, a)
    assert np.array_equal(golden_descriptor_at(orb.float_blur(img), 40, 40, a), want)


def _libm_cosf_sinf():
    name = ctypes.util.find_library("m")
    if name is None:
        pytest.skip("no C library libm to compare with")
    libm = ctypes.CDLL(name)
    for f in (libm.cosf, libm.sinf):
        f.restype, f.argtypes = ctypes.c_float, [ctypes.c_float]
    return libm.cosf, libm.sinf


def test_opencv_rotates_with_the_double_cos(rng: np.random.Generator):
    """OpenCV's `(float)cos(angle)` could be the C library's cosf (not correctly rounded)
    or its double cos (correctly rounded after the cast: the contract). At angles where the
    two give different pattern points, ask cv2.ORB."""
    cosf, sinf = _libm_cosf_sinf()
    # Inputs (not results): angles where glibc 2.36's cosf/sinf differ from the correctly
    # rounded value by enough to move a pattern point, found by screening 4 million random
    # angles (a few per million qualify); the test checks again that they still do.
    degrees = np.array(
        [193.49879455566406, 21.96733283996582, 190.09971618652344, 204.1057586669922]
        + [137.44161987304688, 161.2648162841797, 224.38375854492188],
        np.float32,
    )
    radians = (degrees * orb.DEG_TO_RAD).astype(np.float32).tolist()
    fa = np.array([cosf(r) for r in radians], np.float32)
    fb = np.array([sinf(r) for r in radians], np.float32)
    a, b = orb.cos_sin(degrees)
    x0, y0 = orb.sample_offsets(a, b)
    x1, y1 = orb.sample_offsets(fa, fb)
    found = np.nonzero(((x0 != x1) | (y0 != y1)).any(axis=1))[0]
    if found.size == 0:
        pytest.skip("this C library's cosf/sinf move no pattern point at the chosen angles")
    told_apart = 0  # images where a cosf rotation would have given another descriptor
    for i in found:
        angle = degrees[i]
        fx, fy = orb.sample_offsets(fa[i : i + 1], fb[i : i + 1])
        for _ in range(8):
            img = rng.integers(0, 256, (80, 80), dtype=np.uint8)
            blurred = orb.float_blur(img)
            want = cv2_descriptor_at(img, 40, 40, angle)
            assert np.array_equal(golden_descriptor_at(blurred, 40, 40, angle), want), (
                f"angle {angle!r}: cv2.ORB does not rotate with the double cos"
            )
            v = blurred[40 + fy[0], 40 + fx[0]]
            with_cosf = np.packbits(v[0::2] < v[1::2], bitorder="little")
            told_apart += int(not np.array_equal(with_cosf, want))
    assert told_apart > 0, "no image could tell the two cos apart"


# ---- the blur, angles and constants -----------------------------------------------------


def test_kernel_is_opencvs_error_diffusion():
    """Recompute getGaussianKernelFixedPoint_ED's rounding for sigma 2 (the margins are wide,
    double precision decides them)."""
    g = [math.exp(-(x * x) / 8) for x in range(-3, 1)]
    total = 2 * sum(g[:3]) + g[3]
    taps, err = [], 0.0
    for v in g[:3]:
        adj = v / total * 256 + err
        taps.append(round(adj))
        err = adj - taps[-1]
    assert tuple(taps + [256 - 2 * sum(taps)] + taps[::-1]) == orb.GAUSS_KERNEL


@pytest.mark.parametrize("shape", [(4, 4), (5, 9), (31, 17), (63, 63), (120, 161)])
def test_blur_equals_opencvs_bit_exact_blur(shape, rng: np.random.Generator):
    h, w = shape
    images = [
        rng.integers(0, 256, shape, dtype=np.uint8),
        (rng.integers(0, 2, shape) * 255).astype(np.uint8),
        np.full(shape, 255, np.uint8),
        np.zeros(shape, np.uint8),
        ((np.indices(shape).sum(axis=0) % 2) * 255).astype(np.uint8),
    ]
    for img in images:
        want = cv2.GaussianBlur(img, (7, 7), 2, sigmaY=2, borderType=cv2.BORDER_REFLECT_101)
        assert np.array_equal(orb.gaussian_blur(img), want), f"{w}x{h}"


def test_blur_of_photographs(rng: np.random.Generator):
    for path in bundled_images()[:3]:
        img = _grey(path)
        want = cv2.GaussianBlur(img, (7, 7), 2, sigmaY=2, borderType=cv2.BORDER_REFLECT_101)
        assert np.array_equal(orb.gaussian_blur(img), want), path.name


def test_blur_refuses_tiny_images():
    with pytest.raises(ValueError, match="at least 4x4"):
        orb.gaussian_blur(np.zeros((3, 9), np.uint8))


def test_fast_atan2_equals_opencv(rng: np.random.Generator):
    """The golden's float32 fastAtan2 against cv2.fastAtan2 over the moments' range; the
    bit-true integer model has its own, longer test (test_float32.py)."""
    m = orb.MOMENT_MAX
    y = np.concatenate([rng.integers(-m, m + 1, 100_000), np.arange(-50, 51).repeat(101)])
    x = np.concatenate([rng.integers(-m, m + 1, 100_000), np.tile(np.arange(-50, 51), 101)])
    ours = orb.fast_atan2(y, x)
    theirs = np.array([cv2.fastAtan2(float(a), float(b)) for a, b in zip(y, x, strict=True)])
    bad = np.nonzero(ours != theirs.astype(np.float32))[0]
    assert bad.size == 0, f"{bad.size} differ, first (m01, m10) = ({y[bad[0]]}, {x[bad[0]]})"
    assert ours.min() >= 0 and ours.max() < 360


def test_moment_bound_is_reached():
    """MOMENT_MAX is the largest |m10| (and |m01|): half the patch at 255, half at 0."""
    img = np.zeros((63, 63), np.uint8)
    img[:, 32:] = 255
    m01, m10 = orb.moments(img, np.array([31]), np.array([31]))
    assert (m01[0], m10[0]) == (0, orb.MOMENT_MAX)
    assert orb.moments(img.T.copy(), np.array([31]), np.array([31]))[0][0] == orb.MOMENT_MAX


def test_patch_is_opencvs_circle():
    assert orb.UMAX == (15, 15, 15, 15, 14, 14, 14, 13, 13, 12, 11, 10, 9, 8, 6, 3)
    assert len(orb.PATCH_U) == sum(2 * u + 1 for u in orb.UMAX) * 2 - (2 * orb.UMAX[0] + 1)


# ---- the OpenCV-typed interface ---------------------------------------------------------


def test_detect_and_compute_types(rng: np.random.Generator):
    img = textured_patch(rng, 100)
    kps, des = orb.detect_and_compute(img)
    assert isinstance(kps, tuple) and all(isinstance(k, cv2.KeyPoint) for k in kps)
    assert des.dtype == np.uint8 and des.shape == (len(kps), 32) and len(kps) > 0
    matches = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(des, des)
    assert all(m.queryIdx == m.trainIdx and m.distance == 0 for m in matches)
    plain, none = orb.detect_and_compute(img, orb=False)
    fast = cv2.FastFeatureDetector_create(20).detect(img)
    assert none is None
    assert sorted((k.pt, k.response, k.size, k.angle) for k in plain) == sorted(
        (k.pt, k.response, k.size, k.angle) for k in fast
    )


@pytest.mark.parametrize(
    ("kwargs", "message"),
    [
        ({"threshold": 256}, "threshold"),
        ({"score": "harris"}, "score"),
        ({"nms": "5x5"}, "nms"),
    ],
)
def test_detect_and_compute_rejects_bad_arguments(kwargs, message):
    with pytest.raises(ValueError, match=message):
        orb.detect_and_compute(np.zeros((70, 70), np.uint8), **kwargs)
    with pytest.raises(ValueError, match="uint8"):
        orb.detect_and_compute(np.zeros((70, 70), np.float32))
