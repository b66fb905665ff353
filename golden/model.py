"""The complete golden model: FAST-9/16 segment test, a score, then one NMS variant."""

from __future__ import annotations

import numpy as np

from .fast import SCORE_MODES, fast_maps, validate_image, validate_score, validate_threshold
from .nms import nms_3x3, nms_none, nms_region, validate_min_area

SCORES: tuple[str, ...] = SCORE_MODES
NMS_MODES: tuple[str, ...] = ("none", "3x3", "region4", "region8")
DEFAULT_THRESHOLD = 20


def validate_nms(nms: object) -> str:
    if nms not in NMS_MODES:
        raise ValueError(f"nms must be one of {', '.join(NMS_MODES)}; got {nms!r}")
    return str(nms)


def detect(
    img: np.ndarray,
    threshold: int = DEFAULT_THRESHOLD,
    score: str = "opencv",
    nms: str = "3x3",
    min_area: int = 0,
    with_area: bool = False,
) -> np.ndarray:
    """Corners of a 2-D uint8 image as an int64 (N, 3) array of x, y, score sorted by y
    then x. With score="opencv", nms="3x3" this is cv2.FastFeatureDetector's output.

    min_area (region NMS only; 0 and 1 keep everything): drop the regions with fewer corner
    pixels. with_area: a fourth column, the record's AREA (the region's corner pixels,
    saturated at nms.AREA_MAX; 0 with the other NMS, which have no regions)."""
    # Validate everything up front so a bad nms is reported before any work is done.
    validate_image(img)
    validate_threshold(threshold)
    validate_score(score)
    validate_nms(nms)
    validate_min_area(min_area)
    region = nms.startswith("region")
    if min_area > 1 and not region:
        raise ValueError(f"min_area applies to the region NMS (region4, region8), not {nms!r}")
    corner, scores = fast_maps(img, threshold, score)
    if region:
        return nms_region(corner, scores, 4 if nms == "region4" else 8, min_area, with_area)
    records = nms_none(corner, scores) if nms == "none" else nms_3x3(corner, scores)
    if with_area:
        return np.column_stack([records, np.zeros(len(records), np.int64)])
    return records
