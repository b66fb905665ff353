"""cocotb testbench of fastnms_cell_budget on its own: record streams in raster order
(any density up to a record every clock, scores with many ties or the full range) against
the golden model's budget (fastnms.golden.budget.cell_budget), in the block's documented
output order: cell rows in order, cells left to right, best first within a cell; every
record in input order with K = 0. Frames come with or without row-end beats (one after
the records of every 16th line, as the core's NMS sends them), chosen at random per frame;
row-end beats never reach the output."""

from __future__ import annotations

import ast
import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden.budget import hardware_order
from fastnms.golden.model import detect
from fastnms.testing import images as testimages

from tb.stream import StreamSink, StreamSource, sim_ns, value
from tb.video import PERIOD_NS, record_mismatch

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
MAX_HEIGHT = GENERICS["MAX_HEIGHT"]
SCORE_BITS = GENERICS["SCORE_BITS"]
MAX_PER_CELL = GENERICS.get("MAX_PER_CELL", 15)
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))
CLEAR_CLOCKS = (MAX_WIDTH + 15) // 16
# From a row-end beat taken to its row's drain: the input's two buffers (the decode,
# fastnms_budget_decode), the job queue and the drain's two settle clocks.
DRAIN_PIPELINE = 2 + 1 + 2


def expected(records: np.ndarray, cell_log: int, per_cell: int) -> list[tuple[int, int, int]]:
    """The frame's output records in the block's order."""
    k = min(per_cell, MAX_PER_CELL)
    return [tuple(r) for r in hardware_order(records, 16 << min(cell_log, 4), k).tolist()]


class TB:
    def __init__(self, dut, idle: float = IDLE, stall: float = STALL):
        self.dut = dut
        self.rng = random.Random(cocotb.RANDOM_SEED)
        self.np_rng = np.random.default_rng(cocotb.RANDOM_SEED)
        dut._log.info(
            "seed=%d generics %s idle %.2f stall %.2f", cocotb.RANDOM_SEED, GENERICS, idle, stall
        )
        cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
        self.source = StreamSource(dut, dut.clk, "in", self.rng, idle)
        self.sink = StreamSink(dut, dut.clk, "out", ["x", "y", "score", "eof"], self.rng, stall)
        self.held = 0  # clocks with in_valid high and in_ready low
        self.running = False

    async def reset(self) -> None:
        self.dut.rst.value = 1
        self.dut.in_valid.value = 0
        await ClockCycles(self.dut.clk, 3)
        self.dut.rst.value = 0
        await RisingEdge(self.dut.clk)
        if not self.running:
            self.running = True
            cocotb.start_soon(self.sink.run())
            cocotb.start_soon(self._count_holds())

    async def _count_holds(self) -> None:
        while True:
            await RisingEdge(self.dut.clk)
            if value(self.dut.in_valid) and not value(self.dut.in_ready):
                self.held += 1

    def random_records(self, width: int, height: int, density: float, top: int) -> np.ndarray:
        rng = self.np_rng
        flags = rng.random((height, width)) < density
        ys, xs = np.nonzero(flags)
        scores = rng.integers(0, top + 1, len(xs))
        return np.stack([xs, ys, scores], axis=1).astype(np.int64)

    def random_frame(self) -> tuple[np.ndarray, int, int, int, int]:
        rng = self.np_rng
        width = int(rng.integers(7, MAX_WIDTH + 1))
        height = int(rng.integers(7, MAX_HEIGHT + 1))
        density = float(rng.choice([0.0, 0.02, 0.2, 0.6, 1.0]))
        top = int(rng.choice([1, 3, 2**SCORE_BITS - 1]))
        cell_log = int(rng.choice([0, 0, 1, 2, 4, 7]))
        per_cell = int(rng.choice([0, 1, 2, 5, 15]))
        return self.random_records(width, height, density, top), width, height, cell_log, per_cell

    @staticmethod
    def beats(frame, row_ends: bool = False) -> list[dict[str, int]]:
        """The frame's beats: its records, with `row_ends` a row-end beat after the records
        of each line y with y % 16 == 15 (the frame's last line excepted), then its end."""
        records, width, height, cell_log, per_cell = frame
        cfg = {"cell_log": cell_log, "per_cell": per_cell}
        out = []
        by_line: dict[int, list] = {}
        for x, y, s in records.tolist():
            by_line.setdefault(y, []).append((x, y, s))
        for line in range(height):
            for x, y, s in by_line.get(line, []):
                out.append({"x": x, "y": y, "score": s, "eof": 0, "row_end": 0, **cfg})
            if row_ends and line % 16 == 15 and line < height - 1:
                out.append({"x": width - 1, "y": line, "score": 0, "eof": 0, "row_end": 1, **cfg})
        end = {"x": width - 1, "y": height - 1, "score": 0, "eof": 1, "row_end": 0, **cfg}
        return out + [end]

    async def send_paced(self, beats: list[dict[str, int]], width: int) -> None:
        """Send one frame's beats as an NMS at one pixel per clock does: a beat no earlier
        than its pixel's clock (y * width + x after the first), later when the input waits."""
        clock = 0
        for beat in beats:
            while clock < beat["y"] * width + beat["x"]:
                self.dut.in_valid.value = 0
                await RisingEdge(self.dut.clk)
                clock += 1
            for field, v in beat.items():
                getattr(self.dut, f"in_{field}").value = v
            self.dut.in_valid.value = 1
            await RisingEdge(self.dut.clk)
            clock += 1
            while not value(self.dut.in_ready):
                await RisingEdge(self.dut.clk)
                clock += 1
        self.dut.in_valid.value = 0

    async def run_frames(
        self, frames: list, label: str, row_ends: bool | None = None, paced: bool = False
    ) -> None:
        """Send the frames back to back (with row-end beats, without, or with None at
        random per frame; `paced`: one frame at the pixels' clocks, see send_paced);
        compare every frame's output with the golden."""
        start = len(self.sink.beats)
        beats = []
        for f in frames:
            marked = self.rng.random() < 0.5 if row_ends is None else row_ends
            beats += self.beats(f, marked)
        if paced:
            assert len(frames) == 1
            await self.send_paced(beats, frames[0][1])
        else:
            await self.source.send(beats)
        want_eofs = len(frames)
        for _ in range(200 * len(beats) + 2000):
            got_eofs = sum(b["eof"] for b in self.sink.beats[start:])
            if got_eofs >= want_eofs:
                break
            await RisingEdge(self.dut.clk)
        out = self.sink.beats[start:]
        frames_out: list[list[tuple[int, int, int]]] = [[]]
        ends = []
        for b in out:
            if b["eof"]:
                ends.append((b["x"], b["y"]))
                frames_out.append([])
            else:
                frames_out[-1].append((b["x"], b["y"], b["score"]))
        assert len(ends) == want_eofs, f"{label}: {len(ends)} of {want_eofs} frames ended"
        for i, f in enumerate(frames):
            records, width, height, cell_log, per_cell = f
            want = expected(records, cell_log, per_cell)
            context = f"{label} frame {i} ({width}x{height}, cell_log {cell_log}, K {per_cell})"
            assert frames_out[i] == want, record_mismatch(frames_out[i], want, context)
            assert ends[i] == (width - 1, height - 1), context


@cocotb.test()
async def random_frames(dut):
    """Frames of every size, density, tie pattern and configuration, back to back."""
    tb = TB(dut)
    await tb.reset()
    await ClockCycles(dut.clk, CLEAR_CLOCKS + 2)
    for group in range(6):
        await tb.run_frames([tb.random_frame() for _ in range(5)], f"group {group}")


@cocotb.test()
async def every_configuration(dut):
    """Each CELL (16 .. 256, and a value above) with K 1, MAX_PER_CELL and above it, on a
    dense frame with two scores (most records tie)."""
    tb = TB(dut)
    await tb.reset()
    await ClockCycles(dut.clk, CLEAR_CLOCKS + 2)
    frames = []
    for cell_log in (0, 1, 2, 3, 4, 5):
        for per_cell in (1, MAX_PER_CELL, 15):
            records = tb.random_records(MAX_WIDTH, MAX_HEIGHT, 0.7, 1)
            frames.append((records, MAX_WIDTH, MAX_HEIGHT, cell_log, per_cell))
    await tb.run_frames(frames, "configurations")


@cocotb.test()
async def never_holds_a_dense_stream(dut):
    """A record every clock at full width over many cell rows (K 15, CELL 16, no output
    back-pressure): after the reset's clear the input never waits."""
    tb = TB(dut, idle=0.0, stall=0.0)
    await tb.reset()
    await ClockCycles(dut.clk, CLEAR_CLOCKS + 2)
    held = tb.held
    records = tb.random_records(MAX_WIDTH, MAX_HEIGHT, 1.0, 2**SCORE_BITS - 1)
    await tb.run_frames([(records, MAX_WIDTH, MAX_HEIGHT, 0, 15)], "dense")
    assert tb.held == held, f"the input waited {tb.held - held} clocks"


@cocotb.test()
async def reset_mid_frame(dut):
    """A reset in the middle of a frame (and of a drain): the next frames are exact."""
    tb = TB(dut)
    await tb.reset()
    await ClockCycles(dut.clk, CLEAR_CLOCKS + 2)
    records = tb.random_records(MAX_WIDTH, MAX_HEIGHT, 0.5, 3)
    beats = TB.beats((records, MAX_WIDTH, MAX_HEIGHT, 0, 3), row_ends=True)
    sending = cocotb.start_soon(tb.source.send(beats[: len(beats) // 2]))
    await ClockCycles(dut.clk, len(beats) // 3)
    sending.cancel()
    await tb.reset()
    await ClockCycles(dut.clk, CLEAR_CLOCKS + 2)
    tb.sink.beats.clear()
    await tb.run_frames([tb.random_frame() for _ in range(3)], "after reset")


@cocotb.test()
async def photographs(dut):
    """The 3x3 NMS's records of crops of real photographs (both scores where the scores are
    12 bits, thresholds 5 to 20, the golden model's), CELL 16 to 64, back to back."""
    tb = TB(dut)
    await tb.reset()
    await ClockCycles(dut.clk, CLEAR_CLOCKS + 2)
    frames = []
    for i, path in enumerate(testimages.real_images()[:3]):
        img = testimages.crop(path, MAX_WIDTH, MAX_HEIGHT)
        score = "sad" if SCORE_BITS >= 12 and i % 2 else "opencv"
        records = detect(img, (5, 10, 20, 30)[i % 4], score, "3x3")
        h, w = img.shape
        for cell_log, per_cell in ((0, 15), (1 + i, 2)):
            frames.append((records, w, h, cell_log, per_cell))
    assert sum(len(f[0]) for f in frames) > 0
    await tb.run_frames(frames, "photographs")


@cocotb.test()
async def late_row_then_dense_row(dut):
    """The content that makes the input wait without row-end beats: a full cell row, then
    a cell row whose only record is on its last line, then a full cell row. The third row
    needs the first row's bank while that row still drains (started by the second row's
    record). Measured three ways (K 15, CELL 16):
    - back to back, without row-end beats: the wait is at most the drain, 4 clocks per
      cell plus one per record, plus 4;
    - at the pixels' clocks (one pixel per clock, as from an NMS), without row-end beats:
      the drain has one line more, so the wait is that bound less a line (none when a
      line takes longer than the drain);
    - at the pixels' clocks with row-end beats: the first row's drain starts at its last
      line's row-end beat, a cell row ahead: the input never waits."""
    if MAX_HEIGHT < 48 or MAX_PER_CELL < 15:
        return
    tb = TB(dut, idle=0.0, stall=0.0)
    await tb.reset()
    await ClockCycles(dut.clk, CLEAR_CLOCKS + 2)
    ys, xs = np.mgrid[0:48, 0:MAX_WIDTH]
    keep = (ys < 16) | (ys >= 32) | ((ys == 31) & (xs == 0))
    scores = tb.np_rng.integers(0, 2**SCORE_BITS, keep.sum())
    records = np.stack([xs[keep], ys[keep], scores], axis=1).astype(np.int64)
    frame = (records, MAX_WIDTH, 48, 0, 15)
    bound = -(-MAX_WIDTH // 16) * (4 + 15) + 4
    held = tb.held
    await tb.run_frames([frame], "late row", row_ends=False)
    dut._log.info("back to back: the input waited %d clocks (bound %d)", tb.held - held, bound)
    assert 0 < tb.held - held <= bound, f"waited {tb.held - held}, bound {bound}"
    held = tb.held
    await tb.run_frames([frame], "late row, paced", row_ends=False, paced=True)
    paced_bound = max(0, bound - MAX_WIDTH)
    dut._log.info("paced: the input waited %d clocks (bound %d)", tb.held - held, paced_bound)
    assert tb.held - held <= paced_bound, f"waited {tb.held - held}, bound {paced_bound}"
    held = tb.held
    await tb.run_frames([frame], "late row, paced, row ends", row_ends=True, paced=True)
    assert tb.held == held, f"with row-end beats the input waited {tb.held - held} clocks"


@cocotb.test()
async def row_end_starts_the_drain(dut):
    """A cell row's records leave after its last line's row-end beat, not at the next
    record or the end of frame: within the drain (4 clocks per cell up to the last cell
    written, plus one per record) and DRAIN_PIPELINE clocks, for each CELL
    whose rows end before the frame's last line. Row-end beats at lines that do not end
    a cell row change nothing."""
    if MAX_HEIGHT < 32:
        return
    tb = TB(dut, idle=0.0, stall=0.0)
    await tb.reset()
    await ClockCycles(dut.clk, CLEAR_CLOCKS + 2)
    for cell_log in (0, 1):
        cell = 16 << cell_log
        if cell >= MAX_HEIGHT:
            continue
        k = min(MAX_PER_CELL, 15)
        records = tb.random_records(MAX_WIDTH, cell, 0.5, 2**SCORE_BITS - 1)
        frame = (records, MAX_WIDTH, MAX_HEIGHT, cell_log, k)
        beats = TB.beats(frame, row_ends=True)
        first_row_end = next(i for i, b in enumerate(beats) if b["row_end"] and b["y"] == cell - 1)
        start = len(tb.sink.beats)
        want = expected(records, cell_log, k)
        await tb.source.send(beats[: first_row_end + 1])
        taken = sim_ns()
        cells = -(-MAX_WIDTH // cell)
        bound = cells * 4 + len(want) + DRAIN_PIPELINE
        await ClockCycles(dut.clk, bound + 1)
        got = [(b["x"], b["y"], b["score"]) for b in tb.sink.beats[start:]]
        assert got == want, record_mismatch(got, want, f"CELL {cell}, after its row end")
        last = (tb.sink.times[-1] - taken) // PERIOD_NS if want else 0
        dut._log.info(
            "CELL %d: %d records, the last %d clocks after the row end (bound %d)",
            cell,
            len(want),
            last,
            bound,
        )
        assert last <= bound, f"CELL {cell}: the last record {last} clocks after, bound {bound}"
        await tb.source.send(beats[first_row_end + 1 :])
        await ClockCycles(dut.clk, 20)
        assert [b["eof"] for b in tb.sink.beats[start + len(want) :]] == [1]
