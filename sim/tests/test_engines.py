"""The two simulation engines of fastnms_axi (sim/run.py) against each other and
against the golden model: the same records and the same clock counts, frame by
frame, for every score/NMS variant, with and without input idles and output
stalls; the fast engine's timing options and its independence from power-up
values; whole photographs at 1920x1080 through the top.

Every build is the command line's (MAX 1920x1080), so the tests share it with
`fastnms sim` and the demo."""

from __future__ import annotations

import numpy as np
import pytest
from fastnms.golden.budget import hardware_order
from fastnms.golden.image import load_grey
from fastnms.golden.model import NMS_MODES, SCORES, detect
from fastnms.sim import regs
from fastnms.sim.run import SimResult, budget_in_effect, check_size, generics_for, run_rtl
from fastnms.sim.timing import Pattern, Timing
from fastnms.testing import images as testimages

VARIANTS = [(s, n) for s in SCORES for n in NMS_MODES]
IDS = [f"{s}-{n}" for s, n in VARIANTS]
QUICK_PAIRS = {("opencv", "3x3"), ("sad", "region4")}
# One photograph per NMS in make test (the region NMS with the sad score, the cheaper).
QUICK_PHOTOS = {("opencv", "3x3"), ("sad", "none"), ("sad", "region4"), ("sad", "region8")}


def mixed_frames(rng: np.random.Generator) -> list[tuple[np.ndarray, int]]:
    """Frames of different sizes and kinds, back to back: a photograph crop, blurred
    noise at a low threshold (dense corners and big regions), a small checkerboard."""
    return [
        (testimages.crop(testimages.real_images()[0], 72, 40), 15),
        (testimages.blurred_noise(rng, 33, 20), 4),
        (testimages.checkerboard(rng, 24, 16), 20),
    ]


def assert_golden(
    result: SimResult, frames, score: str, nms: str, seed: int, min_area: int = 0
) -> None:
    """Each frame's records and their AREA equal the golden model's (MIN_AREA `min_area`,
    which only the region NMS applies)."""
    assert any(len(f.records) for f in result.frames), "no corner at all: a weak test"
    if not nms.startswith("region"):
        min_area = 0
    for i, ((img, t), got) in enumerate(zip(frames, result.frames, strict=True)):
        want = detect(img, t, score, nms, min_area, with_area=True)
        assert np.array_equal(got.records, want[:, :3]), (
            f"frame {i}: {len(got.records)} records, golden {len(want)} (seed {seed})"
        )
        assert np.array_equal(got.areas, want[:, 3]), f"frame {i}: areas (seed {seed})"


def assert_same_run(a: SimResult, b: SimResult) -> None:
    assert a.cycles == b.cycles and a.input_stalls == b.input_stalls
    for fa, fb in zip(a.frames, b.frames, strict=True):
        assert np.array_equal(fa.records, fb.records)
        assert np.array_equal(fa.areas, fb.areas)
        assert (fa.cycles, fa.input_stalls) == (fb.cycles, fb.input_stalls)
        # Every record beat on the same clock (each engine counts from its own origin).
        assert np.array_equal(
            fa.word_clocks - a.frames[0].first_pixel, fb.word_clocks - b.frames[0].first_pixel
        )


def emitted(words: np.ndarray) -> list[tuple[int, int, int]]:
    """A frame's records in the order the IP emitted them (EMPTY left out)."""
    out = []
    for w in (int(v) for v in words):
        if not regs.REC_EMPTY.get(w):
            out.append((regs.REC_X.get(w), regs.REC_Y.get(w), regs.REC_SCORE.get(w)))
    return out


# PPC 1 under slow: make test has the budget at PPC 1 through the top (cocotb, LIVE noise
# at full width) and through both engines (cli/tests/test_sim_cli.py).
@pytest.mark.parametrize("ppc", [pytest.param(1, marks=pytest.mark.slow), 4])
def test_budget_at_full_hd(ppc: int, rng, seed):
    """The keypoint budget in the top at 1920x1080 (MAX_PER_CELL 15, opencv + 3x3),
    PPC 1 and 4: a photograph at t = 20 and noise at t = 0 at full width (the heaviest
    record stream), at CELL 16 K 15, CELL 64 K 4 and CELL 256 K 1, each frame the
    golden model's budget in the block's order (a cell row at a time, cells left to
    right, best first); the input never waits, and frames go in W x H / PPC clocks
    apart. Among them the content that made the budget wait before the NMS sent row-end
    beats: 16 lines of noise (a full cell row at CELL 16), then flat lines whose only
    corner is a bright dot on line 31, the next cell row's last, then noise again (a
    record every other pixel from line 32 on)."""
    photo = testimages.cover(testimages.crop(testimages.real_images()[1], 480, 270), 1920, 1080)
    sparse_then_dense = np.full((64, 1920), 128, dtype=np.uint8)
    sparse_then_dense[:13] = testimages.noise(rng, 1920, 13)
    sparse_then_dense[35:] = testimages.noise(rng, 1920, 29)
    sparse_then_dense[31, 1900] = 255
    corners = detect(sparse_then_dense, 0)
    assert [tuple(r[:2]) for r in corners if 16 <= r[1] < 32] == [(1900, 31)]
    frames = [
        (photo, 20),
        (testimages.noise(rng, 1920, 64), 0),
        (sparse_then_dense, 0),
        (photo, 10),
    ]
    generics = generics_for("opencv", "3x3", ppc, budget=True)
    for budget in [(16, 15), (64, 4), (256, 1)]:
        result = run_rtl(frames, "opencv", "3x3", generics=generics, budget=budget)
        for i, ((img, t), f) in enumerate(zip(frames, result.frames, strict=True)):
            want = [tuple(r) for r in hardware_order(detect(img, t), *budget).tolist()]
            assert emitted(f.words) == want, f"budget {budget}, frame {i} (seed {seed})"
            assert f.input_stalls == 0, f"budget {budget}, frame {i}: {f.input_stalls} stalls"
        starts = [f.first_pixel for f in result.frames]
        sizes = [img.size // ppc for img, _ in frames]
        assert np.diff(starts).tolist() == sizes[:-1], f"budget {budget}: input waited"
        print(f"PPC {ppc}, budget {budget}: {[len(f.records) for f in result.frames]} records")


# make test runs 3x3 and a region NMS (none and region8 through the photographs below);
# make test-full every pair.
ENGINE_PAIRS = [
    pytest.param(s, n, id=f"{s}-{n}", marks=[] if (s, n) in QUICK_PAIRS else [pytest.mark.slow])
    for s, n in VARIANTS
]


@pytest.mark.parametrize(("score", "nms"), ENGINE_PAIRS)
def test_engines_agree(score: str, nms: str, rng, seed):
    """Both engines, three frames back to back, without and then with idles and
    stalls (and MIN_AREA 3, which only the region NMS applies): identical records,
    areas and clock counts, equal to the golden model."""
    frames = mixed_frames(rng)
    busy = Timing(idle=Pattern(rate=0.25), stall=Pattern(rate=0.4), seed=seed % 1000)
    results = {}
    for name, timing, min_area in [("free", Timing(), None), ("busy", busy, 3)]:
        fast = run_rtl(frames, score, nms, timing=timing, min_area=min_area)
        assert_golden(fast, frames, score, nms, seed, min_area or 0)
        results[name] = fast
        if name == "busy":  # the cocotb engine once per variant: it is the slow one
            slow = run_rtl(frames, score, nms, engine="cocotb", timing=timing, min_area=3)
            assert_same_run(fast, slow)
    # The pauses cost clocks; at one pixel per clock a free 3x3 frame takes W x H
    # plus its fill, and no input clock is lost to idles.
    assert results["busy"].cycles > results["free"].cycles


# make test: the sad score (the opencv score at PPC 4 runs through the core and the top
# under cocotb in make test: tb/core, tb/top).
@pytest.mark.parametrize(
    "score", [pytest.param(s, marks=[] if s == "sad" else [pytest.mark.slow]) for s in SCORES]
)
def test_engines_four_pixels_per_clock(score: str, rng, seed):
    """PPC 4 (opencv/sad + 3x3, MAX 1920x1080): both engines agree with idles and
    stalls; without them every frame after the first takes its W x H / 4 beats
    in W x H / 4 clocks (the input never waits, not even for a register write),
    also a 1920x1080 photograph, with the golden model's records."""
    generics = generics_for(score, "3x3", 4)
    photo = testimages.cover(testimages.crop(testimages.real_images()[1], 480, 270), 1920, 1080)
    # Each frame at least as wide as the one before (a narrower frame waits
    # for the end of the wider one's last rows, docs/fastnms_window.md).
    frames = [
        (testimages.checkerboard(rng, 24, 16), 20),
        (testimages.blurred_noise(rng, 32, 20), 4),
        (testimages.crop(testimages.real_images()[0], 72, 40), 15),
        (photo, 20),
        (photo, 10),
    ]
    free = run_rtl(frames, score, "3x3", generics=generics)
    assert_golden(free, frames, score, "3x3", seed)
    for i, ((img, _), f) in enumerate(zip(frames, free.frames, strict=True)):
        if i:
            beats = img.size // 4
            assert f.input_stalls == 0, f"frame {i}: {f.input_stalls} input stalls"
            assert f.last_pixel - f.first_pixel + 1 == beats, f"frame {i}: not 4 px/clock"
    busy = Timing(idle=Pattern(rate=0.25), stall=Pattern(rate=0.4), seed=seed % 1000)
    small = frames[:3]
    fast = run_rtl(small, score, "3x3", timing=busy, generics=generics)
    assert_golden(fast, small, score, "3x3", seed)
    slow = run_rtl(small, score, "3x3", engine="cocotb", timing=busy, generics=generics)
    assert_same_run(fast, slow)


def test_engines_agree_without_pauses(rng, seed):
    """The cocotb engine without idles or stalls, on the variants whose timing
    differs most (the region NMS adds its flush pass)."""
    frames = mixed_frames(rng)
    for score, nms in [("opencv", "3x3"), ("sad", "region8")]:
        fast = run_rtl(frames, score, nms)
        slow = run_rtl(frames, score, nms, engine="cocotb")
        assert_same_run(fast, slow)
        assert_golden(fast, frames, score, nms, seed)


def test_power_up_values_do_not_matter(rng):
    """The netlist's registers and memories start from random values (Verilator's
    --x-initial unique, three seeds): same records and clock counts each time."""
    frames = mixed_frames(rng)
    for score, nms in [("opencv", "3x3"), ("sad", "region4")]:
        runs = [run_rtl(frames, score, nms, power_up_seed=s) for s in (1, 2, 3)]
        for other in runs[1:]:
            assert_same_run(runs[0], other)


def test_blanking_adds_exactly_its_clocks(rng):
    """hblank N after each line and vblank V after each frame: the 3x3 top takes
    one pixel per clock, so a frame's cycles grow by N per line boundary and the
    next frame starts V clocks later."""
    frames = [(testimages.blurred_noise(rng, 40, 30), 5)] * 2
    base = run_rtl(frames, "opencv", "3x3")
    blank = run_rtl(frames, "opencv", "3x3", timing=Timing(hblank=7, vblank=100))
    for f0, f1 in zip(base.frames, blank.frames, strict=True):
        assert np.array_equal(f0.records, f1.records)
        assert f1.cycles == f0.cycles + 7 * (30 - 1)
    # The few stall clocks at each start of frame stay: blanking does not hide them.
    assert blank.input_stalls == base.input_stalls
    assert blank.cycles - base.cycles == 2 * 7 * (30 - 1) + 100


def test_bit_patterns_are_periodic():
    """A stall pattern of 0/1 repeats exactly: stalling every other clock halves
    the output rate but not the input rate of a 3x3 frame with few corners."""
    img = testimages.crop(testimages.real_images()[0], 64, 32)
    free = run_rtl([(img, 30)], "opencv", "3x3")
    stalled = run_rtl([(img, 30)], "opencv", "3x3", timing=Timing(stall=Pattern(bits="01")))
    assert np.array_equal(free.records, stalled.records)
    assert stalled.input_stalls == free.input_stalls


PHOTO_PAIRS = [
    pytest.param(s, n, id=f"{s}-{n}", marks=[] if (s, n) in QUICK_PHOTOS else [pytest.mark.slow])
    for s, n in VARIANTS
]


@pytest.mark.parametrize(("score", "nms"), PHOTO_PAIRS)
def test_photograph_1920x1080(score: str, nms: str, seed):
    """A real photograph scaled to 1920x1080 through the top, at two thresholds,
    back to back: the golden model's records; for the 3x3 and none variants,
    exactly one pixel per clock in (the first frame's start-up stalls aside)."""
    img = testimages.cover(testimages.crop(testimages.real_images()[2], 480, 270), 1920, 1080)
    frames = [(img, 20), (img, 10)]
    result = run_rtl(frames, score, nms)
    assert_golden(result, frames, score, nms, seed)
    if nms in ("3x3", "none"):
        assert result.frames[1].input_stalls == result.frames[0].input_stalls


@pytest.mark.slow
@pytest.mark.parametrize(("score", "nms"), VARIANTS, ids=IDS)
def test_every_photograph_through_the_top(score: str, nms: str, seed):
    """Every real photograph (../shared/images, else scikit-image's), at its own
    size, at thresholds 0, 10, 20 and 40, back to back through the top: the
    golden model's records, frame by frame."""
    frames = [
        (load_grey(path), t)
        for path in testimages.real_images()
        for t in (0, 10, 20, 40)
        if check_size(load_grey(path)) is None
    ]
    assert frames
    assert_golden(run_rtl(frames, score, nms), frames, score, nms, seed)


def test_build_key_follows_the_sources(tmp_path, monkeypatch):
    """The fast engine's cache key changes with any RTL file's content and with the
    generics, and with nothing else of the call: a changed RTL file means a new build."""
    from fastnms.sim import verilator

    generics = {"MAX_WIDTH": 64, "MAX_HEIGHT": 32, "SCORE": "opencv", "NMS": "3x3"}
    key = verilator.build_key(generics)
    assert key == verilator.build_key(dict(reversed(generics.items())))
    assert key != verilator.build_key({**generics, "NMS": "none"})
    sources = verilator.rtl_sources()
    edited = tmp_path / sources[-1].name
    edited.write_text(sources[-1].read_text() + "-- an edit\n")
    monkeypatch.setattr(verilator, "rtl_sources", lambda: [*sources[:-1], edited])
    assert verilator.build_key(generics) != key


def checkerboard_image(period: int, width: int, height: int) -> np.ndarray:
    yy, xx = np.mgrid[:height, :width]
    return np.where((yy // period + xx // period) % 2, 200, 40).astype(np.uint8)


def comb_image(pitch: int, width: int, height: int) -> np.ndarray:
    """Bright teeth every `pitch` columns, joined by a bright band at the bottom:
    regions that stay apart for most of the frame and merge at its end."""
    img = np.full((height, width), 40, dtype=np.uint8)
    img[:, ::pitch] = 200
    img[height - 8 :, :] = 200
    return img


def hard_frames(rng: np.random.Generator, width: int, height: int) -> list:
    """Content that makes the region NMS work hardest, at a given size."""
    frames = [
        (testimages.noise(rng, width, height), 0),
        (testimages.blurred_noise(rng, width, height), 0),
        (testimages.blurred_noise(rng, width, height), 5),
    ]
    frames += [(checkerboard_image(p, width, height), 20) for p in (1, 2, 3, 4)]
    frames += [(comb_image(p, width, height), 20) for p in (2, 3, 4)]
    return frames


REGION_VARIANTS = [(s, n) for s, n in VARIANTS if n.startswith("region")]


# make test: region8 (the larger neighbourhood); region4 too in make test-full.
@pytest.mark.parametrize(
    ("score", "nms"),
    [
        pytest.param(s, n, id=f"{s}-{n}", marks=[] if n == "region8" else [pytest.mark.slow])
        for s, n in REGION_VARIANTS
    ],
)
def test_region_nms_hard_content_full_width(score: str, nms: str, rng, seed):
    """The region NMS at full width (1920) on its hardest content, ten frames of
    1920x40 back to back (noise at t = 0, blurred noise at t = 0 and 5,
    checkerboards of periods 1 to 4, combs joined at the bottom): the golden
    model's records, and one pixel per clock whatever the content: every frame
    takes the same clocks from its first pixel to its end-of-frame beat, frames
    start W x H clocks apart (registers written between them), and the input
    never waits; with MIN_AREA 3 the same clocks."""
    frames = hard_frames(rng, 1920, 40)
    result = run_rtl(frames, score, nms)
    assert_golden(result, frames, score, nms, seed)
    assert len({f.cycles for f in result.frames}) == 1, [f.cycles for f in result.frames]
    assert np.diff([f.first_pixel for f in result.frames]).tolist() == [1920 * 40] * 9
    assert [f.input_stalls for f in result.frames] == [0] * 10
    for (_img, t), f in zip(frames, result.frames, strict=True):
        print(f"t={t}: {len(f.records)} records, {f.cycles} clocks")
    # The region filter (MIN_AREA 3) costs no clock: the same clocks per frame, frames
    # W x H clocks apart, the input never held; the golden's records at MIN_AREA 3.
    filtered = run_rtl(frames, score, nms, min_area=3)
    assert_golden(filtered, frames, score, nms, seed, min_area=3)
    assert sum(len(f.records) for f in filtered.frames) < sum(len(f.records) for f in result.frames)
    assert [f.cycles for f in filtered.frames] == [f.cycles for f in result.frames]
    assert np.diff([f.first_pixel for f in filtered.frames]).tolist() == [1920 * 40] * 9
    assert [f.input_stalls for f in filtered.frames] == [0] * 10


@pytest.mark.slow
@pytest.mark.parametrize(
    ("score", "nms"), REGION_VARIANTS, ids=[f"{s}-{n}" for s, n in REGION_VARIANTS]
)
def test_region_nms_hard_content_full_hd(score: str, nms: str, rng, seed):
    """The same content at 1920x1080, and blurred noise at t = 0..20: the golden's
    records, frames W x H clocks apart."""
    frames = hard_frames(rng, 1920, 1080)
    frames += [(testimages.blurred_noise(rng, 1920, 1080), t) for t in (10, 15, 20)]
    result = run_rtl(frames, score, nms)
    assert_golden(result, frames, score, nms, seed)
    starts = [f.first_pixel for f in result.frames]
    assert np.diff(starts).tolist() == [1920 * 1080] * (len(frames) - 1)


def test_netlist_bit_strings_become_binary_literals():
    """GHDL's Verilog output writes constants of more than 32 bits as strings (ASCII in
    Verilog): the build rewrites them as the binary literals they stand for."""
    from fastnms.sim import verilator

    text = 'wire x;\n  assign n1 = s ? "' + "10" * 20 + '" : r;\n  assign b = {m, "011"};\n'
    fixed = verilator.fix_bit_strings(text)
    assert fixed == (
        "wire x;\n  assign n1 = s ? 40'b" + "10" * 20 + " : r;\n  assign b = {m, 3'b011};\n"
    )


def test_orb_back_to_back(rng, seed):
    """ORB at 1920x1080 (opencv + 3x3, CELL 16, K 4) on three frames back to back with no
    blanking at all (noise at t = 0, a photograph, noise): the next frame's pixels come in
    while the frame before's last cell row is in ORB, so the input is never held (the
    engine's input_stalls, as `fastnms sim --orb --json` reports them, are 0) and every
    frame's keypoints equal the golden model's (angles and descriptors)."""
    import cv2
    from fastnms.golden.orb import orb_features

    photo = cv2.resize(load_grey(testimages.real_images()[0]), (1920, 1080))
    frames = [(testimages.noise(rng, 1920, 1080), 0), (photo, 20)]
    frames.append((testimages.noise(rng, 1920, 1080), 0))
    generics = generics_for("opencv", "3x3", orb=True)
    result = run_rtl(frames, "opencv", "3x3", generics=generics, budget=(16, 4))
    assert [f.input_stalls for f in result.frames] == [0, 0, 0], f"seed {seed}"
    for (img, t), got in zip(frames, result.frames, strict=True):
        want = orb_features(img, t, "opencv", "3x3", cell=16, per_cell=4)
        assert np.array_equal(got.records, want.records), f"seed {seed}"
        assert np.array_equal(got.angle_bits, want.angles.view(np.uint32))
        assert np.array_equal(got.descriptors, want.descriptors)


def test_orb_rate_bound_with_blanking(rng, seed):
    """ORB at 1920x1080 (opencv + 3x3, CELL 16, BUDGET written with K 15, which the top
    clamps to 4 = CELL x CELL / 64, the engine's 64 clocks per keypoint; a build with
    MAX_PER_CELL 15): noise at t = 0, two frames back to back with 1080p60's blanking
    (280 clocks after each line, 45 lines of 2200 clocks after each frame): the input is
    never held, the second frame's keypoints equal the golden model's (angles and
    descriptors), and every keypoint's record leaves within CELL + 22 lines of its
    cell row's last pixel. Without blanking the next frame's first pixels wait while the last cell
    row's keypoints are in ORB (one frame at a time in the core): measured, not asserted
    here."""
    from fastnms.golden.orb import orb_features

    frames = [(testimages.noise(rng, 1920, 1080), 0) for _ in range(2)]
    generics = generics_for("opencv", "3x3", orb=True)
    timing = Timing(hblank=280, vblank=45 * 2200)
    result = run_rtl(frames, "opencv", "3x3", generics=generics, budget=(16, 15), timing=timing)
    assert [f.input_stalls for f in result.frames] == [0, 0], f"seed {seed}"
    assert budget_in_effect(16, 15, generics) == (16, 4)
    img, t = frames[1]
    want = orb_features(img, t, "opencv", "3x3", cell=16, per_cell=4)
    got = result.frames[1]
    assert np.array_equal(got.records, want.records), f"seed {seed}"
    assert np.array_equal(got.angle_bits, want.angles.view(np.uint32))
    assert np.array_equal(got.descriptors, want.descriptors)
    assert len(got.records) > 25_000, "noise at t = 0 fills every cell"
    # Each keypoint's record within CELL + 22 lines of its cell row's last pixel
    # (the cell row's drain, the patch's 19 rows below and the engine's lag behind
    # them at its full rate; docs/orb_rtl.md, Latency).
    line = 1920 + timing.hblank
    for f in result.frames:
        beat0 = f.words[:: regs.REC_ORB_BEATS].astype(np.int64)
        ys = (beat0 >> regs.REC_Y.lsb) & ((1 << regs.REC_Y.width) - 1)
        sent = f.word_clocks[regs.REC_ORB_BEATS - 1 :: regs.REC_ORB_BEATS]
        last_line = np.minimum(1079, (ys // 16 + 1) * 16 - 1)
        after = sent - (f.first_pixel + last_line * line + 1919)
        assert after.max() <= (16 + 22) * line, f"{after.max() / line:.1f} lines, seed {seed}"
