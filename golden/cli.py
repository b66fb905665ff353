"""The `fastnms` command line.

Subcommands are registered in SUBCOMMANDS; each gets its own sub-parser and handler, so
`sim` and `compare` can be added next to `golden` without touching the rest. User errors
(bad arguments, unreadable images, unwritable outputs) end as one `fastnms: error: ...`
line on stderr with exit status 2 and leave no output file behind.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import secrets
import sys
import time
from collections.abc import Callable, Iterator, Sequence

import cv2
import numpy as np

from .image import ImageError, load_grey
from .model import DEFAULT_THRESHOLD, NMS_MODES, SCORES, detect

PROG = "fastnms"
EXIT_USAGE = 2

# Box colours (BGR) for the PNG overlay: the lowest score in the result is dark red, the
# highest yellow, as in the paper's Fig. 13.
LOW_BGR = (0, 0, 128)
HIGH_BGR = (0, 255, 255)
BOX_HALF = 3  # 7x7 outline, the size of the FAST circle


class UsageError(Exception):
    """A problem with the user's input or output paths, reported as one line."""


class ArgumentParser(argparse.ArgumentParser):
    """argparse with single-line errors: `fastnms: error: <message>`, exit status 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        self.exit(EXIT_USAGE, f"{PROG}: error: {message}\n")


def threshold_arg(text: str) -> int:
    """argparse type: a decimal integer in 0..255 (no floats, no rounding)."""
    try:
        value = int(text, 10)
    except ValueError:
        raise argparse.ArgumentTypeError(
            f"threshold must be an integer in 0..255, got {text!r}"
        ) from None
    if not 0 <= value <= 255:
        raise argparse.ArgumentTypeError(f"threshold must be an integer in 0..255, got {value}")
    return value


# ---- output files ----------------------------------------------------------------------


def check_output_path(path: str) -> None:
    """Fail early, before any work, when path cannot become a regular file."""
    if os.path.isdir(path):
        raise UsageError(f"{path}: is a directory")
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        raise UsageError(f"{path}: directory {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise UsageError(f"{path}: directory {parent} is not writable")


class OutputSet:
    """Writes every output to a temporary file next to its destination and moves them all
    into place only after every one was written; on failure nothing new is left behind."""

    def __init__(self) -> None:
        self._pending: list[tuple[str, str]] = []  # (temporary, destination)

    def write(self, path: str, data: bytes) -> None:
        parent = os.path.dirname(os.path.abspath(path))
        while True:
            tmp = os.path.join(parent, f".{os.path.basename(path)}.{secrets.token_hex(4)}.tmp")
            try:
                # Not tempfile.mkstemp: its mode 0600 would survive os.replace; 0666 here
                # lets the umask decide, as for any file the user creates.
                fd = os.open(tmp, os.O_WRONLY | os.O_CREAT | os.O_EXCL, 0o666)
                break
            except FileExistsError:
                continue
        self._pending.append((tmp, path))
        with os.fdopen(fd, "wb") as f:
            f.write(data)

    def commit(self) -> None:
        done: list[str] = []
        try:
            for tmp, path in self._pending:
                os.replace(tmp, path)
                done.append(path)
        except BaseException:
            # A later file failed: take back the ones already moved so no partial set remains.
            for path in done:
                with contextlib.suppress(OSError):
                    os.unlink(path)
            raise
        finally:
            self.discard()

    def discard(self) -> None:
        for tmp, _ in self._pending:
            with contextlib.suppress(FileNotFoundError):
                os.unlink(tmp)
        self._pending.clear()


@contextlib.contextmanager
def output_set() -> Iterator[OutputSet]:
    outputs = OutputSet()
    try:
        yield outputs
        outputs.commit()
    finally:
        outputs.discard()


def csv_bytes(records: np.ndarray) -> bytes:
    lines = ["x,y,score"] + [f"{x},{y},{s}" for x, y, s in records.tolist()]
    return ("\n".join(lines) + "\n").encode("ascii")


def score_colours(scores: np.ndarray) -> np.ndarray:
    """(N, 3) BGR colours from LOW_BGR at the lowest score to HIGH_BGR at the highest."""
    scores = scores.astype(np.float64)
    if scores.size == 0:
        return np.zeros((0, 3), dtype=np.uint8)
    lo = scores.min()
    span = scores.max() - lo
    # A single distinct score has nothing to rank: draw it as the strongest.
    frac = (scores - lo) / span if span > 0 else np.ones_like(scores)
    low, high = np.array(LOW_BGR, float), np.array(HIGH_BGR, float)
    return np.rint(low + frac[:, None] * (high - low)).astype(np.uint8)


def overlay(img: np.ndarray, records: np.ndarray) -> np.ndarray:
    """The grey image as BGR with a 7x7 outline around each corner, coloured by score."""
    canvas = cv2.cvtColor(img, cv2.COLOR_GRAY2BGR)
    if records.shape[0] == 0:
        return canvas
    colours = score_colours(records[:, 2])
    # Weakest first, so the strongest corners stay visible where boxes overlap.
    for i in np.argsort(records[:, 2], kind="stable"):
        x, y = int(records[i, 0]), int(records[i, 1])
        cv2.rectangle(
            canvas,
            (x - BOX_HALF, y - BOX_HALF),
            (x + BOX_HALF, y + BOX_HALF),
            tuple(int(c) for c in colours[i]),
            1,
        )
    return canvas


def png_bytes(canvas: np.ndarray) -> bytes:
    ok, buf = cv2.imencode(".png", canvas)
    if not ok:
        raise OSError("PNG encoding failed")
    return buf.tobytes()


# ---- subcommands -----------------------------------------------------------------------


def add_golden_parser(sub: argparse._SubParsersAction) -> argparse.ArgumentParser:
    p = sub.add_parser(
        "golden",
        help="run the golden model on an image",
        description=(
            "Detect FAST-9/16 corners with the Python golden model. Colour images are "
            "converted to grey as OpenCV does: cv2.imread (8-bit BGR) then "
            "cv2.cvtColor(COLOR_BGR2GRAY). Prints one summary line."
        ),
    )
    p.add_argument("image", metavar="IMAGE", help="input image (any format OpenCV reads)")
    p.add_argument(
        "-t",
        "--threshold",
        type=threshold_arg,
        default=DEFAULT_THRESHOLD,
        metavar="T",
        help=f"segment-test threshold, integer 0..255 (default {DEFAULT_THRESHOLD})",
    )
    p.add_argument(
        "--score",
        choices=SCORES,
        default="opencv",
        help="corner score: OpenCV's cornerScore or the paper's SAD (default opencv)",
    )
    p.add_argument(
        "--nms",
        choices=NMS_MODES,
        default="3x3",
        help="non-maxima suppression (default 3x3, OpenCV's)",
    )
    p.add_argument("--csv", metavar="OUT.csv", help="write the corners as CSV: x,y,score")
    p.add_argument("--png", metavar="OUT.png", help="write the image with coloured corner boxes")
    return p


def run_golden(args: argparse.Namespace) -> int:
    outputs = [path for path in (args.csv, args.png) if path]
    if args.csv and args.png and os.path.abspath(args.csv) == os.path.abspath(args.png):
        raise UsageError(f"--csv and --png name the same file: {args.csv}")
    for path in outputs:
        check_output_path(path)
    try:
        img = load_grey(args.image)
    except ImageError as e:
        raise UsageError(str(e)) from None

    start = time.perf_counter()
    records = detect(img, args.threshold, args.score, args.nms)
    elapsed = time.perf_counter() - start

    try:
        with output_set() as out:
            if args.csv:
                out.write(args.csv, csv_bytes(records))
            if args.png:
                out.write(args.png, png_bytes(overlay(img, records)))
    except OSError as e:
        where = f"{e.filename}: " if e.filename else ""
        raise UsageError(f"cannot write output: {where}{e.strerror or e}") from None

    h, w = img.shape
    print(
        f"{os.path.basename(args.image)}: {w}x{h}, score={args.score} nms={args.nms} "
        f"threshold={args.threshold}: {records.shape[0]} corners in {elapsed:.3f} s"
    )
    return 0


Handler = Callable[[argparse.Namespace], int]
SUBCOMMANDS: dict[str, tuple[Callable[..., argparse.ArgumentParser], Handler]] = {
    "golden": (add_golden_parser, run_golden),
}


def build_parser() -> ArgumentParser:
    parser = ArgumentParser(
        prog=PROG,
        description="FAST-9/16 corner detection with non-maxima suppression: golden model.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, (add_parser, handler) in SUBCOMMANDS.items():
        add_parser(sub).set_defaults(handler=handler, command=name)
    return parser


def main(argv: Sequence[str] | None = None) -> int:
    parser = build_parser()
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return EXIT_USAGE
    try:
        return args.handler(args)
    except UsageError as e:
        print(f"{PROG}: error: {e}", file=sys.stderr)
        return EXIT_USAGE


if __name__ == "__main__":
    sys.exit(main())
