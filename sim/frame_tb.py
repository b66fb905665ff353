"""The cocotb module behind the cocotb engine of `fastnms sim` (sim/run.py): frames
sent back to back through fastnms_axi, as sim/verilator_harness.cpp sends them
through the fast engine, so the two give the same records and clock counts.

The video goes in through cocotbext-axi's AxiStreamSource and the registers
through its AxiLiteMaster. The corner records are taken by a plain coroutine
that drives m_axis_corners_tready clock by clock from the stall pattern:
cocotbext-axi's sink sleeps while tvalid is low, which makes its tready depend on
more than the pattern. The idle pattern is read by the source at every clock
edge, indexed by the edge counted from the first one where it has a frame.

Environment: SIM_FRAMES (.npz of uint8 HxW arrays, in order), SIM_THRESHOLDS
(space-separated), SIM_TIMING (sim/timing.py's Timing.as_dict as JSON), SIM_OUT
(JSON written at the end), SIM_PROGRESS (rewritten with "pixels_in pixels"),
SIM_GENERICS (the top's generics), SIM_BUDGET ("CELL K": BUDGET written with
every frame's registers; unset: not written), SIM_MIN_AREA ("N": MIN_AREA written
with every frame's registers; unset: not written).
"""

from __future__ import annotations

import ast
import json
import os
from pathlib import Path

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, Event, RisingEdge, Timer
from cocotb.utils import get_sim_time
from cocotbext.axi import AxiLiteBus, AxiLiteMaster, AxiStreamBus, AxiStreamSource
from fastnms.sim.axi_protocol import AxiProtocolChecker
from fastnms.sim.driver import PERIOD_NS, frame_writes, video_lines
from fastnms.sim.timing import Pattern, Timing


class PatternedSource(AxiStreamSource):
    """AxiStreamSource whose pause is the idle pattern at the current clock edge."""

    pattern = Pattern()
    key = 0
    start_ns: float | None = None  # the time of pattern clock 0

    @property
    def pause(self) -> bool:
        if self.start_ns is None:
            return False
        k = round((get_sim_time("ns") - self.start_ns) / PERIOD_NS)
        return k >= 0 and self.pattern.at(self.key, k)

    @pause.setter
    def pause(self, value: bool) -> None:  # the pattern decides; nothing to store
        pass


class Run:
    def __init__(self, dut, images: list[np.ndarray], timing: Timing, progress: Path, ppc: int = 1):
        self.dut = dut
        self.images = images
        self.ppc = ppc  # pixels per input beat
        self.timing = timing
        self.progress = progress
        self.sizes = [img.size for img in images]
        self.cycle = 0
        self.start_ns: float | None = None  # the time of pattern clock 0
        self.pixels_in = 0
        self.in_frame = 0
        self.in_pos = 0
        self.out_frame = 0
        self.first_pixel = [0] * len(images)
        self.last_pixel = [0] * len(images)
        self.last_record = [0] * len(images)
        self.stalls = [0] * len(images)
        self.words: list[list[int]] = [[] for _ in images]
        self.word_clocks: list[list[int]] = [[] for _ in images]
        self.first_line_seen = [Event() for _ in images]
        self.done = Event()

    async def clock_edges(self) -> None:
        """Counts clocks, sees the handshakes and drives the records' tready."""
        dut = self.dut
        stall, key = self.timing.stall, self.timing.stall_key
        total = sum(self.sizes)
        while True:
            await RisingEdge(dut.aclk)
            self.cycle += 1
            if dut.s_axis_video_tvalid.value == 1:
                if dut.s_axis_video_tready.value == 1:
                    if self.in_pos == 0:
                        self.first_pixel[self.in_frame] = self.cycle
                    self.in_pos += self.ppc
                    if self.in_pos == self.images[self.in_frame].shape[1]:
                        self.first_line_seen[self.in_frame].set()
                    self.pixels_in += self.ppc
                    if self.in_pos == self.sizes[self.in_frame]:
                        self.last_pixel[self.in_frame] = self.cycle
                        self.in_frame += 1
                        self.in_pos = 0
                else:
                    self.stalls[self.in_frame] += 1
            if dut.m_axis_corners_tvalid.value == 1 and dut.m_axis_corners_tready.value == 1:
                self.words[self.out_frame].append(int(dut.m_axis_corners_tdata.value))
                self.word_clocks[self.out_frame].append(self.cycle)
                if dut.m_axis_corners_tlast.value == 1:
                    self.last_record[self.out_frame] = self.cycle
                    self.out_frame += 1
                    if self.out_frame == len(self.images):
                        self.done.set()
            k = -1
            if self.start_ns is not None:
                k = round((get_sim_time("ns") - self.start_ns) / PERIOD_NS)
            dut.m_axis_corners_tready.value = int(k >= 0 and not stall.at(key, k))
            if self.cycle % 4096 == 0:
                self.progress.write_text(f"{self.pixels_in} {total}\n")


async def write(axil: AxiLiteMaster, offset: int, value: int) -> None:
    await axil.write(offset, value.to_bytes(4, "little"))


async def configure(
    axil: AxiLiteMaster,
    img: np.ndarray,
    threshold: int,
    budget: tuple[int, int] | None,
    min_area: int | None = None,
) -> None:
    """The frame's registers (fastnms.sim.driver.frame_writes)."""
    height, width = img.shape[:2]
    for offset, value in frame_writes(width, height, threshold, budget, min_area):
        await write(axil, offset, value)


@cocotb.test()
async def run_frames(dut):
    with np.load(os.environ["SIM_FRAMES"]) as npz:
        images = [npz[f"arr_{i}"] for i in range(len(npz.files))]
    thresholds = [int(t) for t in os.environ["SIM_THRESHOLDS"].split()]
    t = json.loads(os.environ["SIM_TIMING"])
    timing = Timing(Pattern.parse(t["idle"]), Pattern.parse(t["stall"]), int(t["seed"]))
    generics = ast.literal_eval(os.environ.get("SIM_GENERICS", "{}"))
    ppc = int(generics.get("PPC", 1))
    run = Run(dut, images, timing, Path(os.environ["SIM_PROGRESS"]), ppc)

    dut.aresetn.value = 0
    dut.m_axis_corners_tready.value = 0
    dut.m_axis_score_tready.value = 0
    source = PatternedSource(
        AxiStreamBus.from_prefix(dut, "s_axis_video"), dut.aclk, dut.aresetn, False
    )
    source.pattern, source.key = timing.idle, timing.idle_key
    axil = AxiLiteMaster(AxiLiteBus.from_prefix(dut, "s_axi_ctrl"), dut.aclk, dut.aresetn, False)
    source.log.setLevel("WARNING")
    axil.write_if.log.setLevel("WARNING")
    axil.read_if.log.setLevel("WARNING")
    await Timer(1, "ns")
    cocotb.start_soon(Clock(dut.aclk, PERIOD_NS, unit="ns").start())
    AxiProtocolChecker(dut, bool(generics.get("SCORE_VIDEO", False))).start()
    await ClockCycles(dut.aclk, 8)
    dut.aresetn.value = 1
    cocotb.start_soon(run.clock_edges())
    await ClockCycles(dut.aclk, 4)

    budget_env = os.environ.get("SIM_BUDGET", "")
    budget = tuple(int(v) for v in budget_env.split()) if budget_env else None
    min_area_env = os.environ.get("SIM_MIN_AREA", "")
    min_area = int(min_area_env) if min_area_env else None
    await configure(axil, images[0], thresholds[0], budget, min_area)
    await RisingEdge(dut.aclk)
    # The source takes the frame at the next edge: pattern clock 0.
    run.start_ns = source.start_ns = get_sim_time("ns") + PERIOD_NS
    for line in video_lines(images[0], ppc):
        await source.send(line)
    for i in range(1, len(images)):
        # As the fast engine: once the previous frame's first line is in.
        await run.first_line_seen[i - 1].wait()
        await configure(axil, images[i], thresholds[i], budget, min_area)
        for line in video_lines(images[i], ppc):
            await source.send(line)
    await run.done.wait()

    frames = [
        {
            "first_pixel": run.first_pixel[i],
            "last_pixel": run.last_pixel[i],
            "last_record": run.last_record[i],
            "words": run.words[i],
            "word_clocks": run.word_clocks[i],
            "input_stalls": run.stalls[i],
        }
        for i in range(len(images))
    ]
    Path(os.environ["SIM_OUT"]).write_text(
        json.dumps({"frames": frames, "input_stalls": sum(run.stalls)})
    )
