"""`fastnms compare`: the simulated RTL against the golden model (and, for opencv + 3x3,
cv2.FastFeatureDetector) frame by frame; prints the first differences, exit status 1 on
any difference, 0 when identical.
"""

from __future__ import annotations

import argparse
import os

import cv2
import numpy as np
from fastnms.args import budget_of, is_region
from fastnms.golden.budget import cell_budget
from fastnms.golden.model import detect
from fastnms.golden.orb import orb_features
from fastnms.rtl_run import (
    add_rtl_args,
    frame_records,
    rtl_inputs,
    sim_summary,
    simulate,
    write_sim_outputs,
)
from fastnms.sim.run import FrameResult


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
