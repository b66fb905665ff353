"""pytest entry: fastnms_core (detector + NMS) on generated images and
photographs, against the golden model and, for opencv + 3x3, OpenCV."""

import json

import pytest
import testimages
from harness import run_cocotb

SMALL = {"MAX_WIDTH": 24, "MAX_HEIGHT": 32}
PHOTO = {"MAX_WIDTH": 320, "MAX_HEIGHT": 240}
CROP_SIZES = [(128, 96), (160, 120), (200, 150), (320, 240), (176, 144), (256, 192)]


def crops(thresholds: list[int]) -> list[list]:
    images = testimages.real_images()
    assert len(images) >= 6, images
    picked = images[:: max(1, len(images) // 6)][:6]
    return [
        [str(path), w, h, thresholds[i % len(thresholds)]]
        for i, (path, (w, h)) in enumerate(zip(picked, CROP_SIZES, strict=True))
    ]


@pytest.mark.parametrize(("score", "nms"), [("opencv", "3x3"), ("sad", "3x3")])
def test_core_generated(request, score, nms):
    run_cocotb(
        "fastnms_core",
        "core_tb",
        {**SMALL, "SCORE": score, "NMS": nms},
        testcase="generated_images",
        name=request.node.nodeid,
        env={"TB_IDLE": "0.2", "TB_STALL": "0.3"},
    )


@pytest.mark.parametrize(("score", "nms"), [("opencv", "3x3"), ("sad", "3x3")])
def test_core_photos(request, score, nms):
    run_cocotb(
        "fastnms_core",
        "core_tb",
        {**PHOTO, "SCORE": score, "NMS": nms},
        testcase="real_images",
        name=request.node.nodeid,
        env={"TB_IDLE": "0.05", "TB_STALL": "0.2", "TB_CROPS": json.dumps(crops([20, 10, 40]))},
    )
