"""Valid/ready stream drivers for the core's internal interfaces.

The core's blocks use short handshake names (in_valid, in_ready, in_data, ...);
the AXI4-Stream top is driven with cocotbext-axi instead. A transfer happens on
a rising edge where valid and ready are both high; values are sampled at the
edge (before the design updates them), as cocotbext-axi does.
"""

from __future__ import annotations

import random
from collections.abc import Iterable

import cocotb
from cocotb.clock import Clock
from cocotb.handle import SimHandleBase
from cocotb.triggers import ClockCycles, RisingEdge
from cocotb.utils import get_sim_time


def sim_ns() -> int:
    """The simulation time in whole ns (get_sim_time can carry a few fs of
    rounding after earlier tests, which would break `// PERIOD_NS`)."""
    return round(get_sim_time("ns"))


def value(signal: SimHandleBase) -> int:
    """The integer value of a std_logic or std_logic_vector signal."""
    v = signal.value
    return v.to_unsigned() if hasattr(v, "to_unsigned") else int(v)


def offer_times(clk, valid: SimHandleBase) -> list[int]:
    """Start recording the times (ns) at which `valid` rises, that is when each item of
    a stream that holds its item until taken is first offered; returns the list."""
    times: list[int] = []

    async def watch() -> None:
        before = 0
        while True:
            await RisingEdge(clk)
            now = value(valid)
            if now and not before:
                times.append(sim_ns())
            before = now

    cocotb.start_soon(watch())
    return times


class StreamSource:
    """Sends beats (dicts of field -> int) on <prefix>_valid/<prefix>_ready,
    with valid low for a random number of cycles before a beat with
    probability `idle`."""

    def __init__(self, dut, clk, prefix: str, rng: random.Random, idle: float = 0.0):
        self.dut, self.clk, self.prefix, self.rng, self.idle = dut, clk, prefix, rng, idle
        self.valid = getattr(dut, f"{prefix}_valid")
        self.ready = getattr(dut, f"{prefix}_ready")
        self.valid.value = 0
        self.accept_times: list[int] = []

    async def send(self, beats: Iterable[dict[str, int]], on_accept=None) -> None:
        """Send `beats`; `on_accept(i)` runs right after beat i was taken."""
        for i, beat in enumerate(beats):
            while self.rng.random() < self.idle:
                self.valid.value = 0
                await RisingEdge(self.clk)
            for field, v in beat.items():
                getattr(self.dut, f"{self.prefix}_{field}").value = v
            self.valid.value = 1
            await RisingEdge(self.clk)
            while not value(self.ready):
                await RisingEdge(self.clk)
            self.accept_times.append(sim_ns())
            if on_accept is not None:
                on_accept(i)
        self.valid.value = 0


def resolve(v) -> int:
    """A recorded field value as an integer, undefined bits read as 0."""
    if hasattr(v, "to_unsigned"):
        return int(str(v).translate(str.maketrans("UXZWLH-", "0000010")), 2)
    return int(str(v) in ("1", "H"))


class StreamSink:
    """Records every beat of <prefix>_valid/<prefix>_ready with the given
    fields (as integers, undefined bits read as 0), holding ready low on a
    cycle with probability `stall`. Start `run` once the design is out of
    reset."""

    def __init__(
        self, dut, clk, prefix: str, fields: list[str], rng: random.Random, stall: float = 0.0
    ):
        self.dut, self.clk, self.prefix, self.rng, self.stall = dut, clk, prefix, rng, stall
        self.valid = getattr(dut, f"{prefix}_valid")
        self.ready = getattr(dut, f"{prefix}_ready")
        self.fields = {f: getattr(dut, f"{prefix}_{f}") for f in fields}
        self.beats: list[dict[str, int]] = []
        self.times: list[int] = []
        self.ready.value = 0

    async def run(self) -> None:
        while True:
            self.ready.value = 0 if self.rng.random() < self.stall else 1
            await RisingEdge(self.clk)
            if value(self.valid) and value(self.ready):
                self.beats.append({f: resolve(s.value) for f, s in self.fields.items()})
                self.times.append(sim_ns())


class BufferTB:
    """Base of the testbenches of a buffer with in_valid/in_ready/in_data and
    out_valid/out_ready/out_data (FIFO, skid buffer): the seeded random
    generator, the clock, idle inputs and the reset."""

    def __init__(self, dut, generics: dict, period_ns: int = 10):
        self.dut = dut
        self.rng = random.Random(cocotb.RANDOM_SEED)
        dut._log.info("seed=%d generics %s", cocotb.RANDOM_SEED, generics)
        cocotb.start_soon(Clock(dut.clk, period_ns, unit="ns").start())
        dut.in_valid.value = 0
        dut.in_data.value = 0
        dut.out_ready.value = 0

    async def reset(self, clocks: int = 3) -> None:
        """rst for `clocks` clocks with both sides idle, then one clock."""
        self.dut.rst.value = 1
        self.dut.in_valid.value = 0
        self.dut.out_ready.value = 0
        await ClockCycles(self.dut.clk, clocks)
        self.dut.rst.value = 0
        await RisingEdge(self.dut.clk)
