"""The PNG the `--png` option writes: the grey image with a box around each corner,
coloured from dark red (the lowest score) to yellow (the highest), with ORB each
keypoint's orientation and with a budget the grid of its cells; with --levels a circle of
each keypoint's size on the original image, as cv2.drawKeypoints draws rich keypoints.
"""

from __future__ import annotations

from collections.abc import Sequence

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
FAST_SIZE = 7  # cv2.FastFeatureDetector's KeyPoint.size (the FAST circle's diameter)
DRAW_SHIFT = 4  # fractional bits of the circles' centres and radii (cv2.drawKeypoints')


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


def keypoint_circles(
    scale: np.float32, records: np.ndarray, oriented: bool
) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """(cx, cy, radius) int64 (N,) with DRAW_SHIFT fractional bits, as cv2.drawKeypoints
    rounds them: the centre cvRound(pt * 16), pt = float32(x) * scale_k (cv2.KeyPoint.pt),
    the radius cvRound(size / 2 * 16), size (31 with an orientation, else 7) * scale_k."""
    one = 1 << DRAW_SHIFT
    scale = np.float32(scale)
    size = np.float32(PATCH_SIZE if oriented else FAST_SIZE) * scale
    x = records[:, 0].astype(np.float32) * scale
    y = records[:, 1].astype(np.float32) * scale
    radius = np.full(len(records), np.rint(size / np.float32(2) * np.float32(one)), np.int64)
    return (
        np.rint(x * np.float32(one)).astype(np.int64),
        np.rint(y * np.float32(one)).astype(np.int64),
        radius,
    )


def keypoint_overlay(
    img: np.ndarray,
    levels: Sequence[tuple[np.float32, np.ndarray, np.ndarray | None]],
) -> np.ndarray:
    """The grey image as BGR with each level's keypoints drawn at their place in it: for
    (scale_k, records, angles) of level k, a circle of the keypoint's size (diameter
    31 * scale_k with angles, 7 * scale_k without) centred at (x * scale_k, y * scale_k),
    coloured by score over all levels (weakest first), with angles a line from the centre
    along the orientation to the rim."""
    canvas = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR)
    circles, orientations = [], []  # (score, cx, cy, radius) and angle (nan: none)
    for scale, records, angles in levels:
        cx, cy, radius = keypoint_circles(scale, records, angles is not None)
        circles.append(np.column_stack([records[:, 2], cx, cy, radius]).astype(np.int64))
        orientations.append(
            np.full(len(records), np.nan) if angles is None else angles.astype(np.float64)
        )
    drawn = np.concatenate(circles) if circles else np.zeros((0, 4), np.int64)
    angle = np.concatenate(orientations) if orientations else np.zeros(0)
    colours = score_colours(drawn[:, 0])
    for i in np.argsort(drawn[:, 0], kind="stable"):
        _, x, y, r = drawn[i].tolist()
        colour = tuple(int(c) for c in colours[i])
        cv2.circle(canvas, (x, y), r, colour, 1, cv2.LINE_8, DRAW_SHIFT)
        if not np.isnan(angle[i]):
            t = np.radians(angle[i])
            tip = (x + round(r * np.cos(t)), y + round(r * np.sin(t)))
            cv2.line(canvas, (x, y), tip, colour, 1, cv2.LINE_8, DRAW_SHIFT)
    return canvas


def png_bytes(canvas: np.ndarray) -> bytes:
    ok, buf = cv2.imencode(".png", canvas)
    if not ok:
        raise OSError("PNG encoding failed")
    return buf.tobytes()
