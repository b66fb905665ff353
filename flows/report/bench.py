"""The bench section of docs/results.md (`make bench`): the AXI top's throughput
and latency on photographs, the 3840x2160 run at 4 pixels per clock, the
engines, the throughput target, the region NMS's memory, the software
timings, ORB and the keypoint budget in the top, and how long it took."""

from __future__ import annotations

from flows.report.common import minutes, num, nums, source_text, table, target_lines, target_text
from flows.report.engines import engine_lines
from flows.report.orb import orb_lines, orb_rtl_lines
from flows.report.reference import limit

PHASES = {
    "software": "software timings",
    "orb": "ORB against cv2.ORB",
    "budget": "the keypoint budget",
    "orb_rtl": "ORB in the top",
    "builds": "fast-engine builds",
    "simulations": "fast-engine simulations and golden checks",
    "cocotb": "the cocotb run",
}


def bench_section(bench: dict) -> str:
    fr = bench["frames"]
    w, h = fr["width"], fr["height"]
    out = ["## Simulation, memory and software (`make bench`)", ""]
    out.append(
        f"`fastnms_axi` at MAX_WIDTH {w}, MAX_HEIGHT {h}, in {len(bench['simulation'])} "
        "score x NMS configurations, on the fast simulation engine (GHDL's synthesized "
        "netlist compiled by Verilator and driven from C++: `fastnms.sim.run.run_rtl`, engine "
        f"`verilator`): {fr['count']} frames of {w}x{h} sent back to back, no input idles, no "
        f"output back-pressure, threshold {fr['threshold']}, each frame's size and threshold "
        "written over AXI4-Lite once the previous frame's first line is in "
        "([simulation.md](simulation.md)). The frames are photographs "
        f"({', '.join(fr['photographs'])}), {fr['fit']}."
    )
    out.append("")
    out += throughput_lines(bench)
    out += uhd_lines(bench.get("uhd"))
    out += engine_lines(bench.get("engines", []))
    out += ["### Target", ""]
    out += target_lines(bench_targets(bench))
    out.append("")
    out += ["### Region-NMS memory", ""]
    for mem in bench["region_memory"]:
        out += memory_lines(mem)
    out += software_lines(bench)
    out += orb_lines(bench.get("orb"))
    out += budget_lines(bench.get("budget"), w, h)
    out += orb_rtl_lines(bench.get("orb_rtl"), w, h)
    out += how_lines(bench)
    return "\n".join(out)


def throughput_lines(bench: dict) -> list[str]:
    """The table of the configurations' runs and what its columns count."""
    w, h = bench["frames"]["width"], bench["frames"]["height"]
    m = bench["machine"]
    rows = []
    for sim in bench["simulation"]:
        steady = sim["steady_clocks_per_pixel"]
        build = sim.get("build_seconds")
        rows.append(
            [
                f"{sim['score']} + {sim['nms']}",
                f"{sim['input_clocks_per_pixel']:.5f}",
                nums(sim["frame_interval_clocks"]) or "—",
                "—" if steady is None else f"{steady:.5f}",
                nums(sim["latency_clocks"]),
                nums(sim["corners"]),
                "equal" if sim["checked"] else "not checked",
                num(sim["input_stalls"]),
                num(sim["sim_pixels_per_second"]),
                "cached" if build is None else f"{build:.0f} s",
            ]
        )
    header = ["configuration", "input clocks/pixel"]
    header += [f"frame intervals (clocks; W·H = {num(w * h)})", "clocks/pixel, steady"]
    header += ["latency per frame (clocks)", "corners per frame"]
    header += ["vs golden", "input stalls", "simulated pixels/s", "build"]
    out = ["### Throughput and latency", "", *table(header, rows), ""]
    builds = m.get("parallel_builds")
    out.append(
        "Input clocks/pixel: clocks from the first to the last pixel taken, over the "
        "pixels. Frame intervals: clocks between consecutive frames' last records (the "
        "registers are written for every frame; the top never holds the input for them, "
        "[fastnms_axi.md](fastnms_axi.md)). Latency: clocks from a frame's last pixel in (its "
        "input handshake) to its last record out (the `tlast` handshake on "
        "`m_axis_corners`). vs golden: every frame's records against "
        "`fastnms.golden.model.detect` (a difference stops the bench). Simulated pixels/s: "
        "the fast engine's wall-clock speed on the frames, one simulation at a time. Build: "
        "GHDL synthesis, Verilator and g++ for the configuration, "
        f"{builds} build{'' if builds == 1 else 's'} at a time on {m.get('cores')} cores "
        f"({m.get('cpu')}; load average {m.get('load_before', '?')} before the run); "
        "cached: built by an earlier run from the same sources and tools."
    )
    out.append("")
    return out


def uhd_lines(uhd: dict | None) -> list[str]:
    """The 3840x2160 run of the top built with several pixels per clock."""
    if not uhd:
        return []
    w, h, ppc = uhd["width"], uhd["height"], uhd["ppc"]
    out = [f"### {w}x{h} at {ppc} pixels per clock", ""]
    out.append(
        f"`fastnms_axi` built with PPC {ppc}, MAX_WIDTH {w}, MAX_HEIGHT {h}, "
        f"{uhd['score']} + {uhd['nms']}: {uhd['frames']} photographs scaled to {w}x{h} "
        f"({', '.join(uhd.get('photographs', []))}), back to back, threshold "
        f"{uhd['threshold']}, on the fast engine; {ppc} pixels per input beat."
    )
    out.append("")
    header = ["input clocks/pixel", f"frame intervals (clocks; W·H/{ppc} = {num(w * h // ppc)})"]
    header += ["latency per frame (clocks)", "corners per frame", "vs golden", "input stalls"]
    row = [
        f"{uhd['input_clocks_per_pixel']:.5f}",
        nums(uhd["frame_interval_clocks"]) or "—",
        nums(uhd["latency_clocks"]),
        nums(uhd["corners"]),
        "equal" if uhd["checked"] else "not checked",
        num(uhd["input_stalls"]),
        num(uhd["sim_pixels_per_second"]),
    ]
    return [*out, *table([*header, "simulated pixels/s"], [row]), ""]


def bench_targets(bench: dict) -> list[dict]:
    """Sustained throughput: the clocks between consecutive frames' last records
    in steady state (the input side when a single frame was run)."""
    out = []
    pixels = bench["frames"]["width"] * bench["frames"]["height"]
    for sim in bench["simulation"]:
        steady = sim["steady_clocks_per_pixel"]
        value = steady if steady is not None else sim["input_clocks_per_pixel"]
        extra = round((value - 1) * pixels)
        out.append(
            {
                "id": "pixels-per-clock",
                "target": target_text("pixels-per-clock"),
                "on": f"`fastnms_axi` {sim['score']} + {sim['nms']}",
                "measured": f"{value:.5f} clocks/pixel",
                "met": round(value, 2) <= limit("pixels-per-clock"),
                # In clocks per frame: a few clocks are 0.000 % of a full-HD frame.
                "margin": (
                    f"{num(extra)} clocks per frame over W·H ({100 * (value - 1):.4f} %)"
                    if value > 1
                    else "exactly 1 clock per pixel"
                ),
            }
        )
    return out


def memory_lines(mem: dict) -> list[str]:
    """One region-NMS configuration's memories in bits, against the paper's
    formula, a 5-line FIFO NMS and the 3x3 NMS."""
    out = [
        f"`{mem['config']}` ({mem['score_bits']}-bit score, {num(mem['slots'])} slots of "
        f"{mem['slot_bits']} bits, x {mem['x_bits']} bits, y {mem['y_bits']} bits), from "
        "the generics as the RTL sizes its memories:",
        "",
    ]
    w, s = mem["max_width"], mem["score_bits"]
    rows = [
        [r["memory"], f"{num(r['words'])} x {r['bits_per_word']}", num(r["bits"])]
        for r in mem["breakdown"]
    ]
    rows += [
        ["**total**", "", f"**{num(mem['total_bits'])}**"],
        [
            "the paper's formula (W/2) x (score + x + y + index bits)",
            mem["paper_formula"],
            num(mem["paper_formula_bits"]),
        ],
        ["a 5-line FIFO NMS, 5 x W x score bits", f"5 x {w} x {s}", num(mem["fifo5_bits"])],
        ["the 3x3 NMS here, 2 x W x score bits", f"2 x {w} x {s}", num(mem["nms_3x3_bits"])],
    ]
    out += table(["memory", "words x bits", "bits"], rows)
    out.append("")
    out.append(
        f"{mem['total_bits'] / mem['paper_formula_bits']:.1f} times the paper's formula, "
        "which counts only the region maxima (the data table holds the same; the stack "
        "holds the open classes' maxima a second time, and the head and last bits replace "
        f"the paper's label line); {mem['total_bits'] / mem['fifo5_bits']:.2f} times a "
        "5-line FIFO."
    )
    out.append("")
    return out


def software_lines(bench: dict) -> list[str]:
    w, h = bench["frames"]["width"], bench["frames"]["height"]
    m = bench["machine"]
    rows = [
        [r["what"], f"{r['ms']:.1f}", num(r["corners"]), f"best of {r['best_of']}"]
        for r in bench["software"]
    ]
    out = ["### Software on this machine", ""]
    out += table(["what", f"ms per {w}x{h} frame", "corners", ""], rows)
    out.append("")
    out.append(
        f"The first bench frame; golden model = the Python package `fastnms` "
        f"(golden/, timed with `fastnms.bench.best_ms`); OpenCV {m.get('opencv')}, "
        f"Python {m.get('python')}. For scale: at one pixel per clock the IP takes "
        f"{num(w * h)} clocks per frame, {w * h / 134e6 * 1e3:.1f} ms at the paper's "
        "134 MHz."
    )
    out.append("")
    return out


def budget_lines(budget: dict | None, w: int, h: int) -> list[str]:
    """opencv + 3x3 with the keypoint budget in the top, on the bench frames."""
    if not budget:
        return []
    rows = [
        [
            f"{r['per_cell']} per {r['cell']}x{r['cell']}",
            num(r["cells"] * r["per_cell"]),
            nums(r["corners"]),
            f"{r['input_clocks_per_pixel']:.5f}",
            num(r["input_stalls"]),
            nums(r["latency_clocks"]),
            "yes" if r["checked"] else "not checked",
        ]
        for r in budget["rows"]
    ]
    header = ["budget", "bound (cells x K)", "keypoints per frame", "input clocks/pixel"]
    header += ["input stalls", "latency (clocks)", "vs golden"]
    out = ["### The keypoint budget in the top", "", *table(header, rows), ""]
    out.append(
        f"`opencv` + `3x3` at {w}x{h}, `MAX_PER_CELL` 15, the bench frames back to back "
        "with BUDGET written for each (fast engine). Latency: from a frame's last pixel in "
        "to its last record out. vs golden: every frame's records equal "
        "`fastnms.golden.budget.hardware_order` (the golden model's budget in the block's "
        "order). Without the budget, the keypoints per frame are in the table above."
    )
    out.append("")
    return out


def how_lines(bench: dict) -> list[str]:
    m = bench["machine"]
    phases = bench.get("phases", {})
    spent = ", ".join(f"{PHASES.get(k, k)} {minutes(v)}" for k, v in phases.items())
    return [
        "### How long",
        "",
        f"- Source: {source_text(bench.get('source'))}.",
        *([f"- Data: {bench['note']}"] if bench.get("note") else []),
        f"- Tools: {m.get('ghdl')}; {m.get('verilator', 'Verilator unknown')}.",
        f"- Wall time of `make bench`: **{minutes(bench['wall_seconds'])}**"
        + (f" ({spent})." if spent else "."),
    ]
