"""The cocotb side of the simulation driver: drives fastnms_axi's ports with
cocotbext-axi (AxiStreamSource for the video, AxiStreamSink for the corner
records and the score video, AxiLiteMaster for the registers), counts clocks,
and decodes the corner records.

Used by the testbenches of the top (tb/top/), which adds the checks;
the cocotb engine (sim/frame_tb.py) takes its clock period and video packets.
It runs inside the simulator and knows nothing of the tests.
"""

from __future__ import annotations

import logging
import random
from collections.abc import Iterator, Sequence

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, Event, RisingEdge, Timer
from cocotbext.axi import (
    AxiLiteBus,
    AxiLiteMaster,
    AxiResp,
    AxiStreamBus,
    AxiStreamFrame,
    AxiStreamSink,
    AxiStreamSource,
)

from . import regs
from .axi_protocol import AxiProtocolChecker

PERIOD_NS = 10
Record = tuple[int, int, int]


def frame_writes(
    width: int,
    height: int,
    threshold: int,
    budget: tuple[int, int] | None = None,
    min_area: int | None = None,
) -> list[tuple[int, int]]:
    """The register writes of one frame as (offset, value): WIDTH, HEIGHT, then BUDGET =
    (cell, per_cell) and MIN_AREA when given, THRESHOLD last: the one order both engines
    use (the fast engine's: sim/verilator_harness.cpp)."""
    writes = [(regs.WIDTH, width), (regs.HEIGHT, height)]
    if budget is not None:
        cell, per_cell = budget
        value = cell << regs.BUDGET_CELL.lsb | per_cell << regs.BUDGET_PER_CELL.lsb
        writes.append((regs.BUDGET, value))
    if min_area is not None:
        writes.append((regs.MIN_AREA, min_area << regs.MIN_AREA_VALUE.lsb))
    writes.append((regs.THRESHOLD, threshold))
    return writes


def record_words(frame: AxiStreamFrame) -> list[int]:
    """The 64-bit records of one received corner frame (the sink gets 8 byte lanes:
    m_axis_corners has TKEEP, and a byte with TKEEP low would be missing here)."""
    data = bytes(frame.tdata)
    assert len(data) % 8 == 0, f"a corner frame of {len(data)} bytes (TKEEP not all ones?)"
    return [int.from_bytes(data[i : i + 8], "little") for i in range(0, len(data), 8)]


def decode(frame: AxiStreamFrame) -> tuple[list[Record], list[int]]:
    """The records (x, y, score) of one received corner frame and their flags
    (EMPTY | LAST << 1 | ABORTED << 2 | OVERFLOW << 3)."""
    records, flags = [], []
    for word in record_words(frame):
        records.append((regs.REC_X.get(word), regs.REC_Y.get(word), regs.REC_SCORE.get(word)))
        flags.append(
            regs.REC_EMPTY.get(word)
            | regs.REC_LAST.get(word) << 1
            | regs.REC_ABORTED.get(word) << 2
            | regs.REC_OVERFLOW.get(word) << 3
        )
    return records, flags


def corners(frame: AxiStreamFrame) -> list[Record]:
    """The corners of one received frame: its records, none for the one record
    of a frame without corners."""
    records, flags = decode(frame)
    return [] if flags == [0b011] else records


def video_lines(img: np.ndarray, ppc: int = 1) -> list[AxiStreamFrame]:
    """A well-formed frame as AXI4-Stream packets, one per line (tlast at its end),
    tuser on the first beat. With `ppc` pixels per beat (the source's byte
    lanes) the tuser list has one entry per byte: cocotbext-axi drives a beat's
    tuser from its last byte, so every byte of the first beat carries it."""
    h, w = img.shape
    return [
        AxiStreamFrame(bytes(img[y].tobytes()), tuser=[int(y == 0 and i < ppc) for i in range(w)])
        for y in range(h)
    ]


def pauses(rng: random.Random, probability: float) -> Iterator[bool]:
    while True:
        yield rng.random() < probability


class AxiTop:
    """fastnms_axi under cocotbext-axi drivers. Create with `await AxiTop.create(dut,
    generics, ...)`: the drivers must see aresetn fall before the first clock edge
    (the DUT's outputs are undefined until its reset).

    Clocks are counted at rising edges of aclk: `first_pixel` is the clock of the
    first input handshake; `last_pixels` the clock of each frame's last input
    handshake once `frame_pixels` is set; `last_records` the clock of each
    frame's last corner record (tlast handshake); `input_stalls` the clocks with
    video tvalid high and tready low.
    """

    def __init__(self, dut, generics: dict[str, object], idle: float, stall: float):
        self.dut = dut
        self.generics = generics
        self.score_video = bool(generics.get("SCORE_VIDEO", False))
        self.ppc = int(generics.get("PPC", 1))
        self.rng = random.Random(cocotb.RANDOM_SEED)
        self.np_rng = np.random.default_rng(cocotb.RANDOM_SEED)
        dut._log.info(
            "seed=%d idle=%.2f stall=%.2f generics=%s", cocotb.RANDOM_SEED, idle, stall, generics
        )
        self.source = AxiStreamSource(
            AxiStreamBus.from_prefix(dut, "s_axis_video"), dut.aclk, dut.aresetn, False
        )
        self.sink = AxiStreamSink(
            AxiStreamBus.from_prefix(dut, "m_axis_corners"), dut.aclk, dut.aresetn, False
        )
        self.score_sink = None
        if self.score_video:
            self.score_sink = AxiStreamSink(
                AxiStreamBus.from_prefix(dut, "m_axis_score"), dut.aclk, dut.aresetn, False
            )
        else:
            dut.m_axis_score_tready.value = 0
        self.axil = AxiLiteMaster(
            AxiLiteBus.from_prefix(dut, "s_axi_ctrl"), dut.aclk, dut.aresetn, False
        )
        for name in ("s_axis_video", "m_axis_corners", "m_axis_score", "s_axi_ctrl"):
            logging.getLogger(f"cocotb.{dut._name}.{name}").setLevel(logging.WARNING)
        self.set_idle(idle)
        self.set_stall(stall)
        self.cycle = 0
        self.first_pixel: int | None = None
        self.frame_pixels = 0
        self.pixels_in = 0
        self.last_pixels: list[int] = []
        self.last_records: list[int] = []
        self.input_stalls = 0
        self.sof_clocks: list[int] = []  # clocks of the start-of-frame pixels' handshakes
        self.b_clocks: list[int] = []  # clocks of the AXI4-Lite write responses' handshakes
        self.score_without_video = 0  # clocks with m_axis_score_tvalid high, SCORE_VIDEO off

    @classmethod
    async def create(cls, dut, generics: dict[str, object], idle: float = 0, stall: float = 0):
        dut.aresetn.value = 1
        await Timer(1, "ns")
        top = cls(dut, generics, idle, stall)
        await Timer(1, "ns")
        dut.aresetn.value = 0  # the drivers see this edge and wait for the reset's end
        await Timer(1, "ns")
        cocotb.start_soon(Clock(dut.aclk, PERIOD_NS, unit="ns").start())
        cocotb.start_soon(top._monitor())
        top.protocol = AxiProtocolChecker(dut, top.score_video)
        top.protocol.start()
        return top

    def set_idle(self, idle: float) -> None:
        self.source.set_pause_generator(pauses(self.rng, idle) if idle else None)
        self.source.pause = False

    def set_stall(self, stall: float) -> None:
        self.sink.set_pause_generator(pauses(self.rng, stall) if stall else None)
        self.sink.pause = False
        if self.score_sink is not None:
            self.score_sink.set_pause_generator(pauses(self.rng, stall / 3) if stall else None)
            self.score_sink.pause = False

    async def _monitor(self) -> None:
        dut = self.dut
        while True:
            await RisingEdge(dut.aclk)
            self.cycle += 1
            if dut.s_axis_video_tvalid.value == 1:
                if dut.s_axis_video_tready.value == 1:
                    if self.first_pixel is None:
                        self.first_pixel = self.cycle
                    self.pixels_in += 1
                    if dut.s_axis_video_tuser.value == 1:
                        self.sof_clocks.append(self.cycle)
                    if self.frame_pixels and self.pixels_in % self.frame_pixels == 0:
                        self.last_pixels.append(self.cycle)
                else:
                    self.input_stalls += 1
            if (
                dut.m_axis_corners_tvalid.value == 1
                and dut.m_axis_corners_tready.value == 1
                and dut.m_axis_corners_tlast.value == 1
            ):
                self.last_records.append(self.cycle)
            if dut.s_axi_ctrl_bvalid.value == 1 and dut.s_axi_ctrl_bready.value == 1:
                self.b_clocks.append(self.cycle)
            if not self.score_video and dut.m_axis_score_tvalid.value != 0:
                self.score_without_video += 1

    async def reset(self, cycles: int = 6, settle: int = 4) -> None:
        """aresetn low for `cycles` clocks, then `settle` clocks of rest."""
        self.dut.aresetn.value = 0
        self.source.clear()  # what was queued belongs to the frame cut by the reset
        await ClockCycles(self.dut.aclk, cycles)
        self.sink.clear()
        self.dut.aresetn.value = 1
        await ClockCycles(self.dut.aclk, settle)

    # ---- registers ------------------------------------------------------------

    async def write(self, offset: int, value: int) -> None:
        write = self.axil.write(offset, value.to_bytes(4, "little"))
        resp = await self.with_budget(write, 200, f"response to a write at 0x{offset:02x}")
        assert resp.resp == AxiResp.OKAY, f"write 0x{offset:02x}: {resp.resp}"

    async def read(self, offset: int) -> int:
        read = self.axil.read(offset, 4)
        resp = await self.with_budget(read, 200, f"response to a read at 0x{offset:02x}")
        assert resp.resp == AxiResp.OKAY, f"read 0x{offset:02x}: {resp.resp}"
        return int.from_bytes(resp.data, "little")

    async def configure(
        self,
        width: int,
        height: int,
        threshold: int,
        budget: tuple[int, int] | None = None,
        min_area: int | None = None,
    ) -> None:
        """The frame's registers (`frame_writes`)."""
        for offset, value in frame_writes(width, height, threshold, budget, min_area):
            await self.write(offset, value)

    async def soft_reset(self) -> None:
        """CMD.SOFT_RESET with its KEY (0x5A in bits 31:24)."""
        await self.write(regs.CMD, 0x5A << regs.CMD_KEY.lsb | regs.CMD_SOFT_RESET.mask)

    async def status(self) -> int:
        return await self.read(regs.STATUS)

    async def errors(self) -> set[str]:
        """The names of the STATUS error bits that are set."""
        word = await self.status()
        names = ["EOL_EARLY", "EOL_LATE", "SOF_MISSING", "SOF_EARLY", "OVERFLOW"]
        names += ["ORB_ROWS", "ORB_TAGS", "ORB_COUNT", "CONFIG_QUEUE"]  # internal errors
        return {n for n in names if getattr(regs, f"STATUS_{n}").get(word)}

    # ---- streams --------------------------------------------------------------

    async def send_lines(self, lines: Sequence[AxiStreamFrame]) -> Event:
        """Queue packets; returns an event set when the first one has been sent."""
        first = Event()
        for i, line in enumerate(lines):
            if i == 0:
                line.tx_complete = first
            await self.source.send(line)
        return first

    async def send_frames(
        self,
        frames: Sequence[tuple[np.ndarray, int]],
        budgets: Sequence[tuple[int, int]] | None = None,
        min_areas: Sequence[int] | None = None,
    ) -> None:
        """Send frames back to back; the size and threshold of frame i+1 (and its
        BUDGET (cell, per_cell) when `budgets` is given, its MIN_AREA when `min_areas`
        is) are written over AXI-Lite once frame i's first line has gone in (so they
        take effect at frame i+1's start of frame)."""

        async def configure(i: int) -> None:
            img, t = frames[i]
            budget = budgets[i] if budgets is not None else None
            min_area = min_areas[i] if min_areas is not None else None
            await self.configure(img.shape[1], img.shape[0], t, budget, min_area)

        await configure(0)
        for i, (img, _) in enumerate(frames):
            first = await self.send_lines(video_lines(img, self.ppc))
            if i + 1 < len(frames):
                await first.wait()
                await configure(i + 1)

    async def receive(self, count: int, budget: int) -> list[AxiStreamFrame]:
        """The next `count` corner frames; fails after `budget` clocks."""
        got = []
        for _ in range(count):
            frame = await self.with_budget(self.sink.recv(), budget, "corner frame")
            got.append(frame)
        return got

    async def with_budget(self, coro, budget: int, what: str):
        """The result of `coro`; fails if it takes more than `budget` clocks."""
        task = cocotb.start_soon(coro)
        for _ in range(budget):
            if task.done():
                return task.result()
            await RisingEdge(self.dut.aclk)
        task.cancel()
        raise AssertionError(f"no {what} within {budget} clocks")
