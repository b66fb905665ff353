"""cocotb testbench of fastnms_axi with DESCRIPTOR = "orb": video in through
cocotbext-axi, ORB keypoint records out in record format 2 (REC_ORB_BEATS beats each),
decoded by fastnms.sim.records and compared with golden/orb.py's orb_features in the
budget's order: x, y, score, the angle's float32 bits and the 32 descriptor bytes. The
AXI protocol checker follows the beats (TLAST on the frame's last beat only).

Configuration from pytest (tb/top/test_axi.py): TB_GENERICS, TB_IDLE, TB_STALL, TB_OUT
(the record words received are written there, one frame's words per line, for the C
decoder's check).
"""

from __future__ import annotations

import ast
import json
import os
import random
from pathlib import Path

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles
from fastnms.golden import orb
from fastnms.golden.image import load_grey
from fastnms.sim import regs
from fastnms.sim.driver import AxiTop, record_words
from fastnms.sim.records import Frame, decode_records
from fastnms.sim.run import budget_in_effect
from fastnms.testing import images as testimages

from tb.orb.patches import budget_order, random_crop

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH, MAX_HEIGHT = GENERICS["MAX_WIDTH"], GENERICS["MAX_HEIGHT"]
SCORE, NMS = GENERICS["SCORE"], GENERICS["NMS"]
MAX_PER_CELL = GENERICS["MAX_PER_CELL"]
ORB_MAX_CELL = GENERICS.get("ORB_MAX_CELL", 16)
# TB_FULL=1: a fourth frame (CELL 256, clamped) and a frame after the drops.
FULL = os.environ.get("TB_FULL", "0") == "1"
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))
# Clocks a frame may take at most here: the pixels at the worst idle rate, and each
# keypoint's ORB time (a few hundred clocks at the worst stall rate).
FRAME_CLOCKS = 4 * MAX_WIDTH * MAX_HEIGHT + 20_000


def model(img: np.ndarray, t: int, cell: int, k: int) -> list[tuple]:
    """orb_features' keypoints in the budget's order: (x, y, score, angle bits, descriptor
    as an int, bit i = pair i); CELL and K clamped as the BUDGET register does
    (ORB_MAX_CELL, MAX_PER_CELL, the ORB engine's rate)."""
    cell, k = budget_in_effect(cell, k, GENERICS)
    return budget_order(orb.orb_features(img, t, SCORE, NMS, cell=cell, per_cell=k), cell)


def keypoints(frame: Frame) -> list[tuple]:
    """A decoded frame's keypoints in the same form as model()."""
    assert frame.orb or not frame.corners, "keypoint records without ORB"
    return [
        (x, y, s, a, int.from_bytes(d, "little"))
        for (x, y, s), a, d in zip(frame.corners, frame.angle_bits, frame.descriptors, strict=True)
    ]


class TB(AxiTop):
    def __init__(self, dut, generics, idle, stall):
        super().__init__(dut, generics, idle, stall)
        self.words: list[list[int]] = []  # every frame's words, in order

    async def frames(self, count: int) -> list[Frame]:
        """The next `count` corner frames, decoded; each is one AXI4-Stream packet."""
        got = []
        for packet in await self.receive(count, count * FRAME_CLOCKS):
            words = record_words(packet)
            self.words.append(words)
            (frame,) = decode_records(words)
            assert frame.complete and not frame.malformed, f"frame flags {frame.flags}"
            got.append(frame)
        return got

    def check(self, frame: Frame, want: list[tuple], label: str) -> None:
        if not want:
            assert frame.empty and frame.words == 1, f"{label}: not the EMPTY record"
            self.dut._log.info("%s: no keypoint, the EMPTY record", label)
            return
        have = keypoints(frame)
        for i, (h, w) in enumerate(zip(have, want, strict=False)):
            assert h[:3] == w[:3], f"{label}: record {i}: rtl {h[:3]}, model {w[:3]}"
            assert h[3] == w[3], f"{label}: {w[:2]}: angle {h[3]:08x}, model {w[3]:08x}"
            assert h[4] == w[4], f"{label}: {w[:2]}: descriptor bits {h[4] ^ w[4]:064x} differ"
        assert len(have) == len(want), f"{label}: {len(have)} keypoints, model {len(want)}"
        assert frame.words == len(want) * regs.REC_ORB_BEATS
        assert not (frame.overflow or frame.aborted), f"{label}: flags {frame.flags}"
        self.dut._log.info("%s: %d keypoints, equal", label, len(want))

    def save(self) -> None:
        if "TB_OUT" in os.environ:
            Path(os.environ["TB_OUT"]).write_text(json.dumps(self.words))


@cocotb.test()
async def orb_records(dut):
    """MODE and BUDGET read back ORB; frames back to back (a photograph crop, noise at
    t = 0, a flat frame: the EMPTY record), each with its CELL and K, with input idles
    and output stalls; then K = 0 on noise with the output stopped: the core's ORB stage
    drops keypoints, counted in DROPPED and flagged OVERFLOW on the frame's last record,
    the others exact and in raster order; then a frame exact again."""
    tb = await TB.create(dut, GENERICS, IDLE, STALL)
    await tb.reset()
    rng = random.Random(cocotb.RANDOM_SEED)
    nrng = np.random.default_rng(rng.getrandbits(32))
    w, h = MAX_WIDTH, MAX_HEIGHT
    photos = [load_grey(p) for p in testimages.real_images()[:3]]

    mode = await tb.read(regs.MODE)
    assert regs.MODE_DESCRIPTOR.get(mode) == regs.MODE_DESCRIPTOR_VALUES["orb"]
    # BUDGET reads back the (CELL, K) in use: CELL at most ORB_MAX_CELL, K at most
    # MAX_PER_CELL and the engine's rate at that CELL (4 at CELL 16).
    for cell in (256, 16):
        await tb.write(regs.BUDGET, cell << regs.BUDGET_CELL.lsb | 15 << regs.BUDGET_PER_CELL.lsb)
        budget = await tb.read(regs.BUDGET)
        got = regs.BUDGET_CELL.get(budget), regs.BUDGET_PER_CELL.get(budget)
        assert got == budget_in_effect(cell, 15, GENERICS), f"BUDGET 0x{budget:08x}"

    crop = random_crop(rng, photos, max(w, h))[:h, :w]
    frames = [
        (crop, 5),
        (testimages.noise(nrng, w, h), 0),
        (np.full((h, w), 77, np.uint8), 20),
        (testimages.blurred_noise(nrng, w, h), 3),
    ]
    budgets = [(16, MAX_PER_CELL), (32, 2), (16, 4), (256, 1)]
    if not FULL:
        frames, budgets = frames[:3], budgets[:3]
    sender = cocotb.start_soon(tb.send_frames(frames, budgets))
    got = await tb.frames(len(frames))
    await sender
    for i, ((img, t), (cell, k), frame) in enumerate(zip(frames, budgets, got, strict=True)):
        tb.check(frame, model(img, t, cell, k), f"frame {i} (t={t} CELL {cell} K {k})")
    assert await tb.read(regs.DROPPED) == 0

    # K = 0: nothing bounds the keypoints; with the output stopped the core's ORB queue
    # fills and drops keypoints (never holds them: that could deadlock the budget).
    noise = testimages.noise(nrng, w, h)
    tb.set_stall(0)
    tb.sink.pause = True
    sender = cocotb.start_soon(tb.send_frames([(noise, 0)], [(16, 0)]))
    await ClockCycles(dut.aclk, noise.size + 4000)
    tb.set_stall(STALL)
    (frame,) = await tb.frames(1)
    await sender
    want = sorted(model(noise, 0, 16, 0), key=lambda r: (r[1], r[0]))
    have = keypoints(frame)
    dropped = await tb.read(regs.DROPPED)
    kept = set(have)
    assert all(r in set(want) for r in have), "a keypoint that is not the model's"
    assert have == [r for r in want if r in kept], "keypoints out of raster order"
    assert dropped == len(want) - len(have) > 0, (
        f"DROPPED {dropped}, missing {len(want) - len(have)}"
    )
    assert frame.overflow, "keypoints dropped but no OVERFLOW on the frame's last record"
    assert regs.STATUS_OVERFLOW.get(await tb.status())
    dut._log.info(
        "K = 0, output stopped: %d of %d keypoints, %d dropped", len(have), len(want), dropped
    )

    # And the next frame is whole again, its last record without OVERFLOW.
    if not FULL:
        tb.save()
        return
    sender = cocotb.start_soon(tb.send_frames([(crop, 5)], [(16, 3)]))
    (frame,) = await tb.frames(1)
    await sender
    tb.check(frame, model(crop, 5, 16, 3), "after the drops")
    tb.save()
