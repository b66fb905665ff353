"""cocotb testbench of fastnms_orb_moments: every keypoint's (m01, m10) equal to
golden/orb.py's moments (OpenCV's IC_Angle) on 31x31 patches: flat, extreme and half-plane
patches (the largest moments), single pixels on and just outside the circle, checkerboards,
random pixels and patches of real photographs; columns offered on random clocks, the
moments taken with random stalls, keypoints back to back."""

from __future__ import annotations

import os
import random

import cocotb
import numpy as np
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge
from fastnms.golden import orb
from fastnms.golden.image import load_grey
from fastnms.testing import images as testimages

from tb.orb.patches import random_crop
from tb.stream import StreamSink, StreamSource, offer_times

COUNT = int(os.environ["TB_COUNT"])
SIDE = 2 * orb.HALF_PATCH + 1
MOMENT_BITS = 21
# docs/orb_rtl.md: from a keypoint's last column taken to its moments offered.
LATENCY = 10


def patches(rng: random.Random, count: int) -> list[np.ndarray]:
    """count uint8 31x31 patches, the keypoint at the centre."""
    nrng = np.random.default_rng(rng.getrandbits(32))
    v, u = np.mgrid[-orb.HALF_PATCH : orb.HALF_PATCH + 1, -orb.HALF_PATCH : orb.HALF_PATCH + 1]
    out = [np.zeros((SIDE, SIDE), np.uint8), np.full((SIDE, SIDE), 255, np.uint8)]
    for plane in (u > 0, u < 0, v > 0, v < 0, (u > 0) & (v > 0), (u < 0) & (v > 0)):
        out.append(np.where(plane, 255, 0).astype(np.uint8))
    out.append(((u + v) % 2 * 255).astype(np.uint8))
    # Single pixels on the circle's edge and just outside it (must not count).
    for vv in (0, 5, 9, 13, 14, 15):
        for du in (0, 1):
            uu = orb.UMAX[vv] + du
            if uu <= orb.HALF_PATCH:
                for su, sv in ((1, 1), (-1, -1)):
                    img = np.zeros((SIDE, SIDE), np.uint8)
                    img[orb.HALF_PATCH + sv * vv, orb.HALF_PATCH + su * uu] = 255
                    out.append(img)
    photos = [load_grey(p) for p in testimages.real_images()[:3]]
    while len(out) < count:
        if rng.random() < 0.5:
            out.append(nrng.integers(0, 256, size=(SIDE, SIDE), dtype=np.uint8))
        else:
            out.append(random_crop(rng, photos, SIDE))
    return out[:count]


def column_word(patch: np.ndarray, u: int) -> int:
    """Column u (-15 .. 15) as the in_column word: row v = -15 in bits 7 .. 0."""
    col = patch[:, orb.HALF_PATCH + u]
    return int.from_bytes(col.tobytes(), "little")


def signed(v: int) -> int:
    return v - (1 << MOMENT_BITS) if v >= 1 << (MOMENT_BITS - 1) else v


@cocotb.test()
async def equals_the_model(dut):
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d, %d keypoints", cocotb.RANDOM_SEED, COUNT)
    todo = patches(rng, COUNT)
    centre = np.array([orb.HALF_PATCH])
    expected = [tuple(int(m[0]) for m in orb.moments(p, centre, centre)) for p in todo]

    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    source = StreamSource(dut, dut.clk, "in", rng, idle=0.2)
    sink = StreamSink(dut, dut.clk, "out", ["m01", "m10"], rng, stall=0.5)
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    cocotb.start_soon(sink.run())
    offered = offer_times(dut.clk, dut.out_valid)
    await source.send(
        {"column": column_word(p, u)}
        for p in todo
        for u in range(-orb.HALF_PATCH, orb.HALF_PATCH + 1)
    )
    while len(sink.beats) < COUNT:
        await RisingEdge(dut.clk)
    for k, (beat, (m01, m10)) in enumerate(zip(sink.beats, expected, strict=True)):
        got = (signed(beat["m01"]), signed(beat["m10"]))
        assert got == (m01, m10), f"patch {k}: (m01, m10) = {got}, model {(m01, m10)}"
    side = SIDE
    clocks = {(offered[k] - source.accept_times[side * k + side - 1]) // 10 for k in range(COUNT)}
    assert clocks == {LATENCY}, f"moments offered {clocks} clocks after the last column"
    biggest = max(max(abs(a), abs(b)) for a, b in expected)
    dut._log.info("largest |moment| %d (bound %d)", biggest, orb.MOMENT_MAX)
    assert biggest == orb.MOMENT_MAX, "the half-plane patches reach the bound"
