"""pytest entry: fastnms_record_output under GHDL, without and with the ORB payload
(record format 2) or the region NMS's area, at the smallest FIFO and one that is not a
power of two. Each cocotb test of tb/top/record_output_tb.py is a pytest item of its
own, `<configuration>-<cocotb test>`."""

import pytest

from tb.harness import run_cocotb

CASES = [
    pytest.param(
        {"X_BITS": 7, "Y_BITS": 6, "SCORE_BITS": 12, "FIFO_DEPTH": 8, "DESCRIPTOR": "none"},
        id="none-fifo8",
    ),
    pytest.param(
        {"X_BITS": 11, "Y_BITS": 11, "SCORE_BITS": 8, "FIFO_DEPTH": 13, "DESCRIPTOR": "orb"},
        id="orb-fifo13",
    ),
    pytest.param(
        {
            "X_BITS": 11,
            "Y_BITS": 11,
            "SCORE_BITS": 12,
            "FIFO_DEPTH": 8,
            "DESCRIPTOR": "none",
            "AREA": True,
        },
        id="area-fifo8",
    ),
]


TESTS = ["hold", "orb_drops", "live", "abort"]


@pytest.mark.parametrize(
    ("generics", "testcase"),
    [pytest.param(*c.values, t, id=f"{c.id}-{t}") for c in CASES for t in TESTS],
)
def test_record_output(request, generics, testcase):
    run_cocotb(
        "fastnms_record_output",
        "record_output_tb",
        generics,
        testcase=testcase,
        name=request.node.nodeid,
    )
