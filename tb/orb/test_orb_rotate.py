"""pytest entry: the rotated pattern (fastnms_orb_rotate) under GHDL against the golden
model, and its pattern table against golden/orb_pattern.py."""

import re

import pytest
from fastnms.golden.orb_pattern import BIT_PATTERN_31

from sim.sources import RTL
from tb.harness import run_cocotb


def test_pattern_package_is_the_golden_pattern():
    text = (RTL / "orb" / "fastnms_orb_pattern_pkg.vhd").read_text()
    body = text[text.index("ORB_PATTERN : orb_pattern_t") :]
    body = body[body.index("(") + 1 : body.index(");")]
    values = [int(v) for v in re.findall(r"-?\d+", body)]
    assert values == [v for bit in BIT_PATTERN_31 for v in bit]


@pytest.mark.parametrize(
    ("lanes", "count"),
    [
        (8, 100),
        pytest.param(16, 100, marks=pytest.mark.slow),
        pytest.param(1, 30, marks=pytest.mark.slow),
    ],
    ids=["lanes8", "lanes16", "lanes1"],
)
def test_orb_rotate(request, lanes, count):
    run_cocotb(
        "fastnms_orb_rotate",
        "rotate_tb",
        {"LANES": lanes},
        env={"TB_COUNT": str(count)},
        name=request.node.nodeid,
    )
