"""The bench's frame runs: the bench frames back to back through the AXI top on the fast
engine in a score x NMS configuration, every frame's records checked against the golden
model, and the figures derived from the run (clocks per pixel, frame intervals, latency,
simulation speed); the fast engine's speed over all runs, and the cocotb engine's on a
band of the first frame beside the fast engine's."""

from __future__ import annotations

import time

import numpy as np
from fastnms.golden.model import NMS_MODES, SCORES, detect
from fastnms.sim.run import SimError, SimResult, run_rtl

from flows.bench.engine import BenchError, record_text, status_errors

CONFIGS = [(score, nms) for score in SCORES for nms in NMS_MODES]
# The cocotb engine simulates a few thousand pixels per second: it is timed on a
# band of the first frame, with the hardware and line length of the fast runs.
COCOTB_CONFIG = ("opencv", "3x3")
COCOTB_ROWS = 64


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
            f"{len(want)}; first difference at record {at}: RTL {record_text(got, at)}, "
            f"golden {record_text(want, at)}"
        )


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
