"""Test images: generated patterns and crops of real photographs.

Real photographs come from ../shared/images beside the repository when it
exists (FASTNMS_IMAGES overrides the folder), else from the CC0/public-domain
photographs bundled in scikit-image's wheel, so the tests always see real
images and pass on a fresh clone.
"""

from __future__ import annotations

import os
from pathlib import Path

import cv2
import numpy as np
from fastnms.golden.image import load_grey

REPO = Path(__file__).resolve().parents[1]


def shared_images_folder() -> Path:
    """../shared/images beside the repository, or $FASTNMS_IMAGES."""
    return Path(os.environ.get("FASTNMS_IMAGES", REPO.parent / "shared" / "images"))


def shared_images() -> list[Path]:
    """The photographs of the shared folder, sorted; none when it does not exist."""
    folder = shared_images_folder()
    if not folder.is_dir():
        return []
    return sorted(p for p in folder.iterdir() if p.suffix.lower() in (".png", ".jpg", ".jpeg"))


def bundled_images() -> list[Path]:
    import skimage.data

    folder = Path(skimage.data.__file__).parent
    names = ["camera.png", "gravel.png", "grass.png", "brick.png", "moon.png", "coins.png"]
    return [folder / n for n in names if (folder / n).exists()]


def real_images() -> list[Path]:
    """At least six real photographs."""
    return shared_images() or bundled_images()


# Six crop sizes between 128x96 and 320x240.
CROP_SIZES = [(128, 96), (160, 120), (200, 150), (320, 240), (176, 144), (256, 192)]


def photo_crops(thresholds: list[int]) -> list[list]:
    """Six [path, width, height, threshold] crops of different real
    photographs, the thresholds taken in turn."""
    images = real_images()
    assert len(images) >= 6, images
    picked = images[:: max(1, len(images) // 6)][:6]
    return [
        [str(path), w, h, thresholds[i % len(thresholds)]]
        for i, (path, (w, h)) in enumerate(zip(picked, CROP_SIZES, strict=True))
    ]


def crop(path: Path, width: int, height: int) -> np.ndarray:
    """A width x height crop from the centre of a photograph (grey)."""
    img = load_grey(path)
    h, w = img.shape
    width, height = min(width, w), min(height, h)
    y0, x0 = (h - height) // 2, (w - width) // 2
    return np.ascontiguousarray(img[y0 : y0 + height, x0 : x0 + width])


# ---- generated patterns (uint8, height x width) ------------------------------


def noise(rng: np.random.Generator, width: int, height: int) -> np.ndarray:
    return rng.integers(0, 256, (height, width), dtype=np.uint8)


def blurred_noise(rng: np.random.Generator, width: int, height: int) -> np.ndarray:
    return cv2.GaussianBlur(noise(rng, width, height), (5, 5), 1.2)


def saturated(rng: np.random.Generator, width: int, height: int) -> np.ndarray:
    """Blocks of 0 and 255 with scattered extreme pixels: v + t beyond 255,
    v - t below 0."""
    blocks = rng.integers(0, 2, ((height + 3) // 4, (width + 3) // 4), dtype=np.uint8) * 255
    img = np.kron(blocks, np.ones((4, 4), dtype=np.uint8))[:height, :width].copy()
    spots = rng.random((height, width)) < 0.1
    img[spots] = rng.choice(np.array([0, 255], dtype=np.uint8), spots.sum())
    return img


def checkerboard(rng: np.random.Generator, width: int, height: int) -> np.ndarray:
    square = int(rng.integers(1, 5))
    yy, xx = np.mgrid[:height, :width]
    return np.where(((yy // square) + (xx // square)) % 2, 200, 40).astype(np.uint8)


def single_pixels(rng: np.random.Generator, width: int, height: int) -> np.ndarray:
    """A flat background with isolated bright and dark pixels."""
    img = np.full((height, width), 128, dtype=np.uint8)
    spots = rng.random((height, width)) < 0.08
    img[spots] = rng.choice(np.array([0, 10, 245, 255], dtype=np.uint8), spots.sum())
    return img


def constant(rng: np.random.Generator, width: int, height: int) -> np.ndarray:
    return np.full((height, width), int(rng.integers(0, 256)), dtype=np.uint8)


PATTERNS = [noise, blurred_noise, saturated, checkerboard, single_pixels, constant]


def cover(img: np.ndarray, width: int, height: int, enlarge: int = cv2.INTER_CUBIC) -> np.ndarray:
    """`img` scaled to cover width x height (cv2.resize: area when shrinking,
    `enlarge` when enlarging), then cropped at its centre."""
    h, w = img.shape
    scale = max(width / w, height / h)
    size = (max(width, round(w * scale)), max(height, round(h * scale)))
    interp = cv2.INTER_AREA if scale < 1 else enlarge
    big = cv2.resize(img, size, interpolation=interp)
    y0, x0 = (size[1] - height) // 2, (size[0] - width) // 2
    return np.ascontiguousarray(big[y0 : y0 + height, x0 : x0 + width])
