"""cocotb testbench of fastnms_orb_blur: the blurred centre of every 7x7 window equal
to golden/orb.py's gaussian_blur (OpenCV's bit-exact GaussianBlur, which
golden/tests ties to cv2.GaussianBlur), on random windows, the extremes, impulses at
each of the 49 positions (each kernel weight alone, at 255 and at 1), and every
window of crops of real photographs; the advance enable low on random clocks, each
result exactly LATENCY enabled clocks after its window."""

from __future__ import annotations

import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge
from fastnms.golden.orb import gaussian_blur
from fastnms.testing.images import crop, real_images

from tb.stream import value

COUNT = int(os.environ["TB_COUNT"])  # random windows, besides the others
LATENCY = 13
SIDE = 7


def windows(rng: random.Random, count: int) -> np.ndarray:
    """uint8 (N, 7, 7) windows."""
    nprng = np.random.default_rng(rng.getrandbits(32))
    parts = [
        np.zeros((1, SIDE, SIDE), np.uint8),
        np.full((1, SIDE, SIDE), 255, np.uint8),
        nprng.integers(0, 256, (count, SIDE, SIDE), dtype=np.uint8),
    ]
    for level in (255, 1):
        impulses = np.zeros((SIDE * SIDE, SIDE, SIDE), np.uint8)
        impulses.reshape(SIDE * SIDE, -1)[np.arange(SIDE * SIDE), np.arange(SIDE * SIDE)] = level
        parts.append(impulses)
    for path in real_images()[:3]:
        img = crop(path, 40, 40)
        view = np.lib.stride_tricks.sliding_window_view(img, (SIDE, SIDE))
        parts.append(view.reshape(-1, SIDE, SIDE))
    return np.concatenate(parts)


def expected(win: np.ndarray) -> list[int]:
    """The golden's blur at each window's centre: the windows side by side in one
    7 x 7N image, each centre 3 pixels from its neighbours' (the kernel's radius)."""
    mosaic = np.concatenate(list(win), axis=1)
    return gaussian_blur(mosaic)[SIDE // 2, SIDE // 2 :: SIDE].astype(int).tolist()


def pack(win: np.ndarray) -> int:
    """The window as fastnms_window gives it: pixel (row, col) at bits (row*7+col)*8."""
    return int.from_bytes(win.astype(np.uint8).tobytes(), "little")


@cocotb.test()
async def equals_the_model(dut):
    rng = random.Random(cocotb.RANDOM_SEED)
    win = windows(rng, COUNT)
    want = expected(win)
    dut._log.info("seed=%d, %d windows", cocotb.RANDOM_SEED, len(win))
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    dut.en.value = 0
    await RisingEdge(dut.clk)

    got: list[int] = []
    fed = 0
    enabled = 0  # enabled clock edges so far
    while len(got) < len(win):
        en = rng.random() < 0.8
        dut.en.value = int(en)
        if en:
            dut.window.value = pack(win[fed]) if fed < len(win) else 0
        await RisingEdge(dut.clk)
        if en:
            # Sampled at the edge: the result of the window of LATENCY enabled edges ago.
            if enabled >= LATENCY:
                got.append(value(dut.blurred))
            fed += 1
            enabled += 1
    for k, (g, e) in enumerate(zip(got, want, strict=True)):
        assert g == e, f"window {k} {win[k].tolist()}: {g}, the model {e}"
