"""The ORB part of `make demo`: the RTL's ORB descriptors (fastnms_axi with DESCRIPTOR
"orb", on the fast engine) matched between the demo scene and a copy rotated by a known
angle, beside cv2.ORB's own on the same pair.

    python -m flows.demo.orb_match SCENE.png OUT.png [--angle 30] [-t 20]

Both images go through fastnms.sim.detect_and_compute (the budget: at most PER_CELL
keypoints per CELL x CELL cell); each one's keypoints are also checked against the golden
model (positions, scores, angles and descriptors equal). The descriptors are matched with
cv2.BFMatcher(NORM_HAMMING, crossCheck=True); a match is correct when the rotation takes
the first keypoint to within TOLERANCE pixels of the second. cv2.ORB runs on the same pair
with one pyramid level (the RTL has one scale; an image pyramid is future work) and as
many features as the RTL found. OUT.png shows the RTL's matches, correct in green, wrong
in red.
"""

from __future__ import annotations

import argparse
import sys
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from pathlib import Path

import cv2
import numpy as np
from fastnms.golden import orb as golden_orb

CELL, PER_CELL = 32, 4
TOLERANCE = 3.0  # pixels
Features = tuple[Sequence[cv2.KeyPoint], np.ndarray]


@dataclass
class MatchResult:
    keypoints: tuple[int, int]  # in the scene, in the rotated copy
    matches: int
    correct: int

    @property
    def share(self) -> float:
        return self.correct / self.matches if self.matches else 0.0

    def line(self, name: str) -> str:
        return (
            f"{name}: {self.keypoints[0]} and {self.keypoints[1]} keypoints, {self.matches} "
            f"matches, {self.correct} correct ({100 * self.share:.1f} %)"
        )


def rotated(img: np.ndarray, angle: float) -> tuple[np.ndarray, np.ndarray]:
    """The image rotated by `angle` degrees about its centre (same size, black outside),
    and the 2x3 matrix that takes a point of `img` to the rotated image."""
    h, w = img.shape
    m = cv2.getRotationMatrix2D(((w - 1) / 2, (h - 1) / 2), angle, 1.0)
    return cv2.warpAffine(img, m, (w, h), flags=cv2.INTER_LINEAR), m


def match(a: Features, b: Features, m: np.ndarray) -> tuple[MatchResult, list, list[bool]]:
    """Cross-checked Hamming matches of a's descriptors to b's, and which are correct."""
    (kp_a, d_a), (kp_b, d_b) = a, b
    if len(kp_a) == 0 or len(kp_b) == 0:
        return MatchResult((len(kp_a), len(kp_b)), 0, 0), [], []
    matches = cv2.BFMatcher(cv2.NORM_HAMMING, crossCheck=True).match(d_a, d_b)
    ok = []
    for mt in matches:
        x, y = kp_a[mt.queryIdx].pt
        px, py = m @ np.array([x, y, 1.0])
        qx, qy = kp_b[mt.trainIdx].pt
        ok.append(bool(np.hypot(px - qx, py - qy) <= TOLERANCE))
    return MatchResult((len(kp_a), len(kp_b)), len(matches), sum(ok)), list(matches), ok


def drawing(img_a, img_b, a: Features, b: Features, matches, ok) -> np.ndarray:
    """The two images side by side, the correct matches in green, the wrong ones in red."""
    canvas = cv2.drawMatches(
        img_a,
        a[0],
        img_b,
        b[0],
        [mt for mt, good in zip(matches, ok, strict=True) if good],
        None,
        matchColor=(0, 200, 0),
        flags=cv2.DrawMatchesFlags_NOT_DRAW_SINGLE_POINTS,
    )
    wrong = [mt for mt, good in zip(matches, ok, strict=True) if not good]
    return cv2.drawMatches(
        img_a,
        a[0],
        img_b,
        b[0],
        wrong,
        canvas,
        matchColor=(0, 0, 255),
        flags=cv2.DrawMatchesFlags_DRAW_OVER_OUTIMG | cv2.DrawMatchesFlags_NOT_DRAW_SINGLE_POINTS,
    )


def opencv_orb(img: np.ndarray, count: int, threshold: int) -> Features:
    orb = cv2.ORB_create(nfeatures=max(count, 1), nlevels=1, fastThreshold=threshold)
    keypoints, descriptors = orb.detectAndCompute(img, None)
    return keypoints, descriptors if descriptors is not None else np.zeros((0, 32), np.uint8)


def same_features(a: Features, b: Features) -> bool:
    """Equal keypoints (position, score, angle) and descriptors."""
    key = [(k.pt, k.response, k.angle) for k in a[0]]
    return key == [(k.pt, k.response, k.angle) for k in b[0]] and np.array_equal(a[1], b[1])


def run(
    img: np.ndarray,
    out_png: Path,
    angle: float,
    threshold: int,
    features: Callable[[np.ndarray], Features],
) -> list[str]:
    """The report lines; writes out_png."""
    turned, m = rotated(img, angle)
    a, b = features(img), features(turned)
    lines = []
    for name, mine, image in (("scene", a, img), ("rotated copy", b, turned)):
        want = golden_orb.detect_and_compute(image, threshold, cell=CELL, per_cell=PER_CELL)
        if not same_features(mine, want):
            raise SystemExit(
                f"orb_match: the RTL's ORB features of the {name} differ from the golden model's"
            )
        lines.append(f"{name}: {len(mine[0])} RTL keypoints, equal to the golden model's")
    result, matches, ok = match(a, b, m)
    cv2.imwrite(str(out_png), drawing(img, turned, a, b, matches, ok))
    count = (len(a[0]) + len(b[0])) // 2
    cv_result, _, _ = match(
        opencv_orb(img, count, threshold), opencv_orb(turned, count, threshold), m
    )
    lines.append(result.line(f"RTL ORB, rotated {angle:g} degrees"))
    lines.append(cv_result.line(f"cv2.ORB {cv2.__version__} (1 level), same pair"))
    return lines


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m flows.demo.orb_match", description=__doc__)
    parser.add_argument("scene", type=Path)
    parser.add_argument("out_png", type=Path)
    parser.add_argument("--angle", type=float, default=30.0)
    parser.add_argument("-t", "--threshold", type=int, default=20)
    args = parser.parse_args(argv)
    img = cv2.imread(str(args.scene), cv2.IMREAD_GRAYSCALE)
    if img is None:
        parser.error(f"cannot read {args.scene}")
    from fastnms.sim import detect_and_compute

    def features(image: np.ndarray) -> Features:
        return detect_and_compute(image, args.threshold, cell=CELL, per_cell=PER_CELL)

    for line in run(img, args.out_png, args.angle, args.threshold, features):
        print(line)
    print(f"wrote {args.out_png}: the RTL's matches, correct in green, wrong in red")
    return 0


if __name__ == "__main__":
    sys.exit(main())
