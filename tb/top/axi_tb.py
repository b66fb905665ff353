"""cocotb testbench of fastnms_axi, the AXI top level: video in through
cocotbext-axi's AxiStreamSource, corner records (and the score video) out
through AxiStreamSinks, registers through AxiLiteMaster. Records are checked
against the golden model (fastnms.model.detect) and, for opencv + 3x3, against
cv2.FastFeatureDetector; the score video against fastnms.fast.fast_maps.

Configuration from pytest (tb/top/test_axi.py): TB_GENERICS (the top's
generics), TB_IDLE (input idle probability), TB_STALL (corner output
back-pressure probability), TB_CROPS (photograph crops).
"""

from __future__ import annotations

import ast
import json
import os
from collections.abc import Sequence
from pathlib import Path

import cocotb
import cv2
import numpy as np
from cocotb.triggers import ClockCycles, RisingEdge
from cocotbext.axi import AxiResp, AxiStreamFrame
from fastnms.golden.budget import hardware_order
from fastnms.golden.fast import fast_maps
from fastnms.golden.model import detect
from fastnms.sim import regs
from fastnms.sim.driver import AxiTop, Record, decode, pauses, record_words, video_lines
from fastnms.sim.records import decode_records
from fastnms.testing import images as testimages

from tb.video import min_width
from tb.video import whole_beats as round_to_beats

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
MAX_HEIGHT = GENERICS["MAX_HEIGHT"]
SCORE = GENERICS["SCORE"]
NMS = GENERICS["NMS"]
SCORE_VIDEO = bool(GENERICS.get("SCORE_VIDEO", False))
FIFO_DEPTH = GENERICS.get("CORNER_FIFO_DEPTH", 512)
PPC = GENERICS.get("PPC", 1)
MAX_PER_CELL = GENERICS.get("MAX_PER_CELL", 0)
# The narrowest frame the WIDTH register takes (fastnms_axi_regs: the core's
# window generators read their line buffers with latency 1).
MIN_WIDTH = min_width(7, PPC)
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))

# No test may hang: a generous bound in simulated time.
TIMEOUT_MS = 20 + 2e-3 * MAX_WIDTH * MAX_HEIGHT


def all_generics() -> dict[str, object]:
    """The top's generics, defaults filled in."""
    return {
        "SCORE_VIDEO": False,
        "CORNER_FIFO_DEPTH": 512,
        "PPC": 1,
        "MAX_PER_CELL": 0,
        "DESCRIPTOR": "none",
        "ORB_MAX_CELL": 16,
        **GENERICS,
    }


def budget_register(merged: int) -> int:
    """BUDGET after a write whose merged value is `merged`: PER_CELL clamped to
    MAX_PER_CELL; CELL clamped to 16 .. 256 (bits 31:25 count), then rounded
    down to a power of two."""
    cell = min(merged >> regs.BUDGET_CELL.lsb, 256)
    cell = 1 << max(4, cell.bit_length() - 1)
    k = min(regs.BUDGET_PER_CELL.get(merged), MAX_PER_CELL)
    return k << regs.BUDGET_PER_CELL.lsb | cell << regs.BUDGET_CELL.lsb


def whole_beats(width: int) -> int:
    return round_to_beats(width, PPC, MIN_WIDTH)


def width_register(written: int) -> int:
    """What WIDTH reads after a write: clamped to MIN_WIDTH .. MAX_WIDTH (bits
    31:16 count), then rounded down to whole beats."""
    if written > MAX_WIDTH:
        return MAX_WIDTH
    return max(MIN_WIDTH, written) // PPC * PPC


def opencv_keypoints(img: np.ndarray, threshold: int) -> list[Record]:
    """cv2.FAST with nonmaxSuppression=True, as records sorted by y then x."""
    fast = cv2.FastFeatureDetector_create(threshold, True, cv2.FAST_FEATURE_DETECTOR_TYPE_9_16)
    points = [(int(k.pt[0]), int(k.pt[1]), int(k.response)) for k in fast.detect(img)]
    return sorted(points, key=lambda p: (p[1], p[0]))


def golden(img: np.ndarray, threshold: int) -> list[Record]:
    return [tuple(int(v) for v in r) for r in detect(img, threshold, SCORE, NMS)]


def mismatch(got: list, want: list, label: str) -> str:
    padded = zip(got + [None] * len(want), want + [None] * len(got), strict=False)
    for i, (g, w) in enumerate(padded):
        if g != w:
            return f"{label}: rtl {len(got)} records, golden {len(want)}; #{i}: rtl {g}, golden {w}"
    return f"{label}: equal"


class TB(AxiTop):
    """The simulation driver of the top (fastnms.sim.driver) with the checks of
    this testbench: records against the golden model and cv2.FAST."""

    @classmethod
    async def create(cls, dut, idle: float = IDLE, stall: float = STALL) -> TB:
        return await super().create(dut, GENERICS, idle, stall)

    async def input_errors(self) -> set[str]:
        """The error bits of the video input (OVERFLOW excluded: it only says
        that the corner output stalled the pipeline)."""
        return await self.errors() - {"OVERFLOW"}

    async def clear_status(self) -> None:
        await self.write(regs.STATUS, 0xFFFFFFFE)
        assert await self.status() & ~1 == 0

    async def idle_output(self, clocks: int = 200) -> None:
        """Wait until nothing has come out for `clocks` clocks."""
        quiet = 0
        while quiet < clocks:
            await RisingEdge(self.dut.aclk)
            busy = self.dut.m_axis_corners_tvalid.value == 1 or not self.source.idle()
            quiet = 0 if busy else quiet + 1

    def check_frame(self, frame: AxiStreamFrame, want: list[Record], label: str) -> None:
        records, flags = decode(frame)
        if not want:
            assert records == [(0, 0, 0)] and flags == [0b011], (
                f"{label}: expected the empty-frame record, got {records} flags {flags}"
            )
            return
        if NMS.startswith("region"):
            # The region NMS sends a region's record when the region closes.
            records = sorted(records, key=lambda r: (r[1], r[0]))
        assert records == want, mismatch(records, want, label)
        assert flags == [0] * (len(want) - 1) + [0b010], f"{label}: flags {flags}"

    async def check_frames(
        self, frames: Sequence[tuple[np.ndarray, int]], label: str, opencv: bool = True
    ) -> None:
        """Send frames, receive and check every one."""
        sender = cocotb.start_soon(self.send_frames(frames))
        total = sum(img.size for img, _ in frames)
        slack = 1 / max(0.05, (1 - IDLE) * (1 - STALL))
        got = await self.receive(len(frames), int(total * 3 * slack) + 20 * MAX_WIDTH + 2000)
        await sender
        for i, ((img, t), frame) in enumerate(zip(frames, got, strict=True)):
            name = f"{label} frame {i} ({img.shape[1]}x{img.shape[0]} t={t})"
            want = golden(img, t)
            self.check_frame(frame, want, name + " vs golden")
            if opencv and SCORE == "opencv" and NMS == "3x3":
                cv = opencv_keypoints(img, t)
                records, _ = decode(frame)  # 3x3: in raster order
                assert records == (cv or [(0, 0, 0)]), mismatch(records, cv, name + " vs cv2.FAST")
            self.dut._log.info("%s: %d corners, equal", name, len(want))


# ---- tests -----------------------------------------------------------------------


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def registers(dut):
    """ID, VERSION, reset values, read/write, clamping, MODE, read-only and
    unmapped addresses, partial writes, write-1-to-clear."""
    tb = await TB.create(dut, 0, 0)
    await tb.reset()
    generics = all_generics()
    for name, reg in regs.REGISTERS.items():
        value = await tb.read(reg.offset)
        assert value == regs.reset_value(name, generics), f"{name} = 0x{value:08x} after reset"
    assert await tb.read(regs.ID) == 0x46415354
    major, minor, patch = regs.MAP_VERSION
    assert await tb.read(regs.VERSION) == major << 16 | minor << 8 | patch

    await tb.write(regs.THRESHOLD, 0xFFFFFF37)
    assert await tb.read(regs.THRESHOLD) == 0x37
    for written in [0, 6, 7, 8, 9, 10, 11, MAX_WIDTH, MAX_WIDTH - 1, MAX_WIDTH + 1]:
        await tb.write(regs.WIDTH, written)
        want = width_register(written)
        assert await tb.read(regs.WIDTH) == want, f"WIDTH write {written}: want {want}"
    for written in [0x10000 | 9, 0xFFFFFFFF]:
        await tb.write(regs.WIDTH, written)
        assert await tb.read(regs.WIDTH) == MAX_WIDTH, f"WIDTH write 0x{written:x}"
    assert regs.MODE_PPC.get(await tb.read(regs.MODE)) == PPC
    await tb.write(regs.HEIGHT, MAX_HEIGHT + 5)
    assert await tb.read(regs.HEIGHT) == MAX_HEIGHT
    await tb.write(regs.HEIGHT, 3)
    assert await tb.read(regs.HEIGHT) == 7
    assert regs.BUILD_MAX_PER_CELL.get(await tb.read(regs.BUILD)) == MAX_PER_CELL
    for k in range(16):
        for cell in (0, 15, 16, 17, 31, 32, 48, 64, 100, 128, 255, 256, 257, 511, 0x7F00):
            written = k | cell << 16
            await tb.write(regs.BUDGET, written)
            want = budget_register(written)
            got = await tb.read(regs.BUDGET)
            assert got == want, f"BUDGET write 0x{written:x}: 0x{got:x}, want 0x{want:x}"
    await tb.write(regs.BUDGET, 0)

    # MODE: asking for a variant that is not built in changes nothing.
    mode = await tb.read(regs.MODE)
    for ask in (0x00, 0x11, 0x33, 0x21, 0xFFFFFFFF):
        await tb.write(regs.MODE, ask)
        assert await tb.read(regs.MODE) == mode

    # Read-only registers ignore writes.
    read_only = [
        n for n, r in regs.REGISTERS.items() if all(f.access == "ro" for f in r.fields.values())
    ]
    assert {"ID", "DROPPED", "INPUT_STALLS"} <= set(read_only)
    for name in read_only:
        before = await tb.read(regs.REGISTERS[name].offset)
        await tb.write(regs.REGISTERS[name].offset, 0x5A5A5A5A)
        assert await tb.read(regs.REGISTERS[name].offset) == before, name

    # Full decoding: the registers answer at their offset only; any other address
    # of the 4 KiB space answers SLVERR (reads 0) and changes nothing.
    top = max(r.offset for r in regs.REGISTERS.values())
    for address in (top + 4, 0x100 + regs.THRESHOLD, 0x800 + regs.CTRL, 0xFFC):
        resp = await tb.axil.read(address, 4)
        assert resp.resp == AxiResp.SLVERR and resp.data == bytes(4), hex(address)
        resp = await tb.axil.write(address, (0).to_bytes(4, "little"))
        assert resp.resp == AxiResp.SLVERR, hex(address)
    assert await tb.read(regs.THRESHOLD) == 0x37
    assert await tb.read(regs.CTRL) == regs.CTRL_ENABLE.mask

    # Byte strobes: a byte not strobed keeps its value.
    resp = await tb.axil.write(regs.THRESHOLD, b"\x05")  # WSTRB 0001
    assert resp.resp == AxiResp.OKAY
    assert await tb.read(regs.THRESHOLD) == 0x05
    await tb.axil.write(regs.THRESHOLD + 1, b"\x77")  # WSTRB 0010: no THRESHOLD bit
    assert await tb.read(regs.THRESHOLD) == 0x05
    await tb.write(regs.WIDTH, 40)
    await tb.axil.write(regs.WIDTH + 1, b"\x00")  # WSTRB 0010: the high byte of 40
    assert await tb.read(regs.WIDTH) == 40
    await tb.axil.write(regs.WIDTH, b"\x21")  # WSTRB 0001
    assert await tb.read(regs.WIDTH) == width_register(0x21)
    await tb.axil.write(regs.WIDTH + 2, b"\x01")  # bits 31:16 set: clamped
    assert await tb.read(regs.WIDTH) == MAX_WIDTH
    await tb.axil.write(regs.CTRL + 1, b"\xff")  # no CTRL bit in byte 1
    assert await tb.read(regs.CTRL) == regs.CTRL_ENABLE.mask

    # CTRL read/write.
    await tb.write(regs.CTRL, 0b100)
    assert await tb.read(regs.CTRL) == 0b100
    await tb.write(regs.CTRL, regs.CTRL_LIVE.mask | regs.CTRL_ENABLE.mask)
    assert await tb.read(regs.CTRL) == regs.CTRL_LIVE.mask | regs.CTRL_ENABLE.mask
    await tb.write(regs.CTRL, 0b001)
    assert await tb.read(regs.CTRL) == 0b001

    # Write-1-to-clear: a frame sets FRAME_DONE; writing 0 keeps it, 1 clears it.
    await tb.configure(16, 9, 10)
    img = testimages.blurred_noise(tb.np_rng, 16, 9)
    await tb.send_frames([(img, 10)])
    await tb.receive(1, 5000)
    await ClockCycles(dut.aclk, 5)
    assert regs.STATUS_FRAME_DONE.get(await tb.status())
    await tb.write(regs.STATUS, 0)
    assert regs.STATUS_FRAME_DONE.get(await tb.status())
    await tb.axil.write(regs.STATUS + 1, b"\xff")  # WSTRB 0010: FRAME_DONE not strobed
    assert regs.STATUS_FRAME_DONE.get(await tb.status())
    await tb.write(regs.STATUS, regs.STATUS_FRAME_DONE.mask)
    assert await tb.status() == 0
    assert await tb.read(regs.FRAME_COUNT) == 1
    assert await tb.read(regs.CORNER_COUNT) == len(golden(img, 10))


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def generated_frames(dut):
    """Every pattern, back to back, sizes 7x7 to MAX_WIDTH x MAX_HEIGHT, size
    and threshold changed over AXI-Lite between frames, an empty frame."""
    tb = await TB.create(dut)
    await tb.reset()
    rng = tb.np_rng
    sizes = [
        (MIN_WIDTH, 7),
        (MAX_WIDTH, MAX_HEIGHT),
        (whole_beats(9), 8),
        (whole_beats(int(rng.integers(7, MAX_WIDTH + 1))), int(rng.integers(7, 24))),
        (MAX_WIDTH, 7),
        (whole_beats(8), int(rng.integers(7, MAX_HEIGHT + 1))),
    ]
    frames = []
    for i, threshold in enumerate([0, 1, 10, 20, 50, 128, 254, 255, 5, 15, 30, 40]):
        pattern = testimages.PATTERNS[i % len(testimages.PATTERNS)]
        w, h = sizes[i % len(sizes)]
        frames.append((pattern(rng, w, h), threshold))
    assert any(not golden(img, t) for img, t in frames), "no empty frame among the cases"
    await tb.check_frames(frames, "generated")
    await ClockCycles(dut.aclk, 5)
    assert await tb.read(regs.FRAME_COUNT) == len(frames)
    img, t = frames[-1]
    assert await tb.read(regs.CORNER_COUNT) == len(golden(img, t))
    assert await tb.input_errors() == set()
    assert tb.score_without_video == 0


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def region_filter(dut):
    """MIN_AREA written with every frame (0 to 2047), frames back to back: each frame's
    records with their AREA equal the golden model's at that MIN_AREA; with the region
    NMS some frames lose regions to it, the 3x3 and none NMS ignore it (AREA 0)."""
    tb = await TB.create(dut)
    await tb.reset()
    rng = tb.np_rng
    region = NMS.startswith("region")
    w, h = whole_beats(min(MAX_WIDTH, 48)), min(MAX_HEIGHT, 20)
    min_areas = [3, 0, 2047, 5, 1, 2, 9]
    frames = [(testimages.blurred_noise(rng, w, h), int(rng.integers(1, 9))) for _ in min_areas]
    sender = cocotb.start_soon(tb.send_frames(frames, min_areas=min_areas))
    got = await tb.receive(len(frames), 20 * w * h * len(frames) + 2000)
    await sender
    thinned = 0
    for i, ((img, t), frame) in enumerate(zip(frames, got, strict=True)):
        min_area = min_areas[i] if region else 0
        want = [tuple(int(v) for v in r) for r in detect(img, t, SCORE, NMS, min_area, True)]
        thinned += len(want) < len(detect(img, t, SCORE, NMS))
        (decoded,) = decode_records(record_words(frame))
        records = [(*c, a) for c, a in zip(decoded.corners, decoded.areas, strict=True)]
        records = sorted(records, key=lambda r: (r[1], r[0]))
        assert records == want, mismatch(records, want, f"frame {i} MIN_AREA {min_areas[i]}")
    assert thinned >= (3 if region else 0), f"MIN_AREA dropped regions in {thinned} frames"
    assert await tb.read(regs.MIN_AREA) == min_areas[-1]
    dut._log.info("%d frames, %d thinned by MIN_AREA", len(frames), thinned)


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def real_images(dut):
    """Crops of real photographs (TB_CROPS: JSON list of [path, w, h, t])."""
    crops = json.loads(os.environ.get("TB_CROPS", "[]"))
    assert crops, "no crops given in TB_CROPS"
    tb = await TB.create(dut)
    await tb.reset()
    frames = [(testimages.crop(Path(p), whole_beats(w), h), t) for p, w, h, t in crops]
    await tb.check_frames(frames, "photo")
    assert await tb.input_errors() == set()
    assert tb.score_without_video == 0, "m_axis_score_tvalid rose without SCORE_VIDEO"


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def empty_frame(dut):
    """A frame without corners sends exactly one record: EMPTY and LAST, zeros."""
    tb = await TB.create(dut)
    await tb.reset()
    flat = np.full((10, 12), 77, dtype=np.uint8)
    await tb.check_frames([(flat, 20), (flat, 0)], "empty")
    await ClockCycles(dut.aclk, 5)
    assert await tb.read(regs.CORNER_COUNT) == 0
    assert await tb.read(regs.FRAME_COUNT) == 2


def _good(tb: TB, w: int, h: int) -> np.ndarray:
    return testimages.blurred_noise(tb.np_rng, w, h)


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
        good = _good(tb, w, h)
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
    await tb.check_frames([(_good(tb, w, h), t)], "final")
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
    frames = [(_good(tb, w, h), 12), (testimages.saturated(tb.np_rng, w, h), 30)]
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
    frames = [(_good(tb, w, h), 12), (_good(tb, 17, 11), 3)]
    await tb.check_frames(frames, "after soft reset")
    assert await tb.input_errors() == set()


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def interrupt_and_enable(dut):
    """interrupt follows FRAME_DONE when IRQ_ENABLE is set, clears with it;
    CTRL.ENABLE = 0 discards frames from their start of frame on."""
    tb = await TB.create(dut)
    await tb.reset()
    w, h, t = min(MAX_WIDTH, 24), min(MAX_HEIGHT, 10), 15
    img = _good(tb, w, h)
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
async def score_video(dut):
    """m_axis_score: one 8-bit score per pixel (PPC per beat, pixel 0 in the
    low byte), the golden score saturated to 255, tuser on the first beat,
    tlast on the last of each line."""
    assert SCORE_VIDEO, "built without SCORE_VIDEO"
    tb = await TB.create(dut)
    await tb.reset()
    rng = tb.np_rng
    frames = [
        (testimages.saturated(rng, MAX_WIDTH, min(MAX_HEIGHT, 16)), 0),
        (testimages.noise(rng, whole_beats(23), 9), 5),
        (testimages.blurred_noise(rng, whole_beats(9), 7), 1),
    ]
    sender = cocotb.start_soon(tb.check_frames(frames, "with score video", opencv=False))
    for img, t in frames:
        h, w = img.shape
        want = np.minimum(fast_maps(img, t, SCORE)[1], 255)
        for y in range(h):
            line = await tb.with_budget(
                tb.score_sink.recv(compact=False), 50 * img.size, "score line"
            )
            assert len(line.tdata) == w, f"score line {y}: {len(line.tdata)} beats, want {w}"
            # (The sink repeats a beat's tuser on each of its PPC bytes.)
            want_tuser = [int(y == 0 and i < PPC) for i in range(w)]
            assert list(line.tuser) == want_tuser, f"tuser of line {y}"
            assert list(line.tdata) == [int(v) for v in want[y]], f"scores of line {y}"
    await sender
    assert tb.score_sink.empty()
    peak = int(np.max(fast_maps(frames[0][0], 0, SCORE)[1]))
    assert peak > (255 if SCORE == "sad" else 0), f"highest score {peak}: saturation not tested"


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def throughput(dut):
    """No idle, no back-pressure: one frame, then back-to-back frames; clocks
    from the first pixel accepted to each frame's last record."""
    tb = await TB.create(dut, 0, 0)
    await tb.reset()
    w, h = MAX_WIDTH, MAX_HEIGHT
    n = int(os.environ.get("TB_FRAMES", "3"))
    img = testimages.blurred_noise(tb.np_rng, w, h)
    await tb.configure(w, h, 10)
    results = {}
    for count in (1, n):
        tb.first_pixel = None
        tb.last_records.clear()
        for _ in range(count):
            await tb.send_lines(video_lines(img, PPC))
        got = await tb.receive(count, 4 * count * w * h + 10000)
        for frame in got:
            tb.check_frame(frame, golden(img, 10), "throughput")
        clocks = [c - tb.first_pixel for c in tb.last_records]
        results[count] = clocks
        Path(os.environ.get("TB_RESULTS", os.devnull)).write_text(json.dumps(results))
        beats = w * h // PPC
        bound = 1.01 * count * beats + 4 * w + 64
        dut._log.info(
            "%d x %dx%d: last records at %s clocks (W*H = %d, bound %.0f)",
            count,
            w,
            h,
            clocks,
            w * h,
            bound,
        )
        assert clocks[-1] <= bound, f"{clocks[-1]} clocks for {count} frames > {bound:.0f}"
        if count > 1:
            steps = [b - a for a, b in zip(clocks, clocks[1:], strict=False)]
            assert all(s <= 1.01 * beats for s in steps), f"frame intervals {steps}"
        await ClockCycles(dut.aclk, 50)
    # Without back-pressure the corner FIFO never fills.
    assert await tb.errors() == set()


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
        await tb.check_frames([(_good(tb, w, h), 10)], f"after reset {trial}")
    assert tb.protocol.checked_edges > 1000


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
    frames = [(_good(tb, w, h), 10), (_good(tb, 17, 11), 3)]
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


class RegisterModel:
    """What the registers of an idle top (no video) read after any writes: the
    read/write fields with byte strobes, WIDTH/HEIGHT clamped after the byte merge,
    MODE and the read-only registers fixed, STATUS and CMD reading 0."""

    def __init__(self) -> None:
        generics = all_generics()
        self.values = {r.offset: regs.reset_value(n, generics) for n, r in regs.REGISTERS.items()}
        self.rw_mask = {
            r.offset: sum(f.mask for f in r.fields.values() if f.access == "rw")
            for r in regs.REGISTERS.values()
        }

    def write(self, offset: int, data: int, strobe: int) -> None:
        if offset not in self.values:
            return
        bytes_mask = sum(0xFF << 8 * b for b in range(4) if strobe >> b & 1)
        if offset in (regs.WIDTH, regs.HEIGHT):
            limit = MAX_WIDTH if offset == regs.WIDTH else MAX_HEIGHT
            merged = (self.values[offset] & ~bytes_mask) | (data & bytes_mask)
            if merged >> 16 == 0 and (merged & 0xFFFF) < 7:
                merged = 7
            elif merged >> 16 or merged > limit:
                merged = limit
            self.values[offset] = merged
        elif offset == regs.BUDGET:
            merged = (self.values[offset] & ~bytes_mask) | (data & bytes_mask)
            self.values[offset] = budget_register(merged)
        elif offset != regs.MODE:
            keep = self.rw_mask[offset] & bytes_mask
            self.values[offset] = (self.values[offset] & ~keep) | (data & keep)

    def read(self, offset: int) -> int | None:
        """The value, or None for an address outside the map (SLVERR)."""
        return self.values.get(offset)


@cocotb.test(timeout_time=TIMEOUT_MS, timeout_unit="ms")
async def registers_random(dut):
    """Random AXI4-Lite traffic against RegisterModel: writes of random data with
    random byte strobes to any address of the 4 KiB segment (mostly mapped ones),
    reads of any register between them, and all along, on the read channel, reads
    of the registers that writes cannot change; B and R back-pressure. CMD writes
    never carry the key (no soft reset)."""
    tb = await TB.create(dut, 0, 0)
    tb.axil.write_if.b_channel.set_pause_generator(pauses(tb.rng, 0.3))
    tb.axil.read_if.r_channel.set_pause_generator(pauses(tb.rng, 0.3))
    await tb.reset()
    model = RegisterModel()
    rng = tb.rng
    mapped = sorted(model.values)

    def address() -> int:
        if rng.random() < 0.85:
            return rng.choice(mapped)
        return rng.randrange(0, 0x1000, 4)

    async def check_read(offset: int) -> None:
        """A read equal to the model: the value with OKAY, or SLVERR and 0 outside the map."""
        resp = await tb.axil.read(offset, 4)
        want = model.read(offset)
        got = int.from_bytes(resp.data, "little")
        assert (resp.resp == AxiResp.SLVERR) == (want is None), hex(offset)
        assert got == (want or 0), f"read 0x{offset:03x}: 0x{got:08x}, model {want}"

    async def reader(count: int) -> None:
        for _ in range(count):
            await check_read(address())

    fixed = [o for o in mapped if not model.rw_mask[o] and o not in (regs.STATUS, regs.CMD)]
    done = False

    async def fixed_reader() -> int:
        count = 0
        while not done:
            await check_read(rng.choice(fixed + [0x100, 0xFFC]))
            count += 1
        return count

    background = cocotb.start_soon(fixed_reader())
    writes = 300
    for _ in range(writes):
        offset = address()
        first = rng.randrange(4)
        length = rng.randrange(1, 5 - first)
        data = rng.getrandbits(32)
        if offset == regs.CMD:
            data &= ~(0xFF << regs.CMD_KEY.lsb)
        if rng.random() < 0.3:  # small values: the clamping's lower end
            data &= 0x0000000F
        payload = data.to_bytes(4, "little")[first : first + length]
        resp = await tb.axil.write(offset + first, payload)
        strobe = ((1 << length) - 1) << first
        if model.read(offset) is None:
            assert resp.resp == AxiResp.SLVERR, hex(offset)
        else:
            assert resp.resp == AxiResp.OKAY, hex(offset)
        model.write(offset, data, strobe)
        if rng.random() < 0.3:
            await reader(rng.randrange(1, 4))
    done = True
    concurrent = await background
    assert concurrent > 20, f"only {concurrent} reads beside the writes"
    await reader(100)
    for offset in mapped:
        await check_read(offset)
    dut._log.info(
        "%d random writes, %d concurrent reads, every read equal to the model", writes, concurrent
    )
