"""The bench's ORB comparison on scikit-image's photographs (every set-up has them):
identical keypoints, angles and float-blur descriptors, the exact blur's differences
counted, and a golden that drifts from cv2.ORB stopping the bench."""

from __future__ import annotations

import numpy as np
import pytest
from fastnms.golden import orb
from fastnms.testing import images as testimages

from flows.bench import orb as orb_bench


def test_agreement_on_photographs():
    table = orb_bench.agreement_table(testimages.bundled_images()[:2], 20)
    assert table["keypoints"] > 0 and len(table["rows"]) == 2
    assert 0 <= table["differing"] <= table["keypoints"]
    assert table["bits"] >= table["differing"] and table["max_bits"] <= 256
    assert table["mean_bits"] == table["bits"] / table["keypoints"]


def test_a_drifting_golden_stops_the_bench(monkeypatch):
    real = orb.orb_features

    def one_angle_off(img, threshold):
        f = real(img, threshold)
        angles = f.angles.copy()
        angles[0] = np.nextafter(angles[0], np.float32(360))
        return f._replace(angles=angles)

    monkeypatch.setattr(orb, "orb_features", one_angle_off)
    with pytest.raises(orb_bench.OrbMismatch, match="angles differ"):
        orb_bench.agreement_table(testimages.bundled_images()[:1], 20)
