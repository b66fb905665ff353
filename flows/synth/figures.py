"""The figures of one `make synth` row (flows/synth/summary.py) from its GHDL
netlist: yosys synth_xilinx's cells, LUT RAM and logic levels (xc7_figures), and
yosys synth_ecp5 + nextpnr's Fmax on a Lattice ECP5 (ecp5_figures). With
synth.py, ecp5.py and axi_top.py these are the flow files whose content is part of
each cached row's key (flows/synth/cache.py); summary.py, which only chooses the
rows and runs them, is not.
"""

from __future__ import annotations

import shutil
import time
from pathlib import Path

from flows.synth import ecp5, synth
from flows.synth.axi_top import levels_outside

LATCHES = ("LDCE", "LDPE")
# LUT RAM cells and the LUTs each takes (Vivado counts them as "LUT as memory").
LUTRAM_LUTS = {
    "RAM32M": 4,
    "RAM64M": 4,
    "RAM32X1D": 2,
    "RAM64X1D": 2,
    "RAM128X1D": 4,
    "RAM256X1S": 4,
    "RAM32M16": 8,
}


def xc7_figures(netlist: Path, entity: str) -> dict:
    start = time.perf_counter()
    cells = synth.yosys_xc7(netlist, entity)
    figures = synth.summary(cells)
    figures["bram18"] = sum(n for c, n in cells.items() if c.startswith("RAMB18"))
    figures["bram36"] = sum(n for c, n in cells.items() if c.startswith("RAMB36"))
    figures["lutram_luts"] = sum(n * cells.get(c, 0) for c, n in LUTRAM_LUTS.items())
    figures["latches"] = sum(cells.get(c, 0) for c in LATCHES)
    if entity == "fastnms_axi":
        mapped = netlist.with_suffix(".xc7.json")
        figures["logic_levels_outside_core"] = levels_outside(mapped, entity)
    figures["xc7_cells"] = {c: n for c, n in sorted(cells.items()) if c != "logic_levels"}
    figures["xc7_seconds"] = time.perf_counter() - start
    return figures


def ecp5_figures(
    netlist: Path,
    entity: str,
    seed: int,
    extra_seeds: tuple[int, ...] = (),
    device: str = ecp5.DEFAULT_DEVICE,
    timeout: float | None = None,
) -> dict:
    """yosys synth_ecp5 once, then nextpnr on `device` with `seed` (the figures)
    and each of `extra_seeds` (their Fmax only, in `ecp5_seed_fmax_mhz` with
    `seed`'s), each seed in its own folder. A design that does not fit the device
    (or a run stopped after `timeout` s) has `ecp5_fmax_mhz` None and says so in
    `ecp5_result`."""
    start = time.perf_counter()
    design, cells = ecp5.yosys_ecp5(netlist, entity)
    yosys_seconds = time.perf_counter() - start
    pnr = ecp5.nextpnr_ecp5(design, seed=seed, device=device, timeout=timeout)
    figures = {
        "ecp5_fmax_mhz": pnr["fmax_mhz"],
        "ecp5": {**pnr, "cells": cells, "yosys_seconds": yosys_seconds},
    }
    problem = pnr.get("does_not_fit") or pnr.get("timed_out")
    if problem:
        figures["ecp5_result"] = problem
        return figures
    if extra_seeds:
        by_seed = {seed: pnr["fmax_mhz"]}
        for extra in extra_seeds:
            folder = design.parent / f"seed{extra}"
            folder.mkdir(exist_ok=True)
            copy = folder / design.name
            shutil.copyfile(design, copy)
            by_seed[extra] = ecp5.nextpnr_ecp5(copy, seed=extra)["fmax_mhz"]
        figures["ecp5_seed_fmax_mhz"] = by_seed
    return figures
