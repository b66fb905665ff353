"""Operand pairs for the float32 units (fastnms_f32_mul, fastnms_f32_add): random
normals, short significands (exact results and rounding ties), cancellations, zeros
and the ORB constants, kept only inside the units' domain (operands +-0 or normal,
results +-0 or normal), the expected results from golden/float32.py."""

from __future__ import annotations

import random

import numpy as np
from fastnms.golden import float32

ORB_CONSTANTS = [
    float32.ATAN2_P1,
    float32.ATAN2_P3,
    float32.ATAN2_P5,
    float32.ATAN2_P7,
    float32.DEG_TO_RAD,
    float32.F90,
    float32.F180,
    float32.F360,
    float32.ONE,
]


def _pattern(sign: int, exponent: int, mantissa: int) -> int:
    return (sign << 31) | (exponent << 23) | mantissa


def _normal(rng: random.Random, exponent: int | None = None) -> int:
    """A random normal number; half of them with the low bits of the significand
    cleared (exact products and sums, and ties in rounding)."""
    e = rng.randint(1, 254) if exponent is None else exponent
    m = rng.getrandbits(23)
    if rng.random() < 0.5:
        m &= ~((1 << rng.randint(1, 23)) - 1)
    return _pattern(rng.getrandbits(1), e, m)


def _zero(rng: random.Random) -> int:
    return rng.getrandbits(1) << 31


def _mul_pair(rng: random.Random) -> tuple[int, int]:
    kind = rng.random()
    if kind < 0.02:
        return _zero(rng), _normal(rng) if rng.random() < 0.8 else _zero(rng)
    if kind < 0.1:
        return rng.choice(ORB_CONSTANTS) ^ (rng.getrandbits(1) << 31), _normal(
            rng, rng.randint(100, 140)
        )
    a = _normal(rng)
    ea = (a >> 23) & 0xFF
    # The product's exponent inside the normal range: eb around 254 - ea.
    eb = min(254, max(1, 254 - ea + rng.randint(-126, 126)))
    return a, _normal(rng, eb)


def _add_pair(rng: random.Random) -> tuple[int, int]:
    kind = rng.random()
    if kind < 0.03:
        z = _zero(rng)
        return (z, _normal(rng)) if rng.random() < 0.7 else (z, _zero(rng))
    a = _normal(rng, rng.randint(30, 224))
    ea = (a >> 23) & 0xFF
    if kind < 0.15:  # b = -a, or a few ulps away: complete or deep cancellation
        return a, (a ^ 0x80000000) + rng.randint(-3, 3)
    if kind < 0.25:
        return rng.choice(ORB_CONSTANTS), _normal(rng, rng.randint(100, 135))
    return a, _normal(rng, min(254, max(1, ea + rng.randint(-30, 30))))


def _is_zero(bits: np.ndarray) -> np.ndarray:
    return (bits & 0x7FFFFFFF) == 0


def _in_domain(bits: np.ndarray) -> np.ndarray:
    e = (bits >> 23) & 0xFF
    return _is_zero(bits) | ((e >= 1) & (e <= 254))


def vectors(unit: str, rng: random.Random, count: int) -> tuple[list[int], list[int], list[int]]:
    """`count` pairs (a, b) for unit "mul" or "add" and the expected results, every
    one inside the unit's domain."""
    pair = {"mul": _mul_pair, "add": _add_pair}[unit]
    op = {"mul": float32.mul, "add": float32.add}[unit]
    a: list[int] = []
    b: list[int] = []
    while len(a) < count:
        more = [pair(rng) for _ in range(2 * (count - len(a)) + 16)]
        ca = np.array([p[0] for p in more], dtype=np.int64)
        cb = np.array([p[1] for p in more], dtype=np.int64)
        ok = _in_domain(ca) & _in_domain(cb)
        result = op(ca[ok], cb[ok]).astype(np.int64)
        # A product is zero only for a zero operand (else it underflowed).
        underflow = _is_zero(result) & ~_is_zero(ca[ok]) & ~_is_zero(cb[ok]) & (unit == "mul")
        ok[ok] &= _in_domain(result) & ~underflow
        a += ca[ok].tolist()
        b += cb[ok].tolist()
    a, b = a[:count], b[:count]
    expected = op(np.array(a, dtype=np.int64), np.array(b, dtype=np.int64))
    return a, b, [int(v) for v in expected]
