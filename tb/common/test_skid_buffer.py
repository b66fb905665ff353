"""pytest entry: fastnms_skid_buffer under GHDL, in both styles."""

import pytest

from tb.harness import cocotb_tests, run_cocotb


@pytest.mark.parametrize("case", cocotb_tests("skid_buffer_tb"))
@pytest.mark.parametrize("ping_pong", [False, True])
def test_skid_buffer(request, ping_pong, case):
    run_cocotb(
        "fastnms_skid_buffer",
        "skid_buffer_tb",
        {"WIDTH": 10, "PING_PONG": ping_pong},
        testcase=case,
        name=request.node.nodeid,
    )
