"""Correctly rounded float32 cos and sin of a float32 angle in [0, 2*pi], in integer arithmetic.

OpenCV's ORB computes a = (float)cos(x), b = (float)sin(x) with glibc's double cos and sin; for
every float32 x in [0, 2*pi] these are the correctly rounded float32 values. This module is the
bit-true integer model of a unit producing them: only integer operations (numpy uint64/int64,
vectorised) touch the data; the constants are derived at import time with Python integers.

Notation: a "word" is an unsigned 64-bit integer; mulhi(a, b) = floor(a * b / 2**64) is the
high half of the exact 128-bit product (here built from four 32x32 partial products, as a
hardware multiplier builds it from DSP tiles). u = 2**-64.

Algorithm (input: the float32 bit pattern, 0 .. 0x40C90FDB):

1. Tiny x (x < 2**-12, biased exponent < 115, subnormals and 0 included): cos = 1.0,
   sin = x, exactly so: 1 - cos x < x**2/2 < 2**-25, half the gap below 1.0, and
   0 <= x - sin x < x**3/6 < x * 2**-24 / 6, under half the gap to the float below x (a
   third of it, or two thirds when x is a power of two and the gap below is halved).
2. Quadrant: k = round(x / (pi/2)) in 0..4 from four comparisons of the bit pattern with the
   largest floats below (j + 1/2) * pi/2 (positive floats order like their bit patterns).
3. Reduction, r = x - k*pi/2, |r| <= pi/4, as a sign and a normalised word:
   |r| = M * 2**(E - 63), 2**63 <= M < 2**64, -27 <= E <= -1.
   - k = 0: r = x exactly: M = mantissa << 40 (24-bit mantissa), E = unbiased exponent.
   - k >= 1 (x >= pi/4, so x = X * 2**-24 with X an integer < 2**27): with
     K = round(k*pi/2 * 2**120) (123 bits) split as A * 2**96 + B, r * 2**120 =
     (X - A) * 2**96 - B. With d = X - A (|d| < 2**24): r > 0 iff d >= 1, and
     |r| * 2**120 = h * 2**96 + L with h = d - 1, L = 2**96 - B if d >= 1, else h = -d, L = B.
     So the wide subtraction reduces to a 27-bit one (X - A) and a choice among eight 96-bit
     constants L (k, sign of r). The 120-bit value h * 2**96 + L is normalised by the
     leading-zero count c of its top 56 bits (c in 8..34 over the domain: the smallest |r| is
     1.19e-8, at x = 0x4096CBE4 near 3*pi/2) and a left shift by c keeping 64 bits;
     E = 7 - c.
4. z = r**2 as a fixed-point word with 64 fraction bits: Z = mulhi(M, M) >> (-2E - 2)
   (right shift 0..52; z < 0.62).
5. Two Taylor polynomials in z, Horner with unsigned words (every partial value is positive,
   so no sign handling), coefficients round(2**64 / n!) (64-bit, the highest ones only a few
   bits wide):
   sin(r)/r = 1 - z*S(z), S = 1/3! - z(1/5! - z(... - z/19!)): T = S9; T = Sn - mulhi(Z, T)
   for n = 8..1; Y = mulhi(Z, T) ~ z/6. Then sin|r| = (M - mulhi(M, Y)) * 2**(E - 63),
   renormalised by at most one left shift (the factor 1 - z*S is in [0.90, 1]).
   cos(r) = 1 - z*C(z), C = 1/2! - z(1/4! - z(... - z/18!)): the same Horner; Yc ~ z/2 and
   cos r = (2**64 - Yc) * 2**-64, already normalised (cos r >= 0.707, E = -1).
6. Quadrant map: q = k mod 4 selects cos x, sin x among +-cos r, +-sin r.
7. Rounding: the top 24 bits of the 64-bit mantissa, rounded to nearest even on the other
   40; the float's exponent field is E + 127 (a carry out of the mantissa bumps it).

Word widths for sizing the hardware: input 32 bits; quadrant compare 4 x 31 bits; reduction
a 27-bit subtract (X - A, A a 27-bit constant per k) and a 96-bit constant L out of 8;
leading-zero count over 56 bits and a left shift by 8..34 of the 120-bit h * 2**96 + L,
keeping 64 bits (for k = 0 a fixed shift of the 24-bit mantissa); z: a right shift by
0..52; every multiply is 64 x 64 -> high 64 unsigned, the exact floor (all partial products
summed; 12 DSP48E2 tiles of 26 x 17 unsigned); rounding: a 64-bit mantissa to 24 bits plus an
8-bit exponent. Constants: 4 quadrant thresholds (32 bits), 4 x 27 + 8 x 96 bits for the
reduction, 18 Taylor coefficients (704 bits in all: the high-order ones are narrow, 8 to 40
bits, so the first Horner steps could use a smaller multiplier); no table of function values.

Multiplies: 1 (z) + 9 (Horner, sin) + 1 (M * Y) + 9 (Horner, cos) = 20 high-part products.
The two Horner chains are independent, so a single pipelined multiplier can interleave them:
the dependent depth is 11 products (z, 9 Horner steps, M * Y), i.e. ~20 issue clocks or
11 * latency, whichever is larger (with a 3-4 clock multiplier, ~35-45 clocks for cos + sin).

Error bound (in u = 2**-64, relative unless stated): |r| has error < 2u (truncation of the
normalised word, plus 2**-121 absolute from K against |r| >= 2**-27); Z is within 4.5
units of z * 2**64; the coefficient rounding (0.5) and each mulhi floor (1) are damped by
z < 0.62 along Horner, so T stays within 4.1 units of the exact value, Y within 4.3 and Yc
within 6.0 units; the Taylor remainders are z**10/21! < 0.005u and z**10/20! < 0.06u. Hence
sin|r| is within (2 + 4.7 + 2.2)u = 8.9u relative (the last term the floor of M * Y) and
cos r within 6.1u / 0.707 = 8.6u relative. A float32's ulp is more than 2**-24 of its value,
so every result is within 8.9 * 2**-40 = 2**-36.8 ulp of the exact value. No input of the
domain is that close to a rounding midpoint (the closest is 1.7e-9 = 2**-29.1 ulp away, none
is closer than 2**-32 ulp), so the rounding is correct everywhere without an exception table;
the exhaustive test confirms it against the C library, and a high-precision reference in the
tests measures the error before rounding (at most ~2**-38.6 ulp on its samples).
"""

from __future__ import annotations

import numpy as np

X_MAX_BITS = 0x40C90FDB  # the float32 closest to 2*pi (slightly above it): the last input
TINY_BITS = 0x39800000  # 2**-12: below it cos rounds to 1 and sin to x
ONE_BITS = 0x3F800000
BLOCK = 1 << 16  # elements per internal pass: the working set stays in the CPU cache

_M32 = np.uint64(0xFFFFFFFF)
_U32 = np.uint64(32)
_U40 = np.uint64(40)


# ---- constants (derived at import with Python integers) ----------------------------------


def _atan_inv(n: int, bits: int) -> int:
    """atan(1/n) * 2**bits by its Taylor series, to within (number of terms) units."""
    total, power, k, sign = 0, (1 << bits) // n, 1, 1
    while power:
        total += sign * (power // k)
        power //= n * n
        k += 2
        sign = -sign
    return total


_PI_BITS = 256
# pi * 2**256 by Machin's formula (pi = 16 atan(1/5) - 4 atan(1/239)): error < 2**-240.
_PI = 16 * _atan_inv(5, _PI_BITS) - 4 * _atan_inv(239, _PI_BITS)
assert _PI >> (_PI_BITS - 60) == 0x3243F6A8885A308D  # the well-known hex digits of pi


def _scaled(num: int, den: int, bits: int) -> int:
    """round(num * pi / den * 2**bits)."""
    return (num * _PI * 2 ** (bits + 1) // (den * 2**_PI_BITS) + 1) // 2


def _float_below(num: int, den: int) -> int:
    """Bit pattern of the largest float32 <= num * pi / den (a normal number > 0.5)."""
    v = _scaled(num, den, 200)  # num*pi/den * 2**200, far finer than a float32 ulp
    e = v.bit_length() - 1 - 200
    mant = v >> (e + 200 - 23)
    return ((e + 127) << 23) | (mant - (1 << 23))


# k = round(x / (pi/2)) = number of thresholds (j + 1/2) * pi/2, j = 0..3, below x.
_THRESHOLDS = tuple(_float_below(2 * j + 1, 4) for j in range(4))

# Reduction: K_k = round(k*pi/2 * 2**120) = A_k * 2**96 + B_k. Index k (0 unused).
_K = [_scaled(k, 2, 120) for k in range(5)]
_A = np.array([kk >> 96 for kk in _K], dtype=np.int64)
_B = [kk & ((1 << 96) - 1) for kk in _K]
# L for r > 0 (2**96 - B) and r < 0 (B), as the top 32 bits and the low 64 bits.
_L_POS = [(1 << 96) - b for b in _B]
_L_HI = np.array([[b >> 64 for b in _B], [lp >> 64 for lp in _L_POS]], dtype=np.uint64)
_L_LO = np.array(
    [[b & (2**64 - 1) for b in _B], [lp & (2**64 - 1) for lp in _L_POS]], dtype=np.uint64
)

_DEGREE = 9  # Taylor terms up to z**9: r**19/19! for sin, r**18/18! for cos


def _coefficient(n: int) -> np.uint64:
    """round(2**64 / n!)."""
    f = 1
    for i in range(2, n + 1):
        f *= i
    return np.uint64((2**65 // f + 1) // 2)


_SIN_C = tuple(_coefficient(2 * n + 1) for n in range(1, _DEGREE + 1))  # 1/3!, 1/5!, ...
_COS_C = tuple(_coefficient(2 * n) for n in range(1, _DEGREE + 1))  # 1/2!, 1/4!, ...


# ---- integer building blocks -------------------------------------------------------------


def _mulhi(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """floor(a * b / 2**64) for uint64 words, from four 32 x 32 -> 64 partial products."""
    a1, a0 = a >> _U32, a & _M32
    b1, b0 = b >> _U32, b & _M32
    p01 = a0 * b1
    p10 = a1 * b0
    # The middle column: three 32-bit pieces, < 3 * 2**32, no overflow.
    mid = ((a0 * b0) >> _U32) + (p01 & _M32) + (p10 & _M32)
    return a1 * b1 + (p01 >> _U32) + (p10 >> _U32) + (mid >> _U32)


def _clz(v: np.ndarray) -> np.ndarray:
    """Leading-zero count of nonzero uint64 words (a six-stage priority encoder)."""
    n = np.zeros(v.shape, dtype=np.uint64)
    for width in (32, 16, 8, 4, 2, 1):
        w = np.uint64(width)
        empty = (v >> np.uint64(64 - width)) == 0
        v = np.where(empty, v << w, v)
        n += empty * w
    return n


def _horner(z: np.ndarray, coefficients: tuple[np.uint64, ...]) -> np.ndarray:
    """z * P(z) for P = c1 - z(c2 - z(... - z c9)), every partial value positive."""
    t = np.full(z.shape, coefficients[-1], dtype=np.uint64)
    for c in coefficients[-2::-1]:
        t = c - _mulhi(z, t)
    return _mulhi(z, t)


# ---- the unit ------------------------------------------------------------------------------


def _validate(x_bits: object) -> np.ndarray:
    x = np.asarray(x_bits)
    if x.dtype.kind not in "iu":
        raise ValueError(f"x_bits must hold integer float32 bit patterns, got dtype {x.dtype}")
    if x.size and (x.min() < 0 or x.max() > X_MAX_BITS):
        raise ValueError(
            f"x_bits must be float32 bit patterns of 0 <= x <= 2*pi (0..{X_MAX_BITS:#010x}), "
            f"got {int(x.min()):#x}..{int(x.max()):#x}"
        )
    return x


def _reduce(x: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Steps 2-3 for x >= 2**-12 (uint64 bit patterns): k, r < 0, M, E (int64)."""
    k = sum((x > np.uint64(t)).astype(np.int64) for t in _THRESHOLDS)
    e = (x >> np.uint64(23)).astype(np.int64)  # biased exponent, 115..129
    mant = (x & np.uint64(0x7FFFFF)) | np.uint64(0x800000)

    # k >= 1: x >= pi/4 has biased exponent >= 126, X = x * 2**24 = mant << (e - 126).
    big = np.maximum(e - 126, 0).astype(np.uint64)
    d = (mant << big).astype(np.int64) - _A[k]
    pos = d >= 1
    h = np.where(pos, d - 1, -d).astype(np.uint64)
    sel = pos.astype(np.int64)
    hi = (h << _U32) | _L_HI[sel, k]  # the top 56 of the 120 bits of |r| * 2**120
    lo = _L_LO[sel, k]
    c = _clz(hi)
    m_red = (hi << c) | (lo >> (np.uint64(64) - c))
    e_red = 7 - c.astype(np.int64)

    small = k == 0  # r = x exactly
    m = np.where(small, mant << _U40, m_red)
    exp = np.where(small, e - 127, e_red)
    neg = ~small & ~pos
    return k, neg, m, exp


def cos_sin_unrounded(x_bits: np.ndarray) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
    """The unit before its final rounding, for x >= 2**-12 (step 1 not applied).

    Returns ((sign, M, E) for cos x, (sign, M, E) for sin x): |value| = M * 2**(E - 63) with
    2**63 <= M < 2**64 (uint64), sign 1 for negative (uint64), E int64.
    """
    x = np.asarray(x_bits).astype(np.uint64)
    k, neg, m, exp = _reduce(x)

    z = _mulhi(m, m) >> (-2 * exp - 2).astype(np.uint64)
    # sin|r| = r (1 - z S(z)): the product keeps the relative precision of r.
    ms = m - _mulhi(m, _horner(z, _SIN_C))
    low = ms < np.uint64(1 << 63)  # 1 - zS >= 0.90: at most one bit lost
    ms = np.where(low, ms << np.uint64(1), ms)
    es = exp - low
    # cos r = 1 - z C(z) in [0.707, 1): z C > 0 since |r| >= 1.2e-8 over the domain.
    mc = np.uint64(0) - _horner(z, _COS_C)
    ec = np.full(x.shape, -1, dtype=np.int64)

    q = k & 3
    odd = (q & 1).astype(bool)
    neg_u = neg.astype(np.uint64)
    # cos x: q0 +cos r, q1 -sin r, q2 -cos r, q3 +sin r; sin x: q0 +sin r, q1 +cos r,
    # q2 -sin r, q3 -cos r; sin r carries the sign of r.
    cos_sign = ((q == 1) | (q == 2)).astype(np.uint64) ^ (odd * neg_u)
    sin_sign = (q >= 2).astype(np.uint64) ^ (~odd * neg_u)
    cos_part = (cos_sign, np.where(odd, ms, mc), np.where(odd, es, ec))
    sin_part = (sin_sign, np.where(odd, mc, ms), np.where(odd, ec, es))
    return cos_part, sin_part


def _round(sign: np.ndarray, m: np.ndarray, exp: np.ndarray) -> np.ndarray:
    """Step 7: float32 bits of (-1)**sign * M * 2**(E - 63), round to nearest even."""
    top = m >> _U40
    rest = m & np.uint64((1 << 40) - 1)
    half = np.uint64(1 << 39)
    up = (rest > half) | ((rest == half) & (top & np.uint64(1)).astype(bool))
    # top + up is in 2**23 .. 2**24: the carry out of the mantissa adds to the exponent.
    biased = (exp + 126).astype(np.uint64) << np.uint64(23)
    return ((sign << np.uint64(31)) + biased + top + up).astype(np.uint32)


def cos_sin(x_bits: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Correctly rounded float32 cos and sin of float32 angles x, 0 <= x <= 2*pi.

    x_bits: integer array of float32 bit patterns (0 .. X_MAX_BITS). Returns (cos_bits,
    sin_bits), uint32 arrays of x_bits' shape. Raises ValueError outside the domain.
    """
    x = _validate(x_bits)
    shape = x.shape
    x = x.reshape(-1).astype(np.uint64)
    cos_out = np.empty(x.size, dtype=np.uint32)
    sin_out = np.empty(x.size, dtype=np.uint32)
    for start in range(0, x.size, BLOCK):
        xb = x[start : start + BLOCK]
        (cs, cm, ce), (ss, sm, se) = cos_sin_unrounded(np.maximum(xb, np.uint64(TINY_BITS)))
        tiny = xb < np.uint64(TINY_BITS)
        cos_out[start : start + xb.size] = np.where(tiny, ONE_BITS, _round(cs, cm, ce))
        sin_out[start : start + xb.size] = np.where(tiny, xb, _round(ss, sm, se))
    return cos_out.reshape(shape), sin_out.reshape(shape)
