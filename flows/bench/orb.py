"""The golden ORB against cv2.ORB on real photographs, for `make bench`: keypoints and
angles must be identical, descriptors identical once the golden samples cv2.ORB's float
blur (either difference stops the bench); with the contract's bit-exact blur, how many
descriptors differ from cv2.ORB's and by how many bits. Also the time per frame of both.

    python -m flows.bench.orb [--threshold 20]    # prints the table for the photographs
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np
from fastnms.golden import orb
from fastnms.golden.image import load_grey
from fastnms.testing import images as testimages
from fastnms.testing import opencv_orb

from flows.bench import software


class OrbMismatch(Exception):
    """The golden's keypoints, angles or float-blur descriptors differ from cv2.ORB's."""


def agreement(img: np.ndarray, threshold: int, name: str) -> dict:
    """One photograph: keypoint count, and the contract's descriptors against cv2.ORB's."""
    ours = orb.orb_features(img, threshold)
    theirs = opencv_orb.features(img, threshold)
    if not np.array_equal(ours.records, theirs.records):
        raise OrbMismatch(f"{name}: keypoints differ from cv2.ORB's")
    if not np.array_equal(ours.angles.view(np.uint32), theirs.angles.view(np.uint32)):
        raise OrbMismatch(f"{name}: angles differ from cv2.ORB's")
    xs, ys = ours.records[:, 0], ours.records[:, 1]
    with_float_blur = orb.descriptors(orb.float_blur(img), xs, ys, ours.angles)
    if not np.array_equal(with_float_blur, theirs.descriptors):
        raise OrbMismatch(f"{name}: descriptors differ from cv2.ORB's with its own blur")
    bits = np.unpackbits(ours.descriptors ^ theirs.descriptors, axis=1).sum(axis=1)
    return {
        "image": name,
        "size": list(img.shape[::-1]),
        "keypoints": len(bits),
        "differing": int((bits > 0).sum()),
        "bits": int(bits.sum()),
        "mean_bits": float(bits.mean()) if len(bits) else 0.0,
        "max_bits": int(bits.max()) if len(bits) else 0,
    }


def agreement_table(paths: list[Path], threshold: int) -> dict:
    rows = [agreement(load_grey(p), threshold, p.name) for p in paths]
    total = {k: sum(r[k] for r in rows) for k in ("keypoints", "differing", "bits")}
    return {
        "threshold": threshold,
        "rows": rows,
        **total,
        "mean_bits": total["bits"] / max(total["keypoints"], 1),
        "max_bits": max((r["max_bits"] for r in rows), default=0),
    }


def times(frame: np.ndarray, threshold: int) -> list[dict]:
    """Best-of-3 wall times of the golden ORB and cv2.ORB (one level) on a frame."""
    rows = []
    ms, f = software.best_ms(lambda: orb.orb_features(frame, threshold))
    rows.append({"what": "golden ORB, opencv + 3x3", "ms": ms, "corners": len(f.records)})
    det = opencv_orb.detector(threshold)
    ms, (kps, _) = software.best_ms(lambda: det.detectAndCompute(frame, None))
    rows.append({"what": "cv2.ORB, 1 level, FAST score", "ms": ms, "corners": len(kps)})
    return [{**r, "best_of": software.REPEATS} for r in rows]


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--threshold", type=int, default=20)
    args = ap.parse_args(argv)
    table = agreement_table(testimages.real_images(), args.threshold)
    for r in table["rows"]:
        print(
            f"{r['image']:<60} {r['keypoints']:6d} keypoints, {r['differing']:6d} differ, "
            f"mean {r['mean_bits']:.3f} bits ({r['bits'] / max(r['differing'], 1):.2f} over the "
            f"differing ones), max {r['max_bits']}"
        )


if __name__ == "__main__":
    main()
