"""cocotb testbenches of the deferred-select synthesis probes (issue 37):

- chain_random: flows/synth/probes/key_deferred_chain.vhd, a chain of merges (one key
  operand per clock, with a merge bit) against a model that merges the keys themselves.
- key_path_random: flows/synth/probes/key_deferred.vhd, the region NMS's key data path,
  against key_flags_tb's model (the same operations and inputs as the key_flags probe),
  delayed by the probe's lag.

Seeds as every cocotb test here: cocotb.RANDOM_SEED (FASTNMS_SEED through tb.harness),
logged. TB_CYCLES sets the number of clocks (default 20000)."""

from __future__ import annotations

import ast
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.stream import value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
CYCLES = int(os.environ.get("TB_CYCLES", "20000"))

# key_deferred_chain: o(s) is in its input register after edge s, acc(s) in its output
# register after edge s + 2. key_deferred: column e's operation is in its input register
# after edge e - 1, its data after edge e, the keys after it in its key registers after
# edge e + 3.
CHAIN_LATENCY = 2
KEY_PATH_LATENCY = 3


def chain_model(acc: int, key: int, merge: bool) -> int:
    """The next accumulator: the operand starts a class, or the better of the two keys
    (the accumulator, the earlier operand, wins on equal keys)."""
    if not merge:
        return key
    return acc if acc >= key else key


@cocotb.test()
async def chain_random(dut):
    """The resolved accumulator equals the model's, CHAIN_LATENCY clocks after each
    operand, over random keys (drawn from a few values too, so that ties are frequent)
    and random class starts."""
    key_bits = GENERICS["KEY_BITS"]
    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d generics %s cycles %d", cocotb.RANDOM_SEED, GENERICS, CYCLES)
    pool = [rng.getrandbits(key_bits) for _ in range(6)] + [0, (1 << key_bits) - 1]
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start(start_high=False))
    expected = []  # expected[s]: acc(s)
    acc = 0
    for edge in range(CYCLES + CHAIN_LATENCY):
        key = rng.choice(pool) if rng.random() < 0.5 else rng.getrandbits(key_bits)
        # The first operand starts a class: the accumulator before it is not modelled.
        merge = edge > 0 and rng.random() < 0.8
        acc = chain_model(acc, key, merge)
        expected.append(acc)
        dut.in_key.value = key
        dut.in_merge.value = int(merge)
        await RisingEdge(dut.clk)  # edge `edge`: o(edge) into the input register
        await FallingEdge(dut.clk)
        if edge >= CHAIN_LATENCY:
            got = value(dut.out_key)
            want = expected[edge - CHAIN_LATENCY]
            assert got == want, f"edge {edge}: acc({edge - CHAIN_LATENCY}) {got:#x} != {want:#x}"
    dut._log.info("%d operands, every accumulator equal to the model's", CYCLES)


@cocotb.test()
async def key_path_random(dut):
    """Every key register equals key_flags_tb's model's KEY_PATH_LATENCY clocks after its
    column, over key_flags_tb's random operations and inputs."""
    # Imported here: key_flags_tb reads SCORE_BITS and POS_BITS from TB_GENERICS.
    from tb.probes import key_flags_tb as kf

    rng = random.Random(cocotb.RANDOM_SEED)
    dut._log.info("seed=%d generics %s cycles %d", cocotb.RANDOM_SEED, GENERICS, CYCLES)
    tb = kf.KeyFlagsTB(dut, rng)
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start(start_high=False))
    regs = dict.fromkeys(kf.MEMBERS, tb.init_key)
    pixel = tb.init_key
    expected = []  # expected[e]: the keys after column e
    ops = [kf.IDLE]  # ops[e]: column e's operation, driven a column ahead of its data
    for edge in range(CYCLES + KEY_PATH_LATENCY):
        ops.append(tb.random_op() if edge >= 3 else kf.IDLE)
        data = tb.random_data(regs, pixel, ops[edge])
        regs, pixel = kf.step(regs, pixel, ops[edge], data)
        expected.append(regs)
        dut.in_op.value = kf.encode(ops[edge + 1])
        dut.in_next_pixel.value = data["pixel"]
        dut.in_stack_word.value = data["stack"]
        dut.in_table_word.value = data["table"]
        await RisingEdge(dut.clk)  # edge `edge`: column edge's data registered
        await FallingEdge(dut.clk)
        if edge >= KEY_PATH_LATENCY:
            got = tb.dut_keys()
            want = expected[edge - KEY_PATH_LATENCY]
            assert got == want, (
                f"edge {edge}: column {edge - KEY_PATH_LATENCY} keys {got} != {want}"
            )
    dut._log.info("%d columns, every key register equal to the model's", CYCLES)
