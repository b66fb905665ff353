"""cocotb testbench of fastnms_orb_feed: ORB after the budget on whole images. The image and
its blurred copy stream in (each on its own, with idle clocks, back-to-back frames: the next
frame's pixels come in while the frame before's last keypoints are read), the golden model's
kept keypoints (3x3 NMS, ORB's border, the budget) come in a cell row at a time once both
inputs are past that cell row, as the budget hands them over, then a key_frame_end pulse;
every keypoint's x, y, score, angle bits and descriptor equal to golden/orb.py's
orb_features, in the same order.
Frames: a photograph crop, noise at threshold 0 (more keypoints than the engine's rate, so
the input must be held), and a flat image (no keypoint)."""

from __future__ import annotations

import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden import orb
from fastnms.golden.image import load_grey
from fastnms.testing import images as testimages

from tb.orb.patches import budget_order, random_crop
from tb.stream import StreamSink, StreamSource

HEIGHT, WIDTH = 96, 128
CELL = 16
PERIOD_NS = 10
FRAMES = int(os.environ.get("TB_FRAMES", "3"))


def frames(rng: random.Random) -> list[tuple[np.ndarray, int, int]]:
    """(image, threshold, K per cell) of each frame."""
    nrng = np.random.default_rng(rng.getrandbits(32))
    photos = [load_grey(p) for p in testimages.real_images()[:3]]
    out = [
        (random_crop(rng, photos, max(HEIGHT, WIDTH))[:HEIGHT, :WIDTH], 20, 4),
        (nrng.integers(0, 256, size=(HEIGHT, WIDTH), dtype=np.uint8), 0, 15),
        (np.full((HEIGHT, WIDTH), 90, np.uint8), 20, 4),
    ]
    return out[:FRAMES]


def keypoint_groups(img: np.ndarray, threshold: int, per_cell: int):
    """The golden model's kept keypoints, by cell row, and the expected results in the
    order they are sent (a cell row at a time, its cells left to right, best first)."""
    f = orb.orb_features(img, threshold, "opencv", "3x3", cell=CELL, per_cell=per_cell)
    want = budget_order(f, CELL)
    groups: dict[int, list[dict[str, int]]] = {}
    for x, y, score, _, _ in want:
        groups.setdefault(y // CELL, []).append({"x": x, "y": y, "score": score})
    return groups, want


class PixelStream:
    """One image stream (prefix plain or blurred); `row` is the row of the last pixel taken."""

    def __init__(self, dut, prefix: str, rng: random.Random):
        self.source = StreamSource(dut, dut.clk, prefix, rng, idle=0.1)
        self.row = -1

    async def send(self, img: np.ndarray) -> None:
        def beats():
            for y in range(img.shape[0]):
                for x in range(img.shape[1]):
                    yield {"first": int(x == 0 and y == 0), "x": x, "pixel": int(img[y, x])}

        def taken(i: int) -> None:
            self.row = i // img.shape[1]

        await self.source.send(beats(), on_accept=taken)


@cocotb.test()
async def equals_the_model(dut):
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d, %d frames of %dx%d", cocotb.RANDOM_SEED, FRAMES, WIDTH, HEIGHT)
    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    plain = PixelStream(dut, "plain", rng)
    blurred = PixelStream(dut, "blurred", rng)
    keys = StreamSource(dut, dut.clk, "key", rng, idle=0.2)
    sink = StreamSink(
        dut, dut.clk, "out", ["x", "y", "score", "angle", "descriptor"], rng, stall=0.2
    )
    dut.cell_log.value = (CELL // 16).bit_length() - 1  # log2(CELL) - 4
    dut.key_frame_end.value = 0
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    cocotb.start_soon(sink.run())

    stalls = [0]

    async def count_stalls() -> None:
        while True:
            await RisingEdge(dut.clk)
            if dut.plain_valid.value == 1 and dut.plain_ready.value == 0:
                stalls[0] += 1

    cocotb.start_soon(count_stalls())
    expected = []
    for k, (img, threshold, per_cell) in enumerate(frames(rng)):
        before = stalls[0]
        groups, want = keypoint_groups(img, threshold, per_cell)
        dut._log.info("frame %d: %d keypoints", k, len(want))
        expected += want
        plain.row = blurred.row = -1
        writing = [
            cocotb.start_soon(plain.send(img)),
            cocotb.start_soon(blurred.send(orb.gaussian_blur(img))),
        ]
        # A cell row's keypoints once the input is a row past it (the budget's hand-over),
        # then the frame's end, once both inputs are in the frame.
        for r in sorted(groups):
            while min(plain.row, blurred.row) < CELL * r + CELL:
                await RisingEdge(dut.clk)
            await keys.send(groups[r])
        while min(plain.row, blurred.row) < 0:
            await RisingEdge(dut.clk)
        dut.key_frame_end.value = 1
        await RisingEdge(dut.clk)
        dut.key_frame_end.value = 0
        for w in writing:
            await w
        dut._log.info("frame %d: the image input held on %d clocks", k, stalls[0] - before)
        if threshold == 0:
            assert stalls[0] > before, "noise at t = 0 outruns the engine: the input must wait"
    for _ in range(100_000):
        if len(sink.beats) == len(expected):
            break
        await RisingEdge(dut.clk)
    assert len(sink.beats) == len(expected), f"{len(sink.beats)} results of {len(expected)}"
    for n, (beat, (x, y, score, angle, desc)) in enumerate(zip(sink.beats, expected, strict=True)):
        where = f"result {n} (x {x}, y {y})"
        assert (beat["x"], beat["y"], beat["score"]) == (x, y, score), f"{where}: {beat}"
        assert beat["angle"] == angle, f"{where}: angle {beat['angle']:08x}, model {angle:08x}"
        assert beat["descriptor"] == desc, f"{where}: bits {beat['descriptor'] ^ desc:064x}"
