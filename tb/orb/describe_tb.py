"""cocotb testbench of fastnms_orb_describe: every keypoint's angle (float32 bits) and
256-bit descriptor equal to golden/orb.py's ic_angle and descriptors, its record back in
order. Keypoints of real photographs, noise, flat areas (m01 = m10 = 0), saturated half
planes (the largest moments) and a textured patch rotated by many angles; their unblurred
and blurred columns offered on random clocks with the output stalled at random, then back to
back with the output ready: the steady rate (a keypoint every 64 clocks at LANES 8) and the
longest latency from a keypoint's last unblurred column to its output."""

from __future__ import annotations

import os
import random

import cocotb
import cv2
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden import orb
from fastnms.golden.image import load_grey
from fastnms.testing import images as testimages

from tb.stream import StreamSink, StreamSource

COUNT = int(os.environ["TB_COUNT"])
HALF = 18
MOMENT_HALF = orb.HALF_PATCH
PERIOD_NS = 10
# docs/orb_rtl.md, fastnms_orb_describe: the steady rate (512 / LANES clocks at LANES 4 and
# 8) and the bound on a keypoint's latency from its last plain column to its output: the
# moments, the angle (at most 104 + 1), the radians and their hand-over, the cos/sin unit,
# the rotation's first step, the steps, the descriptor.
RATE = {4: 128, 8: 64}
PLAIN = 2 * MOMENT_HALF + 1
BLURRED = 2 * HALF + 1
BORDER = 31


def scenes(rng: random.Random) -> list[np.ndarray]:
    """The images keypoints are taken from."""
    nrng = np.random.default_rng(rng.getrandbits(32))
    out = [load_grey(p) for p in testimages.real_images()[:3]]
    out.append(nrng.integers(0, 256, size=(120, 160), dtype=np.uint8))
    out.append(np.full((100, 100), 77, np.uint8))
    v, u = np.mgrid[0:100, 0:100]
    out.append(np.where(u > 50, 255, 0).astype(np.uint8))
    out.append(np.where(v + u > 100, 255, 0).astype(np.uint8))
    # A textured patch rotated by many angles, side by side.
    tile = cv2.resize(out[0][:64, :64], (64, 64))
    turned = []
    for deg in range(0, 360, 15):
        m = cv2.getRotationMatrix2D((32, 32), deg, 1.0)
        turned.append(cv2.warpAffine(tile, m, (64, 64), borderMode=cv2.BORDER_REFLECT))
    out.append(np.vstack([np.hstack(turned[i : i + 6]) for i in range(0, 24, 6)]))
    return out


def keypoints(rng: random.Random, images: list[np.ndarray], count: int) -> list[tuple]:
    """count (image index, x, y): the centres of the rotated tiles, the flat and half-plane
    centres, then random places at least 31 pixels inside."""
    picks = []
    for i in (4, 5, 6):
        picks.append((i, 50, 50))
    rotated = len(images) - 1
    for r in range(4):
        for c in range(6):
            x, y = 64 * c + 32, 64 * r + 32
            h, w = images[rotated].shape
            if BORDER <= x < w - BORDER and BORDER <= y < h - BORDER:
                picks.append((rotated, x, y))
    while len(picks) < count:
        i = rng.randrange(len(images))
        h, w = images[i].shape
        picks.append((i, rng.randrange(BORDER, w - BORDER), rng.randrange(BORDER, h - BORDER)))
    order = picks[:3] + rng.sample(picks[3:], len(picks) - 3)
    return order[:count]


def plain_columns(img, x, y, tag) -> list[dict[str, int]]:
    """The keypoint's 31 unblurred columns (rows -15 .. 15), its record on each."""
    cols = img[y - MOMENT_HALF : y + MOMENT_HALF + 1, x - MOMENT_HALF : x + MOMENT_HALF + 1]
    return [
        {"column": int.from_bytes(np.ascontiguousarray(c).tobytes(), "little"), "record": tag}
        for c in cols.T
    ]


def blurred_columns(blurred, x, y) -> list[dict[str, int]]:
    """The keypoint's 37 blurred columns (rows -18 .. 18)."""
    cols = blurred[y - HALF : y + HALF + 1, x - HALF : x + HALF + 1]
    return [{"column": int.from_bytes(np.ascontiguousarray(c).tobytes(), "little")} for c in cols.T]


async def run(dut, rng, plain, blurred, count, idle, stall):
    plain_source = StreamSource(dut, dut.clk, "plain", rng, idle=idle)
    blurred_source = StreamSource(dut, dut.clk, "blurred", rng, idle=idle)
    sink = StreamSink(dut, dut.clk, "out", ["record", "angle", "descriptor"], rng, stall=stall)
    task = cocotb.start_soon(sink.run())
    patches = cocotb.start_soon(blurred_source.send(blurred))
    await plain_source.send(plain)
    await patches
    for _ in range(200_000):
        if len(sink.beats) == count:
            break
        await RisingEdge(dut.clk)
    task.cancel()
    assert len(sink.beats) == count, f"{len(sink.beats)} keypoints out of {count}"
    return plain_source, sink


@cocotb.test()
async def equals_the_model(dut):
    lanes = int(dut.LANES.value)
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d, LANES %d, %d keypoints", cocotb.RANDOM_SEED, lanes, COUNT)
    images = scenes(rng)
    blurred = [orb.gaussian_blur(i) for i in images]
    picks = keypoints(rng, images, COUNT)
    want, plain, patches = [], [], []
    for tag, (i, x, y) in enumerate(picks):
        xs, ys = np.array([x]), np.array([y])
        angle = orb.ic_angle(images[i], xs, ys)
        desc = orb.descriptors(blurred[i], xs, ys, angle)[0]
        want.append((tag, int(angle.view(np.uint32)[0]), int.from_bytes(desc.tobytes(), "little")))
        plain += plain_columns(images[i], x, y, tag)
        patches += blurred_columns(blurred[i], x, y)

    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0

    def check(sink):
        for k, (beat, (tag, angle, desc)) in enumerate(zip(sink.beats, want, strict=True)):
            i, x, y = picks[k]
            where = f"keypoint {k} (image {i}, x {x}, y {y})"
            assert beat["record"] == tag, f"{where}: record {beat['record']}"
            assert beat["angle"] == angle, f"{where}: angle {beat['angle']:08x}, model {angle:08x}"
            assert beat["descriptor"] == desc, f"{where}: bits {beat['descriptor'] ^ desc:064x}"

    _, sink = await run(dut, rng, plain, patches, COUNT, idle=0.2, stall=0.3)
    check(sink)

    source, sink = await run(dut, rng, plain, patches, COUNT, idle=0.0, stall=0.0)
    check(sink)
    gaps = {(b - a) // PERIOD_NS for a, b in zip(sink.times[:-1], sink.times[1:], strict=True)}
    dut._log.info("back to back: keypoints %s clocks apart", sorted(gaps))
    assert gaps == {RATE[lanes]}, f"keypoints {sorted(gaps)} clocks apart"

    # One at a time: the latency from a keypoint's last plain column to its output.
    latencies = []
    for k in range(min(COUNT, 12)):
        one = slice(k * PLAIN, (k + 1) * PLAIN)
        source, sink = await run(
            dut, rng, plain[one], patches[k * BLURRED : (k + 1) * BLURRED], 1, 0.0, 0.0
        )
        assert [b["descriptor"] for b in sink.beats] == [want[k][2]]
        latencies.append((sink.times[0] - source.accept_times[-1]) // PERIOD_NS)
    dut._log.info("one keypoint at a time: %d .. %d clocks", min(latencies), max(latencies))
    bound = 10 + 105 + 5 + 59 + 42 + 512 // lanes + 7
    assert max(latencies) <= bound, f"a keypoint took {max(latencies)} clocks (bound {bound})"
