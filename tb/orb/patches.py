"""Patches for the ORB testbenches: random square crops of a set of images."""

from __future__ import annotations

import random

import numpy as np


def random_crop(rng: random.Random, images: list[np.ndarray], side: int) -> np.ndarray:
    """A side x side crop at a random place of a random image of `images`."""
    p = images[rng.randrange(len(images))]
    y = rng.randrange(p.shape[0] - side)
    x = rng.randrange(p.shape[1] - side)
    return np.ascontiguousarray(p[y : y + side, x : x + side])


def budget_order(features, cell: int) -> list[tuple[int, int, int, int, int]]:
    """orb.orb_features' keypoints as (x, y, score, angle bits, descriptor as an int, bit i =
    pair i) in the order the budget hands them over: a cell row at a time, its cells left to
    right, the best score first, ties in raster order."""
    rec = features.records
    order = np.lexsort((rec[:, 0], rec[:, 1], -rec[:, 2], rec[:, 0] // cell, rec[:, 1] // cell))
    return [
        (
            int(rec[i, 0]),
            int(rec[i, 1]),
            int(rec[i, 2]),
            int(features.angles[i : i + 1].view(np.uint32)[0]),
            int.from_bytes(features.descriptors[i].tobytes(), "little"),
        )
        for i in order
    ]
