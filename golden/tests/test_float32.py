"""The integer float32 model (golden/float32.py) against IEEE float32 as numpy computes it
(each numpy float32 operation is rounded to nearest even, no FMA) and against OpenCV's
cv2.fastAtan2, which is the scalar atan_f32. Every comparison is on exact bit patterns.

cv2.fastAtan2 costs about 0.65 us per call from Python, so even the slow suite compares all
its 3.4e7 pairs against OpenCV itself rather than against a float32 reimplementation.
"""

from __future__ import annotations

import re
from collections.abc import Callable
from fractions import Fraction

import cv2
import numpy as np
import pytest
from fastnms.golden import float32 as fm

F32 = np.float32
SIGN = 0x80000000
M_MAX = 624240  # largest |moment| of ORB's 31-pixel patch
ONE = fm.ONE
SPECIALS = np.array(
    [
        0x00000000,  # +0
        0x80000000,  # -0
        0x00000001,  # smallest subnormal
        0x007FFFFF,  # largest subnormal
        0x00800000,  # smallest normal
        0x00800001,
        0x3F800000,  # 1
        0x3F800001,  # 1 + ulp
        0x3F7FFFFF,  # 1 - ulp/2
        0x3FFFFFFF,  # 2 - ulp
        0x3FC00000,  # 1.5
        0x40400000,  # 3
        0x3DCCCCCD,  # 0.1
        0x4B800000,  # 2**24
        0x4B7FFFFF,  # 2**24 - 1
        0x33800000,  # 2**-24
        0x7F7FFFFF,  # largest finite
        0x7F000000,  # 2**127
        0x1F800000,  # 2**-64
        fm.ATAN2_P1,
        fm.ATAN2_P7,
        fm.F360,
        fm.DEG_TO_RAD,
    ],
    dtype=np.uint32,
)
SPECIALS = np.concatenate([SPECIALS, SPECIALS ^ np.uint32(SIGN)])

# OpenCV's source, modules/core/src/mathfuncs_core.simd.hpp.
ATAN2_SOURCE = """
static const float atan2_p1 = 0.9997878412794807f*(float)(180/CV_PI);
static const float atan2_p3 = -0.3258083974640975f*(float)(180/CV_PI);
static const float atan2_p5 = 0.1555786518463281f*(float)(180/CV_PI);
static const float atan2_p7 = -0.04432655554792128f*(float)(180/CV_PI);
"""


def bits(x: object) -> np.ndarray:
    return np.asarray(x, dtype=F32).view(np.uint32)


def show(b: int) -> str:
    return f"{int(b):#010x} ({np.uint32(b).view(F32)!r})"


def assert_same_bits(got: np.ndarray, want: np.ndarray, context: str, **operands) -> None:
    """got (uint32 patterns) must equal want (float32 values, or patterns if uint32)."""
    assert got.dtype == np.uint32, f"{context}: model returned {got.dtype}"
    want = want if want.dtype == np.uint32 else bits(want)
    assert got.shape == want.shape, f"{context}: shape {got.shape} vs {want.shape}"
    bad = np.flatnonzero(got != want)
    if bad.size:
        lines = [f"{context}: {bad.size} of {got.size} differ, first:"]
        for i in bad[:5]:
            ops = ", ".join(f"{k}={np.ravel(v)[i]!r}" for k, v in operands.items())
            lines.append(f"  {ops}: model {show(got.ravel()[i])}, want {show(want.ravel()[i])}")
        pytest.fail("\n".join(lines))


def nonzero(b: np.ndarray) -> np.ndarray:
    return b[(b & 0x7FFFFFFF) != 0]


def exponent(b: np.ndarray) -> np.ndarray:
    """Unbiased exponent of normal float32 patterns."""
    return ((b.astype(np.int64) >> 23) & 0xFF) - 127


# ---- operands -----------------------------------------------------------------------------


def fractions(rng: np.random.Generator, n: int) -> np.ndarray:
    """23-bit fraction fields: uniform, short (random trailing zeros: exact results and ties),
    near all ones (carries on rounding) and near zero."""
    uniform = rng.integers(0, 1 << 23, n)
    k = rng.integers(0, 24, n)
    short = (uniform >> k) << k
    ones = (1 << 23) - 1 - rng.integers(0, 8, n)
    low = rng.integers(0, 8, n)
    return np.choose(rng.integers(0, 4, n), [uniform, short, ones, low])


def floats(rng: np.random.Generator, exps: np.ndarray) -> np.ndarray:
    """Random-signed patterns with the given exponent fields (int64)."""
    n = exps.size
    return (rng.integers(0, 2, n) << 31) | (exps << 23) | fractions(rng, n)


def binary_operands(rng: np.random.Generator, n: int = 1 << 18) -> tuple[np.ndarray, ...]:
    """About 4.1n + 2000 operand pairs (uint32): uniform over all finite floats; near the
    subnormals or overflow; exponents around the ORB ranges (2**-47 .. 2**13) with
    differences up to 30; pairs made to be equal, opposite, 1 ulp apart, or off by half
    an ulp (ties) or less; all special pairs."""
    a_all = floats(rng, rng.integers(0, 255, n))
    b_all = floats(rng, rng.integers(0, 255, n))
    top = rng.integers(0, 2, n // 8) * 250  # both near the subnormals or near overflow
    a_ends = floats(rng, top + rng.integers(0, 5, n // 8))
    b_ends = floats(rng, top + rng.integers(0, 5, n // 8))
    ea = rng.integers(80, 141, 2 * n)
    a_orb = floats(rng, ea)
    b_orb = floats(rng, np.clip(ea + rng.integers(-30, 31, 2 * n), 0, 254))
    ed = rng.integers(80, 141, n)
    a_der = floats(rng, ed)
    sign = rng.integers(0, 2, n) << 31
    derived = [
        a_der,
        a_der ^ SIGN,
        a_der + 1,
        a_der - 1,
        (a_der ^ SIGN) + 1,
        (a_der ^ SIGN) - 1,
        sign | ((ed - 24) << 23),  # half an ulp of a
        sign | ((ed - 24) << 23) | fractions(rng, n),
        sign | ((ed - rng.integers(22, 28, n)) << 23) | fractions(rng, n),
    ]
    b_der = np.choose(rng.integers(0, len(derived), n), derived)
    sa, sb = np.meshgrid(SPECIALS, SPECIALS)
    a = np.concatenate([a_all, a_ends, a_orb, a_der, sa.ravel()]).astype(np.uint32)
    b = np.concatenate([b_all, b_ends, b_orb, b_der, sb.ravel()]).astype(np.uint32)
    return a, b


def rounding_counts(exact: np.ndarray, got: np.ndarray) -> dict[str, int]:
    """How the float64 exact results (nan where not exact) were rounded to got."""
    r = got.view(F32).astype(np.float64)
    ok = np.isfinite(exact) & np.isfinite(r)
    toward = np.where(exact > r, np.inf, -np.inf).astype(F32)
    neighbour = np.nextafter(got.view(F32), toward).astype(np.float64)
    inexact = ok & (exact != r)
    return {
        "exact": int(np.count_nonzero(ok & (exact == r))),
        "tie": int(np.count_nonzero(inexact & (exact - r == neighbour - exact))),
        "carry": int(
            np.count_nonzero(inexact & ((got & 0x7FFFFF) == 0) & (np.abs(r) > np.abs(exact)))
        ),
        "subnormal": int(np.count_nonzero(((got & 0x7F800000) == 0) & ((got & 0x7FFFFF) != 0))),
    }


# ---- constants ----------------------------------------------------------------------------


def float_literal(text: str) -> np.float32:
    """A C float literal: the decimal rounded once, to nearest even, to float32 (going
    through a double could round twice)."""
    exact = Fraction(text)
    f = F32(float(text))
    candidates = [np.nextafter(f, F32(-np.inf)), f, np.nextafter(f, F32(np.inf))]
    return min(candidates, key=lambda c: (abs(Fraction(float(c)) - exact), int(bits(c)) & 1))


def test_constants_rederived_from_opencv_source():
    literals = dict(re.findall(r"atan2_p(\d) = (-?[\d.]+)f\*\(float\)\(180/CV_PI\)", ATAN2_SOURCE))
    assert sorted(literals) == ["1", "3", "5", "7"]
    to_deg = F32(180 / np.pi)  # (float)(180/CV_PI): CV_PI is the double nearest pi
    for k, attr in (("1", "ATAN2_P1"), ("3", "ATAN2_P3"), ("5", "ATAN2_P5"), ("7", "ATAN2_P7")):
        want = float_literal(literals[k]) * to_deg
        assert isinstance(want, F32)
        assert int(bits(want)) == getattr(fm, attr), f"{attr}: {show(getattr(fm, attr))}"
    assert int(bits(F32(np.pi / 180.0))) == fm.DEG_TO_RAD  # (float)(CV_PI/180.f)
    assert [int(bits(F32(v))) for v in (90, 180, 360, 1)] == [fm.F90, fm.F180, fm.F360, ONE]


# ---- the four operations ------------------------------------------------------------------

OPS: dict[str, tuple[Callable, Callable]] = {
    "mul": (fm.mul, np.multiply),
    "add": (fm.add, np.add),
    "sub": (fm.sub, np.subtract),
    "div": (fm.div, np.divide),
}


@pytest.mark.parametrize("name", OPS)
def test_binary_op_matches_ieee(name: str, rng: np.random.Generator, seed: int):
    a, b = binary_operands(rng)
    if name == "div":
        b = np.where((b & 0x7FFFFFFF) == 0, np.uint32(ONE), b)
    model, ieee = OPS[name]
    with np.errstate(all="ignore"):
        want = ieee(a.view(F32), b.view(F32))
        got = model(a, b)
        assert_same_bits(got, want, f"{name} seed {seed}", a=a, b=b)
        assert a.size >= 10**6

        # The operands must reach the cases that matter: exact results, ties to even,
        # carries out of the significand, cancellation to zero, subnormals, overflow.
        a64, b64 = a.view(F32).astype(np.float64), b.view(F32).astype(np.float64)
        if name == "mul":
            exact = a64 * b64  # 48-bit products: exact in float64
        elif name == "div":
            q = got.view(F32).astype(np.float64)
            exact = np.where(q * b64 == a64, q, np.nan)  # only the exact quotients
        else:
            close = np.abs(exponent(a) - exponent(b)) <= 28  # then the sum fits 53 bits
            exact = np.where(close, a64 + b64 if name == "add" else a64 - b64, np.nan)
        counts = rounding_counts(exact, got)
    counts["overflow"] = int(np.count_nonzero((got & 0x7FFFFFFF) == 0x7F800000))
    counts["zero"] = int(np.count_nonzero(((got & 0x7FFFFFFF) == 0) & ((a & 0x7FFFFFFF) != 0)))
    print(name, counts)
    assert counts["exact"] > 10_000, counts
    assert counts["subnormal"] > 100, counts
    assert counts["overflow"] > 100, counts
    if name != "div":
        assert counts["tie"] > 2_000, counts
        assert counts["carry"] > 1_000, counts
    if name in ("add", "sub"):
        assert counts["zero"] > 10_000, counts


def test_signed_zeros():
    z, nz, one = 0, SIGN, ONE
    assert fm.add(z, nz) == z and fm.add(nz, nz) == nz and fm.add(nz, z) == z
    assert fm.sub(nz, z) == nz and fm.sub(one, one) == z and fm.add(one, one ^ SIGN) == z
    assert fm.mul(nz, one) == nz and fm.mul(nz, one ^ SIGN) == z and fm.div(nz, one) == nz


@pytest.mark.parametrize(
    ("call", "error"),
    [
        (lambda: fm.mul(0x7F800000, ONE), ValueError),  # inf
        (lambda: fm.add(ONE, 0xFFC00000), ValueError),  # NaN
        (lambda: fm.mul(-1, ONE), ValueError),
        (lambda: fm.mul(1 << 32, ONE), ValueError),
        (lambda: fm.mul(np.float32(1.0), ONE), TypeError),
        (lambda: fm.div(ONE, 0), ZeroDivisionError),
        (lambda: fm.div(0, SIGN), ZeroDivisionError),
        (lambda: fm.from_int(2**31), ValueError),
        (lambda: fm.from_int(1.0), TypeError),
        (lambda: fm.cv_round(0x4F000000), ValueError),  # 2**31
    ],
)
def test_outside_the_domain_raises(call: Callable, error: type[Exception]):
    with pytest.raises(error):
        call()


def test_from_int(rng: np.random.Generator, seed: int):
    edges = np.array([0, 1, 2, 3, 2**23, 2**24 - 1, 2**24, 2**24 + 1, 2**24 + 3, 2**25 + 2])
    edges = np.concatenate([edges, edges + 2**30, 2**31 - 1 - np.arange(300)])
    i = np.concatenate([edges, -edges, rng.integers(-(2**31) + 1, 2**31, 10**5)])
    i = np.concatenate([i, i >> rng.integers(0, 31, i.size)])
    assert_same_bits(fm.from_int(i), i.astype(F32), f"from_int seed {seed}", i=i)


def test_cv_round(rng: np.random.Generator, seed: int):
    r = floats(rng, rng.integers(0, 158, 10**6))  # |x| < 2**31
    halves = bits(np.arange(-4000, 4000) + F32(0.5))
    edges = np.array([0, SIGN, 1, 0x3F000000, 0x3F000001, 0x3EFFFFFF, 0x4EFFFFFF], np.uint32)
    x = np.concatenate([r.astype(np.uint32), halves, edges, edges ^ np.uint32(SIGN)])
    want = np.rint(x.view(F32)).astype(np.int64)  # ties to even, like cvtss2si
    got = fm.cv_round(x)
    bad = np.flatnonzero(got != want)
    assert bad.size == 0, f"seed {seed}: " + ", ".join(
        f"{show(x[i])} -> {got[i]} not {want[i]}" for i in bad[:5]
    )


# ---- fastAtan2 ----------------------------------------------------------------------------


def cv_fast_atan2(m01: np.ndarray, m10: np.ndarray) -> np.ndarray:
    """cv2.fastAtan2((float)m01, (float)m10) element by element, as float32 bits."""
    out = map(cv2.fastAtan2, m01.astype(float).tolist(), m10.astype(float).tolist())
    return bits(np.fromiter(out, dtype=F32, count=m01.size))


def adversarial_moments(ks: np.ndarray, all_signs: bool, rng: np.random.Generator):
    """Zeros, axes, diagonals |m01| = |m10|, diagonals +- 1, tiny ratios (1 against k,
    k against 624240) for the magnitudes ks, with every sign combination or random signs;
    plus every pair in -40..40 x -40..40."""
    k1 = np.minimum(ks + 1, M_MAX)
    one, top, zero = np.ones_like(ks), np.full_like(ks, M_MAX), np.zeros_like(ks)
    pairs = [(zero, ks), (ks, zero), (ks, ks), (ks, k1), (k1, ks), (one, ks), (ks, one)]
    pairs += [(top, ks), (ks, top)]
    y = np.concatenate([p[0] for p in pairs] + [[0]])
    x = np.concatenate([p[1] for p in pairs] + [[0]])
    if all_signs:
        y = np.concatenate([y, -y, y, -y])
        x = np.concatenate([x, x, -x, -x])
    else:
        y = y * rng.choice([-1, 1], y.size)
        x = x * rng.choice([-1, 1], x.size)
    box_y, box_x = np.meshgrid(np.arange(-40, 41), np.arange(-40, 41))
    return np.concatenate([y, box_y.ravel()]), np.concatenate([x, box_x.ravel()])


def few_magnitudes() -> np.ndarray:
    p = 1 << np.arange(20)
    ks = np.concatenate([np.arange(1, 100), p - 1, p, p + 1, M_MAX - np.arange(100)])
    ks = np.concatenate([ks, np.geomspace(100, M_MAX, 200).astype(np.int64)])
    return np.unique(ks[(ks >= 1) & (ks <= M_MAX)])


def random_moments(rng: np.random.Generator, n: int) -> tuple[np.ndarray, np.ndarray]:
    """Uniform over |m| <= 624240, and half of them scaled down by 2**0 .. 2**19 so that
    small moments and extreme ratios are common too."""
    m = rng.integers(-M_MAX, M_MAX + 1, (2, n))
    m[:, n // 2 :] >>= rng.integers(0, 20, (2, n - n // 2))
    return m[0], m[1]


def assert_atan_matches_opencv(m01: np.ndarray, m10: np.ndarray, context: str) -> None:
    got = fm.fast_atan2(m01, m10)
    assert_same_bits(got, cv_fast_atan2(m01, m10), context, m01=m01, m10=m10)
    deg = got.view(F32)
    assert np.all((deg >= 0) & (deg < 360)), f"{context}: output outside [0, 360)"


def test_fast_atan2_random(rng: np.random.Generator, seed: int):
    m01, m10 = random_moments(rng, 10**6)
    assert_atan_matches_opencv(m01, m10, f"random seed {seed}")


def test_fast_atan2_adversarial(cv_optimized: bool, rng: np.random.Generator, seed: int):
    m01, m10 = adversarial_moments(few_magnitudes(), True, rng)
    assert_atan_matches_opencv(m01, m10, f"adversarial optimized={cv_optimized}")
    zero = fm.fast_atan2(np.zeros(1, np.int64), np.zeros(1, np.int64))
    assert zero[0] == 0 and cv2.fastAtan2(0.0, 0.0) == 0.0
    axes = fm.fast_atan2(np.array([0, 5, 0, -5]), np.array([5, 0, -5, 0]))
    assert axes.view(F32).tolist() == [0.0, 90.0, 180.0, 270.0]


@pytest.mark.slow
def test_fast_atan2_many(rng: np.random.Generator, seed: int):
    """3e7 random pairs plus every magnitude 1 .. 624240 in every adversarial shape."""
    chunk = 1 << 20
    for start in range(0, 3 * 10**7, chunk):
        m01, m10 = random_moments(rng, chunk)
        assert_atan_matches_opencv(m01, m10, f"random chunk {start} seed {seed}")
    m01, m10 = adversarial_moments(np.arange(1, M_MAX + 1), False, rng)
    for start in range(0, m01.size, chunk):
        s = slice(start, start + chunk)
        assert_atan_matches_opencv(m01[s], m10[s], f"adversarial chunk {start} seed {seed}")


def test_fast_atan2_word_widths(rng: np.random.Generator, seed: int):
    """The ranges the module docstring states, measured on adversarial and random moments
    along the same chain of operations as fast_atan2."""
    y, x = adversarial_moments(few_magnitudes(), True, rng)
    ry, rx = random_moments(rng, 2 * 10**5)
    m01, m10 = np.concatenate([y, ry]), np.concatenate([x, rx])
    ay, ax = fm.from_int(np.abs(m01)), fm.from_int(np.abs(m10))
    ge = ax >= ay
    num, den = np.where(ge, ay, ax), np.where(ge, ax, ay)
    live = den != 0
    c = fm.div(num[live], den[live])
    c2 = fm.mul(c, c)
    adds = []  # (constant, the operand added to it, result)
    t = np.full_like(c, fm.ATAN2_P7)
    for p in (fm.ATAN2_P5, fm.ATAN2_P3, fm.ATAN2_P1):
        prod = fm.mul(t, c2)
        t = fm.add(prod, p)
        adds.append((p, prod, t))
    a = fm.mul(t, c)
    ge = ge[live]
    # The subtractions are recorded as additions of -a.
    adds.append((fm.F90, a[~ge] ^ SIGN, fm.sub(fm.F90, a[~ge])))
    a = np.where(ge, a, fm.sub(fm.F90, a))
    adds.append((fm.F180, a ^ SIGN, fm.sub(fm.F180, a)))  # before the x < 0 step: a <= 90
    a = np.where(m10[live] < 0, fm.sub(fm.F180, a), a)
    adds.append((fm.F360, a ^ SIGN, fm.sub(fm.F360, a)))  # before the y < 0 step: a <= 180
    a = np.where(m01[live] < 0, fm.sub(fm.F360, a), a)
    assert np.array_equal(a, fm.fast_atan2(m01, m10)[live]), "chain is not fast_atan2"

    assert exponent(nonzero(ay)).max() <= 19 and exponent(nonzero(ax)).max() <= 19
    assert exponent(nonzero(c)).min() == -20 and exponent(c).max() == 0
    assert exponent(nonzero(c2)).min() == -39 and exponent(c2).max() == 0
    shifts = []
    for const, other, result in adds:
        const = np.uint32(const)
        assert np.all((other & 0x7FFFFFFF) < (const & 0x7FFFFFFF)), show(const)
        other = nonzero(other)
        assert np.all((other >> 31) != (const >> 31)), f"{show(const)}: not a subtraction"
        shift = exponent(const) - exponent(other)
        assert shift.min() >= (2 if const == fm.ATAN2_P5 else 1), show(const)
        assert exponent(result).min() >= exponent(const) - 1, f"{show(const)}: > 1-bit normalise"
        shifts.append((show(const), int(shift.min()), int(shift.max())))
    print("alignment shifts (constant, min, max):", shifts)
    deg = fm.fast_atan2(m01, m10)
    rad = fm.to_radians(deg)
    assert exponent(nonzero(deg)).min() == -14 and exponent(deg).max() == 8
    assert exponent(nonzero(rad)).min() == -20 and exponent(rad).max() == 2
    assert nonzero(deg).view(F32).min() == F32(9.176539e-05)


# ---- to_radians ---------------------------------------------------------------------------


def assert_to_radians(deg: np.ndarray, context: str) -> None:
    deg = deg.astype(np.uint32)
    want = deg.view(F32) * F32(np.pi / 180.0)
    assert_same_bits(fm.to_radians(deg), want, context, deg=deg)


def test_to_radians(rng: np.random.Generator, seed: int):
    m01, m10 = adversarial_moments(few_magnitudes(), True, rng)
    edges = np.array([0, 1, 0x7FFFFF, 0x800000, fm.F90, fm.F180, 0x43870000, fm.F360 - 1])
    deg = np.concatenate(
        [rng.integers(0, fm.F360, 10**6), edges, fm.fast_atan2(m01, m10), np.arange(0, 1 << 16)]
    )
    assert_to_radians(deg, f"seed {seed}")


@pytest.mark.slow
def test_to_radians_exhaustive():
    """Every float32 in [0, 360): 0x00000000 .. 0x43B3FFFF, about 1.14e9 patterns."""
    chunk = 1 << 20
    for start in range(0, fm.F360, chunk):
        assert_to_radians(np.arange(start, min(start + chunk, fm.F360)), f"chunk {start:#x}")


# ---- rotation -----------------------------------------------------------------------------

GRID = np.arange(-13, 13)
PX, PY = (g.ravel() for g in np.meshgrid(GRID, GRID))  # every pattern coordinate pair


def rotate_ieee(px, py, a, b) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """numpy float32: x, y and their cvRound (np.rint is ties to even)."""
    fx, fy, a, b = F32(px), F32(py), a.view(F32), b.view(F32)
    x, y = fx * a - fy * b, fx * b + fy * a
    return x, y, np.rint(x).astype(np.int64), np.rint(y).astype(np.int64)


def assert_rotate(px, py, a, b, context: str) -> tuple[np.ndarray, np.ndarray]:
    """Compare rotate with numpy; returns numpy's float x, y."""
    px, py, a, b = np.broadcast_arrays(px, py, a, b)
    x, y, ix, iy = rotate_ieee(px, py, a, b)
    gx, gy = fm.rotate(px, py, a, b)
    for name, got, want in (("ix", gx, ix), ("iy", gy, iy)):
        bad = np.flatnonzero(got != want)
        assert bad.size == 0, f"{context} {name}: " + ", ".join(
            f"px={px.flat[i]} py={py.flat[i]} a={show(a.flat[i])} b={show(b.flat[i])}: "
            f"{got.flat[i]} not {want.flat[i]}"
            for i in bad[:5]
        )
    return x, y


def unit_patterns(rng: np.random.Generator, n: int) -> np.ndarray:
    """Random-signed bit patterns of magnitude <= 1.0 (every exponent, subnormals too)."""
    return ((rng.integers(0, 2, n) << 31) | rng.integers(0, ONE + 1, n)).astype(np.uint32)


def cos_sin(rad: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """(float)cos(angle), (float)sin(angle) as in computeOrbDescriptor (double libm)."""
    r = rad.view(F32).astype(np.float64)
    return bits(np.cos(r).astype(F32)), bits(np.sin(r).astype(F32))


def test_rotate_random_patterns(rng: np.random.Generator, seed: int):
    n = 10**6
    a, b = unit_patterns(rng, n), unit_patterns(rng, n)
    px, py = rng.integers(-13, 13, (2, n))
    assert_rotate(px, py, a, b, f"seed {seed}")


def test_rotate_angles(rng: np.random.Generator, seed: int):
    """cos/sin of uniform angles and of the angles ORB computes from random moments."""
    n = 5 * 10**5
    uniform = bits(rng.uniform(0, 2 * np.pi, n).astype(F32))
    orb = fm.to_radians(fm.fast_atan2(*random_moments(rng, n)))
    a, b = cos_sin(np.concatenate([uniform, orb]))
    px, py = rng.integers(-13, 13, (2, a.size))
    assert_rotate(px, py, a, b, f"one point per angle, seed {seed}")
    k = rng.integers(0, a.size, 2000)
    assert_rotate(PX, PY, a[k, None], b[k, None], f"whole grid, seed {seed}")


def test_rotate_exact_halves():
    """cos, sin in multiples of 1/8: results are exact, among them every half and integer."""
    eighths = bits(np.arange(-8, 9) / F32(8))
    a, b = (g.ravel()[:, None] for g in np.meshgrid(eighths, eighths))
    x, y = assert_rotate(PX, PY, a, b, "eighths")
    values = set(np.concatenate([x.ravel(), y.ravel()]).tolist())
    assert {-0.5, 0.5, -1.5, 1.5, 2.5, 0.0, -3.0, 26.0} <= values


def test_rotate_float_rounding_matters():
    """A keypoint of real moments (m01, m10) = (495931, -24127): for the point (10, -12)
    x = 11.4999999 rounds to float 11.5 and cvRound gives 12, not the 11 of the exact x."""
    a, b = cos_sin(fm.to_radians(fm.fast_atan2(np.array([495931]), np.array([-24127]))))
    assert (int(a[0]), int(b[0])) == (0xBD46FEFC, 0x3F7FB29D)
    ix, _ = fm.rotate(10, -12, a[0], b[0])
    exact = 10 * np.float64(a.view(F32)[0]) + 12 * np.float64(b.view(F32)[0])
    assert ix == 12 and np.rint(exact) == 11
    assert_rotate(10, -12, a, b, "11.5")


def test_rotate_broadcasts(rng: np.random.Generator):
    a, b = cos_sin(bits(rng.uniform(0, 2 * np.pi, 40).astype(F32)))
    px, py = rng.integers(-13, 13, (2, 512))
    ix, iy = fm.rotate(px, py, a[:, None], b[:, None])
    assert ix.shape == iy.shape == (40, 512)
    for k in (0, 17, 39):
        assert np.array_equal(fm.rotate(px, py, a[k], b[k])[0], ix[k])


def test_orb_cos_sin_not_tiny():
    """The docstring's bound: cos and sin of the angles ORB produces (0, or 1.6e-6 .. 6.3
    rad) are 0 or >= 1.19e-8. They are smallest at the float32 angles nearest k*pi/2."""
    smallest = fm.to_radians(fm.fast_atan2(np.array([1]), np.array([M_MAX])))
    near = [smallest]
    for k in range(1, 5):
        centre = int(bits(F32(k * np.pi / 2)))
        near.append(np.arange(centre - 1000, centre + 1000, dtype=np.uint32))
    a, b = cos_sin(np.concatenate(near))
    magnitude = np.concatenate([a, b]).view(F32)
    assert np.abs(magnitude).min() >= F32(1.19e-8) > 2.0**-27
    assert exponent(np.concatenate([a, b])).min() >= -27
