"""cocotb testbench of the key_flags synthesis probe (flows/synth/probes/key_flags.vhd):
random operations against a model that compares the keys themselves. The probe keeps
its comparisons as order flags, so its keys are right only if every flag is kept right.

Keys are score << POS_BITS | inverted raster position: every new pixel comes after all
the keys already in play (the probe compares the pixel on scores only), and the words
entering from the memories are keys of earlier pixels (some equal to a register's key).
Scores are drawn from a few values, so that ties are frequent."""

from __future__ import annotations

import ast
import os
import random

import cocotb
from cocotb.clock import Clock
from cocotb.triggers import FallingEdge, RisingEdge

from tb.stream import value

GENERICS = ast.literal_eval(os.environ["TB_GENERICS"])
SCORE_BITS = GENERICS["SCORE_BITS"]
POS_BITS = GENERICS["POS_BITS"]
KB = SCORE_BITS + POS_BITS
MEMBERS = ["T", "S", "R", "C", "W", "L", "N"]
# The operation's bits (OP_* in the probe).
BASES = {"T": 0, "L": 1, "W": 2}
MERGES = {"C": 3, "X": 4, "T": 5}
PIX_JOINS, KEEP_TOP, TAKE_SECOND, CUR_START, CUR_PIX = 6, 7, 8, 9, 10
DETACH, FINAL, SPARE = 11, 12, 13
MOVES = {"S": (14, "T", "R"), "R": (16, "S", "FR"), "W": (18, "N", "L"), "N": (20, "FN", "L")}
PIX_STEP = 22
IDLE = {"base": "T", "merge": None, "bits": {KEEP_TOP}, "moves": {}, "pix_step": False}


def encode(op: dict) -> int:
    word = 1 << BASES[op["base"]]
    if op["merge"]:
        word |= 1 << MERGES[op["merge"]]
    for bit in op["bits"]:
        word |= 1 << bit
    for reg, code in op["moves"].items():
        word |= code << MOVES[reg][0]
    if op["pix_step"]:
        word |= 1 << PIX_STEP
    return word


def step(regs: dict[str, int], pixel: int, op: dict, data: dict) -> tuple[dict[str, int], int]:
    """One column, the comparisons made on the keys: the next registers and pixel."""
    vals = {**regs, "X": pixel, "FR": data["stack"], "FN": data["table"]}
    bits = op["bits"]
    base = vals[op["base"]]
    merge = vals[op["merge"]] if op["merge"] else None
    joins = PIX_JOINS in bits
    b_ge_m = merge is None or base >= merge
    b_ge_p = not joins or base >= pixel
    m_ge_p = merge is not None and (not joins or merge >= pixel)
    best = base if b_ge_m and b_ge_p else merge if m_ge_p else pixel
    cur_pix = CUR_START in bits or (CUR_PIX in bits and not regs["C"] >= pixel)
    cur = pixel if cur_pix else regs["C"]
    nxt = dict(regs)
    nxt["T"] = regs["T"] if KEEP_TOP in bits else regs["S"] if TAKE_SECOND in bits else best
    nxt["C"] = best if DETACH in bits else cur
    nxt["L"] = regs["C"] if SPARE in bits else best if FINAL in bits else cur
    for reg, code in op["moves"].items():
        if code:
            nxt[reg] = vals[MOVES[reg][code]]
    return nxt, (data["pixel"] if op["pix_step"] else pixel)


class KeyFlagsTB:
    def __init__(self, dut, rng: random.Random):
        self.dut = dut
        self.rng = rng
        top = (1 << POS_BITS) - 1
        self.init_key = top  # score 0, the earliest position
        self.time = 0
        self.issued = [self.init_key]  # every pixel key so far, for the memory words
        self.scores = [0, 1, 2, 3, (1 << SCORE_BITS) - 1]

    def new_pixel(self, taken: bool) -> int:
        """A pixel after every key so far; a memory word may be its key once the pixel
        is taken (so that every key in play comes before the pixel in raster order)."""
        self.time += 1
        key = (self.rng.choice(self.scores) << POS_BITS) | ((1 << POS_BITS) - 1 - self.time)
        if taken:
            self.issued.append(key)
        return key

    def random_op(self) -> dict:
        rng = self.rng
        bits = {
            b for b in (PIX_JOINS, CUR_START, CUR_PIX, DETACH, FINAL, SPARE) if rng.random() < 0.3
        }
        top = rng.random()
        if top < 0.3:
            bits.add(KEEP_TOP)
        elif top < 0.5:
            bits.add(TAKE_SECOND)
        return {
            "base": rng.choice(list(BASES)),
            "merge": rng.choice([None, *MERGES]),
            "bits": bits,
            "moves": {reg: rng.choice([0, 0, 1, 2]) for reg in MOVES},
            "pix_step": rng.random() < 0.5,
        }

    def random_data(self, regs: dict[str, int], pixel: int, op: dict) -> dict:
        """The inputs of a column (op) on the registers regs and pixel: the next pixel,
        the memory words, their flags against the registers and the pixel."""
        rng = self.rng

        def word() -> int:
            if rng.random() < 0.3:
                return regs[rng.choice(MEMBERS)]  # the same class's key again
            return rng.choice(self.issued)

        stack, table = word(), word()
        nxt = self.new_pixel(op["pix_step"])
        vals = [*(regs[m] for m in MEMBERS), pixel, stack, table]
        return {
            "pixel": nxt,
            "stack": stack,
            "table": table,
            "next_ge": sum(
                int((v >> POS_BITS) >= (nxt >> POS_BITS)) << i for i, v in enumerate(vals)
            ),
            "stack_ge": sum(int(stack >= v) << i for i, v in enumerate(vals[:8] + [table])),
            "table_ge": sum(int(table >= v) << i for i, v in enumerate(vals[:8])),
        }

    def drive(self, op: dict, data: dict) -> None:
        dut = self.dut
        dut.in_op.value = encode(op)
        dut.in_next_pixel.value = data["pixel"]
        dut.in_next_ge.value = data["next_ge"]
        dut.in_stack_word.value = data["stack"]
        dut.in_stack_ge.value = data["stack_ge"]
        dut.in_table_word.value = data["table"]
        dut.in_table_ge.value = data["table_ge"]

    def dut_keys(self) -> dict[str, int]:
        word = value(self.dut.out_keys)
        return {m: (word >> (KB * i)) & ((1 << KB) - 1) for i, m in enumerate(MEMBERS)}


@cocotb.test()
async def random_operations(dut):
    """Every key register equals the model's after every clock, over random operations."""
    rng = random.Random(cocotb.RANDOM_SEED)
    cycles = int(os.environ.get("TB_CYCLES", "10000"))
    dut._log.info("seed=%d generics %s cycles %d", cocotb.RANDOM_SEED, GENERICS, cycles)
    tb = KeyFlagsTB(dut, rng)
    cocotb.start_soon(Clock(dut.clk, 10, unit="ns").start())
    # The probe takes an operation three edges before its column is carried out
    # (in_op, op_ahead, op) and the data two (its input registers); the registers
    # start at the earliest key, the operations at IDLE.
    regs = dict.fromkeys(MEMBERS, tb.init_key)
    pixel = tb.init_key
    ops = [IDLE, IDLE, IDLE]  # ops[e]: the operation carried out at edge e
    data = [None, tb.random_data(regs, pixel, IDLE)]  # data[e]: the inputs of edge e's column
    for cycle in range(cycles):
        # Edge cycle + 1 carries out ops[cycle + 1] with data[cycle + 1].
        regs, pixel = step(regs, pixel, ops[cycle + 1], data[cycle + 1])
        ops.append(tb.random_op() if cycle >= 3 else IDLE)
        data.append(tb.random_data(regs, pixel, ops[cycle + 2]))
        tb.drive(ops[cycle + 3], data[cycle + 2])
        await RisingEdge(dut.clk)
        await FallingEdge(dut.clk)
        if cycle >= 2:
            got = tb.dut_keys()
            assert got == regs, f"edge {cycle + 1}: keys {got} != model {regs}"
    dut._log.info("%d clocks, every key register equal to the model's", cycles)
