"""pytest entry: fastnms_resize under GHDL (tb/resize/resize_tb.py)."""

from pathlib import Path

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


# The chain of steps (sim/, flat ports for GHDL's VPI).
CHAIN = Path(__file__).resolve().parents[2] / "sim" / "fastnms_resize_chain.vhd"


@pytest.mark.parametrize(
    ("size", "frames"),
    [
        ("160x120", 2),
        pytest.param("640x480", 1, marks=pytest.mark.slow),
    ],
)
def test_resize_chain(request, size, frames):
    """cv2.ORB's 8 levels from a chain of 7 steps: every level exact, nothing held."""
    run_cocotb(
        "fastnms_resize_chain",
        "resize_chain_tb",
        {"LEVELS": 8, "MAX_WIDTH": int(size.split("x")[0]), "MAX_HEIGHT": int(size.split("x")[1])},
        name=request.node.nodeid,
        extra_sources=(CHAIN,),
        env={"TB_SIZE": size, "TB_FRAMES": str(frames)},
    )
