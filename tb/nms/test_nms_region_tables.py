"""pytest entry: fastnms_nms_region_tables alone under GHDL (through a wrapper
with flat ports, tb/nms/vhdl/) against a model of its contract
(tb/nms/region_tables_tb.py): small tables (MAX_WIDTH 16 and an odd 13, so
that slots alias and rows wrap often) and the full width (1920)."""

from pathlib import Path

import pytest

from tb.harness import run_cocotb

# The part with flat ports (GHDL's VPI does not show record ports).
FLAT = Path(__file__).with_name("vhdl") / "fastnms_nms_region_tables_flat.vhd"


@pytest.mark.parametrize(
    ("generics", "steps"),
    [
        ({"MAX_WIDTH": 16, "MAX_HEIGHT": 15, "SCORE_BITS": 8}, 20000),
        ({"MAX_WIDTH": 13, "MAX_HEIGHT": 15, "SCORE_BITS": 8}, 12000),
        ({"MAX_WIDTH": 1920, "MAX_HEIGHT": 1080, "SCORE_BITS": 12}, 20000),
    ],
    ids=["w16", "w13", "w1920"],
)
def test_nms_region_tables(request, generics, steps):
    run_cocotb(
        "fastnms_nms_region_tables_flat",
        "region_tables_tb",
        generics,
        name=request.node.nodeid,
        extra_sources=(FLAT,),
        env={"TB_STEPS": str(steps)},
    )
