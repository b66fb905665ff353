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
