"""cocotb tests of fastnms_axi's live-camera mode (CTRL.LIVE): the input never
held, records that do not fit dropped, counted and flagged (live_mode); THRESHOLD
writes landing around a start of frame take effect on a frame boundary
(live_config_writes). Shared driver and configuration: tb/top/axi_common.py.
"""

from __future__ import annotations

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge
from cocotbext.axi import AxiStreamFrame
from fastnms.sim import regs
from fastnms.sim.driver import decode, record_words, video_lines
from fastnms.sim.records import decode_records
from fastnms.testing import images as testimages

from tb.top.axi_common import (
    FIFO_DEPTH,
    MAX_HEIGHT,
    MAX_WIDTH,
    NMS,
    PPC,
    STALL,
    TB,
    TIMEOUT_MS,
    golden,
    good_image,
    whole_beats,
)


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def live_mode(dut):
    """CTRL.LIVE = 1: with the corner sink stalled, s_axis_video_tready stays high
    for whole frames; records that do not fit are dropped, counted exactly in
    DROPPED, flagged (STATUS.OVERFLOW, OVERFLOW on the LAST record); the frames
    after the sink resumes are exact. INPUT_STALLS equals the clocks the testbench
    saw tvalid high and tready low."""
    tb = await TB.create(dut, 0, 0)
    await tb.reset()
    w, h, t = MAX_WIDTH, min(MAX_HEIGHT, 48), 0
    img = testimages.noise(tb.np_rng, w, h)
    want = golden(img, t)
    assert len(want) > FIFO_DEPTH + 8, f"only {len(want)} corners"
    await tb.configure(w, h, t)
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask | regs.CTRL_LIVE.mask)
    tb.sink.pause = True
    n = 3
    # Not a clock of waiting, also at the first start of frame after the
    # configuration writes.
    stalls = tb.input_stalls
    for _ in range(n):
        await tb.send_lines(video_lines(img, PPC))
    while not tb.source.idle():
        await RisingEdge(dut.aclk)
    await ClockCycles(dut.aclk, 20 * w)  # the pipeline's tail (the region NMS flush)
    assert tb.input_stalls == stalls, f"{tb.input_stalls - stalls} input stalls in LIVE mode"
    assert "OVERFLOW" in await tb.errors()
    dropped = await tb.read(regs.DROPPED)

    tb.set_stall(STALL)
    await tb.idle_output()
    got = []
    while not tb.sink.empty():
        got.append(tb.sink.recv_nowait())
    assert 1 <= len(got) <= n, f"{len(got)} frames out of {n}"
    # The software decoder (fastnms.sim.records, twin of sw/fastnms.c) on these words.
    decoded = decode_records(w for frame in got for w in record_words(frame))
    assert [f.flags for f in decoded] == [["overflow"]] * len(got)
    assert [f.corners for f in decoded] == [decode(frame)[0] for frame in got]
    received = 0
    for i, frame in enumerate(got):
        records, flags = decode(frame)
        received += len(records)
        assert flags[-1] == 0b1010, f"frame {i}: LAST flags {flags[-1]:b}, OVERFLOW expected"
        assert not any(flags[:-1]), f"frame {i}: flags before LAST"
        if NMS.startswith("region"):
            assert set(records) <= set(want) and len(set(records)) == len(records)
        else:  # raster order: what is left is a subsequence of the golden records
            it = iter(want)
            assert all(r in it for r in records), f"frame {i}: records out of order"
    assert dropped == n * len(want) - received, (
        f"DROPPED {dropped}, expected {n} x {len(want)} - {received}"
    )
    dut._log.info(
        "LIVE: %d of %d frames out, %d records, %d dropped, no input stall",
        len(got),
        n,
        received,
        dropped,
    )

    # Frames after the sink resumed: exact; the first carries OVERFLOW only if whole
    # frames were lost before it.
    frames = [(good_image(tb, w, h), 10), (good_image(tb, 17, 11), 3)]
    sender = cocotb.start_soon(tb.send_frames(frames))
    after = await tb.receive(2, 400 * w * h)
    await sender
    for i, ((im, th), frame) in enumerate(zip(frames, after, strict=True)):
        words = record_words(frame)
        lost = i == 0 and len(got) < n
        assert regs.REC_OVERFLOW.get(words[-1]) == lost, f"frame {i}: OVERFLOW, lost {lost}"
        words[-1] &= ~regs.REC_OVERFLOW.mask
        exact = AxiStreamFrame(b"".join(v.to_bytes(8, "little") for v in words))
        tb.check_frame(exact, golden(im, th), f"after LIVE drops, frame {i}")
    assert await tb.read(regs.DROPPED) == dropped
    await ClockCycles(dut.aclk, 5)
    assert await tb.read(regs.INPUT_STALLS) == tb.input_stalls
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask)
    await tb.clear_status()


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def live_config_writes(dut):
    """CTRL.LIVE = 1, frames back to back without an idle clock, and THRESHOLD
    writes whose B response lands on every clock from 12 before to 12 after a
    start of frame: a frame whose first pixel is accepted after the write's B
    response takes the new value, a frame accepted before the write began the
    old one, one in between either (exactly); s_axis_video_tready is high on
    every clock."""
    tb = await TB.create(dut, 0, 0)
    await tb.reset()
    w, h = whole_beats(min(MAX_WIDTH, 24)), min(MAX_HEIGHT, 9)
    img = testimages.noise(tb.np_rng, w, h)
    thresholds = (5, 40)
    wants = [golden(img, t) for t in thresholds]
    assert wants[0] != wants[1]
    await tb.configure(w, h, thresholds[0])
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask | regs.CTRL_LIVE.mask)
    # The write's latency, from its start to its B handshake.
    start = tb.cycle
    await tb.write(regs.THRESHOLD, thresholds[0])
    latency = tb.b_clocks[-1] - start

    low = 0

    async def ready_high() -> None:
        nonlocal low
        while True:
            await RisingEdge(dut.aclk)
            low += dut.s_axis_video_tready.value != 1

    offsets = list(range(-12, 13))
    period = w * h // PPC
    sofs = len(tb.sof_clocks)
    cocotb.start_soon(ready_high())
    for _ in range(len(offsets) + 1):
        await tb.send_lines(video_lines(img, PPC))
    while len(tb.sof_clocks) == sofs:
        await RisingEdge(dut.aclk)
    first = tb.sof_clocks[sofs]
    writes = []  # (start clock, B clock, value)
    for k, offset in enumerate(offsets, start=1):
        target = first + k * period + offset - latency
        while tb.cycle < target:
            await RisingEdge(dut.aclk)
        begun = tb.cycle
        await tb.write(regs.THRESHOLD, thresholds[k % 2])
        writes.append((begun, tb.b_clocks[-1], k % 2))
    got = await tb.receive(len(offsets) + 1, 4 * (len(offsets) + 1) * period + 2000)
    frame_sofs = tb.sof_clocks[sofs:]
    assert frame_sofs == [first + k * period for k in range(len(offsets) + 1)], "input waited"
    assert low == 0, f"s_axis_video_tready low on {low} clocks"
    landed = set()
    for k, frame in enumerate(got):
        records, _ = decode(frame)
        if NMS.startswith("region"):  # records leave as regions close
            records = sorted(records, key=lambda r: (r[1], r[0]))
        used = [i for i, want in enumerate(wants) if records == (want or [(0, 0, 0)])]
        assert used, f"frame {k}: records of neither threshold"
        if k == 0:
            assert used == [0]
            continue
        begun, b_clock, value = writes[k - 1]
        sof = frame_sofs[k]
        if sof > b_clock:
            assert used == [value], (
                f"frame {k}: first pixel {sof - b_clock} clocks after B, old value"
            )
        elif sof <= begun:
            assert used == [1 - value], f"frame {k}: first pixel before the write, new value"
        landed.add(b_clock - sof)
    assert len(landed) >= 20 and min(landed) <= -10 and max(landed) >= 10, (
        f"B responses landed at {sorted(landed)} clocks from a start of frame"
    )
    dut._log.info("B responses at %s clocks from a start of frame", sorted(landed))
    assert await tb.read(regs.DROPPED) == 0
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask)
