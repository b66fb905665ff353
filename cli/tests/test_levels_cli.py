"""`fastnms golden --levels` (the golden model on each level of cv2.ORB's image pyramid) and
`fastnms pyramid` (the level images), in-process through main(argv)."""

from __future__ import annotations

import csv
import os
import re
from pathlib import Path

import cv2
import numpy as np
import pytest
from fastnms import main as cli
from fastnms import overlay, pyramid_command
from fastnms.golden import pyramid
from fastnms.golden.budget import cell_budget
from fastnms.golden.model import detect
from fastnms.golden.orb import detect_and_compute, level_features

from cli.tests.test_cli import assert_usage_error, run

LEVELS_SUMMARY = re.compile(
    r"^(?P<name>\S+): (?P<w>\d+)x(?P<h>\d+), score=(?P<score>\w+) nms=(?P<nms>\w+) "
    r"threshold=(?P<t>\d+), (?P<levels>\d+) levels? at scale factor (?P<f>[0-9.]+): "
    r"(?P<n>\d+) (?P<what>corners|keypoints with ORB descriptors)(?P<within> \(at most "
    r"\d+ per \d+x\d+ cell\))? in \d+\.\d{3} s; per level (?P<per>\d+x\d+: \d+(?:, \d+x\d+: "
    r"\d+)*)$"
)


@pytest.fixture
def textured_image(tmp_path: Path, rng: np.random.Generator) -> tuple[Path, np.ndarray]:
    """160x120: levels 133x100 and 111x83 at 1.2, room for ORB keypoints on each."""
    img = cv2.GaussianBlur(rng.integers(0, 256, (120, 160), dtype=np.uint8), (0, 0), 2.0)
    img = cv2.normalize(img, None, 0, 255, cv2.NORM_MINMAX)
    path = tmp_path / "texture.png"
    assert cv2.imwrite(str(path), img)
    return path, img


def read_rows(path: Path) -> tuple[list[str], list[list[str]]]:
    with path.open(newline="") as f:
        rows = list(csv.reader(f))
    return rows[0], rows[1:]


def per_level(line: str) -> list[tuple[int, int, int]]:
    """(width, height, count) of each level in the summary line."""
    m = LEVELS_SUMMARY.match(line)
    assert m, line
    return [(int(w), int(h), int(n)) for w, h, n in re.findall(r"(\d+)x(\d+): (\d+)", m["per"])]


def expected_levels(img, t, orb, budget, nms="3x3", nlevels=3, scale_factor=1.2):
    """The golden model's per-level results, computed here from the library directly."""
    cell, per_cell = budget or (None, 0)
    results = []
    for image in pyramid.pyramid(img, nlevels, scale_factor):
        if orb:
            results.append(level_features(image, t, "opencv", nms, cell, per_cell))
        else:
            records = detect(image, t, "opencv", nms)
            results.append(cell_budget(records, cell, per_cell) if per_cell else records)
    return results


# ---- golden --levels --------------------------------------------------------------------


@pytest.mark.parametrize("budget", [None, (32, 2)], ids=["all", "budget"])
@pytest.mark.parametrize("orb", [False, True], ids=["fast", "orb"])
def test_golden_levels_csv(textured_image, tmp_path: Path, capsys, orb: bool, budget):
    path, img = textured_image
    out_csv = tmp_path / "l.csv"
    argv = ["golden", str(path), "-t", "10", "--levels", "3", "--csv", str(out_csv)]
    argv += ["--orb"] if orb else []
    argv += ["--cell", str(budget[0]), "--per-cell", str(budget[1])] if budget else []
    status, out, err = run(argv, capsys)
    assert (status, err) == (0, "")
    want = expected_levels(img, 10, orb, budget)
    counts = [len(w.records) if orb else len(w) for w in want]
    assert len(want) == 3 and all(counts), counts

    header, rows = read_rows(out_csv)
    if orb:
        assert header == ["level", "x", "y", "score", "angle", "descriptor"]
    else:
        assert header == ["level", "x", "y", "score"]
    assert [int(r[0]) for r in rows] == [k for k, n in enumerate(counts) for _ in range(n)]
    got = np.array([[int(v) for v in r[1:4]] for r in rows], np.int64)
    records = [w.records if orb else w for w in want]
    assert np.array_equal(got, np.concatenate(records))
    if orb:
        angles = np.array([float(r[4]) for r in rows], np.float32)
        want_angles = np.concatenate([w.angles for w in want])
        assert np.array_equal(angles.view(np.uint32), want_angles.view(np.uint32))
        assert all(re.fullmatch(r"[0-9a-f]{64}", r[5]) for r in rows)
        des = np.array([np.frombuffer(bytes.fromhex(r[5]), np.uint8) for r in rows])
        assert np.array_equal(des, np.concatenate([w.descriptors for w in want]))

    line = out.rstrip("\n")
    assert out.count("\n") == 1
    m = LEVELS_SUMMARY.match(line)
    assert m, line
    assert (m["name"], m["w"], m["h"], m["levels"], m["f"]) == (
        "texture.png",
        "160",
        "120",
        "3",
        "1.2",
    )
    assert m["what"] == ("keypoints with ORB descriptors" if orb else "corners")
    assert int(m["n"]) == sum(counts)
    assert bool(m["within"]) == bool(budget)
    sizes = [pyramid.level_size(160, 120, k) for k in range(3)]
    assert sizes == [(160, 120), (133, 100), (111, 83)]
    assert per_level(line) == [(w, h, n) for (w, h), n in zip(sizes, counts, strict=True)]


@pytest.mark.parametrize("budget", [None, (32, 2)], ids=["all", "budget"])
@pytest.mark.parametrize("orb", [False, True], ids=["fast", "orb"])
def test_golden_levels_are_detect_and_compute(
    textured_image, tmp_path: Path, capsys, orb: bool, budget
):
    """The CSV's level positions times scale_k in float32 are cv2.KeyPoint.pt of the golden
    model's detect_and_compute(nlevels=3) (cv2.ORB's keypoints), octave the level."""
    path, img = textured_image
    out_csv = tmp_path / "l.csv"
    argv = ["golden", str(path), "-t", "10", "--levels", "3", "--csv", str(out_csv)]
    argv += ["--orb"] if orb else []
    argv += ["--cell", str(budget[0]), "--per-cell", str(budget[1])] if budget else []
    assert run(argv, capsys)[0] == 0
    cell, per_cell = budget or (None, 0)
    keypoints, descriptors = detect_and_compute(
        img, 10, orb=orb, cell=cell, per_cell=per_cell, nlevels=3
    )
    _, rows = read_rows(out_csv)
    assert len(rows) == len(keypoints) > 0
    for row, kp in zip(rows, keypoints, strict=True):
        level, x, y, score = (int(v) for v in row[:4])
        scale = pyramid.level_scale(level, 1.2)
        assert kp.octave == level
        assert kp.pt == (float(np.float32(x) * scale), float(np.float32(y) * scale))
        assert kp.size == float(np.float32(31 if orb else 7) * scale)
        assert kp.response == score
        if orb:
            assert np.float32(float(row[4])) == np.float32(kp.angle)
    if orb:
        got = np.array([np.frombuffer(bytes.fromhex(r[5]), np.uint8) for r in rows])
        assert np.array_equal(got, descriptors)
    else:
        assert descriptors is None


def test_one_level_is_the_single_level_model(textured_image, tmp_path: Path, capsys):
    """--levels 1: today's corners (and ORB features), each row led by level 0."""
    path, img = textured_image
    for orb in (False, True):
        out_csv = tmp_path / f"one{orb}.csv"
        argv = ["golden", str(path), "-t", "10", "--levels", "1", "--csv", str(out_csv)]
        status, out, _ = run([*argv, *(["--orb"] if orb else [])], capsys)
        assert status == 0 and " 1 level at scale factor 1.2: " in out
        header, rows = read_rows(out_csv)
        assert header[0] == "level" and {r[0] for r in rows} == {"0"}
        single = tmp_path / f"single{orb}.csv"
        argv = ["golden", str(path), "-t", "10", "--csv", str(single)]
        assert run([*argv, *(["--orb"] if orb else [])], capsys)[0] == 0
        assert [r[1:] for r in rows] == list(csv.reader(single.open(newline="")))[1:]
        assert per_level(out.strip()) == [(160, 120, len(rows))]


def test_levels_with_a_region_nms_have_no_area(textured_image, tmp_path: Path, capsys):
    path, img = textured_image
    out_csv = tmp_path / "r.csv"
    argv = ["golden", str(path), "-t", "10", "--nms", "region8", "--levels", "2"]
    status, out, err = run([*argv, "--csv", str(out_csv)], capsys)
    assert (status, err) == (0, "")
    header, rows = read_rows(out_csv)
    assert header == ["level", "x", "y", "score"]
    want = expected_levels(img, 10, False, None, "region8", 2)
    assert [[int(v) for v in r] for r in rows] == [
        [k, *rec] for k, records in enumerate(want) for rec in records.tolist()
    ]


def test_scale_factor(textured_image, tmp_path: Path, capsys):
    path, img = textured_image
    out_csv = tmp_path / "f.csv"
    argv = ["golden", str(path), "-t", "10", "--levels", "4", "--scale-factor", "1.5"]
    status, out, err = run([*argv, "--csv", str(out_csv)], capsys)
    assert (status, err) == (0, "") and " 4 levels at scale factor 1.5: " in out
    want = expected_levels(img, 10, False, None, nlevels=4, scale_factor=1.5)
    sizes = [(160, 120), (107, 80), (71, 53), (47, 36)]
    assert [pyramid.level_size(160, 120, k, 1.5) for k in range(4)] == sizes
    assert per_level(out.strip()) == [(w, h, len(r)) for (w, h), r in zip(sizes, want, strict=True)]
    _, rows = read_rows(out_csv)
    assert len(rows) == sum(map(len, want))


def test_levels_of_no_pixels_have_no_keypoints(tmp_path: Path, rng, capsys):
    """A 2x10 image: from level 8 on (at 1.2) the levels are 0 pixels wide; golden lists
    them with no keypoints (pyramid refuses to write them, below)."""
    path = tmp_path / "thin.png"
    assert cv2.imwrite(str(path), rng.integers(0, 256, (10, 2), dtype=np.uint8))
    out_csv = tmp_path / "t.csv"
    status, out, err = run(["golden", str(path), "--levels", "10", "--csv", str(out_csv)], capsys)
    assert (status, err) == (0, "")
    levels = per_level(out.strip())
    assert len(levels) == 10 and levels[-1][0] == 0 and all(n == 0 for *_, n in levels)
    assert out_csv.read_text() == "level,x,y,score\n"


@pytest.mark.parametrize("orb", [False, True], ids=["fast", "orb"])
def test_levels_png(textured_image, tmp_path: Path, capsys, orb: bool):
    """The keypoints of every level on the original image: circles of their size around
    x * scale_k, y * scale_k; the picture is the grey input away from them."""
    path, img = textured_image
    out_png = tmp_path / "l.png"
    argv = ["golden", str(path), "-t", "10", "--levels", "3", "--png", str(out_png)]
    status, _, err = run([*argv, *(["--orb"] if orb else [])], capsys)
    assert (status, err) == (0, "")
    png = cv2.imread(str(out_png), cv2.IMREAD_UNCHANGED)
    assert png.shape == (120, 160, 3)
    grey = np.repeat(img[:, :, None], 3, axis=2)
    changed = (png != grey).any(axis=2)
    assert changed.any()

    untouched = np.ones(img.shape, bool)
    strongest = (-1, None)
    for k, result in enumerate(expected_levels(img, 10, orb, None)):
        records = result.records if orb else result
        assert len(records) > 0, k
        scale = pyramid.level_scale(k)
        radius = float(np.float32(31 if orb else 7) * scale) / 2
        for x, y, score in records.tolist():
            cx, cy = float(np.float32(x) * scale), float(np.float32(y) * scale)
            box = (
                slice(max(int(cy - radius) - 1, 0), int(cy + radius) + 2),
                slice(max(int(cx - radius) - 1, 0), int(cx + radius) + 2),
            )
            untouched[box] = False
            if score > strongest[0]:
                strongest = (score, box)
    assert untouched.any() and not changed[untouched].any()
    # The strongest keypoint (drawn last) has its circle in the highest score's colour.
    assert (png[strongest[1]] == overlay.HIGH_BGR).all(axis=2).any()


def test_keypoint_circles_round_as_opencv():
    """Centres and radii in 1/16 pixel: cvRound(pt * 16) and cvRound(size / 2 * 16)."""
    scale = pyramid.level_scale(2)  # 1.44
    cx, cy, r = overlay.keypoint_circles(scale, np.array([[10, 31, 5]]), oriented=True)
    assert cx[0] == round(float(np.float32(10) * scale) * 16)
    assert cy[0] == round(float(np.float32(31) * scale) * 16) == 714  # 44.64 pixels
    assert r[0] == round(float(np.float32(31) * scale) / 2 * 16)
    _, _, r = overlay.keypoint_circles(np.float32(1), np.array([[0, 0, 1]]), oriented=False)
    assert r[0] == 56  # 3.5 pixels


# ---- pyramid ------------------------------------------------------------------------------


@pytest.fixture
def odd_image(tmp_path: Path, rng: np.random.Generator) -> tuple[Path, np.ndarray]:
    img = rng.integers(0, 256, (101, 157), dtype=np.uint8)
    path = tmp_path / "odd.png"
    assert cv2.imwrite(str(path), img)
    return path, img


@pytest.mark.parametrize("existing", [False, True], ids=["created", "existing"])
def test_pyramid_writes_the_levels(odd_image, tmp_path: Path, capsys, existing: bool):
    path, img = odd_image
    out = tmp_path / "levels"
    if existing:
        out.mkdir()
        (out / "level_1.png").write_bytes(b"old")
        (out / "notes.txt").write_text("mine\n")
    status, stdout, err = run(["pyramid", str(path), "--levels", "5", "--out", str(out)], capsys)
    assert (status, err) == (0, "")
    want = pyramid.pyramid(img, 5)
    chained = [img]
    for k in range(1, 5):
        size = pyramid.level_size(157, 101, k)
        chained.append(cv2.resize(chained[-1], size, interpolation=cv2.INTER_LINEAR_EXACT))
    lines = stdout.splitlines()
    assert len(lines) == 5
    for k in range(5):
        level = cv2.imread(str(out / f"level_{k}.png"), cv2.IMREAD_UNCHANGED)
        assert level.dtype == np.uint8 and level.ndim == 2
        assert np.array_equal(level, want[k]) and np.array_equal(level, chained[k]), k
        h, w = level.shape
        assert lines[k] == f"level {k}: {w}x{h} -> {out / f'level_{k}.png'}"
    assert np.array_equal(want[0], img)
    names = [f"level_{k}.png" for k in range(5)]
    assert sorted(os.listdir(out)) == sorted(names + (["notes.txt"] if existing else []))


def test_pyramid_scale_factor(odd_image, tmp_path: Path, capsys):
    path, img = odd_image
    out = tmp_path / "p"
    argv = ["pyramid", str(path), "--levels", "3", "--scale-factor", "2", "--out", str(out)]
    status, _, err = run(argv, capsys)
    assert (status, err) == (0, "")
    levels = pyramid.pyramid(img, 3, 2.0)
    assert [level.shape for level in levels] == [(101, 157), (50, 78), (25, 39)]
    for k, want in enumerate(levels):
        got = cv2.imread(str(out / f"level_{k}.png"), cv2.IMREAD_UNCHANGED)
        assert np.array_equal(got, want)


def test_pyramid_failure_leaves_nothing(odd_image, tmp_path: Path, capsys, monkeypatch):
    path, _ = odd_image
    real = pyramid_command.png_bytes
    calls = []

    def failing(level):
        calls.append(level.shape)
        if len(calls) == 3:
            raise OSError(28, "No space left on device")
        return real(level)

    monkeypatch.setattr(pyramid_command, "png_bytes", failing)
    created, existing = tmp_path / "new", tmp_path / "old"
    existing.mkdir()
    for out in (created, existing):
        status, stdout, err = run(
            ["pyramid", str(path), "--levels", "4", "--out", str(out)], capsys
        )
        assert_usage_error(status, stdout, err)
        assert "No space left on device" in err
        calls.clear()
    assert not created.exists()
    assert os.listdir(existing) == []


# ---- errors -------------------------------------------------------------------------------

BAD_LEVELS = {
    "levels_0": ["--levels", "0"],
    "levels_33": ["--levels", "33"],
    "levels_word": ["--levels", "abc"],
    "levels_fraction": ["--levels", "1.5"],
    "levels_empty": ["--levels", ""],
    "scale_1": ["--levels", "3", "--scale-factor", "1"],
    "scale_below_1": ["--levels", "3", "--scale-factor", "0.9"],
    "scale_nan": ["--levels", "3", "--scale-factor", "nan"],
    "scale_inf": ["--levels", "3", "--scale-factor", "inf"],
    "scale_word": ["--levels", "3", "--scale-factor", "abc"],
    "scale_float32_1": ["--levels", "3", "--scale-factor", "1.00000001"],
}

GOLDEN_ONLY = {
    "scale_without_levels": ["--scale-factor", "1.2"],
    "min_area": ["--levels", "3", "--nms", "region8", "--min-area", "2"],
    "min_area_3x3": ["--levels", "3", "--min-area", "2"],
    "half_budget": ["--levels", "3", "--cell", "32"],
}


@pytest.mark.parametrize("name", sorted(BAD_LEVELS | GOLDEN_ONLY))
def test_golden_bad_levels(textured_image, tmp_path: Path, capsys, name: str):
    path, _ = textured_image
    out_csv, out_png = tmp_path / "c.csv", tmp_path / "c.png"
    bad = (BAD_LEVELS | GOLDEN_ONLY)[name]
    argv = ["golden", str(path), "--csv", str(out_csv), "--png", str(out_png), *bad]
    status, out, err = run(argv, capsys)
    assert_usage_error(status, out, err)
    assert sorted(os.listdir(tmp_path)) == ["texture.png"]
    if name.startswith("min_area"):
        assert err == "fastnms: error: --min-area does not go with --levels\n"


@pytest.mark.parametrize("name", sorted(BAD_LEVELS))
def test_pyramid_bad_values(odd_image, tmp_path: Path, capsys, name: str):
    path, _ = odd_image
    bad = ["--levels", "3", *BAD_LEVELS[name]]  # the last --levels is the one used
    status, out, err = run(["pyramid", str(path), "--out", str(tmp_path / "p"), *bad], capsys)
    assert_usage_error(status, out, err)
    assert sorted(os.listdir(tmp_path)) == ["odd.png"]


@pytest.mark.parametrize(
    "case", ["no_out", "no_levels", "out_is_file", "parent_missing", "empty_out", "level_is_dir"]
)
def test_pyramid_bad_out(odd_image, tmp_path: Path, capsys, case: str):
    path, _ = odd_image
    argv = ["pyramid", str(path), "--levels", "3"]
    out = tmp_path / "p"
    if case == "no_out":
        pass
    elif case == "no_levels":
        argv = ["pyramid", str(path), "--out", str(out)]
    elif case == "out_is_file":
        out.write_text("a file\n")
        argv += ["--out", str(out)]
    elif case == "parent_missing":
        argv += ["--out", str(tmp_path / "nope" / "p")]
    elif case == "empty_out":
        argv += ["--out", ""]
    else:
        (out / "level_2.png").mkdir(parents=True)
        argv += ["--out", str(out)]
    before = sorted(os.listdir(tmp_path))
    assert_usage_error(*run(argv, capsys))
    assert sorted(os.listdir(tmp_path)) == before
    if case == "out_is_file":
        assert out.read_text() == "a file\n"
    if case == "level_is_dir":
        assert os.listdir(out) == ["level_2.png"]


def test_pyramid_refuses_levels_of_no_pixels(tmp_path: Path, rng, capsys):
    path = tmp_path / "thin.png"
    assert cv2.imwrite(str(path), rng.integers(0, 256, (10, 2), dtype=np.uint8))
    out = tmp_path / "p"
    status, stdout, err = run(["pyramid", str(path), "--levels", "10", "--out", str(out)], capsys)
    assert_usage_error(status, stdout, err)
    assert "level 8 of a 2x10 image" in err and not out.exists()
    assert run(["pyramid", str(path), "--levels", "8", "--out", str(out)], capsys)[0] == 0
    assert len(os.listdir(out)) == 8


@pytest.mark.parametrize("command", ["golden", "pyramid"])
@pytest.mark.parametrize("kind", ["missing", "text", "directory"])
def test_unreadable_image(tmp_path: Path, capfd, command: str, kind: str):
    """capfd, not capsys: OpenCV's decoders would log to file descriptor 2 directly."""
    path = tmp_path / "x.png"
    if kind == "text":
        path.write_text("hello\n")
    elif kind == "directory":
        path.mkdir()
    if command == "golden":
        argv = ["golden", str(path), "--levels", "3", "--csv", str(tmp_path / "c.csv")]
    else:
        argv = ["pyramid", str(path), "--levels", "3", "--out", str(tmp_path / "p")]
    before = sorted(os.listdir(tmp_path))
    status, out, err = run(argv, capfd)
    assert_usage_error(status, out, err)
    assert str(path) in err
    assert sorted(os.listdir(tmp_path)) == before


def test_help_mentions_levels(capsys):
    for command in ("golden", "pyramid"):
        with pytest.raises(SystemExit) as info:
            cli.main([command, "--help"])
        assert info.value.code == 0
        text = " ".join(capsys.readouterr().out.split())
        assert "--levels N" in text and "--scale-factor F" in text and "1..32" in text
    assert "--out DIR" in text and "--rtl" in text
    with pytest.raises(SystemExit):
        cli.main(["--help"])
    assert "pyramid" in capsys.readouterr().out


def test_pyramid_rtl_equals_the_golden_model(tmp_path: Path, capsys):
    """--rtl: cv2.ORB's 8 levels of a 1920x1080 photograph from the simulated chain of
    resizers (sim/pyramid.py, built once): every level equal to the golden model's, the
    input never held, one clock per pixel and the latency."""
    from fastnms.golden.image import load_grey
    from fastnms.testing.images import cover, real_images

    img = cover(load_grey(real_images()[0]), 1920, 1080)
    path = tmp_path / "photo.png"
    assert cv2.imwrite(str(path), img)
    out = tmp_path / "levels"
    status, stdout, err = run(
        ["pyramid", str(path), "--levels", "8", "--out", str(out), "--rtl"], capsys
    )
    assert (status, err) == (0, ""), err
    note = stdout.splitlines()[-1]
    assert note.endswith("; equal to the golden model's"), note
    clocks = int(re.search(r"in (\d+) clocks", note).group(1))
    assert "input held 0 clocks" in note
    # W x H clocks of input, then the last levels' pipelines (14 clocks each at most).
    assert 1920 * 1080 <= clocks <= 1920 * 1080 + 7 * 14 + 20, clocks
    for k, level in enumerate(pyramid.pyramid(img, 8)):
        assert np.array_equal(cv2.imread(str(out / f"level_{k}.png"), cv2.IMREAD_UNCHANGED), level)


def test_pyramid_rtl_refuses_tiny_levels(tmp_path: Path, rng, capsys):
    path = tmp_path / "small.png"  # levels 3x3, 2x2, 2x2, 2x2, 1x1, ...
    assert cv2.imwrite(str(path), rng.integers(0, 256, (3, 3), dtype=np.uint8))
    argv = ["pyramid", str(path), "--levels", "8", "--out", str(tmp_path / "p"), "--rtl"]
    status, stdout, err = run(argv, capsys)
    assert_usage_error(status, stdout, err)
    assert "shrinks sources of at least 2x2 pixels" in err
