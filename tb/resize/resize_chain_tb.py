"""cocotb testbench of an image pyramid: fastnms_resize in a chain of LEVELS - 1 steps
(tb/resize/vhdl/fastnms_resize_chain.vhd) at cv2.ORB's level sizes: every level's
pixels equal the golden model's pyramid (fastnms.golden.pyramid, equal to cv2.resize),
frames back to back; the camera (the chain's input) is never held once the scales are
computed, and no step holds the one before it."""

from __future__ import annotations

import ast
import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden.image import load_grey
from fastnms.golden.pyramid import level_size, pyramid
from fastnms.testing.images import cover, real_images

from tb.stream import resolve, value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
LEVELS = GENERICS["LEVELS"]
WIDTH, HEIGHT = (int(v) for v in os.environ["TB_SIZE"].split("x"))
FRAMES = int(os.environ.get("TB_FRAMES", "2"))
PERIOD_NS = 10


def picture(rng: random.Random, width: int, height: int, n: int) -> np.ndarray:
    """Frame n: a photograph (even n) or noise (odd n), width x height."""
    if n % 2:
        return np.random.default_rng(rng.getrandbits(32)).integers(
            0, 256, (height, width), np.uint8
        )
    images = real_images()
    return cover(load_grey(images[rng.randrange(len(images))]), width, height)


def bits(v: int, k: int, width: int) -> int:
    return (v >> (width * k)) & ((1 << width) - 1)


@cocotb.test()
async def pyramid_levels(dut):
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d %dx%d, %d levels", cocotb.RANDOM_SEED, WIDTH, HEIGHT, LEVELS)
    cocotb.start_soon(Clock(dut.clk, PERIOD_NS, unit="ns").start())
    sizes = [level_size(WIDTH, HEIGHT, k) for k in range(LEVELS)]
    dut.cfg_widths.value = sum(w << (12 * k) for k, (w, _) in enumerate(sizes))
    dut.cfg_heights.value = sum(h << (12 * k) for k, (_, h) in enumerate(sizes))
    for name in ("in_valid", "in_data", "in_sof", "in_eol"):
        getattr(dut, name).value = 0
    dut.rst.value = 1
    await ClockCycles(dut.clk, 3)
    dut.rst.value = 0
    # The scales of every step (about 1 100 clocks).
    await ClockCycles(dut.clk, 1300)
    frames = [picture(rng, WIDTH, HEIGHT, n) for n in range(FRAMES)]
    got: list[list[int]] = [[] for _ in range(LEVELS)]
    flags: list[list[tuple[int, int]]] = [[] for _ in range(LEVELS)]
    stalls = {"camera": 0, "links": 0, "errors": 0}

    async def record() -> None:
        while True:
            await RisingEdge(dut.clk)
            valid, ready = resolve(dut.link_valid.value), resolve(dut.link_ready.value)
            data, sof = resolve(dut.link_data.value), resolve(dut.link_sof.value)
            eol = resolve(dut.link_eol.value)
            for k in range(1, LEVELS):
                if bits(valid, k, 1):
                    if not bits(ready, k, 1):
                        stalls["links"] += 1
                    else:
                        got[k].append(bits(data, k, 8))
                        flags[k].append((bits(sof, k, 1), bits(eol, k, 1)))
            if value(dut.in_valid) and not value(dut.in_ready):
                stalls["camera"] += 1
            stalls["errors"] += bin(resolve(dut.errors.value)).count("1")

    cocotb.start_soon(record())
    for img in frames:
        h, w = img.shape
        for i, p in enumerate(img.reshape(-1).tolist()):
            dut.in_data.value = p
            dut.in_sof.value = int(i == 0)
            dut.in_eol.value = int(i % w == w - 1)
            dut.in_valid.value = 1
            await RisingEdge(dut.clk)
            while not value(dut.in_ready):
                await RisingEdge(dut.clk)
        dut.in_valid.value = 0
    await ClockCycles(dut.clk, 200)
    assert stalls == {"camera": 0, "links": 0, "errors": 0}, stalls
    for k in range(1, LEVELS):
        want = np.concatenate([pyramid(f, LEVELS)[k].reshape(-1) for f in frames])
        assert len(got[k]) == want.size, f"level {k}: {len(got[k])} pixels, {want.size} expected"
        bad = np.nonzero(np.array(got[k]) != want)[0]
        assert bad.size == 0, f"level {k}: {bad.size} pixels differ, the first at {bad[0]}"
        w, h = sizes[k]
        expect = [(int(i % (w * h) == 0), int(i % w == w - 1)) for i in range(want.size)]
        assert flags[k] == expect, f"level {k}: sof/eol"
    dut._log.info("levels %s exact", sizes[1:])
