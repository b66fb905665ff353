"""The layout rules of rtl/ (the developers' guide): one entity per file, named as
the file, and no file longer than 800 lines (past that a block wants splitting)."""

from __future__ import annotations

import re

import pytest
from fastnms.sim.sources import REPO, tracked_rtl_files

MAX_LINES = 800
_ENTITY = re.compile(r"^\s*entity\s+(\w+)\s+is\b", re.IGNORECASE | re.MULTILINE)

FILES = tracked_rtl_files()


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
