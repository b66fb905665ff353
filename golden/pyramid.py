"""cv2.ORB's image pyramid, exactly (docs/pyramid.md): the level sizes and scales, and
OpenCV's bit-exact bilinear resize (`cv2.resize(..., interpolation=cv2.INTER_LINEAR_EXACT)`)
as a bit-true integer model, the one the RTL resizer follows.

Levels (OpenCV's orb.cpp, `getScale` and the pyramid of `ORB_Impl::detectAndCompute`):
level k of an nlevels pyramid has `scale_k = (float)pow((double)1.2f, k)` (float32) and the
size `(cvRound(W * (1.0f / scale_k)), cvRound(H * (1.0f / scale_k)))`, the products in
float32, cvRound half to even; level k is level k-1 resized to that size (chained: each
step has its own ratio).

The resize (OpenCV's resize.cpp, `resize_bitExact` with `interpolationLinear`, 8-bit
images). For a source of n pixels along an axis and a destination of d:
- `inv = RN(d / n)` and `scale = RN(1 / inv)` in IEEE double (OpenCV: `(double)d / n`,
  then `softdouble` 1 / inv); for each destination index i,
  `f = RN(RN(scale * (i + 0.5)) - 0.5)`, `o = floor(f)`, `c1 = round_half_even((f - o) *
  256)`, `c0 = 256 - c1`: the two source pixels o, o+1 weigh c0 and c1 (ufixedpoint16: 8
  fractional bits). An index with o < 0 (or a 1-pixel source) takes pixel 0 alone, one with
  o >= n-1 pixel n-1 alone: as weights (256, 0) on a clamped position.
- a destination pixel is `(sum over the 2 x 2 source pixels of cy * cx * p + 2**15) >> 16`:
  OpenCV's horizontal pass keeps `cx0 * p0 + cx1 * p1` exact in 16 bits and its vertical
  pass rounds once, so the order of the passes does not matter.

Here every IEEE double step is done on integers (RN: round to nearest, ties to even, to a
53-bit significand); no float is used. The result equals cv2.resize with
INTER_LINEAR_EXACT (tests: golden/tests/test_pyramid.py). Upscaling follows the same rule
(it is OpenCV's), but the RTL resizer only shrinks.
"""

from __future__ import annotations

import math
from typing import NamedTuple

import numpy as np

from .fast import validate_image

DEFAULT_SCALE_FACTOR = 1.2
MAX_LEVELS = 32  # far beyond any use: cv2.ORB's default is 8
COEF_BITS = 8  # ufixedpoint16's fractional bits (one pass)
COEF_ONE = 1 << COEF_BITS
_SIGNIFICAND = 53  # IEEE binary64


# ---- IEEE double steps on integers ------------------------------------------------------


class Double(NamedTuple):
    """The IEEE double m * 2**e (m signed, |m| < 2**53; 0 is m = 0)."""

    m: int
    e: int

    def ratio(self) -> tuple[int, int]:
        """The exact value as (numerator, denominator), the denominator a power of two."""
        return (self.m << self.e, 1) if self.e >= 0 else (self.m, 1 << -self.e)


def round_double(num: int, den: int) -> Double:
    """RN(num / den) to a double (den > 0): the nearest value with a 53-bit significand,
    ties to the even significand (no subnormals: the values here are far from them)."""
    if den <= 0:
        raise ValueError("den must be positive")
    if num == 0:
        return Double(0, 0)
    sign, num = (-1, -num) if num < 0 else (1, num)
    # e such that 2**52 <= num / den / 2**e < 2**53.
    e = num.bit_length() - den.bit_length() - _SIGNIFICAND
    while True:
        q, r = divmod(num << -e, den) if e < 0 else divmod(num, den << e)
        if q >= 1 << _SIGNIFICAND:
            e += 1
        elif q < 1 << (_SIGNIFICAND - 1):
            e -= 1
        else:
            break
    d = den << e if e > 0 else den  # the remainder's scale
    if 2 * r > d or (2 * r == d and q & 1):
        q += 1
        if q == 1 << _SIGNIFICAND:
            q, e = q >> 1, e + 1
    return Double(sign * q, e)


def _scale(src: int, dst: int) -> Double:
    """OpenCV's `scale = 1 / inv_scale` of one axis, inv_scale = (double)dst / src."""
    inv = round_double(dst, src)
    num, den = inv.ratio()
    return round_double(den, num)


def axis_taps(src: int, dst: int) -> tuple[np.ndarray, np.ndarray]:
    """For each of the `dst` destination indices along an axis of `src` pixels: the first
    source index (int64, clamped into 0..src-1) and its weight c0 (int64, 0..256; the next
    pixel weighs 256 - c0), as OpenCV's interpolationLinear::getCoeffs computes them."""
    src, dst = int(src), int(dst)
    if src < 1 or dst < 1:
        raise ValueError(f"sizes must be at least 1, got {src} -> {dst}")
    s_num, s_den = _scale(src, dst).ratio()
    offsets = np.empty(dst, dtype=np.int64)
    weights = np.empty(dst, dtype=np.int64)
    for i in range(dst):
        # t = RN(scale * (i + 0.5)); f = RN(t - 0.5)
        t_num, t_den = round_double(s_num * (2 * i + 1), 2 * s_den).ratio()
        f_num, f_den = round_double(2 * t_num - t_den, 2 * t_den).ratio()
        o = f_num // f_den  # floor
        if o < 0 or src == 1:
            offsets[i], weights[i] = 0, COEF_ONE
        elif o >= src - 1:
            offsets[i], weights[i] = src - 1, COEF_ONE
        else:
            # c1 = cvRound((f - o) * 256): the fraction is exact, times 256 exact.
            frac = (f_num - o * f_den) * COEF_ONE
            c1, rest = divmod(frac, f_den)
            if 2 * rest > f_den or (2 * rest == f_den and c1 & 1):
                c1 += 1
            offsets[i], weights[i] = o, COEF_ONE - c1
    return offsets, weights


def resize_linear_exact(img: np.ndarray, width: int, height: int) -> np.ndarray:
    """`cv2.resize(img, (width, height), interpolation=cv2.INTER_LINEAR_EXACT)` of a 2-D
    uint8 image, in integers."""
    img = validate_image(img)
    h, w = img.shape
    xo, xc = axis_taps(w, width)
    yo, yc = axis_taps(h, height)
    p = img.astype(np.int64)
    x1 = np.minimum(xo + 1, w - 1)  # weighs 0 where clamped
    y1 = np.minimum(yo + 1, h - 1)
    rows = xc * p[:, xo] + (COEF_ONE - xc) * p[:, x1]  # (h, width): exact, < 2**16
    both = yc[:, None] * rows[yo] + (COEF_ONE - yc)[:, None] * rows[y1]
    return ((both + (1 << (2 * COEF_BITS - 1))) >> (2 * COEF_BITS)).astype(np.uint8)


# ---- the levels -------------------------------------------------------------------------


def validate_levels(nlevels: object, scale_factor: object) -> tuple[int, float]:
    """(nlevels, scale_factor) checked: nlevels an integer 1..MAX_LEVELS, scale_factor a
    number > 1 (cv2.ORB refuses <= 1); else ValueError."""
    if isinstance(nlevels, bool) or not isinstance(nlevels, int | np.integer):
        raise ValueError(f"levels must be an integer in 1..{MAX_LEVELS}, got {nlevels!r}")
    if not 1 <= nlevels <= MAX_LEVELS:
        raise ValueError(f"levels must be an integer in 1..{MAX_LEVELS}, got {nlevels}")
    if isinstance(scale_factor, bool) or not isinstance(scale_factor, int | float | np.floating):
        raise ValueError(f"scale factor must be a number above 1, got {scale_factor!r}")
    if not math.isfinite(scale_factor) or not float(np.float32(scale_factor)) > 1.0:
        raise ValueError(f"scale factor must be a number above 1, got {scale_factor}")
    return int(nlevels), float(scale_factor)


def level_scale(level: int, scale_factor: float = DEFAULT_SCALE_FACTOR) -> np.float32:
    """cv2.ORB's getScale: `(float)pow((double)(float)scale_factor, level)`."""
    return np.float32(math.pow(float(np.float32(scale_factor)), level))


def level_size(
    width: int, height: int, level: int, scale_factor: float = DEFAULT_SCALE_FACTOR
) -> tuple[int, int]:
    """(width, height) of a level: cvRound(W * (1.0f / scale)) in float32, half to even."""
    inv = np.float32(1) / level_scale(level, scale_factor)
    return int(np.rint(np.float32(width) * inv)), int(np.rint(np.float32(height) * inv))


def pyramid(
    img: np.ndarray, nlevels: int, scale_factor: float = DEFAULT_SCALE_FACTOR
) -> list[np.ndarray]:
    """The nlevels level images (level 0 is img itself), each the previous one resized
    with INTER_LINEAR_EXACT to its level_size. A level of 0 pixels along an axis ends
    the list early (cv2.ORB would fail there; such a level has no keypoints anyway)."""
    img = validate_image(img)
    nlevels, scale_factor = validate_levels(nlevels, scale_factor)
    h, w = img.shape
    levels = [img]
    for k in range(1, nlevels):
        lw, lh = level_size(w, h, k, scale_factor)
        if lw < 1 or lh < 1:
            break
        levels.append(resize_linear_exact(levels[-1], lw, lh))
    return levels
