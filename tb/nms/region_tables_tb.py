"""cocotb testbench of fastnms_nms_region_tables on its own, against a Python
model of its contract.

The inputs are driven as the schedule and the key data path drive them (a
model reader and random writes); the model is the three tables as memories,
each write applied at the end of the clock it is on the port (it "lands").
On every clock after a fill (and after a reset, once slot 0 is written
again) the outputs are compared exactly with the model, the reader being at
column x of a row of width W (slot(x) = x // 2, bank rb):

- run_head = 1 at columns 0 and 1 (the row's first run is a first), else
  the head word (slot(x), rb) with every write landed before this clock,
  and at column 2 the head write on the port now when it is to (1, rb) (the
  previous row's last column's second write, from the spare register);
- run_last = the last word of slot(x) with the writes landed before this
  clock, or the last write on the port now when it is to slot 0 at columns
  0 and 1 or to slot 1 at column 2 (the row-boundary cases, flagged _s0/_s1);
- data_word = the data word of slot(xd), xd being the reader's column on the
  clock before (the operation's column: op and op_slot are registered by the
  control), with the writes landed before this clock.

The reader (fastnms_nms_region_schedule): rows of random widths from 3 to
MAX_WIDTH with random corner bits (pm, p0: the bits at x - 1 and x, pm = 0 at
column 0), rstep = 1 steps one column (the last column to column 0 of the
next row, toggling r_bank), random idle clocks between steps; r_col0/1/2,
r_slot0, r_last from the column; ahead_slot = slot((x + 2) mod W). The
operation (fastnms_nms_region_control, registered): rv = the clock before's
rstep, op_slot its ahead_slot, r_col0 its r_col0, push = its p_start (p0 and
not pm) and run_head; op's other bits random (the tables ignore them).

The writes (fastnms_nms_region_keys): at most one per table per clock, to
random slots (biased to the reader's words and to slots 0 and 1), random
bits and keys, their flags from their slot (_s0: slot 0, _s1: slot 1, as
the keys compute them); a head write may come with a second one in the
spare register, which is the head port's write on the next clock (no other
head write then). At the end of a reader row the previous row's last
column's writes are replayed as the keys time them: first writes two clocks
after the reader's step from its last column, the second (head from the
spare register) a clock later, to slots 0 and 1 and to random ones.

Preconditions respected (the tables' assertions, severity failure, stop the
simulation otherwise): on a reader step where a previous-row run starts (p0
and not pm) no last write to slot(x) at columns >= 3 and no head write to
(slot(x), rb) at columns >= 2 unless it is the spare's (1, rb) at column 2; a
head write to (1, rb) at column 2 is always the spare's; on a clock whose
operation has push and rv no data write to slot(xd) unless xd = 0 and the
write is to slot 0. A free write that breaks one is dropped; a spare write
that would break one makes the reader idle on that clock. After a reset the
reader's reads in flight are of slot 0 (the schedule's reset: column 0, its
read two ahead): slot 0 of the last and data tables is written before the
reader steps (their values before are undefined). No write lands on a reset
clock (the keys reset their write registers).
"""

from __future__ import annotations

import ast
import os
import random
from collections import Counter

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import RisingEdge

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
MAX_WIDTH = GENERICS["MAX_WIDTH"]
SLOTS = (MAX_WIDTH + 1) // 2
# Reader steps of the random test, and the mid-run resets in it.
STEPS = int(os.environ.get("TB_STEPS", "4000"))
RESETS = int(os.environ.get("TB_RESETS", "2"))
# The narrowest row is 3 wide. Half the rows are 3 to 6 wide and most of the
# others at most 64, so that rows wrap often whatever MAX_WIDTH.
MIN_WIDTH = 3

# op_t's bits (fastnms_nms_region_pkg, to_slv): the three the tables read.
OP_BITS = 31
OP_PUSH = 30
OP_RV = 4
OP_R_COL0 = 1


def read(signal) -> int | str:
    """A signal's value as an integer, or its text when it has undefined bits."""
    try:
        return int(signal.value)
    except ValueError:
        return str(signal.value)


class Reader:
    """The previous row's reader as fastnms_nms_region_schedule walks it:
    rows of random widths and corner bits, column x, bank rb."""

    def __init__(self, rng: random.Random):
        self.rng = rng
        self.reset()

    def reset(self) -> None:
        """The schedule's reset: column 0 of a new row, bank 0."""
        self.bank = 0
        self.x = 0
        self.new_row()

    def new_row(self) -> None:
        rng = self.rng
        c = rng.random()
        if c < 0.5:
            self.width = rng.randint(MIN_WIDTH, min(MAX_WIDTH, 6))
        elif c < 0.9:
            self.width = rng.randint(MIN_WIDTH, min(MAX_WIDTH, 64))
        else:
            self.width = rng.randint(MIN_WIDTH, MAX_WIDTH)
        density = rng.choice([0.1, 0.5, 0.9])
        self.bits = [int(rng.random() < density) for _ in range(self.width)]
        # How often the reader idles on this row (per clock).
        self.idle = rng.choice([0.0, 0.2, 0.5, 0.8])

    @staticmethod
    def slot(x: int) -> int:
        return x // 2

    @property
    def pm(self) -> int:
        return self.bits[self.x - 1] if self.x > 0 else 0

    @property
    def p0(self) -> int:
        return self.bits[self.x]

    @property
    def p_start(self) -> bool:
        return self.p0 == 1 and self.pm == 0

    @property
    def last(self) -> bool:
        return self.x == self.width - 1

    @property
    def ahead_slot(self) -> int:
        """The slot read ahead: the column two ahead, in the next row past the end."""
        return ((self.x + 2) % self.width) // 2

    def step(self) -> bool:
        """One column on; True when the reader left its row's last column."""
        if self.last:
            self.x = 0
            self.bank ^= 1
            self.new_row()
            return True
        self.x += 1
        return False


class Write:
    """One write on a table's port: slot, bank (head table only) and value."""

    __slots__ = ("slot", "bank", "value")

    def __init__(self, slot: int, value: int, bank: int = 0):
        self.slot, self.value, self.bank = slot, value, bank


class TB:
    def __init__(self, dut):
        self.dut = dut
        self.rng = random.Random(cocotb.RANDOM_SEED)
        dut._log.info("seed=%d generics %s", cocotb.RANDOM_SEED, GENERICS)
        self.data_bits = len(dut.data_word)
        cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
        self.reader = Reader(self.rng)
        # The tables: head by (slot, bank), last and data by slot.
        self.head = [[0, 0] for _ in range(SLOTS)]
        self.last = [0] * SLOTS
        self.data = [0] * SLOTS
        # The clock before's reader and operation inputs (the control's
        # registers: the operation seen now).
        self.op_rv = 0
        self.op_push = 0
        self.op_col0 = 0
        self.op_slot = 0
        self.op_x = 0  # the reader's column on the clock before (the data word's)
        self.spare: Write | None = None  # the head write waiting in the spare register
        # The previous row's last column's writes, replayed: clock offset -> writes.
        self.boundary: dict[int, dict[str, Write]] = {}
        self.clock = 0
        self.checking = False
        self.known0 = {"last": True, "data": True}  # slot 0 readable since the reset
        self.cover: Counter[str] = Counter()
        self.compared = 0
        self.steps = 0
        self.idle_clocks = 0
        self._driven: dict[str, int] = {}
        for name, v in self.idle_inputs().items():
            self.drive(name, v)

    def drive(self, name: str, v: int) -> None:
        if self._driven.get(name) != v:
            getattr(self.dut, name).value = v
            self._driven[name] = v

    @staticmethod
    def idle_inputs() -> dict[str, int]:
        names = (
            "rst rstep pm p0 r_last r_col0 r_col1 r_col2 r_slot0 r_bank ahead_slot op op_slot "
            "data_w_en data_w_slot data_w_key data_w_s0 head_w_en head_w_addr head_w_bit "
            "head_w_s1 head_spare_en head_spare_addr head_spare_bit head_spare_s1 last_w_en "
            "last_w_addr last_w_bit last_w_s0 last_w_s1"
        )
        return dict.fromkeys(names.split(), 0)

    # -- stimulus ------------------------------------------------------------

    def random_slot(self) -> int:
        """A slot biased to the reader's words (now, next, read ahead) and to 0 and 1."""
        r, rng = self.reader, self.rng
        c = rng.random()
        if c < 0.35:
            x = min(r.x + rng.randint(-1, 3), r.width - 1)
            return r.slot(max(x, 0))
        if c < 0.5:
            return r.ahead_slot
        if c < 0.65:
            return rng.randint(0, min(1, SLOTS - 1))
        return rng.randrange(SLOTS)

    def random_head(self) -> Write:
        bank = self.reader.bank if self.rng.random() < 0.7 else self.rng.randint(0, 1)
        return Write(self.random_slot(), self.rng.randint(0, 1), bank)

    def random_spare(self) -> Write:
        """A second head write; near column 2 often to slot 1 of either bank (the
        spare's write taken at column 2 is the reader's bank only)."""
        r, rng = self.reader, self.rng
        if r.x in (1, 2) and rng.random() < 0.5:
            return Write(min(1, SLOTS - 1), rng.randint(0, 1), rng.randint(0, 1))
        return self.random_head()

    def key(self) -> int:
        return self.rng.getrandbits(self.data_bits)

    def boundary_writes(self) -> None:
        """After the reader's step from its last column (the control's step at
        the current row's last column, lock-step or a flush): the keys' first
        writes two clocks later, the second (the head's from its spare
        register) three clocks later, to the row the reader now takes."""
        rng, bank = self.rng, self.reader.bank

        def slot() -> int:
            return rng.choice([0, 1, 1, rng.randrange(SLOTS)]) if SLOTS > 1 else 0

        first: dict[str, Write] = {}
        second: dict[str, Write] = {}
        if rng.random() < 0.8:
            first["last"] = Write(rng.choice([0, 0, slot()]), rng.randint(0, 1))
        if rng.random() < 0.6:
            first["data"] = Write(rng.choice([0, slot()]), self.key())
        if rng.random() < 0.8:
            first["head"] = Write(slot(), rng.randint(0, 1), bank)
            if rng.random() < 0.7:
                second["head"] = Write(rng.choice([1, 1, slot()]), rng.randint(0, 1), bank)
        if rng.random() < 0.5 and "last" in first:
            second["last"] = Write(rng.choice([1, slot()]), 1)
        if rng.random() < 0.3 and "data" in first:
            second["data"] = Write(slot(), self.key())
        self.boundary[self.clock + 2] = first
        self.boundary[self.clock + 3] = second

    def choose_writes(self) -> tuple[dict[str, Write], Write | None, bool]:
        """This clock's writes (head, last, data), the spare register's next
        content, and whether the head write is the spare's."""
        rng = self.rng
        writes: dict[str, Write] = {}
        spare_next = None
        from_spare = False
        replay = self.boundary.pop(self.clock, {})
        if self.spare is not None:
            writes["head"] = self.spare
            from_spare = True
        elif "head" in replay:
            writes["head"] = replay["head"]
            nxt = self.boundary.get(self.clock + 1, {})
            if "head" in nxt:
                spare_next = nxt.pop("head")
        elif rng.random() < 0.35:
            writes["head"] = self.random_head()
            if rng.random() < 0.15:
                spare_next = self.random_spare()
        if "last" in replay:
            writes["last"] = replay["last"]
        elif rng.random() < 0.35:
            writes["last"] = Write(self.random_slot(), rng.randint(0, 1))
        if "data" in replay:
            writes["data"] = replay["data"]
        elif rng.random() < 0.35:
            writes["data"] = Write(self.random_slot(), self.key())
        return writes, spare_next, from_spare

    def legal(self, writes: dict[str, Write], from_spare: bool, rstep: bool) -> dict[str, str]:
        """The writes that break a precondition (the tables' assertions) with this
        reader step: table -> why."""
        r = self.reader
        bad = {}
        taken = rstep and r.p_start
        w = writes.get("last")
        if w is not None and taken and w.slot == r.slot(r.x) and r.x >= 3:
            bad["last"] = "last bit taken at a column >= 3"
        w = writes.get("head")
        if w is not None and w.bank == r.bank:
            if r.x == 2 and w.slot == 1 and not from_spare:
                bad["head"] = "head bit of slot 1 at column 2 not from the spare register"
            elif taken and r.x >= 2 and w.slot == r.slot(r.x) and not (r.x == 2 and from_spare):
                bad["head"] = "head bit taken"
        w = writes.get("data")
        if (
            w is not None
            and self.op_push
            and self.op_rv
            and w.slot == self.op_x // 2
            and not (self.op_x == 0 and w.slot == 0)
        ):
            bad["data"] = "data word taken"
        return bad

    # -- the model -------------------------------------------------------------

    def expected(self, writes: dict[str, Write]) -> dict[str, int]:
        """run_head, run_last, data_word on this clock (writes: the ones landing
        at its end); counts the cases seen."""
        r = self.reader
        x, s = r.x, r.slot(r.x)
        if x < 2:
            head = 1
        else:
            head = self.head[s][r.bank]
            w = writes.get("head")
            if x == 2 and w is not None and (w.slot, w.bank) == (1, r.bank):
                head = w.value
                if self.checking:
                    self.cover["head: spare's write at column 2"] += 1
        last = self.last[s]
        w = writes.get("last")
        if w is not None and ((x < 2 and w.slot == 0) or (x == 2 and w.slot == 1)):
            last = w.value
            if self.checking:
                self.cover[f"last: write landing at column {x} taken"] += 1
        return {"run_head": head, "run_last": last, "data_word": self.data[self.op_x // 2]}

    def count(self, writes: dict[str, Write], rstep: bool) -> None:
        """Coverage of the reads in flight: writes to the word being taken, to the
        next column's (read a step ago), to the one read now."""
        r = self.reader
        now = r.slot(r.x)
        nxt = r.slot(r.x + 1) if r.x + 1 < r.width else 0
        kind = "step" if rstep else "idle"
        for table in ("head", "last"):
            w = writes.get(table)
            if w is None or (table == "head" and (w.bank != r.bank or r.x < 2)):
                continue
            if w.slot == now:
                self.cover[f"{table}: write to the word taken, {kind}"] += 1
                if rstep and r.p_start:
                    self.cover[f"{table}: write to the word taken by a run start"] += 1
            if w.slot == nxt and nxt != now:
                self.cover[f"{table}: write to the next column's word, {kind}"] += 1
            if rstep and w.slot == r.ahead_slot:
                self.cover[f"{table}: write to the word read now"] += 1
        w = writes.get("data")
        if w is not None:
            if w.slot == self.op_x // 2:
                self.cover[f"data: write to the word taken, rv={self.op_rv}"] += 1
                if self.op_push and self.op_rv:
                    self.cover["data: slot-0 write as a push at column 0 takes it"] += 1
            if self.op_rv and w.slot == self.op_slot:
                self.cover["data: write to the word read now"] += 1
        if rstep and r.last:
            self.cover["row ends"] += 1

    def land(self, writes: dict[str, Write]) -> None:
        for table, w in writes.items():
            if table == "head":
                self.head[w.slot][w.bank] = w.value
            elif table == "last":
                self.last[w.slot] = w.value
            else:
                self.data[w.slot] = w.value
            if w.slot == 0 and table in self.known0:
                self.known0[table] = True

    # -- one clock -------------------------------------------------------------

    async def clock_edge(self, rstep: bool, writes: dict[str, Write], spare_next: Write | None):
        """Drive one clock's inputs, compare the outputs at its end with the
        model, land the writes and move the reader."""
        r, rng = self.reader, self.rng
        d = self.drive
        d("rstep", int(rstep))
        d("pm", r.pm)
        d("p0", r.p0)
        d("r_last", int(r.last))
        d("r_col0", int(r.x == 0))
        d("r_col1", int(r.x == 1))
        d("r_col2", int(r.x == 2))
        d("r_slot0", int(r.x < 2))
        d("r_bank", r.bank)
        d("ahead_slot", r.ahead_slot)
        op = rng.getrandbits(OP_BITS)
        op &= ~((1 << OP_PUSH) | (1 << OP_RV) | (1 << OP_R_COL0))
        op |= (self.op_push << OP_PUSH) | (self.op_rv << OP_RV) | (self.op_col0 << OP_R_COL0)
        d("op", op)
        d("op_slot", self.op_slot)
        w = writes.get("data")
        d("data_w_en", int(w is not None))
        if w is not None:
            d("data_w_slot", w.slot)
            d("data_w_key", w.value)
            d("data_w_s0", int(w.slot == 0))
        w = writes.get("head")
        d("head_w_en", int(w is not None))
        if w is not None:
            d("head_w_addr", 2 * w.slot + w.bank)
            d("head_w_bit", w.value)
            d("head_w_s1", int(w.slot == 1))
        d("head_spare_en", int(spare_next is not None))
        if spare_next is not None:
            d("head_spare_addr", 2 * spare_next.slot + spare_next.bank)
            d("head_spare_bit", spare_next.value)
            d("head_spare_s1", int(spare_next.slot == 1))
        w = writes.get("last")
        d("last_w_en", int(w is not None))
        if w is not None:
            d("last_w_addr", 2 * w.slot)
            d("last_w_bit", w.value)
            d("last_w_s0", int(w.slot == 0))
            d("last_w_s1", int(w.slot == 1))

        want = self.expected(writes)
        await RisingEdge(self.dut.clk)
        if self.checking:
            self.count(writes, rstep)
            for name, v in want.items():
                if name == "run_last" and not self.known0["last"]:
                    continue
                if name == "data_word" and not self.known0["data"]:
                    continue
                got = read(getattr(self.dut, name))
                assert got == v, (
                    f"clock {self.clock}: {name} = {got}, model {v} (reader at column "
                    f"{r.x} of {r.width}, bank {r.bank}, rstep {int(rstep)}, p_start "
                    f"{int(r.p_start)}; data column {self.op_x}, op rv {self.op_rv} push "
                    f"{self.op_push}; writes "
                    f"{ {t: (w.slot, w.bank, w.value) for t, w in writes.items()} })"
                )
                self.compared += 1
        self.land(writes)
        # The control's registers: the operation of this clock's step.
        self.op_rv = int(rstep)
        self.op_push = int(r.p_start and want["run_head"] == 1)
        self.op_col0 = int(r.x == 0)
        self.op_slot = r.ahead_slot
        self.op_x = r.x
        self.spare = spare_next
        self.clock += 1
        if rstep:
            self.steps += 1
            if r.step():
                self.boundary_writes()
        else:
            self.idle_clocks += 1

    async def random_clock(self, may_step: bool = True) -> None:
        """One clock of the reader (a step, or idle) with random legal writes."""
        r, rng = self.reader, self.rng
        writes, spare_next, from_spare = self.choose_writes()
        rstep = may_step and rng.random() >= r.idle
        bad = self.legal(writes, from_spare, rstep)
        if "head" in bad and from_spare:
            # The spare's write lands now whatever the reader does: it idles.
            self.cover["reader idles for the spare's write"] += 1
            rstep = False
            bad = self.legal(writes, from_spare, rstep)
        for table in bad:
            del writes[table]
            if table == "head":
                spare_next = None  # no second write without the first
        assert not self.legal(writes, from_spare, rstep)
        await self.clock_edge(rstep, writes, spare_next)

    # -- phases ------------------------------------------------------------------

    async def reset(self, clocks: int = 3) -> None:
        """rst with no writes and the reader idle; the model's memories are kept
        (the RAMs are not reset), the reader back at column 0 of a new row."""
        for name, v in self.idle_inputs().items():
            self.drive(name, v)
        self.drive("rst", 1)
        for _ in range(clocks):
            await RisingEdge(self.dut.clk)
        self.drive("rst", 0)
        self.reader.reset()
        self.op_rv = self.op_push = self.op_col0 = self.op_slot = self.op_x = 0
        self.spare = None
        self.boundary.clear()
        self.known0 = {"last": False, "data": False}

    async def write_slot0(self) -> None:
        """After a reset: slot 0 of the last and data tables written (the reads
        in flight), the reader idle, with other random writes."""
        while not all(self.known0.values()):
            writes, spare_next, _ = self.choose_writes()
            writes["last"] = Write(0, self.rng.randint(0, 1))
            writes["data"] = Write(0, self.key())
            await self.clock_edge(False, writes, spare_next)

    async def fill(self) -> None:
        """Every word of the three tables written once, the reader idle at column 0."""
        head = [(s, b) for s in range(SLOTS) for b in (0, 1)]
        self.rng.shuffle(head)
        slots = list(range(SLOTS))
        for k, (s, b) in enumerate(head):
            writes = {"head": Write(s, self.rng.randint(0, 1), b)}
            if k < SLOTS:
                writes["last"] = Write(slots[k], self.rng.randint(0, 1))
                writes["data"] = Write(slots[k], self.key())
            await self.clock_edge(False, writes, None)


@cocotb.test()
async def random_rows(dut):
    """Random rows (widths 3 to MAX_WIDTH, random corner bits), random idle
    clocks, random writes to random slots respecting the preconditions, the
    previous row's last column's writes replayed at each row's end (slots 0
    and 1, the head's second from the spare register) and TB_RESETS
    mid-run resets: run_head, run_last and data_word equal to the model on
    every clock; the cases of the contract are counted and each must occur."""
    tb = TB(dut)
    await tb.reset()
    await tb.fill()
    tb.checking = True
    resets_at = sorted(tb.rng.randrange(STEPS // 4, STEPS) for _ in range(RESETS))
    while tb.steps < STEPS:
        if resets_at and tb.steps >= resets_at[0]:
            resets_at.pop(0)
            await tb.reset(tb.rng.randint(1, 3))
            tb.cover["resets"] += 1
            await tb.write_slot0()
        await tb.random_clock()
    # Idle clocks at the end: the outputs hold while writes land.
    for _ in range(20):
        await tb.random_clock(may_step=False)
    dut._log.info(
        "%d reader steps, %d idle clocks, %d outputs compared",
        tb.steps,
        tb.idle_clocks,
        tb.compared,
    )
    for case, n in sorted(tb.cover.items()):
        dut._log.info("  %6d  %s", n, case)
    required = [
        "head: spare's write at column 2",
        "last: write landing at column 0 taken",
        "last: write landing at column 1 taken",
        "last: write landing at column 2 taken",
        "head: write to the word taken, idle",
        "head: write to the next column's word, step",
        "head: write to the next column's word, idle",
        "head: write to the word read now",
        "head: write to the word taken by a run start",
        "last: write to the word taken, step",
        "last: write to the word taken, idle",
        "last: write to the word taken by a run start",
        "last: write to the next column's word, step",
        "last: write to the next column's word, idle",
        "last: write to the word read now",
        "data: write to the word taken, rv=0",
        "data: write to the word taken, rv=1",
        "data: slot-0 write as a push at column 0 takes it",
        "data: write to the word read now",
        "row ends",
    ]
    if RESETS:
        required.append("resets")
    missing = [c for c in required if tb.cover[c] == 0]
    assert not missing, f"cases never seen: {missing}"
    assert tb.compared > 3 * STEPS
