"""The bench's ORB comparison on scikit-image's photographs (every set-up has them):
identical keypoints, angles and float-blur descriptors, the exact blur's differences
counted, and a golden that drifts from cv2.ORB stopping the bench."""

from __future__ import annotations

import numpy as np
import pytest
from fastnms.golden import orb
from fastnms.testing import images as testimages

from flows.bench import orb as orb_bench


def test_agreement_on_photographs():
    table = orb_bench.agreement_table(testimages.bundled_images()[:2], 20)
    assert table["keypoints"] > 0 and len(table["rows"]) == 2
    assert 0 <= table["differing"] <= table["keypoints"]
    assert table["bits"] >= table["differing"] and table["max_bits"] <= 256
    assert table["mean_bits"] == table["bits"] / table["keypoints"]


def test_a_drifting_golden_stops_the_bench(monkeypatch):
    real = orb.orb_features

    def one_angle_off(img, threshold):
        f = real(img, threshold)
        angles = f.angles.copy()
        angles[0] = np.nextafter(angles[0], np.float32(360))
        return f._replace(angles=angles)

    monkeypatch.setattr(orb, "orb_features", one_angle_off)
    with pytest.raises(orb_bench.OrbMismatch, match="angles differ"):
        orb_bench.agreement_table(testimages.bundled_images()[:1], 20)


# ---- ORB in the top on the fast engine (issue 36) -----------------------------------

W, H = 128, 96


@pytest.fixture(scope="module")
def orb_frames() -> list[np.ndarray]:
    rng = np.random.default_rng(36)
    return [testimages.blurred_noise(rng, W, H) for _ in range(2)]


def golden_frame(img: np.ndarray, cell: int, per_cell: int):
    """A FrameResult carrying the golden model's ORB records, as the RTL's would."""
    from fastnms.sim.run import FrameResult

    want = orb.orb_features(img, 10, "opencv", "3x3", cell, per_cell)
    return FrameResult(
        width=img.shape[1],
        height=img.shape[0],
        threshold=10,
        records=want.records,
        words=np.zeros(0, np.uint64),
        cycles=0,
        input_stalls=0,
        first_pixel=0,
        last_pixel=0,
        last_record=0,
        angle_bits=want.angles.view(np.uint32).copy(),
        descriptors=want.descriptors.copy(),
    )


def test_check_orb_stops_on_any_difference(orb_frames):
    """The bench's ORB check: equal records pass; one descriptor bit, one angle bit or
    one keypoint less stops the bench (without simulating)."""
    from flows.bench.engine import BenchError
    from flows.bench.orb_rtl import check_orb

    img = orb_frames[0]
    frame = golden_frame(img, 16, 4)
    assert len(frame.records) > 0
    check_orb("same", img, frame, 10, 16, 4)
    bad = golden_frame(img, 16, 4)
    bad.descriptors[0, 31] ^= 0x80
    with pytest.raises(BenchError, match="angle or descriptor of 1 of"):
        check_orb("one bit", img, bad, 10, 16, 4)
    bad = golden_frame(img, 16, 4)
    bad.angle_bits[-1] ^= 1
    with pytest.raises(BenchError, match="angle bits"):
        check_orb("one angle", img, bad, 10, 16, 4)
    bad = golden_frame(img, 16, 4)
    bad.records = bad.records[:-1]
    with pytest.raises(BenchError, match="keypoints, the golden model"):
        check_orb("one short", img, bad, 10, 16, 4)


@pytest.mark.slow  # builds the ORB top for 128x96 on the fast engine (a minute or more)
def test_orb_rtl_bench(orb_frames):
    """The ORB rows of `make bench` on a small build: two frames back to back, every
    record equal to the golden's (checked inside), the report's table."""
    from flows.bench.orb_rtl import orb_rtl_bench
    from flows.report.report import orb_rtl_lines

    result = orb_rtl_bench(orb_frames, 10, W, H, True, budgets=[(16, 4)])
    assert result["generics"]["DESCRIPTOR"] == "orb"
    (row,) = result["rows"]
    assert row["checked"] and len(row["corners"]) == 2
    assert all(0 < c <= row["cells"] * row["per_cell"] for c in row["corners"]), row
    assert row["input_clocks_per_pixel"] >= 1.0
    assert all(lat > 0 for lat in row["latency_clocks"])
    lines = orb_rtl_lines(result, W, H)
    assert lines[0] == "### ORB descriptors in the top"
    assert sum(line.startswith("| 4 per 16x16") for line in lines) == 1


def test_only_orb_merges_into_the_summary(monkeypatch, tmp_path):
    """`--only orb` replaces the ORB rows of an earlier summary of the same frames and
    re-renders the section from it; without one it writes the ORB rows alone and leaves
    the results file as it is; other frames are refused (no simulation: parts faked)."""
    import json

    from flows.bench import bench

    orb_rtl = {"generics": {}, "build_seconds": None, "rows": []}
    monkeypatch.setattr(bench, "orb_part", lambda images, args: orb_rtl)
    monkeypatch.setattr(
        bench, "bench_frames", lambda w, h, n: (np.zeros((n, h, w), np.uint8), ["a.png"] * n)
    )
    monkeypatch.setattr(bench.verilator, "missing_tools", lambda: [])
    rendered = []
    results = bench.REPO / "docs" / "results.md"  # not written: update_bench is faked
    monkeypatch.setattr(bench.report, "update_bench", lambda s: rendered.append(s) or results)
    out = tmp_path / "summary.json"
    args = ["--only", "orb", "--width", "64", "--height", "32", "--out", str(out)]
    bench.main(args)
    alone = json.loads(out.read_text())
    assert alone["orb_rtl"] == orb_rtl and "simulation" not in alone and rendered == []
    frames = {"count": 3, "width": 64, "height": 32, "threshold": 20}
    out.write_text(json.dumps({"frames": frames, "simulation": [], "phases": {"builds": 1.0}}))
    bench.main(args)
    merged = json.loads(out.read_text())
    assert merged["orb_rtl"] == orb_rtl and merged["simulation"] == []
    assert set(merged["phases"]) == {"builds", "orb_rtl"} and len(rendered) == 1
    out.write_text(json.dumps({"frames": {**frames, "width": 128}, "simulation": []}))
    with pytest.raises(SystemExit, match="other frames"):
        bench.main(args)
