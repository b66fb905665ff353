"""The `fastnms` command line, in-process through main(argv) and once through the installed
console script; plus load_grey, which it uses."""

from __future__ import annotations

import csv
import os
import re
import subprocess
import sys
from pathlib import Path

import cv2
import numpy as np
import pytest
from fastnms import golden_command, outputs, overlay
from fastnms import main as cli
from fastnms.golden.budget import cell_budget
from fastnms.golden.image import ImageError, load_grey
from fastnms.golden.model import NMS_MODES, SCORES, detect
from fastnms.golden.orb import orb_features

SUMMARY = re.compile(
    r"^(?P<name>\S+): (?P<w>\d+)x(?P<h>\d+), score=(?P<score>\w+) nms=(?P<nms>\w+) "
    r"threshold=(?P<t>\d+): (?P<n>\d+) corners in \d+\.\d{3} s$"
)


@pytest.fixture
def grey_image(tmp_path: Path, rng: np.random.Generator) -> tuple[Path, np.ndarray]:
    img = cv2.GaussianBlur(rng.integers(0, 256, (70, 90), dtype=np.uint8), (0, 0), 1.0)
    img = cv2.normalize(img, None, 0, 255, cv2.NORM_MINMAX)
    path = tmp_path / "in" / "noise.png"
    path.parent.mkdir()
    assert cv2.imwrite(str(path), img)
    return path, img


def read_csv(path: Path, area: bool = False) -> np.ndarray:
    """x,y,score; with `area` (a region NMS) x,y,score,area."""
    header = ["x", "y", "score", *(["area"] if area else [])]
    with path.open(newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == header
    return np.array([[int(v) for v in row] for row in rows[1:]], dtype=np.int64).reshape(
        -1, len(header)
    )


def run(argv: list[str], capsys: pytest.CaptureFixture) -> tuple[int, str, str]:
    """main(argv) as the shell would see it: exit status, stdout, stderr (capsys or capfd)."""
    capsys.readouterr()  # drop anything fixtures printed
    try:
        status = cli.main(argv)
    except SystemExit as e:
        status = e.code if isinstance(e.code, int) else 1
    out, err = capsys.readouterr()
    return status, out, err


def assert_usage_error(status: int, out: str, err: str) -> None:
    assert status == 2
    assert out == ""
    lines = err.splitlines()
    assert len(lines) == 1 and lines[0].startswith("fastnms: error: "), err
    assert "Traceback" not in err


@pytest.mark.parametrize("score", SCORES)
@pytest.mark.parametrize("nms", NMS_MODES)
def test_golden_writes_csv_and_png(grey_image, tmp_path: Path, capsys, score: str, nms: str):
    path, img = grey_image
    out_csv, out_png = tmp_path / "c.csv", tmp_path / "p.png"
    argv = ["golden", str(path), "-t", "12", "--score", score, "--nms", nms]
    status, out, err = run([*argv, "--csv", str(out_csv), "--png", str(out_png)], capsys)
    assert (status, err) == (0, "")
    region = nms.startswith("region")
    expected = detect(img, 12, score, nms, with_area=region)
    assert len(expected) > 0
    m = SUMMARY.match(out.rstrip("\n"))
    assert m and out.count("\n") == 1, out
    assert m["name"] == "noise.png" and (m["w"], m["h"]) == ("90", "70")
    assert (m["score"], m["nms"], m["t"], int(m["n"])) == (score, nms, "12", len(expected))
    # The region NMS's records with the area of their region (a fourth column).
    assert np.array_equal(read_csv(out_csv, area=region), expected)

    png = cv2.imread(str(out_png), cv2.IMREAD_UNCHANGED)
    assert png.shape == (70, 90, 3)
    # Boxes are drawn weakest first, so the last-drawn strongest corner's outline is intact
    # yellow, and away from the boxes the picture is the grey input.
    strongest = expected[np.argsort(expected[:, 2], kind="stable")[-1]]
    x, y = int(strongest[0]), int(strongest[1])
    if 3 <= x <= 86 and 3 <= y <= 66:
        assert png[y - 3, x - 3].tolist() == list(overlay.HIGH_BGR)
        assert png[y + 3, x + 3].tolist() == list(overlay.HIGH_BGR)
    untouched = np.ones(img.shape, bool)
    for cx, cy, *_ in expected.tolist():
        untouched[max(cy - 3, 0) : cy + 4, max(cx - 3, 0) : cx + 4] = False
    assert untouched.any()
    assert np.array_equal(png[untouched], np.repeat(img[untouched][:, None], 3, axis=1))


def test_defaults_and_no_outputs(grey_image, capsys):
    path, img = grey_image
    status, out, err = run(["golden", str(path)], capsys)
    assert (status, err) == (0, "")
    m = SUMMARY.match(out.strip())
    assert m and (m["score"], m["nms"], m["t"]) == ("opencv", "3x3", "20")
    assert int(m["n"]) == len(detect(img))
    assert sorted(os.listdir(path.parent)) == ["noise.png"]  # nothing written


def test_score_colours_span_dark_red_to_yellow():
    colours = overlay.score_colours(np.array([30, 40, 50]))
    assert colours[0].tolist() == list(overlay.LOW_BGR)
    assert colours[-1].tolist() == list(overlay.HIGH_BGR)
    assert 0 < colours[1, 1] < 255  # in between
    assert overlay.score_colours(np.array([7, 7])).tolist() == [list(overlay.HIGH_BGR)] * 2
    assert overlay.score_colours(np.array([], dtype=np.int64)).shape == (0, 3)


def test_colour_input_is_converted_like_opencv(tmp_path: Path, rng, capsys):
    bgr = cv2.GaussianBlur(rng.integers(0, 256, (40, 50, 3), dtype=np.uint8), (0, 0), 1.0)
    path = tmp_path / "colour.png"
    assert cv2.imwrite(str(path), bgr)
    grey = cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)
    assert np.array_equal(load_grey(path), grey)
    out_csv = tmp_path / "c.csv"
    status, _, _ = run(["golden", str(path), "-t", "5", "--csv", str(out_csv)], capsys)
    assert status == 0
    got = read_csv(out_csv)
    assert len(got) > 0 and np.array_equal(got, detect(grey, 5))


def test_load_grey_keeps_grey_values(grey_image):
    path, img = grey_image
    assert load_grey(path).dtype == np.uint8
    assert np.array_equal(load_grey(path), img)


@pytest.mark.parametrize("kind", ["missing", "text", "empty", "directory"])
def test_load_grey_errors(tmp_path: Path, kind: str):
    path = tmp_path / "x.png"
    if kind == "text":
        path.write_text("not an image\n")
    elif kind == "empty":
        path.write_bytes(b"")
    elif kind == "directory":
        path.mkdir()
    with pytest.raises(ImageError, match=re.escape(str(path))):
        load_grey(path)


BAD_ARGS = {
    "threshold_word": ["-t", "abc"],
    "threshold_negative": ["--threshold", "-1"],
    "threshold_256": ["--threshold", "256"],
    "threshold_fraction": ["--threshold", "1.5"],
    "unknown_score": ["--score", "harris"],
    "unknown_nms": ["--nms", "5x5"],
    "unknown_option": ["--frobnicate"],
    "min_area_word": ["--nms", "region8", "--min-area", "abc"],
    "min_area_negative": ["--nms", "region8", "--min-area", "-1"],
    "min_area_2048": ["--nms", "region4", "--min-area", "2048"],
    "min_area_fraction": ["--nms", "region4", "--min-area", "2.5"],
    "min_area_empty": ["--nms", "region4", "--min-area", ""],
    "min_area_without_nms": ["--min-area", "3"],  # the default NMS is 3x3
    "min_area_3x3": ["--nms", "3x3", "--min-area", "3"],
    "min_area_none": ["--nms", "none", "--min-area", "0"],
    "min_area_orb": ["--nms", "region8", "--min-area", "3", "--orb"],
}


@pytest.mark.parametrize("name", sorted(BAD_ARGS))
def test_bad_arguments(grey_image, tmp_path: Path, capsys, name: str):
    path, _ = grey_image
    out_csv = tmp_path / "c.csv"
    status, out, err = run(["golden", str(path), "--csv", str(out_csv), *BAD_ARGS[name]], capsys)
    assert_usage_error(status, out, err)
    assert not out_csv.exists()


def test_missing_image_argument_and_unknown_command(capsys):
    assert_usage_error(*run(["golden"], capsys))
    assert_usage_error(*run(["bogus"], capsys))


@pytest.mark.parametrize("kind", ["missing", "text", "directory", "corrupt_png", "truncated_png"])
def test_bad_image(grey_image, tmp_path: Path, capfd, kind: str):
    """capfd, not capsys: OpenCV's decoders would log to file descriptor 2 directly."""
    path = tmp_path / "x.png"
    if kind == "text":
        path.write_text("hello\n")
    elif kind == "directory":
        path.mkdir()
    elif kind == "corrupt_png":
        path.write_bytes(b"\x89PNG\r\n\x1a\n" + bytes(range(256)) * 4)
    elif kind == "truncated_png":
        data = grey_image[0].read_bytes()
        path.write_bytes(data[: len(data) // 2])
    out_csv, out_png = tmp_path / "c.csv", tmp_path / "p.png"
    before = sorted(os.listdir(tmp_path))
    status, out, err = run(
        ["golden", str(path), "--csv", str(out_csv), "--png", str(out_png)], capfd
    )
    assert_usage_error(status, out, err)
    assert str(path) in err
    assert sorted(os.listdir(tmp_path)) == before


@pytest.mark.parametrize(
    "case", ["csv_dir_missing", "png_dir_missing", "csv_is_dir", "png_is_dir", "same_file"]
)
def test_unwritable_outputs(grey_image, tmp_path: Path, capsys, monkeypatch, case: str):
    path, _ = grey_image
    out = tmp_path / "out"
    out.mkdir()
    csv_path, png_path = out / "c.csv", out / "p.png"
    if case == "csv_dir_missing":
        csv_path = tmp_path / "nope" / "c.csv"
    elif case == "png_dir_missing":
        png_path = tmp_path / "nope" / "p.png"
    elif case == "csv_is_dir":
        csv_path.mkdir()
    elif case == "png_is_dir":
        png_path.mkdir()
    else:
        png_path = csv_path
    before = sorted(os.listdir(out))

    def no_work(*args, **kwargs):
        raise AssertionError("outputs must be checked before any detection work")

    monkeypatch.setattr(golden_command, "detect", no_work)
    argv = ["golden", str(path), "--csv", str(csv_path), "--png", str(png_path)]
    assert_usage_error(*run(argv, capsys))
    assert sorted(os.listdir(out)) == before
    assert not (tmp_path / "nope").exists()


def test_png_failure_removes_csv(grey_image, tmp_path: Path, capsys, monkeypatch):
    path, _ = grey_image

    def broken_png(canvas):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(outputs, "png_bytes", broken_png)
    argv = ["golden", str(path), "--csv", str(tmp_path / "c.csv"), "--png", str(tmp_path / "p.png")]
    status, out, err = run(argv, capsys)
    assert_usage_error(status, out, err)
    assert "No space left on device" in err
    assert sorted(os.listdir(tmp_path)) == ["in"]


def test_failed_move_takes_back_earlier_outputs(grey_image, tmp_path: Path, capsys, monkeypatch):
    path, _ = grey_image
    real_replace = os.replace

    def replace(src, dst):
        if str(dst).endswith(".png"):
            raise PermissionError(13, "Permission denied", str(dst))
        real_replace(src, dst)

    monkeypatch.setattr(outputs.os, "replace", replace)
    argv = ["golden", str(path), "--csv", str(tmp_path / "c.csv"), "--png", str(tmp_path / "p.png")]
    assert_usage_error(*run(argv, capsys))
    assert sorted(os.listdir(tmp_path)) == ["in"]


def test_outputs_replace_existing_files(grey_image, tmp_path: Path, capsys):
    path, img = grey_image
    out_csv = tmp_path / "c.csv"
    out_csv.write_text("old\n")
    status, _, _ = run(["golden", str(path), "--csv", str(out_csv)], capsys)
    assert status == 0
    assert np.array_equal(read_csv(out_csv), detect(img))
    assert sorted(os.listdir(tmp_path)) == ["c.csv", "in"]  # no temporary file left


def test_help_and_no_command(capsys):
    with pytest.raises(SystemExit) as info:
        cli.main(["--help"])
    assert info.value.code == 0
    assert "golden" in capsys.readouterr().out
    with pytest.raises(SystemExit) as info:
        cli.main(["golden", "--help"])
    assert info.value.code == 0
    help_text = capsys.readouterr().out
    assert "COLOR_BGR2GRAY" in help_text and "--threshold" in help_text
    assert cli.main([]) == 2
    out, err = capsys.readouterr()
    assert "usage: fastnms" in out and err == ""


def test_console_script(grey_image, tmp_path: Path):
    """The installed entry point, as a user runs it."""
    exe = Path(sys.executable).parent / "fastnms"
    assert exe.exists(), f"console script missing: {exe}"
    path, img = grey_image
    done = subprocess.run(
        [str(exe), "golden", str(path), "--nms", "region8"],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 0, done.stderr
    assert done.stderr == ""
    m = SUMMARY.match(done.stdout.strip())
    assert m and int(m["n"]) == len(detect(img, 20, "opencv", "region8"))

    done = subprocess.run(
        [str(exe), "golden", str(tmp_path / "missing.png")],
        capture_output=True,
        text=True,
        timeout=60,
    )
    assert done.returncode == 2 and done.stdout == ""
    assert done.stderr.startswith("fastnms: error: ") and done.stderr.count("\n") == 1


# ---- --orb ------------------------------------------------------------------------------

ORB_SUMMARY = re.compile(r": (?P<n>\d+) keypoints with ORB descriptors in \d+\.\d{3} s$")


@pytest.fixture
def textured_image(tmp_path: Path, rng: np.random.Generator) -> tuple[Path, np.ndarray]:
    img = cv2.GaussianBlur(rng.integers(0, 256, (120, 160), dtype=np.uint8), (0, 0), 2.0)
    img = cv2.normalize(img, None, 0, 255, cv2.NORM_MINMAX)
    path = tmp_path / "texture.png"
    assert cv2.imwrite(str(path), img)
    return path, img


@pytest.mark.parametrize("nms", ["3x3", "region8"])
def test_golden_orb_writes_csv_and_png(textured_image, tmp_path: Path, capsys, nms: str):
    path, img = textured_image
    out_csv, out_png = tmp_path / "o.csv", tmp_path / "o.png"
    argv = ["golden", str(path), "--orb", "-t", "10", "--nms", nms]
    status, out, err = run([*argv, "--csv", str(out_csv), "--png", str(out_png)], capsys)
    assert (status, err) == (0, "")
    want = orb_features(img, 10, "opencv", nms)
    m = ORB_SUMMARY.search(out.strip())
    assert m and int(m["n"]) == len(want.records) > 0, out

    with out_csv.open(newline="") as f:
        rows = list(csv.reader(f))
    assert rows[0] == ["x", "y", "score", "angle", "descriptor"]
    assert len(rows) == len(want.records) + 1
    for row, rec, angle, des in zip(
        rows[1:], want.records, want.angles, want.descriptors, strict=True
    ):
        assert [int(v) for v in row[:3]] == rec.tolist()
        assert np.float32(float(row[3])).view(np.uint32) == angle.view(np.uint32)
        assert re.fullmatch(r"[0-9a-f]{64}", row[4]) and bytes.fromhex(row[4]) == bytes(des)

    png = cv2.imread(str(out_png), cv2.IMREAD_UNCHANGED)
    strongest = np.argsort(want.records[:, 2], kind="stable")[-1]
    x, y, _ = want.records[strongest].tolist()
    t = np.radians(float(want.angles[strongest]))
    tip = (
        round(x + overlay.ORIENTATION_LENGTH * np.cos(t)),
        round(y + overlay.ORIENTATION_LENGTH * np.sin(t)),
    )
    assert png[tip[1], tip[0]].tolist() == list(overlay.HIGH_BGR)  # the line's end, drawn last


def test_golden_orb_on_a_small_image_has_a_header_only(textured_image, tmp_path: Path, capsys):
    """62 pixels high: no row is 31 pixels from both borders, although FAST finds corners."""
    _, img = textured_image
    path, out_csv = tmp_path / "low.png", tmp_path / "o.csv"
    assert cv2.imwrite(str(path), img[:62]) and len(detect(img[:62], 10)) > 0
    status, out, err = run(
        ["golden", str(path), "--orb", "-t", "10", "--csv", str(out_csv)], capsys
    )
    assert (status, err) == (0, "") and ORB_SUMMARY.search(out.strip())["n"] == "0"
    assert out_csv.read_text() == "x,y,score,angle,descriptor\n"


@pytest.mark.parametrize("bad", [["-t", "300"], ["--nms", "5x5"], ["--orb=1"]])
def test_golden_orb_bad_arguments(textured_image, tmp_path: Path, capsys, bad: list[str]):
    path, _ = textured_image
    out_csv = tmp_path / "o.csv"
    status, out, err = run(["golden", str(path), "--orb", *bad, "--csv", str(out_csv)], capsys)
    assert_usage_error(status, out, err)
    assert not out_csv.exists()


def test_golden_orb_bad_image(tmp_path: Path, capsys):
    bad = tmp_path / "bad.png"
    bad.write_bytes(b"not an image")
    out_csv = tmp_path / "o.csv"
    status, out, err = run(["golden", str(bad), "--orb", "--csv", str(out_csv)], capsys)
    assert_usage_error(status, out, err)
    assert not out_csv.exists()


# ---- --cell / --per-cell ----------------------------------------------------------------


@pytest.mark.parametrize("orb", [False, True])
def test_golden_budget(textured_image, tmp_path: Path, capsys, orb: bool):
    path, img = textured_image
    out_csv = tmp_path / "b.csv"
    argv = [
        "golden",
        str(path),
        "-t",
        "5",
        "--cell",
        "32",
        "--per-cell",
        "2",
        "--csv",
        str(out_csv),
    ]
    status, out, err = run([*argv, *(["--orb"] if orb else [])], capsys)
    assert (status, err) == (0, "") and "(at most 2 per 32x32 cell)" in out
    with out_csv.open(newline="") as f:
        rows = [[int(v) for v in row[:3]] for row in list(csv.reader(f))[1:]]
    if orb:
        want = orb_features(img, 5, cell=32, per_cell=2).records
    else:
        want = cell_budget(detect(img, 5), 32, 2)
    assert rows == want.tolist() and 0 < len(rows) < len(detect(img, 5))


def test_budget_png_draws_the_grid(textured_image, tmp_path: Path, capsys):
    """With a budget the PNG shows the cells: blue lines every CELL pixels, none between."""
    path, img = textured_image
    out_png = tmp_path / "b.png"
    argv = ["golden", str(path), "-t", "250", "--cell", "16", "--per-cell", "1"]
    status, _, err = run([*argv, "--png", str(out_png)], capsys)
    assert (status, err) == (0, "")
    canvas = cv2.imread(str(out_png))
    grey = canvas[:, :, 0] == canvas[:, :, 2]
    h, w = img.shape
    for x in range(w):
        assert not grey[:, x].any() if x and x % 16 == 0 else grey[1:15, x].all(), x


@pytest.mark.parametrize(
    "bad",
    [
        ["--cell", "48", "--per-cell", "2"],
        ["--cell", "8", "--per-cell", "2"],
        ["--cell", "512", "--per-cell", "2"],
        ["--cell", "x", "--per-cell", "2"],
        ["--cell", "32", "--per-cell", "0"],
        ["--cell", "32", "--per-cell", "16"],
        ["--cell", "32", "--per-cell", "two"],
        ["--cell", "32"],
        ["--per-cell", "3"],
    ],
)
def test_golden_bad_budget(textured_image, tmp_path: Path, capsys, bad: list[str]):
    path, _ = textured_image
    out_csv = tmp_path / "b.csv"
    status, out, err = run(["golden", str(path), *bad, "--csv", str(out_csv)], capsys)
    assert_usage_error(status, out, err)
    assert not out_csv.exists()


# ---- --min-area --------------------------------------------------------------------------


@pytest.mark.parametrize("nms", ["region4", "region8"])
def test_golden_min_area(grey_image, tmp_path: Path, capsys, nms: str):
    """--min-area N: the golden model's regions of N corner pixels or more, each record
    with its area; 0 and 1 keep every region, as without the option; 2047 the largest."""
    path, img = grey_image
    every = detect(img, 8, "opencv", nms, with_area=True)
    areas = every[:, 3]
    assert len(every) and areas.max() >= 4 and (areas == 1).any(), "a weak test image"
    for n in [0, 1, 2, 4, int(areas.max()), int(areas.max()) + 1, 2047]:
        out_csv = tmp_path / f"m{n}.csv"
        argv = ["golden", str(path), "-t", "8", "--nms", nms, "--min-area", str(n)]
        status, out, err = run([*argv, "--csv", str(out_csv)], capsys)
        assert (status, err) == (0, ""), err
        want = every[areas >= n]
        assert np.array_equal(want, detect(img, 8, "opencv", nms, n, with_area=True))
        got = read_csv(out_csv, area=True)
        assert np.array_equal(got, want), f"min-area {n}"
        assert f"threshold=8 min-area={n}: {len(want)} corners in " in out, out
    assert np.array_equal(read_csv(tmp_path / "m1.csv", area=True), every)
    assert read_csv(tmp_path / "m2047.csv", area=True).shape == (0, 4)
    # Without --min-area: every region, and the summary as before.
    status, out, _ = run(["golden", str(path), "-t", "8", "--nms", nms], capsys)
    assert status == 0 and SUMMARY.match(out.strip())["n"] == str(len(every))


def test_golden_min_area_with_a_budget(textured_image, tmp_path: Path, capsys):
    """The budget after the region filtering: each kept record with its own area."""
    path, img = textured_image
    out_csv = tmp_path / "b.csv"
    argv = ["golden", str(path), "-t", "5", "--nms", "region8", "--min-area", "3"]
    status, out, err = run(
        [*argv, "--cell", "32", "--per-cell", "2", "--csv", str(out_csv)], capsys
    )
    assert (status, err) == (0, "")
    regions = detect(img, 5, "opencv", "region8", 3, with_area=True)
    want = cell_budget(regions[:, :3], 32, 2)
    got = read_csv(out_csv, area=True)
    assert np.array_equal(got[:, :3], want) and 0 < len(want) < len(regions)
    area = {(x, y): a for x, y, _, a in regions.tolist()}
    assert [a for x, y, _, a in got.tolist()] == [area[(x, y)] for x, y, _ in want.tolist()]
    assert (got[:, 3] >= 3).all()


def test_min_area_in_the_help(capsys):
    for command in ("golden", "sim", "compare"):
        with pytest.raises(SystemExit):
            cli.main([command, "--help"])
        text = " ".join(capsys.readouterr().out.split())
        assert "--min-area N" in text and "0..2047" in text, command
        assert "x,y,score,area" in text, command
