"""Every row of the synthesis summary, grouped by entity: one heading per entity
(`#### fastnms_fifo`, anchor `#fastnms_fifo`) that the entity's page links to,
then its configurations with their generics and figures (an ORB block alone,
`orb_block`, points to its row in the ORB part, orb.py)."""

from __future__ import annotations

from flows.report.common import ecp5_text, lut_text, num, table

HEADER = [
    "configuration",
    "generics",
    "LUT",
    "FF",
    "CARRY4",
    "BRAM18 equiv. (18 + 2x36)",
    "DSP",
    "logic levels",
    "ECP5-8 Fmax (MHz)",
    "ECP5 critical path",
    "ECP5 LUT4 / FF",
]


def entity_lines(summary: list[dict]) -> list[str]:
    """The section: an introduction, then per entity (in the order they first
    appear) its heading and table; the top's also says where its depth and its
    slowest path are."""
    out = ["### Every configuration and block, by entity", ""]
    out.append(
        "One table per entity, each under a heading named after it, so that the entity's "
        "page links to its figures (`results.md#fastnms_fifo`). LUT: the total as Vivado's "
        "*Slice LUTs* count it, with its logic LUTs, SRL shift registers and LUT RAM in "
        "brackets. A configuration that gives a block the generics of another is the same "
        "synthesis, listed under both names."
    )
    out.append("")
    for entity in dict.fromkeys(r["entity"] for r in summary):
        rows = [r for r in summary if r["entity"] == entity and not r.get("orb_block")]
        alone = [r for r in summary if r["entity"] == entity and r.get("orb_block")]
        out += [f"#### {entity}", ""]
        if rows:
            out += table(HEADER, [entity_row(r) for r in rows])
            out.append("")
        if alone:
            names = ", ".join(f"`{r['config']}`" for r in alone)
            out += [f"Alone ({names}): in [ORB blocks alone](#orb-blocks-alone).", ""]
        if entity == "fastnms_axi":
            out += top_notes(summary)
    return out


def entity_row(row: dict) -> list[str]:
    e = row.get("ecp5") or {}
    return [
        f"`{row['config']}`",
        ", ".join(f"{k} {v}" for k, v in row["generics"].items()),
        lut_text(row),
        num(row["ff"]),
        num(row["carry4"]),
        f"{row['bram18_equiv']} ({row.get('bram18', 0)} + 2x{row.get('bram36', 0)})",
        str(row["dsp"]),
        str(row["logic_levels"]),
        ecp5_text(row, unit=False),
        path_text(e.get("critical_path")),
        cells_text(e.get("cells")),
    ]


def path_text(path: dict | None) -> str:
    """A critical path's ends (cell types), length and the first cell's clock-to-out."""
    if not path:
        return "—"
    text = f"{path.get('from_type') or '?'} → {path.get('to_type') or '?'}, {path['ns']:.2f} ns"
    if path.get("clk_to_q_ns"):
        text += f" ({path['clk_to_q_ns']:.2f} clk-to-q)"
    return text


def cells_text(cells: dict | None) -> str:
    if not cells:
        return "—"
    return f"{num(cells.get('LUT4'))} / {num(cells.get('TRELLIS_FF'))}"


def top_notes(summary: list[dict]) -> list[str]:
    """The tops at the section's size: logic levels outside the core, and the
    slowest one's ECP5 critical path."""
    tops = [
        r
        for r in summary
        if r["entity"] == "fastnms_axi"
        and not (r.get("ppc_table") or r.get("orb_table") or r.get("orb_block"))
    ]
    out = []
    outside = [r for r in tops if "logic_levels_outside_core" in r]
    if outside:
        out.append(
            "Logic levels of the top outside `fastnms_core` (paths that start or end in "
            "the top's own logic): "
            + ", ".join(f"`{r['config']}` {r['logic_levels_outside_core']}" for r in outside)
            + "."
        )
        out.append("")
    paths = [r for r in tops if (r.get("ecp5") or {}).get("critical_path")]
    if paths:
        slow = min(paths, key=lambda r: r["ecp5_fmax_mhz"] or 1e9)
        out += [slowest_path_text(slow, summary), ""]
    return out


def slowest_path_text(slow: dict, summary: list[dict]) -> str:
    cp = slow["ecp5"]["critical_path"]
    start = f"`{cp['from']}`" + (f" ({cp['from_type']})" if cp.get("from_type") else "")
    end = f"`{cp['to']}`" + (f" ({cp['to_type']})" if cp.get("to_type") else "")
    text = (
        f"The slowest top on the ECP5, `{slow['config']}`, is limited by a path from "
        f"{start} to {end}: {cp['ns']:.2f} ns, {cp['logic_ns']:.2f} ns in cells and "
        f"{cp['routing_ns']:.2f} ns in routing, {cp['logic_steps']} logic steps."
    )
    if cp.get("from_type") != "DP16KD" or not cp.get("clk_to_q_ns"):
        return text
    text += (
        " It starts at a block-RAM read port: the DP16KD's clock-to-output without its "
        f"output register is {cp['clk_to_q_ns']:.2f} ns at speed grade 8"
    )
    paths = [(r.get("ecp5") or {}).get("critical_path") for r in summary]
    if all(p.get("from_type") == "DP16KD" for p in paths if p):
        text += (
            f", so on this family a path from a RAM read stays under "
            f"{1000 / cp['clk_to_q_ns']:.0f} MHz before any logic or routing; every "
            "top and block here has its critical path starting at one"
        )
    return text + "."
