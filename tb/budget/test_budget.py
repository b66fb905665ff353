"""pytest entry: the keypoint budget under GHDL against the golden model."""

import pytest

from tb.harness import cocotb_tests, run_cocotb

K15 = {"MAX_WIDTH": 64, "MAX_HEIGHT": 48, "SCORE_BITS": 8, "MAX_PER_CELL": 15}
K4 = {"MAX_WIDTH": 40, "MAX_HEIGHT": 40, "SCORE_BITS": 12, "MAX_PER_CELL": 4}
# Without memory the block is its output skid buffer: one timing is enough.
K0 = {"MAX_WIDTH": 24, "MAX_HEIGHT": 24, "SCORE_BITS": 8, "MAX_PER_CELL": 0}


@pytest.mark.parametrize(
    ("generics", "idle", "stall"),
    [(K15, 0.0, 0.0), (K15, 0.3, 0.5), (K4, 0.0, 0.0), (K4, 0.3, 0.5), (K0, 0.0, 0.0)],
    ids=["k15", "k15-idle-stall", "k4", "k4-idle-stall", "k0"],
)
@pytest.mark.parametrize("case", cocotb_tests("budget_tb"))
def test_cell_budget(request, generics, idle, stall, case):
    run_cocotb(
        "fastnms_cell_budget",
        "budget_tb",
        generics,
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )
