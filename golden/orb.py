"""ORB features (orientation and 256-bit rotated BRIEF) of the NMS's keypoints, defined
exactly as OpenCV's `cv::ORB` computes them (`modules/features2d/src/orb.cpp`, one level).

For every keypoint (x, y) of the NMS's output with 31 <= x < W-31 and 31 <= y < H-31
(cv2.ORB's default `edgeThreshold`; the others are dropped):

1. **Moments** (OpenCV's `IC_Angle`) on the unblurred image, integers:
   `m10 = sum u*I(x+u, y+v)`, `m01 = sum v*I(x+u, y+v)` over the radius-15 circular patch,
   the row at offset v spanning `|u| <= UMAX[|v|]` (OpenCV's `umax` table). v grows downwards.
   `|m10|, |m01| <= MOMENT_MAX` (624 240 < 2**20).
2. **Angle**: `fastAtan2((float)m01, (float)m10)` in IEEE binary32 as OpenCV's scalar
   `atan_f32` evaluates it: its four float constants, the divisor `ax + (float)DBL_EPSILON`,
   every operation rounded to float32, no fused multiply-add; degrees in [0, 360).
3. **Blur**: OpenCV's bit-exact 7x7 Gaussian, sigma 2 (`cv2.GaussianBlur(img, (7, 7), 2,
   sigmaY=2, borderType=cv2.BORDER_REFLECT_101)` on the whole 8-bit image: its fixed-point
   path), which is the integer kernel GAUSS_KERNEL / 256 in each direction, one rounding at
   the end: `(sum k_i k_j I + 2**15) >> 16`.
4. **Rotation**: `r = (float)(angle * (float)(CV_PI/180))`, `a = (float)cos((double)r)`,
   `b = (float)sin((double)r)` with the C library's double cos/sin (the correctly rounded
   float32 values); each pattern point (px, py) of BIT_PATTERN_31 goes to
   `(cvRound(px*a - py*b), cvRound(px*b + py*a))`, every product and sum rounded to float32,
   cvRound rounding half to even.
5. **Bits**: bit i = `blurred(p0) < blurred(p1)` for pair i, stored as bit i % 8 of byte
   i // 8 (OpenCV's layout, byte 0 first).

cv2.ORB itself blurs a sub-matrix of its padded pyramid, which sends OpenCV to its
floating-point filter instead of step 3: with `float_blur` in place of `gaussian_blur` these
functions give cv2.ORB's descriptors bit for bit (the tests show it); with the contract's blur
a fraction of descriptors differ from cv2.ORB's by a few bits (measured by `make bench`).
"""

from __future__ import annotations

import math
from typing import NamedTuple

import cv2
import numpy as np

from .budget import cell_budget, validate_budget
from .fast import validate_image, validate_score, validate_threshold
from .model import DEFAULT_THRESHOLD, detect, validate_nms
from .orb_pattern import BIT_PATTERN_31
from .pyramid import DEFAULT_SCALE_FACTOR, level_scale, pyramid, validate_levels

EDGE = 31  # cv2.ORB's default edgeThreshold: keypoints closer to a border are dropped
PATCH_SIZE = 31  # the moments' patch and cv2.KeyPoint.size
HALF_PATCH = PATCH_SIZE // 2
DESCRIPTOR_BYTES = 32
CHUNK = 4096  # keypoints per vectorised step (bounds memory on dense frames)


def _umax(half: int) -> tuple[int, ...]:
    """OpenCV's `umax`: the half-width of each row of the circular patch, built as
    ORB_Impl::detectAndCompute builds it (rounded circle, then made symmetric about 45
    degrees so that the patch is the same when transposed)."""
    vmax = math.floor(half * math.sqrt(2.0) / 2 + 1)
    vmin = math.ceil(half * math.sqrt(2.0) / 2)
    u = [0] * (half + 2)
    for v in range(vmax + 1):
        u[v] = round(math.sqrt(half * half - v * v))  # cvRound of a value never at .5
    v0 = 0
    for v in range(half, vmin - 1, -1):
        while u[v0] == u[v0 + 1]:
            v0 += 1
        u[v] = v0
        v0 += 1
    return tuple(u[: half + 1])


UMAX: tuple[int, ...] = _umax(HALF_PATCH)
# The patch as (u, v) offsets: every pixel with |v| <= 15 and |u| <= UMAX[|v|].
PATCH_U, PATCH_V = (
    np.array(axis, dtype=np.int64)
    for axis in zip(
        *[
            (u, v)
            for v in range(-HALF_PATCH, HALF_PATCH + 1)
            for u in range(-UMAX[abs(v)], UMAX[abs(v)] + 1)
        ],
        strict=True,
    )
)
MOMENT_MAX = 255 * int(np.abs(PATCH_U).sum()) // 2  # the largest |m10| (and |m01|: symmetric)

# OpenCV's atan_f32 constants: a float literal times (float)(180/CV_PI), product in float.
_DEG = np.float32(180 / math.pi)
ATAN_P1 = np.float32(np.float32(0.9997878412794807) * _DEG)
ATAN_P3 = np.float32(np.float32(-0.3258083974640975) * _DEG)
ATAN_P5 = np.float32(np.float32(0.1555786518463281) * _DEG)
ATAN_P7 = np.float32(np.float32(-0.04432655554792128) * _DEG)
ATAN_EPS = np.float32(np.finfo(np.float64).eps)  # (float)DBL_EPSILON = 2**-52
DEG_TO_RAD = np.float32(math.pi / 180.0)  # (float)(CV_PI/180.f)

# OpenCV's bit-exact kernel for GaussianBlur(7x7, sigma 2) on 8-bit images: the Gaussian
# exp(-x^2/8), x = -3..3, normalised, times 256 and rounded with error diffusion from the
# outside in (getGaussianKernelFixedPoint_ED: 17.96 -> 18, 33.52 -> 34, 48.34 -> 48), the
# centre taking what is left so that the taps sum to exactly 256.
GAUSS_KERNEL: tuple[int, ...] = (18, 34, 48, 56, 48, 34, 18)
GAUSS_SHIFT = 16  # two passes of 8 fractional bits
GAUSS_RADIUS = len(GAUSS_KERNEL) // 2

PATTERN = np.array(BIT_PATTERN_31, dtype=np.int64).reshape(2 * len(BIT_PATTERN_31), 2)
PATTERN_X = PATTERN[:, 0].astype(np.float32)  # point 2i is p0 of bit i, point 2i+1 its p1
PATTERN_Y = PATTERN[:, 1].astype(np.float32)


class OrbFeatures(NamedTuple):
    """Keypoints with their ORB fields, sorted by y then x."""

    records: np.ndarray  # int64 (N, 3): x, y, score
    angles: np.ndarray  # float32 (N,): degrees in [0, 360)
    descriptors: np.ndarray  # uint8 (N, 32)


def in_orb_border(records: np.ndarray, shape: tuple[int, int]) -> np.ndarray:
    """bool (N,): the records cv2.ORB keeps, 31 <= x < W-31 and 31 <= y < H-31."""
    h, w = shape
    x, y = records[:, 0], records[:, 1]
    return (x >= EDGE) & (x < w - EDGE) & (y >= EDGE) & (y < h - EDGE)


def moments(img: np.ndarray, xs: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(m01, m10) int64 of each keypoint's circular patch (IC_Angle's integer moments)."""
    m01 = np.empty(len(xs), dtype=np.int64)
    m10 = np.empty(len(xs), dtype=np.int64)
    for s in range(0, len(xs), CHUNK):
        x, y = xs[s : s + CHUNK, None], ys[s : s + CHUNK, None]
        patch = img[y + PATCH_V, x + PATCH_U].astype(np.int64)
        m01[s : s + CHUNK] = patch @ PATCH_V
        m10[s : s + CHUNK] = patch @ PATCH_U
    return m01, m10


def fast_atan2(y: np.ndarray, x: np.ndarray) -> np.ndarray:
    """OpenCV's scalar cv::fastAtan2(y, x) in degrees, float32 (N,), every step float32."""
    y = np.asarray(y).astype(np.float32)  # exact for the moments (|m| < 2**24)
    x = np.asarray(x).astype(np.float32)
    ax, ay = np.abs(x), np.abs(y)
    flat = ax >= ay  # within 45 degrees of the x axis
    c = np.where(flat, ay, ax) / (np.where(flat, ax, ay) + ATAN_EPS)
    c2 = c * c
    poly = (((ATAN_P7 * c2 + ATAN_P5) * c2 + ATAN_P3) * c2 + ATAN_P1) * c
    a = np.where(flat, poly, np.float32(90) - poly)
    a = np.where(x < 0, np.float32(180) - a, a)
    a = np.where(y < 0, np.float32(360) - a, a)
    return a.astype(np.float32)


def ic_angle(img: np.ndarray, xs: np.ndarray, ys: np.ndarray) -> np.ndarray:
    """The keypoints' orientation, float32 degrees in [0, 360) (OpenCV's IC_Angle)."""
    m01, m10 = moments(img, xs, ys)
    return fast_atan2(m01, m10)


def gaussian_blur(img: np.ndarray) -> np.ndarray:
    """OpenCV's bit-exact GaussianBlur(7x7, sigma 2, BORDER_REFLECT_101) of a uint8 image of
    at least 4x4 pixels (the border needs 3 pixels to reflect), in integers."""
    img = validate_image(img)
    h, w = img.shape
    if h <= GAUSS_RADIUS or w <= GAUSS_RADIUS:
        raise ValueError(f"the 7x7 blur needs an image of at least 4x4 pixels, got {w}x{h}")
    padded = np.pad(img.astype(np.int32), GAUSS_RADIUS, mode="reflect")  # reflect-101
    rows = sum(k * padded[:, i : i + w] for i, k in enumerate(GAUSS_KERNEL))
    both = sum(k * rows[i : i + h, :] for i, k in enumerate(GAUSS_KERNEL))
    return ((both + (1 << (GAUSS_SHIFT - 1))) >> GAUSS_SHIFT).astype(np.uint8)


def float_blur(img: np.ndarray) -> np.ndarray:
    """The blur cv2.ORB applies in fact (OpenCV's floating-point separable filter); not the
    contract: for comparing with cv2.ORB only."""
    k = cv2.getGaussianKernel(len(GAUSS_KERNEL), 2, cv2.CV_32F)
    return cv2.sepFilter2D(img, -1, k, k, borderType=cv2.BORDER_REFLECT_101)


def cos_sin(angles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(a, b) float32: the correctly rounded cos and sin of each angle in radians,
    `(float)cos((double)(angle * (float)(CV_PI/180)))` as OpenCV's computeOrbDescriptor."""
    radians = (np.asarray(angles, dtype=np.float32) * DEG_TO_RAD).astype(np.float32)
    # math.cos is the C library's double cos (numpy's own may differ in the last bit).
    a = np.fromiter((math.cos(r) for r in radians.tolist()), np.float64, len(radians))
    b = np.fromiter((math.sin(r) for r in radians.tolist()), np.float64, len(radians))
    return a.astype(np.float32), b.astype(np.float32)


def sample_offsets(a: np.ndarray, b: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """int64 (N, 512) x and y offsets of the rotated pattern points, float32 then cvRound."""
    a, b = a[:, None], b[:, None]
    x = PATTERN_X * a - PATTERN_Y * b  # each product and the difference rounded to float32
    y = PATTERN_X * b + PATTERN_Y * a
    return np.rint(x).astype(np.int64), np.rint(y).astype(np.int64)  # rint: half to even


def descriptors(
    blurred: np.ndarray, xs: np.ndarray, ys: np.ndarray, angles: np.ndarray
) -> np.ndarray:
    """uint8 (N, 32): the rotated BRIEF descriptors sampled from the blurred image."""
    out = np.empty((len(xs), DESCRIPTOR_BYTES), dtype=np.uint8)
    for s in range(0, len(xs), CHUNK):
        a, b = cos_sin(angles[s : s + CHUNK])
        dx, dy = sample_offsets(a, b)
        v = blurred[ys[s : s + CHUNK, None] + dy, xs[s : s + CHUNK, None] + dx]
        out[s : s + CHUNK] = np.packbits(v[:, 0::2] < v[:, 1::2], axis=1, bitorder="little")
    return out


def orb_features(
    img: np.ndarray,
    threshold: int = DEFAULT_THRESHOLD,
    score: str = "opencv",
    nms: str = "3x3",
    cell: int | None = None,
    per_cell: int = 0,
) -> OrbFeatures:
    """The NMS's keypoints inside cv2.ORB's border, then (per_cell > 0) the budget of
    per_cell keypoints per cell x cell square (budget.py), with their angles and descriptors."""
    cell, per_cell = validate_budget(cell, per_cell)
    records = detect(img, threshold, score, nms)
    records = records[in_orb_border(records, img.shape)]
    if per_cell:
        records = cell_budget(records, cell, per_cell)
    if len(records) == 0:
        return OrbFeatures(
            records, np.zeros(0, np.float32), np.zeros((0, DESCRIPTOR_BYTES), np.uint8)
        )
    xs, ys = records[:, 0], records[:, 1]
    angles = ic_angle(img, xs, ys)
    return OrbFeatures(records, angles, descriptors(gaussian_blur(img), xs, ys, angles))


def detect_and_compute(
    img: np.ndarray,
    threshold: int = DEFAULT_THRESHOLD,
    score: str = "opencv",
    nms: str = "3x3",
    orb: bool = True,
    cell: int | None = None,
    per_cell: int = 0,
    nlevels: int = 1,
    scale_factor: float = DEFAULT_SCALE_FACTOR,
) -> tuple[tuple[cv2.KeyPoint, ...], np.ndarray | None]:
    """Keypoints and descriptors in OpenCV's own types, as cv2.ORB.detectAndCompute gives
    them: a tuple of cv2.KeyPoint and an (N, 32) uint8 array (also for N = 0, where OpenCV
    gives None), level by level, each level's sorted by y then x. With per_cell > 0, at
    most per_cell keypoints per cell x cell square of each level's own pixels (budget.py).

    nlevels > 1: cv2.ORB's image pyramid (pyramid.py): on level k the single-level model
    runs on the level's image; a keypoint's pt is its level position times scale_k in
    float32, its size 31 * scale_k, its octave k (cv2.ORB_create(nlevels, scaleFactor,
    edgeThreshold=31, patchSize=31, fastThreshold, ORB_FAST_SCORE) gives the same
    keypoints). A level narrower or lower than 63 pixels has none.

    With orb=False: every keypoint of the NMS (within the budget), as
    cv2.FastFeatureDetector gives them (size 7, angle -1; on level k pt times scale_k,
    size 7 * scale_k, octave k), and None for the descriptors.
    """
    validate_image(img)
    validate_threshold(threshold)
    validate_score(score)
    validate_nms(nms)
    cell, per_cell = validate_budget(cell, per_cell)
    nlevels, scale_factor = validate_levels(nlevels, scale_factor)
    keypoints: list[cv2.KeyPoint] = []
    described = []
    for level, image in enumerate(pyramid(img, nlevels, scale_factor)):
        scale = level_scale(level, scale_factor)
        if not orb:
            records = detect(image, threshold, score, nms)
            if per_cell:
                records = cell_budget(records, cell, per_cell)
            angles, size = np.full(len(records), -1.0, np.float32), np.float32(7) * scale
        else:
            f = level_features(image, threshold, score, nms, cell, per_cell)
            records, angles, size = f.records, f.angles, np.float32(PATCH_SIZE) * scale
            described.append(f.descriptors)
        xs = (records[:, 0].astype(np.float32) * scale).tolist()
        ys = (records[:, 1].astype(np.float32) * scale).tolist()
        keypoints += [
            cv2.KeyPoint(x, y, float(size), float(a), float(s), level, -1)
            for x, y, a, s in zip(xs, ys, angles.tolist(), records[:, 2].tolist(), strict=True)
        ]
    if not orb:
        return tuple(keypoints), None
    return tuple(keypoints), np.concatenate(described)


def level_features(
    image: np.ndarray,
    threshold: int = DEFAULT_THRESHOLD,
    score: str = "opencv",
    nms: str = "3x3",
    cell: int | None = None,
    per_cell: int = 0,
) -> OrbFeatures:
    """orb_features of one pyramid level; none on a level without room for the border."""
    h, w = image.shape
    if min(h, w) <= 2 * EDGE:
        return OrbFeatures(
            np.zeros((0, 3), np.int64),
            np.zeros(0, np.float32),
            np.zeros((0, DESCRIPTOR_BYTES), np.uint8),
        )
    return orb_features(image, threshold, score, nms, cell, per_cell)
