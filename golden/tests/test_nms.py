"""NMS variants: region NMS against scipy.ndimage.label and cv2.connectedComponents, hand-made
shapes with explicit expected records, and OpenCV's 3x3 rule on hand-made score maps."""

from __future__ import annotations

import cv2
import numpy as np
import pytest
from fastnms.golden.nms import AREA_MAX, nms_3x3, nms_none, nms_region
from fastnms.testing.regions import SHAPES, grid, records, serpentine, square_spiral
from scipy import ndimage

# ---- independent region references ------------------------------------------------------


def scipy_labels(corner: np.ndarray, connectivity: int) -> np.ndarray:
    structure = ndimage.generate_binary_structure(2, 1 if connectivity == 4 else 2)
    return ndimage.label(corner, structure=structure)[0]


def cv2_labels(corner: np.ndarray, connectivity: int) -> np.ndarray:
    return cv2.connectedComponents(corner.astype(np.uint8), connectivity=connectivity)[1]


def region_reference(corner: np.ndarray, score: np.ndarray, labels: np.ndarray) -> np.ndarray:
    """Per label: the highest score, the first pixel in raster order on ties; then the
    label's pixel count, saturated at AREA_MAX (x, y, score, area)."""
    ys, xs = np.nonzero(corner)  # raster order
    lab, sc = labels[ys, xs], score[ys, xs].astype(np.int64)
    order = np.lexsort((np.arange(ys.size), -sc, lab))
    head = np.ones(order.size, dtype=bool)
    head[1:] = lab[order][1:] != lab[order][:-1]
    pick = np.sort(order[head])
    area = np.minimum(np.bincount(labels.ravel())[lab[pick]], AREA_MAX)
    return np.stack([xs[pick], ys[pick], sc[pick], area], axis=1).astype(np.int64).reshape(-1, 4)


def assert_region_matches_references(corner, score, msg="", min_area=0):
    for connectivity in (4, 8):
        got = nms_region(corner, score, connectivity, min_area=min_area, with_area=True)
        ref_scipy = region_reference(corner, score, scipy_labels(corner, connectivity))
        ref_cv2 = region_reference(corner, score, cv2_labels(corner, connectivity))
        assert np.array_equal(ref_scipy, ref_cv2), "the two references disagree"
        ref = ref_scipy[ref_scipy[:, 3] >= min_area]
        assert got.dtype == np.int64 and got.shape[1] == 4
        assert np.array_equal(got, ref), f"region{connectivity} min_area {min_area} {msg}"
        plain = nms_region(corner, score, connectivity, min_area=min_area)
        assert np.array_equal(plain, ref[:, :3]), "without with_area: the same records"


def test_region_random_masks(rng: np.random.Generator, seed):
    for trial in range(300):
        h, w = (int(v) for v in rng.integers(1, 41, size=2))
        density = rng.uniform(0.05, 0.95)
        corner = rng.random((h, w)) < density
        top = 3 if trial % 2 else 1000  # scores 0..3 give many ties
        score = rng.integers(0, top + 1, (h, w)).astype(np.int32)
        if trial % 3 == 0:
            score[~corner] = 0  # as fast_maps produces; otherwise non-corner noise is ignored
        min_area = [0, 1, 2, 3, 5, 40][trial % 6]
        assert_region_matches_references(corner, score, f"trial {trial} seed {seed}", min_area)


@pytest.mark.parametrize("shape", ["serpentine", "spiral", "comb"])
def test_region_large_shapes(shape: str, rng: np.random.Generator, seed):
    if shape == "serpentine":
        corner = serpentine(161, 97)
    elif shape == "spiral":
        corner = square_spiral(151)
    else:  # teeth merging one by one into a spine: many merges in one row
        corner = np.zeros((60, 199), dtype=bool)
        corner[:, ::2] = True
        corner[-1] = True
    score = np.where(corner, rng.integers(0, 4, corner.shape), 0).astype(np.int32)
    assert_region_matches_references(corner, score, f"{shape} seed {seed}")
    assert len(nms_region(corner, score, 8)) == 1, "each shape is one connected set"
    assert len(nms_region(corner, score, 4)) == 1


def test_region_large_random(rng: np.random.Generator, seed):
    for density in (0.3, 0.55, 0.7):
        corner = rng.random((300, 400)) < density
        score = np.where(corner, rng.integers(0, 6, corner.shape), 0).astype(np.int32)
        assert_region_matches_references(corner, score, f"density {density} seed {seed}")


# ---- hand-made shapes --------------------------------------------------------------------


@pytest.mark.parametrize("name", sorted(SHAPES))
def test_region_shapes(name: str):
    text, expect4, expect8 = SHAPES[name]
    corner, score = grid(text)
    assert nms_region(corner, score, 4).tolist() == expect4
    assert nms_region(corner, score, 8).tolist() == expect8
    assert_region_matches_references(corner, score, name)


def test_region_checkerboard_whole_image():
    corner = np.indices((9, 12)).sum(axis=0) % 2 == 0
    score = np.where(corner, 7, 0).astype(np.int32)
    assert np.array_equal(nms_region(corner, score, 4), nms_none(corner, score))
    assert nms_region(corner, score, 8).tolist() == [[0, 0, 7]]


def test_region_full_image_single_record(rng: np.random.Generator, seed):
    corner = np.ones((17, 23), dtype=bool)
    score = rng.integers(0, 50, corner.shape).astype(np.int32)
    y, x = np.unravel_index(np.argmax(score), score.shape)  # first maximum, raster order
    expected = [[int(x), int(y), int(score[y, x])]]
    assert nms_region(corner, score, 4).tolist() == expected, f"seed {seed}"
    assert nms_region(corner, score, 8).tolist() == expected, f"seed {seed}"
    assert nms_region(corner, score, 8, with_area=True).tolist() == [expected[0] + [17 * 23]]
    assert nms_region(corner, score, 8, min_area=17 * 23).tolist() == expected
    assert nms_region(corner, score, 8, min_area=17 * 23 + 1).tolist() == []


def test_region_area_saturates():
    """An area above AREA_MAX reads AREA_MAX, and MIN_AREA = AREA_MAX keeps that region."""
    corner = np.zeros((50, 60), dtype=bool)
    corner[:45, :] = True  # 2700 pixels
    corner[47, 5:8] = True  # 3 pixels
    score = corner.astype(np.int32)
    got = nms_region(corner, score, 4, with_area=True).tolist()
    assert got == [[0, 0, 1, AREA_MAX], [5, 47, 1, 3]]
    assert nms_region(corner, score, 4, min_area=AREA_MAX).tolist() == [[0, 0, 1]]
    assert nms_region(corner, score, 4, min_area=4).tolist() == [[0, 0, 1]]
    assert nms_region(corner, score, 4, min_area=3).tolist() == [[0, 0, 1], [5, 47, 1]]


@pytest.mark.parametrize("bad", [-1, AREA_MAX + 1, 2.0, "3", True, None])
def test_region_min_area_out_of_range(bad):
    corner = np.ones((3, 3), dtype=bool)
    with pytest.raises(ValueError, match="min_area"):
        nms_region(corner, corner.astype(np.int32), 8, min_area=bad)


# ---- 3x3 (OpenCV's rule) ----------------------------------------------------------------


def nms_3x3_reference(corner: np.ndarray, score: np.ndarray) -> list[list[int]]:
    h, w = corner.shape
    out = []
    for y in range(h):
        for x in range(w):
            if not corner[y, x]:
                continue
            s = int(score[y, x])
            neighbours = [
                int(score[y + dy, x + dx]) if corner[y + dy, x + dx] else 0
                for dy in (-1, 0, 1)
                for dx in (-1, 0, 1)
                if (dy or dx) and 0 <= y + dy < h and 0 <= x + dx < w
            ]
            # Neighbours outside the image count as 0 too.
            if len(neighbours) < 8:
                neighbours.append(0)
            if all(s > n for n in neighbours):
                out.append([x, y, s])
    return out


THREE_BY_THREE = {
    "plateau_suppresses_itself": (
        """
        . . . . .
        . 4 4 . .
        . 4 4 . .
        . . . . 6
        . . . 6 .
        """,
        [],
    ),
    "strictly_greater_survives": (
        """
        5 4 . 2 2
        . . . . .
        1 . . . 3
        """,
        records((0, 0, 5), (0, 2, 1), (4, 2, 3)),
    ),
    "image_border_counts_as_zero": (
        """
        1 . 1
        . . .
        1 . 1
        """,
        records((0, 0, 1), (2, 0, 1), (0, 2, 1), (2, 2, 1)),
    ),
    "score_zero_never_survives": (
        """
        0 . .
        . . 0
        . . .
        """,
        [],
    ),
    "diagonal_neighbour_suppresses": (
        """
        . 7 . .
        . . 9 .
        . . . .
        """,
        records((2, 1, 9)),
    ),
}


@pytest.mark.parametrize("name", sorted(THREE_BY_THREE))
def test_3x3_shapes(name: str):
    text, expected = THREE_BY_THREE[name]
    corner, score = grid(text)
    assert nms_3x3(corner, score).tolist() == expected
    assert nms_3x3_reference(corner, score) == expected


def test_3x3_non_corner_neighbour_counts_as_zero():
    corner = np.array([[False, True, False]])
    score = np.array([[9, 5, 9]], dtype=np.int32)  # stray values off the corners
    assert nms_3x3(corner, score).tolist() == [[1, 0, 5]]


def test_3x3_random_maps(rng: np.random.Generator, seed):
    for trial in range(200):
        h, w = (int(v) for v in rng.integers(1, 16, size=2))
        corner = rng.random((h, w)) < rng.uniform(0.1, 0.9)
        score = rng.integers(0, 4 if trial % 2 else 300, (h, w)).astype(np.int32)
        expected = nms_3x3_reference(corner, score)
        assert nms_3x3(corner, score).tolist() == expected, f"trial {trial} seed {seed}"


def test_none_lists_every_corner():
    corner, score = grid(
        """
        3 . 0
        . 7 7
        """
    )
    assert nms_none(corner, score).tolist() == [[0, 0, 3], [2, 0, 0], [1, 1, 7], [2, 1, 7]]
    for fn in (nms_none, nms_3x3, lambda c, s: nms_region(c, s, 8)):
        out = fn(np.zeros((3, 4), bool), np.zeros((3, 4), np.int32))
        assert out.shape == (0, 3) and out.dtype == np.int64


@pytest.mark.parametrize(
    ("corner", "score", "connectivity", "match"),
    [
        (np.zeros((3, 3), bool), np.zeros((3, 4), np.int32), 4, "shape"),
        (np.zeros((3, 3), np.uint8), np.zeros((3, 3), np.int32), 4, "bool"),
        (np.zeros((3, 3), bool), np.zeros((3, 3), np.float64), 4, "integer"),
        (np.zeros(9, bool), np.zeros(9, np.int32), 4, "2-D"),
        (np.zeros((3, 3), bool), np.zeros((3, 3), np.int32), 6, "connectivity"),
    ],
)
def test_nms_rejects_bad_arguments(corner, score, connectivity, match):
    with pytest.raises(ValueError, match=match):
        nms_region(corner, score, connectivity)
    if match != "connectivity":
        for fn in (nms_none, nms_3x3):
            with pytest.raises(ValueError, match=match):
                fn(corner, score)
