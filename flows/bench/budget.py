"""The keypoint budget in the AXI top: opencv + 3x3 built with MAX_PER_CELL 15 on the
bench frames at each (CELL, K) of BUDGETS; every frame's records against the golden
model's budget in the block's order."""

from __future__ import annotations

import numpy as np
from fastnms.golden.budget import hardware_order
from fastnms.golden.model import detect
from fastnms.sim import regs
from fastnms.sim.run import SimError, run_rtl

from flows.bench.engine import BenchError, bench_generics, build_engines, status_errors

BUDGETS = [(64, 4), (32, 2), (16, 1)]


def budget_bench(
    images: list[np.ndarray], threshold: int, width: int, height: int, check: bool
) -> dict:
    """opencv + 3x3 with the keypoint budget (MAX_PER_CELL 15) on the bench frames at
    each of BUDGETS: keypoints per frame, clocks per pixel, latency, input stalls;
    every frame's records against the golden model's budget in the block's order."""
    generics = {**bench_generics("opencv", "3x3", width, height), "MAX_PER_CELL": 15}
    build = build_engines([generics], 1)[0]
    rows = []
    for budget in BUDGETS:
        frames = [(img, threshold) for img in images]
        try:
            result = run_rtl(frames, "opencv", "3x3", generics=generics, budget=budget)
        except SimError as e:
            raise BenchError(f"budget {budget}: {e}") from None
        if status_errors(result.status):
            raise BenchError(f"budget {budget}: STATUS reports {status_errors(result.status)}")
        for i, (img, f) in enumerate(zip(images, result.frames, strict=True)):
            want = hardware_order(detect(img, threshold), *budget)
            words = [int(w) for w in f.words if not regs.REC_EMPTY.get(int(w))]
            got = [(regs.REC_X.get(w), regs.REC_Y.get(w), regs.REC_SCORE.get(w)) for w in words]
            if check and got != [tuple(r) for r in want.tolist()]:
                raise BenchError(f"budget {budget}, frame {i}: records differ from the golden's")
        fr = result.frames
        rows.append(
            {
                "cell": budget[0],
                "per_cell": budget[1],
                "cells": -(-width // budget[0]) * -(-height // budget[0]),
                "corners": [len(f.records) for f in fr],
                "input_clocks_per_pixel": (fr[-1].last_pixel - fr[0].first_pixel + 1)
                / sum(f.width * f.height for f in fr),
                "input_stalls": result.input_stalls,
                "latency_clocks": [f.last_record - f.last_pixel for f in fr],
                "checked": check,
            }
        )
    return {"generics": generics, "build_seconds": build, "rows": rows}
