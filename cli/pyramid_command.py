"""`fastnms pyramid`: the golden model's image pyramid (cv2.ORB's, golden/pyramid.py) of one
image, written as DIR/level_0.png ... level_{N-1}.png, all or none; one line per level.
With --rtl the levels are the RTL resizers' (a chain simulated by Verilator,
sim/pyramid.py), and a last line says whether they equal the golden model's.
"""

from __future__ import annotations

import argparse
import contextlib
import os

import numpy as np
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
        "--rtl",
        action="store_true",
        help="the levels as the RTL computes them: fastnms_resize in a chain, simulated with "
        "Verilator (built once, about a minute); shrinking steps of at least 2x2 pixels, at most "
        f"{RTL_MAX}x{RTL_MAX}",
    )
    p.add_argument(
        "--out",
        metavar="DIR",
        required=True,
        help="the directory of the level files, created if missing (its parent must exist); "
        "its files level_K.png are replaced, its other files left as they are",
    )
    return p


# The simulated chain's generics: one build for every image and up to 8 levels.
RTL_MAX = 4095
RTL_LEVELS = 8


def rtl_levels(img, sizes: list[tuple[int, int]]) -> tuple[list, str]:
    """Levels 1 .. N-1 from the simulated chain, and a line on the run."""
    from fastnms.sim import pyramid as engine
    from fastnms.sim.verilator import EngineError

    h, w = img.shape
    if w > RTL_MAX or h > RTL_MAX:
        raise UsageError(f"--rtl takes images up to {RTL_MAX}x{RTL_MAX}, got {w}x{h}")
    for k in range(1, len(sizes)):
        if min(sizes[k - 1]) < 2:
            raise UsageError(
                f"--rtl: level {k - 1} is {sizes[k - 1][0]}x{sizes[k - 1][1]}; the RTL resizer "
                "shrinks sources of at least 2x2 pixels"
            )
    levels = max(RTL_LEVELS, len(sizes))
    chain = sizes + [
        level_size(w, h, k, 1.2) for k in range(len(sizes), levels)
    ]  # unused levels beyond N: any legal sizes
    chain = [s if min(s) >= 1 else (1, 1) for s in chain]
    try:
        exe, seconds = engine.build(RTL_MAX, RTL_MAX, levels)
        run = engine.run(exe, img, chain)
    except EngineError as e:
        raise UsageError(str(e)) from None
    built = "" if seconds is None else f" (built in {seconds:.0f} s)"
    note = (
        f"rtl: {len(sizes) - 1} steps in {run.clocks} clocks, input held {run.input_held} "
        f"clocks{built}"
    )
    return run.levels[: len(sizes) - 1], note


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
    note = None
    if args.rtl:
        from_rtl, note = rtl_levels(img, sizes)
        same = all(np.array_equal(a, b) for a, b in zip(from_rtl, levels[1:], strict=True))
        note += "; equal to the golden model's" if same else "; NOT equal to the golden model's"
        levels = [img, *from_rtl]
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
    if note:
        print(note)
    return 0
