"""The scene of `make demo`: a real photograph every set-up has, at the size users
run the IP, 1920x1080.

It is scikit-image's `rocket.jpg` (427x640, the launch of DSCOVR on a Falcon 9,
SpaceX, public domain), installed with the Python dependencies: converted to
grey as OpenCV does, scaled by 2.53 (bicubic) to cover 1920x1080 and cropped at
its centre. The launch towers' lattices give corners a viewer can check by eye.

    python -m flows.demo.scene OUT.png
"""

from __future__ import annotations

import sys
from pathlib import Path

import cv2
from fastnms.golden.image import load_grey
from fastnms.testing.images import cover

WIDTH, HEIGHT = 1920, 1080


def scene_source() -> Path:
    import skimage.data

    return Path(skimage.data.__file__).parent / "rocket.jpg"


def main(argv: list[str]) -> int:
    if len(argv) != 1:
        print("usage: python -m flows.demo.scene OUT.png", file=sys.stderr)
        return 2
    out = Path(argv[0])
    out.parent.mkdir(parents=True, exist_ok=True)
    if not cv2.imwrite(str(out), cover(load_grey(scene_source()), WIDTH, HEIGHT)):
        print(f"scene: cannot write {out}", file=sys.stderr)
        return 1
    print(f"scene: {out} ({WIDTH}x{HEIGHT}, from scikit-image's rocket.jpg)")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
