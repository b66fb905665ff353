"""ORB in docs/results.md: in the synthesis section the ORB top, the ORB stage
and the keypoint budget beside the published ORB designs, and their targets
(issues 36 and 53), the ORB blocks alone with theirs, and the memories of ORB
(orb_memory.py); in the bench section the golden ORB against cv2.ORB and the
top with ORB descriptors on the bench frames."""

from __future__ import annotations

from flows.report.common import (
    at_most,
    ecp5_text,
    goal_note,
    lut_text,
    lut_total,
    margin,
    minutes,
    num,
    nums,
    table,
    target_lines,
    target_text,
)
from flows.report.entities import path_text
from flows.report.orb_memory import memory_lines
from flows.report.reference import ORB_ANCHORS, TARGETS, XC7Z020, limit

LABELS = {"top": "the AXI top", "stage": "ORB stage", "budget": "keypoint budget"}
ROLES = {"fastnms_axi": "top", "fastnms_orb_stage": "stage", "fastnms_cell_budget": "budget"}


def orb_rows(summary: list[dict]) -> dict[str, dict]:
    """The ORB rows of a summary by role, in the order top, stage, budget (those present)."""
    found = {ROLES[r["entity"]]: r for r in summary if r.get("orb_table") and r["entity"] in ROLES}
    return {role: found[role] for role in LABELS if role in found}


# ---- targets ----------------------------------------------------------------------


def placed(r: dict) -> bool:
    """The row was placed and routed (or tried: it did not fit or finish)."""
    return bool(r.get("ecp5") or r.get("ecp5_result"))


def orb_targets(summary: list[dict]) -> list[dict]:
    """Issue 36's ORB + budget (the stage and the budget summed) in LUT, BRAM18 and
    DSP; issue 53's: the top's LUT, BRAM18, place-and-route time and ECP5-8 Fmax, the
    Fmax of each ORB entity alone (the stage, the budget, the ORB blocks) and the
    logic levels of the angle, float and rotation units alone. The targets on the
    ORB blocks alone say so (`block`)."""
    rows = orb_rows(summary)
    out = []
    stage, budget, top = rows.get("stage"), rows.get("budget"), rows.get("top")
    if stage and budget:
        on = f"`{stage['config']}` + `{budget['config']}`"
        luts = lut_total(stage) + lut_total(budget)
        out.append(at_most("orb-budget-lut", luts, "LUT", on))
        bram = stage["bram18_equiv"] + budget["bram18_equiv"]
        out.append(at_most("orb-budget-bram", bram, "BRAM18", on))
        out.append(at_most("orb-budget-dsp", stage["dsp"] + budget["dsp"], "DSP", on))
    if top:
        on = f"`{top['config']}`"
        out.append(at_most("orb-top-lut", lut_total(top), "LUT", on))
        out.append(at_most("orb-top-bram", top["bram18_equiv"], "BRAM18", on))
        if placed(top):
            out += [pnr_target(top), fmax_target(top, "orb-top-fmax")]
    out += [fmax_target(r, "orb-block-fmax") for r in (stage, budget) if r and placed(r)]
    return out + block_targets(summary)


def block_targets(summary: list[dict]) -> list[dict]:
    """Issue 53's targets on the ORB blocks alone: each one's ECP5-8 Fmax, the units'
    logic levels; "not measured" for the blocks the summary does not have."""
    blocks = [r for r in summary if r.get("orb_block")]
    out = [fmax_target(r, "orb-block-fmax") for r in blocks if placed(r)]
    if not out:
        what = "not placed and routed" if blocks else "not synthesized alone"
        out.append(absent("orb-block-fmax", "each ORB block alone", what))
    found = {r["entity"]: r for r in blocks}
    units = TARGETS["orb-unit-levels"]["entities"]
    out += [levels_target(found[e]) for e in units if e in found]
    missing = [f"`{e}`" for e in units if e not in found]
    if missing:
        out.append(
            absent("orb-unit-levels", ", ".join(missing) + " alone", "not synthesized alone")
        )
    return [{**t, "block": True} for t in out]


def absent(key: str, on: str, what: str) -> dict:
    """A target on figures the summary does not have (`make synth`'s orb_blocks rows)."""
    return {
        "id": key,
        "target": target_text(key),
        "on": on,
        "measured": f"{what} in this summary",
        "met": None,
        "margin": "—",
    }


def device_of(r: dict) -> str:
    return ((r.get("ecp5") or {}).get("device") or "ECP5").split(" ")[0]


def fmax_target(r: dict, key: str) -> dict:
    """ECP5-8 Fmax of a placed row; not measured when it did not fit or finish."""
    least = limit(key)
    fmax = r.get("ecp5_fmax_mhz")
    met = None if fmax is None else fmax >= least
    spare = "—"
    if fmax is not None:
        spare = f"{fmax - least:+.1f} MHz ({fmax / least - 1:+.0%})"
        if met:
            spare += goal_note(key, fmax >= TARGETS[key]["goal"], "MHz")
    return {
        "id": key,
        "target": target_text(key),
        "on": f"`{r['config']}` ({device_of(r)})",
        "measured": r.get("ecp5_result") or ("—" if fmax is None else f"{fmax:.1f} MHz"),
        "met": met,
        "margin": spare,
    }


def pnr_target(r: dict) -> dict:
    """nextpnr's time on a placed row against the flow's limit: not reached when it
    was stopped or the design did not fit its device."""
    key = "orb-top-pnr"
    e = r.get("ecp5") or {}
    seconds = e.get("nextpnr_seconds")
    out = {"id": key, "target": target_text(key), "on": f"`{r['config']}` ({device_of(r)})"}
    if r.get("ecp5_result") or seconds is None:
        stopped = "does not fit its device" if e.get("does_not_fit") else "did not finish"
        return {
            **out,
            "measured": r.get("ecp5_result") or "—",
            "met": False if r.get("ecp5_result") else None,
            "margin": stopped if r.get("ecp5_result") else "—",
        }
    s, most = round(seconds), limit(key)
    met = s <= most
    text = margin(s, most, "s") + (goal_note(key, s <= TARGETS[key]["goal"], "s") if met else "")
    return {**out, "measured": f"{s} s ({minutes(seconds)})", "met": met, "margin": text}


def levels_target(r: dict) -> dict:
    key = "orb-unit-levels"
    most, levels = limit(key), r["logic_levels"]
    met = levels <= most
    return {
        "id": key,
        "target": target_text(key),
        "on": f"`{r['config']}`",
        "measured": f"{levels} levels",
        "met": met,
        "margin": f"{most - levels} level(s) to spare"
        + goal_note(key, levels <= TARGETS[key]["goal"], "levels")
        if met
        else f"{levels - most} level(s) over",
    }


# ---- the synthesis section's ORB part ---------------------------------------------------


def orb_synth_lines(summary: list[dict]) -> list[str]:
    """The ORB rows (ORB + budget summed), the top's share of a Zynq-7020, the
    published ORB designs beside the top, the targets; then the ORB blocks alone
    with their targets, and the memories of ORB."""
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
    out += orb_table(rows)
    if top:
        out += [zynq_share(top), ""]
    out.append("Beside what exists (issue 36's anchors; their published figures):")
    out.append("")
    out += anchor_lines(top)
    out.append("")
    targets = orb_targets(summary)
    blocks = [r for r in summary if r.get("orb_block")]
    out.append(
        "Targets: issue 36's for ORB + budget, issue 53's for the top and each entity alone:"
    )
    out.append("")
    out += target_lines([t for t in targets if not (blocks and t.get("block"))])
    out.append("")
    if blocks:
        out += blocks_lines(blocks)
        out.append("Issue 53's targets on the blocks alone:")
        out.append("")
        out += target_lines([t for t in targets if t.get("block")])
        out.append("")
    out += memory_lines(summary, top)
    return out


def blocks_lines(blocks: list[dict]) -> list[str]:
    """The ORB blocks synthesized alone (yosys xc7) and placed alone (nextpnr)."""
    body = [
        [
            f"`{r['config']}`",
            ", ".join(f"{k} {v}" for k, v in r["generics"].items()) or "defaults",
            lut_text(r),
            num(r["ff"]),
            str(r["bram18_equiv"]),
            str(r["dsp"]),
            str(r["logic_levels"]),
            ecp5_text(r),
            path_text((r.get("ecp5") or {}).get("critical_path")),
        ]
        for r in blocks
    ]
    devices = sorted({device_of(r) for r in blocks if placed(r)})
    out = ["#### ORB blocks alone", ""]
    out.append(
        "Each block of the ORB engine synthesized and placed on its own, out of context, at "
        "the generics `fastnms_orb_stage` gives it in the ORB top (`fastnms_orb_rows`: the "
        "blurred rows' buffer); "
        + (f"ECP5-8 on {', '.join(devices)}" if devices else "none placed in this summary")
        + ". These rows are listed here only, not in the tables by entity below."
    )
    out.append("")
    header = ["block", "generics", "LUT", "FF", "BRAM18 equiv.", "DSP", "logic levels"]
    out += table([*header, "ECP5-8 Fmax", "ECP5 critical path"], body)
    out.append("")
    return out


def orb_table(rows: dict[str, dict]) -> list[str]:
    body = [
        [
            f"`{r['config']}`",
            LABELS[role],
            lut_text(r),
            num(r["ff"]),
            str(r["bram18_equiv"]),
            str(r["dsp"]),
            str(r["logic_levels"]),
            ecp5_text(r),
        ]
        for role, r in rows.items()
    ]
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
    header = ["configuration", "what", "LUT", "FF", "BRAM18 equiv.", "DSP", "logic levels"]
    return [*table([*header, "ECP5-8"], body), ""]


def zynq_share(top: dict) -> str:
    shares = (
        f"{100 * lut_total(top) / XC7Z020['lut']:.0f} % of its LUTs, "
        f"{100 * top['bram18_equiv'] / XC7Z020['bram18']:.0f} % of its BRAM18 and "
        f"{100 * top['dsp'] / XC7Z020['dsp']:.0f} % of its DSPs"
    )
    return (
        f"On a Zynq-7020 (xc7z020: {num(XC7Z020['lut'])} LUT, {XC7Z020['bram18']} BRAM18, "
        f"{XC7Z020['dsp']} DSP48) the top would take {shares}; it takes "
        f"{lut_total(top) / ORB_ANCHORS[0]['lut']:.2f} times Siudya/ORB_FPGA's LUTs "
        "(the issue's goal: about a third)."
    )


def anchor_lines(top: dict | None) -> list[str]:
    """The published ORB designs, and the top of this run below them."""
    body = [
        [
            a["design"],
            a["computes"],
            a["rate"],
            num(a.get("lut")),
            num(a.get("ff")),
            a["bram"],
            num(a.get("dsp")),
            a["equal"],
            a["source"],
        ]
        for a in ORB_ANCHORS
    ]
    if top:
        g = top["generics"]
        body.append(
            [
                f"fastnms `{top['config']}` (this run)",
                "FAST + 3x3 NMS + budget, moments, float32 angle, bit-exact 7x7 Gaussian, "
                "rotated BRIEF",
                f"{g.get('MAX_WIDTH')}x{g.get('MAX_HEIGHT')}, 1 pixel/clock; ECP5-8: "
                f"{ecp5_text(top)}",
                lut_text(top),
                num(top["ff"]),
                f"{top['bram18_equiv']} BRAM18",
                num(top["dsp"]),
                "records equal the golden model's (cv2.ORB's keypoints and angles; "
                "descriptors with OpenCV's fixed-point blur: the bench section)",
                "yosys xc7 (not Vivado); nextpnr ECP5",
            ]
        )
    header = ["design", "what it computes", "rate", "LUT", "FF", "BRAM", "DSP"]
    out = table([*header, "equal to OpenCV ORB", "figures from"], body)
    out.append("")
    out.append(
        "The anchors' figures come from different tools and devices (Vivado or HLS "
        "reports on Zynq-7000 and UltraScale+), fastnms's from yosys on GHDL's netlist; "
        "a dash: not published in what the issue quotes."
    )
    return out


# ---- the bench section's ORB tables --------------------------------------------------


def orb_lines(orb: dict | None) -> list[str]:
    """The golden ORB's descriptors with the contract's blur against cv2.ORB's."""
    if not orb:
        return []
    out = ["### ORB: the contract against cv2.ORB", ""]
    body = [
        [f"`{r['image']}`", f"{r['size'][0]}x{r['size'][1]}", *agreement(r)] for r in orb["rows"]
    ]
    body.append(["all", "", *agreement(orb)])
    header = ["photograph", "size", "keypoints", "descriptors differing", "mean bits (all)"]
    out += table([*header, "mean bits (differing)", "max bits"], body)
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


def agreement(r: dict) -> list[str]:
    return [
        num(r["keypoints"]),
        f"{r['differing'] / max(r['keypoints'], 1):.1%}",
        f"{r['mean_bits']:.3f}",
        f"{r['bits'] / max(r['differing'], 1):.2f}",
        str(r["max_bits"]),
    ]


def orb_rtl_lines(orb_rtl: dict | None, w: int, h: int) -> list[str]:
    """The AXI top with ORB descriptors on the bench frames."""
    if not orb_rtl:
        return []
    g = orb_rtl["generics"]
    out = ["### ORB descriptors in the top", ""]
    body = [
        [
            f"{r['per_cell']} per {r['cell']}x{r['cell']}",
            num(r["cells"] * r["per_cell"]),
            nums(r["corners"]),
            f"{r['input_clocks_per_pixel']:.5f}",
            nums(r["frame_input_stalls"]),
            nums(r["latency_clocks"]),
            "equal" if r["checked"] else "not checked",
            num(r["sim_pixels_per_second"]),
        ]
        for r in orb_rtl["rows"]
    ]
    header = ["budget (CELL, K)", "bound (cells x K)", "keypoints per frame", "input clocks/pixel"]
    header += ["input stalls per frame", "latency (clocks)", "vs golden", "simulated pixels/s"]
    out += table(header, body)
    out.append("")
    build = orb_rtl.get("build_seconds")
    out.append(
        f"`fastnms_axi` with DESCRIPTOR orb, {g.get('SCORE')} + {g.get('NMS')}, MAX_PER_CELL "
        f"{g.get('MAX_PER_CELL')}, ORB_MAX_CELL {g.get('ORB_MAX_CELL')}, at {w}x{h} on the "
        "fast engine ("
        + ("cached build" if build is None else f"built in {build:.0f} s")
        + "): the bench frames back to back with no blanking, BUDGET written for each. "
        "Input clocks/pixel: from the first pixel taken to the last, over the pixels; "
        "frames overlap in ORB (the next frame's rows come in while a frame's last cell row "
        "is described), so a K within the engine's rate holds no pixel (docs/orb_rtl.md, "
        "*Throughput*; a K above it is clamped to it). Latency: from a frame's last "
        "pixel in to its last record out. vs golden: every record (position, score, the "
        "angle's float32 bits, all 256 descriptor bits) equal to "
        "`fastnms.golden.orb.orb_features` with the frame's CELL and K (a difference stops "
        "the bench)."
    )
    out.append("")
    return out
