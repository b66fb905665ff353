"""Bit-true integer model of the float32 steps of OpenCV's ORB orientation and rotation.

The hardware has to reproduce OpenCV's float32 results exactly, so this module computes
IEEE-754 binary32 arithmetic (round to nearest, ties to even) with integer operations only,
the way a hardware unit does: unpack sign, exponent and 24-bit significand, multiply /
align and add / divide into quotient and remainder, normalise, round with guard, round and
sticky bits, repack. Everything is vectorised over numpy int64 arrays.

Values are float32 bit patterns: inputs are any integer arrays (or ints) holding patterns
in 0 .. 2**32 - 1 (uint32 or int64), outputs are np.uint32 arrays (``.view(np.float32)``
gives the float). Zeros, normal and subnormal numbers are exact IEEE (signed zeros and
gradual underflow included), an overflowing result is +-inf. Inf or NaN operands and
division by zero raise ValueError / ZeroDivisionError: none of them can occur in ORB.
Subnormals cannot occur in ORB either (ranges below); the model handles them only so that it
equals IEEE on every finite input. The hardware needs no subnormal or overflow path.

Word widths for a hardware implementation, from the ranges of the ORB steps (moments
|m| <= 624240 < 2**20, pattern coordinates -13 .. 12, |cos|, |sin| <= 1); e below is the
unbiased exponent, and golden/tests/test_float32.py checks these ranges on its inputs.

- from_int: |m| < 2**20, a 20-bit leading-zero count and left shift into the significand;
  e in 0 .. 19.
- fast_atan2, divide: c = min(|m01|, |m10|) / max(...) in [1/624240, 1], e in -20 .. 0.
  Significands normalised to [2**23, 2**24), so the quotient (num << 25) // den lies in
  [2**24, 2**26): 26 quotient bits (25 or 26 significant, so guard bit always present) and
  remainder != 0 as the sticky bit. The quotient of two 24-bit significands is never an
  exact tie.
- fast_atan2, multiplies: 24 x 24 -> 48-bit products; c2 = c*c has e in -39 .. 0.
- fast_atan2, adds: every add is a constant minus a smaller magnitude: p5 + p7*c2 (8.91
  minus 0 .. 2.54), p3 + t*c2 (-18.67 plus 0 .. 8.91), p1 + t*c2 (57.28 minus 0 .. 18.67),
  90 - a (a <= 45), 180 - a (a <= 90), 360 - a (a <= 180). So no operand swap, alignment
  shift >= 1 (>= 2 for p5) and results at least half the constant: the normalisation is
  at most one bit to the left. Shifts of 26 and more only feed the sticky bit, so the
  shifter saturates at 26. The output is in [0, 360): it is 0 only for m01 = 0 <= m10,
  otherwise at least 9.18e-5 (at m01 = 1, m10 = 624240), and 360 - a rounds to 360 only
  for a <= 2**-16.
- to_radians: 24 x 24 -> 48-bit product; degrees e in -14 .. 8, radians e in -20 .. 2.
- rotate: |px|, |py| <= 13 have 4 significant bits, so px*a is a 24 x 4 -> 28-bit product
  with e <= 3. The add/subtract has both operands of either sign: swap by magnitude, align
  by 0 .. 26 (saturating), a 27-bit adder (24 bits, guard, round, carry) plus sticky, and,
  because px*a and py*b can cancel completely, a 27-bit leading-zero count. |x| <= 26,
  e <= 4. cvRound then shifts right by 19 .. 25 (saturating) with guard and sticky. The
  float rounding of x matters: it can land exactly on a half (11.4999999 -> 11.5 -> 12).
  cos and sin of the angles ORB produces (0 or 1.6e-6 .. 6.3 rad) are 0 or at least
  1.19e-8 > 2**-27 in magnitude, so no product or sum comes near the subnormals.
"""

from __future__ import annotations

import numpy as np

# atan_f32's constants: the float literal times (float)(180/CV_PI), rounded to float32.
#   0.9997878412794807f  * 57.29578f = 57.283627f  (p1)
#   -0.3258083974640975f * 57.29578f = -18.667446f (p3)
#   0.1555786518463281f  * 57.29578f = 8.9140005f  (p5)
#   -0.04432655554792128f * 57.29578f = -2.5397246f (p7)
ATAN2_P1 = 0x4265226F
ATAN2_P3 = 0xC19556EE
ATAN2_P5 = 0x410E9FBF
ATAN2_P7 = 0xC0228AD9
DEG_TO_RAD = 0x3C8EFA35  # (float)(CV_PI/180.f) = 0.017453292f
F90, F180, F360 = 0x42B40000, 0x43340000, 0x43B40000  # 90.f, 180.f, 360.f
ONE = 0x3F800000

SIGNIFICAND_BITS = 24
GUARD_BITS = 2  # extra bits kept by the adder below the significand (guard, round)
ALIGN_MAX = SIGNIFICAND_BITS + GUARD_BITS  # larger alignment shifts only feed the sticky bit
QUOTIENT_SHIFT = 25  # dividend << 25 gives a 25- or 26-bit quotient of two significands
MAX_INT = 2**31 - 1  # from_int and cv_round work on C ints
_SHIFT_MAX = 62  # clamp for variable shifts in int64; every significand product is < 2**48
_POWERS_OF_TWO = np.int64(1) << np.arange(63, dtype=np.int64)


def _bits(x: object) -> np.ndarray:
    """Bit patterns as int64, checked to be finite float32 patterns."""
    b = np.asarray(x)
    if not np.issubdtype(b.dtype, np.integer):
        raise TypeError(f"float32 bit patterns must be integers, got dtype {b.dtype}")
    b = b.astype(np.int64)
    if np.any((b < 0) | (b > 0xFFFFFFFF)):
        raise ValueError("float32 bit patterns must lie in 0 .. 2**32 - 1")
    if np.any((b & 0x7F800000) == 0x7F800000):
        raise ValueError("inf or NaN operand: not part of the modelled float32 domain")
    return b


def _unpack(b: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(sign, significand, scale) with value = (-1)**sign * significand * 2**scale."""
    e = (b >> 23) & 0xFF
    f = b & 0x7FFFFF
    m = np.where(e > 0, f | 0x800000, f)  # subnormals have no hidden one
    return b >> 31, m, np.maximum(e, 1) - 150


def _bit_length(q: np.ndarray) -> np.ndarray:
    """Position of the leading one plus one (0 for 0), for 0 <= q < 2**63: a priority
    encoder, here a binary search of q among the powers of two (integer compares only)."""
    return np.searchsorted(_POWERS_OF_TWO, q, side="right")


def _shift_round(q: np.ndarray, r: np.ndarray, sticky: np.ndarray | bool) -> np.ndarray:
    """q >> r rounded to nearest even; sticky says that something nonzero lies below q."""
    kept = q >> r
    dropped = q & ((1 << r) - 1)
    half = (1 << r) >> 1  # the guard bit; 0 when nothing is dropped
    tie = (dropped == half) & (r > 0)
    up = (dropped > half) | (tie & (sticky | ((kept & 1) == 1)))
    return kept + up


def _round(
    sign: np.ndarray, q: np.ndarray, scale: np.ndarray, sticky: np.ndarray | bool = False
) -> np.ndarray:
    """Bit pattern of (-1)**sign * (q + f) * 2**scale rounded to binary32, where 0 <= f < 1
    and f > 0 exactly when sticky. Callers keep at least one bit below the significand
    (q >= 2**24) whenever sticky is set, so the guard bit is in q."""
    n = _bit_length(q)
    e = scale + n + 126  # biased exponent of the leading one
    sh = n - SIGNIFICAND_BITS + np.maximum(1 - e, 0)  # subnormals keep fewer bits
    right = np.minimum(np.maximum(sh, 0), _SHIFT_MAX)
    kept = _shift_round(q << np.maximum(-sh, 0), right, sticky)
    # The hidden one of kept adds 1 to the exponent field, and a carry out of the
    # significand on rounding (kept = 2**24) carries into the exponent as it should.
    mag = ((np.maximum(e, 1) - 1) << 23) + kept
    mag = np.where(q == 0, 0, np.minimum(mag, 0x7F800000))  # overflow -> inf
    return ((sign << 31) | mag).astype(np.uint32)


def from_int(i: object) -> np.ndarray:
    """(float)i for integers |i| <= 2**31 - 1; exact for |i| < 2**24."""
    v = np.asarray(i)
    if not np.issubdtype(v.dtype, np.integer):
        raise TypeError(f"from_int needs integers, got dtype {v.dtype}")
    v = v.astype(np.int64)
    if np.any(np.abs(v) > MAX_INT):
        raise ValueError("from_int models (float) of a C int: |i| <= 2**31 - 1")
    return _round((v < 0).astype(np.int64), np.abs(v), np.zeros_like(v))


def mul(a: object, b: object) -> np.ndarray:
    """a * b: the exact 48-bit significand product, rounded once."""
    sa, ma, ta = _unpack(_bits(a))
    sb, mb, tb = _unpack(_bits(b))
    return _round(sa ^ sb, ma * mb, ta + tb)


def add(a: object, b: object) -> np.ndarray:
    """a + b: align the smaller magnitude to the larger with guard, round and sticky bits."""
    a, b = _bits(a), _bits(b)
    swap = (a & 0x7FFFFFFF) < (b & 0x7FFFFFFF)
    sl, ml, tl = _unpack(np.where(swap, b, a))
    ss, ms, ts = _unpack(np.where(swap, a, b))
    d = np.minimum(tl - ts, ALIGN_MAX)
    small = ms << GUARD_BITS
    aligned = small >> d
    sticky = (small & ((1 << d) - 1)) != 0
    # Bits lost to the sticky bit mean d > GUARD_BITS, so the larger operand is normal and
    # q keeps at least 25 bits: the guard bit stays in q. On a subtraction the lost bits
    # borrow one from q and leave a nonzero fraction, hence "- sticky".
    big = ml << GUARD_BITS
    q = np.where(sl == ss, big + aligned, big - aligned - sticky)
    # Exact zero: -0 only for (-0) + (-0); x + (-x) is +0 when rounding to nearest.
    sign = np.where(q == 0, (a >> 31) & (b >> 31), sl)
    return _round(sign, q, tl - GUARD_BITS, sticky)


def sub(a: object, b: object) -> np.ndarray:
    """a - b = a + (-b)."""
    return add(a, _bits(b) ^ 0x80000000)


def div(a: object, b: object) -> np.ndarray:
    """a / b: normalised significands, (ma << 25) // mb as a 26-bit quotient, remainder as
    the sticky bit. Raises ZeroDivisionError for b = +-0 (inf or NaN in IEEE)."""
    sa, ma, ta = _unpack(_bits(a))
    sb, mb, tb = _unpack(_bits(b))
    if np.any(mb == 0):
        raise ZeroDivisionError("float32 division by zero is outside the modelled domain")
    ma, ta = _normalise(ma, ta)
    mb, tb = _normalise(mb, tb)
    q, r = np.divmod(ma << QUOTIENT_SHIFT, mb)
    return _round(sa ^ sb, q, ta - tb - QUOTIENT_SHIFT, r != 0)


def _normalise(m: np.ndarray, scale: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Shift subnormal significands up to [2**23, 2**24) (zero stays zero)."""
    s = np.where(m == 0, 0, SIGNIFICAND_BITS - _bit_length(m))
    return m << s, scale - s


def cv_round(x: object) -> np.ndarray:
    """cvRound(float): nearest integer, ties to even (SSE2 cvtss2si), as int64.
    |x| must be below 2**31, the range of the C int result."""
    s, m, t = _unpack(_bits(x))
    if np.any(t > 7):  # m * 2**t < 2**31 needs t <= 7
        raise ValueError("cv_round: |x| >= 2**31 does not fit a C int")
    v = np.where(t >= 0, m << np.maximum(t, 0), _shift_round(m, np.minimum(-t, _SHIFT_MAX), False))
    return np.where(s == 1, -v, v)


def fast_atan2(m01: object, m10: object) -> np.ndarray:
    """cv::fastAtan2((float)m01, (float)m10) in degrees, as float32 bits, for integer
    moments (|m| <= 2**31 - 1; the word widths above assume |m| <= 624240).

    atan_f32 divides by ax + (float)DBL_EPSILON, with DBL_EPSILON = 2**-52. For an integer
    ax >= 1 that sum rounds back to ax (half an ulp of ax is at least 2**-24), and ax = 0
    in the branch ax >= ay means ay = 0 too, where 0 / 2**-52 = +0. So the model divides
    min(|m01|, |m10|) by max(...) and gives 0/0 the quotient +0.
    """
    m01, m10 = np.asarray(m01), np.asarray(m10)
    ay = from_int(m01) & np.uint32(0x7FFFFFFF)
    ax = from_int(m10) & np.uint32(0x7FFFFFFF)
    ge = ax >= ay  # bit patterns of non-negative floats compare like the values
    num, den = np.where(ge, ay, ax), np.where(ge, ax, ay)
    c = np.where(den == 0, np.uint32(0), div(num, np.where(den == 0, ONE, den)))
    c2 = mul(c, c)
    t = ATAN2_P7
    for p in (ATAN2_P5, ATAN2_P3, ATAN2_P1):
        t = add(mul(t, c2), p)
    a = mul(t, c)
    a = np.where(ge, a, sub(F90, a))
    a = np.where(m10 < 0, sub(F180, a), a)
    return np.where(m01 < 0, sub(F360, a), a).astype(np.uint32)


def to_radians(deg: object) -> np.ndarray:
    """angle *= (float)(CV_PI/180.f), as in computeOrbDescriptor."""
    return mul(deg, DEG_TO_RAD)


def rotate(px: object, py: object, a: object, b: object) -> tuple[np.ndarray, np.ndarray]:
    """ORB's rotated pattern point: cvRound(px*a - py*b), cvRound(px*b + py*a), every
    product and sum rounded to float32 (no FMA), for integer px, py and float32 bits a =
    cos, b = sin. Arguments broadcast, e.g. (512,) points against (K, 1) keypoints."""
    fx, fy = from_int(px), from_int(py)
    x = sub(mul(fx, a), mul(fy, b))
    y = add(mul(fx, b), mul(fy, a))
    return cv_round(x), cv_round(y)
