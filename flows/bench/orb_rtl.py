"""ORB in the AXI top (issue 36): opencv + 3x3 built with DESCRIPTOR orb on the bench
frames at each (CELL, K) of ORB_BUDGETS; every record's position, score, angle bits and
descriptor against the golden model (the golden ORB against cv2.ORB is flows/bench/orb.py)."""

from __future__ import annotations

import time

import numpy as np
from fastnms.golden.orb import orb_features
from fastnms.sim.run import SimError, generics_for, run_rtl

from flows.bench.engine import BenchError, build_engines, record_text, status_errors

# ORB in the top (issue 36): opencv + 3x3 with DESCRIPTOR orb, the command line's ORB
# build (generics_for(..., orb=True): MAX_PER_CELL 15, ORB_MAX_CELL 32), on the bench
# frames at each (CELL, K): 4 per 16x16 is the engine's rate bound (a keypoint every
# 64 clocks: K <= CELL * CELL / 64), 15 per 32x32 the most K the budget takes.
ORB_BUDGETS = [(16, 4), (32, 15)]


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
            f"{len(want.records)}; first difference at keypoint {at}: "
            f"RTL {record_text(got, at)}, golden {record_text(want.records, at)}"
        )
    angles = frame.angle_bits != want.angles.view(np.uint32)
    bits = np.unpackbits(frame.descriptors ^ want.descriptors, axis=1).sum(axis=1)
    bad = np.flatnonzero(angles | (bits > 0))
    if bad.size:
        i = int(bad[0])
        raise BenchError(
            f"{what}: angle or descriptor of {bad.size} of {len(got)} keypoints differ from "
            f"the golden's; the first at {record_text(got, i)}: angle bits "
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
