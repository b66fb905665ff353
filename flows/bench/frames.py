"""The bench's frames: the largest real photographs (fastnms.testing.images), each scaled
to cover the frame with cv2.resize and cropped at its centre."""

from __future__ import annotations

from pathlib import Path

import cv2
import numpy as np
from fastnms.testing import images as testimages


def bench_images(count: int) -> list[Path]:
    """The `count` largest real photographs (by pixels, then by name)."""
    sized = []
    for path in testimages.real_images():
        img = cv2.imread(str(path), cv2.IMREAD_UNCHANGED)
        sized.append((-img.shape[0] * img.shape[1], path.name, path))
    return [p for _, _, p in sorted(sized)[:count]]


def bench_frames(width: int, height: int, count: int) -> tuple[np.ndarray, list[str]]:
    """`count` frames (count x height x width, uint8) and the names of their photographs."""
    from fastnms.golden.image import load_grey

    paths = bench_images(count)
    paths = (paths * count)[:count]  # fewer photographs than frames: repeat them
    # Bilinear when enlarging, as the bench has always scaled its frames.
    frames = np.stack(
        [testimages.cover(load_grey(p), width, height, cv2.INTER_LINEAR) for p in paths]
    )
    return frames, [p.name for p in paths]
