"""cocotb testbench of fastnms_record_output: the core's keypoint stream in, record
beats out, decoded by fastnms.sim.records (the Python twin of the C decoder) and
compared with the keypoints sent: x, y, score, with AREA the area (0 without, whatever
in_area is) and, with DESCRIPTOR "orb", the angle bits and the 32 descriptor bytes;
out_last on each frame's last beat only; the status outputs counted clock by clock
(sent_record, sent_last, dropped). Random input idles and output stalls, seeded (logged).

- hold: live = 0, frames of 0 .. 20 keypoints (empty frames included) with the
  output stopped at times: nothing lost, in_ready low while the FIFO is full.
- orb_drops: keypoints the core's ORB stage drops (in_dropped): counted in dropped,
  flagged OVERFLOW on their frame's last record, every record exact.
- live: live = 1 with the output stopped: in_ready never low, the records that come
  out are the frame's in order, each exact; dropped counts every keypoint missing
  (and every in_dropped pulse, some on the clock of a FIFO drop; both at most one
  per 8 clocks, as with ORB); the last record
  carries OVERFLOW; the next frame is whole again.
- abort: a soft reset (abort) while a record is held: the frame closes with an
  ABORTED record, and the next frame is exact.
"""

from __future__ import annotations

import ast
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.sim.records import Frame, decode_records

from tb.stream import StreamSink, StreamSource, value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
X_BITS, Y_BITS = GENERICS["X_BITS"], GENERICS["Y_BITS"]
SCORE_BITS = GENERICS["SCORE_BITS"]
ORB = GENERICS["DESCRIPTOR"] == "orb"
AREA = GENERICS.get("AREA", False)

Keypoint = tuple[int, int, int, int, int, int]  # x, y, score, angle bits, descriptor, area
END_OF_FRAME = {"x": 0, "y": 0, "score": 0, "angle": 0, "descriptor": 0, "area": 0, "eof": 1}


def _beat(k: Keypoint) -> dict[str, int]:
    x, y, s, a, d, area = k
    return {"x": x, "y": y, "score": s, "angle": a, "descriptor": d, "area": area, "eof": 0}


class TB:
    def __init__(self, dut):
        self.dut = dut
        self.rng = random.Random(cocotb.RANDOM_SEED)
        dut._log.info("seed=%d generics %s", cocotb.RANDOM_SEED, GENERICS)
        cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
        dut.in_valid.value = 0
        dut.out_ready.value = 0
        for name in ("pipe_rst", "abort", "live", "in_eof", "in_dropped", "in_error"):
            getattr(dut, name).value = 0
        for name in ("in_x", "in_y", "in_score", "in_area", "in_angle", "in_descriptor"):
            getattr(dut, name).value = 0
        self.source = StreamSource(dut, dut.clk, "in", self.rng, idle=0.25)
        self.sink = StreamSink(dut, dut.clk, "out", ["data", "last"], self.rng, stall=0.3)
        self.counts = {"dropped": 0, "sent_record": 0, "sent_last": 0}
        self.ready_low = 0  # clocks with in_ready low (counted while watched)
        self.watch_ready = False

    async def start(self) -> None:
        dut = self.dut
        dut.rst.value = 1
        dut.pipe_rst.value = 1
        await ClockCycles(dut.clk, 3)
        dut.rst.value = 0
        dut.pipe_rst.value = 0
        await RisingEdge(dut.clk)
        cocotb.start_soon(self.sink.run())
        cocotb.start_soon(self.monitor())

    async def monitor(self) -> None:
        dut = self.dut
        while True:
            await RisingEdge(dut.clk)
            for name in self.counts:
                self.counts[name] += value(getattr(dut, name))
            if self.watch_ready and not value(dut.in_ready):
                self.ready_low += 1

    def keypoints(self, n: int) -> list[Keypoint]:
        r = self.rng
        return [
            (
                r.randrange(1 << X_BITS),
                r.randrange(1 << Y_BITS),
                r.randrange(1 << SCORE_BITS),
                r.getrandbits(32),
                r.getrandbits(256),
                r.choice([0, 1, 2047, r.randrange(2048)]),
            )
            for _ in range(n)
        ]

    async def stop_output(self, clocks: int) -> None:
        self.sink.stall = 1.0
        await ClockCycles(self.dut.clk, clocks)
        self.sink.stall = 0.3

    async def send_frame(self, kps: list[Keypoint]) -> None:
        await self.source.send([_beat(k) for k in kps] + [END_OF_FRAME])

    async def drain(self, frames: int, timeout: int = 20_000) -> list[Frame]:
        """Wait until `frames` frames have come out (and the block is idle); the frames."""
        self.sink.stall = 0.3
        for _ in range(timeout):
            await RisingEdge(self.dut.clk)
            if self.counts["sent_last"] >= frames and not value(self.dut.busy):
                break
        else:
            raise AssertionError(f"{self.counts['sent_last']} of {frames} frames came out")
        await ClockCycles(self.dut.clk, 4)
        words = [b["data"] for b in self.sink.beats]
        lasts = [b["last"] for b in self.sink.beats]
        decoded = decode_records(words)
        ends = [f.first_word + f.words - 1 for f in decoded]
        assert [i for i, last in enumerate(lasts) if last] == ends, "out_last not on frame ends"
        return decoded


def expected(kps: list[Keypoint]) -> list[tuple]:
    """The keypoints as a decoded frame shows them (no payload without ORB, no area
    without AREA)."""
    return [
        (x, y, s, a, d, area if AREA else 0) if ORB else (x, y, s, 0, 0, area if AREA else 0)
        for x, y, s, a, d, area in kps
    ]


def received(frame: Frame) -> list[tuple]:
    assert frame.orb == (ORB and bool(frame.corners)), f"ORB flag {frame.orb}"
    areas = [int(a) for a in frame.areas]
    if not frame.orb:
        return [(x, y, s, 0, 0, area) for (x, y, s), area in zip(frame.corners, areas, strict=True)]
    return [
        (x, y, s, a, int.from_bytes(d, "little"), area)
        for (x, y, s), a, d, area in zip(
            frame.corners, frame.angle_bits, frame.descriptors, areas, strict=True
        )
    ]


def check_whole(frame: Frame, kps: list[Keypoint], overflow: bool = False) -> None:
    assert not frame.malformed and not frame.aborted and frame.complete, frame.flags
    assert frame.empty == (not kps), frame.flags
    assert frame.overflow == overflow, frame.flags
    assert received(frame) == expected(kps)


@cocotb.test()
async def hold(dut):
    """live = 0: every record of every frame, exact, whatever the output does."""
    tb = TB(dut)
    await tb.start()
    sent = []
    for i in range(8):
        kps = tb.keypoints(tb.rng.choice([0, 1, 2, 7, 20]) if i else 0)
        sent.append(kps)
        # The output stopped for 60 clocks during half of the frames: the FIFO fills.
        if i % 2:
            cocotb.start_soon(tb.stop_output(60))
        tb.watch_ready = True
        await tb.send_frame(kps)
    frames = await tb.drain(len(sent))
    assert len(frames) == len(sent)
    for frame, kps in zip(frames, sent, strict=True):
        check_whole(frame, kps)
    n = sum(len(k) for k in sent)
    assert tb.counts == {"dropped": 0, "sent_record": n, "sent_last": len(sent)}, tb.counts
    assert tb.ready_low > 0, "the FIFO never filled: the test did not stop the output"
    dut._log.info("%d frames, %d keypoints, in_ready low %d clocks", len(sent), n, tb.ready_low)


async def pulse(dut, clocks: list[int], signal) -> None:
    """signal high for one clock at each of the given clock offsets from now."""
    now = 0
    for c in sorted(clocks):
        await ClockCycles(dut.clk, c - now)
        signal.value = 1
        await RisingEdge(dut.clk)
        signal.value = 0
        now = c + 1


@cocotb.test()
async def orb_drops(dut):
    """Keypoints dropped upstream: counted and flagged on their frame's LAST record."""
    tb = TB(dut)
    await tb.start()
    kps = tb.keypoints(6)
    drops = sorted(tb.rng.sample(range(2, 40), 3))
    cocotb.start_soon(pulse(dut, drops, dut.in_dropped))
    await ClockCycles(dut.clk, 45)  # the pulses fall before the frame's end of frame
    await tb.send_frame(kps)
    clean = tb.keypoints(3)
    await tb.send_frame(clean)
    frames = await tb.drain(2)
    check_whole(frames[0], kps, overflow=True)
    check_whole(frames[1], clean)
    assert tb.counts == {"dropped": 3, "sent_record": 9, "sent_last": 2}, tb.counts


@cocotb.test()
async def live(dut):
    """live = 1, the output stopped: the input is never held, drops are counted."""
    tb = TB(dut)
    await tb.start()
    dut.live.value = 1
    tb.watch_ready = True
    tb.sink.stall = 1.0
    kps = tb.keypoints(40)
    # Keypoints 8 clocks apart and upstream drops among the FIFO drops, some on
    # the same clock: as the core's ORB stage spaces them (its time per keypoint).
    upstream = 0
    for i, k in enumerate(kps):
        if i % 2 == 0:
            upstream += 1
            cocotb.start_soon(pulse(dut, [tb.rng.randrange(8)], dut.in_dropped))
        await tb.source.send([_beat(k)])
        await ClockCycles(dut.clk, 7)
    await ClockCycles(dut.clk, 10)
    await tb.source.send([END_OF_FRAME])
    frames = await tb.drain(1)
    out = received(frames[0])
    assert frames[0].overflow and not frames[0].malformed, frames[0].flags
    it = iter(expected(kps))
    assert all(k in it for k in out), "the records out are not the frame's, in order"
    assert out[-1] == expected(kps)[-1], "the frame's last keypoint was dropped"
    assert tb.counts["dropped"] == len(kps) - len(out) + upstream, (tb.counts, len(out))
    assert tb.ready_low == 0, f"in_ready low {tb.ready_low} clocks with live = 1"
    dut._log.info(
        "live: %d of %d keypoints out, %d dropped", len(out), len(kps), tb.counts["dropped"]
    )
    # The next frame, with room: whole.
    tb.sink.beats.clear()
    tb.counts["sent_last"] = 0
    again = tb.keypoints(5)
    await tb.send_frame(again)
    frames = await tb.drain(1)
    check_whole(frames[0], again)


@cocotb.test()
async def abort(dut):
    """A soft reset with a record held closes the frame as ABORTED."""
    tb = TB(dut)
    await tb.start()
    kps = tb.keypoints(4)
    await tb.source.send([_beat(k) for k in kps])
    await ClockCycles(dut.clk, 3)
    assert value(dut.open_frame), "no record held"
    dut.abort.value = 1
    dut.pipe_rst.value = 1
    for _ in range(20):
        await RisingEdge(dut.clk)
        if not value(dut.open_frame):
            break
    else:
        raise AssertionError("open_frame stayed high under abort")
    dut.abort.value = 0
    dut.pipe_rst.value = 0
    await RisingEdge(dut.clk)
    after = tb.keypoints(2)
    await tb.send_frame(after)
    frames = await tb.drain(2)
    assert frames[0].aborted and not frames[0].malformed, frames[0].flags
    assert received(frames[0]) == expected(kps)
    check_whole(frames[1], after)
    assert tb.counts == {"dropped": 0, "sent_record": 6, "sent_last": 2}, tb.counts
