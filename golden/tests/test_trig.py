"""The integer cos/sin unit (fastnms.golden.trig) against the C library's (float)cos((double)x)
and (float)sin((double)x), which OpenCV's ORB uses: special inputs and random ones by
default, every input of the domain under `slow`. An independent high-precision reference
(Python integers) measures the unit's error before rounding against its documented bound."""

from __future__ import annotations

import ctypes
import shutil
import subprocess
import time
from pathlib import Path

import numpy as np
import pytest
from fastnms.golden.trig import TINY_BITS, X_MAX_BITS, cos_sin, cos_sin_unrounded

LIBM_SOURCE = Path(__file__).with_name("libm_ref.c")
HARDEST = {"cos": 0.00881955586, "sin": 0.475609273}  # nearest to a rounding midpoint
CHUNK = 1 << 22


def f32_bits(value: float) -> int:
    return int(np.float32(value).view(np.uint32))


def bits_f32(bits) -> np.ndarray:
    return np.asarray(bits, dtype=np.uint32).view(np.float32)


class Libm:
    """ctypes wrapper of libm_ref.c: the reference's float32 bit patterns."""

    def __init__(self, path: Path):
        lib = ctypes.CDLL(str(path))
        buf = np.ctypeslib.ndpointer(dtype=np.uint32, flags="C_CONTIGUOUS")
        lib.ref_range.argtypes = [ctypes.c_uint32, ctypes.c_uint32, buf, buf]
        lib.ref_list.argtypes = [buf, ctypes.c_uint32, buf, buf]
        self._lib = lib

    def range(self, first: int, n: int) -> tuple[np.ndarray, np.ndarray]:
        c, s = np.empty(n, dtype=np.uint32), np.empty(n, dtype=np.uint32)
        self._lib.ref_range(first, n, c, s)
        return c, s

    def list(self, x: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        x = np.ascontiguousarray(x, dtype=np.uint32)
        c, s = np.empty_like(x), np.empty_like(x)
        self._lib.ref_list(x, x.size, c, s)
        return c, s


@pytest.fixture(scope="module")
def libm(tmp_path_factory: pytest.TempPathFactory) -> Libm:
    gcc = shutil.which("gcc")
    if gcc is None:
        pytest.skip("gcc not found: the C library reference (libm_ref.c) cannot be built")
    out = tmp_path_factory.mktemp("libm_ref") / "libm_ref.so"
    # No -ffast-math, no -march: the library's own cos and sin, called one by one.
    cmd = [gcc, "-O2", "-shared", "-fPIC", "-fno-builtin-sin", "-fno-builtin-cos"]
    subprocess.run([*cmd, "-o", str(out), str(LIBM_SOURCE), "-lm"], check=True)
    return Libm(out)


def mismatches(x, ours, ref, limit: int = 8) -> list[str]:
    """The first few differing inputs as 'x=... ours ... libm ...' lines."""
    (cos_ours, sin_ours), (cos_ref, sin_ref) = ours, ref
    bad = np.nonzero((cos_ours != cos_ref) | (sin_ours != sin_ref))[0]
    lines = []
    for i in bad[:limit]:
        lines.append(
            f"x={int(x[i]):#010x} ({bits_f32(x[i]):.9g}): "
            f"cos ours {int(cos_ours[i]):#010x} libm {int(cos_ref[i]):#010x}, "
            f"sin ours {int(sin_ours[i]):#010x} libm {int(sin_ref[i]):#010x}"
        )
    if bad.size > limit:
        lines.append(f"... {bad.size} in all")
    return lines


def special_inputs() -> np.ndarray:
    """Powers of two, +-1000 ulp around 0, j*pi/4 (j = 1..8), the hardest inputs and the
    tiny-x threshold, every float of [0, 2**-140] and the domain's last float."""
    powers = [1 << i for i in range(23)] + [e << 23 for e in range(1, 130)]
    centres = [0, TINY_BITS, X_MAX_BITS]
    centres += [f32_bits(j * np.pi / 4) for j in range(1, 9)]
    centres += [f32_bits(v) for v in HARDEST.values()]
    near = [np.arange(c - 1000, c + 1001) for c in centres]
    x = np.concatenate([np.array(powers), *near, np.arange(f32_bits(2.0**-140) + 1)])
    return np.unique(x[(x >= 0) & (x <= X_MAX_BITS)]).astype(np.uint32)


def test_fast_against_libm(libm: Libm, rng: np.random.Generator, seed):
    x = np.concatenate(
        [
            special_inputs(),
            rng.integers(0, X_MAX_BITS, 50_000, endpoint=True, dtype=np.uint32),
            # Uniform bit patterns are mostly tiny x: these cover the polynomial path.
            rng.integers(TINY_BITS, X_MAX_BITS, 100_000, endpoint=True, dtype=np.uint32),
        ]
    )
    assert x.size >= 100_000
    bad = mismatches(x, cos_sin(x), libm.list(x))
    assert not bad, f"seed {seed}: {len(bad)} mismatches\n" + "\n".join(bad)


def test_special_values():
    c, s = cos_sin(np.array([0, 1, TINY_BITS - 1], dtype=np.uint32))
    assert c.dtype == s.dtype == np.uint32
    assert list(c) == [0x3F800000] * 3  # cos 1.0
    assert list(s) == [0, 1, TINY_BITS - 1]  # sin +0.0, then x itself
    c, s = cos_sin(np.array([[f32_bits(np.pi / 2)], [X_MAX_BITS]], dtype=np.int64))
    assert c.shape == s.shape == (2, 1)
    # cos of the float nearest pi/2 is -(its distance to pi/2), sin of the last float sin r.
    assert np.isclose(bits_f32(c[0, 0]), np.pi / 2 - float(np.float32(np.pi / 2)), rtol=1e-6)
    assert np.isclose(bits_f32(s[1, 0]), float(np.float32(2 * np.pi)) - 2 * np.pi, rtol=1e-6)


@pytest.mark.parametrize(
    "bad",
    [
        np.array([X_MAX_BITS + 1], dtype=np.uint32),
        np.array([0x80000000], dtype=np.uint32),  # -0.0
        np.array([0x7FC00000], dtype=np.uint32),  # NaN
        np.array([-1], dtype=np.int64),
        np.array([1.0], dtype=np.float32),  # a value, not a bit pattern
    ],
    ids=["above-2pi", "minus-zero", "nan", "negative", "float-dtype"],
)
def test_out_of_domain(bad):
    with pytest.raises(ValueError):
        cos_sin(bad)


# ---- independent high-precision reference ------------------------------------------------

P = 256  # fixed-point fraction bits of the reference


def _atan_inv(n: int) -> int:
    total, power, k, sign = 0, (1 << (P + 16)) // n, 1, 1
    while power:
        total += sign * (power // k)
        power //= n * n
        k += 2
        sign = -sign
    return total


# pi/4 = atan(1/2) + atan(1/3) (Euler; trig.py uses Machin's formula), 16 guard bits.
PI_HALF = (2 * (_atan_inv(2) + _atan_inv(3)) + (1 << 15)) >> 16


def exact_cos_sin(bits: int) -> tuple[int, int]:
    """cos x and sin x * 2**P (signed, error a few units) by Taylor series of x - k*pi/2."""
    mant, e = (bits & 0x7FFFFF) | 0x800000, bits >> 23  # normal x only
    x = mant << (P + e - 150)
    k = (2 * x + PI_HALF) // (2 * PI_HALF)
    r = x - k * PI_HALF
    c, s = 0, 0
    term, n = 1 << P, 0  # r**n / n!
    while term:
        if n % 4 == 0:
            c += term
        elif n % 4 == 1:
            s += term
        elif n % 4 == 2:
            c -= term
        else:
            s -= term
        n += 1
        term = term * r // (n << P)
    return [(c, s), (-s, c), (-c, -s), (s, -c)][k % 4]


def test_error_bound_and_rounding(rng: np.random.Generator, seed):
    """Before rounding the unit is within its documented bound, 2**-36.8 ulp, of the exact
    value; its rounding is the exact value's (independently of the C library); and the
    stated hardest inputs are as close to a rounding midpoint as stated."""
    # The floats nearest k*pi/2 give the smallest reduced arguments.
    nearest = [f32_bits(k * np.pi / 2) + d for k in range(1, 5) for d in range(-3, 4)]
    hardest = [f32_bits(v) + d for v in HARDEST.values() for d in range(-3, 4)]
    x = np.concatenate(
        [
            rng.integers(TINY_BITS, X_MAX_BITS, 20_000, endpoint=True, dtype=np.uint32),
            special_inputs()[::10],
            np.array(nearest + hardest),
        ]
    ).astype(np.uint32)
    x = x[(x >= TINY_BITS) & (x <= X_MAX_BITS)]
    parts = cos_sin_unrounded(x)
    rounded = cos_sin(x)
    worst = 0.0
    for i, bits in enumerate(x.tolist()):
        for j, exact in enumerate(exact_cos_sin(bits)):
            sign, m, e = (int(a[i]) for a in parts[j])
            ours = (-1) ** sign * (m << (e - 63 + P))
            ulp_shift = abs(exact).bit_length() - 1 - 23  # ulp * 2**P of the exact value
            worst = max(worst, abs(ours - exact) / 2**ulp_shift)
            # Round the exact value itself (no ties: cos and sin of a nonzero float are
            # irrational).
            mag = (abs(exact) + (1 << (ulp_shift - 1))) >> ulp_shift
            expo = ulp_shift + 23 - P + 127
            want = ((exact < 0) << 31) + ((expo - 1) << 23) + mag
            got = int(rounded[j][i])
            assert got == want, f"seed {seed}: x={bits:#010x} {('cos', 'sin')[j]} {got:#x}"
    assert worst < 2.0**-36.8, f"seed {seed}: error {worst:.3g} ulp (bound 2**-36.8)"

    for j, name in enumerate(("cos", "sin")):
        exact = exact_cos_sin(f32_bits(HARDEST[name]))[j]
        ulp_shift = abs(exact).bit_length() - 1 - 23
        frac = (abs(exact) % (1 << ulp_shift)) / 2**ulp_shift
        assert abs(frac - 0.5) < 2.0**-27, f"{name}: {abs(frac - 0.5):.3g} ulp from a midpoint"


@pytest.mark.slow
def test_exhaustive_against_libm(libm: Libm):
    """Every float32 of [0, 2*pi]: 1 086 918 620 inputs, in chunks."""
    t0 = time.perf_counter()
    bad: list[str] = []
    count = 0
    for first in range(0, X_MAX_BITS + 1, CHUNK):
        n = min(CHUNK, X_MAX_BITS + 1 - first)
        x = np.arange(first, first + n, dtype=np.uint32)
        ours, ref = cos_sin(x), libm.range(first, n)
        if len(bad) < 8:
            bad += mismatches(x, ours, ref, 8 - len(bad))
        count += int(np.count_nonzero((ours[0] != ref[0]) | (ours[1] != ref[1])))
    print(f"{X_MAX_BITS + 1} inputs in {time.perf_counter() - t0:.0f} s, {count} mismatches")
    assert count == 0, f"{count} mismatches, the first:\n" + "\n".join(bad)
