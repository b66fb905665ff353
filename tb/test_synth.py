"""Synthesis regression: every entity synthesizes (GHDL), maps to xc7 cells
without latches and with at most 4 logic levels between registers (yosys
synth_xilinx), and the memories land in block RAM."""

import pytest
from synth import entities, ghdl_synth, summary, yosys_xc7

LATCHES = ("LDCE", "LDPE")
# The most LUT/CARRY4/MUXF/INV cells allowed between two registers.
MAX_LOGIC_LEVELS = 4
LUTRAM = ("RAM32M", "RAM64M", "RAM32X1D", "RAM64X1D", "RAM128X1D", "RAM256X1S", "RAM32M16")


def bram18_equivalents(cells: dict[str, int]) -> int:
    return cells.get("RAMB18E1", 0) + 2 * cells.get("RAMB36E1", 0)


@pytest.mark.parametrize("entity", entities())
def test_entity_synthesizes_without_latches(entity):
    netlist, messages = ghdl_synth(entity)
    assert "latch" not in messages.lower(), messages
    cells = yosys_xc7(netlist, entity)
    print(entity, cells)
    assert not any(cells.get(c) for c in LATCHES), f"latches: {cells}"
    assert sum(cells.values()) > 0
    assert cells["logic_levels"] <= MAX_LOGIC_LEVELS, f"logic levels: {cells}"


@pytest.mark.parametrize("score", ["opencv", "sad"])
def test_detector_1920(score):
    """The FAST detector at MAX_WIDTH 1920: at most 4 logic levels, the line
    buffer in block RAM (three RAMB36), no LUT RAM, no latches."""
    netlist, messages = ghdl_synth("fastnms_fast_detector", {"MAX_WIDTH": 1920, "SCORE": score})
    cells = yosys_xc7(netlist, "fastnms_fast_detector")
    print(score, summary(cells))
    assert cells["logic_levels"] <= MAX_LOGIC_LEVELS, cells
    assert bram18_equivalents(cells) == 6, cells
    assert not any(cells.get(c) for c in LUTRAM + LATCHES), cells


@pytest.mark.parametrize("score", ["opencv", "sad"])
def test_core_1920(score):
    """Detector + 3x3 NMS at MAX_WIDTH 1920: at most 4 logic levels, the six
    pixel lines and the two score lines in block RAM (8 BRAM18-equivalents
    with 8-bit scores, 9 with 12-bit ones), no LUT RAM, no latches."""
    netlist, _ = ghdl_synth("fastnms_core", {"MAX_WIDTH": 1920, "SCORE": score, "NMS": "3x3"})
    cells = yosys_xc7(netlist, "fastnms_core")
    print(score, summary(cells))
    assert cells["logic_levels"] <= MAX_LOGIC_LEVELS, cells
    assert bram18_equivalents(cells) == (8 if score == "opencv" else 9), cells
    assert not any(cells.get(c) for c in LUTRAM + LATCHES), cells


def test_line_buffer_1920_is_block_ram():
    """Six lines of 1920 8-bit pixels (92160 bits) map to block RAM, not to
    LUTs or flip-flops."""
    netlist, _ = ghdl_synth("fastnms_line_buffer", {"MAX_WIDTH": 1920, "LINES": 6})
    cells = yosys_xc7(netlist, "fastnms_line_buffer")
    print(cells)
    assert bram18_equivalents(cells) * 18 * 1024 >= 1920 * 48
    assert not any(cells.get(c) for c in LUTRAM), f"LUT RAM: {cells}"
    ffs = sum(n for c, n in cells.items() if c.startswith("FD"))
    assert ffs < 40, f"{ffs} flip-flops: the lines are not in block RAM"
