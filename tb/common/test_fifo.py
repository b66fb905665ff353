"""pytest entry: fastnms_fifo under GHDL, a power-of-two DEPTH, one rounded up,
and the smallest RAM, each at a few almost-full levels (the region NMS's and
the record output's among them)."""

import pytest

from tb.harness import run_cocotb


@pytest.mark.parametrize(
    ("depth", "level"),
    [(16, 16), (16, 12), (13, 5), (1, 1), (8, 4), (512, 512), (512, 507)],
)
def test_fifo(request, depth, level):
    generics = {"DEPTH": depth, "WIDTH": 10, "ALMOST_FULL_LEVEL": level}
    run_cocotb("fastnms_fifo", "fifo_tb", generics, name=request.node.nodeid)
