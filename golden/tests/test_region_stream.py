"""The streaming region-NMS algorithm planned for the RTL (fastnms.region_stream) gives
exactly the golden's records on every shape the region NMS is tested with, on random maps
and on FAST output of real photographs; and its label and stall bounds."""

from __future__ import annotations

import numpy as np
import pytest
from fastnms.fast import fast_maps
from fastnms.image import load_grey
from fastnms.nms import nms_region
from fastnms.region_stream import region_nms_stream
from regions import SHAPES, grid, serpentine, square_spiral


def assert_stream_equals_golden(corner: np.ndarray, score: np.ndarray, msg: str = "") -> None:
    for connectivity in (4, 8):
        got, stats = region_nms_stream(corner, score, connectivity)
        want = nms_region(corner, score, connectivity)
        assert np.array_equal(got, want), f"{msg} connectivity {connectivity}"
        assert stats.max_labels <= corner.shape[1] // 2 + 2, (msg, stats.max_labels)


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_stream_shapes(name: str):
    corner, score = grid(SHAPES[name][0])
    assert_stream_equals_golden(corner, score, name)


@pytest.mark.parametrize("shape", ["serpentine", "spiral", "comb", "checkerboard", "full"])
def test_stream_large_shapes(shape: str, rng: np.random.Generator, seed):
    if shape == "serpentine":
        corner = serpentine(61, 47)
    elif shape == "spiral":
        corner = square_spiral(51)
    elif shape == "comb":
        corner = np.zeros((30, 99), dtype=bool)
        corner[:, ::2] = True
        corner[-1] = True
    elif shape == "checkerboard":  # W/2 regions open at once under 4-connectivity
        yy, xx = np.mgrid[:20, :40]
        corner = (yy + xx) % 2 == 0
    else:
        corner = np.ones((15, 30), dtype=bool)
    score = np.where(corner, rng.integers(0, 4, corner.shape), 0).astype(np.int32)
    assert_stream_equals_golden(corner, score, f"{shape} seed {seed}")


def test_stream_random_maps(rng: np.random.Generator, seed):
    for density in (0.1, 0.3, 0.5, 0.6, 0.8):
        for _ in range(4):
            h, w = rng.integers(1, 30, 2)
            corner = rng.random((h, w)) < density
            score = np.where(corner, rng.integers(0, 4, corner.shape), 0).astype(np.int32)
            assert_stream_equals_golden(corner, score, f"density {density} seed {seed}")


def test_stream_on_fast_output(shared_or_bundled_photo: np.ndarray):
    """FAST corners of a real photograph: equal to the golden; on such images merges
    never need more than one extra clock in a hundred pixels."""
    img = shared_or_bundled_photo[:160, :240]
    for threshold in (10, 20):
        corner, score = fast_maps(img, threshold, "sad")
        assert_stream_equals_golden(corner, score, f"photo t={threshold}")
        _, stats = region_nms_stream(corner, score, 8)
        assert stats.merge_stall_clocks <= img.size // 100, stats


@pytest.fixture
def shared_or_bundled_photo() -> np.ndarray:
    import os

    import skimage.data

    return load_grey(os.path.join(os.path.dirname(skimage.data.__file__), "gravel.png"))
