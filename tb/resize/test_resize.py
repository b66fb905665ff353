"""pytest entry: fastnms_resize under GHDL (tb/resize/resize_tb.py)."""

import pytest

from tb.harness import cocotb_tests, run_cocotb


@pytest.mark.parametrize("case", cocotb_tests("resize_tb"))
def test_resize(request, case):
    run_cocotb(
        "fastnms_resize",
        "resize_tb",
        {"MAX_WIDTH": 80, "MAX_HEIGHT": 48},
        testcase=case,
        name=request.node.nodeid,
    )
