"""The PNG the `--png` option writes: the grey image with a box around each corner,
coloured from dark red (the lowest score) to yellow (the highest), with ORB each
keypoint's orientation and with a budget the grid of its cells.
"""

from __future__ import annotations

import cv2
import numpy as np
from fastnms.golden.orb import PATCH_SIZE

# Box colours (BGR) for the PNG overlay: the lowest score in the result is dark red, the
# highest yellow, as in the paper's Fig. 13.
LOW_BGR = (0, 0, 128)
HIGH_BGR = (0, 255, 255)
BOX_HALF = 3  # 7x7 outline, the size of the FAST circle
ORIENTATION_LENGTH = PATCH_SIZE // 2  # the orientation line reaches the patch's rim
GRID_COLOUR = (160, 90, 0)  # BGR: the budget's cells, a dim blue under the boxes


def score_colours(scores: np.ndarray) -> np.ndarray:
    """(N, 3) BGR colours from LOW_BGR at the lowest score to HIGH_BGR at the highest."""
    scores = scores.astype(np.float64)
    if scores.size == 0:
        return np.zeros((0, 3), dtype=np.uint8)
    lo = scores.min()
    span = scores.max() - lo
    # A single distinct score has nothing to rank: draw it as the strongest.
    frac = (scores - lo) / span if span > 0 else np.ones_like(scores)
    low, high = np.array(LOW_BGR, float), np.array(HIGH_BGR, float)
    return np.rint(low + frac[:, None] * (high - low)).astype(np.uint8)


def overlay(
    img: np.ndarray,
    records: np.ndarray,
    angles: np.ndarray | None = None,
    cell: int | None = None,
) -> np.ndarray:
    """The grey image as BGR with a 7x7 outline around each corner, coloured by score, with
    angles (degrees, y down) a line from each corner along its orientation, and with `cell`
    the budget's grid in blue."""
    canvas = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR)
    if cell:
        h, w = img.shape
        for x in range(cell, w, cell):
            cv2.line(canvas, (x, 0), (x, h - 1), GRID_COLOUR, 1)
        for y in range(cell, h, cell):
            cv2.line(canvas, (0, y), (w - 1, y), GRID_COLOUR, 1)
    if records.shape[0] == 0:
        return canvas
    colours = score_colours(records[:, 2])
    # Weakest first, so the strongest corners stay visible where boxes overlap.
    for i in np.argsort(records[:, 2], kind="stable"):
        x, y = int(records[i, 0]), int(records[i, 1])
        colour = tuple(int(c) for c in colours[i])
        cv2.rectangle(canvas, (x - BOX_HALF, y - BOX_HALF), (x + BOX_HALF, y + BOX_HALF), colour, 1)
        if angles is not None:
            t = np.radians(float(angles[i]))
            tip = (
                round(x + ORIENTATION_LENGTH * np.cos(t)),
                round(y + ORIENTATION_LENGTH * np.sin(t)),
            )
            cv2.line(canvas, (x, y), tip, colour, 1)
    return canvas


def png_bytes(canvas: np.ndarray) -> bytes:
    ok, buf = cv2.imencode(".png", canvas)
    if not ok:
        raise OSError("PNG encoding failed")
    return buf.tobytes()
