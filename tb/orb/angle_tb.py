"""cocotb testbench of fastnms_orb_angle: every angle's float32 bits equal to
golden/float32.py's fast_atan2 (OpenCV's atan_f32, which golden/tests ties to
cv2.fastAtan2) on moments at the axes, the diagonals, the extremes and random,
offered on random clocks with the result held back at random; the clocks from a
moment pair to its angle never above the unit's bound."""

from __future__ import annotations

import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden import float32
from fastnms.golden.orb import MOMENT_MAX

from tb.stream import StreamSink, StreamSource, offer_times

COUNT = int(os.environ["TB_COUNT"])
# docs/orb_rtl.md: the most clocks from moments taken to angle offered: 5 fixed
# (order, count, shift, round, result), 26 quotient bits, 5 per multiply (5 of them),
# 8 per add (3, and up to 3 quadrant steps).
ANGLE_CLOCKS = 5 + 26 + 5 * 5 + 8 * 6
PERIOD_NS = 10


def moment_pairs(rng: random.Random, count: int) -> list[tuple[int, int]]:
    """(m01, m10): every sign and axis case, equal and nearly equal magnitudes, the
    extremes, small moments (c with few bits), then random pairs."""
    big = MOMENT_MAX
    pairs = [(0, 0), (0, big), (big, 0), (0, -big), (-big, 0), (1, big), (big, 1)]
    pairs += [
        (sy * a, sx * b)
        for a, b in [(1, 1), (big, big), (big, big - 1), (1, 2)]
        for sy in (1, -1)
        for sx in (1, -1)
    ]
    pairs += [(rng.randint(-15, 15), rng.randint(-15, 15)) for _ in range(64)]
    while len(pairs) < count:
        m = rng.randint(-big, big)
        kind = rng.random()
        if kind < 0.2:  # near the diagonal
            pairs.append((m, rng.choice((1, -1)) * (abs(m) + rng.randint(-3, 3))))
        elif kind < 0.3:  # small against large
            pairs.append(
                (m, rng.randint(-64, 64)) if rng.random() < 0.5 else (rng.randint(-64, 64), m)
            )
        else:
            pairs.append((m, rng.randint(-big, big)))
    return pairs[:count]


@cocotb.test()
async def equals_the_model(dut):
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d, %d moment pairs", cocotb.RANDOM_SEED, COUNT)
    pairs = moment_pairs(rng, COUNT)
    m01 = np.array([p[0] for p in pairs], dtype=np.int64)
    m10 = np.array([p[1] for p in pairs], dtype=np.int64)
    expected = [int(v) for v in float32.fast_atan2(m01, m10)]

    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    source = StreamSource(dut, dut.clk, "in", rng, idle=0.3)
    sink = StreamSink(dut, dut.clk, "out", ["angle"], rng, stall=0.3)
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    cocotb.start_soon(sink.run())
    offered = offer_times(dut.clk, dut.out_valid)  # when each angle was first offered
    await source.send({"m01": a, "m10": b} for a, b in pairs)
    while len(sink.beats) < COUNT:
        await RisingEdge(dut.clk)

    for k, (beat, e) in enumerate(zip(sink.beats, expected, strict=True)):
        a, b = pairs[k]
        assert beat["angle"] == e, (
            f"pair {k} (m01 {a}, m10 {b}): {beat['angle']:08x}, model {e:08x}"
        )
    # Each angle is offered at most ANGLE_CLOCKS clocks after its moments were taken.
    clocks = [(offered[k] - source.accept_times[k]) // PERIOD_NS for k in range(COUNT)]
    dut._log.info("clocks from moments to the angle: %d .. %d", min(clocks), max(clocks))
    assert max(clocks) <= ANGLE_CLOCKS, f"an angle after {max(clocks)} clocks"
    # The bound is reached: some pair takes the division and all three quadrant steps.
    assert max(clocks) == ANGLE_CLOCKS, f"at most {max(clocks)} clocks"
