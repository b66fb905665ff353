"""cocotb testbench of fastnms_core with DESCRIPTOR = "orb": pixels in, ORB keypoints out.
Every frame's records (x, y, score, angle bits, descriptor) equal golden/orb.py's
orb_features with the frame's CELL and K, in the budget's order; frames back to back with
their own configuration, input idles and output stalls (TB_IDLE, TB_STALL). With K = 0 a
record may be dropped when ORB's queue is full: the records out are then the model's in
raster order less the dropped ones (orb_dropped counted), each one exact."""

from __future__ import annotations

import ast
import os
import random

import cocotb
import numpy as np
from cocotb.triggers import RisingEdge
from fastnms.golden import orb
from fastnms.golden.image import load_grey
from fastnms.testing import images as testimages

from tb.orb.patches import budget_order, random_crop
from tb.video import VideoTB, frame_beats

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH, MAX_HEIGHT = GENERICS["MAX_WIDTH"], GENERICS["MAX_HEIGHT"]
SCORE = GENERICS.get("SCORE", "opencv")
NMS = GENERICS.get("NMS", "3x3")
MAX_PER_CELL = GENERICS["MAX_PER_CELL"]
ORB_MAX_CELL = GENERICS.get("ORB_MAX_CELL", 16)
IDLE = float(os.environ.get("TB_IDLE", "0"))
STALL = float(os.environ.get("TB_STALL", "0"))
# Clocks with nothing in or out that mean a deadlock: far above any wait of a working core
# (a keypoint alone takes at most 286 clocks, a budget drain at 128 wide 8 x 19 + 4).
STUCK = 10_000
# Frame kinds to run, in order (TB_FRAMES: comma-separated).
KINDS = os.environ.get("TB_FRAMES", "photo,noise,flat").split(",")


def frame_of(kind: str, rng: random.Random, photos: list[np.ndarray]) -> tuple:
    """(image, threshold, CELL asked, K) of a frame kind."""
    nrng = np.random.default_rng(rng.getrandbits(32))
    w, h = MAX_WIDTH, MAX_HEIGHT
    crop = random_crop(rng, photos, max(w, h))[:h, :w]
    noise = nrng.integers(0, 256, size=(h, w), dtype=np.uint8)
    return {
        "photo": (crop, 20, 16, 4),
        "noise": (noise, 0, 16, MAX_PER_CELL),  # the densest records: the input must wait
        "flat": (np.full((h, w), 90, np.uint8), 20, 16, 4),
        "cell32": (crop, 10, 32, 2),
        "cell256": (testimages.blurred_noise(nrng, w, h), 5, 256, 3),  # clamped to ORB_MAX_CELL
        "narrow": (noise[:40, :60], 0, 16, 4),  # no keypoint inside ORB's border
        "off": (crop, 25, 16, 0),  # K = 0: every keypoint, none dropped on a photograph
        "off_noise": (noise, 0, 16, 0),  # K = 0 on noise: records dropped, none wrong
    }[kind]


class TB(VideoTB):
    def __init__(self, dut):
        super().__init__(dut, ["x", "y", "score", "eof", "angle", "descriptor"], IDLE, STALL)
        dut._log.info("generics %s, frames %s", GENERICS, KINDS)
        self.dropped = 0
        self.held = 0
        self.quiet = 0  # clocks since a pixel went in or a record came out

    async def count(self) -> None:
        dut = self.dut
        while True:
            await RisingEdge(dut.clk)
            self.dropped += int(dut.orb_dropped.value)
            offered = dut.in_valid.value == 1
            self.held += int(offered and dut.in_ready.value == 0)
            moved = (offered and dut.in_ready.value == 1) or (
                dut.out_valid.value == 1 and dut.out_ready.value == 1
            )
            self.quiet = 0 if moved else self.quiet + 1

    async def wait_frames(self, count: int) -> None:
        """Until `count` end-of-frame beats are out; a deadlock (nothing in or out for
        STUCK clocks while frames are due) fails the test."""
        while sum(b["eof"] for b in self.sink.beats) < count:
            assert self.quiet < STUCK, f"nothing in or out for {STUCK} clocks: deadlock"
            await RisingEdge(self.dut.clk)
        await self.wait_eofs(count, 0)


@cocotb.test()
async def equals_the_model(dut):
    tb = TB(dut)
    rng = random.Random(cocotb.RANDOM_SEED)
    photos = [load_grey(p) for p in testimages.real_images()[:3]]
    frames = [frame_of(k, rng, photos) for k in KINDS]
    cfgs = [
        {
            "width": img.shape[1],
            "height": img.shape[0],
            "threshold": t,
            "cell_log": cell.bit_length() - 5,
            "per_cell": k,
        }
        for img, t, cell, k in frames
    ]
    tb.set_cfg(**cfgs[0])
    await tb.reset()
    cocotb.start_soon(tb.count())
    sending = cocotb.start_soon(tb.send_frames([f[0] for f in frames], cfgs))
    await tb.wait_frames(len(frames))
    await sending
    got_frames = split_beats(tb.sink.beats)
    dropped_total = 0
    for n, ((img, t, cell, k), got) in enumerate(zip(frames, got_frames, strict=False)):
        cell = min(cell, ORB_MAX_CELL)
        want = model_records(img, t, cell, min(k, MAX_PER_CELL))
        have = got_records(got)
        label = f"frame {n} ({KINDS[n]}, {img.shape[1]}x{img.shape[0]} t={t} CELL {cell} K {k})"
        if k == 0:  # raster order, some possibly dropped
            want = sorted(want, key=lambda r: (r[1], r[0]))
            wanted = set(want)
            assert all(r in wanted for r in have), f"{label}: a record that is not the model's"
            assert have == [r for r in want if r in set(have)], f"{label}: out of order"
            dropped_total += len(want) - len(have)
        else:
            for i, (h, w) in enumerate(zip(have, want, strict=False)):
                assert h[:3] == w[:3], f"{label}: record {i}: rtl {h[:3]}, model {w[:3]}"
                assert h[3] == w[3], f"{label}: record {i} {w[:2]}: angle {h[3]:08x}, {w[3]:08x}"
                assert h[4] == w[4], f"{label}: record {i} {w[:2]}: bits {h[4] ^ w[4]:064x}"
            assert len(have) == len(want), f"{label}: {len(have)} records, model {len(want)}"
        dut._log.info("%s: %d keypoints of %d, equal", label, len(have), len(want))
    dut._log.info("input held on %d clocks; %d records dropped", tb.held, tb.dropped)
    assert tb.dropped == dropped_total, f"orb_dropped {tb.dropped}, missing {dropped_total}"
    if "off_noise" in KINDS:
        assert tb.dropped > 0, "K = 0 on noise at t = 0 must overflow ORB's queue"
    assert tb.err_line == 0 and tb.err_frame == 0


def model_records(img: np.ndarray, t: int, cell: int, k: int) -> list[tuple]:
    f = orb.orb_features(img, t, SCORE, NMS, cell=cell, per_cell=k)
    return budget_order(f, cell)


def got_records(beats: list[dict]) -> list[tuple]:
    return [(b["x"], b["y"], b["score"], b["angle"], b["descriptor"]) for b in beats]


@cocotb.test()
async def bad_input_then_exact(dut):
    """A frame cut short (the next frame's first pixel comes early), then a reset while a
    frame's keypoints are in ORB: nothing hangs, and the frames after each are exact."""
    tb = TB(dut)
    rng = random.Random(cocotb.RANDOM_SEED)
    nrng = np.random.default_rng(rng.getrandbits(32))
    photos = [load_grey(p) for p in testimages.real_images()[:3]]
    w, h = 96, 80
    noise = [nrng.integers(0, 256, size=(h, w), dtype=np.uint8) for _ in range(3)]
    photo = random_crop(rng, photos, w)[:h, :w]
    cfg = {"width": w, "height": h, "threshold": 0, "cell_log": 0, "per_cell": MAX_PER_CELL}
    tb.set_cfg(**cfg)
    await tb.reset()
    cocotb.start_soon(tb.count())

    async def frame(img: np.ndarray, rows: int | None = None) -> None:
        beats = frame_beats(img)
        await tb.source.send(beats if rows is None else beats[: rows * w])

    # A frame cut after 40 rows, completed by the next frame's first pixel; that frame exact.
    await frame(noise[0], rows=40)
    await frame(noise[1])
    await tb.wait_frames(2)
    assert tb.err_frame > 0, "the cut frame was not flagged"
    want = model_records(noise[1], 0, 16, MAX_PER_CELL)
    got = got_records(split_beats(tb.sink.beats)[1])
    assert got == want, f"the frame after the cut one: {len(got)} records, model {len(want)}"
    dut._log.info("after a cut frame: %d keypoints, equal", len(got))

    # A reset once the frame is in but before its keypoints are all out.
    await frame(noise[2])
    while dut.out_valid.value == 0:
        await RisingEdge(dut.clk)
    for _ in range(100):
        await RisingEdge(dut.clk)
    dut.rst.value = 1
    for _ in range(3):
        await RisingEdge(dut.clk)
    dut.rst.value = 0
    before = len(tb.sink.beats)
    tb.set_cfg(**{**cfg, "threshold": 10, "per_cell": 4})
    for _ in range(3):
        await RisingEdge(dut.clk)
    await frame(photo)
    eofs = sum(b["eof"] for b in tb.sink.beats[:before])
    await tb.wait_frames(eofs + 1)
    got = got_records(split_beats(tb.sink.beats[before:])[0])
    want = model_records(photo, 10, 16, 4)
    assert got == want, f"the frame after a reset: {len(got)} records, model {len(want)}"
    dut._log.info("after a reset: %d keypoints, equal", len(got))


def split_beats(beats: list[dict]) -> list[list[dict]]:
    """The beats of each frame, without its end-of-frame beat."""
    frames: list[list[dict]] = [[]]
    for beat in beats:
        if beat["eof"]:
            frames.append([])
        else:
            frames[-1].append(beat)
    return frames
