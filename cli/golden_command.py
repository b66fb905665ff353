"""`fastnms golden`: the golden model on one image (corners, or with --orb ORB features,
optionally through the keypoint budget), one summary line and the --csv/--png outputs.
"""

from __future__ import annotations

import argparse
import os
import time

import numpy as np
from fastnms.args import (
    GREY_NOTE,
    add_budget_args,
    add_detection_args,
    budget_of,
    is_region,
    min_area_of,
    min_area_text,
)
from fastnms.golden.budget import cell_budget
from fastnms.golden.model import detect
from fastnms.golden.orb import orb_features
from fastnms.inputs import load_input
from fastnms.outputs import check_outputs, with_areas, write_outputs


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
