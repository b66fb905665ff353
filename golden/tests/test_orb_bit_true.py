"""The hardware's path through ORB: the bit-true integer models (float32.py, trig.py) chained
as the RTL will chain them give the golden's angles, cos/sin and pattern points, bit for bit,
on photographs and on noise at threshold 0 (every keypoint position)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from fastnms.golden import float32, orb, trig
from fastnms.golden.image import load_grey
from fastnms.testing.images import bundled_images, shared_images


def _bits(x: np.ndarray) -> np.ndarray:
    return np.asarray(x, np.float32).view(np.uint32)


def test_constants_agree():
    assert _bits(orb.DEG_TO_RAD) == float32.DEG_TO_RAD
    p = (orb.ATAN_P1, orb.ATAN_P3, orb.ATAN_P5, orb.ATAN_P7)
    q = (float32.ATAN2_P1, float32.ATAN2_P3, float32.ATAN2_P5, float32.ATAN2_P7)
    assert [int(_bits(c)) for c in p] == list(q)


def assert_bit_true_chain(img: np.ndarray, threshold: int, context: str) -> int:
    f = orb.orb_features(img, threshold)
    xs, ys = f.records[:, 0], f.records[:, 1]
    m01, m10 = orb.moments(img, xs, ys)
    angle = float32.fast_atan2(m01, m10)
    assert np.array_equal(angle, _bits(f.angles)), f"{context}: angles"
    radians = float32.to_radians(angle)
    assert np.array_equal(radians, _bits(f.angles * orb.DEG_TO_RAD)), f"{context}: radians"
    cos, sin = trig.cos_sin(radians)
    a, b = orb.cos_sin(f.angles)
    assert np.array_equal(cos, _bits(a)) and np.array_equal(sin, _bits(b)), f"{context}: cos/sin"
    ix, iy = float32.rotate(orb.PATTERN[:, 0], orb.PATTERN[:, 1], cos[:, None], sin[:, None])
    gx, gy = orb.sample_offsets(a, b)
    assert np.array_equal(ix, gx) and np.array_equal(iy, gy), f"{context}: pattern points"
    return len(xs)


def photographs() -> list[Path]:
    return (shared_images() or bundled_images())[:4]


@pytest.mark.parametrize("path", photographs(), ids=lambda p: p.name)
def test_bit_true_chain_on_photographs(path: Path):
    assert assert_bit_true_chain(load_grey(path), 20, path.name) > 0


def test_bit_true_chain_on_noise(rng: np.random.Generator):
    """Threshold 0 on noise: thousands of keypoints, angles all around the circle."""
    img = rng.integers(0, 256, (160, 200), dtype=np.uint8)
    assert assert_bit_true_chain(img, 0, "noise") > 1000
