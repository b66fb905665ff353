"""The keypoint budget per grid cell against a direct implementation (a dictionary of cells,
each sorted by score then raster order), on generated maps and photographs, and where it sits
in the ORB pipeline (after the 31-pixel border, before the descriptors)."""

from __future__ import annotations

import functools
from pathlib import Path

import numpy as np
import pytest
from fastnms.golden import budget, orb
from fastnms.golden.image import load_grey
from fastnms.golden.model import NMS_MODES, detect
from fastnms.testing.images import real_images


def direct_budget(records: np.ndarray, cell: int, per_cell: int) -> np.ndarray:
    cells: dict[tuple[int, int], list[tuple[int, int, int]]] = {}
    for x, y, s in records.tolist():
        cells.setdefault((x // cell, y // cell), []).append((x, y, s))
    kept = []
    for members in cells.values():
        members.sort(key=lambda r: (-r[2], r[1], r[0]))  # best score, then raster order
        kept += members[:per_cell]
    kept.sort(key=lambda r: (r[1], r[0]))
    return np.array(kept, dtype=np.int64).reshape(-1, 3)


def random_records(rng: np.random.Generator, w: int, h: int, n: int, scores: int) -> np.ndarray:
    """n distinct positions in w x h, scores in 0..scores-1 (few values: many ties)."""
    flat = rng.choice(w * h, size=min(n, w * h), replace=False)
    s = rng.integers(0, scores, len(flat))
    return np.stack([flat % w, flat // w, s], axis=1).astype(np.int64)


@pytest.mark.parametrize("cell", budget.CELL_SIZES)
@pytest.mark.parametrize("per_cell", [1, 2, 7, 15])
def test_random_maps_equal_the_direct_budget(cell: int, per_cell: int, rng: np.random.Generator):
    for w, h, n, scores in [(600, 333, 4000, 3), (257, 513, 20000, 255), (31, 17, 50, 1)]:
        rec = random_records(rng, w, h, n, scores)
        want = direct_budget(rec, cell, per_cell)
        assert np.array_equal(budget.cell_budget(rec, cell, per_cell), want)
        shuffled = rec[rng.permutation(len(rec))]  # the region NMS's closing order
        assert np.array_equal(budget.cell_budget(shuffled, cell, per_cell), want)


def test_ties_go_to_raster_order():
    """One 16x16 cell full of equal scores keeps its first K pixels in raster order."""
    ys, xs = np.mgrid[0:16, 0:16]
    rec = np.stack([xs.ravel(), ys.ravel(), np.full(256, 9)], axis=1)
    kept = budget.cell_budget(rec, 16, 5)
    assert kept.tolist() == [[x, 0, 9] for x in range(5)]


def test_partial_and_empty_cells_and_small_counts():
    rec = np.array(
        [[3, 3, 5], [20, 3, 7], [21, 4, 7], [22, 5, 1], [100, 40, 2], [101, 41, 3]], np.int64
    )
    # Cells of 16: (0,0) one keypoint (K larger than its count), (1,0) three, (6,2) two;
    # every other cell empty; (6,2) also the last, partial cell of a 102x42 image.
    assert budget.cell_budget(rec, 16, 2).tolist() == [
        [3, 3, 5],
        [20, 3, 7],
        [21, 4, 7],
        [100, 40, 2],
        [101, 41, 3],
    ]
    assert budget.cell_budget(rec, 16, 1).tolist() == [[3, 3, 5], [20, 3, 7], [101, 41, 3]]
    assert budget.cell_budget(rec[:0], 16, 1).shape == (0, 3)


def test_per_cell_zero_keeps_everything():
    rec = np.array([[5, 9, 1], [4, 2, 3], [6, 2, 3]], np.int64)
    assert budget.cell_budget(rec, None, 0).tolist() == [[4, 2, 3], [6, 2, 3], [5, 9, 1]]


@pytest.mark.parametrize(
    ("cell", "per_cell"),
    [(8, 1), (48, 1), (512, 1), (None, 1), (16.0, 1), (True, 1), (16, 16), (16, -1), (16, 1.5)],
)
def test_bad_budgets(cell, per_cell):
    with pytest.raises(ValueError, match="cell"):
        budget.cell_budget(np.zeros((0, 3), np.int64), cell, per_cell)


@functools.lru_cache(maxsize=2)
def _grey(path: Path) -> np.ndarray:
    return load_grey(path)


@pytest.mark.parametrize("nms", NMS_MODES)
def test_photographs(nms: str):
    for path in real_images()[:2]:
        rec = detect(_grey(path), 20, "opencv", nms)
        for cell, per_cell in [(16, 1), (32, 4), (64, 15), (256, 15)]:
            want = direct_budget(rec, cell, per_cell)
            got = budget.cell_budget(rec, cell, per_cell)
            assert np.array_equal(got, want), f"{path.name} {nms} {cell} {per_cell}"
            cells = (-(-_grey(path).shape[0] // cell)) * (-(-_grey(path).shape[1] // cell))
            assert len(got) <= per_cell * cells


def test_orb_applies_the_budget_after_the_border():
    """A strong keypoint 30 pixels from the left border is dropped by the border first, so
    it does not take the cell's one place from the weaker one inside."""
    img = np.full((96, 96), 100, np.uint8)
    img[40, 30] = 0  # strong (all 16 circle pixels 100 brighter)
    img[60, 31] = 60  # weaker, inside the border, same 32x32 cell (0, 1)
    assert len(detect(img, 20)) == 2
    f = orb.orb_features(img, 20, cell=32, per_cell=1)
    assert f.records[:, :2].tolist() == [[31, 60]]
    kps, des = orb.detect_and_compute(img, 20, cell=32, per_cell=1)
    assert [k.pt for k in kps] == [(31.0, 60.0)] and des.shape == (1, 32)
    plain, _ = orb.detect_and_compute(img, 20, orb=False, cell=32, per_cell=1)
    assert [k.pt for k in plain] == [(30.0, 40.0)]  # without ORB no border: the strong one
