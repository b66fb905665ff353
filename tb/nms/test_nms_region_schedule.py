"""pytest entry: fastnms_nms_region_schedule alone under GHDL (through a wrapper
with flat ports, tb/nms/vhdl/) against a model of its contract
(tb/nms/region_schedule_tb.py): small builds (MAX_WIDTH 16 and an odd 13, so
that rows wrap, frames change width and flushes overlap often) and a wide one
(1920) with short and full-width rows."""

from pathlib import Path

import pytest

from tb.harness import cocotb_tests, run_cocotb

# The part with flat ports (GHDL's VPI does not show record ports).
FLAT = Path(__file__).with_name("vhdl") / "fastnms_nms_region_schedule_flat.vhd"


@pytest.mark.parametrize(
    ("generics", "env"),
    [
        ({"MAX_WIDTH": 16, "MAX_HEIGHT": 15}, {"TB_FRAMES": "400", "TB_TALLEST": "15"}),
        ({"MAX_WIDTH": 13, "MAX_HEIGHT": 5}, {"TB_FRAMES": "200", "TB_TALLEST": "5"}),
        (
            {"MAX_WIDTH": 1920, "MAX_HEIGHT": 1080},
            {"TB_FRAMES": "40", "TB_TALLEST": "3", "TB_WIDE": "40", "TB_RESETS": "2"},
        ),
    ],
    ids=["w16", "w13", "w1920"],
)
@pytest.mark.parametrize("case", cocotb_tests("region_schedule_tb"))
def test_nms_region_schedule(request, generics, env, case):
    run_cocotb(
        "fastnms_nms_region_schedule_flat",
        "region_schedule_tb",
        generics,
        testcase=case,
        name=request.node.nodeid,
        extra_sources=(FLAT,),
        env=env,
    )
