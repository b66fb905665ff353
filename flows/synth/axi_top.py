"""Synthesis of fastnms_axi with flows/synth/synth.py despite a GHDL 2.0 bug.

GHDL 2.0's synthesis stops with an internal error (synth-vhdl_decls.adb:224)
on any attribute of an *input* port, and fastnms_axi carries Vivado's
X_INTERFACE_INFO / X_INTERFACE_PARAMETER attributes on all its ports (in the
entity, the only place the LRM and GHDL's analyser accept them). Those
attributes only matter to Vivado's IP packager, so synthesis is run on a copy
of rtl/top/fastnms_axi.vhd without their specifications; simulation compiles
the file as it is.

    python -m flows.synth.axi_top [GENERIC=VALUE ...]    figures like flows/synth/synth.py

flows/synth/test_synth.py uses `synthesizable_top()` for all its checks.
"""

from __future__ import annotations

import contextlib
import json
import sys
from collections.abc import Iterator
from pathlib import Path

from fastnms.sim.sources import REPO
from fastnms.sim.verilator import synthesizable_sources

from flows.synth import synth

COPY = REPO / "build" / "synth" / "fastnms_axi_no_attributes.vhd"


def sources() -> list[Path]:
    """rtl_sources() with fastnms_axi.vhd replaced by its copy without the
    X_INTERFACE attributes (the one the fast simulation engine synthesizes too)."""
    return synthesizable_sources(COPY)


def levels_outside(netlist_json: Path, top: str, inside: str = "core.") -> int:
    """Like synth.logic_levels, but counting only the paths that start or end
    at a register or port whose name does not begin with `inside`: the logic
    levels a top level adds around an instance."""
    module = json.loads(netlist_json.read_text())["modules"][top]
    cells = module["cells"]
    names: dict[int, str] = {}
    for name, net in module["netnames"].items():
        for bit in net["bits"]:
            if isinstance(bit, int) and (bit not in names or len(name) < len(names[bit])):
                names[bit] = name
    drivers = synth.cell_drivers(module)
    logic = {n for n, c in cells.items() if synth.LOGIC_CELLS.match(c["type"])}

    def bits(cell: dict, direction: str) -> list[int]:
        return [
            b
            for port, bs in cell["connections"].items()
            if cell["port_directions"].get(port) == direction
            for b in bs
            if isinstance(b, int)
        ]

    def outside(bit: int) -> bool:
        return not names.get(bit, "").startswith(inside)

    # Per logic cell: the longest path ending there, and the longest one that
    # starts outside the instance (0: none).
    depth: dict[str, tuple[int, int]] = {}
    sys.setrecursionlimit(100000)

    def visit(name: str) -> tuple[int, int]:
        if name not in depth:
            depth[name] = (0, 0)
            longest, from_outside = 1, 0
            for bit in bits(cells[name], "input"):
                if drivers.get(bit) in logic:
                    a, o = visit(drivers[bit])
                    longest = max(longest, a + 1)
                    from_outside = max(from_outside, o + 1 if o else 0)
                elif outside(bit):
                    from_outside = max(from_outside, 1)
            depth[name] = (longest, from_outside)
        return depth[name]

    ports = module["ports"].values()
    out_ports = {b for p in ports if p["direction"] == "output" for b in p["bits"]}
    worst = 0
    for name in logic:
        longest, _ = visit(name)
        if any(bit in out_ports for bit in bits(cells[name], "output")):
            worst = max(worst, longest)
    # Endpoints: registers and memories fed by logic.
    for cell in cells.values():
        if synth.LOGIC_CELLS.match(cell["type"]):
            continue
        ends_outside = all(outside(b) for b in bits(cell, "output"))
        for bit in bits(cell, "input"):
            if drivers.get(bit) in logic:
                longest, from_outside = visit(drivers[bit])
                worst = max(worst, longest if ends_outside else from_outside)
    return worst


@contextlib.contextmanager
def synthesizable_top() -> Iterator[None]:
    """flows/synth/synth.py's functions, with the copy in the source list."""
    saved = synth.rtl_sources
    synth.rtl_sources = sources
    try:
        yield
    finally:
        synth.rtl_sources = saved


if __name__ == "__main__":
    gens = dict(a.split("=", 1) for a in sys.argv[1:] if "=" in a)
    with synthesizable_top():
        netlist, _ = synth.ghdl_synth("fastnms_axi", gens)
        cells = synth.yosys_xc7(netlist, "fastnms_axi")
    if "--cells" in sys.argv:
        for cell, count in sorted(cells.items()):
            print(f"{cell:12s} {count}")
    config = " ".join(f"{k}={v}" for k, v in gens.items()) or "default generics"
    figures = "  ".join(f"{k} {v}" for k, v in synth.summary(cells).items())
    outside = levels_outside(netlist.with_suffix(".xc7.json"), "fastnms_axi")
    print(f"fastnms_axi ({config}): {figures}  logic_levels_outside_core {outside}")
