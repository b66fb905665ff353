"""pytest entry: fastnms_skid_buffer under GHDL, in both styles."""

import pytest

from tb.harness import run_cocotb


@pytest.mark.parametrize("ping_pong", [False, True])
def test_skid_buffer(request, ping_pong):
    run_cocotb(
        "fastnms_skid_buffer",
        "skid_buffer_tb",
        {"WIDTH": 10, "PING_PONG": ping_pong},
        name=request.node.nodeid,
    )
