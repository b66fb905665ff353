"""The pyramid plan of docs/results.md (flows/report/pyramid.py and pyramid_memory.py):
the level sizes are the golden model's, the shares and rates, the BRAM18 of the
memories' formulas against hand-computed values, the RTL's constants and the measured
rows, and the section with and without the rows it takes its clocks from."""

from __future__ import annotations

import copy
import json
import re

import pytest
from fastnms.golden.pyramid import level_size
from fastnms.sim.sources import REPO

from flows.report import pyramid, pyramid_memory, report
from flows.report.orb_memory import ramb18
from flows.report.pyramid_memory import BY_KEY, PLAN, cost, levels, plan_cost, shares

RESIZE = {
    "config": "fastnms_resize-1920",
    "entity": "fastnms_resize",
    "generics": {"MAX_WIDTH": 1920, "MAX_HEIGHT": 1080},
    "lut": 900,
    "srl": 10,
    "lutram_luts": 40,
    "ff": 800,
    "bram18_equiv": 1,
    "dsp": 0,
    "logic_levels": 5,
    "ecp5_fmax_mhz": 171.3,
}


@pytest.fixture
def summary() -> list[dict]:
    """The committed synthesis summary without any resizer row."""
    rows = json.loads(report.SYNTH_JSON.read_text())
    return [r for r in rows if r["entity"] != "fastnms_resize"]


def test_level_sizes_are_the_golden_models():
    for size in PLAN["sizes"]:
        w, h = size["width"], size["height"]
        lv = levels(w, h)
        assert len(lv) == PLAN["levels"] == 8
        assert [(x.width, x.height) for x in lv] == [level_size(w, h, k) for k in range(8)]
        assert [x.src_width for x in lv] == [0] + [x.width for x in lv[:-1]]
    # The sizes of 1920x1080.
    assert [(x.width, x.height) for x in levels(1920, 1080)[1:]] == [
        (1600, 900),
        (1333, 750),
        (1111, 625),
        (926, 521),
        (772, 434),
        (643, 362),
        (536, 301),
    ]


def test_shares_and_rates():
    lv = levels(1920, 1080)
    s = shares(lv)
    assert s[0] == 1 and s[1] == 1600 * 900 / (1920 * 1080)
    assert abs(sum(s[1:]) / 2.10 - 1) < 0.01 and abs(sum(s) / 3.10 - 1) < 0.01
    l0, rest, total = pyramid.rates(lv, 60)
    assert l0 == pytest.approx(1920 * 1080 * 60 / 1e6) and total == pytest.approx(l0 + rest)
    # Budget cells by hand: ceil(W / 16) x ceil(H / 16).
    assert [x.cells for x in lv[:2]] == [120 * 68, 100 * 57]
    assert lv[7].cells == 34 * 19


def test_bram18_by_hand():
    """RAMB18 shapes: 16384 x 1, 8192 x 2, 4096 x 4, 2048 x 9, 1024 x 18, 512 x 36."""
    assert ramb18(1920, 8) == 1  # 1920 <= 2048: 9 bits wide, ceil(8 / 9)
    assert ramb18(1920, 48) == 6  # ceil(48 / 9)
    assert ramb18(1920, 240) == 27  # ceil(240 / 9)
    assert ramb18(120, 100) == 3  # 512 x 36: ceil(100 / 36)
    assert ramb18(4096, 8) == 2  # 4096 x 4
    assert ramb18(2048, 8) == 1 and ramb18(2049, 8) == 2
    lv = levels(1920, 1080)
    assert cost(BY_KEY["line"], lv[0]) == (1920 * 48, 6)
    assert cost(BY_KEY["nms"], lv[0]) == (1920 * 16, 2)
    assert cost(BY_KEY["budget"], lv[0]) == (2 * 120 * 4 * 25, 6)
    assert cost(BY_KEY["resizer"], lv[0]) == (0, 0)
    assert cost(BY_KEY["resizer"], lv[1]) == (1920 * 8, 1)  # the row above of level 0
    assert cost(BY_KEY["blurred"], lv[0]) == (37 * 2 * 2048 * 8, 74)
    assert cost(BY_KEY["blurred"], lv[4]) == (37 * 2 * 1024 * 8, 37)  # 926 wide: X = 10
    assert cost(BY_KEY["plain"], lv[4]) == (31 * 2 * 1024 * 8, 31)
    assert cost(BY_KEY["moments"], lv[0]) == (1920 * 240, 27)
    assert pyramid_memory.MOMENT_BITS == 42  # |m| <= 624 240: 21 signed bits each
    assert cost(BY_KEY["budget_m"], lv[0]) == (2 * 120 * 4 * 67, 2 * ramb18(120, 268))
    # Level 0 all on chip: 6 + 2 + 6 + 1 (queue) + 74 + 62.
    level0 = plan_cost(pyramid_memory.PLANS["all on chip"], lv[:1])
    assert level0[1] == 151
    # Once: the corner FIFO and the sampler's two 37-row copies (74 words of 37 pixels).
    assert pyramid_memory.once(lv) == (512 * (4 + 30 + 288) + 2 * 74 * 296, 9 + 18)


def test_formulas_follow_the_rtl():
    """The shapes written as data against the RTL's generic maps and constants."""
    # The detector's 7x7 window and the NMS's 3x3 keep WINDOW - 1 rows (6 and 2).
    window = (REPO / "rtl/common/fastnms_window.vhd").read_text()
    assert re.search(r"LINES\s*=> WINDOW - 1", window)
    fast = (REPO / "rtl/fast/fastnms_fast_pkg.vhd").read_text()
    assert (
        "constant RADIUS      : positive := 3;" in fast
        and "WINDOW_SIZE : positive := 2 * RADIUS + 1;" in fast
    )
    assert (
        "WINDOW       => WINDOW_SIZE," in (REPO / "rtl/fast/fastnms_fast_detector.vhd").read_text()
    )
    nms = (REPO / "rtl/nms/fastnms_nms_3x3.vhd").read_text()
    assert re.search(r"WINDOW\s*=> 3,\s*DATA_WIDTH\s*=> SCORE_BITS", nms)
    line = (REPO / "rtl/common/fastnms_line_buffer.vhd").read_text()
    assert re.search(r"DEPTH\s*=> MAX_WIDTH,\s*WIDTH\s*=> LINES \* DATA_WIDTH", line)
    resize = (REPO / "rtl/resize/fastnms_resize.vhd").read_text()
    assert re.search(r"row_above : entity work.fastnms_ram_sdp", resize)
    assert re.search(r"DEPTH\s*=> MAX_WIDTH,\s*WIDTH\s*=> 8,", resize)
    assert resize.count('STYLE        => "block"') == 1  # the one block RAM
    budget = (REPO / "rtl/budget/fastnms_cell_budget.vhd").read_text()
    assert "constant CELLS      : positive := (MAX_WIDTH + 15) / 16;" in budget
    assert "constant WORD_BITS  : positive := K_MAX * ENTRY_BITS;" in budget
    assert re.search(r"DEPTH\s*=> CELLS,\s*WIDTH\s*=> WORD_BITS", budget)
    pkg = (REPO / "rtl/budget/fastnms_budget_pkg.vhd").read_text()
    assert "return 1 + score_bits + 16;" in pkg


def test_formulas_against_the_measured_rows(summary):
    """At 1920x1080 the formulas give the BRAM18 yosys measured for the blocks alone."""
    lv = levels(1920, 1080)[0]
    expected = {
        "fastnms_line_buffer": cost(BY_KEY["line"], lv)[1],
        "fastnms_nms_3x3": cost(BY_KEY["nms"], lv)[1],
        "fastnms_orb_stage": sum(cost(BY_KEY[k], lv)[1] for k in ("queue", "blurred", "plain"))
        # the engine's patch copies in block RAM, once
        + sum(n * ramb18(w, b) for n, w, b in pyramid_memory.ONCE[1].shape(lv.orb)),
    }
    checked = 0
    for row in summary + [RESIZE]:
        g = row["generics"]
        if row["entity"] in expected and g.get("MAX_WIDTH") == 1920:
            assert row["bram18_equiv"] == expected[row["entity"]], row["config"]
            checked += 1
        budget = {"MAX_WIDTH": 1920, "MAX_PER_CELL": 4, "SCORE_BITS": 8}
        if row["entity"] == "fastnms_cell_budget" and budget.items() <= g.items():
            assert row["bram18_equiv"] == cost(BY_KEY["budget"], lv)[1]
            checked += 1
        if row["entity"] == "fastnms_resize" and g.get("MAX_WIDTH") == 1920:
            assert row["bram18_equiv"] == cost(BY_KEY["resizer"], levels(1920, 1080)[1])[1]
    assert checked >= 3


def test_options_and_engine_by_hand():
    """1080p60: level 0 at 124.4 Mpixel/s fits the paper's 134 MHz as (a), not (b)
    (2.10 times that); one engine at 134 MHz gives K 1 on every level."""
    text = "\n".join(pyramid.rate_lines(pyramid.configs(), []))
    row = next(line for line in text.splitlines() if line.startswith("| 1920x1080 (1080p) | 60"))
    assert row.endswith("| 385.2 | (a) · 3 | (a) · 3 |")  # at 134 and 148.5 MHz
    kitti = next(line for line in text.splitlines() if line.startswith("| 1241x376 (KITTI) | 60"))
    assert "(a), (b) · 1" in kitti
    text = "\n".join(pyramid.engine_lines(pyramid.configs(), []))
    cells = sum(x.cells for x in levels(1920, 1080))
    assert cells == 8160 + 5700 + 3948 + 2800 + 1914 + 1372 + 943 + 646
    row = next(line for line in text.splitlines() if line.startswith("| 1920x1080 (1080p) | 60"))
    share = round(100 * cells * 64 / (134e6 / 60))
    assert f"K 1 ({share} %); K 4: 3 engines" in row


def test_section_with_and_without_the_resizer(summary):
    without = pyramid.pyramid_section(summary)
    assert without.startswith(pyramid.HEADING + "\n")
    assert "Not measured in this summary (no ECP5 Fmax): the resizer." in without
    assert "| resizer | not in this summary |" in without
    assert "The totals leave out the blocks not in this summary." in without
    top = next(r for r in summary if r["config"] == "opencv-3x3-1920")
    assert f"{top['ecp5_fmax_mhz']:g} MHz" in without
    with_row = pyramid.pyramid_section([*summary, RESIZE])
    assert "171.3 MHz, ECP5 Fmax of the resizer (`fastnms_resize-1920`)" in with_row
    assert "| resizer | `fastnms_resize-1920` | 950 | 7 | 7 |" in with_row
    assert "not in this summary" not in with_row and "Not measured" not in with_row
    # A resizer placed without an Fmax, and no summary at all.
    unplaced = pyramid.pyramid_section([*summary, {**copy.deepcopy(RESIZE), "ecp5_fmax_mhz": None}])
    assert "no ECP5 Fmax): the resizer." in unplaced and "`fastnms_resize-1920` | 950" in unplaced
    bare = pyramid.pyramid_section(None)
    assert "### Pyramid plan: memory totals and DDR" in bare
    assert "logic of the options" not in bare and "134 MHz" in bare
    for text in (without, with_row, bare):
        for heading in ("level sizes", "pixel rates and pipelines", "memory per level"):
            assert f"\n### Pyramid plan: {heading}\n" in text


def test_page_links_land_on_the_section():
    """docs/pyramid.md links its figures to this section's headings."""
    page = (REPO / "docs/pyramid.md").read_text()
    links = set(re.findall(r"results\.md#(pyramid-plan[\w-]*)", page))
    assert "pyramid-plan-issue-54" in links and len(links) >= 4
    text = report.RESULTS.read_text()
    slugs = {
        re.sub(r"[^\w\- ]", "", t.strip().lower()).replace(" ", "-")
        for t in re.findall(r"^#+ (.+)$", text, re.M)
    }
    assert links <= slugs
