"""The simulation engines' speeds, as `make bench` measured them (part of the
bench section of docs/results.md)."""

from __future__ import annotations

from flows.report.common import num, table

LABEL = {"verilator": "fast (GHDL netlist + Verilator)", "cocotb": "cocotb (GHDL + cocotb)"}


def engine_lines(engines: list[dict]) -> list[str]:
    """A row per engine, then what each figure counts and their ratio."""
    if not engines:
        return []
    out = ["### Simulation engines", ""]
    rows = [
        [
            LABEL.get(e["engine"], e["engine"]),
            e["measured_on"],
            num(e["pixels"]),
            num(e["clocks"]),
            f"{e['wall_seconds']:.1f}",
            num(e["pixels_per_second"]),
            num(e["clocks_per_second"]),
        ]
        for e in engines
    ]
    out += table(
        ["engine", "measured on", "pixels", "clocks", "wall s", "pixels/s", "clocks/s"], rows
    )
    out.append("")
    notes = [engine_note(e) for e in engines if e["engine"] in LABEL]
    by = {e["engine"]: e for e in engines}
    if "verilator" in by and "cocotb" in by:
        fast, slow = by["verilator"]["pixels_per_second"], by["cocotb"]
        steady = slow.get("steady_pixels_per_second")
        while_in = f" ({fast / steady:.0f} times its speed while the pixels went in)"
        notes.append(
            f"The fast engine simulates {fast / slow['pixels_per_second']:.0f} times as many "
            "pixels per second as the cocotb run" + (while_in if steady else "") + "."
        )
    out.append(" ".join(notes))
    out.append("")
    return out


def engine_note(e: dict) -> str:
    """What one engine's figures count."""
    if e["engine"] == "verilator":
        lo, hi = e["pixels_per_second_range"]
        return (
            f"Fast engine: the runs of the table above, clocks from each run's first pixel "
            f"to its last record, wall time of the simulations alone (the builds apart); "
            f"{num(lo)} to {num(hi)} pixels/s by configuration."
        )
    steady = e.get("steady_pixels_per_second")
    while_in = f"; {num(steady)} pixels/s while the pixels went in (its progress reports)"
    return (
        'cocotb engine: `run_rtl(..., engine="cocotb")` at the same generics, its '
        "wall time including GHDL's build step (`ghdl -i`, `ghdl -m`: incremental), the "
        "elaboration and the cocotb start-up"
        + (while_in if steady else "")
        + ". Its records equal the golden model's, and its records and clock counts "
        "equal the fast engine's on the same frame."
    )
