"""The output files (`--csv`, `--png`, `--json`): checked before any work, written all or
none (each to a temporary file first, moved into place once every one was written), and
the CSV tables of corners (x,y,score, with a region NMS x,y,score,area) and of ORB
features (x,y,score,angle,descriptor).
"""

from __future__ import annotations

import argparse
import contextlib
import os
import secrets
from collections.abc import Iterator

import numpy as np
from fastnms.args import UsageError
from fastnms.golden.orb import OrbFeatures
from fastnms.overlay import overlay, png_bytes


def check_output_path(path: str) -> None:
    """Fail early, before any work, when path cannot become a regular file."""
    if os.path.isdir(path):
        raise UsageError(f"{path}: is a directory")
    parent = os.path.dirname(os.path.abspath(path))
    if not os.path.isdir(parent):
        raise UsageError(f"{path}: directory {parent} does not exist")
    if not os.access(parent, os.W_OK | os.X_OK):
        raise UsageError(f"{path}: directory {parent} is not writable")


def check_outputs(*paths: str | None) -> None:
    given = [os.path.abspath(p) for p in paths if p]
    if len(set(given)) != len(given):
        raise UsageError("two output options name the same file")
    for path in paths:
        if path:
            check_output_path(path)


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


CSV_COLUMNS = ("x", "y", "score", "area")


def csv_bytes(records: np.ndarray) -> bytes:
    """x,y,score, with a fourth column (the region NMS's records) x,y,score,area."""
    columns = records.shape[1] if records.ndim == 2 else 3
    lines = [",".join(CSV_COLUMNS[:columns])]
    lines += [",".join(map(str, r)) for r in records.tolist()]
    return ("\n".join(lines) + "\n").encode("ascii")


def with_areas(records: np.ndarray, areas: np.ndarray) -> np.ndarray:
    """(N, 4) x, y, score, area."""
    return np.column_stack([records, np.asarray(areas, np.int64)]).astype(np.int64)


def orb_csv_bytes(features: OrbFeatures) -> bytes:
    """x,y,score,angle,descriptor: the angle with 9 significant digits (it reads back as the
    same float32), the descriptor as 64 lowercase hex digits, byte 0 first."""
    lines = ["x,y,score,angle,descriptor"] + [
        f"{x},{y},{s},{angle:.9g},{bytes(d).hex()}"
        for (x, y, s), angle, d in zip(
            features.records.tolist(), features.angles.tolist(), features.descriptors, strict=True
        )
    ]
    return ("\n".join(lines) + "\n").encode("ascii")


def write_outputs(
    img: np.ndarray, records: np.ndarray | OrbFeatures, args: argparse.Namespace, extra=()
) -> None:
    """--csv, --png and any (path, bytes) in extra, all or none."""
    if isinstance(records, OrbFeatures):
        table, angles, records = orb_csv_bytes(records), records.angles, records.records
    else:
        table, angles = csv_bytes(records), None
    try:
        with output_set() as out:
            if args.csv:
                out.write(args.csv, table)
            if args.png:
                cell = args.cell if getattr(args, "per_cell", None) else None
                out.write(args.png, png_bytes(overlay(img, records, angles, cell)))
            for path, data in extra:
                out.write(path, data)
    except OSError as e:
        where = f"{e.filename}: " if e.filename else ""
        raise UsageError(f"cannot write output: {where}{e.strerror or e}") from None
