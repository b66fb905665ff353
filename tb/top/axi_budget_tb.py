"""cocotb test of the keypoint budget through fastnms_axi (a build with
MAX_PER_CELL > 0), against the golden model's budget (fastnms.golden.budget) in the
block's output order (budget_frames).

Configuration beyond tb/top/axi_common.py's: TB_CROPS (photograph crops, a JSON list
of [path, w, h, t]).
"""

from __future__ import annotations

import json
import os
from pathlib import Path

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden.budget import hardware_order
from fastnms.sim import regs
from fastnms.sim.driver import Record, video_lines
from fastnms.testing import images as testimages

from tb.top.axi_common import (
    MAX_HEIGHT,
    MAX_PER_CELL,
    MAX_WIDTH,
    MIN_WIDTH,
    PPC,
    STALL,
    TB,
    TIMEOUT_MS,
    all_generics,
    golden,
    whole_beats,
)


def budget_golden(img: np.ndarray, t: int, budget: tuple[int, int]) -> list[Record]:
    """The records of the budgeted frame, in the block's output order; PER_CELL above
    MAX_PER_CELL is clamped as the register does."""
    cell, k = budget
    kept = hardware_order(np.array(golden(img, t), dtype=np.int64), cell, min(k, MAX_PER_CELL))
    return [tuple(int(v) for v in r) for r in kept.tolist()]


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def budget_frames(dut):
    """The keypoint budget through the top (a build with MAX_PER_CELL > 0): frames
    back to back with a different BUDGET each (every CELL, K from 0 to above
    MAX_PER_CELL), photograph crops, noise at threshold 0 at full width, against the
    golden model's budget in the block's order; then LIVE mode with the heaviest
    record stream (noise at t = 0, full width, CELL 16, K = MAX_PER_CELL): tready high
    on every clock; then aresetn in the middle of a budgeted frame."""
    assert MAX_PER_CELL > 0, "a build with the budget"
    tb = await TB.create(dut)
    await tb.reset()
    rng = tb.np_rng
    crops = json.loads(os.environ.get("TB_CROPS", "[]"))
    images = [
        testimages.noise(rng, MAX_WIDTH, MAX_HEIGHT),
        *[testimages.crop(Path(p), cw, ch) for p, cw, ch, _ in crops],
        testimages.blurred_noise(rng, whole_beats(MAX_WIDTH // 2 + 3), MAX_HEIGHT // 2),
        testimages.checkerboard(rng, whole_beats(40), 30),
    ]
    frames, budgets = [], []
    choices = [(16, 1), (32, 2), (64, MAX_PER_CELL), (128, 3), (256, 1), (16, 0), (16, 15)]
    for i, (cell, k) in enumerate(choices):
        img = images[i % len(images)]
        t = 0 if i == 0 else int(tb.rng.choice([0, 10, 20]))
        frames.append((img, t))
        budgets.append((cell, k))
    sender = cocotb.start_soon(tb.send_frames(frames, budgets))
    total = sum(img.size for img, _ in frames)
    got = await tb.receive(len(frames), 20 * total + 20000)
    await sender
    for i, ((img, t), budget, frame) in enumerate(zip(frames, budgets, got, strict=True)):
        want = budget_golden(img, t, budget)
        tb.check_frame(
            frame, want, f"budget {budget} frame {i} ({img.shape[1]}x{img.shape[0]} t={t})"
        )
        dut._log.info("budget %s: %d of %d records", budget, len(want), len(golden(img, t)))
    assert regs.BUDGET_PER_CELL.get(await tb.read(regs.BUDGET)) == min(15, MAX_PER_CELL)

    # Frames without records piling up behind a stopped output (the first frame
    # fills the corner FIFO), each with its own budget, then a frame whose records
    # show which budget it got: the budgets stay with their frames.
    flat = testimages.constant(rng, MIN_WIDTH, 7)
    last = testimages.noise(rng, MAX_WIDTH, 32)
    frames = [(last, 0)] + [(flat, 10)] * 8 + [(last, 0)]
    budgets = [(16, 15)] + [(16 << (i % 5), i % 16) for i in range(8)] + [(32, 1)]
    tb.sink.pause = True
    sender = cocotb.start_soon(tb.send_frames(frames, budgets))
    await ClockCycles(dut.aclk, 2 * last.size + 30 * 8 * flat.size)
    tb.set_stall(STALL)
    got = await tb.receive(len(frames), 80 * last.size + 20000)
    await sender
    for i, ((img, t), budget, frame) in enumerate(zip(frames, budgets, got, strict=True)):
        tb.check_frame(frame, budget_golden(img, t, budget), f"piled-up frame {i}")

    # LIVE: the heaviest stream, the input never waits.
    tb.set_stall(0)
    noise = testimages.noise(rng, MAX_WIDTH, 40)
    budget = (16, MAX_PER_CELL)
    await tb.configure(MAX_WIDTH, 40, 0, budget)
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask | regs.CTRL_LIVE.mask)
    stalls = tb.input_stalls
    for _ in range(3):
        await tb.send_lines(video_lines(noise, PPC))
    got = await tb.receive(3, 20 * noise.size)
    for frame in got:
        tb.check_frame(frame, budget_golden(noise, 0, budget), "LIVE, noise at t = 0")
    assert tb.input_stalls == stalls, f"{tb.input_stalls - stalls} input stalls in LIVE mode"
    assert await tb.read(regs.DROPPED) == 0
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask)
    tb.set_stall(STALL)

    # aresetn while a budgeted frame's records are in flight.
    await tb.configure(MAX_WIDTH, 40, 0, (32, 2))
    await tb.send_lines(video_lines(noise, PPC))
    while not tb.sink.active and tb.sink.empty():
        await RisingEdge(dut.aclk)
    await ClockCycles(dut.aclk, 5)
    await tb.reset()
    assert await tb.read(regs.BUDGET) == regs.reset_value("BUDGET", all_generics())
    img = testimages.blurred_noise(rng, MAX_WIDTH, 40)
    await tb.check_frames([(img, 10)], "after aresetn, budget off", opencv=False)
    frames = [(img, 10), (testimages.noise(rng, 40, 30), 5)]
    budgets = [(64, 1), (16, 2)]
    sender = cocotb.start_soon(tb.send_frames(frames, budgets))
    got = await tb.receive(2, 40 * MAX_WIDTH * 40)
    await sender
    for (img, t), budget, frame in zip(frames, budgets, got, strict=True):
        tb.check_frame(frame, budget_golden(img, t, budget), f"after aresetn, budget {budget}")
