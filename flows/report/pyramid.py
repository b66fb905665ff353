"""The pyramid plan of docs/results.md (issue 54, read with docs/pyramid.md): cv2.ORB's
pyramid at the sizes of [pyramid] in reference.toml, its pixel rates against the clocks
measured in docs/results/synth.json and the clocks given, the ORB engine shared by the
levels, each level's memory (pyramid_memory.py) against the xc7z020's BRAM18 and the DDR
traffic of the rows moved there, and the options' logic from the measured blocks. A
measured row that is missing leaves out its clock or its block, and says so."""

from __future__ import annotations

import math

from fastnms.sim.run import ORB_KEYPOINT_CLOCKS

from flows.report import orb_memory
from flows.report.common import lut_total, num, table
from flows.report.pyramid_memory import (
    BY_KEY,
    CELL,
    DDR_ROWS,
    MEMORIES,
    PER_CELL,
    PLAN,
    PLANS,
    SCORE_BITS,
    Level,
    cost,
    levels,
    once,
    plan_cost,
    shares,
)
from flows.report.reference import PAPER, XC7Z020

HEADING = "## Pyramid plan (issue 54)"


# ---- clocks and measured rows ----------------------------------------------------------


def find(summary: list[dict], spec: dict) -> dict | None:
    """The row of `spec`'s entity with exactly its generics, if the summary has it."""
    return next(
        (r for r in summary if r["entity"] == spec["entity"] and r["generics"] == spec["generics"]),
        None,
    )


def clocks(summary: list[dict]) -> list[tuple[float, str]]:
    """(MHz, what): the measured ECP5 Fmax of [pyramid.measured_clocks] that exist, the
    paper's xc7z020 clock and [pyramid] clocks."""
    out = []
    for spec in PLAN["measured_clocks"]:
        row = find(summary, spec)
        if row and row.get("ecp5_fmax_mhz"):
            out.append((row["ecp5_fmax_mhz"], f"ECP5 Fmax of {spec['name']} (`{row['config']}`)"))
    out.append((PAPER["fmax_mhz"], f"the paper's clock on the {PAPER['device']}"))
    return out + [(c["mhz"], c["name"]) for c in PLAN["clocks"]]


def missing_clocks(summary: list[dict]) -> list[str]:
    return [
        spec["name"]
        for spec in PLAN["measured_clocks"]
        if not (find(summary, spec) or {}).get("ecp5_fmax_mhz")
    ]


def mhz(f: float) -> str:
    return f"{f:g} MHz"


# ---- the section ----------------------------------------------------------------------


def configs() -> list[tuple[str, list[Level]]]:
    return [
        (f"{s['width']}x{s['height']} ({s['name']})", levels(s["width"], s["height"]))
        for s in PLAN["sizes"]
    ]


def pyramid_section(summary: list[dict] | None) -> str:
    summary = summary or []
    out = [HEADING, ""]
    out.append(
        f"The plan of an ORB IP on cv2.ORB's pyramid ({PLAN['levels']} levels, scale factor "
        f"{PLAN['scale_factor']}; [pyramid.md](pyramid.md)), computed by "
        "flows/report/pyramid.py from the level sizes of `fastnms.golden.pyramid.level_size`, "
        "formulas of the RTL's memories and the measured rows of the synthesis section. "
        "Mpixel/s and MB/s are 10^6 pixels and bytes per second."
    )
    out.append("")
    lv = configs()
    for part in (size_lines, rate_lines, engine_lines, memory_lines, total_lines):
        out += part(lv, summary)
    out += logic_lines(summary)
    return "\n".join(out).rstrip() + "\n"


def size_lines(cfgs: list[tuple[str, list[Level]]], summary: list[dict]) -> list[str]:
    s, n = PLAN["scale_factor"], PLAN["levels"]
    out = ["### Pyramid plan: level sizes", ""]
    out.append(
        f"Each level's size and, in brackets, its pixels over level 0's; beside them "
        f"{s * s:.2f}^-k ({s}^-2k), which the rounded sizes follow closely."
    )
    out.append("")
    body = [
        [str(k), f"{s ** (-2 * k):.3f}"]
        + [f"{lv[k].width}x{lv[k].height} ({shares(lv)[k]:.3f})" for _, lv in cfgs]
        for k in range(n)
    ]
    for what, first in ((f"levels 1 to {n - 1}", 1), ("the pyramid", 0)):
        ideal = sum(s ** (-2 * k) for k in range(first, n))
        body.append(
            [f"**{what}**", f"{ideal:.3f}"]
            + [f"**{sum(shares(lv)[first:]):.3f}**" for _, lv in cfgs]
        )
    return [*out, *table(["level", f"{s * s:.2f}^-k", *(c for c, _ in cfgs)], body), ""]


def rates(lv: list[Level], fps: float) -> tuple[float, float, float]:
    """Mpixel/s of level 0, of levels 1 to 7 and of the whole pyramid."""
    px = [x.pixels * fps / 1e6 for x in lv]
    return px[0], sum(px[1:]), sum(px)


def clock_note(summary: list[dict]) -> list[str]:
    text = "Clocks: " + "; ".join(f"{mhz(f)}, {what}" for f, what in clocks(summary)) + "."
    missing = missing_clocks(summary)
    if missing:
        text += " Not measured in this summary (no ECP5 Fmax): " + ", ".join(missing) + "."
    return [text, ""]


def rate_lines(cfgs: list[tuple[str, list[Level]]], summary: list[dict]) -> list[str]:
    n, clk = PLAN["levels"], clocks(summary)
    out = ["### Pyramid plan: pixel rates and pipelines", ""]
    out.append(
        f"Pixels per second of level 0, of levels 1 to {n - 1} and of the whole pyramid "
        "(Mpixel/s), then at each clock the options that fit: (a) one detector, NMS and "
        f"budget pipeline per level ({n} pipelines, each at its level's rate), which needs "
        f"a clock of at least level 0's rate; (b) level 0 on one pipeline and levels 1 to "
        f"{n - 1} time-shared on a second, which needs a clock of at least their rate. "
        "After the dot: the fewest one-pixel-per-clock pipelines that could carry the "
        "whole pyramid at that clock (its rate over the clock, rounded up)."
    )
    out.append("")
    body = []
    for fps in (PLAN["fps"], PLAN["fps_context"]):
        for name, lv in cfgs:
            l0, rest, total = rates(lv, fps)
            fits = []
            for f, _ in clk:
                opts = [o for o, need in (("(a)", l0), ("(b)", max(l0, rest))) if need <= f]
                fits.append(f"{', '.join(opts) or 'neither'} · {math.ceil(total / f)}")
            body.append([name, str(fps), f"{l0:.1f}", f"{rest:.1f}", f"{total:.1f}", *fits])
    header = ["size", "frames/s", "level 0", f"levels 1 to {n - 1}", "pyramid"]
    out += table(header + [mhz(f) for f, _ in clk], body)
    return [*out, "", *clock_note(summary)]


def engine_lines(cfgs: list[tuple[str, list[Level]]], summary: list[dict]) -> list[str]:
    n, clk = PLAN["levels"], clocks(summary)
    out = ["### Pyramid plan: the ORB engine shared by the levels", ""]
    out.append(
        f"The ORB engine describes a keypoint every {ORB_KEYPOINT_CLOCKS} clocks. With K "
        f"keypoints per {CELL}x{CELL} cell of each level, a level gives at most cells x K "
        f"keypoints a frame (cells = ⌈W / {CELL}⌉ ⌈H / {CELL}⌉): below, per level, its "
        f"cells (its keypoints at K 1) and the engine clocks they take ({ORB_KEYPOINT_CLOCKS} "
        "each)."
    )
    out.append("")
    body = [
        [str(k)]
        + [v for _, lv in cfgs for v in (num(lv[k].cells), num(lv[k].cells * ORB_KEYPOINT_CLOCKS))]
        for k in range(n)
    ]
    totals = [sum(x.cells for x in lv) for _, lv in cfgs]
    body.append(
        ["**all**"] + [f"**{num(v)}**" for c in totals for v in (c, c * ORB_KEYPOINT_CLOCKS)]
    )
    header = ["level"] + [h for name, _ in cfgs for h in (f"{name}: cells", "engine clocks")]
    out += [*table(header, body), ""]
    out.append(
        f"One engine for all levels: at each clock, the largest K (up to {PER_CELL}, "
        f"{CELL}²/{ORB_KEYPOINT_CLOCKS}, the clamp of one level at one pixel per clock) on "
        "every level whose keypoints fit in a frame's clocks, with the engine's busy share, "
        f"then the engines K {PER_CELL} on every level would need."
    )
    out.append("")
    body = []
    for fps in (PLAN["fps"], PLAN["fps_context"]):
        for (name, _), cells in zip(cfgs, totals, strict=True):
            row = [name, str(fps), num(cells)]
            for f, _ in clk:
                frame = f * 1e6 / fps
                k = min(PER_CELL, int(frame // (ORB_KEYPOINT_CLOCKS * cells)))
                full = math.ceil(PER_CELL * ORB_KEYPOINT_CLOCKS * cells / frame)
                fit = (
                    f"K {k} ({100 * k * ORB_KEYPOINT_CLOCKS * cells / frame:.0f} %)"
                    if k
                    else f"K 1: {math.ceil(ORB_KEYPOINT_CLOCKS * cells / frame)} engines"
                )
                row.append(f"{fit}; K {PER_CELL}: {full} engine{'s' * (full > 1)}")
            body.append(row)
    header = ["size", "frames/s", "keypoints at K 1"]
    return [*out, *table(header + [mhz(f) for f, _ in clk], body), ""]


TABLE_KEYS = ("line", "nms", "budget", "queue", "blurred", "plain", "resizer", "row", "moments")


def memory_lines(cfgs: list[tuple[str, list[Level]]], summary: list[dict]) -> list[str]:
    name0, lv0 = cfgs[0]
    g = lv0[0].orb
    out = ["### Pyramid plan: memory per level", ""]
    out.append(
        f"Each memory a level needs, as the RTL sizes it for a MAX_WIDTH of the level's "
        f"width W (ORB's formulas from the ORB memory table, MAX_WIDTH = W, CELL {CELL}), "
        f"K = {PER_CELL}, S = {SCORE_BITS}; those with no RTL (—) are the plans' memories. "
        f"Bits and BRAM18 at level 0 of {name0} (X = {g.x_bits}, Y = {g.y_bits}), "
        "or at level 1 for those of levels 1 to 7. BRAM18: the xc7 RAMB18s (simple dual "
        "port, 16384 × 1 to 512 × 36 bits) the shape needs."
    )
    out.append("")
    body = []
    for m in MEMORIES:
        at = lv0[0] if m.shape(lv0[0]) else lv0[1]
        bits, bram = cost(m, at)
        shape = orb_memory.shape_text(m.shape(at)) + (f" (level {at.k})" if at.k else "")
        body.append([m.name, m.rtl, m.formula, shape, num(bits), str(bram)])
    header = ["memory", "in the RTL", "formula", "memories × words × bits", "bits", "BRAM18"]
    out += [*table(header, body), ""]
    out.append(
        "BRAM18 of each memory per level; the totals of today's blocks (the first seven); "
        "beside them the row option (b) adds and the moments window, which would replace "
        "the unblurred rows."
    )
    out.append("")
    keys = PLANS["all on chip"]
    for name, lv in cfgs:
        body = []
        for x in lv:
            bram = {k: cost(BY_KEY[k], x)[1] for k in TABLE_KEYS}
            bits = sum(cost(BY_KEY[k], x)[0] for k in keys)
            body.append(
                [str(x.k), f"{x.width}x{x.height}", *(str(bram[k]) for k in TABLE_KEYS[:7])]
                + [num(bits), f"**{sum(bram[k] for k in keys)}**"]
                + [str(bram["row"]), str(bram["moments"])]
            )
        bits, bram = plan_cost(keys, lv)
        body.append(["**all**", "", *[""] * 7, f"**{num(bits)}**", f"**{bram}**"])
        body[-1] += [str(plan_cost(("row",), lv)[1]), str(plan_cost(("moments",), lv)[1])]
        header = ["level", name, "line buffer", "NMS", "budget", "queue", "blurred rows"]
        header += ["unblurred rows", "resizer", "bits", "BRAM18", "(b) row", "moments window"]
        out += [*table(header, body), ""]
    return out


def total_lines(cfgs: list[tuple[str, list[Level]]], summary: list[dict]) -> list[str]:
    most = XC7Z020["bram18"]
    out = ["### Pyramid plan: memory totals and DDR", ""]
    out.append(
        f"BRAM18 of all levels against the xc7z020's {most}, with the memories there once "
        "(the top's corner FIFO, a record with its angle and descriptor, and the ORB "
        "engine's patch copies in block RAM), for (a); option (b) adds its rows. Rows "
        "in DDR: each level's image is written there by an AXI4 master (as a video DMA "
        "does) and the ORB engine reads its keypoints' patches back."
    )
    out.append("")
    body = []
    for name, lv in cfgs:
        fifo = once(lv)[1]
        row = [name, str(fifo)]
        for keys in PLANS.values():
            bram = plan_cost(keys, lv)[1] + fifo
            verdict = "fits" if bram <= most else "does not fit"
            row.append(f"{bram} ({100 * bram / most:.0f} %): {verdict}")
        body.append([*row, str(plan_cost(("row",), lv)[1])])
    out += [*table(["size", "once", *PLANS, "(b) adds"], body), ""]
    return out + ddr_lines(cfgs, summary)


def ddr_lines(cfgs: list[tuple[str, list[Level]]], summary: list[dict]) -> list[str]:
    """Per plan with rows in DDR: the levels written and the patches read, in MB/s, at
    K 1 on every level, and in words of the DDR port per clock."""
    fps, port = PLAN["fps"], PLAN["ddr_port_bits"] // 8
    f, what = clocks(summary)[-1]
    g = cfgs[0][1][0].orb
    patch = {i: orb_memory.INSTANCES[i].generics(g)["HEIGHT"] for i in DDR_ROWS["both rows in DDR"]}
    # A row of a patch at any byte offset, in whole words of the port.
    row_bytes = {i: -(-(h + port - 1) // port) * port for i, h in patch.items()}
    label = {"blurred rows": "blurred", "plain rows": "unblurred"}
    sizes = ", ".join(f"{label[i]} {h} rows of {row_bytes[i]} bytes" for i, h in patch.items())
    out = [
        f"The DDR traffic at {fps} frames/s: each image in DDR written once (a byte a pixel "
        f"of every level), each keypoint's patch read back in {8 * port}-bit words at any "
        f"offset ({sizes}), keypoints at K 1 on every level; then {8 * port}-bit words per "
        f"clock at {mhz(f)} ({what}).",
        "",
    ]
    body = []
    for name, lv in cfgs:
        keypoints = sum(x.cells for x in lv) * fps
        row = [name, num(keypoints)]
        for rows in DDR_ROWS.values():
            write = len(rows) * rates(lv, fps)[2]
            read = keypoints * sum(patch[i] * row_bytes[i] for i in rows) / 1e6
            words = (write + read) / port / f
            row += [f"{write:.0f} + {read:.0f} = {write + read:.0f}", f"{words:.2f}"]
        body.append(row)
    header = ["size", "keypoints/s at K 1"]
    for plan in DDR_ROWS:
        header += [f"{plan}: written + read (MB/s)", "words per clock"]
    return [*out, *table(header, body), ""]


def logic_lines(summary: list[dict]) -> list[str]:
    """The options' logic from the measured blocks (at 1920x1080), if any is measured."""
    n = PLAN["levels"]
    count = {"pipeline": (n, 2), "resizer": (n - 1, n - 1), "one": (1, 1)}
    found = [(spec, find(summary, spec)) for spec in PLAN["blocks"]]
    if not any(row for _, row in found):
        return []
    out = ["### Pyramid plan: logic of the options", ""]
    out.append(
        f"LUT (logic + SRL + LUT RAM) of the measured blocks, counted as each option has "
        f"them: (a) {n} pipelines, (b) 2; {n - 1} resizers; one ORB stage, its engine "
        "shared (each level's row buffers add their column multiplexers, not counted), "
        f"against the xc7z020's {num(XC7Z020['lut'])} LUT."
    )
    out.append("")
    body, totals = [], [0, 0]
    for spec, row in found:
        a, b = count[spec["count"]]
        if row is None:
            body.append([spec["name"], "not in this summary", "—", str(a), str(b)])
            continue
        luts = lut_total(row)
        totals = [totals[0] + a * luts, totals[1] + b * luts]
        body.append([spec["name"], f"`{row['config']}`", num(luts), str(a), str(b)])
    share = [f"**{num(t)}** ({100 * t / XC7Z020['lut']:.0f} %)" for t in totals]
    body.append(["**total**", "", "", *share])
    out += table(["block", "measured row", "LUT", "in (a)", "in (b)"], body)
    if any(row is None for _, row in found):
        out += ["", "The totals leave out the blocks not in this summary."]
    return [*out, ""]
