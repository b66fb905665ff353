"""pytest entry: the NMS blocks under GHDL against the golden model."""

import pytest
from harness import run_cocotb


@pytest.mark.parametrize("score_bits", [8, 12])
@pytest.mark.parametrize(("idle", "stall"), [(0.0, 0.0), (0.3, 0.3)], ids=str)
def test_nms_3x3(request, score_bits, idle, stall):
    generics = {"MAX_WIDTH": 24, "MAX_HEIGHT": 64, "SCORE_BITS": score_bits}
    run_cocotb(
        "fastnms_nms_3x3",
        "nms3x3_tb",
        generics,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )


@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize(("idle", "stall"), [(0.0, 0.0), (0.3, 0.5)], ids=str)
def test_nms_region(request, connectivity, idle, stall):
    generics = {"MAX_WIDTH": 32, "MAX_HEIGHT": 64, "SCORE_BITS": 8, "CONNECTIVITY": connectivity}
    run_cocotb(
        "fastnms_nms_region",
        "region_tb",
        generics,
        testcase="shapes,random_maps,empty_and_reset,throughput,idle_output",
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )
