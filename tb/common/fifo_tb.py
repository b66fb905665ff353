"""cocotb testbench of fastnms_fifo: data order, capacity, in_ready,
almost_full and out_valid against a model of the RAM's fill level on every
clock, and the guarantees of the header against a count of the words inside,
under random valid/ready."""

from __future__ import annotations

import ast
import os

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge

from tb.stream import BufferTB, value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
DEPTH = GENERICS["DEPTH"]
WIDTH = GENERICS["WIDTH"]
LEVEL = GENERICS["ALMOST_FULL_LEVEL"]
# The RAM's words: DEPTH rounded up to a power of two, at least 4.
WORDS = max(4, 1 << (DEPTH - 1).bit_length())
# The guarantees of the header comment: in_ready is '1' on every clock on
# which fewer than WORDS - 2 words are inside (so at least DEPTH - 2); with
# the output stalled it takes WORDS + 3 words; almost_full = '0' on a clock
# means in_ready = '1' on it and on the next ROOM clocks, and on any later
# clock before ROOM - 1 more words have been written from it on.
READY_BELOW = WORDS - 2
STALLED_CAPACITY = WORDS + 3
ROOM = WORDS - 2 - LEVEL
# A word written into an empty FIFO is on the output this many clocks later.
LATENCY = 4


class FillModel:
    """The FIFO's flags from the words in its RAM, as its header states them:
    in_ready and almost_full on a clock compare the RAM's words at the end of
    the third clock before with WORDS - 3 and ALMOST_FULL_LEVEL. A word leaves
    the RAM for the output stage (the RAM's read register and a two-word skid
    buffer) when the stage has room and the word was in the RAM before the
    last clock's write. Starts from the reset values (in_ready '0',
    almost_full '1'), then one idle clock (BufferTB.reset's)."""

    def __init__(self) -> None:
        self.ram = [0, 0]  # words in the RAM at the end of the last two clocks
        self.wrote = False  # the last clock's write
        self.ready = False
        self.almost_full = True
        self.q_valid = False  # the RAM's read register
        self.main_valid = False  # the skid buffer: out_valid
        self.skid_valid = False  # ... and its second entry
        self.clock(False, False)

    def clock(self, in_valid: bool, out_ready: bool) -> None:
        """One clock with these inputs (its flags are the attributes before the call)."""
        write = in_valid and self.ready
        read_en = not self.q_valid or not self.skid_valid
        read = read_en and self.ram[-1] - self.wrote >= 1
        # The next clock's flags: the words at the end of the clock before this
        # one, the third clock before the next.
        older = self.ram[0]
        self.ready = older <= WORDS - 3
        self.almost_full = older >= LEVEL
        self.ram = self.ram[1:] + [self.ram[-1] + write - read]
        self.wrote = write
        if not self.skid_valid:
            if not self.main_valid or out_ready:
                self.main_valid = self.q_valid
            else:
                self.skid_valid = self.q_valid
        elif out_ready:
            self.skid_valid = False
        if read_en:
            self.q_valid = read
        assert 0 <= self.ram[-1] <= WORDS, f"model: {self.ram[-1]} words in the RAM"


class TB(BufferTB):
    def __init__(self, dut):
        super().__init__(dut, GENERICS, 10)

    async def reset(self) -> None:
        await super().reset(3)
        self.model = FillModel()
        self.clocks = 0
        self.sent = self.received = 0
        self.promise = None  # (clock, words written since) of the last almost_full = '0'
        self.figures = {"almost_full": 0, "not_almost_full": 0, "promised_beyond": 0}

    async def clock(self, valid: bool, ready: bool) -> bool:
        """One clock with these inputs: checks in_ready, almost_full and out_valid
        against the model, in_ready against the header's guarantees and the words
        leaving; returns in_ready."""
        dut = self.dut
        k = self.clocks
        dut.in_valid.value = int(valid)
        dut.in_data.value = self.sent % (1 << WIDTH)
        dut.out_ready.value = int(ready)
        await RisingEdge(dut.clk)
        # Values of the clock that just ended (sampled at its edge).
        model = self.model
        got = {
            "in_ready": bool(value(dut.in_ready)),
            "almost_full": bool(value(dut.almost_full)),
            "out_valid": bool(value(dut.out_valid)),
        }
        want = {
            "in_ready": model.ready,
            "almost_full": model.almost_full,
            "out_valid": model.main_valid,
        }
        assert got == want, f"clock {k}: {got}, the model {want}"
        model.clock(valid, ready)
        in_ready, almost_full = got["in_ready"], got["almost_full"]
        inside = self.sent - self.received
        assert inside <= STALLED_CAPACITY, f"clock {k}: {inside} words inside"
        if inside < READY_BELOW:
            assert in_ready, f"clock {k}: in_ready = 0 with {inside} words inside"
        self.figures["almost_full" if almost_full else "not_almost_full"] += 1
        if not almost_full:
            self.promise = (k, 0)
        if self.promise is not None and ROOM >= 0:
            since, written = self.promise
            if k - since <= ROOM or written < ROOM - 1:
                assert in_ready, (
                    f"clock {k}: in_ready = 0 with almost_full = 0 on clock {since} "
                    f"and {written} words written since"
                )
                self.figures["promised_beyond"] += inside >= READY_BELOW
        wrote = valid and in_ready
        if wrote:
            self.sent += 1
            if self.promise is not None:
                self.promise = (self.promise[0], self.promise[1] + 1)
        if got["out_valid"] and ready:
            word = value(dut.out_data)
            assert word == self.received % (1 << WIDTH), (
                f"clock {k}: word {self.received} is {word}"
            )
            self.received += 1
        assert self.received <= self.sent
        self.clocks += 1
        return in_ready

    async def run(self, clocks: int, p_in, p_out) -> dict[str, int]:
        """`clocks` clocks of random traffic, then a drain; p_in(k)/p_out(k) are
        the chances of in_valid/out_ready on clock k. Returns figures (words
        moved, fewest words inside with in_ready low, most inside)."""
        sent_before = self.sent
        fewest_refused = None
        most_inside = 0
        for k in range(clocks):
            inside = self.sent - self.received
            most_inside = max(most_inside, inside)
            valid = self.rng.random() < p_in(k)
            ready = self.rng.random() < p_out(k)
            if not await self.clock(valid, ready):
                fewest_refused = inside if fewest_refused is None else min(fewest_refused, inside)
        # Drain: every word comes out, then nothing more.
        for _ in range(STALLED_CAPACITY + 10):
            await self.clock(False, True)
        assert self.received == self.sent, f"{self.sent} words in, {self.received} out"
        assert not value(self.dut.busy)
        return {
            "words": self.sent - sent_before,
            "fewest_refused": fewest_refused,
            "most_inside": most_inside,
        }


@cocotb.test()
async def random_traffic(dut):
    """Random valid/ready at several rates, and phases that fill and drain:
    in_ready, almost_full and out_valid as the model of the RAM's words
    predicts on every clock, the words leave in order, in_ready is never low
    with fewer than WORDS - 2 words inside, and almost_full = '0' keeps its
    promise."""
    tb = TB(dut)
    await tb.reset()
    fewest = []
    cases = [
        (lambda k: 0.5, lambda k: 0.5),
        (lambda k: 0.9, lambda k: 0.3),
        (lambda k: 1.0, lambda k: 0.0 if (k // 60) % 2 == 0 else 1.0),
        (lambda k: 0.9, lambda k: 0.0 if (k // 80) % 2 == 0 else 0.6),
        (lambda k: 1.0, lambda k: 0.95),
        (lambda k: 1.0, lambda k: 1.0),
        (lambda k: 0.2, lambda k: 0.9),
        # Stalls long enough to fill the RAM whatever its size.
        (lambda k: 0.8, lambda k: 0.0 if (k // (WORDS + 40)) % 2 == 0 else 0.5),
    ]
    for i, (p_in, p_out) in enumerate(cases):
        figures = await tb.run(max(600, 12 * WORDS), p_in, p_out)
        dut._log.info("case %d: %s", i, figures)
        assert figures["words"] > 100, "nothing moved"
        if figures["fewest_refused"] is not None:
            fewest.append(figures["fewest_refused"])
    dut._log.info("fewest words inside with in_ready = 0: %s", min(fewest))
    dut._log.info("almost_full (level %d, room %d): %s", LEVEL, ROOM, tb.figures)
    assert fewest, "in_ready never dropped: the capacity was not tested"
    assert tb.figures["almost_full"] and tb.figures["not_almost_full"], "almost_full never changed"


@cocotb.test()
async def capacity(dut):
    """With the output stalled the FIFO takes WORDS + 3 words (at least DEPTH)
    and then holds in_ready low; they leave in order. A word written into
    the empty FIFO is on its output LATENCY clocks later, and a full FIFO
    streams one word per clock."""
    tb = TB(dut)
    await tb.reset()
    dut.in_valid.value = 1
    dut.in_data.value = 0
    taken = 0
    for _ in range(STALLED_CAPACITY + 20):
        dut.in_data.value = taken % (1 << WIDTH)
        await RisingEdge(dut.clk)
        if value(dut.in_ready):
            taken += 1
    dut.in_valid.value = 0
    await ClockCycles(dut.clk, 5)
    assert not value(dut.in_ready)
    dut._log.info("stalled capacity: %d words (DEPTH %d, WORDS %d)", taken, DEPTH, WORDS)
    assert taken == STALLED_CAPACITY, f"{taken} words taken"
    assert taken >= DEPTH
    # Drain at full rate.
    dut.out_ready.value = 1
    got = []
    for _ in range(taken + 10):
        await RisingEdge(dut.clk)
        if value(dut.out_valid):
            got.append(value(dut.out_data))
        elif got:
            break
    assert got == [k % (1 << WIDTH) for k in range(taken)], "order, or a gap in the stream"
    # Latency from empty.
    await ClockCycles(dut.clk, 5)
    dut.in_valid.value = 1
    dut.in_data.value = 0x5 % (1 << WIDTH)
    await RisingEdge(dut.clk)
    dut.in_valid.value = 0
    clocks = 0
    while clocks < 20:
        clocks += 1
        await RisingEdge(dut.clk)
        if value(dut.out_valid):
            break
    dut._log.info("latency from empty: %d clocks", clocks)
    assert clocks == LATENCY, f"latency {clocks}"
