"""cocotb bench behind `make bench` (tb/bench_sim.py): back-to-back frames
through fastnms_axi with no input idles and no output back-pressure, timed in
clocks and in wall seconds.

Environment: BENCH_FRAMES (.npy, uint8 N x H x W: the frames, sent back to
back), BENCH_THRESHOLD, BENCH_OUT (JSON written at the end), BENCH_CHECK
("1": compare every frame's records with the golden model), TB_GENERICS (for
axi_tb).

Clocks are counted at rising edges of aclk: `first_pixel` is the clock of the
first input handshake, `last_pixel[i]` the clock of frame i's last input
handshake and `last_record[i]` that of frame i's last corner record (tlast).
"""

from __future__ import annotations

import json
import os
import time
from pathlib import Path

import cocotb
import numpy as np
from axi_tb import MAX_HEIGHT, MAX_WIDTH, TB, decode, golden, video_lines
from cocotb.triggers import RisingEdge

# No run may hang: 4 clocks of 10 ns per pixel of every frame, and some.
TIMEOUT_MS = 20 + 4 * MAX_WIDTH * MAX_HEIGHT * int(os.environ.get("BENCH_COUNT", "3")) // 100_000


class BenchTB(TB):
    """TB with a monitor that also notes each frame's last input handshake."""

    frame_pixels = 0

    async def _monitor(self) -> None:
        dut = self.dut
        self.pixels_in = 0
        self.last_pixels: list[int] = []
        while True:
            await RisingEdge(dut.aclk)
            self.cycle += 1
            if dut.s_axis_video_tvalid.value == 1:
                if dut.s_axis_video_tready.value == 1:
                    if self.first_pixel is None:
                        self.first_pixel = self.cycle
                    self.pixels_in += 1
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


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def back_to_back(dut):
    frames = np.load(os.environ["BENCH_FRAMES"])
    threshold = int(os.environ.get("BENCH_THRESHOLD", "20"))
    check = os.environ.get("BENCH_CHECK", "1") == "1"
    count, height, width = frames.shape
    tb = await BenchTB.create(dut, 0, 0)
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
    corners = []
    for i, (img, frame) in enumerate(zip(frames, got, strict=True)):
        records, flags = decode(frame)
        corners.append(0 if flags == [0b011] else len(records))
        if check:
            tb.check_frame(frame, golden(img, threshold), f"bench frame {i}")
    result = {
        "frames": count,
        "width": width,
        "height": height,
        "threshold": threshold,
        "first_pixel": tb.first_pixel,
        "last_pixel": tb.last_pixels,
        "last_record": tb.last_records,
        "input_stalls": tb.input_stalls,
        "corners": corners,
        "checked": check,
        "wall_seconds": wall,
        "errors": sorted(await tb.errors()),
    }
    Path(os.environ["BENCH_OUT"]).write_text(json.dumps(result))
