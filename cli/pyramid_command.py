"""`fastnms pyramid`: the golden model's image pyramid (cv2.ORB's, golden/pyramid.py) of one
image, written as DIR/level_0.png ... level_{N-1}.png, all or none; one line per level.
"""

from __future__ import annotations

import argparse
import contextlib
import os

from fastnms.args import GREY_NOTE, UsageError, add_level_args, scale_factor_of
from fastnms.golden.pyramid import level_size, pyramid
from fastnms.inputs import load_input
from fastnms.outputs import cannot_write, check_output_path, output_set
from fastnms.overlay import png_bytes


def add_pyramid_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "pyramid",
        help="write the golden model's image pyramid of an image",
        description=(
            "Write the levels of cv2.ORB's image pyramid, as the golden model computes them, "
            "as grey PNG files DIR/level_0.png (the grey input) ... DIR/level_{N-1}.png. "
            f"{GREY_NOTE} Prints one line per level."
        ),
    )
    p.add_argument("image", metavar="IMAGE", help="input image (any format OpenCV reads)")
    add_level_args(p, "write the N levels 0 .. N-1", required=True)
    p.add_argument(
        "--out",
        metavar="DIR",
        required=True,
        help="the directory of the level files, created if missing (its parent must exist); "
        "its files level_K.png are replaced, its other files left as they are",
    )
    return p


def level_path(out: str, k: int) -> str:
    return os.path.join(out, f"level_{k}.png")


def check_out_dir(out: str, nlevels: int) -> bool:
    """Fail before any work when DIR cannot hold the levels; True when DIR is to be
    created."""
    if not out:
        raise UsageError("--out needs a directory name")
    if os.path.exists(out) and not os.path.isdir(out):
        raise UsageError(f"{out}: not a directory")
    if os.path.isdir(out):
        for k in range(nlevels):
            check_output_path(level_path(out, k))
        return False
    parent = os.path.dirname(os.path.abspath(out))
    if not os.path.isdir(parent):
        raise UsageError(f"{out}: directory {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise UsageError(f"{out}: directory {parent} is not writable")
    return True


def run_pyramid(args: argparse.Namespace) -> int:
    scale_factor = scale_factor_of(args)
    create = check_out_dir(args.out, args.levels)
    img = load_input(args.image)
    h, w = img.shape
    sizes = [level_size(w, h, k, scale_factor) for k in range(args.levels)]
    for k, (lw, lh) in enumerate(sizes):
        if lw < 1 or lh < 1:
            raise UsageError(
                f"level {k} of a {w}x{h} image at scale factor {scale_factor:.9g} would be "
                f"{lw}x{lh} pixels: at most {k} levels"
            )
    levels = pyramid(img, args.levels, scale_factor)
    try:
        if create:
            os.mkdir(args.out)
        try:
            with output_set() as out:
                for k, level in enumerate(levels):
                    out.write(level_path(args.out, k), png_bytes(level))
        except BaseException:
            if create:  # all or none: take back the directory made here
                with contextlib.suppress(OSError):
                    os.rmdir(args.out)
            raise
    except OSError as e:
        raise cannot_write(e) from None
    for k, level in enumerate(levels):
        lh, lw = level.shape
        print(f"level {k}: {lw}x{lh} -> {level_path(args.out, k)}")
    return 0
