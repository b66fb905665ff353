"""The command line's shared arguments: the one-line usage errors (`fastnms: error: ...`,
exit status 2), the argument types (threshold, cell, per-cell, min-area, pyramid levels and
scale factor, idle and stall patterns, counts) and the detection, budget and pyramid
options the subcommands take.
"""

from __future__ import annotations

import argparse

from fastnms.golden.budget import CELL_SIZES, MAX_PER_CELL
from fastnms.golden.model import DEFAULT_THRESHOLD, NMS_MODES, SCORES
from fastnms.golden.nms import AREA_MAX
from fastnms.golden.pyramid import DEFAULT_SCALE_FACTOR, MAX_LEVELS, validate_levels
from fastnms.sim.timing import Pattern

PROG = "fastnms"
EXIT_USAGE = 2


class UsageError(Exception):
    """A problem with the user's input or output paths, reported as one line."""


class ArgumentParser(argparse.ArgumentParser):
    """argparse with single-line errors: `fastnms: error: <message>`, exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(EXIT_USAGE, f"{PROG}: error: {message}\n")


# ---- argument types --------------------------------------------------------------------


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

# Keypoints per cell, 1..15.
per_cell_arg = int_in("per-cell", 1, MAX_PER_CELL)


# Pyramid levels, 1..MAX_LEVELS (the golden model's validate_levels, same message).
levels_arg = int_in("levels", 1, MAX_LEVELS)


def scale_factor_arg(text: str) -> float:
    """argparse type: the pyramid's scale factor, a finite number above 1 (as a float32,
    the type cv2.ORB keeps it in)."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"scale factor must be a number above 1, got {text!r}"
        ) from None
    try:
        return validate_levels(1, value)[1]
    except ValueError:
        as_float32 = " (1 as a float32, cv2.ORB's type)" if value > 1 else ""
        raise argparse.ArgumentTypeError(
            f"scale factor must be a number above 1, got {text!r}{as_float32}"
        ) from None


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


# ---- options shared by the subcommands -------------------------------------------------


GREY_NOTE = (
    "Colour images are converted to grey as OpenCV does: cv2.imread (8-bit BGR) then "
    "cv2.cvtColor(COLOR_BGR2GRAY)."
)


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


def add_level_args(p: argparse.ArgumentParser, levels_help: str, required: bool = False) -> None:
    """--levels N and --scale-factor F: cv2.ORB's image pyramid."""
    p.add_argument(
        "--levels",
        type=levels_arg,
        required=required,
        metavar="N",
        help=f"{levels_help}; N an integer 1..{MAX_LEVELS} (cv2.ORB's default is 8)",
    )
    p.add_argument(
        "--scale-factor",
        type=scale_factor_arg,
        metavar="F",
        help="the pyramid's scale factor, a number above 1 (default "
        f"{DEFAULT_SCALE_FACTOR}, cv2.ORB's): level k is 1/F**k the size of the image, "
        "each level resized from the one before with cv2.INTER_LINEAR_EXACT",
    )


def scale_factor_of(args: argparse.Namespace) -> float:
    """--scale-factor, its default without it; only with --levels."""
    if args.scale_factor is None:
        return DEFAULT_SCALE_FACTOR
    if args.levels is None:
        raise UsageError("--scale-factor needs --levels")
    return args.scale_factor


def budget_of(args: argparse.Namespace) -> tuple[int, int] | None:
    """(cell, per_cell) of --cell and --per-cell, None without them."""
    if (args.cell is None) != (args.per_cell is None):
        raise UsageError("--cell and --per-cell go together")
    return None if args.cell is None else (args.cell, args.per_cell)


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


def min_area_text(args: argparse.Namespace) -> str:
    return "" if args.min_area is None else f" min-area={args.min_area}"
