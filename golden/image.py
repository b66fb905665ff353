"""Image loading shared by the command line and the tests."""

from __future__ import annotations

import os

import cv2
import numpy as np


class ImageError(Exception):
    """The image file is missing, unreadable or not an image OpenCV can decode."""


def load_grey(path: str | os.PathLike[str]) -> np.ndarray:
    """Load an image file as 2-D uint8 grey.

    The file is decoded with OpenCV as 8-bit BGR (cv2.IMREAD_COLOR, as cv2.imread does by
    default) and converted with cv2.cvtColor(COLOR_BGR2GRAY), the conversion
    cv2.FastFeatureDetector applies to colour input; grey files come back unchanged.
    """
    name = os.fspath(path)
    try:
        # Reading the bytes ourselves gives precise errors (missing, directory, permission)
        # that cv2.imread would reduce to None.
        with open(name, "rb") as f:
            data = f.read()
    except FileNotFoundError:
        raise ImageError(f"{name}: no such file") from None
    except IsADirectoryError:
        raise ImageError(f"{name}: is a directory, not an image file") from None
    except OSError as e:
        raise ImageError(f"{name}: cannot read: {e.strerror or e}") from None

    # OpenCV logs decoder complaints straight to stderr; keep it quiet while decoding so
    # callers decide how to report the failure.
    logging = cv2.utils.logging
    old_level = logging.getLogLevel()
    logging.setLogLevel(logging.LOG_LEVEL_SILENT)
    try:
        bgr = cv2.imdecode(np.frombuffer(data, dtype=np.uint8), cv2.IMREAD_COLOR)
    except cv2.error:
        bgr = None
    finally:
        logging.setLogLevel(old_level)
    if bgr is None or bgr.size == 0:
        raise ImageError(f"{name}: not an image file OpenCV can decode")
    return cv2.cvtColor(bgr, cv2.COLOR_BGR2GRAY)
