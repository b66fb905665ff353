"""cocotb testbench of fastnms_window: every window against NumPy."""

from __future__ import annotations

import ast
import os
import random

import cocotb
import numpy as np
from cocotb.triggers import ClockCycles

from tb.video import PERIOD_NS, VideoTB, frame_beats, min_width, split_frames

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
MAX_HEIGHT = GENERICS["MAX_HEIGHT"]
WINDOW = GENERICS["WINDOW"]
DATA_WIDTH = GENERICS["DATA_WIDTH"]
LATENCY = GENERICS["READ_LATENCY"]
PPC = GENERICS.get("PPC", 1)
R = WINDOW // 2
LB = -(-R // PPC)  # the output's lag in beats behind the input, after R rows
COLS = WINDOW - 1 + PPC  # columns of a beat's block of windows
MIN_WIDTH = min_width(WINDOW, PPC, LATENCY)
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))


class TB(VideoTB):
    def __init__(self, dut, idle: float = IDLE, stall: float = STALL):
        super().__init__(
            dut,
            ["window", "inside", "sof", "eol", "eof", "x", "y"],
            idle,
            stall,
            ppc=PPC,
            bits=DATA_WIDTH,
        )
        dut._log.info("generics %s", GENERICS)
        self.set_size(MIN_WIDTH, WINDOW)

    def set_size(self, width: int, height: int) -> None:
        self.set_cfg(width=width, height=height)

    def random_image(self, width: int, height: int) -> np.ndarray:
        return self.np_rng.integers(0, 2**DATA_WIDTH, (height, width), dtype=np.int64)

    async def send_images(self, images: list[np.ndarray]) -> None:
        await self.send_frames(
            images, [{"width": i.shape[1], "height": i.shape[0]} for i in images]
        )


def unpack_block(word: int) -> np.ndarray:
    """A beat's WINDOW x COLS block of pixels."""
    mask = (1 << DATA_WIDTH) - 1
    flat = [(word >> (DATA_WIDTH * i)) & mask for i in range(WINDOW * COLS)]
    return np.array(flat, dtype=np.int64).reshape(WINDOW, COLS)


def check_frame(
    img: np.ndarray, beats: list[dict[str, int]], label: str, contents: bool = True
) -> None:
    """Beats of one frame against the model: markers, and unless `contents`
    is False (a frame cut short) inside flags and the window of every pixel
    that is inside."""
    h, w = img.shape
    row_beats = w // PPC
    assert len(beats) == row_beats * h, f"{label}: {len(beats)} beats for a {w}x{h} frame"
    for k, beat in enumerate(beats):
        y, bx = divmod(k, row_beats)
        x = bx * PPC
        where = f"{label} at beat (x={x}, y={y})"
        assert beat["sof"] == int(k == 0), f"{where}: sof={beat['sof']}"
        assert beat["eol"] == int(bx == row_beats - 1), f"{where}: eol={beat['eol']}"
        assert beat["eof"] == int(k == len(beats) - 1), f"{where}: eof={beat['eof']}"
        assert (beat["x"], beat["y"]) == (x, y), f"{where}: position ({beat['x']}, {beat['y']})"
        if not contents:
            continue
        inside = [R <= x + i <= w - 1 - R and R <= y <= h - 1 - R for i in range(PPC)]
        want_flags = sum(1 << i for i in range(PPC) if inside[i])
        assert beat["inside"] == want_flags, f"{where}: inside={beat['inside']:0{PPC}b}"
        block = unpack_block(beat["window"])
        for i in range(PPC):
            if inside[i]:
                got = block[:, i : i + WINDOW]
                want = img[y - R : y + R + 1, x + i - R : x + i + R + 1]
                assert np.array_equal(got, want), f"{where} pixel {i}: window\n{got}\n!=\n{want}"


def random_size(rng: random.Random) -> tuple[int, int]:
    widths = [MIN_WIDTH, MIN_WIDTH + PPC, MAX_WIDTH, rng.randrange(MIN_WIDTH, MAX_WIDTH + 1, PPC)]
    heights = [WINDOW, WINDOW + 1, rng.randrange(WINDOW, min(MAX_HEIGHT, 3 * WINDOW) + 1)]
    return rng.choice(widths), rng.choice(heights)


@cocotb.test()
async def random_frames(dut):
    """Back-to-back frames of random sizes and pixels, every window checked."""
    tb = TB(dut)
    await tb.reset()
    sizes = [(MIN_WIDTH, WINDOW), (MAX_WIDTH, WINDOW + 1)]
    sizes += [random_size(tb.rng) for _ in range(6)]
    images = [tb.random_image(w, h) for w, h in sizes]
    dut._log.info("frame sizes %s", sizes)
    await tb.send_images(images)
    total = sum(img.size for img in images)
    await tb.wait_beats(total // PPC, 20 * total + 1000)
    frames = split_frames(tb.sink.beats)
    assert len(frames) == len(images)
    for i, (img, beats) in enumerate(zip(images, frames, strict=True)):
        check_frame(img, beats, f"frame {i} ({img.shape[1]}x{img.shape[0]})")
    assert tb.err_line == 0 and tb.err_frame == 0


@cocotb.test()
async def tallest_frame(dut):
    """A MAX_WIDTH x MAX_HEIGHT frame (small generics only)."""
    if MAX_WIDTH * MAX_HEIGHT > 4096:
        dut._log.info("MAX_WIDTH x MAX_HEIGHT too large for this test; frame 3 rows high")
    height = MAX_HEIGHT if MAX_WIDTH * MAX_HEIGHT <= 4096 else 3 * WINDOW
    tb = TB(dut)
    await tb.reset()
    img = tb.random_image(MAX_WIDTH, height)
    await tb.send_images([img])
    await tb.wait_beats(img.size // PPC, 20 * img.size + 1000)
    check_frame(img, tb.sink.beats, f"{MAX_WIDTH}x{height}")


@cocotb.test()
async def throughput(dut):
    """No gaps, no stalls: with B = W / PPC beats per row, the last of N
    frames of W x H leaves N*B*H + R*B + LB + READ_LATENCY + 1 cycles after
    the first beat was accepted, i.e. one beat per clock."""
    tb = TB(dut, idle=0.0, stall=0.0)
    await tb.reset()
    width, height, count = min(MAX_WIDTH, 20) // PPC * PPC, WINDOW + 3, 3
    images = [tb.random_image(width, height) for _ in range(count)]
    await tb.send_images(images)
    row_beats = width // PPC
    total = count * row_beats * height
    await tb.wait_beats(total, 4 * total)
    cycles = (tb.sink.times[-1] - tb.source.accept_times[0]) // PERIOD_NS
    expected = total + R * row_beats + LB + LATENCY + 1
    dut._log.info(
        "%d frames of %dx%d: %d cycles (expected %d)", count, width, height, cycles, expected
    )
    assert cycles == expected
    for img, beats in zip(images, split_frames(tb.sink.beats), strict=True):
        check_frame(img, beats, "throughput frame")


@cocotb.test()
async def malformed_frames(dut):
    """Bad input is flagged, never stalls the block, and the next good frame
    comes out exactly right."""
    tb = TB(dut)
    await tb.reset()
    w, h = max(MIN_WIDTH, min(MAX_WIDTH, 12) // PPC * PPC), WINDOW + 2
    row_beats = w // PPC
    good = [tb.random_image(w, h) for _ in range(7)]
    tb.set_size(w, h)
    await ClockCycles(dut.clk, 2)
    start = R * row_beats + LB  # beats in before the first window leaves

    def beats_of(img):
        return frame_beats(img, ppc=PPC, bits=DATA_WIDTH)

    # An end of line missing and one in mid-line: flagged, geometry kept.
    beats = beats_of(good[0])
    beats[row_beats - 1]["eol"] = 0
    beats[row_beats]["eol"] = 1
    await tb.source.send(beats)
    # A frame cut after its output started is completed with border beats.
    await tb.source.send(beats_of(good[1])[: start + row_beats + 2])
    # A frame cut before its output started produces nothing.
    await tb.source.send(beats_of(good[2])[: start - 1])
    await tb.source.send(beats_of(good[3]))
    # Beats outside any frame are dropped, one err_frame pulse each.
    await tb.source.send([{"data": 1, "sof": 0, "eol": 0}] * 5)
    await tb.source.send(beats_of(good[4]))
    # A frame whose configured size is out of range is dropped: too narrow,
    # and with PPC > 1 a width that is not a multiple of PPC.
    bad_widths = [MIN_WIDTH - PPC] + ([MIN_WIDTH + 1] if PPC > 1 else [])
    dropped = 0
    for bad in bad_widths:
        tb.set_size(bad, h)
        await ClockCycles(dut.clk, 2)
        bad_beats = beats_of(good[5][:, :bad])
        dropped += len(bad_beats)
        await tb.source.send(bad_beats)
    tb.set_size(w, h)
    await ClockCycles(dut.clk, 2)
    await tb.source.send(beats_of(good[6]))

    await tb.wait_beats(5 * row_beats * h, 40 * w * h)
    frames = split_frames(tb.sink.beats)
    check_frame(good[0], frames[0], "frame with bad eol")
    check_frame(good[1], frames[1], "cut frame", contents=False)
    check_frame(good[3], frames[2], "frame after two cuts")
    check_frame(good[4], frames[3], "frame after stray beats")
    check_frame(good[6], frames[4], "frame after a bad size")
    assert tb.err_line == 2, f"err_line pulsed {tb.err_line} times"
    expected = 2 + 5 + dropped
    assert tb.err_frame == expected, f"err_frame pulsed {tb.err_frame} times, not {expected}"


@cocotb.test()
async def reset_mid_frame(dut):
    """A reset in mid-frame drops the frame; the next one is exact."""
    tb = TB(dut)
    await tb.reset()
    w, h = max(MIN_WIDTH, min(MAX_WIDTH, 10) // PPC * PPC), WINDOW + 1
    first, second = tb.random_image(w, h), tb.random_image(w, h)
    tb.set_size(w, h)
    await ClockCycles(dut.clk, 2)
    await tb.source.send(frame_beats(first, ppc=PPC, bits=DATA_WIDTH)[: (R + 2) * (w // PPC)])
    await tb.reset()
    tb.sink.beats.clear()
    await tb.source.send(frame_beats(second, ppc=PPC, bits=DATA_WIDTH))
    await tb.wait_beats(w * h // PPC, 40 * w * h)
    check_frame(second, tb.sink.beats, "frame after reset")
