"""pytest entry: fastnms_window under GHDL for several generic sets and pause patterns."""

import pytest

from tb.harness import cocotb_tests, run_cocotb

CASES = cocotb_tests("window_tb")

SMALL = {"MAX_WIDTH": 24, "MAX_HEIGHT": 20, "WINDOW": 7, "DATA_WIDTH": 8, "READ_LATENCY": 1}
ODD_LAT2 = {"MAX_WIDTH": 37, "MAX_HEIGHT": 4095, "WINDOW": 7, "DATA_WIDTH": 8, "READ_LATENCY": 2}
WINDOW3 = {"MAX_WIDTH": 16, "MAX_HEIGHT": 16, "WINDOW": 3, "DATA_WIDTH": 9, "READ_LATENCY": 1}


@pytest.mark.parametrize(
    ("idle", "stall"), [(0.0, 0.0), (0.3, 0.0), (0.0, 0.3), (0.4, 0.4)], ids=str
)
@pytest.mark.parametrize("case", CASES)
def test_window_small(request, idle, stall, case):
    run_cocotb(
        "fastnms_window",
        "window_tb",
        SMALL,
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )


@pytest.mark.parametrize("generics", [ODD_LAT2, WINDOW3], ids=["w37_lat2", "win3"])
@pytest.mark.parametrize("case", CASES)
def test_window_generics(request, generics, case):
    run_cocotb(
        "fastnms_window",
        "window_tb",
        generics,
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": "0.3", "TB_STALL": "0.3"},
    )


# Several pixels per beat: 7x7 (detector) and 3x3 (NMS) windows, narrow and
# odd-sized maxima, both read latencies.
PPC_SETS = {
    "ppc2_w7": {
        "MAX_WIDTH": 24,
        "MAX_HEIGHT": 20,
        "WINDOW": 7,
        "DATA_WIDTH": 8,
        "READ_LATENCY": 1,
        "PPC": 2,
    },
    "ppc4_w7": {
        "MAX_WIDTH": 28,
        "MAX_HEIGHT": 20,
        "WINDOW": 7,
        "DATA_WIDTH": 8,
        "READ_LATENCY": 2,
        "PPC": 4,
    },
    "ppc2_w3": {
        "MAX_WIDTH": 16,
        "MAX_HEIGHT": 16,
        "WINDOW": 3,
        "DATA_WIDTH": 9,
        "READ_LATENCY": 2,
        "PPC": 2,
    },
    "ppc4_w3": {
        "MAX_WIDTH": 16,
        "MAX_HEIGHT": 16,
        "WINDOW": 3,
        "DATA_WIDTH": 9,
        "READ_LATENCY": 1,
        "PPC": 4,
    },
}


@pytest.mark.parametrize("name", sorted(PPC_SETS))
@pytest.mark.parametrize(("idle", "stall"), [(0.0, 0.0), (0.3, 0.3)], ids=str)
@pytest.mark.parametrize("case", CASES)
def test_window_ppc(request, name, idle, stall, case):
    run_cocotb(
        "fastnms_window",
        "window_tb",
        PPC_SETS[name],
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )
