"""cocotb test of fastnms_axi with DESCRIPTOR = "orb" in the live-camera mode (CTRL.LIVE):
frames back to back without an idle clock or any blanking, so each frame's first pixels
come while the frame before's last keypoints are in ORB; s_axis_video_tready must be
high on every clock, and every frame exact against orb_features (x, y, score, angle
bits, descriptor). Register writes of WIDTH, HEIGHT, BUDGET and THRESHOLD (the frame's
values) run back to back from 12 clocks before to 12 after each start of frame;
THRESHOLD and BUDGET change from frame to frame (written while the frame before comes
in).

Configuration from pytest (tb/top/test_axi.py::test_axi_orb_live): TB_GENERICS.
"""

from __future__ import annotations

import ast
import os
import random

import cocotb
import numpy as np
from cocotb.triggers import RisingEdge
from fastnms.golden.image import load_grey
from fastnms.sim import regs
from fastnms.sim.driver import AxiTop, record_words
from fastnms.sim.records import decode_records
from fastnms.testing import images as testimages

from tb.orb.patches import random_crop
from tb.top.axi_orb_tb import keypoints, model

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
W, H = GENERICS["MAX_WIDTH"], GENERICS["MAX_HEIGHT"]


@cocotb.test()
async def orb_live_back_to_back(dut):
    """LIVE with ORB: back-to-back frames (noise at t = 0 with every cell full at the
    engine's rate, photograph crops, a flat frame), tready high on every clock, register
    writes around every start of frame, every frame exact, nothing dropped."""
    tb = await AxiTop.create(dut, GENERICS, 0, 0)
    await tb.reset()
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    photos = [load_grey(p) for p in testimages.real_images()[:3]]
    crop = random_crop(random.Random(cocotb.RANDOM_SEED), photos, max(W, H))[:H, :W]
    frames = [
        (testimages.noise(rng, W, H), 0),
        (crop, 5),
        (testimages.noise(rng, W, H), 0),
        (np.full((H, W), 90, np.uint8), 20),
    ]
    budgets = [(16, 4), (32, 2), (32, 4), (16, 3)]
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask | regs.CTRL_LIVE.mask)

    low = 0

    async def ready_high() -> None:
        nonlocal low
        while True:
            await RisingEdge(dut.aclk)
            low += dut.s_axis_video_tready.value != 1

    async def writes_around_starts() -> None:
        """Back-to-back writes of the values in use from 12 clocks before to 12 after
        each start of frame after the first (frames follow each other every W x H
        clocks)."""
        while not tb.sof_clocks:
            await RisingEdge(dut.aclk)
        first = tb.sof_clocks[0]
        for k in range(1, len(frames)):
            while tb.cycle < first + k * W * H - 12:
                await RisingEdge(dut.aclk)
            cell, per_cell = budgets[k]
            budget = cell << regs.BUDGET_CELL.lsb | per_cell << regs.BUDGET_PER_CELL.lsb
            values = [(regs.WIDTH, W), (regs.HEIGHT, H), (regs.BUDGET, budget)]
            values.append((regs.THRESHOLD, frames[k][1]))
            i = 0
            while tb.cycle < first + k * W * H + 12:
                await tb.write(*values[i % len(values)])
                i += 1

    cocotb.start_soon(ready_high())
    hammer = cocotb.start_soon(writes_around_starts())
    sender = cocotb.start_soon(tb.send_frames(frames, budgets))
    got = await tb.receive(len(frames), 3 * W * H * len(frames) + 20_000)
    await sender
    await hammer
    starts = tb.sof_clocks[-len(frames) :]
    gaps = {b - a for a, b in zip(starts[:-1], starts[1:], strict=True)}
    assert gaps == {W * H}, f"starts of frame {gaps} clocks apart: the input waited"
    assert low == 0 and tb.input_stalls == 0, f"tready low on {low} clocks"
    for i, (packet, (img, t), (cell, k)) in enumerate(zip(got, frames, budgets, strict=True)):
        (frame,) = decode_records(record_words(packet))
        assert frame.complete and not set(frame.flags) - {"orb", "empty"}, frame.flags
        want = model(img, t, cell, k)
        have = keypoints(frame)
        assert have == want or (not want and frame.empty), (
            f"frame {i} (t={t}, CELL {cell}, K {k}): {len(have)} keypoints, model {len(want)}"
        )
        dut._log.info(
            "frame %d (t=%d, CELL %d, K %d): %d keypoints, equal", i, t, cell, k, len(want)
        )
    assert await tb.read(regs.DROPPED) == 0
    assert await tb.read(regs.INPUT_STALLS) == 0
