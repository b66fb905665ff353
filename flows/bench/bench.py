"""`make bench`: measured throughput, latency and simulation speed of the AXI
top (fastnms_axi) in every score x NMS configuration on the fast simulation
engine (GHDL's netlist compiled by Verilator, through fastnms.sim.run.run_rtl),
the cocotb engine's speed on a short run beside it, the region NMS's memory
against the paper's formula, the golden ORB against cv2.ORB on every real
photograph (flows/bench/orb.py), the AXI top with ORB descriptors on the
same frames (issue 36: keypoints, clocks per pixel, latency, every record's
angle and descriptor against the golden model), and the golden model's and
OpenCV's time per frame on this machine. Writes build/bench/summary.json and
the bench section of docs/results.md (flows/report/report.py).

    python -m flows.bench.bench [--width 1920 --height 1080 --frames 3 --jobs 2 ...]
    python -m flows.bench.bench --only orb    the ORB rows alone, merged into the summary

Frames: the largest real photographs (fastnms.testing.images: ../shared/images if
present, else scikit-image's bundled ones), each scaled to cover the frame
with cv2.resize and cropped at its centre; sent back to back with no input
idles and no output back-pressure, every frame's records compared with the
golden model (a difference stops the bench).

Order: the software timings, the fast engine's builds (--jobs at a time), then
the simulations one at a time and the cocotb run, so that every timed run has
the machine to itself.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import cv2
import numpy as np
from fastnms.golden.budget import hardware_order
from fastnms.golden.model import NMS_MODES, SCORES, detect
from fastnms.golden.orb import orb_features
from fastnms.sim import regs, verilator
from fastnms.sim.ghdl import ghdl_version, tool_version
from fastnms.sim.run import SimError, SimResult, generics_for, run_rtl
from fastnms.sim.sources import REPO
from fastnms.testing import images as testimages

from flows.bench import orb as orb_bench
from flows.bench import software
from flows.report import report

BENCH_BUILD = REPO / "build" / "bench"
CONFIGS = [(score, nms) for score in SCORES for nms in NMS_MODES]
# The software timings and the memory tables keep the configurations they had
# when the bench simulated only three; region4 and region8 size their memories
# alike, so one table per score width is enough.
SOFTWARE_CONFIGS = [("opencv", "3x3"), ("sad", "region4"), ("opencv", "region8")]
MEMORY_CONFIGS = [("sad", "region4"), ("opencv", "region8")]
# The cocotb engine simulates a few thousand pixels per second: it is timed on a
# band of the first frame, with the hardware and line length of the fast runs.
COCOTB_CONFIG = ("opencv", "3x3")
COCOTB_ROWS = 64
SCORE_BITS = {"opencv": 8, "sad": 12}
WIDTH, HEIGHT = 1920, 1080
FRAMES = 3
THRESHOLD = 20
# Several pixels per clock (issue 15): 3840x2160 photographs (scaled up) through
# the top built with PPC 4, opencv + 3x3.
UHD_WIDTH, UHD_HEIGHT, UHD_PPC = 3840, 2160, 4
UHD_FRAMES = 2
# ORB in the top (issue 36): opencv + 3x3 with DESCRIPTOR orb, the command line's ORB
# build (generics_for(..., orb=True): MAX_PER_CELL 15, ORB_MAX_CELL 32), on the bench
# frames at each (CELL, K): 4 per 16x16 is the engine's rate bound (a keypoint every
# 64 clocks: K <= CELL * CELL / 64), 15 per 32x32 the most K the budget takes.
ORB_BUDGETS = [(16, 4), (32, 15)]
STATUS_ERRORS = ["EOL_EARLY", "EOL_LATE", "SOF_MISSING", "SOF_EARLY", "OVERFLOW"]


class BenchError(Exception):
    """A result the bench must not publish: records unlike the golden model's,
    STATUS errors, or two engines that disagree."""


# ---- frames ----------------------------------------------------------------------


def bench_images(count: int) -> list[Path]:
    """The `count` largest real photographs (by pixels, then by name)."""
    sized = []
    for path in testimages.real_images():
        img = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
        sized.append((-img.shape[0] * img.shape[1], path.name, path))
    return [p for _, _, p in sorted(sized)[:count]]


def bench_frames(width: int, height: int, count: int) -> tuple[np.ndarray, list[str]]:
    """`count` frames (count x height x width, uint8) and the names of their photographs."""
    from fastnms.golden.image import load_grey

    paths = bench_images(count)
    paths = (paths * count)[:count]  # fewer photographs than frames: repeat them
    # Bilinear when enlarging, as the bench has always scaled its frames.
    frames = np.stack(
        [testimages.cover(load_grey(p), width, height, cv2.INTER_LINEAR) for p in paths]
    )
    return frames, [p.name for p in paths]


# ---- region NMS memory -----------------------------------------------------------


def clog2(n: int) -> int:
    """fastnms_pkg.clog2: the bits of an index into n things (at least 1)."""
    bits = 1
    while 2**bits < n:
        bits += 1
    return bits


def bits_for(n: int) -> int:
    """fastnms_pkg.bits_for: the bits that hold the value n itself."""
    return clog2(n + 1)


def region_memory(max_width: int, max_height: int, score_bits: int) -> dict:
    """The region NMS's memories in bits, from its generics, as the RTL sizes
    them (rtl/nms/fastnms_nms_region.vhd), with the paper's formula and a
    5-line FIFO NMS beside them."""
    slots = (max_width + 1) // 2
    slot_bits = bits_for(slots)
    x_bits, y_bits = clog2(max_width), bits_for(max_height)
    key_bits = score_bits + x_bits + y_bits
    # A class's area beside its key: the count (the record's AREA_BITS, 11) and the flag
    # set once it has saturated (rtl/nms/fastnms_nms_region_keys.vhd).
    area_bits = 11
    data_bits = key_bits + area_bits + 1
    stack_words = max((max_width + 1) // 4 + 1 - 2, 1)
    rows = [
        ("row memory (the previous row's corner bits, two columns per word; LUT RAM)", slots, 2),
        ("head table (first run of its class?, by row parity and slot; LUT RAM)", 2 * slots, 1),
        ("last table (last run of its class?, by slot; LUT RAM)", slots, 1),
        (
            "data table, keys (best key of the class, by slot; the paper's RAM score)",
            slots,
            key_bits,
        ),
        ("data table, areas (corner pixels of the class, by slot; LUT RAM)", slots, area_bits + 1),
        (
            "stack of open classes, slots, keys and areas (below its three registers)",
            stack_words,
            2 * slot_bits + data_bits,
        ),
        ("stack of open classes, flags (LUT RAM)", stack_words, 3),
        ("record FIFO (LUT RAM)", 8, 1 + x_bits + y_bits + score_bits + area_bits),
    ]
    breakdown = [{"memory": m, "words": n, "bits_per_word": b, "bits": n * b} for m, n, b in rows]
    index_bits = clog2(max_width // 2)
    paper = (max_width // 2) * (score_bits + x_bits + y_bits + index_bits)
    return {
        "max_width": max_width,
        "max_height": max_height,
        "score_bits": score_bits,
        "slots": slots,
        "slot_bits": slot_bits,
        "x_bits": x_bits,
        "y_bits": y_bits,
        "breakdown": breakdown,
        "total_bits": sum(r["bits"] for r in breakdown),
        "paper_formula_bits": paper,
        "paper_formula": f"({max_width}/2) x ({score_bits} + {x_bits} + {y_bits} + {index_bits})",
        "fifo5_bits": 5 * max_width * score_bits,
        "nms_3x3_bits": 2 * max_width * score_bits,
    }


# ---- golden model and OpenCV -------------------------------------------------------


def software_times(frame: np.ndarray, threshold: int) -> list[dict]:
    """Best of 3 wall times of the golden model (the bench's configurations)
    and of cv2.FastFeatureDetector on one frame (flows/bench/software.py's timer)."""
    from fastnms.golden.model import detect

    rows = []
    for score, nms in SOFTWARE_CONFIGS:
        ms, rec = software.best_ms(lambda s=score, n=nms: detect(frame, threshold, s, n))
        rows.append(
            {
                "what": f"golden {score} + {nms}",
                "ms": ms,
                "corners": len(rec),
                "best_of": software.REPEATS,
            }
        )
    for nonmax in (True, False):
        det = cv2.FastFeatureDetector_create(
            threshold=threshold, nonmaxSuppression=nonmax, type=cv2.FAST_FEATURE_DETECTOR_TYPE_9_16
        )
        ms, kps = software.best_ms(lambda d=det: d.detect(frame))
        label = "opencv + 3x3" if nonmax else "opencv + none"
        rows.append(
            {
                "what": f"cv2.FastFeatureDetector {label}",
                "ms": ms,
                "corners": len(kps),
                "best_of": software.REPEATS,
            }
        )
    return rows


# ---- simulation ------------------------------------------------------------------


def bench_generics(score: str, nms: str, max_width: int, max_height: int) -> dict[str, object]:
    return {**generics_for(score, nms), "MAX_WIDTH": max_width, "MAX_HEIGHT": max_height}


def build_engines(
    generics: list[dict[str, object]], jobs: int, announce: Callable[[str], None] | None = None
) -> list[float | None]:
    """Build the fast engine for every generic set, `jobs` at a time (each build
    runs GHDL, Verilator and g++ in subprocesses, so threads are enough); each
    one's build seconds, None when it was already built."""
    try:
        with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
            return list(pool.map(lambda g: verilator.build(g, announce)[1], generics))
    except verilator.EngineError as e:
        raise BenchError(str(e)) from None


def status_errors(status: int | None) -> list[str]:
    """The names of the STATUS error bits that are set."""
    if status is None:
        return []
    return [n for n in STATUS_ERRORS if getattr(regs, f"STATUS_{n}").get(status)]


def check_golden(
    what: str, images: list[np.ndarray], result: SimResult, score: str, nms: str
) -> None:
    """Raise BenchError unless every frame's records equal the golden model's."""
    for i, (img, frame) in enumerate(zip(images, result.frames, strict=True)):
        want = np.asarray(detect(img, frame.threshold, score, nms)).reshape(-1, 3)
        got = frame.records
        if np.array_equal(got, want):
            continue
        n = min(len(got), len(want))
        at = next((j for j in range(n) if not np.array_equal(got[j], want[j])), n)
        raise BenchError(
            f"{what}, frame {i}: the RTL gave {len(got)} records, the golden model "
            f"{len(want)}; first difference at record {at}: RTL {_record(got, at)}, "
            f"golden {_record(want, at)}"
        )


def _record(records: np.ndarray, i: int) -> str:
    return str(tuple(int(v) for v in records[i])) if i < len(records) else "none"


def simulate(
    score: str,
    nms: str,
    images: list[np.ndarray],
    threshold: int,
    generics: dict[str, object],
    check: bool = True,
    build_seconds: float | None = None,
) -> dict:
    """The frames back to back through fastnms_axi on the fast engine; its raw
    figures plus the derived ones (clocks per pixel, latencies, speed)."""
    what = f"{score} + {nms}"
    start = time.perf_counter()
    try:
        result = run_rtl([(img, threshold) for img in images], score, nms, generics=generics)
    except SimError as e:
        raise BenchError(f"{what}: {e}") from None
    run_seconds = time.perf_counter() - start
    errors = status_errors(result.status)
    if errors:
        raise BenchError(f"{what}: STATUS reports {', '.join(errors)} after the frames")
    if result.extra.get("frame_count") != len(images):
        raise BenchError(
            f"{what}: FRAME_COUNT is {result.extra.get('frame_count')}, not {len(images)}"
        )
    if check:
        check_golden(what, images, result, score, nms)
    fr = result.frames
    raw = {
        "engine": result.engine,
        "frames": len(fr),
        "width": fr[0].width,
        "height": fr[0].height,
        "threshold": threshold,
        "first_pixel": [f.first_pixel for f in fr],
        "last_pixel": [f.last_pixel for f in fr],
        "last_record": [f.last_record for f in fr],
        "cycles": result.cycles,
        "input_stalls": result.input_stalls,
        "frame_input_stalls": [f.input_stalls for f in fr],
        "corners": [len(f.records) for f in fr],
        "checked": check,
        "status": result.status,
        "errors": errors,
        # The simulation alone: run_rtl's wall time without the build.
        "wall_seconds": result.wall_seconds,
        "build_seconds": build_seconds if result.build_seconds is None else result.build_seconds,
        # The whole run_rtl call: the simulation plus the engine's set-up and the decoding.
        "run_seconds": run_seconds,
    }
    return derive(raw, score, nms, generics, time.perf_counter() - start - run_seconds)


def derive(raw: dict, score: str, nms: str, generics: dict, check_seconds: float) -> dict:
    n, pixels = raw["frames"], raw["width"] * raw["height"]
    first, last_in, last_out = raw["first_pixel"][0], raw["last_pixel"], raw["last_record"]
    intervals = [b - a for a, b in zip(last_out, last_out[1:], strict=False)]
    return {
        "config": f"{score}-{nms}-{raw['width']}x{raw['height']}",
        "score": score,
        "nms": nms,
        "generics": generics,
        **raw,
        # Input side: clocks from the first to the last pixel taken, per pixel.
        "input_clocks_per_pixel": (last_in[-1] - first + 1) / (n * pixels),
        # Output side: clocks between consecutive frames' last records, per pixel.
        "frame_interval_clocks": intervals,
        "steady_clocks_per_pixel": (sum(intervals) / len(intervals) / pixels)
        if intervals
        else None,
        "total_clocks_per_pixel": (last_out[-1] - first + 1) / (n * pixels),
        # From a frame's last pixel in to its last record out.
        "latency_clocks": [o - i for i, o in zip(last_in, last_out, strict=True)],
        "sim_pixels_per_second": n * pixels / raw["wall_seconds"],
        "sim_clocks_per_second": raw["cycles"] / raw["wall_seconds"],
        "check_seconds": check_seconds,
    }


BUDGETS = [(64, 4), (32, 2), (16, 1)]


def budget_bench(
    images: list[np.ndarray], threshold: int, width: int, height: int, check: bool
) -> dict:
    """opencv + 3x3 with the keypoint budget (MAX_PER_CELL 15) on the bench frames at
    each of BUDGETS: keypoints per frame, clocks per pixel, latency, input stalls;
    every frame's records against the golden model's budget in the block's order."""
    generics = {**bench_generics("opencv", "3x3", width, height), "MAX_PER_CELL": 15}
    build = build_engines([generics], 1)[0]
    rows = []
    for budget in BUDGETS:
        frames = [(img, threshold) for img in images]
        try:
            result = run_rtl(frames, "opencv", "3x3", generics=generics, budget=budget)
        except SimError as e:
            raise BenchError(f"budget {budget}: {e}") from None
        if status_errors(result.status):
            raise BenchError(f"budget {budget}: STATUS reports {status_errors(result.status)}")
        for i, (img, f) in enumerate(zip(images, result.frames, strict=True)):
            want = hardware_order(detect(img, threshold), *budget)
            words = [int(w) for w in f.words if not regs.REC_EMPTY.get(int(w))]
            got = [(regs.REC_X.get(w), regs.REC_Y.get(w), regs.REC_SCORE.get(w)) for w in words]
            if check and got != [tuple(r) for r in want.tolist()]:
                raise BenchError(f"budget {budget}, frame {i}: records differ from the golden's")
        fr = result.frames
        rows.append(
            {
                "cell": budget[0],
                "per_cell": budget[1],
                "cells": -(-width // budget[0]) * -(-height // budget[0]),
                "corners": [len(f.records) for f in fr],
                "input_clocks_per_pixel": (fr[-1].last_pixel - fr[0].first_pixel + 1)
                / sum(f.width * f.height for f in fr),
                "input_stalls": result.input_stalls,
                "latency_clocks": [f.last_record - f.last_pixel for f in fr],
                "checked": check,
            }
        )
    return {"generics": generics, "build_seconds": build, "rows": rows}


def check_orb(what: str, img: np.ndarray, frame, threshold: int, cell: int, per_cell: int) -> None:
    """Raise BenchError unless the frame's ORB records equal the golden model's
    (fastnms.golden.orb.orb_features with the budget, as `fastnms compare --orb`
    checks them): positions and scores, every angle's float32 bits, all 256
    descriptor bits."""
    want = orb_features(img, threshold, "opencv", "3x3", cell, per_cell)
    got = frame.records
    if not np.array_equal(got, want.records):
        n = min(len(got), len(want.records))
        at = next((j for j in range(n) if not np.array_equal(got[j], want.records[j])), n)
        raise BenchError(
            f"{what}: the RTL gave {len(got)} keypoints, the golden model "
            f"{len(want.records)}; first difference at keypoint {at}: RTL {_record(got, at)}, "
            f"golden {_record(want.records, at)}"
        )
    angles = frame.angle_bits != want.angles.view(np.uint32)
    bits = np.unpackbits(frame.descriptors ^ want.descriptors, axis=1).sum(axis=1)
    bad = np.flatnonzero(angles | (bits > 0))
    if bad.size:
        i = int(bad[0])
        raise BenchError(
            f"{what}: angle or descriptor of {bad.size} of {len(got)} keypoints differ from "
            f"the golden's; the first at {_record(got, i)}: angle bits "
            f"{int(frame.angle_bits[i]):08x} vs {int(want.angles.view(np.uint32)[i]):08x}, "
            f"{int(bits[i])} descriptor bits"
        )


def orb_rtl_bench(
    images: list[np.ndarray],
    threshold: int,
    width: int,
    height: int,
    check: bool,
    budgets: list[tuple[int, int]] = ORB_BUDGETS,
) -> dict:
    """The AXI top with ORB descriptors (opencv + 3x3) on the bench frames, back to
    back, at each (CELL, K) of `budgets`: keypoints per frame, input clocks per pixel,
    input stalls, latency (a frame's last pixel in to its last record out); every
    record (position, score, angle bits, descriptor) against the golden model."""
    generics = generics_for("opencv", "3x3", size=(width, height), orb=True)
    build = build_engines([generics], 1)[0]
    rows = []
    for cell, per_cell in budgets:
        what = f"ORB, {per_cell} per {cell}x{cell}"
        frames = [(img, threshold) for img in images]
        try:
            result = run_rtl(frames, "opencv", "3x3", generics=generics, budget=(cell, per_cell))
        except SimError as e:
            raise BenchError(f"{what}: {e}") from None
        errors = status_errors(result.status)
        if errors:
            raise BenchError(f"{what}: STATUS reports {', '.join(errors)} after the frames")
        start = time.perf_counter()
        if check:
            for i, (img, f) in enumerate(zip(images, result.frames, strict=True)):
                check_orb(f"{what}, frame {i}", img, f, threshold, cell, per_cell)
        fr = result.frames
        pixels = sum(f.width * f.height for f in fr)
        rows.append(
            {
                "cell": cell,
                "per_cell": per_cell,
                "cells": -(-width // cell) * -(-height // cell),
                "corners": [len(f.records) for f in fr],
                "input_clocks_per_pixel": (fr[-1].last_pixel - fr[0].first_pixel + 1) / pixels,
                "input_stalls": result.input_stalls,
                "frame_input_stalls": [f.input_stalls for f in fr],
                "latency_clocks": [f.last_record - f.last_pixel for f in fr],
                "cycles": result.cycles,
                "checked": check,
                "wall_seconds": result.wall_seconds,
                "sim_pixels_per_second": pixels / result.wall_seconds,
                "check_seconds": time.perf_counter() - start,
            }
        )
    return {"generics": generics, "build_seconds": build, "rows": rows}


def fast_engine_speed(sims: list[dict]) -> dict:
    """The fast engine over all the bench's runs: pixels and clocks (first pixel
    to last record) over the simulations' wall seconds."""
    pixels = sum(s["frames"] * s["width"] * s["height"] for s in sims)
    clocks = sum(s["cycles"] for s in sims)
    seconds = sum(s["wall_seconds"] for s in sims)
    frames = sum(s["frames"] for s in sims)
    w, h = sims[0]["width"], sims[0]["height"]
    return {
        "engine": "verilator",
        "measured_on": f"the runs above: {frames} frames of {w}x{h}",
        "pixels": pixels,
        "clocks": clocks,
        "wall_seconds": seconds,
        "pixels_per_second": pixels / seconds,
        "clocks_per_second": clocks / seconds,
        "pixels_per_second_range": [
            min(s["sim_pixels_per_second"] for s in sims),
            max(s["sim_pixels_per_second"] for s in sims),
        ],
    }


def cocotb_speed(
    frame: np.ndarray,
    threshold: int,
    generics: dict[str, object],
    rows: int = COCOTB_ROWS,
    score: str = COCOTB_CONFIG[0],
    nms: str = COCOTB_CONFIG[1],
) -> dict:
    """Time the cocotb engine (GHDL + cocotb) on the middle `rows` lines of
    `frame`, and run the same band on the fast engine: both must give the
    golden model's records and the same clock counts."""
    rows = min(rows, frame.shape[0])
    y0 = (frame.shape[0] - rows) // 2
    band = np.ascontiguousarray(frame[y0 : y0 + rows])
    samples: list[tuple[float, int]] = []

    def progress(pixels_in: int, pixels: int, seconds: float) -> None:
        if 0 < pixels_in < pixels:
            samples.append((seconds, pixels_in))

    what = f"cocotb engine, {score} + {nms}"
    start = time.perf_counter()
    try:
        slow = run_rtl(
            [(band, threshold)], score, nms, engine="cocotb", generics=generics, progress=progress
        )
        call_seconds = time.perf_counter() - start
        fast = run_rtl([(band, threshold)], score, nms, generics=generics)
    except SimError as e:
        raise BenchError(f"{what}: {e}") from None
    check_golden(what, [band], slow, score, nms)
    a, b = slow.frames[0], fast.frames[0]
    # The engines count clocks from different origins: compare the spans.
    clocks = [
        (f.cycles, f.last_pixel - f.first_pixel, f.last_record - f.first_pixel, f.input_stalls)
        for f in (a, b)
    ]
    if not np.array_equal(a.records, b.records) or clocks[0] != clocks[1]:
        raise BenchError(
            f"{what}: the engines disagree on the {band.shape[1]}x{rows} band: "
            f"{len(a.records)} records and clocks {clocks[0]} (cocotb), "
            f"{len(b.records)} records and clocks {clocks[1]} (fast engine)"
        )
    steady = None
    if len(samples) >= 2 and samples[-1][0] > samples[0][0]:
        (t0, p0), (t1, p1) = samples[0], samples[-1]
        steady = (p1 - p0) / (t1 - t0)
    pixels = band.size
    return {
        "engine": "cocotb",
        "measured_on": (
            f"{score} + {nms}, one {band.shape[1]}x{rows} frame (rows {y0} to {y0 + rows - 1} "
            "of the first bench frame)"
        ),
        "score": score,
        "nms": nms,
        "width": band.shape[1],
        "height": rows,
        "first_row": y0,
        "pixels": pixels,
        "clocks": slow.cycles,
        "wall_seconds": slow.wall_seconds,
        "call_seconds": call_seconds,
        "pixels_per_second": pixels / slow.wall_seconds,
        "clocks_per_second": slow.cycles / slow.wall_seconds,
        # From the run's progress reports while the pixels went in.
        "steady_pixels_per_second": steady,
        "corners": len(a.records),
        "equal_to_fast_engine": True,
    }


def machine() -> dict:
    cpu = platform.processor()
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                cpu = line.split(":", 1)[1].strip()
                break
    except OSError:
        pass
    return {
        "cpu": cpu,
        "cores": os.cpu_count(),
        "python": platform.python_version(),
        "opencv": cv2.__version__,
    }


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--width", type=int, default=WIDTH)
    ap.add_argument("--height", type=int, default=HEIGHT)
    ap.add_argument("--frames", type=int, default=FRAMES)
    ap.add_argument("--threshold", type=int, default=THRESHOLD)
    ap.add_argument(
        "--jobs",
        type=int,
        default=int(os.environ.get("JOBS", "2")),
        help="fast-engine builds at a time",
    )
    ap.add_argument("--configs", default=",".join(f"{s}-{n}" for s, n in CONFIGS))
    ap.add_argument(
        "--cocotb-rows",
        type=int,
        default=COCOTB_ROWS,
        help="lines of the cocotb engine's timed band (0: no cocotb run)",
    )
    ap.add_argument(
        "--uhd-frames",
        type=int,
        default=UHD_FRAMES,
        help=f"{UHD_WIDTH}x{UHD_HEIGHT} frames through the PPC {UHD_PPC} top (0: none)",
    )
    ap.add_argument("--no-check", action="store_true", help="do not compare with the golden")
    ap.add_argument(
        "--only",
        choices=["orb"],
        help="run only this part (orb: the AXI top with ORB descriptors) and merge it into "
        "the summary at --out, if there is one",
    )
    ap.add_argument("--out", type=Path, default=BENCH_BUILD / "summary.json")
    ap.add_argument("--no-report", action="store_true", help="do not rewrite docs/results.md")
    args = ap.parse_args(argv)
    start = time.perf_counter()
    try:
        summary = run_orb_only(args) if args.only == "orb" else run(args)
    except BenchError as e:
        sys.exit(f"bench: FAILED: {e}")
    if args.only and "simulation" not in summary:
        args.no_report = True  # no whole summary to render the section from
        print(f"bench: no earlier summary at {args.out}: the section is not rewritten")
    args.out.parent.mkdir(parents=True, exist_ok=True)
    args.out.write_text(json.dumps(summary, indent=1) + "\n")
    out = args.out.resolve()
    print(f"bench: wrote {out.relative_to(REPO) if out.is_relative_to(REPO) else out}")
    if not args.no_report:
        path = report.update_bench(summary)
        print(f"bench: rewrote the bench section of {path.relative_to(REPO)}")
    print(f"bench: total wall time {report.minutes(time.perf_counter() - start)}")


def orb_part(images: list[np.ndarray], args: argparse.Namespace) -> dict:
    """orb_rtl_bench on the bench frames, with its progress printed."""
    print(f"bench: ORB in the top, {args.width}x{args.height}, at {ORB_BUDGETS} (CELL, K) ...")
    result = orb_rtl_bench(images, args.threshold, args.width, args.height, not args.no_check)
    build = result["build_seconds"]
    print(f"bench: ORB build {'cached' if build is None else f'{build:.0f} s'}")
    for row in result["rows"]:
        print(
            f"bench: ORB {row['per_cell']} per {row['cell']}x{row['cell']}: keypoints "
            f"{row['corners']}, input {row['input_clocks_per_pixel']:.5f} clocks/pixel, "
            f"{row['input_stalls']} input stalls, latency {row['latency_clocks']} clocks"
            + (", every record equal to the golden's" if row["checked"] else "")
        )
    return result


def frames_summary(args, sources) -> dict:
    """The summary's description of the bench frames (compared by --only orb)."""
    return {
        "count": args.frames,
        "width": args.width,
        "height": args.height,
        "threshold": args.threshold,
        "photographs": sources,
        "fit": "cv2.resize to cover, centre crop",
    }


def run_orb_only(args: argparse.Namespace) -> dict:
    """`--only orb`: the ORB rows alone, merged into the summary at args.out when
    there is one (its frames must be the same size), else a summary of them alone."""
    missing = verilator.missing_tools()
    if missing:
        raise BenchError(f"the fast simulation engine needs {', '.join(missing)} (make setup)")
    start = time.perf_counter()
    frames, sources = bench_frames(args.width, args.height, args.frames)
    print(f"bench: {args.frames} frames {args.width}x{args.height} from {', '.join(sources)}")
    orb_rtl = orb_part(list(frames), args)
    seconds = time.perf_counter() - start
    if args.out.exists():
        summary = json.loads(args.out.read_text())
        fr = summary.get("frames", {})
        if (fr.get("width"), fr.get("height"), fr.get("count"), fr.get("threshold")) != (
            args.width,
            args.height,
            args.frames,
            args.threshold,
        ):
            raise BenchError(f"{args.out} has other frames: run the whole bench")
        summary["orb_rtl"] = orb_rtl
        summary.setdefault("phases", {})["orb_rtl"] = seconds
        return summary
    return {
        "frames": frames_summary(args, sources),
        "orb_rtl": orb_rtl,
        "phases": {"orb_rtl": seconds},
        "wall_seconds": seconds,
    }


def run(args: argparse.Namespace) -> dict:
    """Everything `make bench` measures, as the summary it writes."""
    configs = [tuple(c.split("-", 1)) for c in args.configs.split(",")]
    for score, nms in configs:
        if score not in SCORES or nms not in NMS_MODES:
            raise BenchError(f"unknown configuration {score}-{nms}")
    missing = verilator.missing_tools()
    if missing:
        raise BenchError(f"the fast simulation engine needs {', '.join(missing)} (make setup)")
    start = time.perf_counter()
    phases: dict[str, float] = {}
    load = round(os.getloadavg()[0], 1)
    source = report.source_state()
    frames, sources = bench_frames(args.width, args.height, args.frames)
    images = list(frames)
    print(f"bench: {args.frames} frames {args.width}x{args.height} from {', '.join(sources)}")

    # The software timings first, alone on the machine.
    t = time.perf_counter()
    software = software_times(frames[0], args.threshold) + orb_bench.times(
        frames[0], args.threshold
    )
    for row in software:
        print(f"bench: {row['what']:<40} {row['ms']:8.1f} ms  {row['corners']} corners")
    phases["software"] = time.perf_counter() - t

    t = time.perf_counter()
    try:
        orb = orb_bench.agreement_table(testimages.real_images(), args.threshold)
    except orb_bench.OrbMismatch as e:
        raise BenchError(str(e)) from None
    print(
        f"bench: ORB on {len(orb['rows'])} photographs: keypoints and angles equal to "
        f"cv2.ORB's; with the bit-exact blur {orb['differing']} of {orb['keypoints']} "
        f"descriptors differ, {orb['mean_bits']:.3f} bits on average, at most {orb['max_bits']}"
    )
    phases["orb"] = time.perf_counter() - t

    t = time.perf_counter()
    generics = [bench_generics(s, n, args.width, args.height) for s, n in configs]
    print(
        f"bench: building the fast engine for {len(configs)} configurations, {args.jobs} at a time"
    )
    builds = build_engines(generics, args.jobs)
    for (score, nms), seconds in zip(configs, builds, strict=True):
        print(
            f"bench: {score}-{nms}: "
            + ("cached" if seconds is None else f"built in {seconds:.1f} s")
        )
    phases["builds"] = time.perf_counter() - t

    # One simulation at a time: each one's speed is the engine's on an idle core.
    t = time.perf_counter()
    sims = []
    for (score, nms), gens, build in zip(configs, generics, builds, strict=True):
        sim = simulate(score, nms, images, args.threshold, gens, not args.no_check, build)
        sims.append(sim)
        print(
            f"bench: {sim['config']}: input {sim['input_clocks_per_pixel']:.5f} clocks/pixel, "
            f"frame intervals {sim['frame_interval_clocks']} clocks, "
            f"latency {sim['latency_clocks']} clocks, "
            f"{sim['sim_pixels_per_second']:.0f} pixels/s simulated "
            f"({sim['wall_seconds']:.1f} s of {sim['run_seconds']:.1f} s in run_rtl)"
            + (
                f", records equal to the golden model's ({sim['check_seconds']:.1f} s)"
                if sim["checked"]
                else ""
            )
        )
    phases["simulations"] = time.perf_counter() - t
    engines = [fast_engine_speed(sims)]
    print(
        f"bench: fast engine {engines[0]['pixels_per_second']:.0f} pixels/s, "
        f"{engines[0]['clocks_per_second']:.0f} clocks/s"
    )

    if args.cocotb_rows > 0:
        t = time.perf_counter()
        score, nms = COCOTB_CONFIG
        print(f"bench: the cocotb engine on {args.cocotb_rows} lines of the first frame ...")
        slow = cocotb_speed(
            frames[0],
            args.threshold,
            bench_generics(score, nms, args.width, args.height),
            args.cocotb_rows,
        )
        engines.append(slow)
        phases["cocotb"] = time.perf_counter() - t
        print(
            f"bench: cocotb engine {slow['pixels_per_second']:.0f} pixels/s "
            f"({slow['measured_on']}, {slow['wall_seconds']:.1f} s), records and clocks "
            "equal to the fast engine's"
        )

    uhd = None
    if args.uhd_frames > 0:
        t = time.perf_counter()
        uhd_frames, uhd_sources = bench_frames(UHD_WIDTH, UHD_HEIGHT, args.uhd_frames)
        gens = {**bench_generics("opencv", "3x3", UHD_WIDTH, UHD_HEIGHT), "PPC": UHD_PPC}
        print(f"bench: {args.uhd_frames} frames {UHD_WIDTH}x{UHD_HEIGHT} at PPC {UHD_PPC} ...")
        build = build_engines([gens], 1)[0]
        uhd = simulate(
            "opencv", "3x3", list(uhd_frames), args.threshold, gens, not args.no_check, build
        )
        uhd["ppc"] = UHD_PPC
        uhd["photographs"] = uhd_sources
        phases["uhd"] = time.perf_counter() - t
        print(
            f"bench: {uhd['config']} at PPC {UHD_PPC}: input "
            f"{uhd['input_clocks_per_pixel']:.5f} clocks/pixel, frame intervals "
            f"{uhd['frame_interval_clocks']} clocks, latency {uhd['latency_clocks']} clocks"
        )

    t = time.perf_counter()
    budget = budget_bench(images, args.threshold, args.width, args.height, not args.no_check)
    phases["budget"] = time.perf_counter() - t
    for row in budget["rows"]:
        print(
            f"bench: budget {row['per_cell']} per {row['cell']}x{row['cell']} cell: "
            f"corners {row['corners']}, input {row['input_clocks_per_pixel']:.5f} clocks/pixel, "
            f"{row['input_stalls']} input stalls, latency {row['latency_clocks']} clocks"
        )

    t = time.perf_counter()
    orb_rtl = orb_part(images, args)
    phases["orb_rtl"] = time.perf_counter() - t

    memory = [
        {"config": f"{s}-{n}-{args.width}", **region_memory(args.width, args.height, SCORE_BITS[s])}
        for s, n in MEMORY_CONFIGS
    ]
    return {
        "frames": frames_summary(args, sources),
        "simulation": sims,
        "uhd": uhd,
        "engines": engines,
        "region_memory": memory,
        "software": software,
        "orb": orb,
        "budget": budget,
        "orb_rtl": orb_rtl,
        "machine": {
            **machine(),
            "ghdl": ghdl_version(),
            "verilator": tool_version(["verilator", "--version"]),
            "parallel_builds": args.jobs,
            "load_before": load,
        },
        "source": source,
        "phases": phases,
        "wall_seconds": time.perf_counter() - start,
    }


if __name__ == "__main__":
    main()
