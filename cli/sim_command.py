"""`fastnms sim`: the IP's top level, fastnms_axi, simulated on images sent as consecutive
frames; prints corners, cycles and wall time per frame and writes the RTL's corners
(--csv, --png) and a JSON summary of the run (--json).
"""

from __future__ import annotations

import argparse
import json

import numpy as np
from fastnms.args import GREY_NOTE
from fastnms.rtl_run import (
    add_rtl_args,
    rtl_inputs,
    sim_summary,
    simulate,
    timing_of,
    write_sim_outputs,
)
from fastnms.sim import regs
from fastnms.sim.run import (
    LARGEST_HEIGHT,
    LARGEST_WIDTH,
    MAX_HEIGHT,
    MAX_WIDTH,
    MIN_SIZE,
    SimResult,
)


def add_sim_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "sim",
        help="run the RTL (fastnms_axi, simulated) on images",
        description=(
            "Simulate the IP's top level, fastnms_axi, on the images, sent back to back as "
            "consecutive frames (AXI4-Stream video in, AXI4-Lite set-up of each frame's size "
            "and threshold, and of MIN_AREA with --min-area, corner records out), and write "
            "the corners it emitted (with a region NMS each with its region's area). "
            f"{GREY_NOTE} Frames from {MIN_SIZE}x{MIN_SIZE} to {LARGEST_WIDTH}x{LARGEST_HEIGHT}: "
            f"the simulated IP is built for {MAX_WIDTH}x{MAX_HEIGHT} when every frame fits, "
            f"else for {LARGEST_WIDTH}x{LARGEST_HEIGHT} (an engine build of its own). "
            "Needs the source tree, GHDL and (default engine) Verilator with a C++ compiler; "
            "the first run of a configuration builds the engine. Prints corners, cycles, "
            "cycles per pixel and wall time per frame. With several frames the CSV has a "
            "first column `frame` (0 for the first image) and the JSON a list `frames`."
        ),
    )
    add_rtl_args(p, "one frame each")
    p.add_argument(
        "--json",
        metavar="OUT.json",
        help="write width, height, threshold, score, nms, ppc, cell, per_cell (null without a "
        "budget), min_area (null without --min-area), orb, engine, timing, corners, cycles, "
        "input_stalls, status_flags, wall_seconds (and `frames` for several)",
    )
    return p


def status_flags(status: int) -> list[str]:
    """The names of the STATUS bits set in `status`."""
    return [name for name, f in regs.REGISTERS["STATUS"].fields.items() if f.get(status)]


def sim_json(frames: list[tuple[str, np.ndarray]], args: argparse.Namespace, sim: SimResult):
    pixels = sum(f.width * f.height for f in sim.frames)
    summary: dict[str, object] = {}
    if len(frames) == 1:
        summary |= {"width": sim.frames[0].width, "height": sim.frames[0].height}
    summary |= {
        "threshold": args.threshold,
        "score": args.score,
        "nms": args.nms,
        "ppc": args.ppc,
        "cell": args.cell,
        "per_cell": args.per_cell,
        "min_area": args.min_area,
        "orb": args.orb,
        "engine": args.engine,
        "timing": timing_of(args).as_dict(),
        "corners": sum(int(f.records.shape[0]) for f in sim.frames),
        "cycles": sim.cycles,
        "cycles_per_pixel": sim.cycles / pixels,
        "input_stalls": sim.input_stalls,
        # STATUS after the last frame (fast engine): OVERFLOW says the corner
        # output held the pipeline back; None with the cocotb engine.
        "status_flags": None if sim.status is None else status_flags(sim.status),
        "wall_seconds": sim.wall_seconds,
    }
    if len(frames) > 1:
        summary["frames"] = [
            {
                "image": name,
                "width": f.width,
                "height": f.height,
                "corners": int(f.records.shape[0]),
                "cycles": f.cycles,
                "input_stalls": f.input_stalls,
            }
            for (name, _), f in zip(frames, sim.frames, strict=True)
        ]
    return (json.dumps(summary, indent=2) + "\n").encode("ascii")


def run_sim(args: argparse.Namespace) -> int:
    frames = rtl_inputs(args, args.csv, args.png, args.json)
    sim = simulate(frames, args)
    extra = [(args.json, sim_json(frames, args, sim))] if args.json else []
    write_sim_outputs(frames, sim, args, extra)
    print(sim_summary(frames, args, sim))
    return 0
