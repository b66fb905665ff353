"""The matching of `make demo`'s ORB part (flows/demo/orb_match.py), on the golden model's
features (the RTL's equal them, tested elsewhere): a rotated textured image matches, a
wrong rotation does not, the PNG is written."""

from __future__ import annotations

import cv2
import numpy as np
from fastnms.golden import orb
from fastnms.testing import images as testimages

from flows.demo import orb_match


def features(img: np.ndarray) -> orb_match.Features:
    return orb.detect_and_compute(img, 20, cell=orb_match.CELL, per_cell=orb_match.PER_CELL)


def test_rotation_is_matched(tmp_path):
    img = testimages.crop(testimages.real_images()[0], 320, 240)
    out = tmp_path / "matches.png"
    lines = orb_match.run(img, out, 30.0, 20, features)
    rtl = orb_match.MatchResult
    assert cv2.imread(str(out)).shape == (240, 640, 3)
    assert any("correct" in line for line in lines)
    turned, m = orb_match.rotated(img, 30.0)
    result, matches, ok = orb_match.match(features(img), features(turned), m)
    assert isinstance(result, rtl) and result.matches == len(matches) == len(ok)
    assert result.matches > 20 and result.share > 0.5, result
    # The same matches judged against a rotation of 60 degrees are mostly wrong.
    _, m60 = orb_match.rotated(img, 60.0)
    wrong, _, _ = orb_match.match(features(img), features(turned), m60)
    assert wrong.share < 0.2, wrong
