"""cocotb testbench of fastnms_axi's internal errors: a build with a test-only fault
(generic TEST_FAULT) provokes one, and the test checks that the chip reports it and
recovers. For each fault:

- its STATUS bit is set (and no other internal error bit), the interrupt rises with
  CTRL.IRQ_ENABLE and stays up until that bit is cleared;
- exactly one frame's last record carries ERROR (the frame the error cut, closed with
  ABORTED, or the next frame when no record of the cut frame was held);
- the IP keeps running: the next frames are exact against the golden model, without
  flags, and the fault's bit is not set again.

Faults (tb/top/test_axi.py::test_axi_internal_error):
- rows (ORB): the feed never waits for room in its rows; a noise frame at t = 0 with
  the corner output stopped overwrites rows of keypoints not yet read (ORB_ROWS);
- tags (ORB): a tag queue of one record; noise at t = 0 (ORB_TAGS);
- count (ORB): the ORB stage does not count a keypoint that comes in while two are
  in flight; noise at t = 0 (ORB_COUNT);
- config (no ORB, with the budget): a configuration queue of one frame; two frames
  back to back (CONFIG_QUEUE).

And resets_mid_frame (a build without a fault): CMD.SOFT_RESET, then aresetn, each
while a noise frame's keypoints are in ORB; no internal error, the next frames exact.
"""

from __future__ import annotations

import ast
import os

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.sim import regs
from fastnms.sim.driver import AxiTop, record_words
from fastnms.sim.records import Frame, decode_records
from fastnms.testing import images as testimages

from tb.top.axi_common import golden
from tb.top.axi_orb_tb import keypoints, model

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
FAULT = GENERICS.get("TEST_FAULT", "none")
ORB = GENERICS.get("DESCRIPTOR", "none") == "orb"
MAX_WIDTH, MAX_HEIGHT = GENERICS["MAX_WIDTH"], GENERICS["MAX_HEIGHT"]
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))
BIT = {
    "rows": regs.STATUS_ORB_ROWS,
    "tags": regs.STATUS_ORB_TAGS,
    "count": regs.STATUS_ORB_COUNT,
    "config": regs.STATUS_CONFIG_QUEUE,
}
INTERNAL = list(BIT.values())
# The good frames: ORB's 31-pixel border leaves room for one keypoint at (60, 40).
GOOD_W, GOOD_H = (128, 80) if ORB else (MAX_WIDTH, MAX_HEIGHT)
# (CELL, K): K = 0 without ORB keeps every record, as the golden model without budget.
BUDGET = (16, 4) if ORB else (16, 0)


def flags(frame: Frame) -> set[str]:
    """The frame's flags that say something went wrong."""
    return set(frame.flags) - {"orb", "empty"}


def internal_bits(status: int) -> set[str]:
    return {name for name, field in BIT.items() if field.get(status)}


def dot_frame() -> np.ndarray:
    """A flat frame with one bright pixel: exactly one FAST corner, so no fault fires."""
    img = np.full((GOOD_H, GOOD_W), 50, np.uint8)
    img[40, 60] = 200
    return img


def want(img: np.ndarray, t: int) -> list[tuple]:
    if ORB:
        return model(img, t, *BUDGET)
    return golden(img, t)


def have(frame: Frame) -> list[tuple]:
    return keypoints(frame) if ORB else list(frame.corners)


class TB(AxiTop):
    async def wait_for_bit(self, field, clocks: int) -> None:
        for _ in range(clocks // 50):
            if field.get(await self.status()):
                return
            await ClockCycles(self.dut.aclk, 50)
        raise AssertionError(f"STATUS.{FAULT} not set within {clocks} clocks")

    async def drain(self, quiet: int = 400) -> list[Frame]:
        """The frames received until the output has been quiet for `quiet` clocks."""
        frames, still = [], 0
        while still < quiet:
            await ClockCycles(self.dut.aclk, 1)
            busy = self.dut.m_axis_corners_tvalid.value == 1 or not self.source.idle()
            still = 0 if busy else still + 1
            while not self.sink.empty():
                frames += decode_records(record_words(self.sink.recv_nowait()))
        return frames

    async def good(self, img: np.ndarray, t: int, label: str) -> Frame:
        sender = cocotb.start_soon(self.send_frames([(img, t)], [BUDGET]))
        (packet,) = await self.receive(1, 8 * img.size + 20_000)
        await sender
        (frame,) = decode_records(record_words(packet))
        assert frame.complete and not frame.malformed, f"{label}: flags {frame.flags}"
        got, expected = have(frame), want(img, t)
        assert got == expected or (not expected and frame.empty), (
            f"{label}: {len(got)} records, model {len(expected)}: {got[:3]} vs {expected[:3]}"
        )
        self.dut._log.info("%s: %d records, equal; flags %s", label, len(got), frame.flags)
        return frame

    async def provoke(self, rng) -> None:
        """Send what makes the fault fire, and wait until its STATUS bit is set."""
        field = BIT[FAULT]
        if FAULT == "config":
            imgs = [testimages.blurred_noise(rng, GOOD_W, GOOD_H) for _ in range(2)]
            sender = cocotb.start_soon(self.send_frames([(i, 10) for i in imgs], [BUDGET] * 2))
            await self.wait_for_bit(field, 20 * GOOD_W * GOOD_H)
        elif FAULT == "rows":
            # The corner output stopped until the frame is in: the engine stops, the rows
            # go on; with the output running again the stale keypoints are found.
            noise = testimages.noise(rng, MAX_WIDTH, MAX_HEIGHT)
            self.set_stall(0)
            self.sink.pause = True
            sender = cocotb.start_soon(self.send_frames([(noise, 0)], [BUDGET]))
            await ClockCycles(self.dut.aclk, noise.size + 2000)
            self.set_stall(STALL)
            await self.wait_for_bit(field, 40 * noise.size)
        else:
            noise = testimages.noise(rng, GOOD_W, GOOD_H)
            sender = cocotb.start_soon(self.send_frames([(noise, 0)], [BUDGET]))
            await self.wait_for_bit(field, 40 * noise.size)
        await sender


@cocotb.test()
async def internal_error(dut):
    """The fault fires: its STATUS bit, the interrupt, ERROR on one frame's last
    record; then frames exact again (see the module's docstring)."""
    tb = await TB.create(dut, GENERICS, IDLE, STALL)
    await tb.reset()
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask | regs.CTRL_IRQ_ENABLE.mask)
    good = dot_frame() if ORB else testimages.blurred_noise(rng, GOOD_W, GOOD_H)
    t = 20 if ORB else 10

    # Before the fault: exact, no flag, no internal error.
    frame = await tb.good(good, t, "before")
    assert not flags(frame) and not internal_bits(await tb.status())

    await tb.provoke(rng)
    cut = await tb.drain()
    after = await tb.good(good, t, "after the error")
    flagged = [f for f in [*cut, after] if f.error]
    assert len(flagged) == 1, f"ERROR on {len(flagged)} frames: {[f.flags for f in cut]}"
    assert not after.malformed
    if cut:
        assert cut[-1].error and cut[-1].aborted, f"the cut frame's flags: {cut[-1].flags}"
    status = await tb.status()
    assert internal_bits(status) == {FAULT}, f"STATUS 0x{status:08x}"
    dut._log.info(
        "%s: STATUS 0x%08x, %d frame(s) cut, ERROR on %s",
        FAULT,
        status,
        len(cut),
        "the cut frame" if cut else "the next frame",
    )

    # The interrupt: up while the fault's bit is set, FRAME_DONE cleared or not.
    await tb.write(regs.STATUS, regs.STATUS_FRAME_DONE.mask)
    await ClockCycles(dut.aclk, 4)
    assert dut.interrupt.value == 1, "the internal error does not hold the interrupt"
    await tb.write(regs.STATUS, BIT[FAULT].mask)
    await ClockCycles(dut.aclk, 4)
    assert dut.interrupt.value == 0, "the interrupt stays up after clearing the error"
    assert not internal_bits(await tb.status())

    # And the IP goes on: exact frames, no flag, no error again.
    for i in range(2):
        frame = await tb.good(good, t, f"next frame {i}")
        assert not flags(frame), f"next frame {i}: flags {frame.flags}"
    assert not internal_bits(await tb.status()), "the error fired again"


@cocotb.test()
async def resets_mid_frame(dut):
    """CMD.SOFT_RESET once a noise frame's first keypoint has left ORB (the others in
    ORB or behind it): the cut frame ends with ABORTED (without ERROR), no internal
    error bit, the next frames exact. Then aresetn in the same place: the next frames
    exact."""
    tb = await TB.create(dut, GENERICS, IDLE, STALL)
    await tb.reset()
    rng = np.random.default_rng(cocotb.RANDOM_SEED)
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask)
    good = dot_frame() if ORB else testimages.blurred_noise(rng, GOOD_W, GOOD_H)
    t = 20 if ORB else 10
    await tb.good(good, t, "before")

    for reset in ("soft", "aresetn"):
        noise = testimages.noise(rng, GOOD_W, GOOD_H)
        sender = cocotb.start_soon(tb.send_frames([(noise, 0)], [BUDGET]))
        # The frame's first keypoint leaves ORB: the others are in ORB or behind it.
        while dut.m_axis_corners_tvalid.value != 1:
            await RisingEdge(dut.aclk)
        await ClockCycles(dut.aclk, 20)
        if reset == "soft":
            await tb.soft_reset()
            await sender
            cut = await tb.drain()
            assert not any(f.error for f in cut), [f.flags for f in cut]
            assert len(cut) == 1 and cut[-1].aborted, [f.flags for f in cut]
        else:
            sender.cancel()
            await tb.reset(8)
            await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask)
            cut = await tb.drain()
            assert not cut, f"{len(cut)} frames after aresetn"
        assert not internal_bits(await tb.status()), f"{reset}: STATUS 0x{await tb.status():08x}"
        for i in range(2):
            frame = await tb.good(good, t, f"{reset}: next frame {i}")
            assert not flags(frame), f"{reset}: next frame {i}: flags {frame.flags}"
        dut._log.info("%s reset mid-frame: %d frame(s) cut, then exact", reset, len(cut))
