"""Simulation of the AXI top `fastnms_axi`, behind `fastnms sim`, `make demo` and `make bench`.

- `sources`: the RTL files in compile order (shared with the testbenches and the flows);
- `run`: runs frames through the top with either engine (`run_rtl`), and
  `detect_and_compute`: the RTL's ORB keypoints and descriptors in OpenCV's types;
- `verilator` (+ verilator_harness.cpp): the fast engine, GHDL's netlist under Verilator;
- `frame_tb`: the cocotb engine's module, started in GHDL by `run`;
- `timing`: the seeded idle and stall patterns both engines draw;
- `ghdl`: GHDL build and cocotb run (shared with the testbenches);
- `driver`: cocotbext-axi drivers of the top's ports and record decoding;
- `records`: the corner record stream decoded into frames (the twin of sw/fastnms.c);
- `regs`: the register map and record format (generated from rtl/top/fastnms_regs.toml).

It needs the source tree (rtl/), GHDL, and Verilator with g++ for the fast engine; it
imports nothing from the testbenches (tb/) or the flows.
"""

from .run import detect_and_compute  # noqa: E402 (the module's one entry point here)

__all__ = ["detect_and_compute"]
