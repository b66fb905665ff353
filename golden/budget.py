"""A keypoint budget per grid cell: at most K keypoints per CELL x CELL square, the ones with
the largest scores, so that keypoints spread over the image and a frame's count is bounded.

The definition (the contract the RTL will follow):
- cells are CELL x CELL squares from the image origin; the keypoint (x, y) is in cell
  (x // CELL, y // CELL); CELL is a power of two, 16 to 256; the last column and row of cells
  may be partial;
- in each cell the K keypoints with the largest score are kept (K 1 to 15); a tie goes to
  the keypoint first in raster order (smaller y, then smaller x); K = 0 turns the budget off
  (every keypoint passes);
- it applies to the NMS's output (any score, any NMS) and, for ORB, after the 31-pixel border
  filter and before the descriptors;
- the result is sorted by y then x.
"""

from __future__ import annotations

import numpy as np

CELL_SIZES: tuple[int, ...] = (16, 32, 64, 128, 256)
MAX_PER_CELL = 15


def validate_budget(cell: object, per_cell: object) -> tuple[int, int]:
    """(cell, per_cell) as ints, or ValueError. per_cell 0 (off) accepts any cell."""
    if isinstance(per_cell, bool) or not isinstance(per_cell, int | np.integer):
        raise ValueError(f"per_cell must be an integer in 0..{MAX_PER_CELL}, got {per_cell!r}")
    if not 0 <= per_cell <= MAX_PER_CELL:
        raise ValueError(f"per_cell must be an integer in 0..{MAX_PER_CELL}, got {per_cell}")
    if per_cell == 0:
        return 0, 0
    if not isinstance(cell, int | np.integer) or isinstance(cell, bool) or cell not in CELL_SIZES:
        sizes = ", ".join(map(str, CELL_SIZES))
        raise ValueError(f"cell must be a power of two in 16..256 ({sizes}), got {cell!r}")
    return int(cell), int(per_cell)


def cell_budget(records: np.ndarray, cell: int, per_cell: int) -> np.ndarray:
    """The records (int64 (N, 3) x, y, score, any order) the budget keeps, sorted by y then
    x: in each cell the per_cell largest scores, ties to the first in raster order."""
    cell, per_cell = validate_budget(cell, per_cell)
    records = np.asarray(records, dtype=np.int64).reshape(-1, 3)
    x, y, score = records[:, 0], records[:, 1], records[:, 2]
    if per_cell and len(records):
        columns = int(x.max()) // cell + 1
        key = (y // cell) * columns + x // cell
        order = np.lexsort((x, y, -score, key))  # by cell, best first, raster order on ties
        grouped = key[order]
        rank = np.arange(len(order)) - np.searchsorted(grouped, grouped, side="left")
        records = records[order[rank < per_cell]]
    return records[np.lexsort((records[:, 0], records[:, 1]))]


def hardware_order(records: np.ndarray, cell: int, per_cell: int) -> np.ndarray:
    """The budget's records in the order fastnms_cell_budget emits them: cell rows top to
    bottom, cells left to right, best first within a cell (ties in raster order); with
    per_cell = 0 the input order (raster order for the 3x3 NMS and "none")."""
    records = np.asarray(records, dtype=np.int64).reshape(-1, 3)
    if per_cell == 0:
        return records
    kept = cell_budget(records, cell, per_cell)
    x, y, score = kept[:, 0], kept[:, 1], kept[:, 2]
    return kept[np.lexsort((x, y, -score, x // cell, y // cell))]
