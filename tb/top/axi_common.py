"""What the cocotb testbenches of fastnms_axi (tb/top/axi_*_tb.py) share: the build's
generics and the stimulus knobs, the golden references, and TB, the simulation driver
of the top (fastnms.sim.driver.AxiTop: video in through cocotbext-axi's
AxiStreamSource, records and score video out through AxiStreamSinks, registers through
AxiLiteMaster) with the checks: records against the golden model
(fastnms.golden.model.detect) and, for opencv + 3x3, against cv2.FastFeatureDetector.

Configuration from pytest (tb/top/test_axi.py), as environment variables: TB_GENERICS
(the top's generics), TB_IDLE (input idle probability), TB_STALL (corner output
back-pressure probability).
"""

from __future__ import annotations

import ast
import os
from collections.abc import Sequence

import cocotb
import cv2
import numpy as np
from cocotb.triggers import RisingEdge
from cocotbext.axi import AxiStreamFrame
from fastnms.golden.model import detect
from fastnms.sim import regs
from fastnms.sim.driver import AxiTop, Record, decode
from fastnms.sim.run import budget_in_effect
from fastnms.testing import images as testimages

from tb.video import min_width
from tb.video import whole_beats as round_to_beats

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
MAX_HEIGHT = GENERICS["MAX_HEIGHT"]
SCORE = GENERICS["SCORE"]
NMS = GENERICS["NMS"]
SCORE_VIDEO = bool(GENERICS.get("SCORE_VIDEO", False))
FIFO_DEPTH = GENERICS.get("CORNER_FIFO_DEPTH", 512)
PPC = GENERICS.get("PPC", 1)
MAX_PER_CELL = GENERICS.get("MAX_PER_CELL", 0)
# The narrowest frame the WIDTH register takes (fastnms_axi_regs: the core's
# window generators read their line buffers with latency 1).
MIN_WIDTH = min_width(7, PPC)
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))

# No test may hang: a generous bound in simulated time.
TIMEOUT_MS = 20 + 2e-3 * MAX_WIDTH * MAX_HEIGHT


def all_generics() -> dict[str, object]:
    """The top's generics, defaults filled in."""
    return {
        "SCORE_VIDEO": False,
        "CORNER_FIFO_DEPTH": 512,
        "PPC": 1,
        "MAX_PER_CELL": 0,
        "DESCRIPTOR": "none",
        "ORB_MAX_CELL": 16,
        **GENERICS,
    }


def budget_register(merged: int) -> int:
    """BUDGET after a write whose merged value is `merged`: CELL clamped to 16 .. 256
    (bits 31:25 count), then rounded down to a power of two; then both clamped as the
    build does (budget_in_effect: MAX_PER_CELL, with ORB ORB_MAX_CELL and the rate)."""
    cell = min(merged >> regs.BUDGET_CELL.lsb, 256)
    cell = 1 << max(4, cell.bit_length() - 1)
    cell, k = budget_in_effect(cell, regs.BUDGET_PER_CELL.get(merged), all_generics())
    return k << regs.BUDGET_PER_CELL.lsb | cell << regs.BUDGET_CELL.lsb


def whole_beats(width: int) -> int:
    return round_to_beats(width, PPC, MIN_WIDTH)


def width_register(written: int) -> int:
    """What WIDTH reads after a write: clamped to MIN_WIDTH .. MAX_WIDTH (bits
    31:16 count), then rounded down to whole beats."""
    if written > MAX_WIDTH:
        return MAX_WIDTH
    return max(MIN_WIDTH, written) // PPC * PPC


def opencv_keypoints(img: np.ndarray, threshold: int) -> list[Record]:
    """cv2.FAST with nonmaxSuppression=True, as records sorted by y then x."""
    fast = cv2.FastFeatureDetector_create(threshold, True, cv2.FAST_FEATURE_DETECTOR_TYPE_9_16)
    points = [(int(k.pt[0]), int(k.pt[1]), int(k.response)) for k in fast.detect(img)]
    return sorted(points, key=lambda p: (p[1], p[0]))


def golden(img: np.ndarray, threshold: int) -> list[Record]:
    return [tuple(int(v) for v in r) for r in detect(img, threshold, SCORE, NMS)]


def mismatch(got: list, want: list, label: str) -> str:
    padded = zip(got + [None] * len(want), want + [None] * len(got), strict=False)
    for i, (g, w) in enumerate(padded):
        if g != w:
            return f"{label}: rtl {len(got)} records, golden {len(want)}; #{i}: rtl {g}, golden {w}"
    return f"{label}: equal"


class TB(AxiTop):
    """The simulation driver of the top (fastnms.sim.driver) with the checks of
    this testbench: records against the golden model and cv2.FAST."""

    @classmethod
    async def create(cls, dut, idle: float = IDLE, stall: float = STALL) -> TB:
        return await super().create(dut, GENERICS, idle, stall)

    async def input_errors(self) -> set[str]:
        """The error bits of the video input (OVERFLOW excluded: it only says
        that the corner output stalled the pipeline)."""
        return await self.errors() - {"OVERFLOW"}

    async def clear_status(self) -> None:
        await self.write(regs.STATUS, 0xFFFFFFFE)
        assert await self.status() & ~1 == 0

    async def idle_output(self, clocks: int = 200) -> None:
        """Wait until nothing has come out for `clocks` clocks."""
        quiet = 0
        while quiet < clocks:
            await RisingEdge(self.dut.aclk)
            busy = self.dut.m_axis_corners_tvalid.value == 1 or not self.source.idle()
            quiet = 0 if busy else quiet + 1

    def check_frame(self, frame: AxiStreamFrame, want: list[Record], label: str) -> None:
        records, flags = decode(frame)
        if not want:
            assert records == [(0, 0, 0)] and flags == [0b011], (
                f"{label}: expected the empty-frame record, got {records} flags {flags}"
            )
            return
        if NMS.startswith("region"):
            # The region NMS sends a region's record when the region closes.
            records = sorted(records, key=lambda r: (r[1], r[0]))
        assert records == want, mismatch(records, want, label)
        assert flags == [0] * (len(want) - 1) + [0b010], f"{label}: flags {flags}"

    async def check_frames(
        self, frames: Sequence[tuple[np.ndarray, int]], label: str, opencv: bool = True
    ) -> None:
        """Send frames, receive and check every one."""
        sender = cocotb.start_soon(self.send_frames(frames))
        total = sum(img.size for img, _ in frames)
        slack = 1 / max(0.05, (1 - IDLE) * (1 - STALL))
        got = await self.receive(len(frames), int(total * 3 * slack) + 20 * MAX_WIDTH + 2000)
        await sender
        for i, ((img, t), frame) in enumerate(zip(frames, got, strict=True)):
            name = f"{label} frame {i} ({img.shape[1]}x{img.shape[0]} t={t})"
            want = golden(img, t)
            self.check_frame(frame, want, name + " vs golden")
            if opencv and SCORE == "opencv" and NMS == "3x3":
                cv = opencv_keypoints(img, t)
                records, _ = decode(frame)  # 3x3: in raster order
                assert records == (cv or [(0, 0, 0)]), mismatch(records, cv, name + " vs cv2.FAST")
            self.dut._log.info("%s: %d corners, equal", name, len(want))


def good_image(tb: TB, w: int, h: int) -> np.ndarray:
    """A well-formed frame's image (blurred noise: some corners, not too many)."""
    return testimages.blurred_noise(tb.np_rng, w, h)
