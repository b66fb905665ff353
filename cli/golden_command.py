"""`fastnms golden`: the golden model on one image (corners, or with --orb ORB features,
optionally through the keypoint budget; with --levels on each level of cv2.ORB's image
pyramid), one summary line and the --csv/--png outputs.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
from fastnms.args import (
    GREY_NOTE,
    UsageError,
    add_budget_args,
    add_detection_args,
    add_level_args,
    budget_of,
    is_region,
    min_area_of,
    min_area_text,
    scale_factor_of,
)
from fastnms.golden.budget import cell_budget
from fastnms.golden.model import detect
from fastnms.golden.orb import DESCRIPTOR_BYTES, OrbFeatures, level_features, orb_features
from fastnms.golden.pyramid import level_scale, level_size, pyramid
from fastnms.inputs import load_input
from fastnms.outputs import check_outputs, with_areas, write_level_outputs, write_outputs


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
    add_budget_args(p, " (with --orb after the 31-pixel border; with --levels per level)")
    add_level_args(
        p,
        "run on each of the N levels of cv2.ORB's image pyramid (CSV level,x,y,score, with "
        "--orb level,x,y,score,angle,descriptor, x and y in the level's own pixels; the PNG "
        "draws each keypoint on the image as a circle of its size); not with --min-area",
    )
    return p


def golden_budget(records: np.ndarray, cell: int, per_cell: int) -> np.ndarray:
    """cell_budget of (N, 3) or (N, 4) records (the area kept with its record)."""
    kept = cell_budget(records[:, :3], cell, per_cell)
    if records.shape[1] == 3:
        return kept
    area = {(x, y): a for x, y, _, a in records.tolist()}  # one record per position
    return with_areas(kept, [area[(x, y)] for x, y, _ in kept.tolist()])


def run_golden(args: argparse.Namespace) -> int:
    budget = budget_of(args) or (None, 0)
    scale_factor = scale_factor_of(args)
    if args.levels is not None and args.min_area is not None:
        raise UsageError("--min-area does not go with --levels")
    min_area = min_area_of(args)
    check_outputs(args.csv, args.png)
    img = load_input(args.image)
    if args.levels is not None:
        return run_levels(img, args, budget, scale_factor)

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
    print(
        f"{os.path.basename(args.image)}: {w}x{h}, score={args.score} nms={args.nms} "
        f"threshold={args.threshold}{min_area_text(args)}: {count} {what}{within_text(args)} "
        f"in {elapsed:.3f} s"
    )
    return 0


def within_text(args: argparse.Namespace) -> str:
    return f" (at most {args.per_cell} per {args.cell}x{args.cell} cell)" if args.cell else ""


NO_FEATURES = OrbFeatures(
    np.zeros((0, 3), np.int64), np.zeros(0, np.float32), np.zeros((0, DESCRIPTOR_BYTES), np.uint8)
)


def level_result(
    image: np.ndarray | None, args: argparse.Namespace, budget: tuple[int | None, int]
) -> np.ndarray | OrbFeatures:
    """The single-level model on one level's image (None: a level of no pixels)."""
    if args.orb:
        if image is None:
            return NO_FEATURES
        return level_features(image, args.threshold, args.score, args.nms, *budget)
    if image is None:
        return np.zeros((0, 3), np.int64)
    records = detect(image, args.threshold, args.score, args.nms)
    return cell_budget(records, *budget) if args.per_cell else records


def run_levels(
    img: np.ndarray, args: argparse.Namespace, budget: tuple[int | None, int], scale_factor: float
) -> int:
    """--levels N: the model on each level of the pyramid, one summary line, the outputs."""
    h, w = img.shape
    sizes = [level_size(w, h, k, scale_factor) for k in range(args.levels)]
    start = time.perf_counter()
    images = pyramid(img, args.levels, scale_factor)  # ends early at a level of no pixels
    results = [
        level_result(images[k] if k < len(images) else None, args, budget)
        for k in range(args.levels)
    ]
    elapsed = time.perf_counter() - start
    scales = [level_scale(k, scale_factor) for k in range(args.levels)]
    write_level_outputs(img, list(zip(scales, results, strict=True)), args)

    counts = [len(r.records) if isinstance(r, OrbFeatures) else len(r) for r in results]
    what = "keypoints with ORB descriptors" if args.orb else "corners"
    per_level = ", ".join(f"{lw}x{lh}: {n}" for (lw, lh), n in zip(sizes, counts, strict=True))
    levels = f"{args.levels} level{'s' if args.levels > 1 else ''}"
    print(
        f"{os.path.basename(args.image)}: {w}x{h}, score={args.score} nms={args.nms} "
        f"threshold={args.threshold}, {levels} at scale factor {scale_factor:.9g}: "
        f"{sum(counts)} {what}{within_text(args)} in {elapsed:.3f} s; per level {per_level}"
    )
    return 0
