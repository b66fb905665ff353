"""The output files (`--csv`, `--png`, `--json`): checked before any work, written all or
none (each to a temporary file first, moved into place once every one was written), and
the CSV tables of corners (x,y,score, with a region NMS x,y,score,area) and of ORB
features (x,y,score,angle,descriptor), with --levels each row led by its pyramid level.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import secrets
from collections.abc import Callable, Iterable, Iterator, Sequence

import numpy as np
from fastnms.args import UsageError
from fastnms.golden.orb import OrbFeatures
from fastnms.overlay import keypoint_overlay, overlay, png_bytes


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
ORB_COLUMNS = ("x", "y", "score", "angle", "descriptor")


def table_bytes(header: Sequence[str], rows: Iterable[str]) -> bytes:
    return ("\n".join([",".join(header), *rows]) + "\n").encode("ascii")


def csv_bytes(records: np.ndarray) -> bytes:
    """x,y,score, with a fourth column (the region NMS's records) x,y,score,area."""
    columns = records.shape[1] if records.ndim == 2 else 3
    return table_bytes(CSV_COLUMNS[:columns], (",".join(map(str, r)) for r in records.tolist()))


def with_areas(records: np.ndarray, areas: np.ndarray) -> np.ndarray:
    """(N, 4) x, y, score, area."""
    return np.column_stack([records, np.asarray(areas, np.int64)]).astype(np.int64)


def orb_rows(features: OrbFeatures) -> list[str]:
    """x,y,score,angle,descriptor of each keypoint: the angle with 9 significant digits (it
    reads back as the same float32), the descriptor as 64 lowercase hex digits, byte 0
    first."""
    return [
        f"{x},{y},{s},{angle:.9g},{bytes(d).hex()}"
        for (x, y, s), angle, d in zip(
            features.records.tolist(), features.angles.tolist(), features.descriptors, strict=True
        )
    ]


def orb_csv_bytes(features: OrbFeatures) -> bytes:
    """x,y,score,angle,descriptor (orb_rows)."""
    return table_bytes(ORB_COLUMNS, orb_rows(features))


def levels_csv_bytes(levels: Sequence[np.ndarray | OrbFeatures]) -> bytes:
    """level,x,y,score (each level's (N, 3) records) or level,x,y,score,angle,descriptor
    (each level's OrbFeatures), level 0 first, each level's rows in its own order."""
    orb = isinstance(levels[0], OrbFeatures)
    header = ("level", *(ORB_COLUMNS if orb else CSV_COLUMNS[:3]))
    rows = []
    for k, result in enumerate(levels):
        if orb:
            rows += [f"{k},{row}" for row in orb_rows(result)]
        else:
            rows += [",".join(map(str, (k, *r))) for r in result[:, :3].tolist()]
    return table_bytes(header, rows)


def cannot_write(e: OSError) -> UsageError:
    where = f"{e.filename}: " if e.filename else ""
    return UsageError(f"cannot write output: {where}{e.strerror or e}")


def write_files(files: Iterable[tuple[str | None, Callable[[], bytes]]]) -> None:
    """For each (path, make) with a path, make()'s bytes to path: all or none."""
    try:
        with output_set() as out:
            for path, make in files:
                if path:
                    out.write(path, make())
    except OSError as e:
        raise cannot_write(e) from None


def write_outputs(
    img: np.ndarray, records: np.ndarray | OrbFeatures, args: argparse.Namespace, extra=()
) -> None:
    """--csv, --png and any (path, bytes) in extra, all or none."""
    if isinstance(records, OrbFeatures):
        table, angles, records = orb_csv_bytes(records), records.angles, records.records
    else:
        table, angles = csv_bytes(records), None
    cell = args.cell if getattr(args, "per_cell", None) else None
    write_files(
        [
            (args.csv, lambda: table),
            (args.png, lambda: png_bytes(overlay(img, records, angles, cell))),
            *((path, lambda data=data: data) for path, data in extra),
        ]
    )


def write_level_outputs(
    img: np.ndarray,
    levels: Sequence[tuple[np.float32, np.ndarray | OrbFeatures]],
    args: argparse.Namespace,
) -> None:
    """--csv (levels_csv_bytes) and --png (keypoint_overlay on the original image) of each
    level's (scale, result), all or none."""

    def drawn() -> bytes:
        keypoints = [
            (scale, r.records, r.angles) if isinstance(r, OrbFeatures) else (scale, r, None)
            for scale, r in levels
        ]
        return png_bytes(keypoint_overlay(img, keypoints))

    write_files([(args.csv, lambda: levels_csv_bytes([r for _, r in levels])), (args.png, drawn)])
