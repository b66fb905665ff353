"""The synthesis section of docs/results.md (`make synth`): the detector beside
the paper and AMD, its targets, then the PPC and ORB tables, every row by
entity, and how the figures were made."""

from __future__ import annotations

from flows.report.common import (
    at_most,
    by_config,
    lut_text,
    lut_total,
    minutes,
    num,
    source_text,
    table,
    target_lines,
    target_text,
    unique,
)
from flows.report.entities import entity_lines
from flows.report.orb import orb_synth_lines
from flows.report.ppc import ppc_lines
from flows.report.reference import AMD, PAPER, limit


def main_rows(summary: list[dict]) -> list[dict]:
    """The rows at the section's size: neither the PPC nor the ORB comparison's, nor
    an ORB block alone."""
    return [r for r in summary if not (r.get("ppc_table") or orb_row(r))]


def orb_row(r: dict) -> bool:
    """A row of the ORB comparison or an ORB block alone (orb.py has their tables and
    targets)."""
    return bool(r.get("orb_table") or r.get("orb_block"))


def synth_section(summary: list[dict], info: dict) -> str:
    width = summary[0]["generics"]["MAX_WIDTH"] if summary else 0
    height = summary[0]["generics"].get("MAX_HEIGHT", "?") if summary else 0
    out = ["## Synthesis and place and route (`make synth`)", ""]
    out.append(
        f"MAX_WIDTH {width}, MAX_HEIGHT {height}. LUT and FF figures: yosys "
        "`synth_xilinx`, xc7 (not Vivado); Fmax: nextpnr, Lattice ECP5-8, out of "
        "context (not a Xilinx figure)."
    )
    out.append("")
    out += side_by_side_lines(summary)
    out += bram_note(summary)
    out += ["### Targets", ""]
    out += target_lines(synth_targets(summary))
    out.append("")
    out += ppc_lines(summary)
    out += orb_synth_lines(summary)
    out += entity_lines(summary)
    out += how_lines(summary, info)
    return "\n".join(out)


def side_by_side_lines(summary: list[dict]) -> list[str]:
    """The paper's and AMD's published figures above the tops and cores."""
    rows = main_rows(summary)
    ours = [r for r in rows if r["entity"] == "fastnms_axi"]
    ours += [r for r in rows if r["entity"] == "fastnms_core"]
    body = [
        [
            ref["name"],
            ref["what"],
            num(ref["lut"]),
            num(ref["ff"]),
            ref["bram_text"],
            "—",
            f"{ref['fmax_mhz']} MHz on {ref['device']}",
            str(ref["pixels_per_clock"]),
            ref["tool"],
        ]
        for ref in (PAPER, AMD)
    ]
    for row in ours:
        fmax = row.get("ecp5_fmax_mhz")
        body.append(
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
    header = ["design", "configuration", "LUT", "FF", "BRAM18 equiv.", "logic levels", "Fmax"]
    out = ["### Side by side with the paper and AMD", ""]
    out += table([*header, "pixels/clock", "figures from"], body)
    out.append("")
    out.append(
        "LUT for fastnms: logic LUTs (INV included) + SRL shift registers + LUT RAM, "
        "as Vivado's *Slice LUTs* would count them. The paper's and AMD's "
        "DSP counts and logic depths are not compared (not in the quoted figures); "
        "fastnms uses no DSP."
    )
    out.append("")
    return out


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


def synth_targets(summary: list[dict]) -> list[dict]:
    """The detector's targets against the paper (sad + region4) and AMD (opencv +
    3x3, at every size), and the logic levels of every row but ORB's (ORB has its
    own, orb.orb_targets)."""
    summary = [r for r in summary if not orb_row(r)]
    rows = by_config(summary)
    out = []
    for entity in ("fastnms_axi", "fastnms_core"):
        for cfg, row in rows.items():
            if row["entity"] == entity and (row["score"], row["nms"]) == ("sad", "region4"):
                out.append(at_most("lut-half-paper", lut_total(row), "LUT", f"`{cfg}`"))
                out.append(at_most("ff-half-paper", row["ff"], "FF", f"`{cfg}`"))
    for entity in ("fastnms_core", "fastnms_axi"):
        for cfg, row in rows.items():
            if row["entity"] == entity and (row["score"], row["nms"]) == ("opencv", "3x3"):
                out.append(at_most("lut-below-amd", lut_total(row), "LUT", f"`{cfg}`"))
                out.append(at_most("bram-amd", row["bram18_equiv"], "BRAM18", f"`{cfg}`"))
    out.append(levels_target(summary))
    return out


def levels_target(summary: list[dict]) -> dict:
    """The logic-levels target over every row: the worst, and the rows over."""
    most = limit("logic-levels")
    deep = [r for r in summary if r["logic_levels"] > most]
    worst = max((r["logic_levels"] for r in summary), default=0)
    over = ", ".join(
        f"`{r['config']}` {r['logic_levels']} (+{r['logic_levels'] - most})" for r in deep
    )
    return {
        "id": "logic-levels",
        "target": target_text("logic-levels"),
        "on": f"all {len(summary)} entries",
        "measured": f"worst {worst}",
        "met": not deep,
        "margin": (
            f"{most - worst} level(s) to spare"
            if not deep
            else f"{len(deep)} of {len(summary)} entries over: {over}"
        ),
    }


def how_lines(summary: list[dict], info: dict) -> list[str]:
    """The source, tools, flows, jobs and wall times of the run."""
    runs = unique(summary)
    out = ["### How, and how long", ""]
    out.append(f"- Source: {source_text(info.get('source'))}.")
    if info.get("note"):
        out.append(f"- Data: {info['note']}")
    tools = ", ".join(f"{k} {v}" for k, v in info.get("tools", {}).items())
    out.append(f"- Tools: {tools}. Flow: {info.get('xc7_flow')}; {info.get('ecp5_flow')}.")
    if info.get("ecp5_orb_device") and any(r.get("orb_table") for r in summary):
        stop = info.get("ecp5_timeout_seconds")
        out.append(
            f"- The ORB rows are placed and routed on the {info['ecp5_orb_device']} (the "
            "others on the LFE5U-45F), "
            + (f"nextpnr stopped after {minutes(stop)}" if stop else "without a time limit")
            + "; a design larger than its device is recorded as not fitting."
        )
    out.append(
        f"- {info.get('distinct_syntheses')} distinct syntheses for {len(summary)} entries "
        f"(a block shared by two configurations is synthesized once), "
        f"{info.get('ecp5_runs')} of them placed and routed; "
        f"{info.get('jobs')} parallel jobs on {info.get('cores')} cores "
        f"(load average {info.get('load_before', '?')} before the run)."
    )
    xc7_s = sum(r.get("xc7_seconds", 0) for r in runs)
    yos_s = sum((r.get("ecp5") or {}).get("yosys_seconds", 0) for r in runs)
    pnr_s = sum((r.get("ecp5") or {}).get("nextpnr_seconds", 0) for r in runs)
    cache = info.get("cache") or {}
    reused = len(cache.get("cached", [])) + len(cache.get("previous_summary", []))
    this_run = (
        f" ({len(cache.get('run', []))} rows run, {reused} from the cache or the previous summary)"
        if cache
        else ""
    )
    out.append(
        f"- Wall time of `make synth`: **{minutes(info.get('wall_seconds', 0))}**{this_run}; "
        f"the rows' own run times, summed over the jobs: yosys xc7 {minutes(xc7_s)}, "
        f"yosys ECP5 {minutes(yos_s)}, nextpnr {minutes(pnr_s)}."
    )
    placed = [r for r in runs if r.get("ecp5")]
    slowest = max(placed, key=lambda r: r["ecp5"]["nextpnr_seconds"], default=None)
    if slowest:
        out.append(
            f"- The longest place and route: `{slowest['config']}`, "
            f"{minutes(slowest['ecp5']['nextpnr_seconds'])}."
        )
    return out
