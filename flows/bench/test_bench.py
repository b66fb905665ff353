"""The bench flow kept working on a small configuration: two back-to-back 64x32
frames through the fast engine built for 64x32 (a build of about 15 s, then
cached in build/vsim), their figures derived as `make bench` derives them, and a
difference from the golden model failing the bench."""

from __future__ import annotations

import numpy as np
import pytest
from fastnms.testing import images as testimages

from flows.bench import budget, engine, frame_runs

W, H = 64, 32


@pytest.fixture(scope="module")
def frames() -> list[np.ndarray]:
    rng = np.random.default_rng(7)
    return [testimages.blurred_noise(rng, W, H) for _ in range(2)]


def simulate(frames: list[np.ndarray], nms: str = "3x3") -> dict:
    generics = engine.bench_generics("opencv", nms, W, H)
    return frame_runs.simulate("opencv", nms, frames, 10, generics)


def test_bench_simulates_back_to_back_frames(frames):
    row = simulate(frames)
    assert row["engine"] == "verilator" and row["frames"] == 2
    assert row["checked"] and row["errors"] == []
    assert row["corners"][0] > 0  # the records were compared with the golden model
    # 3x3: the frames' last records exactly W x H clocks apart, and no input
    # stall: the registers are written for every frame (answered before its first
    # pixel), and the top never holds the input for them (docs/fastnms_axi.md).
    assert row["frame_interval_clocks"] == [W * H]
    assert row["frame_input_stalls"] == [0, 0] and row["input_stalls"] == 0
    pixels_in = 2 * W * H
    input_clocks = round(row["input_clocks_per_pixel"] * pixels_in)
    assert input_clocks == pixels_in + row["input_stalls"]
    assert row["first_pixel"][1] == row["last_pixel"][0] + 1  # back to back
    assert len(row["latency_clocks"]) == 2 and row["latency_clocks"][0] == row["latency_clocks"][1]
    assert row["cycles"] == row["last_record"][1] - row["first_pixel"][0] + 1
    assert row["sim_pixels_per_second"] > 0


def test_bench_fails_on_a_golden_difference(frames, monkeypatch):
    real = frame_runs.detect

    def one_corner_short(img, threshold, score, nms):
        return real(img, threshold, score, nms)[:-1]

    monkeypatch.setattr(frame_runs, "detect", one_corner_short)
    with pytest.raises(engine.BenchError, match="frame 0: the RTL gave"):
        simulate(frames)


def test_budget_bench(frames):
    """The budget rows of `make bench`: each budget's frames equal the golden model's
    budget in the block's order (checked inside, a difference raises), at most
    cells x K keypoints per frame, no input stall, and the report's table."""
    from flows.report.report import budget_lines

    result = budget.budget_bench(frames, 10, W, H, True)
    assert [(r["cell"], r["per_cell"]) for r in result["rows"]] == budget.BUDGETS
    for r in result["rows"]:
        assert r["checked"] and r["input_stalls"] == 0
        assert all(0 < c <= r["cells"] * r["per_cell"] for c in r["corners"]), r
        assert r["input_clocks_per_pixel"] == 1.0
    lines = budget_lines(result, W, H)
    assert lines[0] == "### The keypoint budget in the top"
    assert sum(line.startswith("| 4 per 64x64") for line in lines) == 1
