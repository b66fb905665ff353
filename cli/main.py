"""The `fastnms` command line.

Subcommands (`golden`, `sim`, `compare`) are registered in SUBCOMMANDS; each gets its own
sub-parser and handler. User errors
(bad arguments, unreadable images, unwritable outputs) end as one `fastnms: error: ...`
line on stderr with exit status 2 and leave no output file behind.
"""

from __future__ import annotations

import argparse
import contextlib
import json
import os
import secrets
import sys
import time
from collections.abc import Callable, Iterator, Sequence

import cv2
import numpy as np
from fastnms.golden.budget import CELL_SIZES, MAX_PER_CELL, cell_budget
from fastnms.golden.image import ImageError, load_grey
from fastnms.golden.model import DEFAULT_THRESHOLD, NMS_MODES, SCORES, detect
from fastnms.golden.nms import AREA_MAX
from fastnms.golden.orb import PATCH_SIZE, OrbFeatures, orb_features
from fastnms.sim import regs
from fastnms.sim.run import (
    ENGINES,
    LARGEST_HEIGHT,
    LARGEST_WIDTH,
    MAX_HEIGHT,
    MAX_WIDTH,
    MIN_SIZE,
    ORB_MAX_CELL,
    FrameResult,
    SimError,
    SimResult,
    build_size,
    check_size,
    generics_for,
    run_rtl,
)
from fastnms.sim.timing import Pattern, Timing

PROG = "fastnms"
EXIT_USAGE = 2

# Box colours (BGR) for the PNG overlay: the lowest score in the result is dark red, the
# highest yellow, as in the paper's Fig. 13.
LOW_BGR = (0, 0, 128)
HIGH_BGR = (0, 255, 255)
BOX_HALF = 3  # 7x7 outline, the size of the FAST circle
ORIENTATION_LENGTH = PATCH_SIZE // 2  # the orientation line reaches the patch's rim
GRID_COLOUR = (160, 90, 0)  # BGR: the budget's cells, a dim blue under the boxes


class UsageError(Exception):
    """A problem with the user's input or output paths, reported as one line."""


class ArgumentParser(argparse.ArgumentParser):
    """argparse with single-line errors: `fastnms: error: <message>`, exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(EXIT_USAGE, f"{PROG}: error: {message}\n")


def threshold_arg(text: str) -> int:
    """argparse type: a decimal integer in 0..255 (no floats, no rounding)."""
    try:
        value = int(text, 10)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"threshold must be an integer in 0..255, got {text!r}"
        ) from None
    if not 0 <= value <= 255:
        raise argparse.ArgumentTypeError(f"threshold must be an integer in 0..255, got {value}")
    return value


def cell_arg(text: str) -> int:
    """argparse type: a cell size, a power of two in 16..256."""
    sizes = ", ".join(map(str, CELL_SIZES))
    try:
        value = int(text, 10)
    except ValueError:
        raise argparse.ArgumentTypeError(f"cell must be one of {sizes}, got {text!r}") from None
    if value not in CELL_SIZES:
        raise argparse.ArgumentTypeError(f"cell must be one of {sizes}, got {value}")
    return value


def add_budget_args(p: argparse.ArgumentParser, where: str = "") -> None:
    p.add_argument(
        "--cell",
        type=cell_arg,
        metavar="N",
        help="keypoint budget: cells of N x N pixels from the origin, N a power of two in "
        "16..256 (with --per-cell)",
    )
    p.add_argument(
        "--per-cell",
        type=per_cell_arg,
        metavar="K",
        help=f"keypoint budget: keep the K (1..{MAX_PER_CELL}) best-scoring keypoints of "
        f"each cell, ties to the first in raster order (with --cell){where}",
    )


def budget_of(args: argparse.Namespace) -> tuple[int, int] | None:
    """(cell, per_cell) of --cell and --per-cell, None without them."""
    if (args.cell is None) != (args.per_cell is None):
        raise UsageError("--cell and --per-cell go together")
    return None if args.cell is None else (args.cell, args.per_cell)


def int_in(name: str, low: int, high: int):
    """An argparse type: a decimal integer in low..high, else the error naming `name`."""

    def parse(text: str) -> int:
        try:
            value = int(text, 10)
        except ValueError:
            value = None
        if value is None or not low <= value <= high:
            raise argparse.ArgumentTypeError(
                f"{name} must be an integer in {low}..{high}, got {text!r}"
            )
        return value

    return parse


# MIN_AREA, 0..AREA_MAX (2047).
min_area_arg = int_in("min-area", 0, AREA_MAX)


def is_region(args: argparse.Namespace) -> bool:
    """The region NMS (region4, region8): its records carry the region's area."""
    return args.nms.startswith("region")


def min_area_of(args: argparse.Namespace) -> int | None:
    """--min-area, None without it; only with a region NMS and without --orb."""
    if args.min_area is None:
        return None
    if not is_region(args):
        raise UsageError(
            f"--min-area needs --nms region4 or region8 (the {args.nms} NMS has no regions)"
        )
    if args.orb:
        raise UsageError("--min-area does not go with --orb")
    return args.min_area


def with_areas(records: np.ndarray, areas: np.ndarray) -> np.ndarray:
    """(N, 4) x, y, score, area."""
    return np.column_stack([records, np.asarray(areas, np.int64)]).astype(np.int64)


# Keypoints per cell, 1..15.
per_cell_arg = int_in("per-cell", 1, MAX_PER_CELL)


# ---- output files ----------------------------------------------------------------------


def check_output_path(path: str) -> None:
    """Fail early, before any work, when path cannot become a regular file."""
    if os.path.isdir(path):
        raise UsageError(f"{path}: is a directory")
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        raise UsageError(f"{path}: directory {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise UsageError(f"{path}: directory {parent} is not writable")


class OutputSet:
    """Writes every output to a temporary file next to its destination and moves them all
    into place only after every one was written; on failure nothing new is left behind."""

    def __init__(self) -> None:
        self._pending: list[tuple[str, str]] = []  # (temporary, destination)

    def write(self, path: str, data: bytes) -> None:
        parent = os.path.dirname(os.path.abspath(path))
        while True:
            tmp = os.path.join(parent, f".{os.path.basename(path)}.{secrets.token_hex(4)}.tmp")
            try:
                # Not tempfile.mkstemp: its mode 0600 would survive os.replace; 0666 here
                # lets the umask decide, as for any file the user creates.
                fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
                break
            except FileExistsError:
                continue
        self._pending.append((tmp, path))
        with os.fdopen(fd, "wb") as f:
            f.write(data)

    def commit(self) -> None:
        done: list[str] = []
        try:
            for tmp, path in self._pending:
                os.replace(tmp, path)
                done.append(path)
        except BaseException:
            # A later file failed: take back the ones already moved so no partial set remains.
            for path in done:
                with contextlib.suppress(OSError):
                    os.unlink(path)
            raise
        finally:
            self.discard()

    def discard(self) -> None:
        for tmp, _ in self._pending:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(tmp)
        self._pending.clear()


@contextlib.contextmanager
def output_set() -> Iterator[OutputSet]:
    outputs = OutputSet()
    try:
        yield outputs
        outputs.commit()
    finally:
        outputs.discard()


CSV_COLUMNS = ("x", "y", "score", "area")


def csv_bytes(records: np.ndarray) -> bytes:
    """x,y,score, with a fourth column (the region NMS's records) x,y,score,area."""
    columns = records.shape[1] if records.ndim == 2 else 3
    lines = [",".join(CSV_COLUMNS[:columns])]
    lines += [",".join(map(str, r)) for r in records.tolist()]
    return ("\n".join(lines) + "\n").encode("ascii")


def orb_csv_bytes(features: OrbFeatures) -> bytes:
    """x,y,score,angle,descriptor: the angle with 9 significant digits (it reads back as the
    same float32), the descriptor as 64 lowercase hex digits, byte 0 first."""
    lines = ["x,y,score,angle,descriptor"] + [
        f"{x},{y},{s},{angle:.9g},{bytes(d).hex()}"
        for (x, y, s), angle, d in zip(
            features.records.tolist(), features.angles.tolist(), features.descriptors, strict=True
        )
    ]
    return ("\n".join(lines) + "\n").encode("ascii")


def score_colours(scores: np.ndarray) -> np.ndarray:
    """(N, 3) BGR colours from LOW_BGR at the lowest score to HIGH_BGR at the highest."""
    scores = scores.astype(np.float64)
    if scores.size == 0:
        return np.zeros((0, 3), dtype=np.uint8)
    lo = scores.min()
    span = scores.max() - lo
    # A single distinct score has nothing to rank: draw it as the strongest.
    frac = (scores - lo) / span if span > 0 else np.ones_like(scores)
    low, high = np.array(LOW_BGR, float), np.array(HIGH_BGR, float)
    return np.rint(low + frac[:, None] * (high - low)).astype(np.uint8)


def overlay(
    img: np.ndarray,
    records: np.ndarray,
    angles: np.ndarray | None = None,
    cell: int | None = None,
) -> np.ndarray:
    """The grey image as BGR with a 7x7 outline around each corner, coloured by score, with
    angles (degrees, y down) a line from each corner along its orientation, and with `cell`
    the budget's grid in blue."""
    canvas = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR)
    if cell:
        h, w = img.shape
        for x in range(cell, w, cell):
            cv2.line(canvas, (x, 0), (x, h - 1), GRID_COLOUR, 1)
        for y in range(cell, h, cell):
            cv2.line(canvas, (0, y), (w - 1, y), GRID_COLOUR, 1)
    if records.shape[0] == 0:
        return canvas
    colours = score_colours(records[:, 2])
    # Weakest first, so the strongest corners stay visible where boxes overlap.
    for i in np.argsort(records[:, 2], kind="stable"):
        x, y = int(records[i, 0]), int(records[i, 1])
        colour = tuple(int(c) for c in colours[i])
        cv2.rectangle(canvas, (x - BOX_HALF, y - BOX_HALF), (x + BOX_HALF, y + BOX_HALF), colour, 1)
        if angles is not None:
            t = np.radians(float(angles[i]))
            tip = (
                round(x + ORIENTATION_LENGTH * np.cos(t)),
                round(y + ORIENTATION_LENGTH * np.sin(t)),
            )
            cv2.line(canvas, (x, y), tip, colour, 1)
    return canvas


def png_bytes(canvas: np.ndarray) -> bytes:
    ok, buf = cv2.imencode(".png", canvas)
    if not ok:
        raise OSError("PNG encoding failed")
    return buf.tobytes()


# ---- subcommands -----------------------------------------------------------------------


def add_detection_args(p: argparse.ArgumentParser, with_image: bool = True) -> None:
    """IMAGE, threshold, score, NMS and the output files, shared by every subcommand."""
    if with_image:
        p.add_argument("image", metavar="IMAGE", help="input image (any format OpenCV reads)")
    p.add_argument(
        "-t",
        "--threshold",
        type=threshold_arg,
        default=DEFAULT_THRESHOLD,
        metavar="T",
        help=f"segment-test threshold, integer 0..255 (default {DEFAULT_THRESHOLD})",
    )
    p.add_argument(
        "--score",
        choices=SCORES,
        default="opencv",
        help="corner score: OpenCV's cornerScore or the paper's SAD (default opencv)",
    )
    p.add_argument(
        "--nms",
        choices=NMS_MODES,
        default="3x3",
        help="non-maxima suppression (default 3x3, OpenCV's)",
    )
    p.add_argument(
        "--min-area",
        type=min_area_arg,
        metavar="N",
        help=f"the paper's region filtering (MIN_AREA): drop the regions with fewer than N "
        f"corner pixels, N an integer 0..{AREA_MAX} (0 and 1 keep every region; areas "
        f"saturate at {AREA_MAX}); only with --nms region4 or region8",
    )
    p.add_argument(
        "--csv",
        metavar="OUT.csv",
        help="write the corners as CSV: x,y,score; with --nms region4 or region8 "
        "x,y,score,area (the region's corner pixels, saturating at "
        f"{AREA_MAX})",
    )
    p.add_argument("--png", metavar="OUT.png", help="write the image with coloured corner boxes")


GREY_NOTE = (
    "Colour images are converted to grey as OpenCV does: cv2.imread (8-bit BGR) then "
    "cv2.cvtColor(COLOR_BGR2GRAY)."
)


def add_golden_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "golden",
        help="run the golden model on an image",
        description=(
            f"Detect FAST-9/16 corners with the Python golden model. {GREY_NOTE} "
            "Prints one summary line."
        ),
    )
    add_detection_args(p)
    p.add_argument(
        "--orb",
        action="store_true",
        help="ORB features as OpenCV computes them: keep the keypoints 31 pixels or more from "
        "each border and add each one's orientation and 256-bit rotated BRIEF descriptor "
        "(CSV x,y,score,angle,descriptor: the angle in degrees as a float32, the "
        "descriptor as 64 hex digits, byte 0 first; the PNG draws each orientation)",
    )
    add_budget_args(p, " (with --orb after the 31-pixel border)")
    return p


VIDEO_SUFFIXES = (".avi", ".mp4", ".mkv", ".mov", ".webm", ".m4v", ".mpg", ".mpeg")
IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm", ".ppm", ".webp")


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


def add_compare_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "compare",
        help="run the RTL and the golden model on images and compare them",
        description=(
            "Run `fastnms sim` and the golden model on the images (and, for opencv + 3x3, "
            "cv2.FastFeatureDetector) and compare the sets of (x, y, score) frame by frame; with "
            "--nms region4 or region8 the sets of (x, y, score, area), the golden model "
            "filtered by --min-area as the RTL is. "
            "Prints the first differences; exit status 1 on any difference, 0 when identical. "
            "--csv and --png write the RTL's corners."
        ),
    )
    add_rtl_args(p, "sent as consecutive frames")
    return p


def pattern_arg(text: str) -> Pattern:
    try:
        return Pattern.parse(text)
    except ValueError as e:
        raise argparse.ArgumentTypeError(str(e)) from None


def count_arg(text: str) -> int:
    try:
        value = int(text, 10)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {text!r}") from None
    if value < 0:
        raise argparse.ArgumentTypeError(f"expected an integer >= 0, got {value}")
    return value


def check_outputs(*paths: str | None) -> None:
    given = [os.path.abspath(p) for p in paths if p]
    if len(set(given)) != len(given):
        raise UsageError("two output options name the same file")
    for path in paths:
        if path:
            check_output_path(path)


def load_input(path: str) -> np.ndarray:
    try:
        return load_grey(path)
    except ImageError as e:
        raise UsageError(str(e)) from None


def load_video(path: str) -> list[np.ndarray]:
    """Every frame of a video file, grey as load_grey converts images."""
    capture = cv2.VideoCapture(path)
    frames = []
    try:
        while True:
            ok, bgr = capture.read()
            if not ok:
                break
            frames.append(cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY))
    finally:
        capture.release()
    if not frames:
        raise UsageError(f"{path}: no frame OpenCV can decode in this video file")
    return frames


def load_frames(paths: Sequence[str]) -> list[tuple[str, np.ndarray]]:
    """(name, grey image) for each input: an image, a directory's image files in name
    order, or a video file's frames (named file#index)."""
    frames: list[tuple[str, np.ndarray]] = []
    for path in paths:
        if os.path.isdir(path):
            files = sorted(
                e.path
                for e in os.scandir(path)
                if e.is_file() and e.name.lower().endswith(IMAGE_SUFFIXES)
            )
            if not files:
                raise UsageError(f"{path}: a directory without image files")
            frames += [(f, load_input(f)) for f in files]
        elif path.lower().endswith(VIDEO_SUFFIXES) and os.path.isfile(path):
            frames += [(f"{path}#{i}", img) for i, img in enumerate(load_video(path))]
        else:
            frames.append((path, load_input(path)))
    return frames


def write_outputs(
    img: np.ndarray, records: np.ndarray | OrbFeatures, args: argparse.Namespace, extra=()
) -> None:
    """--csv, --png and any (path, bytes) in extra, all or none."""
    if isinstance(records, OrbFeatures):
        table, angles, records = orb_csv_bytes(records), records.angles, records.records
    else:
        table, angles = csv_bytes(records), None
    try:
        with output_set() as out:
            if args.csv:
                out.write(args.csv, table)
            if args.png:
                cell = args.cell if getattr(args, "per_cell", None) else None
                out.write(args.png, png_bytes(overlay(img, records, angles, cell)))
            for path, data in extra:
                out.write(path, data)
    except OSError as e:
        where = f"{e.filename}: " if e.filename else ""
        raise UsageError(f"cannot write output: {where}{e.strerror or e}") from None


def golden_budget(records: np.ndarray, cell: int, per_cell: int) -> np.ndarray:
    """cell_budget of (N, 3) or (N, 4) records (the area kept with its record)."""
    kept = cell_budget(records[:, :3], cell, per_cell)
    if records.shape[1] == 3:
        return kept
    area = {(x, y): a for x, y, _, a in records.tolist()}  # one record per position
    return with_areas(kept, [area[(x, y)] for x, y, _ in kept.tolist()])


def run_golden(args: argparse.Namespace) -> int:
    budget = budget_of(args) or (None, 0)
    min_area = min_area_of(args)
    check_outputs(args.csv, args.png)
    img = load_input(args.image)

    start = time.perf_counter()
    if args.orb:
        result = orb_features(img, args.threshold, args.score, args.nms, *budget)
        count, what = len(result.records), "keypoints with ORB descriptors"
    else:
        result = detect(
            img, args.threshold, args.score, args.nms, min_area or 0, with_area=is_region(args)
        )
        if args.per_cell:
            result = golden_budget(result, *budget)
        count, what = len(result), "corners"
    elapsed = time.perf_counter() - start
    write_outputs(img, result, args)

    h, w = img.shape
    within = f" (at most {args.per_cell} per {args.cell}x{args.cell} cell)" if args.cell else ""
    print(
        f"{os.path.basename(args.image)}: {w}x{h}, score={args.score} nms={args.nms} "
        f"threshold={args.threshold}{min_area_text(args)}: {count} {what}{within} in "
        f"{elapsed:.3f} s"
    )
    return 0


def min_area_text(args: argparse.Namespace) -> str:
    return "" if args.min_area is None else f" min-area={args.min_area}"


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


def status_flags(status: int) -> list[str]:
    """The names of the STATUS bits set in `status`."""
    return [name for name, f in regs.REGISTERS["STATUS"].fields.items() if f.get(status)]


def frames_csv_bytes(sim: SimResult, orb: bool = False, region: bool = False) -> bytes:
    if orb:
        tables = [orb_csv_bytes(frame_features(f)).decode("ascii") for f in sim.frames]
    else:
        tables = [csv_bytes(frame_records(f, region)).decode("ascii") for f in sim.frames]
    lines = ["frame," + tables[0].splitlines()[0]]
    for i, table in enumerate(tables):
        lines += [f"{i},{line}" for line in table.splitlines()[1:]]
    return ("\n".join(lines) + "\n").encode("ascii")


def frame_records(frame: FrameResult, region: bool) -> np.ndarray:
    """A simulated frame's records: x, y, score, and with the region NMS its area."""
    return with_areas(frame.records, frame.areas) if region else frame.records


def frame_features(frame: FrameResult) -> OrbFeatures:
    """A simulated ORB frame's keypoints as the golden model's OrbFeatures."""
    return OrbFeatures(frame.records, frame.angle_bits.view(np.float32), frame.descriptors)


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


def rtl_inputs(args: argparse.Namespace, *outputs: str | None) -> list[tuple[str, np.ndarray]]:
    check_outputs(*outputs)
    frames = load_frames(args.images)
    if len(frames) > 1 and args.png:
        raise UsageError(f"--png draws one image; {len(frames)} frames were given")
    return frames


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


def run_sim(args: argparse.Namespace) -> int:
    frames = rtl_inputs(args, args.csv, args.png, args.json)
    sim = simulate(frames, args)
    extra = [(args.json, sim_json(frames, args, sim))] if args.json else []
    write_sim_outputs(frames, sim, args, extra)
    print(sim_summary(frames, args, sim))
    return 0


def differences(got: np.ndarray, want: np.ndarray, limit: int = 10) -> list[str]:
    """The first records (sorted by y, x) only in one of the two sets: (x, y, score), or
    (x, y, score, area) with the region NMS's areas."""
    a = {tuple(int(v) for v in r) for r in got}
    b = {tuple(int(v) for v in r) for r in want}
    only = sorted(
        [(r, "rtl only") for r in a - b] + [(r, "reference only") for r in b - a],
        key=lambda item: (item[0][1], item[0][0]),
    )
    return [f"  ({', '.join(map(str, r))}): {where}" for r, where in only[:limit]]


def opencv_records(img: np.ndarray, threshold: int) -> np.ndarray:
    fast = cv2.FastFeatureDetector_create(threshold, True, cv2.FAST_FEATURE_DETECTOR_TYPE_9_16)
    points = [(int(k.pt[0]), int(k.pt[1]), int(k.response)) for k in fast.detect(img)]
    return np.array(sorted(points, key=lambda p: (p[1], p[0])), dtype=np.int64).reshape(-1, 3)


def run_compare(args: argparse.Namespace) -> int:
    frames = rtl_inputs(args, args.csv, args.png)
    sim = simulate(frames, args)
    write_sim_outputs(frames, sim, args)
    print(sim_summary(frames, args, sim))
    status = 0
    budget = budget_of(args)
    for i, ((name, img), got) in enumerate(zip(frames, sim.frames, strict=True)):
        prefix = f"frame {i} ({os.path.basename(name)}): " if len(frames) > 1 else ""
        if args.orb:
            status |= compare_orb(prefix, img, got, args)
            continue
        region = is_region(args)
        golden = detect(
            img, args.threshold, args.score, args.nms, args.min_area or 0, with_area=region
        )
        references = {"golden model": golden}
        records = frame_records(got, region)
        if args.score == "opencv" and args.nms == "3x3":
            references[f"OpenCV {cv2.__version__} FAST"] = opencv_records(img, args.threshold)
        if budget is not None:
            references = {f"{k} + budget": cell_budget(v, *budget) for k, v in references.items()}
        for ref, want in references.items():
            diff = differences(records, want)
            what = "corners with their areas" if region else "corners"
            if diff:
                status = 1
                print(
                    f"{prefix}rtl vs {ref}: DIFFERENT "
                    f"({records.shape[0]} vs {want.shape[0]} {what})"
                )
                print("\n".join(diff))
            else:
                print(f"{prefix}rtl vs {ref}: identical ({want.shape[0]} {what})")
    return status


def compare_orb(prefix: str, img: np.ndarray, got: FrameResult, args: argparse.Namespace) -> int:
    """The RTL's ORB keypoints against the golden model's: positions and scores, then
    each keypoint's angle (float32 bits) and descriptor (all 256 bits); 1 if any differ."""
    want = orb_features(img, args.threshold, args.score, args.nms, args.cell, args.per_cell)
    diff = differences(got.records, want.records)
    if diff:
        print(
            f"{prefix}rtl vs golden model ORB: DIFFERENT "
            f"({got.records.shape[0]} vs {want.records.shape[0]} keypoints)"
        )
        print("\n".join(diff))
        return 1
    angles = got.angle_bits != want.angles.view(np.uint32)
    bits = np.unpackbits(got.descriptors ^ want.descriptors, axis=1).sum(axis=1)
    bad = np.flatnonzero(angles | (bits > 0))
    if bad.size:
        print(
            f"{prefix}rtl vs golden model ORB: DIFFERENT (angle or descriptor of {bad.size} "
            f"of {want.records.shape[0]} keypoints)"
        )
        for i in bad[:10].tolist():
            x, y, _ = want.records[i].tolist()
            print(
                f"  ({x}, {y}): angle bits {int(got.angle_bits[i]):08x} vs "
                f"{int(want.angles.view(np.uint32)[i]):08x}, {int(bits[i])} descriptor bits differ"
            )
        return 1
    print(
        f"{prefix}rtl vs golden model ORB: identical ({want.records.shape[0]} keypoints, "
        "angle bits and descriptors)"
    )
    return 0


Handler = Callable[[argparse.Namespace], int]
SUBCOMMANDS: dict[str, tuple[Callable[..., argparse.ArgumentParser], Handler]] = {
    "golden": (add_golden_parser, run_golden),
    "sim": (add_sim_parser, run_sim),
    "compare": (add_compare_parser, run_compare),
}


def build_parser() -> ArgumentParser:
    parser = ArgumentParser(
        prog=PROG,
        description=(
            "FAST-9/16 corner detection with non-maxima suppression: the golden model, the "
            "RTL in simulation, and the comparison of the two."
        ),
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, (add_parser, handler) in SUBCOMMANDS.items():
        add_parser(sub).set_defaults(handler=handler, command=name)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return EXIT_USAGE
    try:
        return args.handler(args)
    except UsageError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
