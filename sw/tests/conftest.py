"""The C test programs of sw/, built once per session (sw/tests/cbuild.py)."""

from __future__ import annotations

from pathlib import Path

import pytest
from cbuild import build_programs


@pytest.fixture(scope="session")
def c_programs(tmp_path_factory: pytest.TempPathFactory) -> dict[str, Path]:
    """The test programs decode_records and unit, built with sw/fastnms.c."""
    return build_programs(tmp_path_factory.mktemp("sw"))
