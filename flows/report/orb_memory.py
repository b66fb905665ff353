"""The memories of ORB in the AXI top as data: each one's shape (memories, words,
bits a word) as the RTL sizes it, a formula in the top's generics (MAX_WIDTH,
MAX_HEIGHT, ORB_MAX_CELL written CELL, MAX_PER_CELL written K), evaluated at a
summary row's generics; and the BRAM18 each block needs by the formulas beside
the count yosys measured for it (docs/results.md, the ORB part of the synthesis
section). Sources: rtl/orb/fastnms_orb_stage.vhd (the queue), fastnms_orb_feed.vhd
(the rows kept and the keypoint queues), fastnms_orb_rows.vhd, fastnms_orb_describe.vhd,
fastnms_orb_rotate.vhd, fastnms_orb_sample.vhd and rtl/top/fastnms_record_output.vhd
(the corner FIFO); test_report.py checks the formulas against their constants."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

from flows.report.common import num, table

BLOCK_RAM, LUT_RAM = "block RAM", "LUT RAM"
# fastnms_pkg.ORB_LANES: the engine's points per clock in fastnms_core.
ORB_LANES = 8
# fastnms_fast_pkg.score_width.
SCORE_BITS = {"sad": 12}
# The ORB payload of a corner record: the angle (32 bits) and the descriptor (256).
ORB_PAYLOAD_BITS = 32 + 256
# The xc7 RAMB18E1 in simple dual port: (words, bits a word) of each shape.
RAMB18_SHAPES = ((16384, 1), (8192, 2), (4096, 4), (2048, 9), (1024, 18), (512, 36))


def clog2(n: int) -> int:
    """fastnms_pkg.clog2: the bits of an address of n words, at least 1."""
    return max(1, (n - 1).bit_length())


def bits_for(n: int) -> int:
    """fastnms_pkg.bits_for: the bits that hold the value n."""
    return clog2(n + 1)


def fifo_words(depth: int) -> int:
    """fastnms_pkg.fifo_words: a fastnms_fifo's RAM words."""
    return 2 ** max(2, clog2(depth))


def slots(cell: int, half: int) -> int:
    """fastnms_orb_feed.slots_for: slots of 2 HALF + 1 rows that hold 2 CELL + 2 HALF."""
    return (2 * cell + 4 * half) // (2 * half + 1)


def lane_reach(lanes: int) -> list[int]:
    """Each sampler lane's reach (fastnms_orb_pattern_pkg.orb_lane_reach), from its
    model fastnms.golden.sample_order."""
    from fastnms.golden.sample_order import lane_reach as reach

    return [int(r) for r in reach(lanes)]


@dataclass(frozen=True)
class Generics:
    """The top's generics the memories depend on."""

    width: int  # MAX_WIDTH
    height: int  # MAX_HEIGHT
    cell: int  # ORB_MAX_CELL (the stage's MAX_CELL)
    per_cell: int  # MAX_PER_CELL (K)
    score_bits: int
    lanes: int = ORB_LANES
    corner_fifo_depth: int = 512

    @property
    def x_bits(self) -> int:
        return clog2(self.width)

    @property
    def y_bits(self) -> int:
        return bits_for(self.height)

    @property
    def record_bits(self) -> int:
        """A keypoint's record in ORB: x, y, score."""
        return self.x_bits + self.y_bits + self.score_bits

    @property
    def ring_bits(self) -> int:
        """fastnms_orb_feed.RING_BITS."""
        return max(self.y_bits, clog2(37 * slots(self.cell, 18))) + 2


def generics_of(row: dict) -> Generics | None:
    """The generics of an ORB top's row (fastnms_axi, DESCRIPTOR orb) or of the ORB
    stage's (fastnms_orb_stage); None for any other row."""
    g = row["generics"]
    if row["entity"] == "fastnms_axi" and g.get("DESCRIPTOR") == "orb":
        return Generics(
            width=g["MAX_WIDTH"],
            height=g["MAX_HEIGHT"],
            cell=g.get("ORB_MAX_CELL", 16),
            per_cell=max(g.get("MAX_PER_CELL", 1), 1),
            score_bits=SCORE_BITS.get(g.get("SCORE"), 8),
            corner_fifo_depth=g.get("CORNER_FIFO_DEPTH", 512),
        )
    if row["entity"] == "fastnms_orb_stage":
        return Generics(
            width=g.get("MAX_WIDTH", 1920),
            height=g.get("MAX_HEIGHT", 1080),
            cell=g.get("MAX_CELL", 16),
            per_cell=g.get("MAX_PER_CELL", 15),
            score_bits=g.get("SCORE_BITS", 8),
            lanes=g.get("LANES", ORB_LANES),
        )
    return None


# ---- the instances: where each memory is, and the generics the top gives it ------------


@dataclass(frozen=True)
class Instance:
    entity: str
    parent: str | None
    generics: Callable[[Generics], dict]


INSTANCES: dict[str, Instance] = {
    "top": Instance("fastnms_axi", None, lambda g: {}),
    "stage": Instance(
        "fastnms_orb_stage",
        "top",
        lambda g: {
            "MAX_WIDTH": g.width,
            "MAX_HEIGHT": g.height,
            "SCORE_BITS": g.score_bits,
            "LANES": g.lanes,
            "MAX_CELL": g.cell,
            "MAX_PER_CELL": g.per_cell,
        },
    ),
    "feed": Instance(
        "fastnms_orb_feed",
        "stage",
        lambda g: {
            "MAX_WIDTH": g.width,
            "MAX_HEIGHT": g.height,
            "SCORE_BITS": g.score_bits,
            "LANES": g.lanes,
            "MAX_CELL": g.cell,
        },
    ),
    "blurred rows": Instance(
        "fastnms_orb_rows",
        "feed",
        lambda g: {"MAX_WIDTH": g.width, "HEIGHT": 37, "SLOTS": slots(g.cell, 18)},
    ),
    "plain rows": Instance(
        "fastnms_orb_rows",
        "feed",
        lambda g: {"MAX_WIDTH": g.width, "HEIGHT": 31, "SLOTS": slots(g.cell, 15)},
    ),
    "engine": Instance(
        "fastnms_orb_describe",
        "feed",
        lambda g: {"LANES": g.lanes, "RECORD_BITS": g.record_bits},
    ),
    "rotation": Instance("fastnms_orb_rotate", "engine", lambda g: {"LANES": g.lanes}),
    "sampler": Instance("fastnms_orb_sample", "engine", lambda g: {"LANES": g.lanes}),
}


def within(where: str, instance: str) -> bool:
    """`where` is `instance` or inside it."""
    node: str | None = where
    while node is not None:
        if node == instance:
            return True
        node = INSTANCES[node].parent
    return False


# ---- the memories -------------------------------------------------------------------

# (memories, words, bits a word) groups of one memory.
Shape = list[tuple[int, int, int]]


@dataclass(frozen=True)
class Memory:
    where: str  # a key of INSTANCES
    name: str
    kind: str  # BLOCK_RAM or LUT_RAM
    formula: str  # memories x words x bits, in the top's generics
    shape: Callable[[Generics], Shape]


# fastnms_orb_sample: a lane's copy of more than this many rows is block RAM.
SAMPLER_LUT_ROWS = 32


def _sampler(in_block: bool) -> Callable[[Generics], Shape]:
    """Per lane: two banks of 2 R + 1 columns of 2 R + 1 rows (fastnms_orb_sample),
    the copies of more than SAMPLER_LUT_ROWS rows (in_block) or the others."""

    def shape(g: Generics) -> Shape:
        out: Shape = []
        for r in lane_reach(g.lanes):
            rows = 2 * r + 1
            if (rows > SAMPLER_LUT_ROWS) == in_block:
                out.append((1, 2 * rows, 8 * rows))
        return out

    return shape


MEMORIES: list[Memory] = [
    Memory(
        "top",
        "corner FIFO (record, angle and descriptor)",
        BLOCK_RAM,
        "512 words (CORNER_FIFO_DEPTH) × (4 + X + Y + S + 288) bits",
        lambda g: [(1, fifo_words(g.corner_fifo_depth), 4 + g.record_bits + ORB_PAYLOAD_BITS)],
    ),
    Memory(
        "stage",
        "record queue (a cell row's records)",
        BLOCK_RAM,
        "2^⌈log2(⌈MAX_WIDTH / 16⌉ · K + 2)⌉ words × (X + Y + S) bits",
        lambda g: [(1, fifo_words(max(16, -(-g.width // 16) * g.per_cell + 2)), g.record_bits)],
    ),
    Memory(
        "blurred rows",
        "blurred rows: 2·CELL + 36 kept, in slots of 37",
        BLOCK_RAM,
        "37 memories × ⌈(2·CELL + 36) / 37⌉ · 2^X words × 8 bits",
        lambda g: [(37, slots(g.cell, 18) * 2**g.x_bits, 8)],
    ),
    Memory(
        "plain rows",
        "unblurred rows: 2·CELL + 30 kept, in slots of 31",
        BLOCK_RAM,
        "31 memories × ⌈(2·CELL + 30) / 31⌉ · 2^X words × 8 bits",
        lambda g: [(31, slots(g.cell, 15) * 2**g.x_bits, 8)],
    ),
    Memory(
        "blurred rows",
        "blurred columns' FIFO",
        LUT_RAM,
        "16 words × 37 · 8 bits",
        lambda g: [(1, 16, 37 * 8)],
    ),
    Memory(
        "plain rows",
        "unblurred columns' FIFO",
        LUT_RAM,
        "16 words × 31 · 8 bits",
        lambda g: [(1, 16, 31 * 8)],
    ),
    Memory(
        "feed",
        "keypoint queues (one per image)",
        LUT_RAM,
        "2 × 16 words × (2·RING + X + Y + S) bits",
        lambda g: [(2, 16, 2 * g.ring_bits + g.record_bits)],
    ),
    Memory(
        "feed",
        "tag queue (the unblurred columns' records)",
        LUT_RAM,
        "16 words × (X + Y + S) bits",
        lambda g: [(1, 16, g.record_bits)],
    ),
    Memory(
        "engine",
        "record and angle FIFOs",
        LUT_RAM,
        "16 words × (X + Y + S) bits, 16 words × 32 bits",
        lambda g: [(1, 16, g.record_bits), (1, 16, 32)],
    ),
    Memory(
        "rotation",
        "pattern tables (PA twice, PB, NB; two banks)",
        LUT_RAM,
        "4 · LANES × 64 words × 33 bits",
        lambda g: [(4 * g.lanes, 64, 33)],
    ),
    Memory(
        "rotation",
        "point FIFO (a step's points, first and last)",
        LUT_RAM,
        "16 words × (12 · LANES + 2) bits",
        lambda g: [(1, 16, 12 * g.lanes + 2)],
    ),
    Memory(
        "sampler",
        "patch copies of more than 32 rows (one per lane, two banks)",
        BLOCK_RAM,
        "per lane with 2 R + 1 > 32: 2 (2 R + 1) words × 8 (2 R + 1) bits, R its reach",
        _sampler(in_block=True),
    ),
    Memory(
        "sampler",
        "patch copies of up to 32 rows (one per lane, two banks)",
        LUT_RAM,
        "per lane with 2 R + 1 ≤ 32: 2 (2 R + 1) words × 8 (2 R + 1) bits, R its reach",
        _sampler(in_block=False),
    ),
]


def ramb18(words: int, width: int) -> int:
    """The RAMB18 (simple dual port) one memory of `words` x `width` bits needs."""
    return min(-(-words // w) * -(-width // b) for w, b in RAMB18_SHAPES)


def evaluate(memory: Memory, g: Generics) -> dict:
    """A memory at generics `g`: its shape, bits and BRAM18 (0 in LUT RAM)."""
    shape = memory.shape(g)
    bits = sum(n * words * width for n, words, width in shape)
    bram = sum(n * ramb18(words, width) for n, words, width in shape)
    return {
        "memory": memory,
        "block": INSTANCES[memory.where].entity,
        "shape": shape,
        "bits": bits,
        "bram18": bram if memory.kind == BLOCK_RAM else 0,
    }


def memories(g: Generics, instance: str = "top") -> list[dict]:
    """The memories inside `instance` (a key of INSTANCES) evaluated at `g`."""
    return [evaluate(m, g) for m in MEMORIES if within(m.where, instance)]


def shape_text(shape: Shape) -> str:
    """`37 × 4096 × 8`; several groups, equal ones counted together."""
    counts: dict[tuple[int, int], int] = {}
    for n, words, width in shape:
        counts[words, width] = counts.get((words, width), 0) + n
    return ", ".join(
        (f"{n} × " if n > 1 else "") + f"{words} × {width}" for (words, width), n in counts.items()
    )


# ---- the section's tables -----------------------------------------------------------


def instance_of(row: dict, g: Generics) -> str | None:
    """The instance (a key of INSTANCES below the top) that a row synthesized alone
    is: its entity, with every generic it sets equal to what the top gives it."""
    for key, inst in INSTANCES.items():
        if key != "top" and inst.entity == row["entity"]:
            given = inst.generics(g)
            if all(given.get(k) == v for k, v in row["generics"].items()):
                return key
    return None


def measured_rows(summary: list[dict], source: dict, g: Generics) -> list[list[str]]:
    """The rows synthesized with memories of the table (the ORB top the table is
    evaluated on, the ORB stage, the ORB blocks alone at the generics the top gives
    them): the formulas' BRAM18 beside the count yosys measured."""
    out = []
    for row in summary:
        if row is source and row["entity"] == "fastnms_axi":
            key = "top"
        elif row.get("orb_table") or row.get("orb_block"):
            key = instance_of(row, g)
        else:
            continue
        mems = memories(g, key) if key else []
        if not mems:
            continue
        what = f"{len(mems)} ({sum(m['memory'].kind == BLOCK_RAM for m in mems)} in block RAM)"
        if key == "top":
            what += "; the top's other memories (line buffer, budget) are not ORB's"
        out.append(
            [
                f"`{row['config']}`",
                what,
                num(sum(m["bits"] for m in mems)),
                str(sum(m["bram18"] for m in mems)),
                f"{row['bram18_equiv']} ({row.get('bram18', 0)} + 2x{row.get('bram36', 0)})",
                num(row.get("lutram_luts", 0)),
            ]
        )
    return out


def memory_lines(summary: list[dict], top: dict | None) -> list[str]:
    """The memories of ORB at the top's generics (else the stage's), then the blocks
    synthesized alone: the formulas' BRAM18 beside the measured count."""
    source = top or next((r for r in summary if r["entity"] == "fastnms_orb_stage"), None)
    g = generics_of(source) if source else None
    if not source or not g:
        return []
    root = "top" if source is top else "stage"
    mems = memories(g, root)
    body = [
        [
            f"`{m['block']}`",
            m["memory"].name,
            m["memory"].kind,
            m["memory"].formula,
            shape_text(m["shape"]),
            num(m["bits"]),
            str(m["bram18"]) if m["memory"].kind == BLOCK_RAM else "—",
        ]
        for m in mems
    ]
    body.append(
        [
            "**total**",
            "",
            "",
            "",
            "",
            f"**{num(sum(m['bits'] for m in mems))}**",
            f"**{sum(m['bram18'] for m in mems)}**",
        ]
    )
    out = ["#### ORB memory", ""]
    out.append(
        f"Every memory of ORB in `{source['config']}` as the RTL sizes it: MAX_WIDTH "
        f"{g.width}, MAX_HEIGHT {g.height}, CELL {g.cell} (ORB_MAX_CELL), K {g.per_cell} "
        f"(MAX_PER_CELL), LANES {g.lanes}; X = ⌈log2 MAX_WIDTH⌉ = {g.x_bits}, Y = bits of "
        f"MAX_HEIGHT = {g.y_bits}, S = score bits = {g.score_bits}, RING = {g.ring_bits} "
        "(fastnms_orb_feed), R = each sampler lane's reach "
        f"({', '.join(str(r) for r in lane_reach(g.lanes))}). BRAM18: the xc7 "
        "RAMB18s (simple dual port, 16384 × 1 to 512 × 36 bits) the memory's shape needs; "
        "a memory in LUT RAM takes none."
    )
    out.append("")
    header = ["block", "memory", "in", "formula", "memories × words × bits", "bits", "BRAM18"]
    out += table(header, body)
    out.append("")
    measured = measured_rows(summary, source, g)
    if measured:
        out.append("The rows synthesized with these memories, BRAM18 by the formulas and measured:")
        out.append("")
        header = [
            "synthesized",
            "memories of the table",
            "bits (at the generics above)",
            "BRAM18 (formulas)",
        ]
        header += ["BRAM18 measured (18 + 2x36)", "LUT RAM LUTs measured"]
        out += table(header, measured)
        out.append("")
    return out
