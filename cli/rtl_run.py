"""What `fastnms sim` and `fastnms compare` share: the RTL's options (inputs, engine,
timing, pixels per clock, ORB), the checks of a configuration before the simulation,
the simulation with its progress line, the summary lines and the output files of the
simulated frames.
"""

from __future__ import annotations

import argparse
import os
import sys

import numpy as np
from fastnms.args import (
    PROG,
    UsageError,
    add_budget_args,
    add_detection_args,
    budget_of,
    count_arg,
    is_region,
    min_area_of,
    min_area_text,
    pattern_arg,
)
from fastnms.golden.orb import OrbFeatures
from fastnms.inputs import load_frames
from fastnms.outputs import check_outputs, csv_bytes, orb_csv_bytes, with_areas, write_outputs
from fastnms.sim.run import (
    ENGINES,
    LARGEST_HEIGHT,
    LARGEST_WIDTH,
    ORB_MAX_CELL,
    FrameResult,
    SimError,
    SimResult,
    budget_in_effect,
    build_size,
    check_size,
    generics_for,
    run_rtl,
)
from fastnms.sim.timing import Pattern, Timing


def add_rtl_args(p: argparse.ArgumentParser, what: str) -> None:
    """Inputs, engine and timing options shared by `sim` and `compare`."""
    p.add_argument(
        "images",
        metavar="IMAGE",
        nargs="+",
        help=f"input images (any format OpenCV reads), {what}; a directory stands for its "
        "image files in name order, a video file for its frames",
    )
    add_detection_args(p, with_image=False)
    add_budget_args(
        p,
        "; the simulated IP is then built with the budget (MAX_PER_CELL 15); --nms 3x3 or none",
    )
    p.add_argument(
        "--orb",
        action="store_true",
        help="build the simulated IP with ORB (DESCRIPTOR orb): keypoints 31 pixels or more "
        "inside the frame with their angles and descriptors, as `golden --orb` writes them; "
        f"needs --cell 16 or {ORB_MAX_CELL} and --per-cell (ORB in the RTL runs behind the "
        "budget), --nms 3x3 or none, --ppc 1",
    )
    p.add_argument(
        "--engine",
        choices=ENGINES,
        default="verilator",
        help="verilator (default): the synthesized netlist compiled by Verilator, about a "
        "million clocks per second; cocotb: the RTL under GHDL with cocotb and cocotbext-axi, "
        "a few thousand",
    )
    p.add_argument(
        "--idle",
        type=pattern_arg,
        default=Pattern(),
        metavar="P",
        help="input idles: a rate in [0, 1) or a repeated pattern of 0/1 (1 = no pixel offered "
        "on that clock); default none",
    )
    p.add_argument(
        "--stall",
        type=pattern_arg,
        default=Pattern(),
        metavar="P",
        help="output back-pressure on the corner records, as --idle (1 = tready low)",
    )
    p.add_argument(
        "--seed", type=count_arg, default=1, metavar="N", help="seed of the rate patterns"
    )
    p.add_argument(
        "--hblank",
        type=count_arg,
        default=0,
        metavar="N",
        help="clocks without video after each line (verilator engine)",
    )
    p.add_argument(
        "--ppc",
        type=int,
        choices=(1, 2, 4),
        default=1,
        help="pixels per clock of the simulated IP (its PPC generic): 1 (default), 2 or 4; "
        "2 and 4 need --nms 3x3 or none and an image width that is a multiple of PPC",
    )
    p.add_argument(
        "--vblank",
        type=count_arg,
        default=0,
        metavar="N",
        help="clocks without video after each frame's last line, instead of --hblank "
        "(verilator engine)",
    )


def rtl_inputs(args: argparse.Namespace, *outputs: str | None) -> list[tuple[str, np.ndarray]]:
    check_outputs(*outputs)
    frames = load_frames(args.images)
    if len(frames) > 1 and args.png:
        raise UsageError(f"--png draws one image; {len(frames)} frames were given")
    return frames


class Progress:
    """One status line on stderr, rewritten in place, once the simulation has taken
    more than a few seconds."""

    AFTER_SECONDS = 3.0

    def __init__(self) -> None:
        self.shown = False

    def __call__(self, pixels_in: int, pixels: int, seconds: float) -> None:
        if seconds < self.AFTER_SECONDS:
            return
        pct = 100 * pixels_in // max(1, pixels)
        print(
            f"\r{PROG} sim: {pixels_in}/{pixels} pixels in ({pct} %), {seconds:.0f} s",
            end="",
            file=sys.stderr,
            flush=True,
        )
        self.shown = True

    def done(self) -> None:
        if self.shown:
            print(file=sys.stderr)
            self.shown = False


def timing_of(args: argparse.Namespace) -> Timing:
    return Timing(args.idle, args.stall, args.seed, args.hblank, args.vblank)


def simulate(frames: list[tuple[str, np.ndarray]], args: argparse.Namespace) -> SimResult:
    min_area = min_area_of(args)
    if args.ppc != 1 and args.nms not in ("3x3", "none"):
        raise UsageError(
            f"--ppc {args.ppc} needs --nms 3x3 or none (the region NMS takes one pixel per clock)"
        )
    for name, img in frames:
        why = check_size(img, args.ppc, LARGEST_WIDTH, LARGEST_HEIGHT)
        if why:
            raise UsageError(f"{name}: {why}")
    if args.engine != "verilator" and (args.hblank or args.vblank):
        raise UsageError("--hblank and --vblank need --engine verilator")
    budget = budget_of(args)
    if budget is not None and args.nms not in ("3x3", "none"):
        raise UsageError(
            "--cell and --per-cell need --nms 3x3 or none (the budget takes records in "
            "raster order; the region NMS's come as regions close)"
        )
    if args.orb:
        if budget is None:
            raise UsageError(
                "--orb needs --cell and --per-cell (ORB in the RTL runs behind the budget)"
            )
        if budget[0] not in (16, ORB_MAX_CELL):
            raise UsageError(
                f"--orb takes --cell 16 or {ORB_MAX_CELL} (the simulated IP's "
                f"ORB_MAX_CELL), got {budget[0]}"
            )
        if args.ppc != 1:
            raise UsageError("--orb needs --ppc 1")
        # The IP clamps K to the ORB engine's rate; the run and its checks use that K.
        _, k = budget_in_effect(*budget, generics_for(args.score, args.nms, orb=True))
        if k != args.per_cell:
            print(
                f"{PROG} sim: --per-cell {args.per_cell} at --cell {budget[0]} is above the "
                f"ORB engine's rate; the IP uses {k} (BUDGET.PER_CELL)",
                file=sys.stderr,
            )
            args.per_cell, budget = k, (budget[0], k)
    progress = Progress()

    def announce(text: str) -> None:
        print(f"{PROG} sim: {text}", file=sys.stderr, flush=True)

    try:
        sim = run_rtl(
            [(img, args.threshold) for _, img in frames],
            args.score,
            args.nms,
            engine=args.engine,
            timing=timing_of(args),
            progress=progress,
            announce=announce,
            generics=generics_for(
                args.score,
                args.nms,
                args.ppc,
                build_size([img.shape for _, img in frames]),
                budget is not None,
                args.orb,
            ),
            budget=budget,
            min_area=min_area,
        )
    except SimError as e:
        raise UsageError(str(e)) from None
    finally:
        progress.done()
    if sim.build_seconds is not None:
        announce(f"built in {sim.build_seconds:.1f} s (reused from now on)")
    return sim


def frame_summary(name: str, args: argparse.Namespace, frame: FrameResult) -> str:
    w, h = frame.width, frame.height
    return (
        f"{name}: {w}x{h}, score={args.score} nms={args.nms} threshold={args.threshold}"
        f"{min_area_text(args)}"
        f"{f' ppc={args.ppc}' if args.ppc != 1 else ''}"
        f"{f' cell={args.cell} per-cell={args.per_cell}' if args.cell else ''}: "
        f"{frame.records.shape[0]} {'ORB keypoints' if args.orb else 'corners'}; "
        f"{frame.cycles} cycles, "
        f"{frame.cycles / (w * h):.4f} cycles per pixel"
    )


def sim_summary(frames: list[tuple[str, np.ndarray]], args: argparse.Namespace, sim: SimResult):
    lines = [
        frame_summary(os.path.basename(name), args, f)
        for (name, _), f in zip(frames, sim.frames, strict=True)
    ]
    pixels = sum(f.width * f.height for f in sim.frames)
    tail = f"{sim.wall_seconds:.1f} s wall ({args.engine})"
    if len(frames) == 1:
        lines[0] += f"; {tail}"
    else:
        lines.append(
            f"{len(frames)} frames: {sum(f.records.shape[0] for f in sim.frames)} corners; "
            f"{sim.cycles} cycles, {sim.cycles / pixels:.4f} cycles per pixel; {tail}"
        )
    return "\n".join(lines)


def frame_records(frame: FrameResult, region: bool) -> np.ndarray:
    """A simulated frame's records: x, y, score, and with the region NMS its area."""
    return with_areas(frame.records, frame.areas) if region else frame.records


def frame_features(frame: FrameResult) -> OrbFeatures:
    """A simulated ORB frame's keypoints as the golden model's OrbFeatures."""
    return OrbFeatures(frame.records, frame.angle_bits.view(np.float32), frame.descriptors)


def frames_csv_bytes(sim: SimResult, orb: bool = False, region: bool = False) -> bytes:
    if orb:
        tables = [orb_csv_bytes(frame_features(f)).decode("ascii") for f in sim.frames]
    else:
        tables = [csv_bytes(frame_records(f, region)).decode("ascii") for f in sim.frames]
    lines = ["frame," + tables[0].splitlines()[0]]
    for i, table in enumerate(tables):
        lines += [f"{i},{line}" for line in table.splitlines()[1:]]
    return ("\n".join(lines) + "\n").encode("ascii")


def write_sim_outputs(frames, sim: SimResult, args: argparse.Namespace, extra=()) -> None:
    if args.orb:
        first = frame_features(sim.frames[0])
    else:
        first = frame_records(sim.frames[0], is_region(args))
    if len(frames) == 1:
        write_outputs(frames[0][1], first, args, extra)
        return
    extra = list(extra)
    if args.csv:
        extra.append((args.csv, frames_csv_bytes(sim, args.orb, is_region(args))))
    args_no_csv = argparse.Namespace(**{**vars(args), "csv": None})
    write_outputs(frames[0][1], first, args_no_csv, extra)
