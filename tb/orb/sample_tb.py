"""cocotb testbench of fastnms_orb_sample: every keypoint's 256-bit descriptor equal to
golden/orb.py's descriptors, on 37x37 blurred patches (random pixels, few-valued pixels
where ties decide, flat, saturated, checkerboards and combs, blurred photographs) and
angles that put the points at their reach (0, 45, 90 ... degrees), random angles and the
angles of random moments. The rotated points are the golden model's, in the lanes and steps
of golden/sample_order.py (fastnms_orb_rotate's order, tested on its own). Patch columns and
points offered on random clocks, the descriptors taken with random stalls, short and longer
than a keypoint; then back to back
with everything ready: a keypoint every max(512 / LANES, 37) clocks, each descriptor
offered 6 clocks after its last step was taken."""

from __future__ import annotations

import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden import orb, sample_order
from fastnms.golden.image import load_grey
from fastnms.testing import images as testimages

from tb.orb.patches import random_crop
from tb.stream import StreamSink, StreamSource, offer_times

COUNT = int(os.environ["TB_COUNT"])
HALF = 18
SIDE = 2 * HALF + 1
POINT_BITS = 6
PERIOD_NS = 10
# docs/orb_rtl.md: from a keypoint's last step taken to its descriptor offered.
LATENCY = 7
# A patch is 37 columns, written one per clock; the copies take the next while one is read.
CAPTURE_CLOCKS = SIDE


def patches(rng: random.Random, count: int) -> list[np.ndarray]:
    """count uint8 37x37 blurred patches, the keypoint at the centre."""
    nrng = np.random.default_rng(rng.getrandbits(32))
    v, u = np.mgrid[0:SIDE, 0:SIDE]
    out = [
        np.zeros((SIDE, SIDE), np.uint8),
        np.full((SIDE, SIDE), 255, np.uint8),
        ((u + v) % 2 * 255).astype(np.uint8),
        (u % 2 * 255).astype(np.uint8),
        (v % 3 * 100).astype(np.uint8),
        (u * 7).astype(np.uint8),
        (255 - v * 7).astype(np.uint8),
    ]
    photos = [orb.gaussian_blur(load_grey(p)) for p in testimages.real_images()[:3]]
    while len(out) < count:
        kind = rng.random()
        if kind < 0.3:
            out.append(nrng.integers(0, 256, size=(SIDE, SIDE), dtype=np.uint8))
        elif kind < 0.5:
            low = rng.choice([0, 100, 254])
            out.append(nrng.integers(low, low + 2, size=(SIDE, SIDE), dtype=np.uint8))
        else:
            out.append(random_crop(rng, photos, SIDE))
    return out[:count]


def angles(rng: random.Random, count: int) -> np.ndarray:
    """count float32 angles in degrees: multiples of 45 first, then random and moments'."""
    nrng = np.random.default_rng(rng.getrandbits(32))
    special = np.arange(0, 360, 45, dtype=np.float32)
    m = nrng.integers(-orb.MOMENT_MAX, orb.MOMENT_MAX + 1, size=(2, count))
    moment = orb.fast_atan2(m[0].astype(np.float32), m[1].astype(np.float32))
    deg = (nrng.random(count) * 360).astype(np.float32)
    mixed = np.where(nrng.random(count) < 0.5, moment, np.minimum(deg, np.float32(359.9)))
    return np.concatenate([special, mixed.astype(np.float32)])[:count]


def point_steps(angle: np.float32, lanes: int) -> list[dict[str, int]]:
    """The keypoint's steps as fastnms_orb_rotate gives them (golden/sample_order.py)."""
    a, b = orb.cos_sin(np.array([angle], dtype=np.float32))
    dx, dy = orb.sample_offsets(a, b)
    order = sample_order.point_order(lanes)
    mask = (1 << POINT_BITS) - 1
    steps = []
    for s, points in enumerate(order):
        wx = sum((int(dx[0, p]) & mask) << (POINT_BITS * lane) for lane, p in enumerate(points))
        wy = sum((int(dy[0, p]) & mask) << (POINT_BITS * lane) for lane, p in enumerate(points))
        steps.append({"first": int(s == 0), "last": int(s == len(order) - 1), "dx": wx, "dy": wy})
    return steps


def column_words(patch: np.ndarray) -> list[dict[str, int]]:
    """The patch's columns dx = -18 .. 18 as patch_column words, row dy = -18 in bits 7 .. 0."""
    return [{"column": int.from_bytes(patch[:, c].tobytes(), "little")} for c in range(SIDE)]


def descriptor_word(d: np.ndarray) -> int:
    """OpenCV's 32 descriptor bytes as out_descriptor: byte k in bits 8k + 7 .. 8k."""
    return int.from_bytes(d.tobytes(), "little")


async def run_keypoints(dut, rng, todo, turns, lanes, idle, stall):
    """Offer the keypoints' columns and steps, take the descriptors; returns the sources,
    the sink and the clocks the descriptors were offered on."""
    patch_source = StreamSource(dut, dut.clk, "patch", rng, idle=idle)
    point_source = StreamSource(dut, dut.clk, "point", rng, idle=idle)
    sink = StreamSink(dut, dut.clk, "out", ["descriptor"], rng, stall=stall)
    sink_task = cocotb.start_soon(sink.run())
    offered = offer_times(dut.clk, dut.out_valid)
    columns = cocotb.start_soon(patch_source.send(w for p in todo for w in column_words(p)))
    await point_source.send(s for t in turns for s in point_steps(t, lanes))
    await columns
    # A descriptor lost would leave the sink waiting: give up after any stall could end.
    for _ in range(100_000):
        if len(sink.beats) == len(todo):
            break
        await RisingEdge(dut.clk)
    assert len(sink.beats) == len(todo), f"{len(sink.beats)} descriptors of {len(todo)}"
    sink_task.cancel()
    return patch_source, point_source, sink, offered


def check(dut, sink, todo, turns) -> None:
    centre = np.array([HALF])
    for k, (beat, patch, turn) in enumerate(zip(sink.beats, todo, turns, strict=True)):
        want = descriptor_word(orb.descriptors(patch, centre, centre, np.array([turn]))[0])
        got = beat["descriptor"]
        assert got == want, (
            f"keypoint {k} (angle {turn!r}): bits {got ^ want:064x} differ from the model"
        )


@cocotb.test()
async def equals_the_model(dut):
    lanes = len(dut.point_dx) // POINT_BITS
    steps = 512 // lanes
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d, LANES %d, %d keypoints", cocotb.RANDOM_SEED, lanes, COUNT)
    todo, turns = patches(rng, COUNT), angles(rng, COUNT)

    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    _, _, sink, _ = await run_keypoints(dut, rng, todo, turns, lanes, idle=0.2, stall=0.3)
    check(dut, sink, todo, turns)
    # Descriptors left waiting for longer than a keypoint takes: the next one must wait.
    few = min(COUNT, 12)
    _, _, sink, _ = await run_keypoints(dut, rng, todo[:few], turns[:few], lanes, 0.0, 0.99)
    check(dut, sink, todo[:few], turns[:few])

    # Back to back, everything ready: the steady rate and the latency.
    _, points, sink, offered = await run_keypoints(dut, rng, todo, turns, lanes, 0.0, 0.0)
    check(dut, sink, todo, turns)
    lasts = points.accept_times[steps - 1 :: steps]
    latency = {(t - last) // PERIOD_NS for t, last in zip(offered, lasts, strict=True)}
    assert latency == {LATENCY}, f"descriptors offered {latency} clocks after the last step"
    gaps = {(b - a) // PERIOD_NS for a, b in zip(sink.times[1:-1], sink.times[2:], strict=True)}
    dut._log.info("back to back: a keypoint every %s clocks", sorted(gaps))
    assert gaps == {max(steps, CAPTURE_CLOCKS)}, f"keypoints {gaps} clocks apart"
