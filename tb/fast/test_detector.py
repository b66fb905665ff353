"""pytest entry: fastnms_fast_detector under GHDL, both scores, against the golden."""

import json

import pytest
from fastnms.testing import images as testimages

from tb.harness import run_cocotb

SMALL = {"MAX_WIDTH": 24, "MAX_HEIGHT": 32, "READ_LATENCY": 1}
PHOTO = {"MAX_WIDTH": 320, "MAX_HEIGHT": 4095, "READ_LATENCY": 2}


GENERATED = ["generated_images", "throughput"]


@pytest.mark.parametrize("case", GENERATED)
@pytest.mark.parametrize("score", ["opencv", "sad"])
@pytest.mark.parametrize(("idle", "stall"), [(0.0, 0.0), (0.3, 0.3)], ids=str)
def test_detector_generated(request, score, idle, stall, case):
    run_cocotb(
        "fastnms_fast_detector",
        "detector_tb",
        {**SMALL, "SCORE": score},
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": str(idle), "TB_STALL": str(stall)},
    )


@pytest.mark.parametrize("case", GENERATED)
@pytest.mark.parametrize("score", ["opencv", "sad"])
def test_detector_pixels(request, score, case):
    """PIXELS (ORB's images): every pixel and its blur, with the scores, on generated
    frames and one photograph crop, and the clock count with the score waiting for the blur."""
    run_cocotb(
        "fastnms_fast_detector",
        "detector_tb",
        {**SMALL, "MAX_WIDTH": 48, "SCORE": score, "PIXELS": True},
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": "0.2", "TB_STALL": "0.2"},
    )


@pytest.mark.parametrize("case", GENERATED)
@pytest.mark.parametrize("ppc", [2, 4])
@pytest.mark.parametrize("score", ["opencv", "sad"])
def test_detector_ppc(request, score, ppc, case):
    """Beats of 2 and 4 pixels: generated images with idles and back-pressure,
    and the clock count of back-to-back frames."""
    generics = {"MAX_WIDTH": 24, "MAX_HEIGHT": 32, "READ_LATENCY": 2 if ppc == 4 else 1}
    run_cocotb(
        "fastnms_fast_detector",
        "detector_tb",
        {**generics, "SCORE": score, "PPC": ppc},
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": "0.2", "TB_STALL": "0.2"},
    )


# Both in make test-full; make test has photographs at PPC 4 through the core
# (tb/core/test_core.py::test_core_ppc).
@pytest.mark.parametrize("ppc", [pytest.param(p, marks=pytest.mark.slow) for p in (2, 4)])
def test_detector_ppc_photos(request, ppc):
    """Photograph crops with 2 and 4 pixels per beat."""
    cases = testimages.photo_crops([10, 20, 50])[:3]
    cases = [[p, w // ppc * ppc, h, t] for p, w, h, t in cases]
    run_cocotb(
        "fastnms_fast_detector",
        "detector_tb",
        {**PHOTO, "SCORE": "opencv", "PPC": ppc},
        testcase="real_images",
        name=request.node.nodeid,
        env={"TB_IDLE": "0.1", "TB_STALL": "0.1", "TB_CROPS": json.dumps(cases)},
    )


@pytest.mark.parametrize("crops", [1, pytest.param(6, marks=pytest.mark.slow)])
@pytest.mark.parametrize("score", ["opencv", "sad"])
def test_detector_photos(request, score, crops):
    """The smallest photograph crop in `make test`, all six in `make test-full`."""
    cases = testimages.photo_crops([10, 20, 50])[:crops]
    run_cocotb(
        "fastnms_fast_detector",
        "detector_tb",
        {**PHOTO, "SCORE": score},
        testcase="real_images",
        name=request.node.nodeid,
        env={"TB_IDLE": "0.1", "TB_STALL": "0.1", "TB_CROPS": json.dumps(cases)},
    )


@pytest.mark.slow
@pytest.mark.parametrize("score", ["opencv", "sad"])
def test_detector_full_kitti_frame(request, score):
    """A whole 1241x376 KITTI frame at MAX_WIDTH 1920 (needs ../shared/images)."""
    kitti = [p for p in testimages.shared_images() if "kitti" in p.name and "1241x376" in p.name]
    if not kitti:
        pytest.skip("no 1241x376 KITTI frame in ../shared/images")
    cases = [[str(kitti[0]), 1241, 376, 20]]
    run_cocotb(
        "fastnms_fast_detector",
        "detector_tb",
        {"MAX_WIDTH": 1920, "SCORE": score},
        testcase="real_images",
        name=request.node.nodeid,
        env={"TB_IDLE": "0.05", "TB_STALL": "0.05", "TB_CROPS": json.dumps(cases)},
    )
