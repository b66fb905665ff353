"""The cocotb module that `fastnms sim` (sim/run.py) starts in the simulator: one
image through fastnms_axi (AXI4-Lite set-up, AXI4-Stream video in, corner
records out, all with cocotbext-axi), no idle cycles and no back-pressure. The
records and the cycle count go to a JSON file for the command line.

Environment: SIM_IMAGE (.npy, uint8 HxW), SIM_THRESHOLD, SIM_OUT (JSON
written at the end), SIM_PROGRESS (a file rewritten with "rows_in total_rows"
while the frame goes in), SIM_GENERICS (the top's generics).
"""

from __future__ import annotations

import ast
import json
import os
from pathlib import Path

import cocotb
import numpy as np
from cocotb.triggers import RisingEdge
from fastnms.sim.driver import AxiTop, corners, video_lines


async def count_pixels(tb: AxiTop, width: int, height: int, progress: Path) -> None:
    """Writes the number of input lines taken so far every 4096 clocks."""
    dut = tb.dut
    taken = 0
    clocks = 0
    while True:
        await RisingEdge(dut.aclk)
        if dut.s_axis_video_tvalid.value == 1 and dut.s_axis_video_tready.value == 1:
            taken += 1
        clocks += 1
        if clocks % 4096 == 0:
            progress.write_text(f"{taken // width} {height}\n")


@cocotb.test()
async def run_image(dut):
    img = np.load(os.environ["SIM_IMAGE"])
    threshold = int(os.environ["SIM_THRESHOLD"])
    out = Path(os.environ["SIM_OUT"])
    height, width = img.shape
    tb = await AxiTop.create(dut, ast.literal_eval(os.environ["SIM_GENERICS"]))
    await tb.reset()
    await tb.configure(width, height, threshold)
    cocotb.start_soon(count_pixels(tb, width, height, Path(os.environ["SIM_PROGRESS"])))
    await tb.send_lines(video_lines(img))
    records = corners(await tb.sink.recv())
    cycles = tb.last_records[-1] - tb.first_pixel + 1
    out.write_text(json.dumps({"records": records, "cycles": cycles}))
