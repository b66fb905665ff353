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

This module is the entry point: the options, the order of the parts, their
progress lines, the summary and the report. The parts are modules beside it:
frames.py (the bench frames), engine.py (the fast engine's builds, STATUS,
BenchError), frame_runs.py (the score x NMS runs and both engines' speed),
budget.py (the keypoint budget in the top), orb_rtl.py (ORB in the top), orb.py
(the golden ORB against cv2.ORB), region_memory.py (the region NMS's memory) and
software.py (the golden model's and OpenCV's time per frame).
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import sys
import time
from pathlib import Path

import cv2
import numpy as np
from fastnms.golden.model import NMS_MODES, SCORES
from fastnms.sim import verilator
from fastnms.sim.ghdl import ghdl_version, tool_version
from fastnms.sim.sources import REPO
from fastnms.testing import images as testimages

from flows.bench import orb as orb_bench
from flows.bench.budget import budget_bench
from flows.bench.engine import BenchError, bench_generics, build_engines
from flows.bench.frame_runs import (
    COCOTB_CONFIG,
    COCOTB_ROWS,
    CONFIGS,
    cocotb_speed,
    fast_engine_speed,
    simulate,
)
from flows.bench.frame_runs import derive as derive  # flows/report/test_report.py uses it
from flows.bench.frames import bench_frames
from flows.bench.orb_rtl import ORB_BUDGETS, orb_rtl_bench
from flows.bench.region_memory import MEMORY_CONFIGS, SCORE_BITS, region_memory
from flows.bench.software import software_times
from flows.report import report

BENCH_BUILD = REPO / "build" / "bench"
WIDTH, HEIGHT = 1920, 1080
FRAMES = 3
THRESHOLD = 20
# Several pixels per clock (issue 15): 3840x2160 photographs (scaled up) through
# the top built with PPC 4, opencv + 3x3.
UHD_WIDTH, UHD_HEIGHT, UHD_PPC = 3840, 2160, 4
UHD_FRAMES = 2


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
        print(f"bench: wrote docs/results/bench.json and rendered {path.relative_to(REPO)}")
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
