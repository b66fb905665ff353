"""pytest entry: the keypoint budget under GHDL against the golden model."""

import pytest

from tb.harness import run_cocotb


@pytest.mark.parametrize(
    "generics",
    [
        {"MAX_WIDTH": 64, "MAX_HEIGHT": 48, "SCORE_BITS": 8, "MAX_PER_CELL": 15},
        {"MAX_WIDTH": 40, "MAX_HEIGHT": 40, "SCORE_BITS": 12, "MAX_PER_CELL": 4},
        {"MAX_WIDTH": 24, "MAX_HEIGHT": 24, "SCORE_BITS": 8, "MAX_PER_CELL": 0},
    ],
    ids=["k15", "k4", "k0"],
)
@pytest.mark.parametrize(("idle", "stall"), [(0.0, 0.0), (0.3, 0.5)], ids=str)
def test_cell_budget(request, generics, idle, stall):
    run_cocotb(
        "fastnms_cell_budget",
        "budget_tb",
        generics,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )
