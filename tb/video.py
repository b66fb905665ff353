"""Shared testbench pieces for the core's pixel-stream blocks (window
generator, detector, ...): frames as input beats, a TB class with clock,
reset, a source and a sink with idle/back-pressure, configuration ports set
per frame, and error-pulse counters."""

from __future__ import annotations

import random
from collections.abc import Sequence

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge

from tb.stream import StreamSink, StreamSource, value

PERIOD_NS = 10


def min_width(window: int, ppc: int = 1, read_latency: int = 1) -> int:
    """The narrowest frame fastnms_window takes: `window` pixels, raised to
    whole beats of `ppc` pixels and to at least read_latency + 1 beats."""
    return -(-max(window, (read_latency + 1) * ppc) // ppc) * ppc


def whole_beats(width: int, ppc: int, narrowest: int) -> int:
    """A frame width rounded down to whole beats, at least `narrowest`."""
    return max(narrowest, width // ppc * ppc)


def frame_beats(
    img: np.ndarray, data: str = "data", ppc: int = 1, bits: int = 8
) -> list[dict[str, int]]:
    """The input beats of a well-formed frame: `ppc` pixels of `bits` bits
    each per beat in field `data`, pixel 0 in the low bits (as UG934 packs
    video). A width that is not a multiple of `ppc` ends each row with a
    short beat padded with zeros (a malformed frame)."""
    h, w = img.shape
    beats = []
    for y in range(h):
        for x0 in range(0, w, ppc):
            word = 0
            for i, v in enumerate(img[y, x0 : x0 + ppc]):
                word |= int(v) << (bits * i)
            beats.append({data: word, "sof": int(x0 == 0 and y == 0), "eol": int(x0 + ppc >= w)})
    return beats


def record_mismatch(got: list, want: list, label: str) -> str:
    """A one-line description of how two record lists differ."""
    for i, (g, w) in enumerate(
        zip(got + [None] * len(want), want + [None] * len(got), strict=False)
    ):
        if g != w:
            return f"{label}: rtl {len(got)} records, golden {len(want)}; #{i}: rtl {g}, golden {w}"
    return f"{label}: equal"


def split_records(
    beats: list[dict[str, int]], fields: tuple[str, ...] = ("x", "y", "score")
) -> list[list[tuple[int, ...]]]:
    """Record beats (their `fields`, x, y, score by default) grouped into
    frames, each closed by an end-of-frame beat; a trailing group without its
    end is dropped."""
    frames: list[list[tuple[int, ...]]] = []
    current: list[tuple[int, ...]] = []
    for beat in beats:
        if beat["eof"]:
            frames.append(current)
            current = []
        else:
            current.append(tuple(beat[f] for f in fields))
    return frames


def split_frames(beats: list[dict[str, int]]) -> list[list[dict[str, int]]]:
    """Output beats grouped into frames at each sof."""
    frames: list[list[dict[str, int]]] = []
    for beat in beats:
        if beat["sof"] or not frames:
            frames.append([])
        frames[-1].append(beat)
    return frames


class VideoTB:
    """A DUT with clk, rst, cfg_* ports, an `in` pixel stream (`ppc` pixels
    of `bits` bits per beat), an `out` stream with the given fields, and
    err_line/err_frame pulses."""

    def __init__(
        self,
        dut,
        out_fields: list[str],
        idle: float = 0.0,
        stall: float = 0.0,
        data: str = "data",
        ppc: int = 1,
        bits: int = 8,
    ):
        self.dut = dut
        self.data = data
        self.ppc = ppc
        self.bits = bits
        self.rng = random.Random(cocotb.RANDOM_SEED)
        self.np_rng = np.random.default_rng(cocotb.RANDOM_SEED)
        dut._log.info("seed=%d idle=%.2f stall=%.2f", cocotb.RANDOM_SEED, idle, stall)
        cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
        self.source = StreamSource(dut, dut.clk, "in", self.rng, idle)
        self.sink = StreamSink(dut, dut.clk, "out", out_fields, self.rng, stall)
        self.err_line = 0
        self.err_frame = 0
        self.running = False

    def set_cfg(self, **cfg: int) -> None:
        """Drive cfg_<name> ports."""
        for name, v in cfg.items():
            getattr(self.dut, f"cfg_{name}").value = v

    async def reset(self) -> None:
        self.dut.rst.value = 1
        self.dut.in_valid.value = 0
        await ClockCycles(self.dut.clk, 3)
        self.dut.rst.value = 0
        await RisingEdge(self.dut.clk)
        if not self.running:  # monitors start once outputs are defined
            self.running = True
            cocotb.start_soon(self.sink.run())
            cocotb.start_soon(self._count_errors())

    async def _count_errors(self) -> None:
        while True:
            await RisingEdge(self.dut.clk)
            self.err_line += value(self.dut.err_line)
            self.err_frame += value(self.dut.err_frame)

    async def send_frames(self, frames: Sequence[np.ndarray], cfgs: Sequence[dict]) -> None:
        """Send frames back to back. Frame i's configuration is driven two
        clocks before its first pixel for the first frame, and as soon as
        frame i-1's first pixel was accepted for the others."""
        self.set_cfg(**cfgs[0])
        await ClockCycles(self.dut.clk, 2)  # the documented set-up time
        for i, img in enumerate(frames):
            nxt = cfgs[i + 1] if i + 1 < len(frames) else None

            def after(k, nxt=nxt):
                if k == 0 and nxt is not None:
                    self.set_cfg(**nxt)

            await self.source.send(
                frame_beats(img, self.data, self.ppc, self.bits), on_accept=after
            )

    async def wait_eofs(self, count: int, budget_cycles: int) -> None:
        """Wait until the sink holds `count` end-of-frame beats; fail after
        the budget or on any extra beat."""
        for _ in range(budget_cycles):
            if sum(b["eof"] for b in self.sink.beats) >= count:
                break
            await RisingEdge(self.dut.clk)
        await ClockCycles(self.dut.clk, 20)  # anything extra would show up now
        eofs = sum(b["eof"] for b in self.sink.beats)
        assert eofs == count, f"expected {count} end-of-frame beats, got {eofs}"
        assert self.sink.beats[-1]["eof"], "beats after the last end of frame"

    async def wait_beats(self, count: int, budget_cycles: int) -> None:
        """Wait until the sink holds `count` beats; fail after the budget."""
        for _ in range(budget_cycles):
            if len(self.sink.beats) >= count:
                break
            await RisingEdge(self.dut.clk)
        await ClockCycles(self.dut.clk, 20)  # anything extra would show up now
        lengths = [len(f) for f in split_frames(self.sink.beats)]
        self.dut._log.info("frame lengths %s", lengths)
        assert len(self.sink.beats) == count, (
            f"expected {count} output beats, got {len(self.sink.beats)}"
        )
