"""OpenCV's own ORB as the reference the golden ORB is checked against (its tests and
`make bench`): one level, FAST scores, cv2.ORB's default border and patch."""

from __future__ import annotations

import cv2
import numpy as np
from fastnms.golden import orb


def detector(threshold: int) -> cv2.ORB:
    return cv2.ORB_create(
        nfeatures=10**6,
        nlevels=1,
        edgeThreshold=orb.EDGE,
        patchSize=orb.PATCH_SIZE,
        scoreType=cv2.ORB_FAST_SCORE,
        fastThreshold=threshold,
    )


def features(img: np.ndarray, threshold: int) -> orb.OrbFeatures:
    """cv2.ORB's keypoints as the golden's OrbFeatures (x, y, response; float32 angles;
    descriptors, (0, 32) when there are none), sorted by y then x. Raises AssertionError
    when OpenCV gives a field the golden fixes otherwise (non-integer positions or
    responses, another size or octave)."""
    kps, des = detector(threshold).detectAndCompute(img, None)
    raw = np.array([(*k.pt, k.response) for k in kps], np.float64).reshape(-1, 3)
    records = raw.astype(np.int64)
    assert np.array_equal(records, raw), "OpenCV gave non-integer positions or responses"
    assert all(k.size == orb.PATCH_SIZE and k.octave == 0 for k in kps)
    angles = np.array([k.angle for k in kps], np.float32)
    des = np.zeros((0, orb.DESCRIPTOR_BYTES), np.uint8) if des is None else des
    order = np.lexsort((records[:, 0], records[:, 1]))
    return orb.OrbFeatures(records[order], angles[order], des[order])
