"""Several pixels per clock: the rows `make synth` adds at 3840x2160 for PPC 1, 2
and 4, beside AMD at 1 and 8 pixels per clock, and their targets (PPC 4
against PPC 1; the clock 3840x2160 at 60 frames/s needs)."""

from __future__ import annotations

import statistics

from flows.report.common import lut_text, lut_total, num, table, target_lines, target_text
from flows.report.reference import AMD, AMD_8PPC, UHD60_MHZ, UHD60_MPIXELS, limit

HEADER = [
    "configuration",
    "PPC",
    "LUT",
    "LUT per pixel lane",
    "FF",
    "BRAM18 equiv.",
    "logic levels",
    "Fmax",
    "Mpixel/s",
]


def ppc_lines(summary: list[dict]) -> list[str]:
    """The PPC table, its targets and the tops' ECP5 critical paths."""
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
        f"{UHD60_MHZ:.1f} MHz at PPC 4."
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
    order = sorted(rows, key=lambda r: (r["entity"] != "fastnms_axi", r["ppc"]))
    body = [ppc_row(r) for r in order]
    for ref in (AMD, AMD_8PPC):
        ppc, lut, fmax = ref["pixels_per_clock"], ref["lut"], ref["fmax_mhz"]
        body.append(
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
    out += table(HEADER, body)
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


def ppc_row(r: dict) -> list[str]:
    fmax = r.get("ecp5_fmax_mhz")
    spread = r.get("ecp5_seed_fmax_mhz")
    fmax_text = "—" if fmax is None else f"{fmax:.0f} MHz"
    if fmax is not None and spread:
        fmax_text += f" ({min(spread.values()):.0f}–{max(spread.values()):.0f})"
    return [
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


def ppc_targets(rows: list[dict]) -> list[dict]:
    """Per entity, PPC 4 against PPC 1: LUT and BRAM ratios; for placed rows the
    Fmax drop and the 3840x2160-at-60 clock."""
    out = []
    for entity in ("fastnms_axi", "fastnms_core"):
        by_ppc = {r["ppc"]: r for r in rows if r["entity"] == entity}
        one, four = by_ppc.get(1), by_ppc.get(4)
        if not one or not four:
            continue
        name = f"`{entity}` PPC 4 vs 1"
        lut_ratio = lut_total(four) / lut_total(one)
        most = limit("ppc4-lut-ratio")
        out.append(
            {
                "id": "ppc4-lut-ratio",
                "target": target_text("ppc4-lut-ratio"),
                "on": name,
                "measured": f"{lut_total(four)} / {lut_total(one)} = {lut_ratio:.3f}x",
                "met": lut_ratio <= most,
                "margin": f"{most - lut_ratio:+.3f}x",
            }
        )
        bram_ratio = four["bram18_equiv"] / max(1, one["bram18_equiv"])
        most = limit("ppc4-bram-ratio")
        out.append(
            {
                "id": "ppc4-bram-ratio",
                "target": target_text("ppc4-bram-ratio"),
                "on": name,
                "measured": f"{four['bram18_equiv']} / {one['bram18_equiv']} BRAM18 "
                f"= {bram_ratio:.2f}x",
                "met": bram_ratio <= most,
                "margin": f"{most - bram_ratio:+.2f}x",
            }
        )
        if one.get("ecp5_fmax_mhz") and four.get("ecp5_fmax_mhz"):
            out += fmax_targets(name, one, four)
    return out


def seed_fmax(row: dict) -> list[float]:
    """A row's Fmax over its placement seeds (its one Fmax when it has no seeds)."""
    return list((row.get("ecp5_seed_fmax_mhz") or {1: row["ecp5_fmax_mhz"]}).values())


def fmax_targets(name: str, one: dict, four: dict) -> list[dict]:
    """Over the placement seeds: the median for the drop, the worst seed for the
    frame rate."""
    s1, s4 = seed_fmax(one), seed_fmax(four)
    m1, m4 = statistics.median(s1), statistics.median(s4)
    drop = limit("ppc4-fmax-drop")
    how = f"median of {len(s4)} seeds: " if len(s4) > 1 else ""
    worst = min(s4)
    lowest = f"lowest of {len(s4)} seeds: " if len(s4) > 1 else ""
    return [
        {
            "id": "ppc4-fmax-drop",
            "target": target_text("ppc4-fmax-drop"),
            "on": name,
            "measured": f"{how}{m4:.0f} vs {m1:.0f} MHz ({m4 / m1 - 1:+.0%})",
            "met": m4 >= (1 - drop) * m1,
            "margin": f"{m4 - (1 - drop) * m1:+.0f} MHz",
        },
        {
            "id": "uhd60-fmax",
            "target": target_text("uhd60-fmax"),
            "on": f"`{four['config']}`",
            "measured": f"{lowest}{worst:.0f} MHz (ECP5-8)",
            "met": worst >= UHD60_MHZ,
            "margin": f"{worst - UHD60_MHZ:+.1f} MHz ({worst / UHD60_MHZ - 1:+.0%})",
        },
    ]
