"""The input images: a file OpenCV reads (converted to grey as OpenCV does), a directory's
image files in name order, or a video file's frames; an unreadable input is a usage error.
"""

from __future__ import annotations

import os
from collections.abc import Sequence

import cv2
import numpy as np
from fastnms.args import UsageError
from fastnms.golden.image import ImageError, load_grey

VIDEO_SUFFIXES = (".avi", ".mp4", ".mkv", ".mov", ".webm", ".m4v", ".mpg", ".mpeg")
IMAGE_SUFFIXES = (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm", ".ppm", ".webp")


def load_input(path: str) -> np.ndarray:
    try:
        return load_grey(path)
    except ImageError as e:
        raise UsageError(str(e)) from None


def load_video(path: str) -> list[np.ndarray]:
    """Every frame of a video file, grey as load_grey converts images."""
    capture = cv2.VideoCapture(path)
    frames = []
    try:
        while True:
            ok, bgr = capture.read()
            if not ok:
                break
            frames.append(cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY))
    finally:
        capture.release()
    if not frames:
        raise UsageError(f"{path}: no frame OpenCV can decode in this video file")
    return frames


def load_frames(paths: Sequence[str]) -> list[tuple[str, np.ndarray]]:
    """(name, grey image) for each input: an image, a directory's image files in name
    order, or a video file's frames (named file#index)."""
    frames: list[tuple[str, np.ndarray]] = []
    for path in paths:
        if os.path.isdir(path):
            files = sorted(
                e.path
                for e in os.scandir(path)
                if e.is_file() and e.name.lower().endswith(IMAGE_SUFFIXES)
            )
            if not files:
                raise UsageError(f"{path}: a directory without image files")
            frames += [(f, load_input(f)) for f in files]
        elif path.lower().endswith(VIDEO_SUFFIXES) and os.path.isfile(path):
            frames += [(f"{path}#{i}", img) for i, img in enumerate(load_video(path))]
        else:
            frames.append((path, load_input(path)))
    return frames
