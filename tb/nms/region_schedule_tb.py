"""cocotb testbench of fastnms_nms_region_schedule on its own, against a Python
model of its contract (docs/fastnms_nms_region.md: Pipeline, *Reader
prefetch* and *Flush beside the next frame*; Parts, Schedule; Latency and
throughput; the step model's scheduling, golden/region_stream.py `run`).

Driven as fastnms_nms_region drives it: px_* is the input skid buffer's
output, a stream (a pixel offered is held until px_valid and px_ready meet
at an edge; px_width is the frame's width on its first pixel and a random
width, as cfg_width for a later frame can be, on the others; while px_valid
is low the pixel fields are random); rec_room is the record FIFO's
not almost_full, here random (periods without room). Frames are 3 .. MAX_WIDTH
wide and 1 .. a few rows tall, with random corner bits; rst is synchronous
(the skid buffer drops its pixel from the reset's second clock).

The model: the current row (the next pixel's frame, row y, column x, the
corner bit before it, the rows accepted since the reset) and the reader, a
queue of the rows written and not yet read (each with its corner bits, its
head table bank, and whether it is its frame's last row, read in a flush),
with the reader's column in the first. On every clock after a reset
(outputs sampled at the clock's end, before the edge's update) it checks:

- Steps: nothing steps without rec_room (cstep, rstep, px_ready low);
  cstep = px_valid and px_ready; lock = cstep on a row >= 1; flush_ends =
  rstep at a flush's last column. A cstep takes the offered pixel (so each
  pixel is accepted once, in order; the stream's hold rule).
- The current row's outputs: cx, cy, first_row (y = 0), cm (the accepted
  corner bit at x - 1, 0 at column 0), cur_bank (rows since the reset, mod 2).
- The reader's outputs, its next column x of its next row (column 0 when no
  row is queued): r_col0/1/2 (x = 0, 1, 2), r_slot0 (x < 2), r_last (x = the
  row's last column), ahead_slot ((x + 2) mod W) / 2 (the next row's slots 0
  past the end), r_bank (the row's bank, the rows read since the reset mod
  2); pm and p0 equal the corner bits the row was written with at x - 1 (0 at
  column 0) and x, on every reader step and, inside a row, on every clock.
- Which side steps: a row >= 1 steps only with the reader in lock-step on
  the row above at the same column (every row is read once, each column once,
  in order); the reader steps alone only on a frame's last row (the flush); a
  frame's first row steps beside a flush only in the same clock as it, at a
  column <= the flush's, its last column with the flush's last, never while
  a second flush is queued; the reader never steps with no row written.
- The flush steps on every clock with room once it started; a frame of >= 2
  rows starts its flush on the first clock with room after its last pixel; a
  one-row frame's (queued behind a flush, or after a first row whose read
  ahead the flush held) within PENDING_START clocks of its last pixel or of
  the end of the flush before it (the two PRIME clocks).
- px_ready, with a pixel offered and room, is low only where the step
  model's schedule (golden/region_stream.py `run`) also waits, or at a
  second row's first pixel for at most PRIME_WAIT clocks (the PRIME clocks).

Tests: `random_sequences` (random frame sequences, back to back and with gaps,
narrower and wider frames, runs of one-row frames, random input gaps and
periods without room, resets in mid-frame or mid-flush followed by a clean
frame, idle clocks at the end: every queued row read) and `throughput` (no
input gap, room always: frames never narrower than the one before take W x H
clocks each with px_ready never low, and each flush ends W clocks after its
frame's last pixel; any sequence waits at most the sum over its narrower
frames of W_previous - W + 4 clocks, a bound reached by a one-row narrower
frame followed by another frame).
"""

from __future__ import annotations

import ast
import os
import random
from collections import deque
from dataclasses import dataclass

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

from tb.stream import value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
MAX_HEIGHT = GENERICS["MAX_HEIGHT"]
MIN_WIDTH = 3
# Frames of the random test, the tallest random frame, the resets in it.
FRAMES = int(os.environ.get("TB_FRAMES", "300"))
TALLEST = min(MAX_HEIGHT, int(os.environ.get("TB_TALLEST", "6")))
RESETS = int(os.environ.get("TB_RESETS", "4"))
# Widths of the random frames: up to this many columns most of the time (a
# wide build's rows stay short enough to run many frames).
WIDE = min(MAX_WIDTH, int(os.environ.get("TB_WIDE", str(MAX_WIDTH))))
# The schedule's waits beyond the step model's (docs: two PRIME clocks): the
# clocks a second row's first pixel may be refused with room (the clock that
# starts PRIME, and the two PRIME clocks), and the clocks from a one-row
# frame's last pixel, or the end of the flush before it, to its own flush's
# first step when the reader must be primed first (PRIME, then the start).
PRIME_WAIT = 3
PENDING_START = 5


@dataclass
class Frame:
    """A frame to send: its serial number, size and corner bits; reset_at:
    assert rst once this many of its pixels were accepted (the rest dropped)."""

    serial: int
    w: int
    h: int
    bits: list[list[int]]
    reset_at: int | None = None
    gap: int = 0  # idle clocks after it (px_valid low)


@dataclass
class Row:
    """A row written by the current row, waiting for the reader."""

    serial: int  # its frame's
    y: int
    w: int
    bits: list[int]
    bank: int
    last: bool  # its frame's last row: read in a flush
    started: bool = False
    start_by: int | None = None  # the clock from which its flush must step (with room)
    eof_clock: int | None = None  # the clock of its frame's last pixel
    first_step: int | None = None
    last_step: int | None = None


@dataclass
class Stats:
    clocks: int = 0
    pixels: int = 0
    frames: int = 0
    rsteps: int = 0
    lock: int = 0
    flush: int = 0
    beside: int = 0  # first-row steps beside a flush
    refused: int = 0  # pixel offered with room, px_ready low
    prime_refused: int = 0
    no_room: int = 0
    resets: int = 0


class Model:
    """The schedule's contract, advanced by the steps the RTL takes."""

    def __init__(self):
        self.stats = Stats()
        self.reset()

    def reset(self) -> None:
        self.y = 0  # the next pixel's row and column (0, 0 between frames)
        self.x = 0
        self.cm = 0
        self.row_bits: list[int] = []
        self.rows_done = 0  # rows written since the reset: cur_bank
        self.queue: deque[Row] = deque()
        self.rx = 0  # the reader's column in queue[0]
        self.rows_read = 0  # r_bank
        self.prime_refused_here = 0  # at the current pixel
        self.flushes: list[Row] = []  # the flushes completed since the reset

    def check(self, k: int, inp: dict, o: dict) -> None:
        """One clock: `inp` the inputs driven, `o` the outputs sampled at its end."""
        st = self.stats
        st.clocks += 1
        where = f"clock {k}"
        room, valid = inp["room"], inp["valid"]
        cs, rs, pr = o["cstep"], o["rstep"], o["px_ready"]
        frame: Frame | None = inp["frame"]
        assert frame is not None or not valid
        # The current row's position (registers: before this clock's step).
        want = {
            "cx": self.x,
            "cy": self.y,
            "first_row": int(self.y == 0),
            "cm": self.cm,
            "cur_bank": self.rows_done % 2,
        }
        got = {n: o[n] for n in want}
        assert got == want, f"{where}: current row {got}, expected {want}"
        # The reader's position.
        head = self.queue[0] if self.queue else None
        rx = self.rx if head else 0
        rw = head.w if head else None
        want = {
            "r_col0": int(rx == 0),
            "r_col1": int(rx == 1),
            "r_col2": int(rx == 2),
            "r_slot0": int(rx < 2),
            "r_last": int(rw is not None and rx == rw - 1),
            "ahead_slot": ((rx + 2) % rw) // 2 if rw else 1,
            "r_bank": self.rows_read % 2,
        }
        got = {n: o[n] for n in want}
        assert got == want, (
            f"{where}: reader at column {rx} of {self._row(head)}: {got}, expected {want}"
        )
        if head and (rx > 0 or rs):
            want = {"pm": head.bits[rx - 1] if rx else 0, "p0": head.bits[rx]}
            got = {"pm": o["pm"], "p0": o["p0"]}
            assert got == want, (
                f"{where}: reader at column {rx} of {self._row(head)} ({'' if rs else 'not '}"
                f"stepping): bits {got}, written {want}"
            )
        if head:
            assert head.bank == self.rows_read % 2
        # Steps.
        if not room:
            st.no_room += 1
            assert not (cs or rs or pr), (
                f"{where}: a step without rec_room (cstep {cs}, rstep {rs}, px_ready {pr})"
            )
        assert cs == (valid and pr), f"{where}: cstep {cs} with px_valid {valid}, px_ready {pr}"
        assert o["lock"] == int(cs and self.y >= 1), (
            f"{where}: lock {o['lock']}, cstep {cs}, row {self.y}"
        )
        flush_step = bool(rs and head and head.last)
        want_fe = int(flush_step and rx == head.w - 1)
        assert o["flush_ends"] == want_fe, (
            f"{where}: flush_ends {o['flush_ends']}, expected {want_fe}"
        )
        if rs:
            assert head is not None, f"{where}: the reader stepped with no row written"
            st.rsteps += 1
            if cs and self.y >= 1:
                assert (head.serial, head.y) == (frame.serial, self.y - 1) and rx == self.x, (
                    f"{where}: lock-step of row {self.y} column {self.x} (frame {frame.serial}) "
                    f"with the reader at column {rx} of {self._row(head)}"
                )
                st.lock += 1
            else:
                assert head.last, (
                    f"{where}: the reader stepped alone (column {rx} of {self._row(head)}), "
                    "not on a frame's last row"
                )
                st.flush += 1
        elif head and head.last and room:
            if head.started:
                raise AssertionError(
                    f"{where}: the flush of {self._row(head)} paused at column {rx} with room"
                )
            if head.start_by is not None and k >= head.start_by:
                raise AssertionError(
                    f"{where}: the flush of {self._row(head)} not started (due at {head.start_by})"
                )
        if cs and self.y >= 1:
            assert rs, f"{where}: row {self.y} stepped without the reader"
        if cs and self.y == 0 and head:
            assert len(self.queue) == 1 and head.last, (
                f"{where}: a first row stepped with {len(self.queue)} rows to read"
            )
            assert rs, f"{where}: a first row stepped beside a flush that did not"
            assert self.x <= rx, (
                f"{where}: a first row at column {self.x} ahead of the flush at {rx}"
            )
            if self.x == frame.w - 1:
                assert rx == head.w - 1, (
                    f"{where}: a first row's last column {self.x} beside the flush's column {rx} "
                    f"of {head.w}"
                )
            st.beside += 1
        if cs and self.y == 0 and not head:
            assert not rs
        # Waits: where the step model's schedule also waits, or PRIME.
        if valid and room and not pr:
            st.refused += 1
            if self._model_goes(frame, rs, head, rx):
                self.prime_refused_here += 1
                st.prime_refused += 1
                assert self.y == 1 and self.x == 0, (
                    f"{where}: pixel ({self.x}, {self.y}) of frame {frame.serial} refused with "
                    "room where the step model steps"
                )
                assert self.prime_refused_here <= PRIME_WAIT, (
                    f"{where}: a second row's first pixel refused {self.prime_refused_here} clocks"
                )
        # Advance: the reader, then the current row.
        if rs:
            if not head.started:
                head.started = True
                head.first_step = k
            self.rx += 1
            if self.rx == head.w:
                self.queue.popleft()
                self.rx = 0
                self.rows_read += 1
                if head.last:
                    head.last_step = k
                    self.flushes.append(head)
        if cs:
            self._accept(k, frame, inp["corner"])

    def _accept(self, k: int, frame: Frame, corner: int) -> None:
        st = self.stats
        st.pixels += 1
        self.prime_refused_here = 0
        self.row_bits.append(corner)
        eol = self.x == frame.w - 1
        if not eol:
            self.x += 1
            self.cm = corner
            return
        last = self.y == frame.h - 1
        row = Row(frame.serial, self.y, frame.w, self.row_bits, self.rows_done % 2, last)
        if last:
            # (A one-row frame's last pixel waits for the flush before it:
            # that flush ended with this clock's reader step.)
            assert not self.queue, (
                f"clock {k}: a frame's last row with {len(self.queue)} rows unread"
            )
            row.eof_clock = k
            row.start_by = k + 1 if frame.h >= 2 else k + PENDING_START
            st.frames += 1
        self.queue.append(row)
        self.rows_done += 1
        self.row_bits = []
        self.x = 0
        self.cm = 0
        self.y = 0 if last else self.y + 1

    def _model_goes(self, frame: Frame, rs: int, head: Row | None, rx: int) -> bool:
        """Whether golden/region_stream.py's schedule steps the offered pixel
        (with room), given this clock's flush step."""
        if self.y >= 1:
            return head is not None and (head.serial, head.y) == (frame.serial, self.y - 1)
        if head is None:
            return True
        if len(self.queue) > 1 or not rs:
            return False
        return self.x <= rx and (self.x < frame.w - 1 or rx == head.w - 1)

    @staticmethod
    def _row(row: Row | None) -> str:
        if row is None:
            return "no row"
        kind = "flush row" if row.last else "row"
        return f"{kind} {row.y} of frame {row.serial} ({row.w} wide)"

    def idle(self) -> bool:
        return not self.queue and self.x == 0 and self.y == 0


OUTPUTS = (
    "px_ready",
    "cstep",
    "rstep",
    "lock",
    "flush_ends",
    "first_row",
    "cm",
    "cx",
    "cy",
    "cur_bank",
    "pm",
    "p0",
    "r_last",
    "r_col0",
    "r_col1",
    "r_col2",
    "r_slot0",
    "r_bank",
    "ahead_slot",
)


class TB:
    def __init__(self, dut):
        self.dut = dut
        self.rng = random.Random(cocotb.RANDOM_SEED)
        dut._log.info("seed=%d generics %s", cocotb.RANDOM_SEED, GENERICS)
        cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
        self.handles = {n: getattr(dut, n) for n in OUTPUTS}
        self.model = Model()
        self.serial = 0
        self.k = 0
        self.drive(rst=1, valid=0, room=0, frame=None, pixel=0)

    def drive(self, *, rst: int, valid: int, room: int, frame: Frame | None, pixel: int) -> dict:
        """This clock's inputs: the pixel `pixel` of `frame` when valid, else random fields."""
        dut, rng = self.dut, self.rng
        dut.rst.value = rst
        dut.px_valid.value = valid
        dut.rec_room.value = room
        corner = 0
        if valid:
            y, x = divmod(pixel, frame.w)
            corner = frame.bits[y][x]
            first = pixel == 0
            dut.px_corner.value = corner
            dut.px_width.value = frame.w if first else rng.randint(MIN_WIDTH, MAX_WIDTH)
            dut.px_sof.value = int(first)
            dut.px_eol.value = int(x == frame.w - 1)
            dut.px_eof.value = int(x == frame.w - 1 and y == frame.h - 1)
        else:
            dut.px_corner.value = rng.getrandbits(1)
            dut.px_width.value = rng.randint(MIN_WIDTH, MAX_WIDTH)
            dut.px_sof.value = rng.getrandbits(1)
            dut.px_eol.value = rng.getrandbits(1)
            dut.px_eof.value = rng.getrandbits(1)
        return {"rst": rst, "valid": valid, "room": room, "frame": frame, "corner": corner}

    def sample(self) -> dict[str, int]:
        """The outputs at the clock's end; -1 for one with undefined bits."""
        out = {}
        for n, h in self.handles.items():
            try:
                out[n] = value(h)
            except ValueError:
                out[n] = -1
        return out

    async def reset(self, clocks: int = 3) -> None:
        """rst for `clocks` clocks with no pixel offered."""
        for _ in range(clocks):
            self.drive(rst=1, valid=0, room=self.rng.getrandbits(1), frame=None, pixel=0)
            await RisingEdge(self.dut.clk)
            self.k += 1
        self.model.reset()
        self.model.stats.resets += 1

    def new_frame(self, w: int, h: int, density: float | None = None) -> Frame:
        rng = self.rng
        if density is None:
            density = rng.choice([0.0, 0.1, 0.5, 0.9, 1.0])
        bits = [[int(rng.random() < density) for _ in range(w)] for _ in range(h)]
        self.serial += 1
        return Frame(self.serial, w, h, bits)

    async def run(
        self,
        frames: list[Frame],
        *,
        idle: float = 0.0,
        room_off: float = 0.0,
        room_on: float = 1.0,
    ) -> list[int]:
        """Send `frames` (each followed by its gap), pixels offered with a gap
        of random length with chance `idle` before each, rec_room a Markov
        chain (off with chance `room_off`, back on with `room_on`). Returns
        the clocks each frame's pixels were refused with room."""
        rng, dut, model = self.rng, self.dut, self.model
        room = 1
        refused = [0] * len(frames)
        for i, frame in enumerate(frames):
            pixel = 0
            offered = False
            while pixel < frame.w * frame.h:
                if frame.reset_at is not None and pixel == frame.reset_at:
                    # The skid buffer still offers its pixel on the reset's first clock.
                    self.drive(rst=1, valid=int(offered), room=room, frame=frame, pixel=pixel)
                    await RisingEdge(dut.clk)
                    self.k += 1
                    await self.reset(rng.randint(1, 3))
                    dut._log.debug("reset at pixel %d of frame %d", pixel, frame.serial)
                    break
                if not offered and rng.random() < idle:
                    valid = 0
                else:
                    valid, offered = 1, True
                if room and rng.random() < room_off:
                    room = 0
                elif not room and rng.random() < room_on:
                    room = 1
                inp = self.drive(rst=0, valid=valid, room=room, frame=frame, pixel=pixel)
                await RisingEdge(dut.clk)
                o = self.sample()
                model.check(self.k, inp, o)
                self.k += 1
                if valid and not o["px_ready"] and room:
                    refused[i] += 1
                if o["cstep"]:
                    pixel += 1
                    offered = False
            for _ in range(frame.gap):
                await self.idle_clock(room_off, room_on)
        return refused

    async def idle_clock(self, room_off: float, room_on: float) -> None:
        room = int(self.dut.rec_room.value)
        if room and self.rng.random() < room_off:
            room = 0
        elif not room and self.rng.random() < room_on:
            room = 1
        inp = self.drive(rst=0, valid=0, room=room, frame=None, pixel=0)
        await RisingEdge(self.dut.clk)
        self.model.check(self.k, inp, self.sample())
        self.k += 1

    async def settle(self) -> None:
        """Idle clocks with room until every row is read, then a few more."""
        for _ in range(5 * MAX_WIDTH + 20):
            if self.model.idle():
                break
            await self.idle_clock(0.0, 1.0)
        assert self.model.idle(), f"rows left unread: {[Model._row(r) for r in self.model.queue]}"
        for _ in range(8):
            await self.idle_clock(0.0, 1.0)

    def report(self, label: str) -> None:
        s = self.model.stats
        self.dut._log.info(
            "%s: %d clocks, %d pixels, %d frames completed, reader steps %d (lock %d, "
            "flush %d), first-row steps beside a flush %d, refused with room %d (PRIME %d), "
            "no room %d, resets %d",
            label,
            s.clocks,
            s.pixels,
            s.frames,
            s.rsteps,
            s.lock,
            s.flush,
            s.beside,
            s.refused,
            s.prime_refused,
            s.no_room,
            s.resets,
        )

    def random_width(self, prev: int | None) -> int:
        rng = self.rng
        c = rng.random()
        if prev is not None and c < 0.25:
            return rng.randint(MIN_WIDTH, prev)  # narrower (or as wide)
        if prev is not None and c < 0.4:
            return rng.randint(prev, WIDE) if prev <= WIDE else prev
        if c < 0.5:
            return rng.choice([MIN_WIDTH, MIN_WIDTH + 1, WIDE - 1, WIDE, MAX_WIDTH])
        if c < 0.55:
            return rng.randint(MIN_WIDTH, MAX_WIDTH)
        return rng.randint(MIN_WIDTH, WIDE)

    def random_height(self) -> int:
        c = self.rng.random()
        if c < 0.3:
            return 1
        if c < 0.9:
            return self.rng.randint(2, min(4, TALLEST)) if TALLEST >= 2 else 1
        return self.rng.randint(1, TALLEST)


@cocotb.test()
async def random_sequences(dut):
    """Random frame sequences in regimes (back to back or with gaps between
    frames, random input gaps, random periods without room), narrower and
    wider frames, runs of one-row frames, resets in mid-frame (or mid-flush)
    followed by a clean frame: every check of the module docstring on every
    clock; at the end every row written is read."""
    tb = TB(dut)
    rng = tb.rng
    await tb.reset()
    regimes = [
        # idle, room_off, room_on, gap between frames (max)
        (0.0, 0.0, 1.0, 0),
        (0.3, 0.0, 1.0, 0),
        (0.0, 0.2, 0.3, 0),
        (0.3, 0.3, 0.5, 0),
        (0.0, 0.0, 1.0, MAX_WIDTH + 6),
        (0.5, 0.1, 0.2, 8),
        (0.05, 0.05, 0.6, 3),
    ]
    reset_frames = set(rng.sample(range(10, FRAMES), min(RESETS, max(0, FRAMES - 10))))
    done = 0
    prev = None
    while done < FRAMES:
        idle, room_off, room_on, gap = rng.choice(regimes)
        frames = []
        for _ in range(rng.randint(2, 8)):
            h = 1 if rng.random() < 0.15 else tb.random_height()  # runs of one-row frames
            w = tb.random_width(prev)
            prev = w
            frame = tb.new_frame(w, h)
            frame.gap = rng.randint(0, gap) if gap else 0
            if done in reset_frames:
                frame.reset_at = rng.randint(0, w * h - 1)
            frames.append(frame)
            done += 1
        await tb.run(frames, idle=idle, room_off=room_off, room_on=room_on)
    await tb.settle()
    tb.report("random_sequences")
    s = tb.model.stats
    assert s.resets == 1 + len(reset_frames)
    if FRAMES >= 50:  # the cases the contract is about all happened
        assert s.flush and s.beside and s.lock and s.no_room and s.prime_refused


@cocotb.test()
async def throughput(dut):
    """No input gap and room on every clock. Frames never narrower than the one
    before them: px_ready never low (W x H clocks per frame back to back), each
    flush's W columns on the W clocks after its frame's last pixel. Any
    sequence (narrower, wider, runs of one-row frames): up to the end of any
    frame, at most the sum over its narrower frames of W_previous - W + 4
    refused clocks. A one-row narrower frame followed by another frame: that
    bound exactly (docs: the bound is reached)."""
    tb = TB(dut)
    rng = tb.rng
    await tb.reset()
    cases: list[tuple[str, list[tuple[int, int]]]] = []
    for _ in range(6):  # never narrower
        widths = sorted(tb.random_width(None) for _ in range(rng.randint(2, 5)))
        cases.append(("wider", [(w, tb.random_height()) for w in widths]))
    cases.append(("same", [(MAX_WIDTH, 2), (MAX_WIDTH, 1), (MAX_WIDTH, 1), (MAX_WIDTH, 3)]))
    cases.append(("same3", [(3, 1), (3, 1), (3, 2), (3, 1)]))
    worst = [(MAX_WIDTH, 2, MIN_WIDTH), (MAX_WIDTH, 1, MAX_WIDTH - 1)]
    worst += [(rng.randint(MIN_WIDTH + 1, WIDE), rng.randint(1, 3), 0) for _ in range(3)]
    for wp, hp, w in worst:
        w = w or rng.randint(MIN_WIDTH, wp - 1)
        nxt = rng.randint(w, WIDE if w <= WIDE else w)  # not narrower: it adds no wait of its own
        cases.append(("reached", [(wp, hp), (w, 1), (nxt, tb.random_height())]))
    for _ in range(8):
        sizes, prev = [], None
        for _ in range(rng.randint(2, 6)):
            w = tb.random_width(prev)
            sizes.append((w, 1 if rng.random() < 0.4 else tb.random_height()))
            prev = w
        cases.append(("random", sizes))
    for kind, sizes in cases:
        frames = [tb.new_frame(w, h) for w, h in sizes]
        first_clock = tb.k
        refused = await tb.run(frames)
        last_clock = tb.k - 1  # the clock of the last pixel
        await tb.settle()
        bound, total = 0, 0
        for i, (w, _) in enumerate(sizes):
            if i and w < sizes[i - 1][0]:
                bound += sizes[i - 1][0] - w + 4
            total += refused[i]
            assert total <= bound, (
                f"{kind} {sizes}: {total} clocks refused by frame {i}, bound {bound}"
            )
        narrower = any(w < sizes[i - 1][0] for i, (w, _) in enumerate(sizes) if i)
        pixels = sum(w * h for w, h in sizes)
        flushes = tb.model.flushes[-len(sizes) :]
        assert [f.serial for f in flushes] == [f.serial for f in frames]
        if not narrower:
            assert total == 0
            assert last_clock - first_clock + 1 == pixels, (
                f"{kind} {sizes}: {last_clock - first_clock + 1} clocks for {pixels} pixels"
            )
            for f in flushes:
                assert (f.first_step, f.last_step) == (f.eof_clock + 1, f.eof_clock + f.w), (
                    f"{kind} {sizes}: the flush of frame {f.serial} ({f.w} wide) from clock "
                    f"{f.first_step} to {f.last_step}, its last pixel at {f.eof_clock}"
                )
        if kind == "reached":
            assert total == bound, f"{kind} {sizes}: {total} clocks refused, the bound is {bound}"
        dut._log.info("%s %s: %d refused, bound %d", kind, sizes, total, bound)
    tb.report("throughput")
