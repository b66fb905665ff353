"""The levels of the pyramid plan (flows/report/pyramid.py, docs/pyramid.md) and the
memories each level needs, as data: each one's shape (memories, words, bits a word)
as the RTL sizes it for a MAX_WIDTH of the level's width, a formula in W, evaluated
per level; ORB's memories are orb_memory.py's, evaluated at the level's size. Level
sizes: `fastnms.golden.pyramid.level_size`. Sources: rtl/common/fastnms_line_buffer.vhd
(the detector's 6 rows), rtl/nms/fastnms_nms_3x3.vhd, rtl/budget/fastnms_cell_budget.vhd,
rtl/resize/fastnms_resize.vhd (its one row above) and orb_memory.py's."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from fastnms.golden.pyramid import level_size
from fastnms.sim.run import ORB_KEYPOINT_CLOCKS

from flows.report import orb_memory
from flows.report.orb_memory import Generics, Shape, bits_for, ramb18
from flows.report.reference import DATA

PLAN: dict = DATA["pyramid"]
CELL: int = PLAN["cell"]
# Each level's K: the ORB engine's rate on one level at one pixel per clock (4 at CELL 16).
PER_CELL = CELL * CELL // ORB_KEYPOINT_CLOCKS
SCORE_BITS: int = PLAN["score_bits"]
# m01 and m10 carried with a keypoint: |m| <= 624 240 (docs/orb_rtl.md), signed.
MOMENT_BITS = 2 * (bits_for(624240) + 1)


@dataclass(frozen=True)
class Level:
    """Level k of a pyramid: its size and the width of the level it is resized from."""

    k: int
    width: int
    height: int
    src_width: int  # 0 on level 0

    @property
    def pixels(self) -> int:
        return self.width * self.height

    @property
    def cells(self) -> int:
        """The budget's CELL x CELL cells in the level's own pixels."""
        return -(-self.width // CELL) * -(-self.height // CELL)

    @property
    def orb(self) -> Generics:
        """orb_memory's generics for this level's ORB rows and queue."""
        return Generics(self.width, self.height, CELL, PER_CELL, SCORE_BITS)


def levels(width: int, height: int) -> list[Level]:
    """The levels of cv2.ORB's pyramid of a width x height image."""
    sizes = [level_size(width, height, k, PLAN["scale_factor"]) for k in range(PLAN["levels"])]
    return [Level(k, w, h, sizes[k - 1][0] if k else 0) for k, (w, h) in enumerate(sizes)]


def shares(lv: list[Level]) -> list[float]:
    """Each level's pixels over level 0's."""
    return [x.pixels / lv[0].pixels for x in lv]


# ---- the memories of a level, as data ---------------------------------------------------


@dataclass(frozen=True)
class LevelMemory:
    key: str
    name: str
    rtl: str  # where it is in the RTL today, or "—" for a plan's memory
    formula: str  # in W (the level's width), W_src, K, S, X, Y
    shape: Callable[[Level], Shape]


def _orb(key: str, name: str) -> LevelMemory:
    """An ORB memory of orb_memory.MEMORIES (its name's start) at the level's size."""
    m = next(m for m in orb_memory.MEMORIES if m.name.startswith(name))
    entity = orb_memory.INSTANCES[m.where].entity
    return LevelMemory(key, m.name, f"`{entity}`", m.formula, lambda lv: m.shape(lv.orb))


def _budget(extra: int) -> Callable[[Level], Shape]:
    """fastnms_cell_budget: two banks of ceil(W / 16) words of K entries (valid, score,
    y and x in the cell), each `extra` bits wider."""
    return lambda lv: [(2, -(-lv.width // 16), PER_CELL * (1 + SCORE_BITS + 16 + extra))]


QUEUE = _orb("queue", "record queue")
MEMORIES: list[LevelMemory] = [
    LevelMemory(
        "line",
        "detector's line buffer: the 7x7 window's 6 rows above",
        "`fastnms_line_buffer`",
        "W words × 6 · 8 bits",
        lambda lv: [(1, lv.width, 6 * 8)],
    ),
    LevelMemory(
        "nms",
        "3x3 NMS's two score lines",
        "`fastnms_nms_3x3`",
        "W words × 2 · S bits",
        lambda lv: [(1, lv.width, 2 * SCORE_BITS)],
    ),
    LevelMemory(
        "budget",
        "budget: two banks of a cell row",
        "`fastnms_cell_budget`",
        "2 × ⌈W / 16⌉ words × K · (1 + S + 16) bits",
        _budget(0),
    ),
    QUEUE,
    _orb("blurred", "blurred rows"),
    _orb("plain", "unblurred rows"),
    LevelMemory(
        "resizer",
        "resizer's row above (levels 1 to 7)",
        "`fastnms_resize`",
        "W_src words × 8 bits (W_src: the width of the level before)",
        lambda lv: [(1, lv.src_width, 8)] if lv.src_width else [],
    ),
    LevelMemory(
        "row",
        "(b): a row waiting for the shared pipeline (levels 1 to 7)",
        "—",
        "W words × 8 bits",
        lambda lv: [(1, lv.width, 8)] if lv.k else [],
    ),
    LevelMemory(
        "moments",
        "moments in the stream: the 31-row window's 30 rows above",
        "—",
        "W words × 30 · 8 bits",
        lambda lv: [(1, lv.width, 30 * 8)],
    ),
    LevelMemory(
        "budget_m",
        "budget carrying the moments",
        "—",
        f"2 × ⌈W / 16⌉ words × K · (1 + S + 16 + {MOMENT_BITS}) bits",
        _budget(MOMENT_BITS),
    ),
    LevelMemory(
        "queue_m",
        "record queue carrying the moments",
        "—",
        f"as the record queue, {MOMENT_BITS} bits wider",
        lambda lv: [(n, w, b + MOMENT_BITS) for n, w, b in QUEUE.shape(lv)],
    ),
]
BY_KEY = {m.key: m for m in MEMORIES}
# The memories of each plan on every level; option (b) adds "row" on levels 1 to 7.
PLANS: dict[str, tuple[str, ...]] = {
    "all on chip": ("line", "nms", "budget", "queue", "blurred", "plain", "resizer"),
    "blurred rows in DDR": ("line", "nms", "budget", "queue", "plain", "resizer"),
    "blurred rows in DDR, moments in the stream": (
        *("line", "nms", "budget_m", "queue_m", "moments", "resizer"),
    ),
    "both rows in DDR": ("line", "nms", "budget", "queue", "resizer"),
}
# The rows in DDR of the plans that have some: (orb_memory instance, its patch's rows).
DDR_ROWS = {
    "blurred rows in DDR": ("blurred rows",),
    "both rows in DDR": ("blurred rows", "plain rows"),
}
# Memories there once whatever the levels: the top's corner FIFO (a record with its
# angle and descriptor) and the shared ORB engine's patch copies in block RAM.
ONCE = tuple(
    next(m for m in orb_memory.MEMORIES if m.name.startswith(name))
    for name in ("corner FIFO", "patch copies of more than")
)


def cost(memory: LevelMemory, lv: Level) -> tuple[int, int]:
    """(bits, BRAM18) of a memory on a level."""
    shape = memory.shape(lv)
    return sum(n * w * b for n, w, b in shape), sum(n * ramb18(w, b) for n, w, b in shape)


def plan_cost(keys: tuple[str, ...], lv: list[Level]) -> tuple[int, int]:
    """(bits, BRAM18) of memories `keys` over the levels."""
    costs = [cost(BY_KEY[k], x) for k in keys for x in lv]
    return sum(c[0] for c in costs), sum(c[1] for c in costs)


def once(lv: list[Level]) -> tuple[int, int]:
    """(bits, BRAM18) of the memories there once (ONCE), at level 0's size."""
    shapes = [shape for m in ONCE for shape in m.shape(lv[0].orb)]
    return sum(n * w * b for n, w, b in shapes), sum(n * ramb18(w, b) for n, w, b in shapes)
