"""The streaming region-NMS algorithm planned for the RTL, modelled pixel by pixel.

This is not the contract (that is `fastnms.nms.nms_region`); it is the hardware's algorithm
in Python, checked against the contract, so that the RTL has a proven plan and measured
bounds (labels in use, extra clocks for merges). It sees the pixels one at a time in raster
order and keeps only what the hardware keeps:

- the label line: one label per column, columns left of x from row y, the rest from row y-1;
- registers A (north-west, 8-connectivity only) and D (west);
- per label, the representative (a flat merger table: always one look-up) and the number of
  line entries (plus register A) holding that literal label;
- per representative, the region's maximum (score, y, x), its reference count (all line
  references to any of its labels) and its list of aliases (labels merged into it);
- a free list of labels.

A pixel touches at most two regions, so a step does at most one merge. A merge re-points
the aliases of the absorbed region at the survivor; each alias beyond the first costs the
hardware one extra clock (input held). A region whose reference count reaches 0 can never
be touched again: it is closed and emitted. After the last row, one pass of W non-corner
pixels closes every region still open.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass, field

import numpy as np


@dataclass
class StreamStats:
    """What the hardware would need: label capacity and extra clocks."""

    max_labels: int = 0  # labels allocated at once (the label RAM depth needed)
    merges: int = 0
    merge_stall_clocks: int = 0  # aliases re-pointed beyond one per merge
    records_order: list[tuple[int, int, int]] = field(default_factory=list)


def region_nms_stream(
    corner: np.ndarray, score: np.ndarray, connectivity: int
) -> tuple[np.ndarray, StreamStats]:
    """Region NMS by the streaming algorithm: records sorted by y then x (as the golden),
    and the statistics. Emission order is kept in stats.records_order."""
    if connectivity not in (4, 8):
        raise ValueError(f"connectivity must be 4 or 8, got {connectivity!r}")
    h, w = corner.shape
    eight = connectivity == 8
    line = [0] * w
    parent: dict[int, int] = {}
    line_refs: dict[int, int] = {}  # per literal label
    region_refs: dict[int, int] = {}  # per representative
    best: dict[int, tuple[int, int, int]] = {}  # representative -> (score, y, x)
    aliases: dict[int, list[int]] = {}  # representative -> its labels (itself first)
    free: deque[int] = deque()
    next_label = 1
    stats = StreamStats()

    def allocate() -> int:
        nonlocal next_label
        if free:
            return free.popleft()
        next_label += 1
        return next_label - 1

    def better(a: tuple[int, int, int], b: tuple[int, int, int]) -> tuple[int, int, int]:
        # Larger score; on a tie the first in raster order (smaller y, then x).
        return a if (a[0], -a[1], -a[2]) >= (b[0], -b[1], -b[2]) else b

    def release(label: int) -> None:
        del parent[label], line_refs[label]
        free.append(label)

    def drop(label: int) -> None:
        if not label:
            return
        root = parent[label]
        line_refs[label] -= 1
        region_refs[root] -= 1
        if line_refs[label] == 0 and label != root:
            aliases[root].remove(label)
            release(label)
        if region_refs[root] == 0:
            assert aliases[root] == [root], "a closed region still has aliases"
            s, y, x = best.pop(root)
            stats.records_order.append((x, y, s))
            del region_refs[root], aliases[root]
            release(root)

    for y in range(h + 1):  # row h: the flush pass
        a_reg = 0
        d_reg = 0
        for x in range(w):
            c = y < h and bool(corner[y, x])
            b_label = line[x]
            c_label = line[x + 1] if eight and x + 1 < w else 0
            if c:
                s = int(score[y, x])
                near = [d_reg, b_label] + ([a_reg, c_label] if eight else [])
                roots = []
                for label in near:
                    if label and parent[label] not in roots:
                        roots.append(parent[label])
                assert len(roots) <= 2, "more than one merge in a step"
                if not roots:
                    j = allocate()
                    parent[j], line_refs[j], region_refs[j] = j, 0, 0
                    best[j] = (s, y, x)
                    aliases[j] = [j]
                else:
                    j = roots[0]  # D's region when D is a corner: the run keeps its label
                    for k in roots[1:]:
                        stats.merges += 1
                        stats.merge_stall_clocks += len(aliases[k]) - 1
                        region_refs[j] += region_refs.pop(k)
                        best[j] = better(best[j], best.pop(k))
                        for label in aliases[k]:
                            parent[label] = j
                        aliases[j] += aliases.pop(k)
                    if s > best[j][0]:
                        best[j] = (s, y, x)
                line[x] = j
                line_refs[j] += 1
                region_refs[j] += 1
                d_reg = j
            else:
                line[x] = 0
                d_reg = 0
            # The entry leaving the neighbourhood: B under 4-connectivity; under
            # 8-connectivity B moves into register A and the old A leaves (and B as
            # well at the end of a row).
            if eight:
                drop(a_reg)
                a_reg = b_label
                if x == w - 1:
                    drop(a_reg)
                    a_reg = 0
            else:
                drop(b_label)
            stats.max_labels = max(stats.max_labels, len(parent))
    assert not parent and not best, "regions left open after the flush pass"
    records = sorted(stats.records_order, key=lambda r: (r[1], r[0]))
    return np.array(records, dtype=np.int64).reshape(-1, 3), stats
