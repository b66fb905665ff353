"""The C library of sw/ as a user builds it: freestanding (no C library at all), its
header from C++, the Linux UIO example; and its unit tests (sw/tests/unit.c: the
register helpers against a fake register file, the decoder's argument errors)."""

from __future__ import annotations

import re
import subprocess
from pathlib import Path

from cbuild import CC, SW, WARNINGS, compile_c

ALLOWED_INCLUDES = {"<stdbool.h>", "<stddef.h>", "<stdint.h>", '"fastnms.h"', '"fastnms_regs.h"'}


def test_unit_tests_pass(c_programs):
    result = subprocess.run([c_programs["unit"]], capture_output=True, text=True, timeout=30)
    assert result.returncode == 0, result.stdout + result.stderr
    assert result.stdout.startswith("ok "), result.stdout


def test_library_is_freestanding(tmp_path: Path):
    """Only the freestanding headers, and an object that calls nothing outside itself
    (not even memcpy or memset), at -O2 and -Os."""
    for name in ("fastnms.c", "fastnms.h"):
        includes = set(re.findall(r"^#include\s+(\S+)", (SW / name).read_text(), re.M))
        assert includes <= ALLOWED_INCLUDES, f"{name}: {includes - ALLOWED_INCLUDES}"
    for opt in ("-O2", "-Os"):
        obj = tmp_path / f"fastnms{opt}.o"
        compile_c([SW / "fastnms.c"], obj, ["-c", opt, "-ffreestanding", "-fno-builtin"])
        undefined = subprocess.run(["nm", "-u", obj], capture_output=True, text=True, check=True)
        assert undefined.stdout.split() == [], f"{opt}: calls {undefined.stdout.split()}"


def test_header_compiles_as_cpp(tmp_path: Path):
    src = tmp_path / "use.cpp"
    src.write_text('#include "fastnms.h"\nint main() { return fastnms_strerror(0)[0] != 0; }\n')
    cmd = ["g++", "-std=c++11", "-Wall", "-Wextra", "-Werror", "-pedantic", f"-I{SW}"]
    result = subprocess.run([*cmd, "-fsyntax-only", str(src)], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr


def test_uio_example_compiles(tmp_path: Path):
    """Compiled and linked (never run: it needs the hardware)."""
    cmd = [CC, *WARNINGS, f"-I{SW}", str(SW / "examples" / "uio_example.c"), str(SW / "fastnms.c")]
    result = subprocess.run([*cmd, "-o", str(tmp_path / "uio")], capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
