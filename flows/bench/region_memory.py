"""The region NMS's memories in bits, computed from its generics as the RTL sizes them,
beside the paper's formula and the FIFO and 3x3 NMS's line memories."""

from __future__ import annotations

# The memory tables keep the configurations they had when the bench simulated only
# three; region4 and region8 size their memories alike, so one table per score width is
# enough.
MEMORY_CONFIGS = [("sad", "region4"), ("opencv", "region8")]
SCORE_BITS = {"opencv": 8, "sad": 12}


def clog2(n: int) -> int:
    """fastnms_pkg.clog2: the bits of an index into n things (at least 1)."""
    bits = 1
    while 2**bits < n:
        bits += 1
    return bits


def bits_for(n: int) -> int:
    """fastnms_pkg.bits_for: the bits that hold the value n itself."""
    return clog2(n + 1)


def region_memory(max_width: int, max_height: int, score_bits: int) -> dict:
    """The region NMS's memories in bits, from its generics, as the RTL sizes
    them (rtl/nms/fastnms_nms_region.vhd), with the paper's formula and a
    5-line FIFO NMS beside them."""
    slots = (max_width + 1) // 2
    slot_bits = bits_for(slots)
    x_bits, y_bits = clog2(max_width), bits_for(max_height)
    key_bits = score_bits + x_bits + y_bits
    # A class's area beside its key: the count (the record's AREA_BITS, 11) and the flag
    # set once it has saturated (rtl/nms/fastnms_nms_region_keys.vhd).
    area_bits = 11
    data_bits = key_bits + area_bits + 1
    stack_words = max((max_width + 1) // 4 + 1 - 2, 1)
    rows = [
        ("row memory (the previous row's corner bits, two columns per word; LUT RAM)", slots, 2),
        ("head table (first run of its class?, by row parity and slot; LUT RAM)", 2 * slots, 1),
        ("last table (last run of its class?, by slot; LUT RAM)", slots, 1),
        (
            "data table, keys (best key of the class, by slot; the paper's RAM score)",
            slots,
            key_bits,
        ),
        ("data table, areas (corner pixels of the class, by slot; LUT RAM)", slots, area_bits + 1),
        (
            "stack of open classes, slots, keys and areas (below its three registers)",
            stack_words,
            2 * slot_bits + data_bits,
        ),
        ("stack of open classes, flags (LUT RAM)", stack_words, 3),
        ("record FIFO (LUT RAM)", 8, 1 + x_bits + y_bits + score_bits + area_bits),
    ]
    breakdown = [{"memory": m, "words": n, "bits_per_word": b, "bits": n * b} for m, n, b in rows]
    index_bits = clog2(max_width // 2)
    paper = (max_width // 2) * (score_bits + x_bits + y_bits + index_bits)
    return {
        "max_width": max_width,
        "max_height": max_height,
        "score_bits": score_bits,
        "slots": slots,
        "slot_bits": slot_bits,
        "x_bits": x_bits,
        "y_bits": y_bits,
        "breakdown": breakdown,
        "total_bits": sum(r["bits"] for r in breakdown),
        "paper_formula_bits": paper,
        "paper_formula": f"({max_width}/2) x ({score_bits} + {x_bits} + {y_bits} + {index_bits})",
        "fifo5_bits": 5 * max_width * score_bits,
        "nms_3x3_bits": 2 * max_width * score_bits,
    }
