"""pytest entry: fastnms_core (detector + NMS) on generated images and
photographs, against the golden model and, for opencv + 3x3, OpenCV."""

import json

import pytest
from fastnms.testing import images as testimages

from tb.harness import run_cocotb

SMALL = {"MAX_WIDTH": 24, "MAX_HEIGHT": 32}
PHOTO = {"MAX_WIDTH": 320, "MAX_HEIGHT": 240}


CONFIGS = [
    ("opencv", "3x3"),
    ("sad", "3x3"),
    ("opencv", "none"),
    ("sad", "region4"),
    ("opencv", "region8"),
    ("sad", "region8"),
    ("opencv", "region4"),
]


@pytest.mark.parametrize("case", ["generated_images", "malformed_then_good", "region_filter"])
@pytest.mark.parametrize(("score", "nms"), CONFIGS)
def test_core_generated(request, score, nms, case):
    run_cocotb(
        "fastnms_core",
        "core_tb",
        {**SMALL, "SCORE": score, "NMS": nms},
        testcase=case,
        name=request.node.nodeid,
        env={"TB_IDLE": "0.2", "TB_STALL": "0.3"},
    )


# The smallest photograph crop in `make test` for one configuration per NMS and
# score (whole photographs go through the top with the fast engine there:
# sim/tests/test_engines.py), all six crops of every configuration in
# `make test-full`.
QUICK_PHOTO_CONFIGS = {
    ("opencv", "3x3"),
    ("opencv", "none"),
    ("sad", "region4"),
    ("opencv", "region8"),
}
PHOTO_CASES = [
    pytest.param(
        s, n, c, marks=[] if c == 1 and (s, n) in QUICK_PHOTO_CONFIGS else [pytest.mark.slow]
    )
    for s, n in CONFIGS
    for c in (1, 6)
]


@pytest.mark.parametrize(("score", "nms", "crops"), PHOTO_CASES)
def test_core_photos(request, score, nms, crops):
    run_cocotb(
        "fastnms_core",
        "core_tb",
        {**PHOTO, "SCORE": score, "NMS": nms},
        testcase="real_images",
        name=request.node.nodeid,
        env={
            "TB_IDLE": "0.05",
            "TB_STALL": "0.2",
            "TB_CROPS": json.dumps(testimages.photo_crops([20, 10, 40])[:crops]),
        },
    )


# Three cases in `make test`, all six in `make test-full`.
PPC_CONFIGS = [
    pytest.param("opencv", "3x3", 2, marks=pytest.mark.slow),
    ("opencv", "3x3", 4),
    ("sad", "none", 2),
    pytest.param("sad", "none", 4, marks=pytest.mark.slow),
    pytest.param("sad", "3x3", 2, marks=pytest.mark.slow),
    pytest.param("sad", "3x3", 4, marks=pytest.mark.slow),
]


@pytest.mark.parametrize("case", ["generated_images", "malformed_then_good", "real_images"])
@pytest.mark.parametrize(("score", "nms", "ppc"), PPC_CONFIGS)
def test_core_ppc(request, score, nms, ppc, case):
    """Detector + 3x3 NMS or none with 2 and 4 pixels per beat: generated
    images (noise at threshold 0 among them), malformed frames (widths that
    are not whole beats among them), and photograph crops, against the golden
    model and cv2.FAST."""
    generics = {"MAX_WIDTH": 320, "MAX_HEIGHT": 240, "READ_LATENCY": 2 if ppc == 2 else 1}
    run_cocotb(
        "fastnms_core",
        "core_tb",
        {**generics, "SCORE": score, "NMS": nms, "PPC": ppc},
        testcase=case,
        name=request.node.nodeid,
        env={
            "TB_IDLE": "0.1",
            "TB_STALL": "0.2",
            "TB_CROPS": json.dumps(testimages.photo_crops([20, 10, 40])[:2]),
        },
    )


ORB_GENERICS = {"MAX_WIDTH": 128, "MAX_HEIGHT": 96, "MAX_PER_CELL": 15, "DESCRIPTOR": "orb"}


@pytest.mark.parametrize(
    ("generics", "frames"),
    [
        pytest.param({}, "noise,narrow", id="cell16", marks=pytest.mark.slow),
        pytest.param({}, "photo,flat,noise", id="photo", marks=pytest.mark.slow),
        pytest.param(
            {"ORB_MAX_CELL": 32, "NMS": "none", "SCORE": "sad"},
            "cell32,cell256,off,off_noise,photo",
            id="cell32",
            marks=pytest.mark.slow,
        ),
    ],
)
def test_core_orb(request, generics, frames):
    """DESCRIPTOR "orb": whole frames back to back, each with its CELL and K, every
    keypoint's record, angle bits and descriptor equal to orb.orb_features."""
    run_cocotb(
        "fastnms_core",
        "core_orb_tb",
        {**ORB_GENERICS, **generics},
        testcase="equals_the_model",
        name=request.node.nodeid,
        env={"TB_IDLE": "0.1", "TB_STALL": "0.2", "TB_FRAMES": frames},
    )


@pytest.mark.slow
def test_core_orb_bad_input(request):
    """DESCRIPTOR "orb": a frame cut short and a reset while keypoints are in ORB, each
    followed by an exact frame; noise at t = 0 with K = 15 (the input held)."""
    run_cocotb(
        "fastnms_core",
        "core_orb_tb",
        ORB_GENERICS,
        testcase="bad_input_then_exact",
        name=request.node.nodeid,
        env={"TB_IDLE": "0.1", "TB_STALL": "0.2"},
    )
