"""Synthesis regression: every entity synthesizes (GHDL), maps to xc7 cells
without latches and with at most 4 logic levels between registers (yosys
synth_xilinx), and the memories land in block RAM."""

from pathlib import Path

import pytest

from flows.synth.axi_top import levels_outside, synthesizable_top
from flows.synth.synth import (
    entities,
    flip_flops_reading,
    ghdl_synth,
    levels_by_register,
    netlist_problems,
    probe_sources,
    summary,
    yosys_xc7,
)

LATCHES = ("LDCE", "LDPE")
# The most LUT/CARRY4/MUXF/INV cells allowed between two registers.
MAX_LOGIC_LEVELS = 4
# Known exceptions, recorded so that they cannot grow unnoticed: the region NMS
# does a column of its connected-components step per clock, its decisions a
# clock ahead of its data path, which still compares keys, selects the best
# and routes it through a pop in one clock: yosys maps it into 7 levels,
# alone and inside a core; a merge of two keys in one clock alone takes 5
# (test_one_clock_key_merge_depth, docs/fastnms_nms_region.md, *Depth and clock*).
DEEPER = {
    # The same RTL maps to 4 or 5 levels depending on the netlist around it:
    # abc9 maps for delay in its own model (a LUT2 through pin I1 costs 127 ps,
    # a LUT6 through I0 642 ps, a block RAM's clock-to-out 2454 ps), in which
    # chains of small LUTs look fast and paths from flip-flops have slack, so
    # it builds such chains wherever sharing saves a LUT (docs/fastnms_core.md).
    "fastnms_core": MAX_LOGIC_LEVELS + 1,
    # Its FIFO (fastnms_fifo, 4 levels on its own at 512 words) maps one level
    # deeper beside the output stage: abc chains the FIFO's level flags.
    "fastnms_nms_serializer": MAX_LOGIC_LEVELS + 1,
    "fastnms_nms_region": 7,
    # Its parts alone, at their default generics (a port counts as a register, so
    # paths that cross parts are cut or joined differently than in the block): the
    # schedule's flush and prime chains and the keys' merge are the block's 7; the
    # control's decisions and the tables' reads ahead from the ports map into 5. The
    # keys alone map into 8 since the areas came in: abc chains the slot-0 flags of the
    # last table's write from the op port (in the block it still maps into 7).
    "fastnms_nms_region_schedule": 7,
    "fastnms_nms_region_keys": 8,
    "fastnms_nms_region_control": 5,
    "fastnms_nms_region_tables": 5,
    # The float32 units' carry chains are not split yet: the rounding increment into
    # the exponent (mul, add) and the 31-bit magnitude compare and 27-bit add (add)
    # are 6 to 8 CARRY4 long, and the angle unit adds its division step and
    # multiplexers (docs/orb_rtl.md, *Limits*).
    "fastnms_f32_mul": 8,
    "fastnms_f32_add": 11,
    "fastnms_orb_angle": 13,
    # The rotation's table fill: the rounding of |k| times a significand and the
    # entry's 32-bit add are one carry chain each (docs/orb_rtl.md, *Limits*); a
    # point's coordinate (fastnms_orb_round_point) takes 5 in its last stage.
    "fastnms_orb_rotate": 12,
    "fastnms_orb_round_point": 5,
    # The column moment T (16 bits) and the column sum (13) are adds of more than
    # 12 bits, one clock each.
    "fastnms_orb_moments": 5,
    # The ORB engine, and ORB after the budget around it: the angle units' depth.
    "fastnms_orb_describe": 13,
    "fastnms_orb_feed": 13,
    # The ORB row buffers: a request's top row split by ROMs (which of the
    # memories read the next slot: a 37-bit thermometer of a 7-bit row), which
    # abc maps into a compare chain (docs/orb_rtl.md, *The rows*).
    "fastnms_orb_rows": 5,
}
# Entities made of the ones above, several minutes in yosys: under make test-full.
# (The ORB blocks of more than a minute each; the float units' netlists are also simulated
# in tb/orb/test_orb_netlists.py.)
SLOW_SYNTH = (
    "fastnms_orb_describe",
    "fastnms_orb_feed",
    "fastnms_orb_stage",
    "fastnms_orb_cos_sin",
    "fastnms_mulhi64",
    "fastnms_orb_rotate",
)
LUTRAM = ("RAM32M", "RAM64M", "RAM32X1D", "RAM64X1D", "RAM128X1D", "RAM256X1S", "RAM32M16")


def bram18_equivalents(cells: dict[str, int]) -> int:
    return cells.get("RAMB18E1", 0) + 2 * cells.get("RAMB36E1", 0)


@pytest.fixture(autouse=True)
def _top_without_vivado_attributes():
    """fastnms_axi is synthesized from a copy without its X_INTERFACE
    attributes: GHDL 2.0's synthesis crashes on attributes of input ports
    (flows/synth/axi_top.py)."""
    with synthesizable_top():
        yield


# fastnms_axi at its default generics is test_axi_top_1920 below.
@pytest.mark.parametrize(
    "entity",
    [
        pytest.param(e, marks=pytest.mark.slow) if e in SLOW_SYNTH else e
        for e in entities()
        if e != "fastnms_axi"
    ],
)
def test_entity_synthesizes_without_latches(entity):
    netlist, messages = ghdl_synth(entity)
    assert "latch" not in messages.lower(), messages
    problems = netlist_problems(netlist, entity)
    assert not problems, problems
    cells = yosys_xc7(netlist, entity)
    print(entity, cells)
    assert not any(cells.get(c) for c in LATCHES), f"latches: {cells}"
    assert sum(cells.values()) > 0
    allowed = DEEPER.get(entity, MAX_LOGIC_LEVELS)
    assert cells["logic_levels"] <= allowed, f"logic levels: {cells}"


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
    """Detector + 3x3 NMS at MAX_WIDTH 1920: at most 5 logic levels (see DEEPER), the six
    pixel lines and the two score lines in block RAM (8 BRAM18-equivalents
    with 8-bit scores, 9 with 12-bit ones), no LUT RAM, no latches."""
    netlist, _ = ghdl_synth("fastnms_core", {"MAX_WIDTH": 1920, "SCORE": score, "NMS": "3x3"})
    cells = yosys_xc7(netlist, "fastnms_core")
    print(score, summary(cells))
    assert cells["logic_levels"] <= DEEPER["fastnms_core"], cells
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


def test_axi_top_1920():
    """fastnms_axi at its default generics (1920x1080, opencv, 3x3, FIFO 512):
    no latches, no LUT RAM, the core's 8 BRAM18 plus one for the corner FIFO,
    and at most 4 logic levels on every path that starts or ends outside
    fastnms_core. One more is tolerated inside the core: its two window
    generators have mapped to 5 levels at MAX_HEIGHT 1080 (fastnms_core alone
    at 1920x1080 does too), depending on how abc maps the whole design."""
    netlist, messages = ghdl_synth("fastnms_axi")
    assert "latch" not in messages.lower(), messages
    cells = yosys_xc7(netlist, "fastnms_axi")
    outside = levels_outside(netlist.with_suffix(".xc7.json"), "fastnms_axi")
    print(summary(cells), "logic levels outside the core:", outside)
    assert not any(cells.get(c) for c in LUTRAM + LATCHES), cells
    assert bram18_equivalents(cells) == 9, cells
    assert outside <= MAX_LOGIC_LEVELS, f"{outside} logic levels outside fastnms_core"
    assert cells["logic_levels"] <= MAX_LOGIC_LEVELS + 1, cells


@pytest.mark.parametrize("window", [3, 7])
@pytest.mark.parametrize("ppc", [1, 2, 4])
def test_window_3840_every_ppc(ppc, window):
    """The window generator of the detector (7x7) and of the 3x3 NMS at MAX_WIDTH
    3840 with 1, 2 and 4 pixels per clock: at most 4 logic levels on its own (its
    decisions each read a few registers), the lines in block RAM."""
    generics = {"MAX_WIDTH": 3840, "MAX_HEIGHT": 2160, "WINDOW": window, "PPC": ppc}
    netlist, _ = ghdl_synth("fastnms_window", generics)
    cells = yosys_xc7(netlist, "fastnms_window")
    print(generics, summary(cells))
    assert cells["logic_levels"] <= MAX_LOGIC_LEVELS, cells
    assert bram18_equivalents(cells) * 18 * 1024 >= 3840 * 8 * (window - 1), cells
    assert not any(cells.get(c) for c in LUTRAM + LATCHES), cells


@pytest.mark.parametrize(("score", "nms"), [("sad", "region4"), ("opencv", "region8")])
def test_core_region_1920(score, nms):
    """Detector + region NMS at 1920x1080: no latches; the detector's 6 BRAM18-equivalents
    and the region NMS's 4 (the data table's keys: 2; stack: 2); LUT RAM only for the
    region NMS's bit memories (row memory 960 x 2, head table 2 x 960 x 1, last table
    960 x 1: 15 + 30 + 15 RAM64M; the stack's flags 479 x 3: 8 RAM64M), the data table's
    areas (960 x 12: 60 RAM64M), its record FIFO (8 words of 1 + 11 + 11 + score + 11
    bits: 8 RAM32M with the 12-bit sad score, 7 with opencv's 8) and the core's
    configuration queue (8 frames' MIN_AREA, 11 bits: 2 RAM32M); the region NMS's logic
    depth (see DEEPER) not exceeded."""
    generics = {"MAX_WIDTH": 1920, "MAX_HEIGHT": 1080, "SCORE": score, "NMS": nms}
    netlist, messages = ghdl_synth("fastnms_core", generics)
    assert "latch" not in messages.lower(), messages
    cells = yosys_xc7(netlist, "fastnms_core")
    print(score, nms, summary(cells))
    assert not any(cells.get(c) for c in LATCHES), cells
    lutram = {c: n for c, n in cells.items() if c in LUTRAM and n}
    assert lutram == {"RAM64M": 128, "RAM32M": (8 if score == "sad" else 7) + 2}, cells
    assert bram18_equivalents(cells) == 10, cells
    assert cells["logic_levels"] <= DEEPER["fastnms_nms_region"], cells


def probe_cells(entity: str, generics: dict[str, object], tmp_path: Path) -> dict[str, int]:
    """A probe of flows/synth/probes (entity in the file of its name, which may use
    fastnms_pkg) through the core's synthesis flow: its xc7 cell counts and logic levels."""
    netlist, _ = ghdl_synth(entity, generics, tmp_path, probe_sources(entity))
    cells = yosys_xc7(netlist, entity)
    print(entity, generics, summary(cells))
    return cells


@pytest.mark.slow  # a probe of the region NMS's depth: make test-full
@pytest.mark.parametrize(
    ("key_bits", "order_flag", "levels"),
    [(34, False, 5), (30, False, 5), (12, True, 3), (8, True, 3)],
)
def test_one_clock_key_merge_depth(key_bits, order_flag, levels, tmp_path):
    """The floor under the region NMS's depth in this flow: two key registers merged in
    one clock (the better key chosen, the choice a register) map into 5 levels with the
    region NMS's keys (score, row, column: 34 bits with sad scores at 1920x1080, 30 with
    opencv), 3 when the keys are scores (12, 8 bits) and the raster order of the two
    pixels is a register beside them. Exact, so that docs/fastnms_nms_region.md (Depth and clock)
    follows the tools."""
    generics = {"KEY_BITS": key_bits, "ORDER_FLAG": str(order_flag).lower()}
    cells = probe_cells("key_merge", generics, tmp_path)
    assert cells["logic_levels"] == levels, cells
    # The depth is in front of the merged key register, by name (synth.py --registers).
    by_register = levels_by_register(tmp_path / "key_merge.v", "key_merge")
    assert by_register["a"] == levels and by_register["a_r"] == 0, by_register


@pytest.mark.slow  # a probe of the region NMS's depth: make test-full
@pytest.mark.parametrize(("key_bits", "levels"), [(34, 4), (30, 4), (12, 2)])
def test_registered_key_compare_depth(key_bits, levels, tmp_path):
    """A region key comparison as a stage of its own (two key registers in, the result a
    register) maps into 4 levels with the region NMS's 34- and 30-bit keys, 2 with a
    12-bit score: a design that compares full keys a clock ahead has no level left in
    that stage for anything else. Exact, so that docs/fastnms_nms_region.md (Depth and clock)
    follows the tools."""
    cells = probe_cells("key_compare", {"KEY_BITS": key_bits}, tmp_path)
    assert cells["logic_levels"] == levels, cells


@pytest.mark.slow  # a probe of the region NMS's depth: make test-full
@pytest.mark.parametrize(
    ("score_bits", "compared_ahead", "levels"),
    [(12, False, 6), (8, False, 7), (12, True, 3), (8, True, 3)],
)
def test_key_step_depth(score_bits, compared_ahead, levels, tmp_path):
    """The region NMS data path's key selection for one column (the merge of its base,
    the class merging in and the pixel; the current class; the pop's choice; the table
    write) with the tie rule as order flags (scores compared in the clock) maps into 6 or
    7 levels, as many as the block: order flags alone do not reach 4. With every
    comparison of the column a register, 3: a 4-level data path needs its comparisons
    made a clock ahead. Exact, so that docs/fastnms_nms_region.md (Depth and clock) follows the
    tools."""
    generics = {
        "SCORE_BITS": score_bits,
        "POS_BITS": 22,
        "COMPARED_AHEAD": str(compared_ahead).lower(),
    }
    cells = probe_cells("key_step", generics, tmp_path)
    assert cells["logic_levels"] == levels, cells


@pytest.mark.parametrize(
    ("decided_ahead", "pixel_ahead", "levels"),
    [
        # Each takes one to three minutes to map: all under `make test-full`.
        pytest.param(False, True, 5, marks=pytest.mark.slow),
        pytest.param(False, False, 6, marks=pytest.mark.slow),
        pytest.param(True, False, 8, marks=pytest.mark.slow),
        pytest.param(True, True, 7, marks=pytest.mark.slow),
    ],
)
def test_key_flags_depth(decided_ahead, pixel_ahead, levels, tmp_path):
    """The region NMS data path's keys with every comparison kept up to date as order
    flags (one per pair of its seven key registers, one per register against the pixel;
    keys from memories come with their flags as inputs, so a lower bound) maps into 6
    levels, 5 with the next pixel's comparisons made a clock ahead, 8 and 7 with the
    column's decision itself made a clock ahead from the next flags: none of these
    reaches 4. tb/probes/ simulates the probe against a model. Exact, so that
    docs/fastnms_nms_region.md (Depth and clock) follows the tools."""
    generics = {
        "SCORE_BITS": 12,
        "POS_BITS": 22,
        "DECIDED_AHEAD": str(decided_ahead).lower(),
        "PIXEL_AHEAD": str(pixel_ahead).lower(),
    }
    cells = probe_cells("key_flags", generics, tmp_path)
    assert cells["logic_levels"] == levels, cells


@pytest.mark.slow  # a probe of the region NMS's depth: make test-full
@pytest.mark.parametrize("connectivity", [4, 8])
def test_step_control_depth(connectivity, tmp_path):
    """The region NMS step's control alone (its flags and decisions, from registered
    inputs to a registered operation code, no slot, key or address) maps into 3 levels,
    against 7 for the whole step: the depth is in routing slots and keys by decisions
    made in the same clock, which a 4-level design must do a clock after them. Exact,
    so that docs/fastnms_nms_region.md (Depth and clock) follows the tools."""
    cells = probe_cells("step_control", {"CONNECTIVITY": connectivity}, tmp_path)
    assert cells["logic_levels"] == 3, cells


@pytest.mark.parametrize("ping_pong", [False, True])
def test_skid_buffer_handshake_fanout(ping_pong):
    """The ping-pong style's in_valid and out_ready reach its four control
    flip-flops only; the main/skid style's out_ready reaches every data
    register too (the contrast shows that the count sees enables)."""
    width = 34
    netlist, _ = ghdl_synth("fastnms_skid_buffer", {"WIDTH": width, "PING_PONG": ping_pong})
    cells = yosys_xc7(netlist, "fastnms_skid_buffer")
    mapped = netlist.with_suffix(".xc7.json")
    readers = {
        p: flip_flops_reading(mapped, "fastnms_skid_buffer", p) for p in ("in_valid", "out_ready")
    }
    print(ping_pong, summary(cells), "flip-flops reading:", readers)
    assert cells["logic_levels"] <= 2, cells
    if ping_pong:
        assert max(readers.values()) <= 4, readers
    else:
        assert readers["out_ready"] >= 2 * width, readers


# ---- the ORB rows of `make synth` (issue 36), without synthesizing ------------------


def test_orb_entries_have_the_cores_generics():
    """The ORB rows: the top `opencv-3x3-orb-1920` with the issue's generics, and the
    stage with the generics fastnms_core gives fastnms_orb_stage (LANES, MAX_CELL,
    MAX_PER_CELL as the core's generic map computes them), the budget beside it; all
    placed on the LFE5U-85F."""
    import re

    from flows.synth import summary as synth_summary

    rows = {r.entity: r for r in synth_summary.orb_entries(1920, 1080)}
    top = rows["fastnms_axi"]
    assert top.config == "opencv-3x3-orb-1920"
    assert top.generics == {
        "MAX_WIDTH": 1920,
        "MAX_HEIGHT": 1080,
        "SCORE": "opencv",
        "NMS": "3x3",
        "MAX_PER_CELL": 4,
        "DESCRIPTOR": "orb",
        "ORB_MAX_CELL": 16,
    }
    stage = rows["fastnms_orb_stage"].generics
    core = (Path(__file__).resolve().parents[2] / "rtl" / "core" / "fastnms_core.vhd").read_text()
    lanes = re.search(
        r"orb_keypoints : entity work.fastnms_orb_stage.*?LANES\s*=>\s*(\d+)", core, re.S
    )
    assert lanes and stage["LANES"] == int(lanes.group(1))
    assert stage["MAX_CELL"] == top.generics["ORB_MAX_CELL"]  # 2 ** (ORB_CELL_LOG + 4)
    assert stage["MAX_PER_CELL"] == top.generics["MAX_PER_CELL"]
    assert stage["SCORE_BITS"] == 8  # opencv
    assert rows["fastnms_cell_budget"].generics == {
        "MAX_WIDTH": 1920,
        "MAX_HEIGHT": 1080,
        "SCORE_BITS": 8,
        "MAX_PER_CELL": 4,
    }
    assert all(r.orb_table and r.ecp5_device == "85k" for r in rows.values())
    # `make synth`'s default entities: the configurations' rows, then the ORB rows once.
    per_config = synth_summary.entries("opencv", "3x3", 1920, 1080, synth_summary.ENTITIES)
    assert [r.entity for r in per_config][:2] == ["fastnms_axi", "fastnms_core"]
    assert not any(r.orb_table for r in per_config)


def test_orb_rows_in_the_flow(monkeypatch, tmp_path):
    """summary.run with `orb` alone: the three ORB rows, flagged, each synthesized once,
    the place and route of the top on the 85F with the timeout, a design that does not
    fit recorded as such (the tools replaced by fakes)."""
    from flows.synth import summary as synth_summary

    def fake_ghdl(entity, generics, out_dir, sources=None):
        out_dir.mkdir(parents=True, exist_ok=True)
        netlist = out_dir / f"{entity}.v"
        netlist.write_text("// fake\n")
        return netlist, ""

    calls = []

    def fake_xc7(netlist, entity):
        return {
            "lut": 100,
            "ff": 50,
            "bram18_equiv": 2,
            "dsp": 1,
            "logic_levels": 3,
            "carry4": 4,
            "xc7_seconds": 1,
        }

    def fake_ecp5(netlist, entity, seed, extra, device, timeout):
        calls.append((entity, device, timeout))
        return {
            "ecp5_fmax_mhz": None,
            "ecp5_result": "does not fit LFE5U-85F: DP16KD 300/208",
            "ecp5": {"device_key": device, "nextpnr_seconds": 1.0, "yosys_seconds": 1.0},
        }

    monkeypatch.setattr(synth_summary.synth, "ghdl_synth", fake_ghdl)
    monkeypatch.setattr(synth_summary, "xc7_figures", fake_xc7)
    monkeypatch.setattr(synth_summary, "ecp5_figures", fake_ecp5)
    summary, info = synth_summary.run(
        [], entities=["orb"], ecp5_for="top", root=tmp_path, ecp5_timeout=60, log=lambda s: None
    )
    assert [r["config"] for r in summary] == [
        "opencv-3x3-orb-1920",
        "fastnms_orb_stage-opencv-1920",
        "fastnms_cell_budget-opencv-k4-1920",
    ]
    assert all(r["orb_table"] and not r["ppc_table"] for r in summary)
    assert calls == [("fastnms_axi", "85k", 60)]
    assert summary[0]["ecp5_result"].startswith("does not fit")
    assert info["distinct_syntheses"] == 3 and info["ecp5_runs"] == 1
    assert "85F" in info["ecp5_orb_device"]
    # `make synth`'s default entities with a configuration, rendered into the section.
    from flows.report import report

    summary, info = synth_summary.run(
        [("opencv", "3x3")], ecp5_for="none", root=tmp_path, log=lambda s: None
    )
    orb = [r["config"] for r in summary if r["orb_table"]]
    assert orb == ["opencv-3x3-orb-1920", "fastnms_orb_stage-opencv-1920", orb[2]]
    assert summary[0]["config"] == "opencv-3x3-1920"
    text = report.synth_section(summary, info)
    assert "### ORB descriptors (issue 36)" in text and "| ORB + budget |" in text
    assert "`opencv-3x3-orb-1920`" not in text.split("### Side by side")[1].split("###")[1]


def test_nextpnr_does_not_fit_or_timeout(monkeypatch, tmp_path):
    """nextpnr stopping on an over-used resource, or running past the timeout, is a
    result (fmax None, the reason), not an error."""
    import subprocess

    from flows.synth import ecp5

    log = (
        "Info: Logic utilisation before packing:\n"
        "Info:     Total LUT4s:     50000/83640    59%\n"
        "Info: Device utilisation:\n"
        "Info: \t          DP16KD:   178/  108   164%\n"
        "Info: \t      MULT18X18D:    21/   72    29%\n"
        "ERROR: Unable to place cell 'x', no BELs remaining to implement cell type 'DP16KD'\n"
    )
    assert ecp5.over_used(log) == {"DP16KD": (178, 108)}

    def failing(cmd, **kwargs):
        return subprocess.CompletedProcess(cmd, 1, log, "")

    design = tmp_path / "top.ecp5.json"
    design.write_text("{}")
    monkeypatch.setattr(ecp5.subprocess, "run", failing)
    result = ecp5.nextpnr_ecp5(design, device="45k")
    assert result["fmax_mhz"] is None
    assert result["does_not_fit"] == "does not fit LFE5U-45F: DP16KD 178/108"
    assert "--45k" not in ecp5.DEVICES["85k"]["args"] and "--85k" in ecp5.DEVICES["85k"]["args"]

    def slow(cmd, **kwargs):
        raise subprocess.TimeoutExpired(cmd, kwargs["timeout"], b"Info: placing\n")

    monkeypatch.setattr(ecp5.subprocess, "run", slow)
    result = ecp5.nextpnr_ecp5(design, device="85k", timeout=5)
    assert result["fmax_mhz"] is None and "timeout 5 s" in result["timed_out"]
    assert "LFE5U-85F" in result["device"]
