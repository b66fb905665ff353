"""cocotb tests of frames through fastnms_axi, against the golden model (and
cv2.FAST for opencv + 3x3): generated images back to back with AXI-Lite
reconfiguration (generated_frames), MIN_AREA per frame (region_filter), photograph crops
(real_images), the empty frame (empty_frame), the score video against
fastnms.golden.fast.fast_maps (score_video), clocks per frame (throughput).

Configuration beyond tb/top/axi_common.py's: TB_CROPS (real_images: a JSON list of
[path, w, h, t]), TB_FRAMES and TB_RESULTS (throughput: frames back to back, and a
JSON file for the clocks measured).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles
from fastnms.golden.fast import fast_maps
from fastnms.golden.model import detect
from fastnms.sim import regs
from fastnms.sim.driver import record_words, video_lines
from fastnms.sim.records import decode_records
from fastnms.testing import images as testimages

from tb.top.axi_common import (
    MAX_HEIGHT,
    MAX_WIDTH,
    MIN_WIDTH,
    NMS,
    PPC,
    SCORE,
    SCORE_VIDEO,
    TB,
    TIMEOUT_MS,
    golden,
    mismatch,
    whole_beats,
)


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def generated_frames(dut):
    """Every pattern, back to back, sizes 7x7 to MAX_WIDTH x MAX_HEIGHT, size
    and threshold changed over AXI-Lite between frames, an empty frame."""
    tb = await TB.create(dut)
    await tb.reset()
    rng = tb.np_rng
    sizes = [
        (MIN_WIDTH, 7),
        (MAX_WIDTH, MAX_HEIGHT),
        (whole_beats(9), 8),
        (whole_beats(int(rng.integers(7, MAX_WIDTH + 1))), int(rng.integers(7, 24))),
        (MAX_WIDTH, 7),
        (whole_beats(8), int(rng.integers(7, MAX_HEIGHT + 1))),
    ]
    frames = []
    for i, threshold in enumerate([0, 1, 10, 20, 50, 128, 254, 255, 5, 15, 30, 40]):
        pattern = testimages.PATTERNS[i % len(testimages.PATTERNS)]
        w, h = sizes[i % len(sizes)]
        frames.append((pattern(rng, w, h), threshold))
    assert any(not golden(img, t) for img, t in frames), "no empty frame among the cases"
    await tb.check_frames(frames, "generated")
    await ClockCycles(dut.aclk, 5)
    assert await tb.read(regs.FRAME_COUNT) == len(frames)
    img, t = frames[-1]
    assert await tb.read(regs.CORNER_COUNT) == len(golden(img, t))
    assert await tb.input_errors() == set()
    assert tb.score_without_video == 0


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def region_filter(dut):
    """MIN_AREA written with every frame (0 to 2047), frames back to back: each frame's
    records with their AREA equal the golden model's at that MIN_AREA; with the region
    NMS some frames lose regions to it, the 3x3 and none NMS ignore it (AREA 0)."""
    tb = await TB.create(dut)
    await tb.reset()
    rng = tb.np_rng
    region = NMS.startswith("region")
    w, h = whole_beats(min(MAX_WIDTH, 48)), min(MAX_HEIGHT, 20)
    min_areas = [3, 0, 2047, 5, 1, 2, 9]
    frames = [(testimages.blurred_noise(rng, w, h), int(rng.integers(1, 9))) for _ in min_areas]
    sender = cocotb.start_soon(tb.send_frames(frames, min_areas=min_areas))
    got = await tb.receive(len(frames), 20 * w * h * len(frames) + 2000)
    await sender
    thinned = 0
    for i, ((img, t), frame) in enumerate(zip(frames, got, strict=True)):
        min_area = min_areas[i] if region else 0
        want = [tuple(int(v) for v in r) for r in detect(img, t, SCORE, NMS, min_area, True)]
        thinned += len(want) < len(detect(img, t, SCORE, NMS))
        (decoded,) = decode_records(record_words(frame))
        records = [(*c, a) for c, a in zip(decoded.corners, decoded.areas, strict=True)]
        records = sorted(records, key=lambda r: (r[1], r[0]))
        assert records == want, mismatch(records, want, f"frame {i} MIN_AREA {min_areas[i]}")
    assert thinned >= (3 if region else 0), f"MIN_AREA dropped regions in {thinned} frames"
    assert await tb.read(regs.MIN_AREA) == min_areas[-1]
    dut._log.info("%d frames, %d thinned by MIN_AREA", len(frames), thinned)


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def real_images(dut):
    """Crops of real photographs (TB_CROPS: JSON list of [path, w, h, t])."""
    crops = json.loads(os.environ.get("TB_CROPS", "[]"))
    assert crops, "no crops given in TB_CROPS"
    tb = await TB.create(dut)
    await tb.reset()
    frames = [(testimages.crop(Path(p), whole_beats(w), h), t) for p, w, h, t in crops]
    await tb.check_frames(frames, "photo")
    assert await tb.input_errors() == set()
    assert tb.score_without_video == 0, "m_axis_score_tvalid rose without SCORE_VIDEO"


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def empty_frame(dut):
    """A frame without corners sends exactly one record: EMPTY and LAST, zeros."""
    tb = await TB.create(dut)
    await tb.reset()
    flat = np.full((10, 12), 77, dtype=np.uint8)
    await tb.check_frames([(flat, 20), (flat, 0)], "empty")
    await ClockCycles(dut.aclk, 5)
    assert await tb.read(regs.CORNER_COUNT) == 0
    assert await tb.read(regs.FRAME_COUNT) == 2


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def score_video(dut):
    """m_axis_score: one 8-bit score per pixel (PPC per beat, pixel 0 in the
    low byte), the golden score saturated to 255, tuser on the first beat,
    tlast on the last of each line."""
    assert SCORE_VIDEO, "built without SCORE_VIDEO"
    tb = await TB.create(dut)
    await tb.reset()
    rng = tb.np_rng
    frames = [
        (testimages.saturated(rng, MAX_WIDTH, min(MAX_HEIGHT, 16)), 0),
        (testimages.noise(rng, whole_beats(23), 9), 5),
        (testimages.blurred_noise(rng, whole_beats(9), 7), 1),
    ]
    sender = cocotb.start_soon(tb.check_frames(frames, "with score video", opencv=False))
    for img, t in frames:
        h, w = img.shape
        want = np.minimum(fast_maps(img, t, SCORE)[1], 255)
        for y in range(h):
            line = await tb.with_budget(
                tb.score_sink.recv(compact=False), 50 * img.size, "score line"
            )
            assert len(line.tdata) == w, f"score line {y}: {len(line.tdata)} beats, want {w}"
            # (The sink repeats a beat's tuser on each of its PPC bytes.)
            want_tuser = [int(y == 0 and i < PPC) for i in range(w)]
            assert list(line.tuser) == want_tuser, f"tuser of line {y}"
            assert list(line.tdata) == [int(v) for v in want[y]], f"scores of line {y}"
    await sender
    assert tb.score_sink.empty()
    peak = int(np.max(fast_maps(frames[0][0], 0, SCORE)[1]))
    assert peak > (255 if SCORE == "sad" else 0), f"highest score {peak}: saturation not tested"


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def throughput(dut):
    """No idle, no back-pressure: one frame, then back-to-back frames; clocks
    from the first pixel accepted to each frame's last record."""
    tb = await TB.create(dut, 0, 0)
    await tb.reset()
    w, h = MAX_WIDTH, MAX_HEIGHT
    n = int(os.environ.get("TB_FRAMES", "3"))
    img = testimages.blurred_noise(tb.np_rng, w, h)
    await tb.configure(w, h, 10)
    results = {}
    for count in (1, n):
        tb.first_pixel = None
        tb.last_records.clear()
        for _ in range(count):
            await tb.send_lines(video_lines(img, PPC))
        got = await tb.receive(count, 4 * count * w * h + 10000)
        for frame in got:
            tb.check_frame(frame, golden(img, 10), "throughput")
        clocks = [c - tb.first_pixel for c in tb.last_records]
        results[count] = clocks
        Path(os.environ.get("TB_RESULTS", os.devnull)).write_text(json.dumps(results))
        beats = w * h // PPC
        bound = 1.01 * count * beats + 4 * w + 64
        dut._log.info(
            "%d x %dx%d: last records at %s clocks (W*H = %d, bound %.0f)",
            count,
            w,
            h,
            clocks,
            w * h,
            bound,
        )
        assert clocks[-1] <= bound, f"{clocks[-1]} clocks for {count} frames > {bound:.0f}"
        if count > 1:
            steps = [b - a for a, b in zip(clocks, clocks[1:], strict=False)]
            assert all(s <= 1.01 * beats for s in steps), f"frame intervals {steps}"
        await ClockCycles(dut.aclk, 50)
    # Without back-pressure the corner FIFO never fills.
    assert await tb.errors() == set()
