"""cocotb testbench of fastnms_orb_rows: two frames of random pixels written one pixel per
clock (with idle clocks) while columns are requested at random places among the rows kept:
every column equal to the image's rows top .. top + HEIGHT - 1 at its x, in request order;
requests on random clocks, the columns taken with random stalls; a request taken on every
clock while the columns are taken at once; the first column offered LATENCY clocks after its
request."""

from __future__ import annotations

import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge

from tb.stream import StreamSink, offer_times, sim_ns, value

PERIOD_NS = 10
# docs/orb_rtl.md, fastnms_orb_rows: from a request taken to its column offered, the
# FIFO empty: the request and the addresses registered, the block RAM's two clocks, the
# rotation (two stages a clock), the FIFO's four.
ROTATION_CLOCKS = {31: 3, 37: 3}


class Writer:
    """Writes frames pixel by pixel; `row` is the row of the last pixel sent in its
    frame, `base` the ring's number of the frame's row 0 (rows are numbered on across
    frames from 0 after reset)."""

    def __init__(self, dut, rng):
        self.dut, self.rng = dut, rng
        self.row = -1
        self.base, self.next_base = 0, 0
        dut.wr_valid.value = 0

    def begin(self, height: int) -> None:
        """A frame of `height` rows starts."""
        self.base, self.next_base = self.next_base, self.next_base + height
        self.row = -1

    async def frame(self, img: np.ndarray, idle: float) -> None:
        dut = self.dut
        for y, line in enumerate(img):
            for x, p in enumerate(line):
                while self.rng.random() < idle:
                    dut.wr_valid.value = 0
                    await RisingEdge(dut.clk)
                dut.wr_valid.value = 1
                dut.wr_x.value = x
                dut.wr_pixel.value = int(p)
                self.row = y
                await RisingEdge(dut.clk)
        dut.wr_valid.value = 0


async def request(dut, writer, img, rows, height, count, rng, idle, expected):
    """count requests for columns whose rows are written and still kept."""
    h, w = img.shape
    sent = 0
    times = []
    while sent < count:
        c = writer.row
        low, high = max(0, c - rows + 3), c - height  # top row range: complete and kept
        if high < low or rng.random() < idle:
            dut.rd_valid.value = 0
            await RisingEdge(dut.clk)
            continue
        top = rng.randint(low, high)
        x = rng.randrange(w)
        dut.rd_valid.value = 1
        dut.rd_x.value = x
        dut.rd_top.value = (writer.base + top) % rows
        await RisingEdge(dut.clk)
        while not value(dut.rd_ready):
            await RisingEdge(dut.clk)
        times.append(sim_ns())
        expected.append(int.from_bytes(img[top : top + height, x].tobytes(), "little"))
        sent += 1
    dut.rd_valid.value = 0
    return times


@cocotb.test()
async def columns_equal_the_image(dut):
    height, slots = int(dut.HEIGHT.value), int(dut.SLOTS.value)
    width = int(dut.MAX_WIDTH.value)
    rows = height * slots
    rng = random.Random(cocotb.RANDOM_SEED)
    nrng = np.random.default_rng(rng.getrandbits(32))
    dut._log.info("seed=%d, HEIGHT %d, SLOTS %d", cocotb.RANDOM_SEED, height, slots)
    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    dut.rd_valid.value = 0
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    writer = Writer(dut, rng)
    sink = StreamSink(dut, dut.clk, "out", ["column"], rng, stall=0.3)
    sink_task = cocotb.start_soon(sink.run())
    offered = offer_times(dut.clk, dut.out_valid)

    # The first request alone: the latency.
    img = nrng.integers(0, 256, size=(rows + height, width), dtype=np.uint8)
    expected: list[int] = []
    sink.stall = 0.0
    writer.begin(len(img))
    await writer.frame(img[: height + 1], idle=0.0)
    first = await request(dut, writer, img, rows, height, 1, rng, 0.0, expected)
    while len(sink.beats) < 1:
        await RisingEdge(dut.clk)
    latency = (offered[0] - first[0]) // PERIOD_NS
    dut._log.info("first column offered %d clocks after its request", latency)
    assert latency == 2 + 2 + ROTATION_CLOCKS[height] + 4, latency

    # Two frames (the first goes on), requests while they are written; the second's
    # rows follow the first's in the ring.
    sink.stall = 0.3
    for frame in range(2):
        if frame:
            img = nrng.integers(0, 256, size=(rows + 2 * height, width), dtype=np.uint8)
            writer.begin(len(img))
            start = 0
        else:
            start = height + 1
        writing = cocotb.start_soon(writer_rest(writer, img, start))
        await request(dut, writer, img, rows, height, 300, rng, 0.5, expected)
        # Back to back: a request on every clock.
        sink.stall = 0.0
        times = await request(dut, writer, img, rows, height, 100, rng, 0.0, expected)
        gaps = {(b - a) // PERIOD_NS for a, b in zip(times[:-1], times[1:], strict=True)}
        assert gaps == {1}, f"requests taken {gaps} clocks apart"
        sink.stall = 0.3
        await writing
    for _ in range(1000):
        if len(sink.beats) == len(expected):
            break
        await RisingEdge(dut.clk)
    sink_task.cancel()
    assert len(sink.beats) == len(expected)
    for k, (beat, want) in enumerate(zip(sink.beats, expected, strict=True)):
        assert beat["column"] == want, f"column {k}: {beat['column']:x}, image {want:x}"


async def writer_rest(writer, img, start):
    """The rest of a frame from row `start`."""
    dut = writer.dut
    for y in range(start, len(img)):
        for x in range(img.shape[1]):
            while writer.rng.random() < 0.1:
                dut.wr_valid.value = 0
                await RisingEdge(dut.clk)
            dut.wr_valid.value = 1
            dut.wr_x.value = x
            dut.wr_pixel.value = int(img[y, x])
            writer.row = y
            await RisingEdge(dut.clk)
    dut.wr_valid.value = 0
