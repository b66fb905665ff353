"""Compiling the C of sw/ in its tests: the strictest warnings as errors and, where
this machine supports them, AddressSanitizer and UndefinedBehaviorSanitizer (a
finding aborts the program). $CC picks the compiler (default gcc)."""

from __future__ import annotations

import os
import subprocess
from pathlib import Path

SW = Path(__file__).resolve().parents[1]
TESTS = SW / "tests"
CC = os.environ.get("CC", "gcc")
WARNINGS = [
    "-std=c99",
    "-pedantic",
    "-Wall",
    "-Wextra",
    "-Werror",
    "-Wshadow",
    "-Wconversion",
    "-Wstrict-prototypes",
    "-Wmissing-prototypes",
]
SANITIZERS = ["-fsanitize=address,undefined", "-fno-sanitize-recover=all"]


def compile_c(sources: list[Path], out: Path, flags: list[str]) -> None:
    cmd = [CC, *WARNINGS, *flags, f"-I{SW}", *map(str, sources), "-o", str(out)]
    result = subprocess.run(cmd, capture_output=True, text=True)
    assert result.returncode == 0, f"{' '.join(cmd)}\n{result.stderr}"


def sanitizers_work(where: Path) -> bool:
    probe = where / "probe.c"
    probe.write_text("int main(void) { return 0; }\n")
    cmd = [CC, *SANITIZERS, str(probe), "-o", str(where / "probe")]
    built = subprocess.run(cmd, capture_output=True).returncode == 0
    return built and subprocess.run([str(where / "probe")], capture_output=True).returncode == 0


def build_programs(where: Path) -> dict[str, Path]:
    """The test programs decode_records and unit, built with sw/fastnms.c in `where`."""
    flags = ["-g", "-O1"] + (SANITIZERS if sanitizers_work(where) else [])
    programs = {}
    for name in ("decode_records", "unit"):
        programs[name] = where / name
        compile_c([SW / "fastnms.c", TESTS / f"{name}.c"], programs[name], flags)
    return programs
