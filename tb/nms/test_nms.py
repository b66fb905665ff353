"""pytest entry: the NMS blocks under GHDL against the golden model."""

import json

import pytest
from fastnms.testing import images as testimages

from tb.harness import cocotb_tests, run_cocotb

NMS3X3_CASES = cocotb_tests("nms3x3_tb")
REGION_CASES = [
    "shapes",
    "area_saturates",
    "random_maps",
    "random_sequences",
    "empty_and_reset",
    "never_stalls",
    "size_changes",
    "output_backpressure",
    "idle_output",
]


@pytest.mark.parametrize("case", NMS3X3_CASES)
@pytest.mark.parametrize("score_bits", [8, 12])
@pytest.mark.parametrize(("idle", "stall"), [(0.0, 0.0), (0.3, 0.3)], ids=str)
def test_nms_3x3(request, score_bits, idle, stall, case):
    """With 12-bit scores the block is built with ROW_MARKS (as the core with a budget)."""
    generics = {"MAX_WIDTH": 24, "MAX_HEIGHT": 64, "SCORE_BITS": score_bits}
    if score_bits == 12:
        generics["ROW_MARKS"] = True
    run_cocotb(
        "fastnms_nms_3x3",
        "nms3x3_tb",
        generics,
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )


@pytest.mark.parametrize(
    "generics",
    [
        {"MAX_WIDTH": 24, "SCORE_BITS": 8, "PPC": 2, "READ_LATENCY": 2},
        {"MAX_WIDTH": 64, "SCORE_BITS": 12, "PPC": 4, "READ_LATENCY": 1, "ROW_MARKS": True},
    ],
    ids=["ppc2", "ppc4"],
)
@pytest.mark.parametrize(("idle", "stall"), [(0.0, 0.0), (0.3, 0.3)], ids=str)
@pytest.mark.parametrize("case", NMS3X3_CASES)
def test_nms_3x3_ppc(request, generics, idle, stall, case):
    """Beats of 2 and 4 scores: random maps, plateaus, and the densest map
    through the serializer without an input wait (PPC 4 with ROW_MARKS)."""
    run_cocotb(
        "fastnms_nms_3x3",
        "nms3x3_tb",
        {**generics, "MAX_HEIGHT": 64},
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )


@pytest.mark.parametrize("case", REGION_CASES)
@pytest.mark.parametrize("connectivity", [4, 8])
@pytest.mark.parametrize(("idle", "stall"), [(0.0, 0.0), (0.3, 0.5)], ids=str)
def test_nms_region(request, connectivity, idle, stall, case):
    generics = {"MAX_WIDTH": 33, "MAX_HEIGHT": 64, "SCORE_BITS": 8, "CONNECTIVITY": connectivity}
    run_cocotb(
        "fastnms_nms_region",
        "region_tb",
        generics,
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )


@pytest.mark.parametrize("case", ["area_merges_saturated", "area_saturates"])
@pytest.mark.parametrize("connectivity", [4, 8])
def test_nms_region_area_saturation(request, connectivity, case):
    """Areas past AREA_MAX merging as either operand (a build large enough for them)."""
    generics = {"MAX_WIDTH": 64, "MAX_HEIGHT": 80, "SCORE_BITS": 8, "CONNECTIVITY": connectivity}
    run_cocotb(
        "fastnms_nms_region",
        "region_tb",
        generics,
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": "0.1", "TB_STALL": "0.2"},
    )


def _gravel() -> str:
    """The CC0 gravel photograph (512x512): in ../shared/images or scikit-image's wheel."""
    images = testimages.real_images()
    return str(next((p for p in images if "gravel" in p.name), images[0]))


@pytest.mark.parametrize("connectivity", [pytest.param(c, marks=pytest.mark.slow) for c in (4, 8)])
def test_nms_region_photo(request, connectivity):
    """A whole photograph's FAST output (gravel 512x512, t = 20, sad): records
    equal to the golden, and at most 1.01 clocks per pixel (the flush pass
    is 1/512 of it)."""
    generics = {"MAX_WIDTH": 512, "MAX_HEIGHT": 512, "SCORE_BITS": 12, "CONNECTIVITY": connectivity}
    run_cocotb(
        "fastnms_nms_region",
        "region_tb",
        generics,
        testcase="photo_maps",
        name=request.node.nodeid,
        env={
            "TB_PHOTOS": json.dumps([[_gravel(), 20, "sad"]]),
            "TB_MAX_CLOCKS_PER_PIXEL": "1.01",
        },
    )


@pytest.mark.slow
@pytest.mark.parametrize("connectivity", [4, 8])
def test_nms_region_all_photos(request, connectivity):
    """Every real photograph at thresholds 10 and 20 (sad) at MAX_WIDTH 1920:
    records equal to the golden; clocks per pixel logged."""
    photos = [[str(p), t, "sad"] for p in testimages.real_images() for t in (10, 20)]
    generics = {
        "MAX_WIDTH": 1920,
        "MAX_HEIGHT": 1080,
        "SCORE_BITS": 12,
        "CONNECTIVITY": connectivity,
    }
    run_cocotb(
        "fastnms_nms_region",
        "region_tb",
        generics,
        testcase="photo_maps",
        name=request.node.nodeid,
        env={"TB_PHOTOS": json.dumps(photos)},
    )
