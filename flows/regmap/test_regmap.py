"""The register map: the generated files are up to date with rtl/top/fastnms_regs.toml,
and the source is consistent."""

from __future__ import annotations

import shutil
import subprocess

import pytest
from fastnms.sim import regs

from flows.regmap import regmap


def test_generated_files_are_up_to_date():
    stale = regmap.stale()
    assert not stale, (
        f"out of date: {', '.join(map(str, stale))}; run `.venv/bin/python -m fastnms.regmap`"
    )


def test_python_constants_match_the_source():
    source = regmap.load()
    assert list(regs.REGISTERS) == [r.name for r in source.registers]
    for reg in source.registers:
        entry = regs.REGISTERS[reg.name]
        assert entry.offset == reg.offset
        for fld in reg.fields:
            assert entry.fields[fld.name] == (fld.lsb, fld.width, fld.access, fld.reset)


def test_reset_values_follow_the_generics():
    generics = {
        "MAX_WIDTH": 320,
        "MAX_HEIGHT": 240,
        "SCORE": "sad",
        "NMS": "none",
        "CORNER_FIFO_DEPTH": 64,
        "SCORE_VIDEO": True,
        "PPC": 1,
        "MAX_PER_CELL": 0,
        "DESCRIPTOR": "none",
    }
    assert regs.reset_value("ID", generics) == 0x46415354
    assert regs.reset_value("CTRL", generics) == 1
    assert regs.reset_value("THRESHOLD", generics) == 20
    assert regs.reset_value("WIDTH", generics) == 320
    assert regs.reset_value("MODE", generics) == 0x101  # PPC 1, NMS none, SCORE sad
    assert regs.reset_value("MAX_SIZE", generics) == 240 << 16 | 320
    assert regs.reset_value("BUILD", generics) == 1 << 16 | 64
    generics.update(SCORE="opencv", NMS="3x3", SCORE_VIDEO=False)
    assert regs.reset_value("MODE", generics) == 0x110
    assert regs.reset_value("BUILD", generics) == 64
    generics.update(PPC=4)
    assert regs.reset_value("MODE", generics) == 0x410  # PPC 4
    generics.update(MAX_PER_CELL=15)
    assert regs.reset_value("BUILD", generics) == 15 << 20 | 64
    assert regs.reset_value("BUDGET", generics) == 16 << 16  # CELL 16, PER_CELL 0
    generics.update(PPC=1, DESCRIPTOR="orb")
    assert regs.reset_value("MODE", generics) == 0x1110  # ORB, PPC 1


def test_docs_table_lists_every_field():
    table = regmap.markdown(regmap.load())
    for reg in regmap.load().registers:
        assert f"`{reg.name}`" in table
        for fld in reg.fields:
            assert f"`{fld.name}` | {fld.bits} | {fld.access}" in table


def test_c_header_compiles_and_agrees(tmp_path):
    """sw/fastnms_regs.h compiles as C99 without warnings, and its offsets,
    masks and record fields equal the Python constants."""
    compiler = shutil.which("cc") or shutil.which("gcc") or shutil.which("clang")
    if compiler is None:
        pytest.skip("no C compiler")
    checks = []
    for name, reg in regs.REGISTERS.items():
        checks.append((f"FASTNMS_{name}_OFFSET", reg.offset))
        for fname, fld in reg.fields.items():
            checks.append((f"FASTNMS_{name}_{fname}_MASK", fld.mask))
            checks.append((f"FASTNMS_{name}_{fname}_SHIFT", fld.lsb))
    for fname in ("X", "Y", "SCORE", "EMPTY", "LAST", "ABORTED"):
        fld = getattr(regs, f"REC_{fname}")
        checks.append((f"FASTNMS_REC_{fname}_MASK", fld.mask))
    source = tmp_path / "check.c"
    source.write_text(
        '#include "fastnms_regs.h"\n'
        + "".join(f"#if {macro} != {value}ull\n#error {macro}\n#endif\n" for macro, value in checks)
        + "int main(void) { return 0; }\n"
    )
    include = regmap.ROOT / "sw"
    proc = subprocess.run(
        [compiler, "-std=c99", "-Wall", "-Wextra", "-pedantic", "-Werror", f"-I{include}",
         "-fsyntax-only", str(source)],
        capture_output=True,
        text=True,
    )  # fmt: skip
    assert proc.returncode == 0, proc.stderr
