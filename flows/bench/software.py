"""Time detect() on a 1920x1080 frame for every score and NMS mode, and OpenCV's FAST on the
same frame. Run as `python -m flows.bench.software`; prints one line per case (best of 3).
`make bench` times its first frame with software_times."""

from __future__ import annotations

import time
from collections.abc import Callable

import cv2
import numpy as np
from fastnms.golden.model import DEFAULT_THRESHOLD, NMS_MODES, SCORES, detect

WIDTH, HEIGHT = 1920, 1080
REPEATS = 3
# `make bench`'s software timings keep the configurations they had when the bench
# simulated only three.
SOFTWARE_CONFIGS = [("opencv", "3x3"), ("sad", "region4"), ("opencv", "region8")]


def bench_frame() -> tuple[np.ndarray, str]:
    """The scikit-image gravel photo tiled to 1920x1080 (real texture, realistic corner
    density), or Gaussian-blurred noise when scikit-image is not installed."""
    try:
        from skimage import data

        tile = data.gravel()
        if tile.ndim == 3:
            tile = cv2.cvtColor(tile, cv2.COLOR_RGB2GRAY)
        reps = (-(-HEIGHT // tile.shape[0]), -(-WIDTH // tile.shape[1]))
        frame = np.tile(tile.astype(np.uint8), reps)[:HEIGHT, :WIDTH]
        return np.ascontiguousarray(frame), "skimage gravel, tiled"
    except ImportError:
        noise = np.random.default_rng(0).integers(0, 256, (HEIGHT, WIDTH), dtype=np.uint8)
        return cv2.GaussianBlur(noise, (0, 0), 1.5), "blurred noise"


def best_ms(fn: Callable[[], object]) -> tuple[float, object]:
    best, result = float("inf"), None
    for _ in range(REPEATS):
        start = time.perf_counter()
        result = fn()
        best = min(best, time.perf_counter() - start)
    return best * 1e3, result


def software_times(frame: np.ndarray, threshold: int) -> list[dict]:
    """Best of 3 wall times of the golden model (the bench's configurations)
    and of cv2.FastFeatureDetector on one frame, for `make bench`."""
    rows = []
    for score, nms in SOFTWARE_CONFIGS:
        ms, rec = best_ms(lambda s=score, n=nms: detect(frame, threshold, s, n))
        rows.append(
            {
                "what": f"golden {score} + {nms}",
                "ms": ms,
                "corners": len(rec),
                "best_of": REPEATS,
            }
        )
    for nonmax in (True, False):
        det = cv2.FastFeatureDetector_create(
            threshold=threshold, nonmaxSuppression=nonmax, type=cv2.FAST_FEATURE_DETECTOR_TYPE_9_16
        )
        ms, kps = best_ms(lambda d=det: d.detect(frame))
        label = "opencv + 3x3" if nonmax else "opencv + none"
        rows.append(
            {
                "what": f"cv2.FastFeatureDetector {label}",
                "ms": ms,
                "corners": len(kps),
                "best_of": REPEATS,
            }
        )
    return rows


def main() -> None:
    frame, source = bench_frame()
    t = DEFAULT_THRESHOLD
    print(f"frame {frame.shape[1]}x{frame.shape[0]} ({source}), threshold={t}, best of {REPEATS}")
    for score in SCORES:
        for nms in NMS_MODES:
            ms, rec = best_ms(lambda s=score, n=nms: detect(frame, t, s, n))
            print(f"golden score={score:<6} nms={nms:<7} {ms:9.1f} ms  {len(rec):7d} corners")
    for nonmax in (True, False):
        det = cv2.FastFeatureDetector_create(
            threshold=t, nonmaxSuppression=nonmax, type=cv2.FAST_FEATURE_DETECTOR_TYPE_9_16
        )
        ms, kps = best_ms(lambda d=det: d.detect(frame))
        label = "3x3" if nonmax else "none"
        print(f"cv2.FastFeatureDetector nms={label:<7}  {ms:9.1f} ms  {len(kps):7d} corners")


if __name__ == "__main__":
    main()
