"""fastnms golden model: FAST-9/16 corners with non-maxima suppression, bit-exact with
OpenCV's cv::FAST (TYPE_9_16), plus the paper's SAD score and region NMS, and ORB features
(orientation and rotated BRIEF) of the keypoints, defined exactly as OpenCV computes them.

This package is the contract the RTL is checked against.
"""

from .budget import cell_budget
from .fast import CIRCLE_OFFSETS, fast_maps
from .image import ImageError, load_grey
from .model import NMS_MODES, SCORES, detect
from .nms import nms_3x3, nms_none, nms_region
from .orb import OrbFeatures, detect_and_compute, orb_features

__all__ = [
    "CIRCLE_OFFSETS",
    "NMS_MODES",
    "SCORES",
    "OrbFeatures",
    "ImageError",
    "cell_budget",
    "detect",
    "detect_and_compute",
    "fast_maps",
    "load_grey",
    "nms_3x3",
    "nms_none",
    "nms_region",
    "orb_features",
]
