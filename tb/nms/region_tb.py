"""cocotb testbench of fastnms_nms_region on its own: any corner/score map
(not only what FAST can produce) against the golden model's region rule
(fastnms.nms.nms_region), compared as sets of (x, y, score, area)."""

from __future__ import annotations

import ast
import json
import os
from pathlib import Path

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden.nms import AREA_MAX, nms_region
from fastnms.testing.regions import SHAPES, comb, grid, nested_arches, serpentine, square_spiral

from tb.stream import sim_ns, value
from tb.video import PERIOD_NS, VideoTB, record_mismatch, split_records

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
MAX_HEIGHT = GENERICS["MAX_HEIGHT"]
SCORE_BITS = GENERICS["SCORE_BITS"]
CONNECTIVITY = GENERICS["CONNECTIVITY"]
IDLE = float(os.environ.get("TB_IDLE", "0"))
MIN_WIDTH = 3  # fastnms_nms_region's narrowest row (the core's is 7)
RECORD_FIELDS = ("x", "y", "score", "area")
STALL = float(os.environ.get("TB_STALL", "0"))


def map_beats(corner: np.ndarray, score: np.ndarray) -> list[dict[str, int]]:
    h, w = corner.shape
    return [
        {
            "corner": int(corner[y, x]),
            "score": int(score[y, x]),
            "sof": int(x == 0 and y == 0),
            "eol": int(x == w - 1),
            "eof": int(x == w - 1 and y == h - 1),
        }
        for y in range(h)
        for x in range(w)
    ]


class TB(VideoTB):
    def __init__(self, dut, idle: float = IDLE, stall: float = STALL):
        super().__init__(dut, ["x", "y", "score", "area", "eof"], idle, stall)
        dut._log.info("generics %s", GENERICS)
        self.set_cfg(width=3)

    async def _count_errors(self) -> None:  # this block has no error outputs
        return

    def random_map(self, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
        """Sparse to dense corners, few distinct scores (many ties) or the full range."""
        rng = self.np_rng
        density = float(rng.choice([0.05, 0.3, 0.5, 0.7, 1.0]))
        top = int(rng.choice([2, 2**SCORE_BITS - 1]))
        corner = rng.random((height, width)) < density
        score = rng.integers(0, top + 1, (height, width)) * corner
        return corner, score.astype(np.int64)

    async def run_maps(self, maps: list[tuple[np.ndarray, np.ndarray]], label: str) -> int:
        """Send the maps back to back and compare each frame's records with the golden.
        Returns the clocks from the first pixel accepted to the last end-of-frame beat."""
        start = len(self.sink.beats)
        eofs = sum(b["eof"] for b in self.sink.beats) + len(maps)
        first = sim_ns()
        self.set_cfg(width=maps[0][0].shape[1])
        await ClockCycles(self.dut.clk, 2)
        for i, (corner, score) in enumerate(maps):
            nxt = maps[i + 1][0].shape[1] if i + 1 < len(maps) else None

            def after(k, nxt=nxt):
                if k == 0 and nxt is not None:
                    self.set_cfg(width=nxt)

            await self.source.send(map_beats(corner, score), on_accept=after)
        total = sum(c.size for c, _ in maps)
        await self.wait_eofs(eofs, 40 * total + 2000)
        frames = split_records(self.sink.beats[start:], RECORD_FIELDS)
        for i, ((corner, score), got) in enumerate(zip(maps, frames, strict=True)):
            want = nms_region(corner, score, CONNECTIVITY, with_area=True)
            want = [tuple(int(v) for v in r) for r in want]
            name = f"{label} frame {i} ({corner.shape[1]}x{corner.shape[0]})"
            got = sorted(got, key=lambda r: (r[1], r[0]))
            assert got == want, record_mismatch(got, want, name)
        last_eof = max(t for b, t in zip(self.sink.beats, self.sink.times, strict=True) if b["eof"])
        return (last_eof - first) // PERIOD_NS


def stress_maps(width: int, rng: np.random.Generator) -> list[tuple[np.ndarray, np.ndarray]]:
    """The stress shapes of the issue, each with random scores (ties included)."""

    def scored(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return mask, (rng.integers(0, 4, mask.shape) * mask).astype(np.int64)

    maps = []
    for text, *_ in SHAPES.values():
        corner, score = grid(text)
        if corner.shape[1] < MIN_WIDTH:  # pad on the right: the block's narrowest row
            pad = ((0, 0), (0, MIN_WIDTH - corner.shape[1]))
            corner, score = np.pad(corner, pad), np.pad(score, pad)
        maps.append((corner, score.astype(np.int64)))
    h = 12
    maps.append(scored(comb(h, width)))  # teeth joined by the bottom row
    checker = (np.indices((h, width)).sum(0) % 2) == 0  # width/2 regions per row (4-conn)
    maps.append(scored(checker))
    columns = np.zeros((h, width), dtype=bool)
    columns[:, ::2] = True  # width/2 regions open over the whole frame
    maps.append(scored(columns))
    maps.append(scored(serpentine(h, width)))
    maps.append(scored(square_spiral(min(width, 24))))
    maps.append(scored(np.ones((h, width), dtype=bool)))  # one region, the whole frame
    diagonal = np.zeros((h, width), dtype=bool)  # chains joined only under 8-connectivity
    for k in range(0, width + h, 3):
        for y in range(h):
            if 0 <= k - y < width:
                diagonal[y, k - y] = True
    maps.append(scored(diagonal))
    stairs = np.zeros((h, width), dtype=bool)
    for y in range(h):
        stairs[y, max(0, width - 2 - 2 * y) : width - 2 * y] = True
    maps.append(scored(stairs))
    edges = np.zeros((h, width), dtype=bool)  # regions on the first and last rows and columns
    edges[0, ::3] = edges[-1, 1::3] = edges[:, 0] = edges[:, -1] = True
    maps.append(scored(edges))
    return maps


@cocotb.test()
async def shapes(dut):
    """U, nested U, spirals, staircases, combs, checkerboards, diagonal chains,
    a full frame, ties across merges, regions on the first and last rows."""
    tb = TB(dut)
    await tb.reset()
    await tb.run_maps(stress_maps(MAX_WIDTH, tb.np_rng), "shapes")


@cocotb.test()
async def area_saturates(dut):
    """Areas at the saturation: a region of AREA_MAX - 1, AREA_MAX and AREA_MAX + 1
    pixels, and the whole frame (MAX_WIDTH x MAX_HEIGHT) when that is more."""
    tb = TB(dut)
    await tb.reset()
    maps = []
    for area in (AREA_MAX - 1, AREA_MAX, AREA_MAX + 1):
        height = min(MAX_HEIGHT, -(-area // MAX_WIDTH) + 1)
        if MAX_WIDTH * (height - 1) < area:
            continue  # the build's frames are too small for this area
        corner = np.zeros((height, MAX_WIDTH), dtype=bool)
        corner.flat[:area] = True  # rows from the top: one region, then an empty row
        maps.append((corner, (tb.np_rng.integers(0, 9, corner.shape) * corner).astype(np.int64)))
    full = np.ones((MAX_HEIGHT, MAX_WIDTH), dtype=bool)
    maps.append((full, tb.np_rng.integers(0, 9, full.shape).astype(np.int64)))
    await tb.run_maps(maps, "areas")


@cocotb.test()
async def area_merges_saturated(dut):
    """Two arms joined at the bottom (a U), either or both with more than AREA_MAX
    pixels, so that a saturated area merges as either operand; and the same arms
    joined at the top. Needs MAX_WIDTH x MAX_HEIGHT of at least 64 x 80."""
    assert MAX_WIDTH >= 64 and MAX_HEIGHT >= 80, "a build too small for this test"
    tb = TB(dut)
    await tb.reset()
    maps = []
    for left, right in ((30, 2), (2, 30), (30, 30), (30, 1)):
        for joined in ("bottom", "top"):
            corner = np.zeros((80, 64), dtype=bool)
            corner[:78, :left] = True
            corner[:78, 64 - right :] = True
            corner[77 if joined == "bottom" else 0, :] = True
            score = tb.np_rng.integers(0, 9, corner.shape) * corner
            maps.append((corner, score.astype(np.int64)))
    await tb.run_maps(maps, "saturated merges")


@cocotb.test()
async def random_maps(dut):
    """Back-to-back random maps, 3x1 to MAX_WIDTH wide, sparse to full, many ties."""
    tb = TB(dut)
    await tb.reset()
    rng = tb.np_rng
    sizes = [
        (7, 7),
        (MAX_WIDTH, 8),
        (3, 1),
        (3, 6),
        (4, 1),
        (3, 5),
        (3, 9),
        (4, 6),
        (4, 9),
        (MAX_WIDTH, 1),
        (5, 3),
    ]
    sizes += [
        (int(rng.integers(MIN_WIDTH, MAX_WIDTH + 1)), int(rng.integers(1, 24))) for _ in range(14)
    ]
    await tb.run_maps([tb.random_map(w, h) for w, h in sizes], "random")


@cocotb.test()
async def random_sequences(dut):
    """Many short sequences of three small frames of random sizes (3 to MAX_WIDTH wide,
    1 to 5 high) back to back: the frame boundaries (a flush beside the next frame's
    first row, narrower and wider frames, one-row frames) as often as possible."""
    tb = TB(dut)
    await tb.reset()
    rng = tb.np_rng
    for trial in range(120):
        maps = []
        for _ in range(3):
            w, h = int(rng.integers(MIN_WIDTH, MAX_WIDTH + 1)), int(rng.integers(1, 6))
            corner = rng.random((h, w)) < rng.random()
            maps.append((corner, (rng.integers(0, 5, (h, w)) * corner).astype(np.int64)))
        await tb.run_maps(maps, f"sequence {trial}")


@cocotb.test()
async def empty_and_reset(dut):
    """Frames without corners still end with an end-of-frame beat; a reset in
    mid-frame is followed by exact frames."""
    tb = TB(dut)
    await tb.reset()
    blank = np.zeros((7, 9), dtype=bool)
    await tb.run_maps([(blank, blank.astype(np.int64))] * 2, "empty")
    assert split_records(tb.sink.beats) == [[], []]
    corner, score = tb.random_map(MAX_WIDTH, 10)
    beats = map_beats(corner, score)
    tb.set_cfg(width=MAX_WIDTH)
    await ClockCycles(dut.clk, 2)
    await tb.source.send(beats[: len(beats) // 2])
    await tb.reset()
    tb.sink.beats.clear()
    tb.sink.times.clear()
    await tb.run_maps([tb.random_map(MAX_WIDTH, 9), tb.random_map(7, 7)], "after reset")


def worst_maps(width: int, rng: np.random.Generator) -> dict[str, np.ndarray]:
    """Content that made the paper's region NMS stall, at a given width."""
    h = 12
    yy, xx = np.indices((h, width))
    return {
        "noise 50%": rng.random((h, width)) < 0.5,
        "checkerboard": (xx + yy) % 2 == 0,
        "comb": comb(h, width),  # teeth joined at the bottom
        "single pixels": (xx % 2 == 0) & (yy % 2 == 0),  # width / 2 regions per row
        "serpentine": serpentine(h, width),
        "nested arches": nested_arches(width),
        "full": np.ones((h, width), dtype=bool),
    }


def region_ends(corner: np.ndarray) -> dict[int, int]:
    """For each region (by its pixels' raster indices): the raster index of its last pixel."""
    from scipy import ndimage

    structure = ndimage.generate_binary_structure(2, 1 if CONNECTIVITY == 4 else 2)
    labels, _ = ndimage.label(corner, structure=structure)
    flat = labels.ravel()
    last = {}
    for i in np.flatnonzero(flat):
        last[int(flat[i])] = int(i)
    return {int(i): last[int(flat[i])] for i in np.flatnonzero(flat)}


# A record enters the output FIFO in the clock after the step that closes its region, and
# leaves it OUT_LATENCY clocks after the pixel of that step was accepted, at most, when
# out_ready is high (the input skid buffer, the step, the FIFO).
OUT_LATENCY = 8


@cocotb.test()
async def never_stalls(dut):
    """The worst content at MAX_WIDTH, three frames each back to back, output always
    ready: in_ready stays high on every clock from the first pixel to the last, the
    end-of-frame beats come exactly W x H clocks apart, each at most W + OUT_LATENCY
    clocks after its frame's last pixel, and every record leaves at most
    OUT_LATENCY clocks after the pixel W + 1 positions after its region's last one (raster
    order), or W + OUT_LATENCY clocks after the frame's last pixel for a region on the
    last row."""
    if IDLE or STALL:
        return
    tb = TB(dut)
    await tb.reset()
    for name, corner in worst_maps(MAX_WIDTH, tb.np_rng).items():
        score = (tb.np_rng.integers(0, 2**SCORE_BITS, corner.shape) * corner).astype(np.int64)
        h, w = corner.shape
        stalls = []

        async def watch_ready(total=3 * corner.size, stalls=stalls):
            seen = 0
            while seen < total:
                await RisingEdge(dut.clk)
                if value(dut.in_valid):
                    if value(dut.in_ready):
                        seen += 1
                    else:
                        stalls.append(sim_ns())

        start_beats, start_accepts = len(tb.sink.beats), len(tb.source.accept_times)
        watcher = cocotb.start_soon(watch_ready())
        await tb.run_maps([(corner, score)] * 3, name)
        await watcher
        assert not stalls, f"{name}: in_ready low at {stalls[:5]} ns"
        accepts = tb.source.accept_times[start_accepts:]
        assert (accepts[-1] - accepts[0]) // PERIOD_NS == 3 * corner.size - 1, name
        beats = tb.sink.beats[start_beats:]
        times = tb.sink.times[start_beats:]
        eofs = [t // PERIOD_NS for b, t in zip(beats, times, strict=True) if b["eof"]]
        assert np.diff(eofs).tolist() == [corner.size] * 2, f"{name}: end-of-frame beats {eofs}"
        for f, eof in enumerate(eofs):
            last_in = accepts[(f + 1) * corner.size - 1] // PERIOD_NS
            assert eof - last_in <= w + OUT_LATENCY, f"{name}: end of frame {f} at {eof}"
        ends = region_ends(corner)
        frame = 0
        for b, t in zip(beats, times, strict=True):
            if b["eof"]:
                frame += 1
                continue
            base = frame * corner.size
            last = ends[b["y"] * w + b["x"]]
            if last + w + 1 < corner.size:
                bound = accepts[base + last + w + 1] + OUT_LATENCY * PERIOD_NS
            else:
                bound = accepts[base + corner.size - 1] + (w + OUT_LATENCY) * PERIOD_NS
            assert t <= bound, f"{name} frame {frame}: record {b} at {t} ns, bound {bound} ns"
        dut._log.info("%s %dx%d: 3 frames at one pixel per clock, records in bound", name, w, h)


def size_change_allowance(widths: list[int]) -> list[int]:
    """Input waits allowed by each frame of a back-to-back sequence (the first follows an
    idle block): W_previous - W + 4 clocks for a frame narrower than the one before it,
    none for any other. A narrower frame's first row ends while the previous frame's flush
    still runs; its last pixel, or, for a one-row frame, the next frame, waits for it."""
    return [0] + [a - b + 4 if b < a else 0 for a, b in zip(widths, widths[1:], strict=False)]


@cocotb.test()
async def size_changes(dut):
    """Back-to-back frames of changing widths (MAX_WIDTH down to 3 and back, runs of
    one-row frames, random widths and heights) with the output always ready: records
    exact, and, counted clock by clock, the input waits up to the end of any frame are at
    most the allowances of the frames so far (size_change_allowance)."""
    if IDLE or STALL:
        return
    tb = TB(dut)
    await tb.reset()
    rng = tb.np_rng
    sequences = [
        ([MAX_WIDTH, MIN_WIDTH, MAX_WIDTH], [3, 3, 3]),
        ([MAX_WIDTH, MAX_WIDTH - 1, MIN_WIDTH, MIN_WIDTH], [2, 1, 1, 2]),
        ([MAX_WIDTH] + [MIN_WIDTH] * 5, [1] * 6),
    ]
    for _ in range(60):
        n = int(rng.integers(2, 7))
        widths = rng.integers(MIN_WIDTH, MAX_WIDTH + 1, n).tolist()
        sequences.append((widths, rng.choice([1, 1, 2, 3], n).tolist()))
    at_bound = 0
    for widths, heights in sequences:
        maps = []
        for w, h in zip(widths, heights, strict=True):
            corner = rng.random((h, w)) < rng.random()
            maps.append((corner, (rng.integers(0, 5, (h, w)) * corner).astype(np.int64)))
        ends = np.cumsum([c.size for c, _ in maps]).tolist()
        waits = [0] * len(maps)

        async def watch(waits=waits, ends=ends):
            taken = 0
            while taken < ends[-1]:
                await RisingEdge(dut.clk)
                if value(dut.in_valid):
                    if value(dut.in_ready):
                        taken += 1
                    else:
                        waits[int(np.searchsorted(ends, taken, side="right"))] += 1

        watcher = cocotb.start_soon(watch())
        await tb.run_maps(maps, f"widths {widths}")
        await watcher
        waited = np.cumsum(waits).tolist()
        allowed = np.cumsum(size_change_allowance(widths)).tolist()
        assert all(a <= b for a, b in zip(waited, allowed, strict=True)), (
            f"widths {widths}, heights {heights}: waits {waits}, allowed so far {allowed}"
        )
        at_bound += waited[-1] == allowed[-1] > 0
    dut._log.info("size changes: waits within the allowance, reached in %d sequences", at_bound)


@cocotb.test()
async def idle_output(dut):
    """The end-of-frame beat leaves without further input."""
    tb = TB(dut)
    await tb.reset()
    await tb.run_maps([tb.random_map(MAX_WIDTH, 5)], "single")
    for _ in range(10):
        await RisingEdge(dut.clk)


@cocotb.test()
async def photo_maps(dut):
    """FAST output of whole photographs (TB_PHOTOS: JSON list of [path, threshold,
    score]): records against the golden, and clocks per pixel logged. With
    TB_MAX_CLOCKS_PER_PIXEL set, each frame is held to it."""
    from fastnms.golden.fast import fast_maps
    from fastnms.golden.image import load_grey

    photos = json.loads(os.environ.get("TB_PHOTOS", "[]"))
    limit = float(os.environ.get("TB_MAX_CLOCKS_PER_PIXEL", "0"))
    assert photos, "no photographs given in TB_PHOTOS"
    tb = TB(dut)
    await tb.reset()
    for path, threshold, score in photos:
        img = load_grey(path)[:MAX_HEIGHT, :MAX_WIDTH]
        corner, scores = fast_maps(img, threshold, score)
        clocks = await tb.run_maps([(corner, scores.astype(np.int64))], Path(path).name)
        per_pixel = clocks / img.size
        dut._log.info(
            "%s %dx%d t=%d %s: %d clocks, %.4f per pixel (flush pass included)",
            Path(path).name,
            img.shape[1],
            img.shape[0],
            threshold,
            score,
            clocks,
            per_pixel,
        )
        if limit:
            assert per_pixel <= limit, f"{path}: {per_pixel:.4f} clocks per pixel > {limit}"


@cocotb.test()
async def output_backpressure(dut):
    """Random output back-pressure (out_ready low with probability 0.3 to 0.9) on the
    worst content at MAX_WIDTH, two frames each back to back: records exact, and,
    counted clock by clock, the input's waits so far never exceed the clocks so far in
    which the output held a record that was not taken (out_valid high, out_ready low)."""
    if IDLE or STALL:
        return
    tb = TB(dut)
    await tb.reset()
    waited = 0
    for stall in (0.3, 0.6, 0.9):
        tb.sink.stall = stall
        for name, corner in worst_maps(MAX_WIDTH, tb.np_rng).items():
            score = (tb.np_rng.integers(0, 2**SCORE_BITS, corner.shape) * corner).astype(np.int64)
            counts = {"waits": 0, "held": 0, "excess": -(10**9), "done": False}

            async def watch(counts=counts):
                while not counts["done"]:
                    await RisingEdge(dut.clk)
                    counts["held"] += value(dut.out_valid) and not value(dut.out_ready)
                    counts["waits"] += value(dut.in_valid) and not value(dut.in_ready)
                    counts["excess"] = max(counts["excess"], counts["waits"] - counts["held"])

            watcher = cocotb.start_soon(watch())
            await tb.run_maps([(corner, score)] * 2, f"{name} stall {stall}")
            counts["done"] = True
            await watcher
            dut._log.info(
                "%s, out_ready low %.0f %%: input waits %d, output held %d, worst excess %d",
                name,
                100 * stall,
                counts["waits"],
                counts["held"],
                counts["excess"],
            )
            assert counts["excess"] <= 0, f"{name}, stall {stall}: input waited beyond the output"
            waited += counts["waits"]
    tb.sink.stall = 0.0
    assert waited, "the record FIFO never filled: the test did not reach its case"
    dut._log.info("input waits %d in all, never more than the output-held clocks", waited)
