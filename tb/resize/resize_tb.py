"""cocotb testbench of fastnms_resize: every destination pixel (and its sof/eol) equal to
the golden model's INTER_LINEAR_EXACT (fastnms.golden.pyramid, itself equal to
cv2.resize), frames back to back at changing sizes with idle cycles and back-pressure,
the input never held when the output is not, a reset mid-frame, and malformed frames
flagged and dropped with recovery at the next start of frame."""

from __future__ import annotations

import ast
import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden.pyramid import axis_taps, level_size, resize_linear_exact

from tb.stream import StreamSink, sim_ns, value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_W, MAX_H = GENERICS["MAX_WIDTH"], GENERICS["MAX_HEIGHT"]
PERIOD_NS = 10
# Clocks a change of the sizes may hold the input: the two divisions and the taps' start
# (docs/fastnms_resize.md).
SIZES_CLOCKS = 1200
# Clocks from the source pixel that completes a destination pixel to that pixel on the
# output, the output always ready (docs/fastnms_resize.md).
LATENCY = 14


class TB:
    def __init__(self, dut, idle: float = 0.0, stall: float = 0.0):
        self.dut = dut
        self.rng = random.Random(cocotb.RANDOM_SEED)
        self.np_rng = np.random.default_rng(cocotb.RANDOM_SEED)
        dut._log.info("seed=%d generics %s", cocotb.RANDOM_SEED, GENERICS)
        cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
        self.idle = idle
        for name in ("in_valid", "in_data", "in_sof", "in_eol"):
            getattr(dut, name).value = 0
        self.errors = {"err_size": 0, "err_frame": 0, "err_line": 0}
        self.sink = StreamSink(dut, dut.clk, "out", ["data", "sof", "eol"], self.rng, stall)
        self.held = 0  # clocks with in_valid high and in_ready low
        self.accepted: list[int] = []  # the time of each pixel taken

    async def reset(self) -> None:
        self.dut.rst.value = 1
        await ClockCycles(self.dut.clk, 3)
        self.dut.rst.value = 0
        await RisingEdge(self.dut.clk)

    def start(self) -> None:
        cocotb.start_soon(self.sink.run())
        cocotb.start_soon(self.watch())

    async def watch(self) -> None:
        while True:
            await RisingEdge(self.dut.clk)
            for name in self.errors:
                self.errors[name] += value(getattr(self.dut, name))
            if value(self.dut.in_valid) and not value(self.dut.in_ready):
                self.held += 1

    def sizes(self, sw: int, sh: int, dw: int, dh: int) -> None:
        self.dut.cfg_src_width.value = sw
        self.dut.cfg_src_height.value = sh
        self.dut.cfg_dst_width.value = dw
        self.dut.cfg_dst_height.value = dh

    async def send(self, img: np.ndarray, sof_at: int = 0, eol_ok: bool = True) -> None:
        """One frame, raster order; in_sof on pixel `sof_at` (0: a well-formed frame)."""
        dut = self.dut

        h, w = img.shape
        flat = img.reshape(-1).tolist()
        for i, p in enumerate(flat):
            while self.idle and self.rng.random() < self.idle:
                dut.in_valid.value = 0
                await RisingEdge(dut.clk)
            dut.in_data.value = p
            dut.in_sof.value = int(i == sof_at)
            dut.in_eol.value = int((i % w == w - 1) == eol_ok)
            dut.in_valid.value = 1
            await RisingEdge(dut.clk)
            while not value(dut.in_ready):
                await RisingEdge(dut.clk)
            self.accepted.append(sim_ns())
        dut.in_valid.value = 0

    async def drain(self, count: int, limit: int = 20000) -> None:
        """Until `count` pixels came out (or `limit` clocks: check() says what is missing)."""
        for _ in range(limit):
            if len(self.sink.beats) >= count:
                break
            await RisingEdge(self.dut.clk)
        await ClockCycles(self.dut.clk, 20)

    def check(self, frames: list[np.ndarray], first: int = 0) -> None:
        """The sink's beats from `first` on are the frames, with sof and eol."""
        beats = self.sink.beats[first:]
        at = 0
        for n, out in enumerate(frames):
            h, w = out.shape
            for i, p in enumerate(out.reshape(-1).tolist()):
                exp = {"data": p, "sof": int(i == 0), "eol": int(i % w == w - 1)}
                assert at < len(beats), f"frame {n} ({w}x{h}): pixel {i} missing"
                assert beats[at] == exp, f"frame {n} ({w}x{h}) pixel {i}: {beats[at]} != {exp}"
                at += 1
        assert at == len(beats), f"{len(beats) - at} pixels more than expected"

    def image(self, w: int, h: int) -> np.ndarray:
        kind = self.rng.choice(["noise", "smooth", "steps"])
        if kind == "noise":
            return self.np_rng.integers(0, 256, (h, w), dtype=np.uint8)
        if kind == "smooth":
            yy, xx = np.mgrid[:h, :w]
            return ((xx * 7 + yy * 13 + (xx * yy) % 31) % 256).astype(np.uint8)
        return (self.np_rng.integers(0, 2, (h, w)) * 255).astype(np.uint8)


def random_sizes(rng: random.Random) -> tuple[int, int, int, int]:
    sw, sh = rng.randint(2, min(MAX_W, 72)), rng.randint(2, min(MAX_H, 40))
    pick = rng.random()
    if pick < 0.4:
        dw, dh = level_size(sw, sh, 1)
    elif pick < 0.5:
        dw, dh = sw, sh
    elif pick < 0.6:
        dw, dh = 1, rng.randint(1, sh)
    else:
        dw, dh = rng.randint(1, sw), rng.randint(1, sh)
    return sw, sh, max(dw, 1), max(dh, 1)


async def frames_at_sizes(dut, idle: float, stall: float, count: int) -> TB:
    tb = TB(dut, idle, stall)
    await tb.reset()
    tb.start()
    expected = []
    for _ in range(count):
        sw, sh, dw, dh = random_sizes(tb.rng)
        tb.sizes(sw, sh, dw, dh)
        await ClockCycles(dut.clk, 2)
        img = tb.image(sw, sh)
        expected.append(resize_linear_exact(img, dw, dh))
        dut._log.info("frame %dx%d -> %dx%d", sw, sh, dw, dh)
        held = tb.held
        await tb.send(img)
        if not stall:
            assert tb.held - held <= SIZES_CLOCKS, f"input held {tb.held - held} clocks"
        dut._log.info("input held %d clocks", tb.held - held)
    await tb.drain(sum(e.size for e in expected))
    tb.check(expected)
    assert tb.errors == {"err_size": 0, "err_frame": 0, "err_line": 0}, tb.errors
    return tb


@cocotb.test()
async def sizes_back_to_back(dut):
    """Frames of random sizes (pyramid steps, identity, one column, any) back to back."""
    await frames_at_sizes(dut, 0.0, 0.0, 14)


@cocotb.test()
async def idles_and_back_pressure(dut):
    await frames_at_sizes(dut, 0.3, 0.4, 10)


def completing_pixels(sw: int, sh: int, dw: int, dh: int) -> list[int]:
    """For each destination pixel, the raster index of the source pixel that completes it."""
    xo, xc = axis_taps(sw, dw)
    yo, yc = axis_taps(sh, dh)
    x_need, y_need = xo + (xc != 256), yo + (yc != 256)
    return [int(y) * sw + int(x) for y in y_need for x in x_need]


@cocotb.test()
async def input_never_held(dut):
    """Same sizes frame after frame, no idle, output always ready: after the first frame's
    start (the scales), in_ready never drops; each destination pixel leaves LATENCY clocks
    after the source pixel that completes it."""
    tb = TB(dut)
    await tb.reset()
    tb.start()
    sw, sh = min(MAX_W, 64), min(MAX_H, 36)
    dw, dh = level_size(sw, sh, 1)
    tb.sizes(sw, sh, dw, dh)
    await ClockCycles(dut.clk, SIZES_CLOCKS)
    imgs = [tb.image(sw, sh) for _ in range(4)]
    tb.held = 0
    for img in imgs:
        await tb.send(img)
    assert tb.held == 0, f"input held {tb.held} clocks"
    await tb.drain(4 * dw * dh)
    tb.check([resize_linear_exact(img, dw, dh) for img in imgs])
    done = [n * sw * sh + i for n in range(4) for i in completing_pixels(sw, sh, dw, dh)]
    waits = {(t - tb.accepted[i]) // PERIOD_NS for i, t in zip(done, tb.sink.times, strict=True)}
    assert waits == {LATENCY}, f"latencies {sorted(waits)}"


@cocotb.test()
async def reset_mid_frame(dut):
    """A reset in the middle of a frame, then frames exact again."""
    tb = TB(dut, 0.1, 0.1)
    await tb.reset()
    tb.start()
    sw, sh, dw, dh = 40, 30, 33, 25
    tb.sizes(sw, sh, dw, dh)
    await ClockCycles(dut.clk, 2)
    task = cocotb.start_soon(tb.send(tb.image(sw, sh)))
    await ClockCycles(dut.clk, 500)
    task.cancel()
    dut.in_valid.value = 0
    await tb.reset()
    await ClockCycles(dut.clk, 30)
    first = len(tb.sink.beats)
    imgs = [tb.image(sw, sh) for _ in range(2)]
    for img in imgs:
        await tb.send(img)
    await tb.drain(first + 2 * dw * dh)
    tb.check([resize_linear_exact(img, dw, dh) for img in imgs], first)


@cocotb.test()
async def malformed_frames(dut):
    """A frame cut short by a start of frame (err_frame; it and the frame cutting it are
    dropped), a bad eol (err_line, resized anyway), sizes dst > src (err_size, dropped),
    pixels between frames (err_frame): the next well-formed frame is exact."""
    tb = TB(dut, 0.1, 0.1)
    await tb.reset()
    tb.start()
    sw, sh, dw, dh = 36, 20, 30, 17
    tb.sizes(sw, sh, dw, dh)
    await ClockCycles(dut.clk, 2)
    good = [tb.image(sw, sh) for _ in range(4)]
    await tb.send(good[0])
    # Cut short: half a frame, then a whole one (dropped: the taps prime again).
    await tb.send(good[1][: sh // 2])
    await tb.send(good[2])
    assert tb.errors["err_frame"] == 1, tb.errors
    await tb.send(good[3])
    # A wrong eol on every row: flagged, still resized.
    bad_eol = tb.image(sw, sh)
    await tb.send(bad_eol, eol_ok=False)
    assert tb.errors["err_line"] > 0, tb.errors
    # Pixels between frames: no sof.
    await tb.send(tb.image(5, 1), sof_at=-1)
    assert tb.errors["err_frame"] >= 2, tb.errors
    # Sizes not allowed: dropped.
    tb.sizes(sw, sh, sw + 1, dh)
    await ClockCycles(dut.clk, 2)
    await tb.send(tb.image(sw, sh))
    assert tb.errors["err_size"] == 1, tb.errors
    tb.sizes(sw, sh, dw, dh)
    await ClockCycles(dut.clk, 2)
    last = tb.image(sw, sh)
    await tb.send(last)
    # The frame cut short gave the rows whose last source row came before the cut.
    offsets, weights = axis_taps(sh, dh)
    needs = offsets + (weights != 256)
    rows = int(np.count_nonzero(needs < sh // 2))
    want = [resize_linear_exact(f, dw, dh) for f in (good[0], good[1], good[3], bad_eol, last)]
    want[1] = want[1][:rows]
    await tb.drain(sum(w.size for w in want))
    tb.check(want)
