"""The VHDL files of rtl/ and their compile order: the one list that the testbenches,
the simulation driver and the flows compile, and the constraints against which the
file lists other tools keep (fastnms.core, the Vivado scripts) are checked."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

REPO = Path(__file__).resolve().parents[1]
RTL = REPO / "rtl"
# The areas of rtl/, building blocks first.
RTL_AREAS = ["common", "fast", "nms", "budget", "orb", "resize", "core", "top"]

_DEFINES = re.compile(r"^\s*(?:entity|package)\s+(\w+)\s+is\b", re.IGNORECASE | re.MULTILINE)
_USES = re.compile(r"\b(?:entity|use)\s+work\.(\w+)", re.IGNORECASE)


def _code(path: Path) -> str:
    return re.sub(r"--[^\n]*", "", path.read_text()).lower()


def defined_units(path: Path) -> set[str]:
    """Entities and packages declared in a file (not package bodies)."""
    return set(_DEFINES.findall(_code(path)))


def used_units(path: Path) -> set[str]:
    """Units of library work a file needs first: packages it uses, entities it
    instantiates."""
    return set(_USES.findall(_code(path))) - defined_units(path)


def all_rtl_files() -> list[Path]:
    """Every .vhd file under rtl/, at any depth."""
    return sorted(RTL.rglob("*.vhd"))


def tracked_files(pathspec: str, fallback: list[Path]) -> list[Path]:
    """The files git tracks that match `pathspec` (existing ones, sorted): the project's
    files, without those someone is still writing. `fallback` when this is not a git
    checkout."""
    try:
        out = subprocess.run(
            ["git", "ls-files", "-z", "--", pathspec],
            cwd=REPO,
            capture_output=True,
            check=True,
            text=True,
        ).stdout
    except (OSError, subprocess.CalledProcessError):
        return fallback
    return sorted(f for f in (REPO / name for name in out.split("\0") if name) if f.exists())


def tracked_rtl_files() -> list[Path]:
    """The .vhd files under rtl/ that git tracks; every file under rtl/ when this is not
    a git checkout."""
    return tracked_files("rtl/*.vhd", all_rtl_files())


def order_problems(files: list[Path]) -> list[str]:
    """Why `files` cannot be analysed in this order: a unit of work used before
    the file that defines it, or defined by none of them. Empty when the order
    is good."""
    defined_at: dict[str, int] = {}
    for i, f in enumerate(files):
        for unit in defined_units(f):
            defined_at.setdefault(unit, i)
    problems = []
    for i, f in enumerate(files):
        for unit in sorted(used_units(f)):
            if unit not in defined_at:
                problems.append(f"{f.relative_to(REPO)} uses work.{unit}, defined in none of them")
            elif defined_at[unit] > i:
                where = files[defined_at[unit]].relative_to(REPO)
                problems.append(f"{f.relative_to(REPO)} uses work.{unit} before {where}")
    return problems


def compile_order(files: list[Path]) -> list[Path]:
    """`files` in a valid compile order: each after the files it needs, otherwise
    in the given order."""
    defined_in = {unit: f for f in files for unit in defined_units(f)}
    ordered: list[Path] = []
    pending = list(files)
    while pending:
        done = set(ordered)
        ready = [
            f
            for f in pending
            if {defined_in[u] for u in used_units(f) if u in defined_in} - {f} <= done
        ]
        assert ready, f"circular dependency among {[str(f) for f in pending]}"
        ordered += ready
        pending = [f for f in pending if f not in ready]
    return ordered


def rtl_sources() -> list[Path]:
    """Every VHDL file of the core in a valid compile order: area by area (common,
    fast, nms, core, top), each file after the units it needs."""
    areas = [d.name for d in RTL.iterdir() if d.is_dir()]
    unknown = sorted(set(areas) - set(RTL_AREAS))
    assert not unknown, f"rtl/ folders missing from RTL_AREAS: {unknown}"
    files = [f for area in RTL_AREAS for f in sorted((RTL / area).rglob("*.vhd"))]
    return compile_order(files)
