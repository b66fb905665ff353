"""cocotb testbenches of the RTL, mirroring rtl/ (common, fast, nms, core, top), and their
harness (`harness`: GHDL runner and seeds; `stream`, `video`: stream drivers and a TB base).
"""
