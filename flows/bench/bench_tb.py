"""cocotb module behind `make bench` (flows/bench/bench.py): back-to-back frames
through fastnms_axi with no input idles and no output back-pressure, timed in
clocks and in wall seconds.

Environment: BENCH_FRAMES (.npy, uint8 N x H x W: the frames, sent back to
back), BENCH_THRESHOLD, BENCH_OUT (JSON written at the end), BENCH_CHECK
("1": compare every frame's records with the golden model), BENCH_GENERICS (the
top's generics).

Clocks are counted at rising edges of aclk: `first_pixel` is the clock of the
first input handshake, `last_pixel[i]` the clock of frame i's last input
handshake and `last_record[i]` that of frame i's last corner record (tlast).
"""

from __future__ import annotations

import ast
import json
import os
import time
from pathlib import Path

import cocotb
import numpy as np
from fastnms.golden.model import detect
from fastnms.sim.driver import AxiTop, corners, video_lines

GENERICS = ast.literal_eval(os.environ["BENCH_GENERICS"])
MAX_WIDTH, MAX_HEIGHT = GENERICS["MAX_WIDTH"], GENERICS["MAX_HEIGHT"]
# No run may hang: 4 clocks of 10 ns per pixel of every frame, and some.
TIMEOUT_MS = 20 + 4 * MAX_WIDTH * MAX_HEIGHT * int(os.environ.get("BENCH_COUNT", "3")) // 100_000


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def back_to_back(dut):
    frames = np.load(os.environ["BENCH_FRAMES"])
    threshold = int(os.environ.get("BENCH_THRESHOLD", "20"))
    check = os.environ.get("BENCH_CHECK", "1") == "1"
    count, height, width = frames.shape
    tb = await AxiTop.create(dut, GENERICS)
    await tb.reset()
    await tb.configure(width, height, threshold)
    tb.frame_pixels = width * height
    lines = [line for img in frames for line in video_lines(img)]
    start = time.perf_counter()
    for line in lines:
        await tb.source.send(line)
    # Not tb.receive: its clock-by-clock budget would slow the simulation down.
    got = [await tb.sink.recv() for _ in range(count)]
    wall = time.perf_counter() - start
    counts = []
    for i, (img, frame) in enumerate(zip(frames, got, strict=True)):
        records = corners(frame)
        counts.append(len(records))
        if check:
            golden = detect(img, threshold, GENERICS["SCORE"], GENERICS["NMS"])
            want = [tuple(int(v) for v in r) for r in golden]
            # The region NMS sends a region's record when the region closes.
            got_sorted = sorted(records, key=lambda r: (r[1], r[0]))
            assert got_sorted == want, f"frame {i}: {len(records)} records, golden {len(want)}"
    result = {
        "frames": count,
        "width": width,
        "height": height,
        "threshold": threshold,
        "first_pixel": tb.first_pixel,
        "last_pixel": tb.last_pixels,
        "last_record": tb.last_records,
        "input_stalls": tb.input_stalls,
        "corners": counts,
        "checked": check,
        "wall_seconds": wall,
        "errors": sorted(await tb.errors()),
    }
    Path(os.environ["BENCH_OUT"]).write_text(json.dumps(result))
