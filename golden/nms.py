"""Non-maxima suppression over FAST corner/score maps.

Every function takes corner (bool HxW) and score (integer HxW) and returns an int64 array of
shape (N, 3) with columns x, y, score, sorted by y then x ((0, 3) when empty).
"""

from __future__ import annotations

import numpy as np

CONNECTIVITIES = (4, 8)
# A region's area (its number of corner pixels) as its record carries it: 11 bits, saturating.
AREA_BITS = 11
AREA_MAX = 2**AREA_BITS - 1


def _check_maps(corner: object, score: object) -> tuple[np.ndarray, np.ndarray]:
    if not isinstance(corner, np.ndarray) or not isinstance(score, np.ndarray):
        raise ValueError("corner and score must be numpy arrays")
    if corner.ndim != 2 or corner.shape != score.shape:
        raise ValueError(
            f"corner and score must be 2-D maps of one shape, got {corner.shape} and {score.shape}"
        )
    if corner.dtype != bool:
        raise ValueError(f"corner must be a bool map, got dtype {corner.dtype}")
    if not np.issubdtype(score.dtype, np.integer):
        raise ValueError(f"score must be an integer map, got dtype {score.dtype}")
    return corner, score.astype(np.int64, copy=False)


def _records(xs: np.ndarray, ys: np.ndarray, scores: np.ndarray) -> np.ndarray:
    """(N, 3) int64 x, y, score; the callers pass points already in raster order."""
    return np.stack([xs, ys, scores], axis=1).astype(np.int64, copy=False).reshape(-1, 3)


def nms_none(corner: np.ndarray, score: np.ndarray) -> np.ndarray:
    """Every corner with its score."""
    corner, score = _check_maps(corner, score)
    ys, xs = np.nonzero(corner)
    return _records(xs, ys, score[ys, xs])


def nms_3x3(corner: np.ndarray, score: np.ndarray) -> np.ndarray:
    """OpenCV's rule: keep a corner whose score is strictly greater than each of its 8
    neighbours, a non-corner or out-of-image neighbour counting as 0. Equal neighbours
    therefore suppress each other and a corner scoring 0 never survives."""
    corner, score = _check_maps(corner, score)
    h, w = corner.shape
    padded = np.zeros((h + 2, w + 2), dtype=np.int64)
    padded[1:-1, 1:-1] = np.where(corner, score, 0)
    centre = padded[1:-1, 1:-1]
    keep = corner.copy()
    for dy in (-1, 0, 1):
        for dx in (-1, 0, 1):
            if dy or dx:
                keep &= centre > padded[1 + dy : h + 1 + dy, 1 + dx : w + 1 + dx]
    ys, xs = np.nonzero(keep)
    return _records(xs, ys, score[ys, xs])


def _runs(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Horizontal runs of True in raster order: row, start, end (exclusive), all int64."""
    h, w = mask.shape
    padded = np.zeros((h, w + 2), dtype=np.int8)
    padded[:, 1:-1] = mask
    step = np.diff(padded, axis=1)  # step[:, j] = mask[:, j] - mask[:, j - 1]
    rows, starts = np.nonzero(step == 1)
    _, ends = np.nonzero(step == -1)  # same row-major order, so each end pairs with a start
    return rows.astype(np.int64), starts.astype(np.int64), ends.astype(np.int64)


def _touching_runs(
    rows: np.ndarray, starts: np.ndarray, ends: np.ndarray, width: int, connectivity: int
) -> tuple[np.ndarray, np.ndarray]:
    """Index pairs (a, b) of runs in consecutive rows (row a = row b - 1) that are connected.

    Runs of one row are disjoint and sorted, so the runs of the previous row touching run b
    form one contiguous index range, found with two binary searches on row-major keys.
    """
    key = width + 2  # larger than any start or end, so keys never cross rows
    above = (rows - 1) * key
    if connectivity == 4:  # overlap: a.start < b.end and b.start < a.end
        lo = np.searchsorted(rows * key + ends, above + starts, side="right")
        hi = np.searchsorted(rows * key + starts, above + ends, side="left")
    else:  # diagonal contact too: a.start <= b.end and b.start <= a.end
        lo = np.searchsorted(rows * key + ends, above + starts, side="left")
        hi = np.searchsorted(rows * key + starts, above + ends, side="right")
    counts = np.maximum(hi - lo, 0)
    b = np.repeat(np.arange(rows.size), counts)
    within = np.arange(b.size) - np.repeat(np.cumsum(counts) - counts, counts)
    a = np.repeat(lo, counts) + within
    return a, b


def _components(n: int, a: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Union-find over n nodes and edges (a, b), vectorised as hook-and-compress.

    Returns for each node the smallest node index of its component. Each round hooks every
    root that has an edge to a smaller root onto it, then compresses all paths; every tree
    with an outside edge merges each round, so the number of rounds is logarithmic.
    """
    labels = np.arange(n)
    while True:
        la, lb = labels[a], labels[b]
        differ = la != lb
        if not differ.any():
            return labels
        a, b = a[differ], b[differ]  # edges inside one tree never matter again
        la, lb = la[differ], lb[differ]
        np.minimum.at(labels, np.maximum(la, lb), np.minimum(la, lb))
        while True:
            jumped = labels[labels]
            if np.array_equal(jumped, labels):
                break
            labels = jumped


def validate_min_area(min_area: object) -> int:
    """MIN_AREA: an integer 0 .. AREA_MAX (0 and 1 keep every region)."""
    if isinstance(min_area, bool) or not isinstance(min_area, (int, np.integer)):
        raise ValueError(f"min_area must be an integer 0..{AREA_MAX}, got {min_area!r}")
    if not 0 <= min_area <= AREA_MAX:
        raise ValueError(f"min_area must be in 0..{AREA_MAX}, got {min_area}")
    return int(min_area)


def nms_region(
    corner: np.ndarray,
    score: np.ndarray,
    connectivity: int,
    min_area: int = 0,
    with_area: bool = False,
) -> np.ndarray:
    """The paper's NMS: one record per connected set of corner pixels (4- or 8-connected),
    holding the set's maximum score; ties go to the first pixel in raster order.

    Membership is the corner flag alone, so a corner scoring 0 still joins its neighbours.
    The paper's region filtering: a region with fewer than `min_area` corner pixels has no
    record (0 and 1 keep every region). `with_area`: a fourth column, the region's area
    saturated at AREA_MAX, as the hardware's record carries it.
    """
    if connectivity not in CONNECTIVITIES:
        raise ValueError(f"connectivity must be 4 or 8, got {connectivity!r}")
    min_area = validate_min_area(min_area)
    corner, score = _check_maps(corner, score)
    rows, starts, ends = _runs(corner)
    columns = 4 if with_area else 3
    if rows.size == 0:
        return np.zeros((0, columns), dtype=np.int64)
    a, b = _touching_runs(rows, starts, ends, corner.shape[1], connectivity)
    run_label = _components(rows.size, a, b)

    # Pixels of all runs in raster order, i.e. np.nonzero(corner) order.
    lengths = ends - starts
    n_pix = int(lengths.sum())
    run_of = np.repeat(np.arange(rows.size), lengths)
    xs = np.repeat(starts, lengths) + (
        np.arange(n_pix) - np.repeat(np.cumsum(lengths) - lengths, lengths)
    )
    ys = rows[run_of]
    values = score[ys, xs]
    label = run_label[run_of]

    best = np.full(rows.size, np.iinfo(np.int64).min)
    np.maximum.at(best, label, values)
    candidates = np.flatnonzero(values == best[label])  # increasing = raster order
    first = np.full(rows.size, n_pix)
    np.minimum.at(first, label[candidates], candidates)
    area = np.bincount(label, minlength=rows.size)
    closed = first < n_pix  # the labels that are regions
    chosen_area = area[closed]
    order = np.argsort(first[closed])
    chosen, chosen_area = first[closed][order], chosen_area[order]
    kept = chosen_area >= min_area
    chosen, chosen_area = chosen[kept], chosen_area[kept]
    records = _records(xs[chosen], ys[chosen], values[chosen])
    if with_area:
        return np.column_stack([records, np.minimum(chosen_area, AREA_MAX)]).astype(np.int64)
    return records
