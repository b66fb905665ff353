"""The bench flow kept working on a small configuration: flows/bench/bench_tb.py
through the shared GHDL runner on two back-to-back 64x32 frames (about 20 s), its
figures derived as `make bench` derives them."""

from __future__ import annotations

import numpy as np
from fastnms.testing import images as testimages

from flows.bench import bench


def test_bench_simulates_back_to_back_frames(tmp_path):
    rng = np.random.default_rng(7)
    frames = np.stack([testimages.blurred_noise(rng, 64, 32) for _ in range(2)])
    frames_file = tmp_path / "frames.npy"
    np.save(frames_file, frames)
    row = bench.simulate("opencv", "3x3", frames_file, 2, 10, 64, 32)
    assert row["frames"] == 2 and row["checked"] and row["errors"] == []
    assert row["corners"][0] > 0  # the records were compared with the golden in the bench
    # 3x3: the frames' last records exactly W x H clocks apart; the input taken
    # at one pixel per clock but for a few stall clocks at the first frame's
    # start (4, as at 1920x1080), all of them counted.
    assert row["frame_interval_clocks"] == [64 * 32]
    pixels_in = 2 * 64 * 32
    input_clocks = round(row["input_clocks_per_pixel"] * pixels_in)
    assert input_clocks == pixels_in + row["input_stalls"] and row["input_stalls"] <= 4
    assert len(row["latency_clocks"]) == 2 and row["latency_clocks"][0] == row["latency_clocks"][1]
