"""cocotb testbench of fastnms_orb_cos_sin: every cos and sin bit pattern equal to
golden/trig.py's cos_sin (correctly rounded float32, which golden/tests ties to the C
library) on the domain's edges (0, the tiny threshold, the quadrant thresholds, 2*pi,
the smallest reduced angle, the hardest roundings, powers of two, multiples of pi/2)
and on random bit patterns, random angles and ORB's angles in radians; the 64-bit
words of sin|r| and cos r before the rounding equal to the model's too (cos_sin_unrounded:
the results are far from rounding midpoints, so a product off by one unit would not
show in them); angles offered on random clocks, results taken with random stalls;
every result offered exactly the unit's bound of clocks after its angle was taken."""

from __future__ import annotations

import math
import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden import float32, trig

from tb.orb.angle_tb import moment_pairs
from tb.stream import StreamSink, StreamSource, sim_ns, value

COUNT = int(os.environ["TB_COUNT"])
# rtl/orb/fastnms_orb_cos_sin.vhd: 7 clocks of reduction, 1 to issue mulhi(M, M), 4 for
# it, 1 to shift Z, 1 to issue the sine's first product, 4 for each of the sine's 10 (the
# cosine's 9 interleaved), 3 of rounding, 1 to offer the result; the same for every angle.
COS_SIN_CLOCKS = 7 + 1 + 4 + 1 + 1 + 10 * 4 + 3 + 1
PERIOD_NS = 10
WORD = (1 << 64) - 1


def f32_bits(v: float) -> int:
    """The bit pattern of the float32 nearest to v."""
    return int(np.float32(v).view(np.uint32))


def edge_angles() -> list[int]:
    """The domain's edges and the hard cases, as float32 bit patterns."""
    xs = [0, 1, trig.X_MAX_BITS, trig.X_MAX_BITS - 1]
    xs += [trig.TINY_BITS + d for d in (-1, 0, 1)]
    xs += [t + d for t in trig._THRESHOLDS for d in (-1, 0, 1)]
    # The smallest |r| (near 3*pi/2) and the roundings closest to a midpoint.
    xs += [0x4096CBE4 + d for d in (-1, 0, 1)]
    xs += [f32_bits(0.00881955586), f32_bits(0.475609273)]
    # Powers of two: the subnormals, then every exponent up to 4.
    xs += [1 << n for n in range(23)] + [e << 23 for e in range(1, 130)]
    for j in (1, 2, 3):
        near = f32_bits(j * math.pi / 2)
        xs += [near + d for d in range(-2, 3)]
    return [x for x in xs if 0 <= x <= trig.X_MAX_BITS]


def angles(rng: random.Random, count: int) -> list[int]:
    """The edges, then a third each of random bit patterns in 0 .. X_MAX_BITS, random
    values in [0, 2*pi] and ORB's angles in radians from random moments."""
    xs = edge_angles()
    rest = max(count - len(xs), 0)
    xs += [rng.randint(0, trig.X_MAX_BITS) for _ in range(rest // 3)]
    xs += [min(f32_bits(rng.uniform(0, 2 * math.pi)), trig.X_MAX_BITS) for _ in range(rest // 3)]
    pairs = moment_pairs(rng, rest - 2 * (rest // 3))
    m01 = np.array([p[0] for p in pairs], dtype=np.int64)
    m10 = np.array([p[1] for p in pairs], dtype=np.int64)
    xs += [int(v) for v in float32.to_radians(float32.fast_atan2(m01, m10))]
    return xs[:count]


@cocotb.test()
async def equals_the_model(dut):
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d, %d angles", cocotb.RANDOM_SEED, COUNT)
    xs = angles(rng, COUNT)
    cos_bits, sin_bits = trig.cos_sin(np.array(xs, dtype=np.int64))

    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    source = StreamSource(dut, dut.clk, "in", rng, idle=0.3)
    sink = StreamSink(dut, dut.clk, "out", ["cos", "sin"], rng, stall=0.3)
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    cocotb.start_soon(sink.run())
    offered: list[int] = []  # the clock edge on which each result first shows on out_valid
    words: list[tuple[int, int]] = []  # sin|r| and cos r before the rounding, then

    async def watch() -> None:
        while True:
            # out_valid rises just after a clock edge; the next edge samples it.
            await RisingEdge(dut.out_valid)
            offered.append(sim_ns() + PERIOD_NS)
            words.append((value(dut.res), value(dut.mc_r)))

    cocotb.start_soon(watch())
    await source.send({"x": x} for x in xs)
    while len(sink.beats) < len(xs):
        await RisingEdge(dut.clk)

    for k, (beat, x) in enumerate(zip(sink.beats, xs, strict=True)):
        want = (int(cos_bits[k]), int(sin_bits[k]))
        got = (beat["cos"], beat["sin"])
        assert got == want, (
            f"angle {k} ({x:08x}): cos {got[0]:08x} sin {got[1]:08x}, "
            f"model cos {want[0]:08x} sin {want[1]:08x}"
        )
    # The words before the rounding: golden/trig.py's (M of cos x, M of sin x) are
    # (cos r, sin|r|) for an even k, swapped for an odd k; the unit's sin|r| (res) is
    # not yet renormalised. Below 2**-12 both compute x = 2**-12.
    (_, cos_m, _), (_, sin_m, _) = trig.cos_sin_unrounded(
        np.maximum(np.array(xs, dtype=np.uint64), np.uint64(trig.TINY_BITS))
    )
    for k, ((ms, mc), x) in enumerate(zip(words, xs, strict=True)):
        odd = sum(x > t for t in trig._THRESHOLDS) % 2
        want = (int(sin_m[k]), int(cos_m[k])) if not odd else (int(cos_m[k]), int(sin_m[k]))
        got = ((ms << 1) & WORD if ms >> 63 == 0 else ms, mc)
        assert got == want, (
            f"angle {k} ({x:08x}): sin|r| {got[0]:016x} cos r {got[1]:016x}, "
            f"model {want[0]:016x} {want[1]:016x}"
        )
    # Each result is offered at most COS_SIN_CLOCKS clocks after its angle was taken,
    # and the bound is reached.
    clocks = [(offered[k] - source.accept_times[k]) // PERIOD_NS for k in range(len(xs))]
    dut._log.info("clocks from angle to cos, sin: %d .. %d", min(clocks), max(clocks))
    assert max(clocks) <= COS_SIN_CLOCKS, f"a result after {max(clocks)} clocks"
    assert max(clocks) == COS_SIN_CLOCKS, f"at most {max(clocks)} clocks"
