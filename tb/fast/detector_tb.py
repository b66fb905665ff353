"""cocotb testbench of fastnms_fast_detector: every pixel's corner flag and
score against the golden model (fastnms.fast.fast_maps); with PIXELS, every
pixel and its blur against the image and orb.gaussian_blur, 3 or more pixels inside the frame."""

from __future__ import annotations

import ast
import json
import os
from pathlib import Path

import cocotb
import numpy as np
from fastnms.golden import orb
from fastnms.golden.fast import fast_maps
from fastnms.testing import images as testimages

from tb.video import PERIOD_NS, VideoTB, min_width, split_frames, whole_beats

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
MAX_HEIGHT = GENERICS.get("MAX_HEIGHT", 4095)
SCORE = GENERICS["SCORE"]
LATENCY = GENERICS.get("READ_LATENCY", 1)
PPC = GENERICS.get("PPC", 1)
SCORE_BITS = 12 if SCORE == "sad" else 8
PIXELS = GENERICS.get("PIXELS", False)
MIN_WIDTH = min_width(7, PPC, LATENCY)
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))
THRESHOLDS = [0, 1, 10, 20, 50, 128, 254, 255]
# Clocks from the acceptance of beat k + 3*B + ceil(3/PPC) to the transfer of
# result k (B = W / PPC beats per row).
# With PIXELS the score waits for the 13-stage blur.
RESULT_LATENCY = LATENCY + (16 if PIXELS else 13 if SCORE == "sad" else 12)


class TB(VideoTB):
    def __init__(self, dut, idle: float = IDLE, stall: float = STALL):
        super().__init__(
            dut,
            ["corner", "score", "sof", "eol", "eof", "width", "height"]
            + (["pixel", "blurred"] if PIXELS else []),
            idle,
            stall,
            ppc=PPC,
        )
        dut._log.info("generics %s", GENERICS)
        self.set_cfg(width=MIN_WIDTH, height=7, threshold=0)

    async def run_frames(self, frames: list[tuple[np.ndarray, int]], label: str) -> None:
        """Send (image, threshold) frames back to back and check every result."""
        images = [img for img, _ in frames]
        cfgs = [{"width": i.shape[1], "height": i.shape[0], "threshold": t} for i, t in frames]
        await self.send_frames(images, cfgs)
        total = sum(img.size for img in images) // PPC
        await self.wait_beats(total, int(total * 6 / max(0.05, 1 - max(IDLE, STALL))) + 2000)
        out = split_frames(self.sink.beats)
        assert len(out) == len(frames), f"{len(out)} frames out of {len(frames)}"
        for i, ((img, t), beats) in enumerate(zip(frames, out, strict=True)):
            check_frame(img, t, beats, f"{label} frame {i} ({img.shape[1]}x{img.shape[0]} t={t})")
        assert self.err_line == 0 and self.err_frame == 0


def check_frame(img: np.ndarray, threshold: int, beats: list[dict], label: str) -> None:
    """Markers, corner mask and score map of one frame, exactly (pixel i of a
    beat is bit i of corner and slice i of score)."""
    h, w = img.shape
    row_beats = w // PPC
    assert len(beats) == row_beats * h, f"{label}: {len(beats)} beats"
    sof = np.array([b["sof"] for b in beats]).reshape(h, row_beats)
    eol = np.array([b["eol"] for b in beats]).reshape(h, row_beats)
    mask = (1 << SCORE_BITS) - 1
    got_corner = np.array(
        [(b["corner"] >> i) & 1 for b in beats for i in range(PPC)], dtype=bool
    ).reshape(h, w)
    got_score = np.array(
        [(b["score"] >> (SCORE_BITS * i)) & mask for b in beats for i in range(PPC)],
        dtype=np.int64,
    ).reshape(h, w)
    want_corner, want_score = fast_maps(img.astype(np.uint8), threshold, SCORE)
    want_sof = np.zeros((h, row_beats), dtype=int)
    want_sof[0, 0] = 1
    want_eol = np.zeros((h, row_beats), dtype=int)
    want_eol[:, -1] = 1
    assert np.array_equal(sof, want_sof), f"{label}: sof markers"
    assert np.array_equal(eol, want_eol), f"{label}: eol markers"
    eof = [b["eof"] for b in beats]
    assert eof == [0] * (len(beats) - 1) + [1], f"{label}: eof markers"
    size = (beats[0]["width"], beats[0]["height"])
    assert size == (w, h), f"{label}: out_width/out_height {size} with out_sof"
    bad = np.argwhere((got_corner != want_corner) | (got_score != want_score))
    if len(bad):
        y, x = bad[0]
        raise AssertionError(
            f"{label}: {len(bad)} pixels differ; first at (x={x}, y={y}): "
            f"rtl corner={int(got_corner[y, x])} score={got_score[y, x]}, "
            f"golden corner={int(want_corner[y, x])} score={want_score[y, x]}"
        )
    if PIXELS:
        check_pixels(img, beats, label)


def check_pixels(img: np.ndarray, beats: list[dict], label: str) -> None:
    """out_pixel is the image and out_blurred its ORB blur wherever the 7x7 window is inside
    (the border's windows are not the image's: no ORB sample reaches them)."""
    h, w = img.shape

    def plane(name: str) -> np.ndarray:
        values = [(b[name] >> (8 * i)) & 255 for b in beats for i in range(PPC)]
        return np.array(values, dtype=np.uint8).reshape(h, w)

    pixel, blurred = plane("pixel"), plane("blurred")
    inner = img[3 : h - 3, 3 : w - 3]
    assert np.array_equal(pixel[3 : h - 3, 3 : w - 3], inner), f"{label}: out_pixel differs"
    want = orb.gaussian_blur(img)[3 : h - 3, 3 : w - 3]
    bad = np.argwhere(blurred[3 : h - 3, 3 : w - 3] != want)
    if len(bad):
        y, x = bad[0] + 3
        raise AssertionError(
            f"{label}: {len(bad)} blurred pixels differ; first at (x={x}, y={y}): "
            f"rtl {blurred[y, x]}, golden {orb.gaussian_blur(img)[y, x]}"
        )


def generated_frames(tb: TB) -> list[tuple[np.ndarray, int]]:
    """Every pattern at every threshold, in sizes from the narrowest to
    MAX_WIDTH wide (whole beats)."""
    rng = tb.np_rng

    def beats(width: int) -> int:
        return whole_beats(width, PPC, MIN_WIDTH)

    sizes = [(MIN_WIDTH, 7), (beats(8), 8), (MAX_WIDTH, 9), (beats(9), 7), (MIN_WIDTH, 12)]
    sizes += [(beats(MAX_WIDTH - 1 | 1), 8)]
    sizes += [
        (beats(int(rng.integers(7, MAX_WIDTH + 1))), int(rng.integers(7, 16))) for _ in range(4)
    ]
    frames = []
    for i, threshold in enumerate(THRESHOLDS * 2):
        pattern = testimages.PATTERNS[i % len(testimages.PATTERNS)]
        width, height = sizes[i % len(sizes)]
        frames.append((pattern(rng, width, height), threshold))
    return frames


@cocotb.test()
async def generated_images(dut):
    """Noise, blurred noise, saturated, checkerboard, single pixels, constant,
    at thresholds 0..255, back to back with changing sizes and thresholds."""
    tb = TB(dut)
    await tb.reset()
    await tb.run_frames(generated_frames(tb), "generated")


@cocotb.test()
async def real_images(dut):
    """Crops of real photographs (TB_CROPS: JSON list of [path, w, h, t])."""
    crops = json.loads(os.environ.get("TB_CROPS", "[]"))
    assert crops, "no crops given in TB_CROPS"
    tb = TB(dut)
    await tb.reset()
    frames = [(testimages.crop(Path(p), w, h), t) for p, w, h, t in crops]
    for img, t in frames:
        dut._log.info("crop %dx%d t=%d", img.shape[1], img.shape[0], t)
    await tb.run_frames(frames, "photo")


@cocotb.test()
async def throughput(dut):
    """No gaps, no stalls: the last of N frames of W x H (B = W / PPC beats
    per row) leaves N*B*H + 3*B + ceil(3/PPC) + RESULT_LATENCY - 1 clocks
    after the first beat."""
    tb = TB(dut, idle=0.0, stall=0.0)
    await tb.reset()
    width, height, count = min(MAX_WIDTH, 40) // PPC * PPC, 12, 3
    frames = [(testimages.blurred_noise(tb.np_rng, width, height), 10) for _ in range(count)]
    await tb.run_frames(frames, "throughput")
    cycles = (tb.sink.times[-1] - tb.source.accept_times[0]) // PERIOD_NS
    row_beats = width // PPC
    expected = count * row_beats * height + 3 * row_beats + -(-3 // PPC) + RESULT_LATENCY - 1
    dut._log.info(
        "%d frames of %dx%d: %d cycles, expected %d", count, width, height, cycles, expected
    )
    assert cycles == expected
