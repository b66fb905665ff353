"""cocotb testbench of fastnms_nms_3x3 on its own: arbitrary score maps
against the golden model's 3x3 rule (fastnms.nms.nms_3x3). With ROW_MARKS,
also the row-end beats: one after the records of each line y with
y % 16 == 15 (not the frame's last), before any record of a later line."""

from __future__ import annotations

import ast
import os

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden.nms import nms_3x3

from tb.stream import value
from tb.video import VideoTB, min_width, record_mismatch, split_records, whole_beats

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
SCORE_BITS = GENERICS["SCORE_BITS"]
LATENCY = GENERICS.get("READ_LATENCY", 1)
PPC = GENERICS.get("PPC", 1)
ROW_MARKS = GENERICS.get("ROW_MARKS", False)
# The core's narrowest frame (7), as the window generator raises it.
MIN_WIDTH = min_width(7, PPC, LATENCY)
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))


class TB(VideoTB):
    def __init__(self, dut, idle: float = IDLE, stall: float = STALL):
        super().__init__(
            dut,
            ["x", "y", "score", "eof", "row_end"],
            idle,
            stall,
            data="score",
            ppc=PPC,
            bits=SCORE_BITS,
        )
        dut._log.info("generics %s", GENERICS)
        self.set_cfg(width=MIN_WIDTH, height=7)
        self.input_waits = 0  # clocks with in_valid high and in_ready low

    async def count_input_waits(self) -> None:
        while True:
            await RisingEdge(self.dut.clk)
            if value(self.dut.in_valid) and not value(self.dut.in_ready):
                self.input_waits += 1

    def score_map(self, width: int, height: int) -> np.ndarray:
        """A random map: sparse to dense, few distinct values (many ties) or
        the full range; the outermost ring is 0 (the block's precondition)."""
        rng = self.np_rng
        density = rng.choice([0.05, 0.3, 0.7, 1.0])
        top = int(rng.choice([3, 2**SCORE_BITS - 1]))
        scores = rng.integers(1, top + 1, (height, width)) * (rng.random((height, width)) < density)
        scores[0, :] = scores[-1, :] = scores[:, 0] = scores[:, -1] = 0
        return scores.astype(np.int64)

    async def run_maps(self, maps: list[np.ndarray]) -> None:
        await self.send_frames(maps, [{"width": m.shape[1], "height": m.shape[0]} for m in maps])
        total = sum(m.size for m in maps)
        await self.wait_eofs(len(maps), 20 * total + 1000)
        records = [b for b in self.sink.beats if not b["row_end"]]
        frames = split_records(records)
        row_ends = split_row_ends(self.sink.beats)
        for i, (scores, got) in enumerate(zip(maps, frames, strict=True)):
            want = [tuple(int(v) for v in r) for r in nms_3x3(scores > 0, scores)]
            height, width = scores.shape
            label = f"frame {i} ({width}x{height})"
            assert got == want, record_mismatch(got, want, label)
            lines = range(15, height - 1, 16) if ROW_MARKS else []
            assert row_ends[i] == [(width - 1, y) for y in lines], (
                f"{label}: row ends {row_ends[i]}"
            )
        assert self.err_line == 0 and self.err_frame == 0


def split_row_ends(beats: list[dict[str, int]]) -> list[list[tuple[int, int]]]:
    """Per frame, the row-end beats (x, y), each checked to have score 0 and to come
    after every record of its line and before every record of a later line."""
    frames: list[list[tuple[int, int]]] = [[]]
    last_y = -1
    for beat in beats:
        if beat["eof"]:
            assert not beat["row_end"], beat
            frames.append([])
            last_y = -1
        elif beat["row_end"]:
            assert beat["score"] == 0 and beat["y"] >= last_y, (beat, last_y)
            frames[-1].append((beat["x"], beat["y"]))
            last_y = beat["y"] + 1  # records after it are on later lines
        else:
            assert beat["y"] >= last_y, f"record {beat} after the row end of line {last_y - 1}"
            last_y = beat["y"]
    return frames


@cocotb.test()
async def random_maps(dut):
    """Back-to-back maps of several sizes, including the smallest (7x7) and
    MAX_WIDTH wide, plateaus of equal scores, sparse and dense maps."""
    tb = TB(dut)
    await tb.reset()
    rng = tb.np_rng

    def beats(width: int) -> int:
        return whole_beats(width, PPC, MIN_WIDTH)

    sizes = [(MIN_WIDTH, 7), (MAX_WIDTH, 8), (beats(9), 12), (beats(8), 7)]
    sizes += [
        (beats(int(rng.integers(7, MAX_WIDTH + 1))), int(rng.integers(7, 20))) for _ in range(6)
    ]
    await tb.run_maps([tb.score_map(w, h) for w, h in sizes])


@cocotb.test()
async def plateaus(dut):
    """Flat areas: equal neighbours suppress each other, so a plateau keeps
    nothing and a single peak on it survives."""
    tb = TB(dut)
    await tb.reset()
    flat = np.zeros((9, 12), dtype=np.int64)
    flat[1:-1, 1:-1] = 5
    peak = flat.copy()
    peak[4, 6] = 6
    empty = np.zeros((7, MIN_WIDTH), dtype=np.int64)
    await tb.run_maps([flat, peak, empty])
    assert split_records(tb.sink.beats)[1] == [(6, 4, 6)]


@cocotb.test()
async def idle_after_frame(dut):
    """The end-of-frame beat of the last frame leaves without further input."""
    tb = TB(dut)
    await tb.reset()
    await tb.run_maps([tb.score_map(MAX_WIDTH, 9)])
    await ClockCycles(dut.clk, 10)


@cocotb.test()
async def densest_survivors(dut):
    """The most survivors a map can have (every other pixel of every other
    row, MAX_WIDTH wide; with PPC = 4 two per beat on those rows), three
    frames back to back with the output always ready: the input never waits,
    and the records are exact."""
    tb = TB(dut, idle=0.0, stall=0.0)
    await tb.reset()
    cocotb.start_soon(tb.count_input_waits())
    height = 40  # two row ends per frame with ROW_MARKS
    dense = np.ones((height, MAX_WIDTH), dtype=np.int64)
    dense[1::2, 1::2] = 2
    dense[0, :] = dense[-1, :] = dense[:, 0] = dense[:, -1] = 0
    survivors = len(nms_3x3(dense > 0, dense))
    dut._log.info("%d survivors in a %dx%d map", survivors, MAX_WIDTH, height)
    assert survivors >= (MAX_WIDTH // 2 - 1) * (height // 2 - 1)
    await tb.run_maps([dense, dense, dense])
    assert tb.input_waits == 0, f"the input waited {tb.input_waits} clocks"
