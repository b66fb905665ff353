"""Simulation driver of the AXI top `fastnms_axi`, behind `fastnms sim` and `make bench`.

- `sources`: the RTL files in compile order (shared with the testbenches and the flows);
- `run`: builds the top under GHDL and runs one image through it (`run_rtl`);
- `driver`: the cocotb side: drives the top's AXI4-Stream and AXI4-Lite ports with
  cocotbext-axi and decodes the corner records;
- `frame_tb`: the cocotb module that `run` starts in the simulator;
- `regs`: the register map and record format (generated from rtl/top/fastnms_regs.toml).

It needs the source tree (rtl/) and GHDL; it imports nothing from the testbenches (tb/).
"""
