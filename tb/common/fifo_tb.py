"""cocotb testbench of fastnms_fifo: data order, capacity, in_ready,
in_room2, in_room3 and in_spare against a count of the words inside, under random
valid/ready."""

from __future__ import annotations

import ast
import os

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge

from tb.stream import BufferTB, value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
DEPTH = GENERICS["DEPTH"]
WIDTH = GENERICS["WIDTH"]
# The RAM's words: DEPTH rounded up to a power of two, at least 4.
WORDS = max(4, 1 << (DEPTH - 1).bit_length())
# The guarantees of the header comment: in_ready is '1' on every clock on
# which fewer than WORDS - 2 words are inside (so at least DEPTH - 2); with
# the output stalled it takes WORDS + 3 words; in_room2 = '1' on a clock means
# in_ready = '1' on the next one, in_room3 on the next two.
READY_BELOW = WORDS - 2
STALLED_CAPACITY = WORDS + 3
# A word written into an empty FIFO is on the output this many clocks later.
LATENCY = 4


class TB(BufferTB):
    def __init__(self, dut):
        super().__init__(dut, GENERICS, 10)

    async def reset(self) -> None:
        await super().reset(3)

    async def run(self, clocks: int, p_in, p_out) -> dict[str, int]:
        """`clocks` clocks of random traffic; p_in(k)/p_out(k) are the chances of
        in_valid/out_ready on clock k. Checks every word and every flag;
        returns figures (words moved, fewest words inside with in_ready low)."""
        dut = self.dut
        sent = received = 0
        next_data = 0
        fewest_refused = None
        room2_before = 0
        room3_before = [0, 0]  # in_room3 one and two clocks ago
        room3_seen = 0
        promise = False  # the last write had in_spare: in_ready holds until the next
        spares = 0
        most_inside = 0
        for k in range(clocks):
            valid = self.rng.random() < p_in(k)
            dut.in_valid.value = int(valid)
            dut.in_data.value = next_data % (1 << WIDTH)
            dut.out_ready.value = int(self.rng.random() < p_out(k))
            await RisingEdge(dut.clk)
            # Values of the clock that just ended (sampled at its edge).
            inside = sent - received
            most_inside = max(most_inside, inside)
            ready = value(dut.in_ready)
            assert inside <= STALLED_CAPACITY, f"clock {k}: {inside} words inside"
            if inside < READY_BELOW:
                assert ready, f"clock {k}: in_ready = 0 with {inside} words inside"
            if room2_before:
                assert ready, f"clock {k}: in_ready = 0 the clock after in_room2 = 1"
            if any(room3_before):
                assert ready, f"clock {k}: in_ready = 0 within two clocks of in_room3 = 1"
            if promise:
                assert ready, f"clock {k}: in_ready = 0 after a write with in_spare = 1"
            if not ready:
                fewest_refused = inside if fewest_refused is None else min(fewest_refused, inside)
            room2_before = value(dut.in_room2)
            room3_before = [value(dut.in_room3), room3_before[0]]
            room3_seen += room3_before[0]
            if valid and ready:
                promise = bool(value(dut.in_spare))
                spares += promise
                sent += 1
                next_data += 1
            if value(dut.out_valid) and value(dut.out_ready):
                got = value(dut.out_data)
                want = received % (1 << WIDTH)
                assert got == want, f"clock {k}: word {received} is {got}, not {want}"
                received += 1
            assert received <= sent
        dut.in_valid.value = 0
        # Drain: every word comes out, then nothing more.
        dut.out_ready.value = 1
        for _ in range(STALLED_CAPACITY + 10):
            await RisingEdge(dut.clk)
            if value(dut.out_valid):
                assert value(dut.out_data) == received % (1 << WIDTH)
                received += 1
        assert received == sent, f"{sent} words in, {received} out"
        assert not value(dut.busy)
        return {
            "words": sent,
            "fewest_refused": fewest_refused,
            "most_inside": most_inside,
            "spare_writes": spares,
            "room3_clocks": room3_seen,
        }


@cocotb.test()
async def random_traffic(dut):
    """Random valid/ready at several rates, and phases that fill and drain:
    the words leave in order, in_ready is never low with fewer than
    WORDS - 2 words inside, in_room2 promises in_ready one clock ahead,
    in_room3 two clocks ahead,
    in_spare promises it until the next write."""
    tb = TB(dut)
    await tb.reset()
    fewest = []
    spares = 0
    room3 = 0
    cases = [
        (lambda k: 0.5, lambda k: 0.5),
        (lambda k: 0.9, lambda k: 0.3),
        (lambda k: 1.0, lambda k: 0.0 if (k // 60) % 2 == 0 else 1.0),
        (lambda k: 0.9, lambda k: 0.0 if (k // 80) % 2 == 0 else 0.6),
        (lambda k: 1.0, lambda k: 0.95),
        (lambda k: 1.0, lambda k: 1.0),
        (lambda k: 0.2, lambda k: 0.9),
    ]
    for i, (p_in, p_out) in enumerate(cases):
        figures = await tb.run(max(600, 12 * WORDS), p_in, p_out)
        dut._log.info("case %d: %s", i, figures)
        assert figures["words"] > 100, "nothing moved"
        spares += figures["spare_writes"]
        room3 += figures["room3_clocks"]
        if figures["fewest_refused"] is not None:
            fewest.append(figures["fewest_refused"])
    dut._log.info("fewest words inside with in_ready = 0: %s", min(fewest))
    assert fewest, "in_ready never dropped: the capacity was not tested"
    assert (spares > 0) == (WORDS >= 8), f"{spares} writes with in_spare = 1 (WORDS {WORDS})"
    assert (room3 > 0) == (WORDS >= 8), f"{room3} clocks with in_room3 = 1 (WORDS {WORDS})"


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
