"""cocotb testbench of fastnms_orb_rotate: every rotated pattern point of every keypoint, in
the lanes and steps of golden/sample_order.py, equal to golden/float32.py's rotate (cvRound
of ORB's float32 rotation) on the cos/sin of whole and special degrees, random degrees, the
angles of random moments, the angles where the float rounding of a point changes its
cvRound, and cos/sin pairs off the circle that land a point beside a half-integer; keypoints
offered on random clocks, the output stalled at random. Then back-to-back keypoints with the
output always ready: one step per clock, no gap, 512 / LANES clocks per keypoint."""

from __future__ import annotations

import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden import float32, sample_order
from fastnms.golden.orb import MOMENT_MAX, PATTERN
from fastnms.testing.orb_angles import cos_sin_of_degrees, near_half_integer_angles

from tb.stream import StreamSink, StreamSource

COUNT = int(os.environ["TB_COUNT"])
POINT_BITS = 6
PERIOD_NS = 10
# docs/orb_rtl.md: from cos/sin taken to the keypoint's first step offered, with the
# output ready and the other bank free: 26 products, 4 fill stages, the bank marked
# full, the table address and read, the 5 stages of fastnms_orb_round_point, the point
# FIFO (4).
LATENCY = 26 + 4 + 1 + 2 + 5 + 4


def cos_sin_pairs(rng: random.Random, count: int) -> tuple[np.ndarray, np.ndarray]:
    """count (cos, sin) pairs: the special ones first, then a mix of the kinds above."""
    nrng = np.random.default_rng(rng.getrandbits(32))
    special = np.array([0, 90, 180, 270, 45, 135, 30, 60, 120, 359.5], dtype=np.float32)
    a, b = cos_sin_of_degrees(special)
    hard_a, hard_b = near_half_integer_angles(nrng, 1)
    # Off the circle: a point on a half-integer (a multiple of 1/8) nudged by a tiny b.
    half = np.float32(0.5).view(np.uint32)
    tiny = [np.float32(v).view(np.uint32) for v in (2.0**-25 + 2.0**-40, -(2.0**-26), 2.0**-27)]
    off_a = np.array([half] * 3 + tiny, dtype=np.int64)
    off_b = np.array(tiny + [half] * 3, dtype=np.int64)
    m = nrng.integers(-MOMENT_MAX, MOMENT_MAX + 1, size=(2, count))
    moment_a, moment_b = cos_sin_of_degrees(float32.fast_atan2(m[0], m[1]).view(np.float32))
    deg = (nrng.random(count) * 360).astype(np.float32)
    random_a, random_b = cos_sin_of_degrees(np.minimum(deg, np.float32(359.9)))
    # The special and off-circle pairs first, the rest shuffled.
    fixed = len(special) + len(off_a)
    a = np.concatenate([a, off_a, hard_a, moment_a, random_a])
    b = np.concatenate([b, off_b, hard_b, moment_b, random_b])
    order = np.concatenate([np.arange(fixed), fixed + nrng.permutation(len(a) - fixed)])
    return a[order][:count], b[order][:count]


def lanes_of(word: int, lanes: int) -> list[int]:
    """The signed 6-bit lanes of a packed output word, lane 0 first."""
    out = []
    for lane in range(lanes):
        v = (word >> (POINT_BITS * lane)) & ((1 << POINT_BITS) - 1)
        out.append(v - (1 << POINT_BITS) if v >= 1 << (POINT_BITS - 1) else v)
    return out


def check(beats: list[dict[str, int]], a: np.ndarray, b: np.ndarray, lanes: int) -> None:
    steps = len(PATTERN) // lanes
    assert len(beats) == len(a) * steps, f"{len(beats)} steps for {len(a)} keypoints"
    gx, gy = float32.rotate(PATTERN[None, :, 0], PATTERN[None, :, 1], a[:, None], b[:, None])
    order = sample_order.point_order(lanes).ravel()  # step by step, lane 0 first
    for k in range(len(a)):
        got = beats[k * steps : (k + 1) * steps]
        for s, beat in enumerate(got):
            assert beat["first"] == (s == 0) and beat["last"] == (s == steps - 1), (
                f"keypoint {k} step {s}: first {beat['first']}, last {beat['last']}"
            )
        dx = [v for beat in got for v in lanes_of(beat["dx"], lanes)]
        dy = [v for beat in got for v in lanes_of(beat["dy"], lanes)]
        for i, p in enumerate(order):
            assert (dx[i], dy[i]) == (gx[k, p], gy[k, p]), (
                f"keypoint {k} (cos {a[k]:08x}, sin {b[k]:08x}) point {p} {tuple(PATTERN[p])}:"
                f" ({dx[i]}, {dy[i]}), float32.rotate ({gx[k, p]}, {gy[k, p]})"
            )


@cocotb.test()
async def equals_the_model(dut):
    lanes = len(dut.out_dx) // POINT_BITS
    steps = len(PATTERN) // lanes
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d, LANES %d, %d keypoints", cocotb.RANDOM_SEED, lanes, COUNT)
    a, b = cos_sin_pairs(rng, COUNT)

    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    source = StreamSource(dut, dut.clk, "in", rng, idle=0.3)
    sink = StreamSink(dut, dut.clk, "out", ["first", "last", "dx", "dy"], rng, stall=0.2)
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    sink_task = cocotb.start_soon(sink.run())
    await source.send({"cos": int(c), "sin": int(s)} for c, s in zip(a, b, strict=True))
    while len(sink.beats) < COUNT * steps:
        await RisingEdge(dut.clk)
    check(sink.beats, a, b, lanes)

    # Back to back, the output always ready: no gap between steps.
    sink_task.cancel()
    sink.beats.clear()
    sink.times.clear()
    sink.stall = 0.0
    cocotb.start_soon(sink.run())
    source.idle = 0.0
    first_accept = len(source.accept_times)
    await source.send({"cos": int(c), "sin": int(s)} for c, s in zip(a, b, strict=True))
    while len(sink.beats) < COUNT * steps:
        await RisingEdge(dut.clk)
    check(sink.beats, a, b, lanes)
    latency = (sink.times[0] - source.accept_times[first_accept]) // PERIOD_NS
    dut._log.info("first point %d clocks after its cos and sin were taken", latency)
    assert latency == LATENCY, f"first point after {latency} clocks"
    span = (sink.times[-1] - sink.times[0]) // PERIOD_NS + 1
    dut._log.info(
        "%d keypoints back to back: %d clocks (%d per keypoint)", COUNT, span, span // COUNT
    )
    assert span == COUNT * steps, f"{span} clocks for {COUNT} keypoints of {steps} steps"
