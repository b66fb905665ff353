"""pytest entry: fastnms_fifo under GHDL, a power-of-two DEPTH, one rounded up,
and the smallest RAM."""

import pytest

from tb.harness import run_cocotb


@pytest.mark.parametrize("depth", [16, 13, 1, 512])
def test_fifo(request, depth):
    run_cocotb("fastnms_fifo", "fifo_tb", {"DEPTH": depth, "WIDTH": 10}, name=request.node.nodeid)
