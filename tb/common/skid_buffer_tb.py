"""cocotb testbench of fastnms_skid_buffer (both PING_PONG styles): order and
no loss under random valid/ready, in_ready and out_valid as registers, the
AXI4-Stream hold rule, one beat per clock, two beats held when stalled, one
clock of latency, reset."""

from __future__ import annotations

import ast
import os

import cocotb
from cocotb.triggers import ClockCycles, RisingEdge, Timer

from tb.stream import BufferTB, value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
WIDTH = GENERICS["WIDTH"]
PERIOD_NS = 10


class TB(BufferTB):
    def __init__(self, dut):
        super().__init__(dut, GENERICS, PERIOD_NS)

    async def reset(self) -> None:
        await super().reset(2)

    def outputs(self) -> tuple[int, int, int | None]:
        """in_ready, out_valid and (while valid: before the first beat the
        entries hold no value) out_data."""
        valid = value(self.dut.out_valid)
        return value(self.dut.in_ready), valid, value(self.dut.out_data) if valid else None

    async def run(self, clocks: int, p_in: float, p_out: float) -> dict[str, int]:
        """`clocks` clocks of random traffic. The inputs change twice in each
        clock (a first guess, then the final value, 3 ns apart): in_ready,
        out_valid and out_data must not follow them within the clock."""
        dut = self.dut
        sent = received = 0
        held = None  # (data) of an offered beat not taken yet
        most_inside = 0
        for k in range(clocks):
            await Timer(2, unit="ns")
            before = self.outputs()
            dut.in_valid.value = self.rng.random() < 0.5
            dut.out_ready.value = self.rng.random() < 0.5
            dut.in_data.value = self.rng.getrandbits(WIDTH)
            await Timer(3, unit="ns")
            after = self.outputs()
            assert after == before, f"clock {k}: outputs follow the inputs {before} -> {after}"
            valid = self.rng.random() < p_in
            ready = self.rng.random() < p_out
            dut.in_valid.value = int(valid)
            dut.in_data.value = sent % (1 << WIDTH)
            dut.out_ready.value = int(ready)
            await RisingEdge(dut.clk)
            # Values of the clock that just ended (sampled at its edge). Both
            # styles are a function of the beats inside: in_ready below two,
            # out_valid above none (so they behave alike on every clock).
            out_valid = value(dut.out_valid)
            inside = sent - received
            assert value(dut.in_ready) == (inside < 2), f"clock {k}: in_ready with {inside} inside"
            assert out_valid == (inside > 0), f"clock {k}: out_valid with {inside} inside"
            if held is not None:
                assert out_valid and value(dut.out_data) == held, (
                    f"clock {k}: an offered beat changed or left before it was taken"
                )
            if valid and value(dut.in_ready):
                sent += 1
            if out_valid:
                got = value(dut.out_data)
                assert got == received % (1 << WIDTH), f"clock {k}: beat {received} is {got}"
                if ready:
                    received += 1
                    held = None
                else:
                    held = got
            most_inside = max(most_inside, sent - received)
            assert sent - received <= 2, f"clock {k}: {sent - received} beats inside"
        dut.in_valid.value = 0
        dut.out_ready.value = 1
        for _ in range(4):
            await RisingEdge(dut.clk)
            if value(dut.out_valid):
                assert value(dut.out_data) == received % (1 << WIDTH)
                received += 1
        assert received == sent, f"{sent} beats in, {received} out"
        return {"beats": sent, "most_inside": most_inside}


@cocotb.test()
async def random_traffic(dut):
    """Random valid/ready at several rates: every beat leaves once, in order;
    at most two inside; the outputs are registers (or, for PING_PONG, a
    multiplexer of registers) and an offered beat holds until taken."""
    tb = TB(dut)
    await tb.reset()
    for p_in, p_out in [(0.5, 0.5), (0.9, 0.3), (0.3, 0.9), (1.0, 1.0), (1.0, 0.7)]:
        figures = await tb.run(400, p_in, p_out)
        dut._log.info("in %.1f out %.1f: %s", p_in, p_out, figures)
        assert figures["beats"] > 100, "nothing moved"
        if p_out < 1.0:
            assert figures["most_inside"] == 2, "the second entry was never used"


@cocotb.test()
async def rate_capacity_latency(dut):
    """One beat per clock with both sides always ready; a beat is on the
    output one clock after it is taken; with the output stalled exactly two
    beats are taken, then in_ready stays low; a reset empties it."""
    tb = TB(dut)
    await tb.reset()
    dut.in_valid.value = 1
    dut.out_ready.value = 1
    got = []
    for k in range(50):
        dut.in_data.value = k
        await RisingEdge(dut.clk)
        assert value(dut.in_ready), f"clock {k}: in_ready low with the output ready"
        if value(dut.out_valid):
            got.append(value(dut.out_data))
    assert got == list(range(49)), "one clock of latency, one beat per clock"
    await tb.reset()
    dut.in_valid.value = 1
    taken = 0
    for k in range(10):
        dut.in_data.value = 100 + k
        await RisingEdge(dut.clk)
        taken += value(dut.in_ready)
    assert taken == 2, f"{taken} beats taken with the output stalled"
    dut.in_valid.value = 0
    dut.out_ready.value = 1
    drained = []
    for _ in range(4):
        await RisingEdge(dut.clk)
        if value(dut.out_valid):
            drained.append(value(dut.out_data))
    assert drained == [100, 101], drained
    # Reset with two beats inside: nothing leaves afterwards.
    dut.out_ready.value = 0
    dut.in_valid.value = 1
    await ClockCycles(dut.clk, 3)
    await tb.reset()
    assert value(dut.in_ready) and not value(dut.out_valid)
