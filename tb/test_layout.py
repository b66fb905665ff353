"""The layout rules of the repository (the developers' guide): in rtl/, one entity
per file, named as the file; and no source file, VHDL or Python, longer than 800
lines (past that a block or a module wants splitting)."""

from __future__ import annotations

import re

import pytest
from fastnms.sim.sources import REPO, tracked_files, tracked_rtl_files

MAX_LINES = 800
_ENTITY = re.compile(r"^\s*entity\s+(\w+)\s+is\b", re.IGNORECASE | re.MULTILINE)

FILES = tracked_rtl_files()


def tracked_python_files() -> list:
    """The .py files git tracks (every .py file outside .venv and build when this is not
    a git checkout)."""
    skip = {".venv", "build", "sim_build"}
    every = [f for f in REPO.rglob("*.py") if not skip & set(f.relative_to(REPO).parts)]
    return tracked_files("*.py", sorted(every))


def line_count(path) -> int:
    return path.read_text().count("\n")


@pytest.mark.parametrize("path", FILES, ids=[str(f.relative_to(REPO)) for f in FILES])
def test_rtl_file_layout(path):
    text = path.read_text()
    lines = text.count("\n")
    assert lines <= MAX_LINES, f"{path.name}: {lines} lines (at most {MAX_LINES}): split it"
    code = re.sub(r"--[^\n]*", "", text)
    entities = _ENTITY.findall(code)
    if path.stem.endswith("_pkg"):
        assert not entities, f"{path.name}: a package file declares {entities}"
    else:
        assert [e.lower() for e in entities] == [path.stem], f"{path.name}: entities {entities}"


def test_python_files_are_short():
    """Every tracked Python file: at most MAX_LINES lines."""
    files = tracked_python_files()
    assert len(files) > 50, f"only {len(files)} Python files found: the listing is broken"
    long = {str(f.relative_to(REPO)): n for f in files if (n := line_count(f)) > MAX_LINES}
    assert not long, f"Python files over {MAX_LINES} lines (split them): {long}"
