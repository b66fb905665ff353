"""The deferred-select probes of issue 37 (flows/synth/probes/key_deferred_chain.vhd,
key_deferred.vhd) through the core's synthesis flow: their logic levels, exact, so that
docs/fastnms_nms_region.md (Depth and clock) follows the tools. tb/probes/test_key_deferred.py
simulates both against models that compare the keys themselves."""

import pytest

from flows.synth import ecp5
from flows.synth.synth import ghdl_synth, levels_by_register, probe_sources
from flows.synth.test_synth import probe_cells


@pytest.mark.slow  # a probe of the region NMS's depth: make test-full
@pytest.mark.parametrize(
    ("key_bits", "lag", "levels"),
    [(34, 2, 4), (30, 2, 4), (34, 1, 5), (30, 1, 5)],
)
def test_deferred_chain_depth(key_bits, lag, levels, tmp_path):
    """A chain of full-key merges (one operand per clock, the accumulator out two clocks
    later) with its select deferred. LAG 1, the pending pair and its flag: the next
    pair's flag chooses between two comparisons, a level after the comparators (f: 5).
    LAG 2, the accumulator two operands back against the last two operands: three
    comparisons register to register (4 levels, as key_compare) and the choice a clock
    later (2 levels: a LUT shared by the bits, then one per bit): 4 levels for merges
    that chain from clock to clock, with the region NMS's 34- and 30-bit keys."""
    cells = probe_cells("key_deferred_chain", {"KEY_BITS": key_bits, "LAG": lag}, tmp_path)
    assert cells["logic_levels"] == levels, cells
    by_register = levels_by_register(tmp_path / "key_deferred_chain.v", "key_deferred_chain")
    if lag == 2:
        flags = (by_register["r_ge_y"], by_register["r_ge_x"], by_register["y_ge_x"])
        assert flags == (4, 4, 4) and by_register["r"] == 2, by_register
    else:
        assert by_register["f"] == 5 and by_register["r"] == 1, by_register


@pytest.mark.slow  # a probe of the region NMS's depth: make test-full
@pytest.mark.parametrize(
    ("score_bits", "gated_flags", "levels"),
    [(12, True, 4), (8, True, 4), (12, False, 5)],
)
def test_deferred_key_path_depth(score_bits, gated_flags, levels, tmp_path):
    """The region NMS's key data path as key_flags models it (seven key registers, the
    pixel, the stack and table words), exact (no flags as inputs), with the keys resolved
    two columns behind the control: every register's pending choice is a mask over the
    window's atoms, the atoms are compared register to register (15 full-key and 13 score
    comparators, 4 levels) and each key resolved a clock later. With each register's
    flags gated by its mask in their flip-flops (the masks are known a clock ahead), the
    resolution maps into 4 levels and so does the whole data path; reading the masks in
    the resolution instead, 5."""
    generics = {
        "SCORE_BITS": score_bits,
        "POS_BITS": 22,
        "GATED_FLAGS": str(gated_flags).lower(),
    }
    cells = probe_cells("key_deferred", generics, tmp_path)
    assert cells["logic_levels"] == levels, cells
    by_register = levels_by_register(tmp_path / "key_deferred.v", "key_deferred")
    assert by_register["kr"] == levels, by_register


# Issue 37's clock target for the region NMS's AXI tops (ECP5-8, nextpnr).
TARGET_MHZ = 150


@pytest.mark.slow  # place and route of a probe: make test-full
def test_deferred_key_path_clock(tmp_path):
    """The deferred key data path alone (gated flags, no memory, no control around it)
    placed and routed on the ECP5-8 as `make synth` does: about issue 37's target with
    sad scores (12 bits), above it with opencv scores (8 bits), the slowest path mostly
    routing (docs/fastnms_nms_region.md, Depth and clock). Deterministic for the pinned
    tools and seed; the bounds say "about", not the figure."""
    fmax = {}
    for score_bits in (12, 8):
        generics = {"SCORE_BITS": score_bits, "POS_BITS": 22, "GATED_FLAGS": "true"}
        out = tmp_path / f"s{score_bits}"
        netlist, _ = ghdl_synth("key_deferred", generics, out, probe_sources("key_deferred"))
        design, _ = ecp5.yosys_ecp5(netlist, "key_deferred")
        result = ecp5.nextpnr_ecp5(design)
        path = result["critical_path"]
        print(score_bits, result["fmax_mhz"], path)
        assert path["routing_ns"] > path["logic_ns"], path
        fmax[score_bits] = result["fmax_mhz"]
    assert 0.93 * TARGET_MHZ <= fmax[12] <= 1.07 * TARGET_MHZ, fmax
    assert fmax[8] > TARGET_MHZ, fmax
