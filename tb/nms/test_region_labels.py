"""pytest entry: fastnms_nms_region with the fewest labels its assertion allows
(LABELS = MAX_WIDTH / 2 + 3), on the worst shapes for labels (a MAX_WIDTH-wide
checkerboard, columns, combs, spirals): it runs to completion and every record
equals the golden's. One label fewer stalls the 4-connected checkerboard
forever (see the assertion in rtl/nms/fastnms_nms_region.vhd)."""

import pytest

from tb.harness import run_cocotb


@pytest.mark.parametrize("max_width", [32, 33])
@pytest.mark.parametrize("connectivity", [4, 8])
def test_nms_region_fewest_labels(request, max_width, connectivity):
    generics = {
        "MAX_WIDTH": max_width,
        "MAX_HEIGHT": 64,
        "SCORE_BITS": 8,
        "CONNECTIVITY": connectivity,
        "LABELS": max_width // 2 + 3,
    }
    run_cocotb(
        "fastnms_nms_region",
        "region_tb",
        generics,
        testcase="shapes,throughput",
        name=request.node.nodeid,
        env={"TB_IDLE": "0.2", "TB_STALL": "0.3"},
    )
