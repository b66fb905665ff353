"""`fastnms sim` and `fastnms compare`: the RTL top under GHDL from the command line."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import cv2
import numpy as np
import pytest
from fastnms import main as cli
from fastnms.golden.model import detect
from fastnms.sim import run as sim
from fastnms.testing import images as testimages


@pytest.fixture(scope="module")
def photo(tmp_path_factory) -> Path:
    """A 64x48 crop of a real photograph, as a PNG file."""
    path = tmp_path_factory.mktemp("img") / "crop.png"
    cv2.imwrite(str(path), testimages.crop(testimages.real_images()[0], 64, 48))
    return path


def read_csv(path: Path) -> list[tuple[int, int, int]]:
    with open(path) as f:
        return [(int(r["x"]), int(r["y"]), int(r["score"])) for r in csv.DictReader(f)]


@pytest.mark.parametrize(("score", "nms"), [("opencv", "3x3"), ("sad", "region8")])
def test_sim_writes_the_rtl_corners(photo: Path, tmp_path: Path, capsys, score: str, nms: str):
    out_csv, out_json, out_png = tmp_path / "c.csv", tmp_path / "c.json", tmp_path / "c.png"
    argv = ["sim", str(photo), "-t", "15", "--score", score, "--nms", nms]
    argv += ["--csv", str(out_csv), "--json", str(out_json), "--png", str(out_png)]
    assert cli.main(argv) == 0
    img = cv2.imread(str(photo), cv2.IMREAD_GRAYSCALE)
    want = [tuple(int(v) for v in r) for r in detect(img, 15, score, nms)]
    assert want, "the crop should have corners"
    assert read_csv(out_csv) == want
    summary = json.loads(out_json.read_text())
    assert summary["corners"] == len(want)
    assert (summary["width"], summary["height"], summary["threshold"]) == (64, 48, 15)
    assert (summary["score"], summary["nms"]) == (score, nms)
    # Throughput: one pixel per clock plus the pipeline's fill (rows of the window and NMS).
    assert 64 * 48 <= summary["cycles"] <= 64 * 48 + 8 * 64 + 200, summary
    assert summary["wall_seconds"] > 0
    assert cv2.imread(str(out_png)).shape == (48, 64, 3)
    line = capsys.readouterr().out
    assert f"{len(want)} corners; {summary['cycles']} cycles" in line


def test_compare_identical_and_different(photo: Path, capsys, monkeypatch):
    assert cli.main(["compare", str(photo), "-t", "15"]) == 0
    out = capsys.readouterr().out
    assert "rtl vs golden model: identical" in out and "OpenCV" in out

    real_run = sim.run_rtl

    def one_corner_off(*args, **kwargs):
        result = real_run(*args, **kwargs)
        result.records[0, 2] += 1
        return result

    monkeypatch.setattr(cli, "run_rtl", one_corner_off)
    assert cli.main(["compare", str(photo), "-t", "15"]) == 1
    out = capsys.readouterr().out
    assert "DIFFERENT" in out and "rtl only" in out and "reference only" in out


@pytest.mark.parametrize("size", [(6, 20), (20, 6), (1921, 8), (8, 1081)])
def test_sim_refuses_sizes_outside_the_ip(tmp_path: Path, capsys, size: tuple[int, int]):
    path = tmp_path / "odd.png"
    cv2.imwrite(str(path), np.zeros((size[1], size[0]), dtype=np.uint8))
    out = tmp_path / "c.csv"
    assert cli.main(["sim", str(path), "--csv", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fastnms: error: ") and err.count("\n") == 1
    assert not out.exists()


def test_sim_bad_input(tmp_path: Path, capsys):
    assert cli.main(["sim", str(tmp_path / "missing.png")]) == 2
    assert capsys.readouterr().err.startswith("fastnms: error: ")
    assert cli.main(["compare", str(tmp_path / "missing.png")]) == 2
    assert capsys.readouterr().err.startswith("fastnms: error: ")
