"""cocotb testbench of the float32 units (fastnms_f32_mul, fastnms_f32_add): every
result bit for bit equal to golden/float32.py on random and boundary operands
(f32_vectors.py), operands offered on random clocks, each result exactly the unit's
latency after its operands."""

from __future__ import annotations

import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import ClockCycles, RisingEdge

from tb.orb.f32_vectors import vectors
from tb.stream import value

UNIT = os.environ["TB_UNIT"]  # "mul" or "add"
COUNT = int(os.environ["TB_COUNT"])
LATENCY = {"mul": 4, "add": 7}[UNIT]
RESULT = {"mul": "out_p", "add": "out_s"}[UNIT]


@cocotb.test()
async def equals_the_model(dut):
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d unit %s, %d operand pairs", cocotb.RANDOM_SEED, UNIT, COUNT)
    a, b, expected = vectors(UNIT, rng, COUNT)
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    dut.in_valid.value = 0
    dut.rst.value = 1
    await ClockCycles(dut.clk, 2)
    dut.rst.value = 0
    result = getattr(dut, RESULT)

    sent_at: list[int] = []
    got: list[tuple[int, int]] = []  # (clock, result)
    clock = 0
    i = 0
    while len(got) < COUNT:
        offer = i < COUNT and rng.random() < 0.8
        dut.in_valid.value = int(offer)
        if offer:
            dut.in_a.value = a[i]
            dut.in_b.value = b[i]
            sent_at.append(clock)
            i += 1
        await RisingEdge(dut.clk)
        if value(dut.out_valid):
            got.append((clock, value(result)))
        clock += 1
        assert clock < 2 * COUNT + 100, "results missing"

    for k, ((at, r), e) in enumerate(zip(got, expected, strict=True)):
        assert r == e, f"pair {k}: {a[k]:08x} {UNIT} {b[k]:08x} gave {r:08x}, the model {e:08x}"
        assert at - sent_at[k] == LATENCY, f"pair {k}: latency {at - sent_at[k]}"
    await ClockCycles(dut.clk, LATENCY + 2)
    assert not value(dut.out_valid), "a result with no operands"
