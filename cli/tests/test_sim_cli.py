"""`fastnms sim` and `fastnms compare`: the RTL top, simulated, from the command line
(the fast engine unless a test says otherwise)."""

from __future__ import annotations

import csv
import json
from pathlib import Path

import cv2
import numpy as np
import pytest
from fastnms import main as cli
from fastnms import rtl_run
from fastnms.golden.budget import cell_budget
from fastnms.golden.image import load_grey
from fastnms.golden.model import detect
from fastnms.sim import run as sim
from fastnms.testing import images as testimages

from cli.tests.test_cli import run


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
    assert summary["engine"] == "verilator" and summary["input_stalls"] >= 0
    assert summary["status_flags"] == ["FRAME_DONE"]  # and no error flag
    line = capsys.readouterr().out
    assert f"{len(want)} corners; {summary['cycles']} cycles" in line


def test_sim_four_pixels_per_clock(photo: Path, tmp_path: Path):
    """--ppc 4: the corners of the golden model, in a quarter of the clocks."""
    out_json = tmp_path / "c.json"
    assert cli.main(["sim", str(photo), "-t", "15", "--ppc", "4", "--json", str(out_json)]) == 0
    summary = json.loads(out_json.read_text())
    img = cv2.imread(str(photo), cv2.IMREAD_GRAYSCALE)
    assert summary["corners"] == len(detect(img, 15, "opencv", "3x3")) > 0
    assert summary["ppc"] == 4
    assert 64 * 48 // 4 <= summary["cycles"] <= 64 * 48 // 4 + 8 * 16 + 200, summary
    assert cli.main(["compare", str(photo), "-t", "15", "--ppc", "4"]) == 0


def test_engines_give_the_same_json(photo: Path, tmp_path: Path):
    """--engine cocotb and the default engine: the same corners, cycles and input
    stalls, with idles and stalls."""
    got = {}
    for engine in ("verilator", "cocotb"):
        out = tmp_path / f"{engine}.json"
        argv = ["sim", str(photo), "--engine", engine, "--idle", "0.3", "--stall", "0110"]
        assert cli.main([*argv, "--seed", "5", "--json", str(out), "--csv", f"{out}.csv"]) == 0
        summary = json.loads(out.read_text())
        assert summary["engine"] == engine
        assert summary["timing"] == {
            "idle": "0.3",
            "stall": "0110",
            "seed": 5,
            "hblank": 0,
            "vblank": 0,
        }
        got[engine] = (summary["corners"], summary["cycles"], summary["input_stalls"])
        got[engine + " csv"] = Path(f"{out}.csv").read_text()
    assert got["verilator"] == got["cocotb"]
    assert got["verilator csv"] == got["cocotb csv"]


def test_several_frames(photo: Path, tmp_path: Path, capsys):
    """Images sent back to back (sizes differ; a directory stands for its images):
    CSV with a frame column, JSON with per-frame figures, one summary line each."""
    small = tmp_path / "frames" / "b_small.png"
    small.parent.mkdir()
    img = cv2.imread(str(photo), cv2.IMREAD_GRAYSCALE)
    cv2.imwrite(str(small), img[8:40, 4:44])
    cv2.imwrite(str(small.with_name("a_same.png")), img)
    out_csv, out_json = tmp_path / "f.csv", tmp_path / "f.json"
    argv = ["sim", str(photo), str(small.parent), "-t", "12", "--hblank", "20"]
    assert cli.main([*argv, "--csv", str(out_csv), "--json", str(out_json)]) == 0
    images = [img, img, img[8:40, 4:44]]  # the directory's files in name order
    with open(out_csv) as f:
        rows = list(csv.DictReader(f))
    for i, frame in enumerate(images):
        want = [tuple(int(v) for v in r) for r in detect(frame, 12, "opencv", "3x3")]
        got = [(int(r["x"]), int(r["y"]), int(r["score"])) for r in rows if r["frame"] == str(i)]
        assert got == want, i
    summary = json.loads(out_json.read_text())
    frames = summary["frames"]
    assert [(f["width"], f["height"]) for f in frames] == [(64, 48), (64, 48), (40, 32)]
    assert summary["corners"] == len(rows) == sum(f["corners"] for f in frames)
    assert "width" not in summary and summary["timing"]["hblank"] == 20
    # hblank 20 after each of a 48-line frame's first 47 lines.
    assert frames[0]["cycles"] >= 64 * 48 + 47 * 20
    assert frames[0]["cycles"] == frames[1]["cycles"]  # the same image, the same clocks
    out = capsys.readouterr().out.splitlines()
    assert len(out) == 4 and out[-1].startswith("3 frames: ")


def test_several_frames_from_a_video(photo: Path, tmp_path: Path):
    """A video file stands for its frames (here 3 frames of MJPG in AVI)."""
    video = tmp_path / "clip.avi"
    img = cv2.imread(str(photo))
    writer = cv2.VideoWriter(str(video), cv2.VideoWriter_fourcc(*"MJPG"), 10, (64, 48))
    for shift in range(3):
        writer.write(np.roll(img, 4 * shift, axis=1))
    writer.release()
    out_json = tmp_path / "v.json"
    assert cli.main(["sim", str(video), "--json", str(out_json)]) == 0
    frames = json.loads(out_json.read_text())["frames"]
    assert [f["image"] for f in frames] == [f"{video}#{i}" for i in range(3)]


@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--png", "x.png", "IMG", "IMG"], "--png draws one image"),
        (["--engine", "cocotb", "--hblank", "4", "IMG"], "--hblank and --vblank need"),
        (["--stall", "111", "IMG"], "pauses on every clock"),
        (["--idle", "1.0", "IMG"], "rate must be in [0, 1)"),
        (["--idle", "abc", "IMG"], "expected a rate"),
        (["--hblank", "-1", "IMG"], "expected an integer >= 0"),
        (["EMPTYDIR"], "a directory without image files"),
        (["--ppc", "4", "--nms", "region4", "IMG"], "--ppc 4 needs --nms 3x3 or none"),
        (["--ppc", "4", "IMG60"], "not a multiple of 4"),
        (["--cell", "32", "IMG"], "--cell and --per-cell go together"),
        (["--cell", "32", "--per-cell", "2", "--nms", "region8", "IMG"], "need --nms 3x3 or none"),
        (["--cell", "48", "--per-cell", "2", "IMG"], "cell must be one of"),
        (["--cell", "32", "--per-cell", "16", "IMG"], "per-cell must be an integer in 1..15"),
        (["--orb", "IMG"], "--orb needs --cell and --per-cell"),
        (["--orb", "--cell", "64", "--per-cell", "2", "IMG"], "--orb takes --cell 16 or 32"),
        (["--orb", "--cell", "16", "--per-cell", "2", "--ppc", "2", "IMG"], "--orb needs --ppc 1"),
        (["--orb", "--cell", "16", "--per-cell", "2", "--nms", "region4", "IMG"], "3x3 or none"),
        (["--min-area", "3", "IMG"], "--min-area needs --nms region4 or region8"),
        (["--nms", "none", "--min-area", "0", "IMG"], "--min-area needs --nms region4"),
        (["--nms", "region8", "--min-area", "2048", "IMG"], "min-area must be an integer in"),
        (["--nms", "region8", "--min-area", "x", "IMG"], "min-area must be an integer in"),
        (["--nms", "region8", "--min-area", "-5", "IMG"], "min-area must be an integer in"),
        (["--nms", "region4", "--min-area", "3", "--ppc", "4", "IMG"], "--ppc 4 needs --nms"),
    ],
)
def test_sim_usage_errors(photo: Path, tmp_path: Path, capsys, argv, message):
    (tmp_path / "empty").mkdir()
    narrow = tmp_path / "w62.png"
    cv2.imwrite(str(narrow), testimages.crop(testimages.real_images()[0], 62, 48))
    subst = {"IMG": str(photo), "EMPTYDIR": str(tmp_path / "empty"), "x.png": str(tmp_path / "x")}
    subst["IMG60"] = str(narrow)
    status, _, err = run(["sim", *[subst.get(a, a) for a in argv]], capsys)
    assert status == 2
    assert err.startswith("fastnms: error: ") and message in err and err.count("\n") == 1


def test_sim_and_compare_with_a_budget(photo: Path, tmp_path: Path, capsys):
    """--cell 16 --per-cell 1 (the top built with the budget): the golden model's
    budget (the CSV sorted by y then x, as always), the same records and clocks from
    both engines with idles and stalls; `compare` says identical, against the golden
    model and OpenCV, each with the budget."""
    img = cv2.imread(str(photo), cv2.IMREAD_GRAYSCALE)
    want = cell_budget(detect(img, 10), 16, 1).tolist()
    assert 0 < len(want) < len(detect(img, 10))
    got = {}
    for engine in ("verilator", "cocotb"):
        out = tmp_path / f"{engine}.json"
        argv = ["sim", str(photo), "-t", "10", "--cell", "16", "--per-cell", "1"]
        argv += ["--engine", engine, "--idle", "0.2", "--stall", "0.3", "--seed", "3"]
        assert cli.main([*argv, "--json", str(out), "--csv", f"{out}.csv"]) == 0
        assert [list(r) for r in read_csv(Path(f"{out}.csv"))] == want
        summary = json.loads(out.read_text())
        assert (summary["cell"], summary["per_cell"]) == (16, 1)
        got[engine] = (summary["corners"], summary["cycles"], summary["input_stalls"])
    assert got["verilator"] == got["cocotb"]
    capsys.readouterr()
    argv = ["compare", str(photo), "-t", "10", "--cell", "16", "--per-cell", "1"]
    assert cli.main(argv) == 0
    out = capsys.readouterr().out
    assert "rtl vs golden model + budget: identical" in out
    assert "FAST + budget: identical" in out


@pytest.fixture(scope="module")
def textured(tmp_path_factory) -> Path:
    """96x72 blurred noise (keypoints inside ORB's border at t = 8), as a PNG file."""
    path = tmp_path_factory.mktemp("img") / "textured.png"
    cv2.imwrite(str(path), testimages.blurred_noise(np.random.default_rng(7), 96, 72))
    return path


def test_sim_and_compare_orb(textured: Path, tmp_path: Path, capsys):
    """--orb (the top built with DESCRIPTOR orb, the fast engine): the CSV equals `golden
    --orb`'s (angles and descriptors), the JSON says orb, and `compare --orb` finds the
    angles' float32 bits and every descriptor bit identical; fastnms.sim.detect_and_compute
    gives golden detect_and_compute's keypoints and descriptors."""
    path = textured
    budget = ["--cell", "16", "--per-cell", "3"]
    gold, rtl, out = tmp_path / "g.csv", tmp_path / "r.csv", tmp_path / "r.json"
    assert cli.main(["golden", str(path), "-t", "8", "--orb", *budget, "--csv", str(gold)]) == 0
    argv = ["sim", str(path), "-t", "8", "--orb", *budget]
    assert cli.main([*argv, "--csv", str(rtl), "--json", str(out)]) == 0
    assert rtl.read_text() == gold.read_text()
    assert len(gold.read_text().splitlines()) > 3, "too few keypoints for a test"
    assert json.loads(out.read_text())["orb"] is True
    capsys.readouterr()
    argv = ["compare", str(path), "-t", "8", "--orb", *budget]
    assert cli.main(argv) == 0
    assert "rtl vs golden model ORB: identical" in capsys.readouterr().out

    from fastnms.golden import orb
    from fastnms.sim import detect_and_compute

    img = load_grey(path)
    keypoints, descriptors = detect_and_compute(img, 8, cell=16, per_cell=3)
    want_kp, want_d = orb.detect_and_compute(img, 8, cell=16, per_cell=3)
    got = [(k.pt, k.angle, k.response, k.size, k.octave) for k in keypoints]
    assert got == [(k.pt, k.angle, k.response, k.size, k.octave) for k in want_kp]
    assert descriptors.dtype == np.uint8 and np.array_equal(descriptors, want_d)


@pytest.mark.slow
def test_orb_engines_agree(textured: Path, tmp_path: Path):
    """--orb on both engines with idles and stalls: the same records (angles, descriptors)
    and the same clock counts."""
    got = {}
    for engine in ("verilator", "cocotb"):
        out = tmp_path / f"{engine}.json"
        argv = ["sim", str(textured), "-t", "8", "--orb", "--cell", "32", "--per-cell", "2"]
        argv += ["--engine", engine, "--idle", "0.2", "--stall", "0.3", "--seed", "5"]
        assert cli.main([*argv, "--json", str(out), "--csv", f"{out}.csv"]) == 0
        summary = json.loads(out.read_text())
        csv_text = Path(f"{out}.csv").read_text()
        got[engine] = (csv_text, summary["corners"], summary["cycles"], summary["input_stalls"])
    assert got["verilator"] == got["cocotb"]
    assert got["verilator"][1] > 2, "too few keypoints for a test"


def test_missing_simulator_is_named(photo: Path, capsys, monkeypatch):
    """Without Verilator on PATH, `fastnms sim` says what is missing and how to get it."""
    monkeypatch.setenv("PATH", "/nonexistent")
    assert cli.main(["sim", str(photo)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fastnms: error: ") and "verilator" in err and "apt-get" in err


def test_compare_identical_and_different(photo: Path, capsys, monkeypatch):
    assert cli.main(["compare", str(photo), "-t", "15"]) == 0
    out = capsys.readouterr().out
    assert "rtl vs golden model: identical" in out and "OpenCV" in out

    real_run = sim.run_rtl

    def one_corner_off(*args, **kwargs):
        result = real_run(*args, **kwargs)
        result.frames[0].records[0, 2] += 1
        return result

    monkeypatch.setattr(rtl_run, "run_rtl", one_corner_off)
    assert cli.main(["compare", str(photo), "-t", "15"]) == 1
    out = capsys.readouterr().out
    assert "DIFFERENT" in out and "rtl only" in out and "reference only" in out


@pytest.mark.parametrize("size", [(6, 20), (20, 6), (3841, 8), (8, 2161)])
def test_sim_refuses_sizes_outside_the_ip(tmp_path: Path, capsys, size: tuple[int, int]):
    path = tmp_path / "odd.png"
    cv2.imwrite(str(path), np.zeros((size[1], size[0]), dtype=np.uint8))
    out = tmp_path / "c.csv"
    assert cli.main(["sim", str(path), "--csv", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fastnms: error: ") and err.count("\n") == 1
    assert not out.exists()


def test_build_size_follows_the_largest_frame():
    """Full HD keeps the 1920x1080 build; a larger frame (either way) takes 3840x2160."""
    assert sim.build_size([(1080, 1920), (7, 7)]) == (1920, 1080)
    assert sim.build_size([(1080, 1920), (8, 1928)]) == (3840, 2160)
    assert sim.build_size([(1088, 8)]) == (3840, 2160)
    assert sim.generics_for("opencv", "3x3", 4, (3840, 2160)) == {
        "MAX_WIDTH": 3840,
        "MAX_HEIGHT": 2160,
        "SCORE": "opencv",
        "NMS": "3x3",
        "PPC": 4,
    }


@pytest.mark.slow
def test_sim_4k_at_four_pixels_per_clock(tmp_path: Path):
    """A 3840x2160 photograph through `fastnms sim --ppc 4` (the top built for 3840x2160,
    the build `make bench` uses): the golden model's corners."""
    path, out_json, out_csv = tmp_path / "uhd.png", tmp_path / "c.json", tmp_path / "c.csv"
    img = testimages.cover(load_grey(testimages.real_images()[0]), 3840, 2160)
    cv2.imwrite(str(path), img)
    argv = ["sim", str(path), str(path), "--ppc", "4", "--json", str(out_json)]
    assert cli.main([*argv, "--csv", str(out_csv)]) == 0
    summary = json.loads(out_json.read_text())
    want = [tuple(int(v) for v in r) for r in detect(img, 20)]
    assert [f["corners"] for f in summary["frames"]] == [len(want)] * 2
    with open(out_csv) as f:
        got = [(int(r["x"]), int(r["y"]), int(r["score"])) for r in csv.DictReader(f)]
    assert got == [(x, y, s) for _ in range(2) for x, y, s in want]


def test_sim_bad_input(tmp_path: Path, capsys):
    assert cli.main(["sim", str(tmp_path / "missing.png")]) == 2
    assert capsys.readouterr().err.startswith("fastnms: error: ")
    assert cli.main(["compare", str(tmp_path / "missing.png")]) == 2
    assert capsys.readouterr().err.startswith("fastnms: error: ")


# ---- --min-area, without an engine ---------------------------------------------------------


@pytest.mark.parametrize("command", ["sim", "compare"])
@pytest.mark.parametrize(
    "bad",
    [
        ["--min-area", "3"],
        ["--nms", "3x3", "--min-area", "1"],
        ["--nms", "region4", "--min-area", "2048"],
        ["--nms", "region4", "--min-area", "1e3"],
        ["--nms", "region4", "--min-area", "3", "--orb", "--cell", "16", "--per-cell", "2"],
    ],
)
def test_min_area_usage_errors(photo: Path, tmp_path: Path, capsys, monkeypatch, command, bad):
    """One `fastnms: error:` line, exit status 2, no output file, and no engine started."""

    def no_engine(*args, **kwargs):
        raise AssertionError("the engine was started")

    monkeypatch.setattr(rtl_run, "run_rtl", no_engine)
    out_csv = tmp_path / "c.csv"
    status, out, err = run([command, str(photo), *bad, "--csv", str(out_csv)], capsys)
    assert status == 2 and out == "" and err.startswith("fastnms: error: ")
    assert err.count("\n") == 1 and "min-area" in err
    assert not out_csv.exists()


def record_words(records: np.ndarray) -> np.ndarray:
    """The record words of one frame of (x, y, score, area) records, as the IP emits them."""
    from fastnms.sim import regs

    if len(records) == 0:
        return np.array([regs.REC_EMPTY.mask | regs.REC_LAST.mask], dtype=np.uint64)
    words = [
        x << regs.REC_X.lsb | y << regs.REC_Y.lsb | s << regs.REC_SCORE.lsb | a << regs.REC_AREA.lsb
        for x, y, s, a in records.tolist()
    ]
    words[-1] |= regs.REC_LAST.mask
    return np.array(words, dtype=np.uint64)


@pytest.fixture
def golden_engine(monkeypatch) -> list[dict]:
    """run_rtl replaced by the golden model's region records (with their areas, filtered
    by min_area) encoded as record words and decoded as the engines' are: the command
    line's plumbing of --min-area without an engine. Gives the calls' keyword arguments."""
    from fastnms.sim.verilator import RawFrame

    calls: list[dict] = []

    def fake_run_rtl(frames, score, nms, **kwargs):
        calls.append(kwargs)
        min_area = kwargs.get("min_area")
        raw = []
        for img, t in frames:
            records = detect(img, t, score, nms, min_area or 0, with_area=True)
            words = record_words(records)
            clocks = np.arange(len(words), dtype=np.int64)
            raw.append(RawFrame(0, img.size - 1, img.size + len(words), words, 0, clocks))
        results = sim._frame_results(frames, raw)
        return sim.SimResult(results, 1000, 0, 0.1, kwargs.get("engine", "verilator"))

    monkeypatch.setattr(rtl_run, "run_rtl", fake_run_rtl)
    return calls


def read_area_csv(path: Path, frame: bool = False) -> list[tuple[int, ...]]:
    names = ["frame"] * frame + ["x", "y", "score", "area"]
    with open(path) as f:
        reader = csv.DictReader(f)
        assert reader.fieldnames == names
        return [tuple(int(r[n]) for n in names) for r in reader]


@pytest.mark.parametrize("nms", ["region4", "region8"])
def test_sim_min_area_plumbing(photo: Path, tmp_path: Path, capsys, golden_engine, nms: str):
    """--min-area N reaches run_rtl as min_area (None without it); the CSV has the
    records' areas (decoded from AREA), the JSON min_area, the summary min-area=N."""
    img = cv2.imread(str(photo), cv2.IMREAD_GRAYSCALE)
    every = detect(img, 10, "opencv", nms, with_area=True)
    assert len(every) and every[:, 3].max() >= 3 and (every[:, 3] < 3).any(), "a weak test"
    out_csv, out_json = tmp_path / "c.csv", tmp_path / "c.json"
    argv = ["sim", str(photo), "-t", "10", "--nms", nms, "--csv", str(out_csv)]
    assert cli.main([*argv, "--json", str(out_json), "--min-area", "3"]) == 0
    assert golden_engine[-1]["min_area"] == 3
    want = [tuple(r) for r in every[every[:, 3] >= 3].tolist()]
    assert read_area_csv(out_csv) == want
    assert json.loads(out_json.read_text())["min_area"] == 3
    assert f"threshold=10 min-area=3: {len(want)} corners;" in capsys.readouterr().out

    assert cli.main([*argv, "--json", str(out_json)]) == 0
    assert golden_engine[-1]["min_area"] is None
    assert read_area_csv(out_csv) == [tuple(r) for r in every.tolist()]
    assert json.loads(out_json.read_text())["min_area"] is None

    # Several frames: the CSV's first column is the frame.
    two = ["sim", str(photo), str(photo), *argv[2:]]
    assert cli.main([*two, "--min-area", "2047"]) == 0
    assert read_area_csv(out_csv, frame=True) == []
    assert cli.main([*two, "--min-area", "2"]) == 0
    twice = [(i, *r) for i in range(2) for r in every[every[:, 3] >= 2].tolist()]
    assert read_area_csv(out_csv, frame=True) == twice
    # The other NMS: no area column, MIN_AREA not written.
    assert cli.main(["sim", str(photo), "-t", "10", "--csv", str(out_csv)]) == 0
    assert golden_engine[-1]["min_area"] is None
    with open(out_csv) as f:
        assert f.readline() == "x,y,score\n"


def test_compare_min_area_checks_the_areas(photo: Path, capsys, golden_engine, monkeypatch):
    """compare with a region NMS: the golden model filtered by --min-area, and the
    records' areas compared too (one area off is a difference)."""
    argv = ["compare", str(photo), "-t", "10", "--nms", "region8", "--min-area", "2"]
    capsys.readouterr()
    assert cli.main(argv) == 0
    out = capsys.readouterr().out
    assert "rtl vs golden model: identical" in out and "with their areas" in out
    assert golden_engine[-1]["min_area"] == 2

    fake = rtl_run.run_rtl

    def one_area_off(*args, **kwargs):
        result = fake(*args, **kwargs)
        result.frames[0].areas[0] += 1
        return result

    monkeypatch.setattr(rtl_run, "run_rtl", one_area_off)
    assert cli.main(argv) == 1
    out = capsys.readouterr().out
    assert "DIFFERENT" in out and "rtl only" in out and "reference only" in out
    # The regions the golden model drops are a difference too.
    monkeypatch.setattr(rtl_run, "run_rtl", fake)
    assert cli.main([*argv[:-1], "3"]) == 0
    golden_engine.clear()

    def unfiltered(frames, score, nms, **kwargs):
        return fake(frames, score, nms, **{**kwargs, "min_area": None})

    monkeypatch.setattr(rtl_run, "run_rtl", unfiltered)
    capsys.readouterr()
    assert cli.main(argv) == 1
    out = capsys.readouterr().out
    assert "DIFFERENT" in out and "rtl only" in out and "reference only" not in out
