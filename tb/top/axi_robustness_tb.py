"""cocotb tests of fastnms_axi under misuse and resets: malformed frames
(malformed_then_good), aresetn and soft reset mid-frame (reset_mid_frame), interrupt
and CTRL.ENABLE (interrupt_and_enable), the corner FIFO filling (fifo_full), every
VALID low in reset (valids_low_in_reset).

Configuration beyond tb/top/axi_common.py's: TB_CASES (malformed_then_good: a
comma-separated subset of its malformed kinds, to debug one; all when unset).
"""

from __future__ import annotations

import os

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
    SCORE_VIDEO,
    STALL,
    TB,
    TIMEOUT_MS,
    golden,
    good_image,
    whole_beats,
)


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def malformed_then_good(dut):
    """Each kind of malformed input sets its STATUS bit, never locks up, and
    the well-formed frame after it is exact."""
    tb = await TB.create(dut)
    await tb.reset()
    w, h, t = whole_beats(min(MAX_WIDTH, 20)), min(MAX_HEIGHT, 12), 10
    await tb.configure(w, h, t)
    n = PPC  # bytes per beat: the cases below cut and add whole beats
    mid = min(5, w // n - 2)  # a beat inside a line

    def lines(img):
        return video_lines(img, PPC)

    def short_line(img):
        out = lines(img)
        out[4] = AxiStreamFrame(out[4].tdata[: -3 * n], tuser=[0] * (w - 3 * n))
        return out

    def long_line(img):
        out = lines(img)
        out[5] = AxiStreamFrame(out[5].tdata + b"\x10\x20" * n, tuser=[0] * (w + 2 * n))
        return out

    def no_tlast(img):  # lines 2 and 3 as one packet: no tlast at the end of line 2
        out = lines(img)
        merged = AxiStreamFrame(out[2].tdata + out[3].tdata, tuser=[0] * (2 * w))
        return out[:2] + [merged] + out[4:]

    def no_tuser(img):
        return [AxiStreamFrame(p.tdata, tuser=[0] * w) for p in lines(img)]

    def cut_short(img):
        return lines(img)[: h - 3]

    def tuser_mid_frame(img):
        out = lines(img)
        tuser = [0] * mid * n + [1] * n + [0] * (w - (mid + 1) * n)
        out[4] = AxiStreamFrame(out[4].tdata, tuser=tuser)
        return out

    def extra_lines(img):
        return lines(img) + lines(img)[1:3]

    def cut_mid_line(img):
        out = lines(img)[:6]
        out[5] = AxiStreamFrame(out[5].tdata[: mid * n], tuser=[0] * mid * n)
        return out

    cases = [
        (short_line, {"EOL_EARLY"}),
        (long_line, {"EOL_LATE"}),
        (no_tlast, {"EOL_LATE", "SOF_EARLY"}),  # the frame looks one line short
        (no_tuser, {"SOF_MISSING"}),
        (cut_short, {"SOF_EARLY"}),
        (tuser_mid_frame, {"SOF_EARLY", "EOL_EARLY"}),
        (extra_lines, {"SOF_MISSING"}),
        (cut_mid_line, {"SOF_EARLY", "EOL_EARLY"}),
    ]
    only = os.environ.get("TB_CASES")
    for make, bits in cases:
        if only and make.__name__ not in only.split(","):
            continue
        bad = testimages.noise(tb.np_rng, w, h)
        good = good_image(tb, w, h)
        before = len(tb.last_records)
        await tb.send_lines(make(bad))
        await tb.send_lines(lines(good))
        await tb.idle_output()
        frames = []
        while not tb.sink.empty():
            frames.append(tb.sink.recv_nowait())
        # The malformed input gives at most two (well-formed) frames of junk.
        assert 1 <= len(frames) <= 3, f"{make.__name__}: {len(frames)} frames out"
        assert len(tb.last_records) - before == len(frames)
        for frame in frames:
            _, flags = decode(frame)
            assert flags[-1] & 0b010 and not any(f & 0b010 for f in flags[:-1]), make.__name__
        tb.check_frame(frames[-1], golden(good, t), f"good frame after {make.__name__}")
        errors = await tb.input_errors()
        assert errors == bits, f"{make.__name__}: STATUS errors {errors}, expected {bits}"
        await tb.clear_status()
        dut._log.info(
            "%s: %s, %d frame(s) out, the last one exact", make.__name__, sorted(bits), len(frames)
        )
    # A frame of the right size after all that, and the status stays clean.
    await tb.check_frames([(good_image(tb, w, h), t)], "final")
    assert await tb.input_errors() == set()


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def reset_mid_frame(dut):
    """aresetn in the middle of a frame (records in flight): the registers
    return to their reset values and the next frames are exact. Then a soft
    reset in the middle of a frame: the open output frame is closed with
    ABORTED, the rest of the input frame is discarded, the next frame is exact."""
    tb = await TB.create(dut)
    await tb.reset()
    w, h = min(MAX_WIDTH, 40), min(MAX_HEIGHT, 30)
    busy = testimages.noise(tb.np_rng, w, h)
    await tb.configure(w, h, 5)
    await tb.send_lines(video_lines(busy, PPC))
    while tb.sink.empty() and not tb.sink.active:
        await RisingEdge(dut.aclk)
    await ClockCycles(dut.aclk, 7)
    # Traffic on the first clock after aresetn rises (the DUT's own reset ends
    # up to 3 clocks later): a frame at the reset size and threshold, and
    # register reads, must neither be lost nor hang.
    await tb.reset(8, settle=0)
    first = testimages.blurred_noise(tb.np_rng, MAX_WIDTH, MAX_HEIGHT)
    await tb.send_lines(video_lines(first, PPC))
    assert await tb.read(regs.ID) == 0x46415354
    assert await tb.read(regs.THRESHOLD) == 20
    assert await tb.read(regs.WIDTH) == MAX_WIDTH
    assert await tb.read(regs.FRAME_COUNT) == 0
    (frame,) = await tb.receive(1, 20 * first.size)
    tb.check_frame(frame, golden(first, 20), "first frame after aresetn")
    frames = [(good_image(tb, w, h), 12), (testimages.saturated(tb.np_rng, w, h), 30)]
    await tb.check_frames(frames, "after aresetn")

    # Soft reset while records of a frame are waiting in the output.
    tb.set_stall(0.9)
    await tb.configure(w, h, 5)
    await tb.send_lines(video_lines(busy, PPC))
    while not tb.sink.active:
        await RisingEdge(dut.aclk)
    # Without KEY, or with KEY in a byte not strobed, the command does nothing.
    await tb.write(regs.CMD, regs.CMD_SOFT_RESET.mask)
    await tb.axil.write(regs.CMD, b"\x01")
    await tb.write(regs.CTRL, await tb.read(regs.CTRL))  # read-modify-write of CTRL
    assert await tb.read(regs.CMD) == 0
    await tb.soft_reset()
    tb.set_stall(STALL)
    await tb.idle_output()
    assert await tb.read(regs.CMD) == 0
    assert await tb.read(regs.CTRL) == regs.CTRL_ENABLE.mask
    cut = tb.sink.recv_nowait()
    assert tb.sink.empty()
    records, flags = decode(cut)
    assert flags[-1] == 0b110, f"soft reset: flags of the last record {flags[-1]:b}"
    (decoded,) = decode_records(record_words(cut))
    assert decoded.flags == ["aborted"] and decoded.corners == records
    assert not any(flags[:-1])
    want = golden(busy, 5)
    if NMS.startswith("region"):
        # Records leave as regions close, not in raster order; a closed
        # region's record is final.
        assert set(records) < set(want) and len(set(records)) == len(records)
    else:
        assert records == want[: len(records)] and len(records) < len(want)
    assert await tb.input_errors() == set()
    frames = [(good_image(tb, w, h), 12), (good_image(tb, 17, 11), 3)]
    await tb.check_frames(frames, "after soft reset")
    assert await tb.input_errors() == set()


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def interrupt_and_enable(dut):
    """interrupt follows FRAME_DONE when IRQ_ENABLE is set, clears with it;
    CTRL.ENABLE = 0 discards frames from their start of frame on."""
    tb = await TB.create(dut)
    await tb.reset()
    w, h, t = min(MAX_WIDTH, 24), min(MAX_HEIGHT, 10), 15
    img = good_image(tb, w, h)
    await tb.check_frames([(img, t)], "irq off")
    await ClockCycles(dut.aclk, 5)
    assert regs.STATUS_FRAME_DONE.get(await tb.status())
    assert dut.interrupt.value == 0
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask | regs.CTRL_IRQ_ENABLE.mask)
    await ClockCycles(dut.aclk, 2)
    assert dut.interrupt.value == 1
    await tb.write(regs.STATUS, regs.STATUS_FRAME_DONE.mask)
    await ClockCycles(dut.aclk, 2)
    assert dut.interrupt.value == 0

    # The interrupt rises a few clocks after the last record left.
    sender = cocotb.start_soon(tb.send_frames([(img, t)]))
    await tb.receive(1, 50 * w * h)
    last = tb.last_records[-1]
    while dut.interrupt.value == 0:
        await RisingEdge(dut.aclk)
        assert tb.cycle - last < 10, "no interrupt after the frame's last record"
    dut._log.info("interrupt %d clocks after the last record", tb.cycle - last)
    await sender
    await tb.write(regs.STATUS, regs.STATUS_FRAME_DONE.mask)
    await ClockCycles(dut.aclk, 2)
    assert dut.interrupt.value == 0

    # Disabled: frames are consumed and dropped; enabled again: processed.
    await tb.write(regs.CTRL, regs.CTRL_IRQ_ENABLE.mask)
    frames_before = await tb.read(regs.FRAME_COUNT)
    await tb.send_lines(video_lines(img, PPC))
    await tb.send_lines(video_lines(img, PPC))
    await tb.idle_output()
    assert tb.sink.empty() and dut.interrupt.value == 0
    await tb.write(regs.CTRL, regs.CTRL_ENABLE.mask)
    other = testimages.checkerboard(tb.np_rng, w, h)
    await tb.check_frames([(other, 40), (img, t)], "enabled again")
    await ClockCycles(dut.aclk, 5)
    assert await tb.read(regs.FRAME_COUNT) == frames_before + 2
    assert await tb.input_errors() == set()


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def fifo_full(dut):
    """A long stall of the corner output with a corner-rich image: the FIFO
    fills, the video input is stalled (tready low), OVERFLOW is set, and no
    record is lost or repeated."""
    tb = await TB.create(dut, 0, 0)
    await tb.reset()
    w, h = MAX_WIDTH, min(MAX_HEIGHT, 40)
    img = testimages.noise(tb.np_rng, w, h)
    t = 0
    want = golden(img, t)
    assert len(want) > 2 * FIFO_DEPTH + 20, f"only {len(want)} corners"
    tb.sink.pause = True
    stalls = tb.input_stalls
    sender = cocotb.start_soon(tb.send_frames([(img, t), (img, t)]))
    await ClockCycles(dut.aclk, 3 * w * h)
    assert tb.input_stalls - stalls > w, "the video input was not stalled"
    assert "OVERFLOW" in await tb.errors()
    dut._log.info(
        "%d records per frame; input stalled %d clocks with the output paused",
        len(want),
        tb.input_stalls - stalls,
    )
    tb.set_stall(0.5)
    got = await tb.receive(2, 40 * w * h)
    await sender
    for frame in got:
        tb.check_frame(frame, want, "after the FIFO filled")
    await tb.clear_status()


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def valids_low_in_reset(dut):
    """Every VALID of the top (corner records, score video, B, R) is low from the
    first clock edge at which aresetn is sampled low (the protocol checker asserts
    it on every edge of every test; here each one is high when aresetn falls)."""
    tb = await TB.create(dut, 0, 0)
    await tb.reset()
    w, h = min(MAX_WIDTH, 32), min(MAX_HEIGHT, 16)
    img = testimages.noise(tb.np_rng, w, h)
    outputs = ["m_axis_corners_tvalid", "s_axi_ctrl_bvalid", "s_axi_ctrl_rvalid"]
    if SCORE_VIDEO:
        outputs.append("m_axis_score_tvalid")
    for trial in range(3):
        await tb.configure(w, h, 0)
        tb.sink.pause = True
        await tb.send_lines(video_lines(img, PPC))

        async def rises(name: str) -> None:
            for _ in range(50 * w * h):
                await RisingEdge(dut.aclk)
                if getattr(dut, name).value == 1:
                    return
            raise AssertionError(f"{name} did not rise")

        await rises("m_axis_corners_tvalid")
        if tb.score_sink is not None:  # (a stalled score video stalls the pipeline)
            tb.score_sink.pause = True
            await rises("m_axis_score_tvalid")
        # Responses held: BREADY and RREADY low while a write and a read are answered.
        tb.axil.write_if.b_channel.pause = True
        tb.axil.read_if.r_channel.pause = True
        writing = cocotb.start_soon(tb.axil.write(regs.THRESHOLD, (9).to_bytes(4, "little")))
        reading = cocotb.start_soon(tb.axil.read(regs.ID, 4))
        await rises("s_axi_ctrl_bvalid")
        await rises("s_axi_ctrl_rvalid")
        assert all(getattr(dut, name).value == 1 for name in outputs)
        if trial:
            await ClockCycles(dut.aclk, trial)
        checked = tb.protocol.reset_edges
        writing.cancel()
        reading.cancel()
        await tb.reset(5 + trial)
        assert tb.protocol.reset_edges - checked == 5 + trial
        for name in outputs:
            assert getattr(dut, name).value == 0, name
        tb.axil.write_if.b_channel.pause = False
        tb.axil.read_if.r_channel.pause = False
        tb.set_stall(0)
        # And everything works after the reset.
        await tb.check_frames([(good_image(tb, w, h), 10)], f"after reset {trial}")
    assert tb.protocol.checked_edges > 1000
