"""pytest entry: the ORB cos/sin unit (fastnms_orb_cos_sin) under GHDL against
golden/trig.py."""

import pytest

from tb.harness import run_cocotb


@pytest.mark.parametrize(
    "count", [500, pytest.param(100000, marks=pytest.mark.slow)], ids=["500", "100000"]
)
def test_orb_cos_sin(request, count):
    run_cocotb(
        "fastnms_orb_cos_sin",
        "cos_sin_tb",
        {},
        env={"TB_COUNT": str(count)},
        name=request.node.nodeid,
    )
