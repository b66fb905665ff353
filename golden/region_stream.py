"""Step-by-step model of the region NMS hardware (rtl/nms/fastnms_nms_region.vhd).

It holds exactly the state the RTL holds and changes it with the same operations, one column
per step: the previous row's corner bits (row memory), a data table and two bit tables indexed
by run slot (start column // 2), a stack of the previous row's open classes, and the current
run's class. The bit tables say, per run, whether it is the first run of its class in its row
("head", kept per row parity) and whether it is the last ("last"). Its records, in closing
order, must equal `nms.nms_region` as sets; its asserts are the design's invariants (the stack
discipline, one access per memory port per step, every table word read in the row after the
one that wrote it). docs/fastnms_nms_region.md explains
the algorithm; this file is its executable form.

Why no content needs a stall: the classes of one row's runs never cross (two regions cannot
interleave along a row without meeting above it), so the open classes of the previous row
nest and live on a stack, and every operation of a step touches only the stack's top two
entries, the current run's class and one word of each table. Nesting also makes the stack's
moves known from two bits per run of the previous row: a run that is not its class's first
continues the class on top (the only open class it can belong to), a first run pushes; the
class's last run pops it.

Parts, named as the RTL's entities (docs/fastnms_nms_region.md, Parts): `RegionStream.run` is
the schedule (fastnms_nms_region_schedule: which side steps each clock, the flush); the
`_Table`s are the tables (fastnms_nms_region_tables; the hardware reads them ahead of the
reader, which the model needs not); `RegionStream.step` is the control
(fastnms_nms_region_control: its flags, `Entry.last`/`merged`, `head != NONE` as the RTL's
`runs`, `attached`, `active` and which numbered operation happens) and the key data path
(fastnms_nms_region_keys: the keys and slots those operations move, the table writes, the
records) in one, as the hardware's two halves a clock apart make the same operations.

Clock schedule (what `RegionStream.run` models clock by clock): a current-row step takes one
input pixel; rows >= 1 step the previous row's reader in lock-step with it. After a frame's
last pixel the reader "flushes" that last row alone (no current row), one column per clock,
in parallel with the next frame's first row (which has no previous row), then emits the
end-of-frame beat. The input waits only for the output (a full record buffer) and, when a
frame is narrower than the one before it, at its first row's last pixel for the flush's last
column (after a one-row frame, the next frame waits for the flushes queued before it).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .nms import AREA_MAX

NONE = -1  # "no slot" in head and tail fields


def key(score: int, x: int, y: int) -> tuple[int, int, int]:
    """Larger key = better: higher score, then earlier in raster order."""
    return (score, -y, -x)


def best(a: tuple[int, int, int], b: tuple[int, int, int]) -> tuple[int, int, int]:
    return a if a >= b else b


def add_area(a: int, b: int) -> int:
    """Areas merge by addition, saturating as the hardware's AREA_BITS-bit sum does."""
    return min(a + b, AREA_MAX)


@dataclass
class Entry:
    """A previous-row class on the stack (an open region seen from the current row)."""

    last: bool  # its run under the reader is its last in the previous row
    data: tuple[int, int, int]  # best key (valid unless merged into the entry above)
    area: int  # its corner pixels so far, saturated (valid with data)
    head: int = NONE  # slot of its first run in the current row, NONE if none yet
    tail: int = NONE  # slot of its latest run in the current row
    merged: bool = False  # holds the data of the entry below too (merged with it)
    merge_step: int = -2  # step of the last full-key merge into its data (Stats.chained_merges)


@dataclass
class Group:
    """The current run's class while it is not attached to the stack's top."""

    data: tuple[int, int, int]
    area: int
    head: int
    tail: int
    merge_step: int = -2


@dataclass
class Stats:
    max_depth: int = 0
    steps: int = 0
    flush_steps: int = 0
    records: int = 0
    clocks: int = 0
    # Full-key merges (two classes, step 3) with an operand that the previous step's full-key
    # merge produced: the hardware cannot compare it on registers of its own before then
    # (fastnms_nms_region.md, Depth and clock). By the column of the second merge: 0, or later.
    chained_merges_col0: int = 0
    chained_merges_in_row: int = 0


@dataclass
class _Table:
    """One RAM: word per slot, with the (frame, row) that wrote it, to check the schedule.
    (The tables part of the RTL: fastnms_nms_region_tables.)"""

    words: dict[int, tuple[object, tuple[int, int]]] = field(default_factory=dict)
    writes_this_step: int = 0
    allowed: int = 1  # writes the port can take in this step (2 with the spare register)
    total: int = 0

    def write(self, slot: int, value: object, tag: tuple[int, int]) -> None:
        self.writes_this_step += 1
        self.total += 1
        assert self.writes_this_step <= self.allowed, "more writes than the port takes"
        self.words[slot] = (value, tag)

    def read(self, slot: int, tag: tuple[int, int]) -> object:
        value, written = self.words[slot]
        assert written == tag, f"slot {slot} holds row {written}, expected {tag}"
        return value


class RegionStream:
    """The region NMS state machine. `step` advances one column; `run` schedules clocks."""

    def __init__(self, connectivity: int, max_width: int):
        if connectivity not in (4, 8):
            raise ValueError("connectivity must be 4 or 8")
        self.conn8 = connectivity == 8
        self.max_width = max_width
        self.stack_depth = stack_depth(max_width)
        self.data = _Table()
        self.head = _Table()  # word (row parity, slot): the run is its class's first
        self.last = _Table()  # word slot: the run is its class's last
        self.parity: dict[tuple[int, int], int] = {}  # (frame, row) -> global row parity
        self.rows_seen = 0
        self.stack: list[Entry] = []
        self.stats = Stats()
        self.step_count = 0
        self.table_merge_step: dict[int, int] = {}  # data table slot -> its key's merge_step
        self.out: list[tuple[int, int, int, int]] = []  # x, y, score, area
        self._reset_current()

    def _reset_current(self) -> None:
        self.group: Group | None = None  # current run's class when not attached
        self.attached = False  # current run belongs to the stack's top
        self.active = False  # a current run is open

    # ---- one column ---------------------------------------------------------------------

    def step(
        self,
        x: int,
        width: int,
        prev: tuple[int, int] | None,
        cur: tuple[int, int, int] | None,
        prev_tag: tuple[int, int],
        cur_tag: tuple[int, int],
    ) -> None:
        """Column x of a row of `width`: the control's decisions (fastnms_nms_region_control)
        and the key data path's moves of keys, slots and table words
        (fastnms_nms_region_keys), which the RTL makes a clock apart.

        prev: (bit at x - 1, bit at x) of the previous row, or None when the reader does not
        step (first row of a frame). cur: (bit at x - 1, bit at x, score at x) of the current
        row, or None (flush). prev_tag / cur_tag: (frame, row) of those rows.
        """
        eol = x == width - 1
        self.step_count += 1
        for t in self.tables:
            t.writes_this_step = 0
        # The last column of a row may write a table twice (a current run and a previous-row
        # run that end there without touching finalize two classes; or a contact links and
        # the class then ends); the second write waits in a spare register for the next
        # clock, whose step (column 0, or a flush) never writes.
        for t in self.tables:
            t.allowed = 2 if eol else 1
        pm, p0 = prev if prev is not None else (0, 0)
        cm, c0, score = cur if cur is not None else (0, 0, 0)
        slot = x // 2
        pushed = False
        # 1. A previous-row run starts: a run that is not its class's first continues the top
        # (classes nest, so its class is the top), a first run pushes its class.
        if p0 and not pm:
            last = self.last.read(slot, prev_tag)
            if not self.head.read((self.parity[prev_tag], slot), prev_tag):
                assert self.stack, "a continuing run without an open class"
                self.stack[-1].last = last
            else:
                data, area = self.data.read(slot, prev_tag)
                self.stack.append(Entry(last, data, area, merge_step=self.table_merge_step[slot]))
                pushed = True
                assert len(self.stack) <= self.stack_depth, "stack overflow"
                self.stats.max_depth = max(self.stats.max_depth, len(self.stack))
        # 2. A current-row run starts: a class of its own until it touches the previous row.
        if c0 and not cm:
            self.group = Group(key(score, x, cur_tag[1]), 1, slot, slot)
            self.attached = False
            self.active = True
        # 3. Contact between the current run and a previous-row run (always the top's).
        touch = bool(prev is not None and cur is not None) and (
            bool(c0 and p0) or (self.conn8 and bool((c0 and pm) or (cm and p0)))
        )
        if touch:
            top = self.stack[-1]
            if not self.attached:
                g = self.group
                if top.head == NONE:
                    top.head = g.head
                else:  # the class's latest run is no longer its last, g's first not a first
                    self.last.write(top.tail, False, cur_tag)
                    self.head.write((self.parity[cur_tag], g.head), False, cur_tag)
                top.tail = g.tail
                self._count_chained(x, top, g)
                top.data = best(top.data, g.data)
                top.area = add_area(top.area, g.area)
                self.group = None
                self.attached = True
            elif pushed:
                # The current run's class is the entry below: the new entry takes it over.
                below = self.stack[-2]
                assert below.head != NONE
                self._count_chained(x, top, below)
                top.data = best(top.data, below.data)
                top.area = add_area(top.area, below.area)
                top.head, top.tail = below.head, below.tail
                top.merged = True
        # 4. The current pixel joins its run's class.
        if c0 and cm:
            pix = key(score, x, cur_tag[1])
            owner = self.stack[-1] if self.attached else self.group
            owner.data = best(owner.data, pix)
            owner.area = add_area(owner.area, 1)
        # 5. The current run ends (at x - 1, or at x at the end of the row).
        if (cm and not c0) or (c0 and eol):
            if not self.attached:
                self._finalize(self.group, cur_tag)
            self._reset_current()
        # 6. A previous-row run ends: the last run of its class pops it.
        if ((pm and not p0) or (p0 and eol)) and self.stack[-1].last:
            e = self.stack.pop()
            if e.merged:
                below = self.stack[-1]
                below.data, below.area, below.head, below.tail = e.data, e.area, e.head, e.tail
                below.merge_step = e.merge_step
            elif self.active and self.attached:
                self.group = Group(e.data, e.area, e.head, e.tail, e.merge_step)
                self.attached = False
            elif e.head != NONE:
                self._finalize(e, cur_tag)
            else:
                score_, ny, nx = e.data
                self.out.append((-nx, -ny, score_, e.area))
                self.stats.records += 1
        if eol and cur is not None:
            assert not self.active
        if eol and prev is not None and cur is not None:
            assert not self.stack, "classes left open at the end of a row"

    @property
    def tables(self) -> tuple[_Table, _Table, _Table]:
        return (self.data, self.head, self.last)

    def _finalize(self, g: Group | Entry, tag: tuple[int, int]) -> None:
        """The class has all its current-row runs: its data waits at its first run's slot,
        which is marked first, and its latest run is marked last."""
        self.data.write(g.head, (g.data, g.area), tag)
        self.table_merge_step[g.head] = g.merge_step
        self.head.write((self.parity[tag], g.head), True, tag)
        self.last.write(g.tail, True, tag)

    def _count_chained(self, x: int, a: Entry, b: Entry | Group) -> None:
        """A full-key merge of a and b (into a) in this step."""
        if self.step_count - 1 in (a.merge_step, b.merge_step):
            if x == 0:
                self.stats.chained_merges_col0 += 1
            else:
                self.stats.chained_merges_in_row += 1
        a.merge_step = self.step_count

    # ---- clock schedule -------------------------------------------------------------------

    def run(
        self,
        frames: list[tuple[np.ndarray, np.ndarray]],
        in_valid=None,
        out_ready=None,
        out_depth: int = 4,
    ) -> tuple[list[list[tuple[int, int, int, int]]], list[int]]:
        """Frames back to back through the clock schedule (fastnms_nms_region_schedule).

        in_valid(clock) / out_ready(clock): the input offers a pixel / the consumer takes a
        record in that clock (default: always). Returns per frame its records in output order
        and the clock of its end-of-frame beat.
        """
        in_valid = in_valid or (lambda _c: True)
        out_ready = out_ready or (lambda _c: True)
        bits = {}  # (frame, y) -> corner bits of the row
        pixels = []  # (frame, y, x, width, height, score)
        for f, (corner, score) in enumerate(frames):
            h, w = corner.shape
            assert 3 <= w <= self.max_width, "width out of range"
            for y in range(h):
                bits[(f, y)] = [int(b) for b in corner[y]]
                # The parity of the row counted over every frame, as the hardware counts it.
                self.parity[(f, y)] = self.rows_seen % 2
                self.rows_seen += 1
                pixels += [(f, y, x, w, h, int(score[y, x])) for x in range(w)]
        per_frame: list[list[tuple[int, int, int, int]]] = [[] for _ in frames]
        eof_clock = [0] * len(frames)
        order: list[int] = []  # frame of each beat leaving, to check frames do not mix
        fifo: list[tuple[str, int, tuple[int, int, int, int] | None]] = []
        flush = None  # [frame, column, width, height]: the reader flushing a last row
        queued = None  # the next frame's flush, when its last pixel came before the reader
        eof_pending = None  # frame whose end-of-frame beat is due
        i = clock = 0
        spare_busy = {id(t): False for t in self.tables}
        while i < len(pixels) or flush or queued or eof_pending is not None or fifo:
            if fifo and out_ready(clock):
                kind, f, rec = fifo.pop(0)
                order.append(f)
                if kind == "eof":
                    eof_clock[f] = clock
                else:
                    per_frame[f].append(rec)
            room = len(fifo) < out_depth  # a clock emits at most one record
            before = {id(t): t.total for t in self.tables}
            emitted = []
            flushed_past = -1
            if flush is None and queued is not None:
                flush, queued = queued, None
            if flush and room:  # the reader alone, on a frame's last row
                ff, fx, fw, fh = flush
                up = bits[(ff, fh - 1)]
                tag = (ff, fh - 1)
                n0 = len(self.out)
                self.step(fx, fw, (up[fx - 1] if fx else 0, up[fx]), None, tag, tag)
                emitted += [("rec", ff, r) for r in self.out[n0:]]
                self.stats.flush_steps += 1
                flush[1] += 1
                flushed_past = fx
            if i < len(pixels) and in_valid(clock) and room:
                f, y, x, w, h, s = pixels[i]
                if y >= 1:  # needs the reader, in lock-step
                    go = flush is None and queued is None
                else:  # no previous row: steps with the previous frame's flush, which
                    # started first, so never overtakes it; its last column waits for the
                    # flush's last (it writes the slot of column x + 1 of a wider flush)
                    go = queued is None and (
                        flush is None
                        or (flushed_past >= 0 and (x < w - 1 or flushed_past == flush[2] - 1))
                    )
                    assert not (go and flush is not None and x > flushed_past), "overtaken"
                if go:
                    row = bits[(f, y)]
                    prev = None
                    if y >= 1:
                        up = bits[(f, y - 1)]
                        prev = (up[x - 1] if x else 0, up[x])
                    n0 = len(self.out)
                    self.step(x, w, prev, (row[x - 1] if x else 0, row[x], s), (f, y - 1), (f, y))
                    emitted += [("rec", f, r) for r in self.out[n0:]]
                    self.stats.steps += 1
                    i += 1
                    if x == w - 1 and y == h - 1:
                        queued = [f, 0, w, h]
            assert len(emitted) <= 1, "two records in one clock"
            if flush and flush[1] == flush[2]:
                flush, eof_done = None, flush[0]
            else:
                eof_done = None
            if eof_pending is not None and not emitted and room:
                emitted.append(("eof", eof_pending, None))
                eof_pending = None
            fifo += emitted
            for t in self.tables:  # one write port, one spare register
                n = t.total - before[id(t)]
                assert n <= 2 and not (spare_busy[id(t)] and n), "write port overbooked"
                spare_busy[id(t)] = n == 2
            if eof_done is not None:
                assert eof_pending is None
                eof_pending = eof_done
            clock += 1
        assert order == sorted(order), "records of two frames mixed"
        self.stats.clocks = clock
        return per_frame, eof_clock


def stack_depth(max_width: int) -> int:
    """Open classes of the previous row at once: each entry below the top has a run left of
    the column and one right of it, all distinct, so at most (MAX_WIDTH + 1) // 4 + 1."""
    return (max_width + 1) // 4 + 1
