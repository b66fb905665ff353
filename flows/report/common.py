"""What every section of docs/results.md uses: number and table formatting,
the LUT total, a row's ECP5 result, the provenance line, and targets (one
target evaluated is a dict: id, target, on, measured, met, margin)."""

from __future__ import annotations

import json
import subprocess
from pathlib import Path

from flows.report.reference import TARGETS, limit

REPO = Path(__file__).resolve().parents[2]

# ---- provenance -------------------------------------------------------------------


def source_state() -> dict:
    """The commit the figures come from and whether rtl/ differed from it."""

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


def nums(values: list[float | int]) -> str:
    return ", ".join(num(v) for v in values)


def table(header: list[str], rows: list[list[str]]) -> list[str]:
    lines = ["| " + " | ".join(header) + " |", "|" + "---|" * len(header)]
    lines += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return lines


def minutes(seconds: float) -> str:
    m, s = divmod(round(seconds), 60)
    return f"{m} min {s:02d} s" if m else f"{s} s"


# ---- summary rows -------------------------------------------------------------------


def by_config(summary: list[dict]) -> dict[str, dict]:
    return {row["config"]: row for row in summary}


def unique(summary: list[dict]) -> list[dict]:
    """The rows of distinct syntheses (entity and generics): one per synthesis run."""
    seen, out = set(), []
    for r in summary:
        key = (r["entity"], json.dumps(r["generics"], sort_keys=True))
        if key not in seen:
            seen.add(key)
            out.append(r)
    return out


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


# ---- targets ----------------------------------------------------------------------


def target_text(key: str, value: float | None = None) -> str:
    """The row text of target `key` (reference.toml), with its limit (or `value`)
    and its goal if it has one."""
    t = TARGETS[key]
    lim = limit(key) if value is None else value
    fields = {**t, "limit": num(lim) if isinstance(lim, int) else lim}
    if "goal" in t:
        fields["goal"] = num(t["goal"]) if isinstance(t["goal"], int) else t["goal"]
    return t["text"].format(**fields)


def goal_note(key: str, reached: bool, unit: str) -> str:
    """For a target met that has a goal: whether the goal is reached too ("" without a goal)."""
    goal = TARGETS[key].get("goal")
    if goal is None:
        return ""
    text = num(goal) if isinstance(goal, int) else str(goal)
    return f"; goal {text} {unit}: {'reached' if reached else 'not yet'}"


def margin(value: int, lim: int, unit: str, strict: bool = False) -> str:
    """How far `value` is from `lim` (at most `lim`, or below it if strict)."""
    if value == lim and not strict:
        return "at the limit"
    if value < lim:
        return f"{lim - value} {unit} under ({100 * (lim - value) / lim:.0f} %)"
    if value == lim:
        return f"equal: 1 {unit} over"
    return f"{value - lim} {unit} over ({100 * (value - lim) / lim:.0f} %)"


def at_most(key: str, value: int, unit: str, on: str) -> dict:
    """Target `key` (a limit, `strict` for "below") evaluated on `value`."""
    t, lim = TARGETS[key], limit(key)
    strict = t.get("strict", False)
    met = value < lim if strict else value <= lim
    goal = t.get("goal")
    return {
        "id": key,
        "target": target_text(key),
        "on": on,
        "measured": f"{num(value)} {unit}",
        "met": met,
        "margin": margin(value, lim, unit, strict)
        + (goal_note(key, value <= goal, unit) if met and goal is not None else ""),
    }


def verdict(met: bool | None, missed: str = "missed") -> str:
    """**met**, **missed** (or the target's own word for a miss), **not measured**."""
    if met is None:
        return "**not measured**"
    return "**met**" if met else f"**{missed}**"


def why_missed(key: str) -> str | None:
    """The sentence that says why target `key` is missed, if one is known."""
    t = TARGETS[key]
    return TARGETS[t.get("same_reason_as", key)].get("why_missed")


def target_lines(targets: list[dict]) -> list[str]:
    """The targets' table, then one line per reason for the targets missed (a
    reason shared by several targets once, with their names)."""
    rows = [
        [
            t["target"],
            t["on"],
            t["measured"],
            verdict(t["met"], TARGETS[t["id"]].get("miss", "missed")),
            t["margin"],
        ]
        for t in targets
    ]
    lines = table(["target", "on", "measured", "", "margin"], rows)
    reasons: dict[str, list[str]] = {}
    for t in targets:
        why = why_missed(t["id"])
        if t["met"] is not True and why and t["id"] not in reasons.setdefault(why, []):
            reasons[why].append(t["id"])
    reasons = {why: ids for why, ids in reasons.items() if ids}
    if reasons:
        lines += ["", "Why the misses:", ""]
        lines += [
            f"- {', '.join(f'*{i}*' for i in ids)}: {' '.join(why.split())}"
            for why, ids in reasons.items()
        ]
    return lines
