"""Generic checks: every entity with generics refuses an illegal value with its
own `assert ... report "<entity>: ..." severity failure`, and elaborates
cleanly at its defaults. The RTL is analysed once into a temporary library;
each case is a GHDL elaboration run to time 0."""

from __future__ import annotations

import re
import subprocess

import pytest
from fastnms.sim.sources import rtl_sources

# Entity -> (an illegal generic set, the start of its assertion message).
ILLEGAL = {
    "fastnms_counter": ({"SEGMENT": 1}, "SEGMENT must be at least 2"),
    "fastnms_fifo": ({"DEPTH": 70000}, "DEPTH must be at most 65536"),
    "fastnms_line_buffer": ({"READ_LATENCY": 3}, "READ_LATENCY must be 1 or 2"),
    "fastnms_position": ({"X_BITS": 17}, "X_BITS and Y_BITS must be at most 16"),
    "fastnms_ram_sdp": ({"STYLE": "ultra"}, "STYLE must be"),
    "fastnms_window": ({"WINDOW": 4}, "WINDOW must be odd and at least 3"),
    "fastnms_fast_detector": ({"MAX_WIDTH": 6}, "MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"),
    "fastnms_nms_3x3": ({"MAX_HEIGHT": 2}, "MAX_WIDTH and MAX_HEIGHT must be in 3 .. 65535"),
    "fastnms_nms_none": ({"MAX_HEIGHT": 70000}, "MAX_WIDTH must be in 2 .. 65535"),
    "fastnms_nms_region": ({"MAX_WIDTH": 2}, "MAX_WIDTH must be at least 3"),
    "fastnms_nms_region_schedule": ({"MAX_WIDTH": 2}, "MAX_WIDTH must be at least 3"),
    "fastnms_nms_region_tables": ({"MAX_WIDTH": 2}, "MAX_WIDTH must be at least 3"),
    "fastnms_nms_region_control": ({"MAX_WIDTH": 2}, "MAX_WIDTH must be at least 3"),
    "fastnms_nms_region_keys": ({"MAX_WIDTH": 2}, "MAX_WIDTH must be at least 3"),
    "fastnms_nms_serializer": ({"PPC": 3}, "PPC must be 2 or 4"),
    "fastnms_cell_budget": ({"MAX_PER_CELL": 16}, "MAX_PER_CELL must be 0 .. 15"),
    "fastnms_budget_insert": ({"K_MAX": 16}, "K_MAX must be 1 .. 15"),
    "fastnms_budget_decode": ({"K_MAX": 16}, "K_MAX must be 1 .. 15"),
    "fastnms_orb_rotate": ({"LANES": 3}, "LANES must be 1, 2, 4, 8 or 16"),
    "fastnms_orb_sample": ({"LANES": 3}, "LANES must be 2, 4, 8 or 16"),
    "fastnms_orb_describe": ({"LANES": 3}, "LANES must be 2, 4, 8 or 16"),
    "fastnms_orb_rows": ({"HEIGHT": 1}, "HEIGHT must be at least 2"),
    "fastnms_orb_feed": ({"MAX_CELL": 20}, "MAX_CELL must be 16, 32, 64, 128 or 256"),
    "fastnms_orb_stage": ({"MAX_PER_CELL": 16}, "MAX_PER_CELL must be 1 .. 15"),
    "fastnms_resize_scale": ({"SIZE_BITS": 13}, "SIZE_BITS must be at most 12"),
    "fastnms_resize_taps": ({"SIZE_BITS": 13}, "SIZE_BITS must be at most 12"),
    "fastnms_resize": ({"MAX_WIDTH": 5000}, "MAX_WIDTH and MAX_HEIGHT must be at most 4095"),
    "fastnms_core": ({"NMS": "5x5"}, "NMS must be"),
    "fastnms_axi_regs": ({"CORNER_FIFO_DEPTH": 70000}, "CORNER_FIFO_DEPTH must be below 65536"),
    "fastnms_axil_slave": ({"WORDS": 2000}, "WORDS must fit in the ADDR_WIDTH space"),
    "fastnms_corner_pack": ({"X_BITS": 30, "Y_BITS": 30}, "X_BITS + Y_BITS + SCORE_BITS + 2"),
    "fastnms_record_beats": ({"BEATS": 17}, "BEATS must be 1 .. 16"),
    "fastnms_record_output": ({"FIFO_DEPTH": 4}, "FIFO_DEPTH must be at least 8"),
    "fastnms_video_check": ({"MAX_WIDTH": 6}, "MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"),
    "fastnms_axi": ({"NMS": "5x5"}, "NMS must be"),
}
# Entities whose generics have no illegal value beyond their VHDL subtype
# (GHDL refuses those at elaboration already).
NOTHING_TO_CHECK = {
    "fastnms_skid_buffer": "WIDTH: any positive width works",
    "fastnms_resize_walk": "SIZE_BITS: any positive width works (a count of positions)",
    "fastnms_video_gate": "DATA_WIDTH: any positive width works",
}
# More illegal values of entities with several checks: (entity, generics, message).
MORE = [
    ("fastnms_ram_sdp", {"READ_LATENCY": 3}, "READ_LATENCY must be 1 or 2"),
    ("fastnms_core", {"SCORE": "harris"}, 'SCORE must be "opencv" or "sad"'),
    (
        "fastnms_core",
        {"NMS": "region4", "MAX_PER_CELL": 4},
        "the budget (MAX_PER_CELL > 0) takes records in raster order",
    ),
    ("fastnms_core", {"MAX_PER_CELL": 16}, "MAX_PER_CELL must be 0 .. 15"),
    ("fastnms_budget_decode", {"Y_BITS": 17}, "X_BITS and Y_BITS must be at most 16"),
    ("fastnms_axi_regs", {"MAX_PER_CELL": 16}, "MAX_PER_CELL must be 0 .. 15"),
    ("fastnms_axi_regs", {"DESCRIPTOR": "sift"}, 'DESCRIPTOR must be "none" or "orb"'),
    ("fastnms_axi_regs", {"ORB_MAX_CELL": 8}, "ORB_MAX_CELL must be at least 16"),
    ("fastnms_record_output", {"DESCRIPTOR": "sift"}, 'DESCRIPTOR must be "none" or "orb"'),
    ("fastnms_record_output", {"X_BITS": 17}, "X_BITS, Y_BITS and SCORE_BITS must fit"),
    (
        "fastnms_record_output",
        {"DESCRIPTOR": "orb", "AREA": True},
        'AREA (the region NMS) and DESCRIPTOR "orb" do not go together',
    ),
    ("fastnms_axi", {"DESCRIPTOR": "orb"}, 'DESCRIPTOR must be "none" or "orb"; "orb" needs PPC 1'),
    ("fastnms_core", {"MAX_HEIGHT": 70000}, "MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"),
    ("fastnms_fast_detector", {"SCORE": "harris"}, 'SCORE must be "opencv" or "sad"'),
    ("fastnms_nms_region", {"CONNECTIVITY": 6}, "CONNECTIVITY must be 4 or 8"),
    ("fastnms_nms_region_control", {"CONNECTIVITY": 6}, "CONNECTIVITY must be 4 or 8"),
    ("fastnms_axi", {"MAX_WIDTH": 6}, "MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"),
    ("fastnms_window", {"READ_LATENCY": 3}, "READ_LATENCY must be 1 or 2"),
    ("fastnms_window", {"PPC": 3}, "PPC must be 1, 2 or 4"),
    ("fastnms_window", {"PPC": 4, "MAX_WIDTH": 30}, "MAX_WIDTH must be a multiple of PPC"),
    ("fastnms_nms_serializer", {"DEPTH": 2}, "DEPTH must be at least 4"),
    ("fastnms_fifo", {"ALMOST_FULL_LEVEL": 513}, "ALMOST_FULL_LEVEL must be within 1 .. DEPTH"),
    ("fastnms_core", {"PPC": 4, "NMS": "region4"}, 'NMS "region4" takes one pixel per clock'),
    ("fastnms_core", {"PPC": 3}, "PPC must be 1, 2 or 4"),
    ("fastnms_core", {"DESCRIPTOR": "sift"}, 'DESCRIPTOR must be "none" or "orb"'),
    (
        "fastnms_core",
        {"DESCRIPTOR": "orb", "MAX_PER_CELL": 0},
        'DESCRIPTOR "orb" takes PPC 1, NMS "3x3" or "none" and a budget',
    ),
    (
        "fastnms_core",
        {"DESCRIPTOR": "orb", "MAX_PER_CELL": 4, "ORB_MAX_CELL": 48},
        "ORB_MAX_CELL must be 16, 32, 64, 128 or 256",
    ),
    ("fastnms_axi", {"PPC": 2, "NMS": "region8"}, 'only NMS "3x3" and "none" take 2 or 4'),
    ("fastnms_nms_none", {"PPC": 4, "MAX_WIDTH": 30}, "PPC must be 1, 2 or 4, and MAX_WIDTH"),
    ("fastnms_axi", {"PPC": 4, "MAX_WIDTH": 1918}, "PPC must be 1, 2 or 4, and MAX_WIDTH"),
    ("fastnms_video_check", {"PPC": 3}, "PPC must be 1, 2 or 4"),
    (
        "fastnms_axi",
        {"DESCRIPTOR": "orb", "MAX_PER_CELL": 5, "ORB_MAX_CELL": 16},
        'with DESCRIPTOR "orb", MAX_PER_CELL must be at most ORB_MAX_CELL ** 2 / 64',
    ),
    ("fastnms_core", {"TEST_FAULT": "rows"}, 'TEST_FAULT must be "none" or "config"'),
    ("fastnms_orb_stage", {"TEST_FAULT": "config"}, 'TEST_FAULT must be "none", "rows"'),
    ("fastnms_orb_feed", {"TEST_FAULT": "count"}, 'TEST_FAULT must be "none", "rows"'),
]

_GENERIC = re.compile(r"\bentity\s+(\w+)\s+is\s+generic\s*\(", re.IGNORECASE)


def entities_with_generics() -> set[str]:
    found = set()
    for f in rtl_sources():
        code = re.sub(r"--[^\n]*", "", f.read_text())
        found.update(m.lower() for m in _GENERIC.findall(code))
    return found


@pytest.fixture(scope="module")
def workdir(tmp_path_factory):
    """The RTL analysed once into a temporary GHDL library."""
    work = tmp_path_factory.mktemp("ghdl_generics")
    files = [str(f) for f in rtl_sources()]
    subprocess.run(
        ["ghdl", "-a", "--std=08", f"--workdir={work}", *files],
        cwd=work,
        check=True,
        capture_output=True,
        text=True,
    )
    return work


def elaborate(work, entity: str, generics: dict[str, object]) -> str:
    """Elaborate `entity` and run it to time 0 (where the concurrent assertions
    run); every assertion is reported, none stops the run. Returns GHDL's output."""
    cmd = ["ghdl", "--elab-run", "--std=08", f"--workdir={work}", entity]
    cmd += [f"-g{k}={v}" for k, v in generics.items()]
    cmd += ["--assert-level=none", "--stop-time=0ns", "--ieee-asserts=disable"]
    proc = subprocess.run(cmd, cwd=work, capture_output=True, text=True, timeout=120)
    return proc.stdout + proc.stderr


def test_every_entity_with_generics_is_listed():
    assert entities_with_generics() == set(ILLEGAL) | set(NOTHING_TO_CHECK)


@pytest.mark.parametrize(
    ("entity", "generics", "message"),
    [(e, g, m) for e, (g, m) in ILLEGAL.items()] + MORE,
    ids=lambda v: v if isinstance(v, str) and v.startswith("fastnms") else None,
)
def test_illegal_generic_fails(workdir, entity, generics, message):
    out = elaborate(workdir, entity, generics)
    want = f"(assertion failure): {entity}: {message}"
    assert want in out, f"{entity} {generics}: no {want!r} in\n{out}"


@pytest.mark.parametrize("entity", sorted(set(ILLEGAL) | set(NOTHING_TO_CHECK)))
def test_defaults_elaborate(workdir, entity):
    out = elaborate(workdir, entity, {})
    assert "assertion failure" not in out and "error" not in out.lower(), out
