"""cocotb testbench of fastnms_core (detector + NMS): the corner records of
each frame (with the region NMS's areas, under a MIN_AREA that changes from
frame to frame, which the other NMS ignore) against the golden model's
detect(), and, for opencv + 3x3, against cv2.FastFeatureDetector itself."""

from __future__ import annotations

import ast
import json
import os
from pathlib import Path

import cocotb
import cv2
import numpy as np
from cocotb.triggers import ClockCycles
from fastnms.golden.model import detect
from fastnms.testing import images as testimages

from tb.video import VideoTB, frame_beats, min_width, record_mismatch, split_records
from tb.video import whole_beats as round_to_beats

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
SCORE = GENERICS["SCORE"]
NMS = GENERICS["NMS"]
LATENCY = GENERICS.get("READ_LATENCY", 1)
PPC = GENERICS.get("PPC", 1)
MIN_WIDTH = min_width(7, PPC, LATENCY)
REGION = NMS.startswith("region")
RECORD_FIELDS = ("x", "y", "score", "area")
# MIN_AREA of frame i (cfg_min_area), in turn.
MIN_AREAS = (0, 3, 1, 2, 6, 2047, 4)


def whole_beats(width: int) -> int:
    return round_to_beats(width, PPC, MIN_WIDTH)


IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))


def opencv_keypoints(img: np.ndarray, threshold: int) -> list[tuple[int, int, int]]:
    """cv2.FAST with nonmaxSuppression=True, as records sorted by y then x."""
    fast = cv2.FastFeatureDetector_create(threshold, True, cv2.FAST_FEATURE_DETECTOR_TYPE_9_16)
    points = [(int(k.pt[0]), int(k.pt[1]), int(k.response)) for k in fast.detect(img)]
    return sorted(points, key=lambda p: (p[1], p[0]))


class TB(VideoTB):
    def __init__(self, dut, idle: float = IDLE, stall: float = STALL):
        super().__init__(dut, ["x", "y", "score", "area", "eof"], idle, stall, ppc=PPC)
        dut._log.info("generics %s", GENERICS)
        self.set_cfg(width=MIN_WIDTH, height=7, threshold=0, min_area=0)

    async def run_frames(self, frames: list[tuple[np.ndarray, int]], label: str) -> None:
        images = [img for img, _ in frames]
        cfgs = [
            {"width": img.shape[1], "height": img.shape[0], "threshold": t}
            | {"min_area": MIN_AREAS[i % len(MIN_AREAS)]}
            for i, (img, t) in enumerate(frames)
        ]
        await self.send_frames(images, cfgs)
        total = sum(img.size for img in images)
        await self.wait_eofs(len(frames), int(total * 6 / max(0.05, 1 - max(IDLE, STALL))) + 5000)
        records = split_records(self.sink.beats, RECORD_FIELDS)
        for i, ((img, t), got) in enumerate(zip(frames, records, strict=True)):
            min_area = cfgs[i]["min_area"] if REGION else 0
            name = f"{label} frame {i} ({img.shape[1]}x{img.shape[0]} t={t} min_area={min_area})"
            want = detect(img, t, SCORE, NMS, min_area=min_area, with_area=True)
            want = [tuple(int(v) for v in r) for r in want]
            if REGION:  # records leave as regions close
                got = sorted(got, key=lambda r: (r[1], r[0]))
            assert got == want, record_mismatch(got, want, name + " vs golden")
            if SCORE == "opencv" and NMS == "3x3":
                cv = opencv_keypoints(img, t)
                got = [r[:3] for r in got]
                assert got == cv, record_mismatch(got, cv, name + " vs cv2.FAST")
            self.dut._log.info("%s: %d corners, equal", name, len(got))
        assert self.err_line == 0 and self.err_frame == 0


@cocotb.test()
async def generated_images(dut):
    """Every pattern at several thresholds, back to back, sizes from the
    narrowest (7x7 with one pixel per beat) to MAX_WIDTH."""
    tb = TB(dut)
    await tb.reset()
    rng = tb.np_rng
    sizes = [(MIN_WIDTH, 7), (MAX_WIDTH, 12), (whole_beats(9), 8)]
    sizes += [(whole_beats(int(rng.integers(7, MAX_WIDTH + 1))), 16)]
    frames = []
    for i, threshold in enumerate([0, 1, 10, 20, 50, 128, 254, 255, 5, 15, 30, 40]):
        pattern = testimages.PATTERNS[i % len(testimages.PATTERNS)]
        w, h = sizes[i % len(sizes)]
        frames.append((pattern(rng, w, h), threshold))
    await tb.run_frames(frames, "generated")


@cocotb.test()
async def region_filter(dut):
    """MIN_AREA changing from frame to frame on content with regions of every size
    (blurred noise at low thresholds), back to back: the region NMS drops exactly the
    regions the golden model drops (and each frame drops some); the other NMS ignore it."""
    tb = TB(dut)
    await tb.reset()
    rng = tb.np_rng
    w = whole_beats(min(MAX_WIDTH, 64))
    frames = []
    for min_area in MIN_AREAS:
        # Draw frames until one whose regions MIN_AREA thins (when it can).
        for _ in range(200):
            img, t = testimages.blurred_noise(rng, w, 24), int(rng.integers(1, 12))
            if not REGION or not 1 < min_area < 2047:
                break
            if len(detect(img, t, SCORE, NMS, min_area=min_area)) < len(detect(img, t, SCORE, NMS)):
                break
        else:
            raise AssertionError(f"no frame that MIN_AREA {min_area} thins")
        frames.append((img, t))
    await tb.run_frames(frames, "region filter")


@cocotb.test()
async def real_images(dut):
    """Crops of real photographs (TB_CROPS: JSON list of [path, w, h, t])."""
    crops = json.loads(os.environ.get("TB_CROPS", "[]"))
    assert crops, "no crops given in TB_CROPS"
    tb = TB(dut)
    await tb.reset()
    frames = [(testimages.crop(Path(p), whole_beats(w), h), t) for p, w, h, t in crops]
    await tb.run_frames(frames, "photo")


@cocotb.test()
async def malformed_then_good(dut):
    """Bad input never stalls the pipeline: a frame cut after its first
    results still ends with an end-of-frame beat, one cut earlier produces
    nothing, stray pixels and a frame of bad size are dropped, and the frames
    after them are exact."""
    tb = TB(dut)
    await tb.reset()
    rng = tb.np_rng
    w, h = whole_beats(min(MAX_WIDTH, 20)), 12
    row_beats = w // PPC
    good = [testimages.blurred_noise(rng, w, h) for _ in range(3)]
    cut = testimages.noise(rng, w, h)
    tb.set_cfg(width=w, height=h, threshold=10)
    await ClockCycles(dut.clk, 2)

    def beats_of(img):
        return frame_beats(img, ppc=PPC)

    beats = beats_of(cut)
    await tb.source.send(beats[: 6 * row_beats])  # cut after its first results
    await tb.source.send(beats_of(good[0]))
    await tb.source.send(beats[:row_beats])  # cut before any result
    await tb.source.send([{"data": 7, "sof": 0, "eol": 0}] * 4)  # outside any frame
    await tb.source.send(beats_of(good[1]))
    # Bad sizes, dropped: too narrow; with PPC > 1 not whole beats.
    for bad in [5] + ([w + 1] if PPC > 1 else []):
        tb.set_cfg(width=bad, height=h, threshold=10)
        await ClockCycles(dut.clk, 2)
        await tb.source.send(beats_of(np.resize(good[2], (h, bad))))
    tb.set_cfg(width=w, height=h, threshold=10)
    await ClockCycles(dut.clk, 2)
    await tb.source.send(beats_of(good[2]))
    await tb.wait_eofs(4, 100 * w * h)
    records = split_records(tb.sink.beats)
    for img, got in zip(good, records[1:], strict=True):
        want = [tuple(int(v) for v in r) for r in detect(img, 10, SCORE, NMS)]
        if REGION:
            got = sorted(got, key=lambda r: (r[1], r[0]))
        assert got == want, record_mismatch(got, want, "frame after bad input")
    assert tb.err_frame > 0
