"""cv2.ORB's image pyramid in the golden model (golden/pyramid.py): the integer model of
INTER_LINEAR_EXACT against cv2.resize itself, its double steps against the CPU's IEEE
double arithmetic, the level sizes, and the keypoints of every level against cv2.ORB's
(pt, size, octave, response and angle bit for bit; descriptors with cv2.ORB's float blur).

Seeds: FASTNMS_SEED (default 2026) for the random sizes and noise, logged on failure."""

from __future__ import annotations

import math
import os
import shutil
import subprocess
from pathlib import Path

import cv2
import numpy as np
import pytest
from fastnms.golden import orb, pyramid
from fastnms.golden.budget import cell_budget
from fastnms.golden.image import load_grey
from fastnms.golden.model import detect
from fastnms.testing.images import blurred_noise, cover, noise, real_images

SEED = int(os.environ.get("FASTNMS_SEED", "2026"))
# Camera sizes of the issue: 1080p, 720p, KITTI, EuRoC, TUM.
CAMERAS = [(1920, 1080), (1280, 720), (1241, 376), (752, 480), (640, 480)]
THRESHOLDS = (10, 20, 40)


def cv2_exact(img: np.ndarray, width: int, height: int) -> np.ndarray:
    return cv2.resize(img, (width, height), interpolation=cv2.INTER_LINEAR_EXACT)


def photograph(width: int, height: int, index: int = 0) -> np.ndarray:
    images = real_images()
    return cover(load_grey(images[index % len(images)]), width, height)


# ---- the double steps -------------------------------------------------------------------


def test_round_double_equals_ieee_division():
    """round_double(a, b) is the CPU's correctly rounded a / b (Python floats are IEEE
    doubles), on random and on tie-prone operands."""
    rng = np.random.default_rng(SEED)
    pairs = [(int(a), int(b)) for a, b in rng.integers(1, 1 << 40, (20000, 2))]
    pairs += [(d, s) for s in range(1, 300) for d in range(1, 300)]
    pairs += [((1 << 53) + 1, 2), ((1 << 53) + 3, 2), ((1 << 54) + 2, 4), (-7, 3)]
    for a, b in pairs:
        m, e = pyramid.round_double(a, b)
        assert math.ldexp(m, e) == a / b, (a, b, SEED)


def float_taps(src: int, dst: int) -> tuple[list[int], list[int]]:
    """axis_taps written with the CPU's doubles, as OpenCV's getCoeffs reads."""
    scale = 1.0 / (dst / src)
    offsets, weights = [], []
    for i in range(dst):
        f = scale * (i + 0.5) - 0.5  # Python: two IEEE double roundings, no fused step
        o = math.floor(f)
        if o < 0 or src == 1:
            offsets.append(0)
            weights.append(256)
        elif o >= src - 1:
            offsets.append(src - 1)
            weights.append(256)
        else:
            offsets.append(o)
            weights.append(256 - round((f - o) * 256))  # round: half to even
    return offsets, weights


def test_axis_taps_equal_double_arithmetic():
    """The integer positions and weights equal the same steps in IEEE double on every
    pyramid axis of the cameras and on random size pairs (shrinking and enlarging)."""
    rng = np.random.default_rng(SEED)
    axes = set()
    for w, h in CAMERAS:
        for k in range(1, 8):
            axes.add((pyramid.level_size(w, h, k - 1)[0], pyramid.level_size(w, h, k)[0]))
            axes.add((pyramid.level_size(w, h, k - 1)[1], pyramid.level_size(w, h, k)[1]))
    axes |= {(int(s), int(rng.integers(1, s + 1))) for s in rng.integers(1, 3841, 200)}
    axes |= {(int(s), int(d)) for s, d in rng.integers(1, 300, (50, 2))}
    for src, dst in sorted(axes):
        offsets, weights = pyramid.axis_taps(src, dst)
        assert (offsets.tolist(), weights.tolist()) == float_taps(src, dst), (src, dst, SEED)


TAPS_CHECK = Path(__file__).with_name("resize_taps_check.c")


def run_taps_check(tmp_path: Path, max_src: int, setup_max: int) -> str:
    gcc = shutil.which("gcc")
    if gcc is None:
        pytest.skip("gcc not found: resize_taps_check.c cannot be built")
    exe = tmp_path / "resize_taps_check"
    subprocess.run(
        [gcc, "-O2", "-ffp-contract=off", "-o", str(exe), str(TAPS_CHECK), "-lm"], check=True
    )
    done = subprocess.run([str(exe), str(max_src), str(setup_max)], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    return done.stdout


def test_rtl_tap_algorithm_equals_double_steps(tmp_path):
    """The RTL's steps (integer divisions for the scale; P = m (2i + 1) rounded to 53 bits
    at its leading one) equal OpenCV's double steps: the scale of every shrink pair up to
    3840, the taps of every pair up to 300 (resize_taps_check.c, built with gcc)."""
    out = run_taps_check(tmp_path, 300, 3840)
    assert "scale_differ 0" in out and "taps_differ 0" in out, out


@pytest.mark.slow
def test_rtl_tap_algorithm_equals_double_steps_wider(tmp_path):
    """The taps of every shrink pair up to 1200 (about a minute); every pair up to 3840
    (9 444 558 080 taps, about 13 minutes) with FASTNMS_TAPS_MAX=3840."""
    top = int(os.environ.get("FASTNMS_TAPS_MAX", "1200"))
    out = run_taps_check(tmp_path, top, 3840)
    assert "scale_differ 0" in out and "taps_differ 0" in out, out


# ---- the resize against cv2.resize ------------------------------------------------------


def test_level_sizes_of_1080p():
    """The issue's sizes (measured with cv2.ORB): 1920x1080 and its 7 levels."""
    sizes = [pyramid.level_size(1920, 1080, k) for k in range(8)]
    assert sizes == [
        (1920, 1080),
        (1600, 900),
        (1333, 750),
        (1111, 625),
        (926, 521),
        (772, 434),
        (643, 362),
        (536, 301),
    ]


@pytest.mark.parametrize("camera", CAMERAS, ids=lambda c: f"{c[0]}x{c[1]}")
def test_pyramid_transitions_equal_cv2_resize(camera):
    """Every step of the 8-level pyramid of a photograph and of noise at the camera's size
    equals cv2.resize with INTER_LINEAR_EXACT (from the previous level, as cv2.ORB)."""
    w, h = camera
    rng = np.random.default_rng(SEED)
    for img in (photograph(w, h), noise(rng, w, h)):
        levels = pyramid.pyramid(img, 8)
        assert len(levels) == 8
        for k in range(1, 8):
            lh, lw = levels[k].shape
            assert (lw, lh) == pyramid.level_size(w, h, k)
            assert np.array_equal(levels[k], cv2_exact(levels[k - 1], lw, lh)), (camera, k)


def random_sizes(rng: np.random.Generator, count: int, largest: tuple[int, int]):
    for _ in range(count):
        w, h = (int(rng.integers(16, largest[0] + 1)), int(rng.integers(16, largest[1] + 1)))
        yield w, h, int(rng.integers(1, w + 1)), int(rng.integers(1, h + 1))


def test_random_sizes_equal_cv2_resize():
    """Random shrinks from 16x16 up to 640x480, noise and photographs, and enlargements
    (OpenCV's rule also enlarges; the RTL only shrinks)."""
    rng = np.random.default_rng(SEED)
    for i, (w, h, dw, dh) in enumerate(random_sizes(rng, 60, (640, 480))):
        img = noise(rng, w, h) if i % 2 else photograph(w, h, i)
        assert np.array_equal(pyramid.resize_linear_exact(img, dw, dh), cv2_exact(img, dw, dh)), (
            w,
            h,
            dw,
            dh,
            SEED,
        )
    for w, h, dw, dh in [(1, 1, 5, 3), (7, 3, 40, 1), (16, 16, 17, 33), (3, 50, 1, 1)]:
        img = noise(rng, w, h)
        assert np.array_equal(pyramid.resize_linear_exact(img, dw, dh), cv2_exact(img, dw, dh))


@pytest.mark.slow
def test_random_large_sizes_equal_cv2_resize():
    """Random shrinks up to 3840x2160 (and a 4K frame's whole pyramid)."""
    rng = np.random.default_rng(SEED + 1)
    for i, (w, h, dw, dh) in enumerate(random_sizes(rng, 40, (3840, 2160))):
        img = blurred_noise(rng, w, h) if i % 2 else photograph(w, h, i)
        assert np.array_equal(pyramid.resize_linear_exact(img, dw, dh), cv2_exact(img, dw, dh)), (
            w,
            h,
            dw,
            dh,
            SEED + 1,
        )
    levels = pyramid.pyramid(photograph(3840, 2160), 8)
    for k in range(1, 8):
        lh, lw = levels[k].shape
        assert np.array_equal(levels[k], cv2_exact(levels[k - 1], lw, lh))


def test_small_images_end_the_pyramid():
    """A 16x16 image: its levels shrink to 6x6 by level 5; 2x2 at 1.2 still has 8 levels
    of at least one pixel; a 1x1 image stays 1x1."""
    rng = np.random.default_rng(SEED)
    levels = pyramid.pyramid(noise(rng, 16, 16), 8)
    assert [lv.shape for lv in levels] == [
        (16, 16),
        (13, 13),
        (11, 11),
        (9, 9),
        (8, 8),
        (6, 6),
        (5, 5),
        (4, 4),
    ]
    assert [lv.shape for lv in pyramid.pyramid(noise(rng, 1, 1), 3)] == [(1, 1)] * 3
    # Scale factor 4: 5 -> 1 -> 0 (the list ends where a level would be empty).
    assert [lv.shape for lv in pyramid.pyramid(noise(rng, 5, 5), 4, 4.0)] == [(5, 5), (1, 1)]


@pytest.mark.parametrize(
    "levels, factor, message",
    [
        (0, 1.2, "levels must be an integer in 1..32, got 0"),
        (33, 1.2, "levels must be an integer in 1..32, got 33"),
        (True, 1.2, "levels must be an integer"),
        (2.0, 1.2, "levels must be an integer"),
        (8, 1.0, "scale factor must be a number above 1, got 1.0"),
        (8, 0.5, "scale factor must be a number above 1"),
        (8, float("nan"), "scale factor must be a number above 1"),
        (8, float("inf"), "scale factor must be a number above 1"),
        (8, "1.2", "scale factor must be a number above 1"),
    ],
)
def test_bad_levels_are_refused(levels, factor, message):
    img = np.zeros((64, 64), np.uint8)
    with pytest.raises(ValueError, match=message):
        pyramid.pyramid(img, levels, factor)
    with pytest.raises(ValueError, match=message):
        orb.detect_and_compute(img, 20, nlevels=levels, scale_factor=factor)


# ---- the keypoints of every level against cv2.ORB ---------------------------------------


def cv2_orb_levels(img: np.ndarray, threshold: int, nlevels: int = 8):
    detector = cv2.ORB_create(
        nfeatures=10**7,
        scaleFactor=1.2,
        nlevels=nlevels,
        edgeThreshold=orb.EDGE,
        firstLevel=0,
        WTA_K=2,
        scoreType=cv2.ORB_FAST_SCORE,
        patchSize=orb.PATCH_SIZE,
        fastThreshold=threshold,
    )
    return detector.detectAndCompute(img, None)


def fields(keypoints) -> list[tuple]:
    """Each keypoint's octave, pt, size, angle as float32 bits, and response; sorted."""

    def bits(v: float) -> int:
        return int(np.float32(v).view(np.uint32))

    rows = [
        (k.octave, bits(k.pt[1]), bits(k.pt[0]), bits(k.size), bits(k.angle), k.response)
        for k in keypoints
    ]
    return rows


def assert_levels_equal_cv2_orb(img: np.ndarray, threshold: int, context: str) -> int:
    kc, dc = cv2_orb_levels(img, threshold)
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(orb, "gaussian_blur", orb.float_blur)  # cv2.ORB's own blur
        kg, dg = orb.detect_and_compute(img, threshold, nlevels=8)
    a, b = fields(kc), fields(kg)
    order_c, order_g = np.argsort([str(r) for r in a]), np.argsort([str(r) for r in b])
    assert [a[i] for i in order_c] == [b[i] for i in order_g], context
    assert np.array_equal(dc[order_c], dg[order_g]), context
    assert len({k.octave for k in kg}) > 1, context
    return len(kg)


@pytest.mark.parametrize("threshold", THRESHOLDS)
def test_every_level_equals_cv2_orb(threshold):
    """Keypoints of all 8 levels (pt, size, octave, response, angle bits) and their
    descriptors (with cv2.ORB's float blur) equal cv2.ORB's, on a photograph at 600x400
    and on textured noise at 512x512."""
    rng = np.random.default_rng(SEED)
    for img, name in (
        (photograph(600, 400, 1), "photograph"),
        (blurred_noise(rng, 512, 512), "noise"),
    ):
        assert assert_levels_equal_cv2_orb(img, threshold, f"{name} t={threshold}") > 0


@pytest.mark.slow
@pytest.mark.parametrize("camera", CAMERAS, ids=lambda c: f"{c[0]}x{c[1]}")
def test_every_level_equals_cv2_orb_on_photographs(camera):
    w, h = camera
    for i in range(3):
        for t in THRESHOLDS:
            assert_levels_equal_cv2_orb(photograph(w, h, i), t, f"{camera} image {i} t={t}")


def test_one_level_is_todays_model():
    """nlevels 1 gives the single-level model's keypoints and descriptors."""
    img = photograph(320, 240, 2)
    f = orb.orb_features(img, 20)
    kps, des = orb.detect_and_compute(img, 20, nlevels=1)
    assert [(k.pt, k.response, k.size, k.octave) for k in kps] == [
        ((float(x), float(y)), float(s), 31.0, 0) for x, y, s in f.records.tolist()
    ]
    assert np.array_equal(des, f.descriptors)


def test_budget_applies_per_level():
    """With a budget each level keeps cell_budget of its own keypoints, cells in the
    level's pixels; without ORB every level's NMS keypoints come with size 7 * scale."""
    img = photograph(640, 480, 3)
    kps, des = orb.detect_and_compute(img, 10, nlevels=4, cell=16, per_cell=2)
    levels = pyramid.pyramid(img, 4)
    for k, level in enumerate(levels):
        scale = pyramid.level_scale(k)
        expected = orb.orb_features(level, 10, cell=16, per_cell=2).records
        got = [kp for kp in kps if kp.octave == k]
        assert [(kp.pt, kp.response) for kp in got] == [
            ((float(np.float32(x) * scale), float(np.float32(y) * scale)), float(s))
            for x, y, s in expected.tolist()
        ]
    assert des.shape == (len(kps), 32)
    plain, none = orb.detect_and_compute(img, 10, orb=False, nlevels=3, cell=32, per_cell=3)
    assert none is None
    for k, level in enumerate(pyramid.pyramid(img, 3)):
        got = [kp for kp in plain if kp.octave == k]
        expected = cell_budget(detect(level, 10, "opencv", "3x3"), 32, 3)
        assert len(got) == len(expected) > 0
        assert {kp.size for kp in got} == {float(np.float32(7) * pyramid.level_scale(k))}


def test_levels_below_63_pixels_have_no_keypoints():
    """A 100x90 image: levels 0-2 (100x90, 83x75, 69x62 ...) then none once a side is at
    most 62 pixels; cv2.ORB agrees."""
    rng = np.random.default_rng(SEED)
    img = blurred_noise(rng, 100, 90)
    kps, des = orb.detect_and_compute(img, 5, nlevels=8)
    sides = [pyramid.level_size(100, 90, k) for k in range(8)]
    octaves = {k.octave for k in kps}
    assert octaves and all(min(sides[o]) > 2 * orb.EDGE for o in octaves)
    assert any(min(s) <= 2 * orb.EDGE for s in sides)
    kc, _ = cv2_orb_levels(img, 5)
    assert sorted(fields(kc)) == sorted(fields(kps))
