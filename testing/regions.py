"""Hand-made corner maps shared by the NMS tests: a text grid reader and the region shapes
with their expected records."""

from __future__ import annotations

import numpy as np


def grid(text: str) -> tuple[np.ndarray, np.ndarray]:
    """Whitespace-separated cells: '.' is no corner, an integer a corner with that score."""
    rows = [line.split() for line in text.strip().splitlines()]
    corner = np.array([[cell != "." for cell in row] for row in rows], dtype=bool)
    score = np.array([[0 if cell == "." else int(cell) for cell in row] for row in rows])
    return corner, score.astype(np.int32)


def records(*xys: tuple[int, int, int]) -> list[list[int]]:
    return [list(r) for r in xys]


def serpentine(h: int, w: int) -> np.ndarray:
    """Full rows joined alternately at the right and left ends: one long chain of merges."""
    mask = np.zeros((h, w), dtype=bool)
    mask[::2] = True
    mask[1::4, -1] = True
    mask[3::4, 0] = True
    return mask


def comb(h: int, w: int) -> np.ndarray:
    """Teeth every other column joined by the bottom row: regions apart until the last row."""
    mask = np.zeros((h, w), dtype=bool)
    mask[:-1, ::2] = True
    mask[-1] = True
    return mask


def nested_arches(w: int) -> np.ndarray:
    """Arches inside arches, each open downwards: the most regions of one row open at once
    ((w + 3) // 4 nested classes)."""
    levels = (w + 1) // 4 + 1
    mask = np.zeros((2 * levels + 2, w), dtype=bool)
    for k in range(levels):
        left, right = 2 * k, w - 1 - 2 * k
        if left > right:
            break
        mask[2 * k, left : right + 1] = True
        mask[2 * k + 1 :, left] = mask[2 * k + 1 :, right] = True
    return mask


def square_spiral(n: int) -> np.ndarray:
    """A spiral path of width 1 with 1-pixel gaps between its turns."""
    mask = np.zeros((n, n), dtype=bool)
    y, x, dy, dx = 0, 0, 0, 1
    mask[0, 0] = True
    while True:
        moved = False
        # Walk while the cell two steps ahead is free and in bounds (keeps the gap).
        while True:
            ny, nx, fy, fx = y + dy, x + dx, y + 2 * dy, x + 2 * dx
            if not (0 <= ny < n and 0 <= nx < n) or mask[ny, nx]:
                break
            if 0 <= fy < n and 0 <= fx < n and mask[fy, fx]:
                break
            y, x = ny, nx
            mask[y, x] = True
            moved = True
        if not moved:
            return mask
        dy, dx = dx, -dy  # turn right


# ---- hand-made shapes with (region4, region8) records ----------------------------------

SHAPES = {
    "u": (
        """
        5 . . 7
        1 . . 1
        1 . . 1
        1 1 1 1
        """,
        records((3, 0, 7)),
        records((3, 0, 7)),
    ),
    # Tie across the merge at the bottom: the right arm is labelled after the left one in
    # raster order but holds the first tied maximum in raster order.
    "u_tie_right_arm_first": (
        """
        1 . . 4
        4 . . 1
        1 1 1 1
        """,
        records((3, 0, 4)),
        records((3, 0, 4)),
    ),
    "u_tie_left_arm_first": (
        """
        4 . . 1
        1 . . 4
        1 1 1 1
        """,
        records((0, 0, 4)),
        records((0, 0, 4)),
    ),
    # The left branch opens two rows after the right one (a streaming labeller may give it a
    # recycled, smaller label once the lone pixel at (0, 0) has closed). The tie is decided
    # by raster order of the maxima, not by which branch opened or was labelled first.
    "late_branch_tie_early_branch_wins": (
        """
        2 . . . . 3 .
        . . . . . 1 .
        . . 3 . . 1 .
        . . 1 . . 1 .
        . . 1 1 1 1 .
        """,
        records((0, 0, 2), (5, 0, 3)),
        records((0, 0, 2), (5, 0, 3)),
    ),
    "late_branch_tie_late_branch_wins": (
        """
        2 . . . . 1 .
        . . . . . 1 .
        . . 3 . . 1 .
        . . 1 . . 3 .
        . . 1 1 1 1 .
        """,
        records((0, 0, 2), (2, 2, 3)),
        records((0, 0, 2), (2, 2, 3)),
    ),
    "nested_u": (
        """
        1 . . . . . . . 1
        1 . 2 . . . 6 . 1
        1 . 2 . . . 2 . 1
        1 . 2 2 2 2 2 . 1
        1 . . . . . . . 1
        1 1 1 1 1 1 1 1 3
        """,
        records((6, 1, 6), (8, 5, 3)),
        records((6, 1, 6), (8, 5, 3)),
    ),
    "nested_u_touching_diagonally": (
        """
        1 . . . . . . . 1
        1 . 2 . . . 6 . 1
        1 . 2 . . . 2 . 1
        1 . 2 2 2 2 2 . 1
        1 . . . . . . 1 1
        1 1 1 1 1 1 1 1 3
        """,
        records((6, 1, 6), (8, 5, 3)),
        records((6, 1, 6)),
    ),
    # One path from (0, 0) round to the centre (2, 4). The 9 at (6, 7) comes first along the
    # path, the 9 at (2, 4) first in raster order.
    "spiral": (
        """
        1 1 1 1 1 1 1
        . . . . . . 1
        1 1 1 1 1 . 1
        1 . . . 1 . 1
        1 . 9 . 1 . 1
        1 . 1 1 1 . 1
        1 . . . . . 1
        1 1 1 1 1 1 9
        """,
        records((2, 4, 9)),
        records((2, 4, 9)),
    ),
    "staircase": (
        """
        1 1 . . .
        . 1 1 . .
        . . 1 1 .
        . . . 1 5
        """,
        records((4, 3, 5)),
        records((4, 3, 5)),
    ),
    "diagonal_pixels": (
        """
        3 . . .
        . 1 . .
        . . 4 .
        . . . 1
        """,
        records((0, 0, 3), (1, 1, 1), (2, 2, 4), (3, 3, 1)),
        records((2, 2, 4)),
    ),
    "diagonal_blocks": (
        """
        2 2 . .
        2 2 . .
        . . 3 5
        . . 3 3
        """,
        records((0, 0, 2), (3, 2, 5)),
        records((3, 2, 5)),
    ),
    "antidiagonal_blocks": (
        """
        . . 4 4
        . . 4 4
        6 1 . .
        1 1 . .
        """,
        records((2, 0, 4), (0, 2, 6)),
        records((0, 2, 6)),
    ),
    "antidiagonal_pixels": (
        """
        . 1
        1 .
        """,
        records((1, 0, 1), (0, 1, 1)),
        records((1, 0, 1)),
    ),
    "plateau": (
        """
        . . . .
        . 3 3 3
        . 3 3 3
        """,
        records((1, 1, 3)),
        records((1, 1, 3)),
    ),
    # Membership is the corner flag: zero scores still connect, and an all-zero set still
    # yields its record.
    "zero_score_members": (
        """
        5 0 0 7
        . . . .
        0 0 . .
        """,
        records((3, 0, 7), (0, 2, 0)),
        records((3, 0, 7), (0, 2, 0)),
    ),
    "whole_image": (
        """
        1 2 3
        4 9 2
        9 1 9
        """,
        records((1, 1, 9)),
        records((1, 1, 9)),
    ),
    "single_pixels": (
        """
        5 . 3
        . . .
        0 . 8
        """,
        records((0, 0, 5), (2, 0, 3), (0, 2, 0), (2, 2, 8)),
        records((0, 0, 5), (2, 0, 3), (0, 2, 0), (2, 2, 8)),
    ),
    "checkerboard": (
        """
        1 . 2 .
        . 3 . 3
        1 . 2 .
        """,
        records((0, 0, 1), (2, 0, 2), (1, 1, 3), (3, 1, 3), (0, 2, 1), (2, 2, 2)),
        records((1, 1, 3)),
    ),
    "arch_split_not_merge": (
        """
        1 1 1 1 1
        1 . 1 . 1
        8 . 1 . 8
        """,
        records((0, 2, 8)),
        records((0, 2, 8)),
    ),
    "empty": (
        """
        . . .
        . . .
        """,
        [],
        [],
    ),
}
