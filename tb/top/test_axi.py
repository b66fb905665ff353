"""pytest entry: fastnms_axi, the AXI top level, under cocotb (tb/top/axi_*_tb.py).

Each cocotb test is a pytest item of its own, `<configuration>-<cocotb test>`:
`pytest "tb/top/test_axi.py::test_axi_robustness[opencv-3x3-live_mode]"` runs that one
test alone, with the seed of its node id (tb/harness.py)."""

from __future__ import annotations

import ast
import importlib.util
import json
import subprocess
from pathlib import Path

import numpy as np
import pytest
from fastnms.sim.records import decode_records
from fastnms.testing import images as testimages

from tb.harness import run_cocotb

REPO = Path(__file__).resolve().parents[2]

# The cocotb module that holds each cocotb test of the top.
MODULE = {
    **dict.fromkeys(["registers", "registers_random"], "axi_registers_tb"),
    **dict.fromkeys(
        [
            "generated_frames",
            "region_filter",
            "real_images",
            "empty_frame",
            "score_video",
            "throughput",
        ],
        "axi_frames_tb",
    ),
    **dict.fromkeys(
        [
            "malformed_then_good",
            "reset_mid_frame",
            "interrupt_and_enable",
            "fifo_full",
            "valids_low_in_reset",
        ],
        "axi_robustness_tb",
    ),
    **dict.fromkeys(["live_mode", "live_config_writes"], "axi_live_tb"),
    "budget_frames": "axi_budget_tb",
    **dict.fromkeys(["internal_error", "resets_mid_frame"], "axi_errors_tb"),
    "orb_live_back_to_back": "axi_orb_live_tb",
}


def each(configs: list, testcases: list[str]) -> list:
    """Every configuration (a pytest.param with an id) with every cocotb test: one pytest
    item each, id `<configuration>-<test>`, with the configuration's marks (slow)."""
    return [
        pytest.param(*c.values, test, id=f"{c.id}-{test}", marks=c.marks)
        for c in configs
        for test in testcases
    ]


def test_axi_modules():
    """MODULE names every cocotb test of tb/top/axi_*_tb.py (axi_orb_tb's aside, run
    whole by test_axi_orb) with the module that holds it (no simulation)."""
    found = {}
    for path in sorted(Path(__file__).parent.glob("axi_*_tb.py")):
        if path.stem == "axi_orb_tb":
            continue
        for node in ast.parse(path.read_text()).body:
            if isinstance(node, ast.AsyncFunctionDef) and any(
                ast.unparse(d).startswith("cocotb.test") for d in node.decorator_list
            ):
                found[node.name] = path.stem
    assert found == MODULE


def run_axi(request, generics: dict, testcase: str, env: dict | None = None) -> None:
    """One cocotb test of the top, from the module that holds it."""
    run_cocotb(
        "fastnms_axi",
        MODULE[testcase],
        generics,
        testcase=testcase,
        name=request.node.nodeid,
        env=env,
    )


SMALL = {"MAX_WIDTH": 64, "MAX_HEIGHT": 48, "SCORE_VIDEO": True, "CORNER_FIFO_DEPTH": 64}
PHOTO = {"MAX_WIDTH": 320, "MAX_HEIGHT": 240}
PHOTO_BUDGET = {"MAX_WIDTH": 128, "MAX_HEIGHT": 96, "CORNER_FIFO_DEPTH": 64}
# (SCORE, NMS) variants of fastnms_core; one line per variant.
VARIANTS = [
    ("opencv", "3x3"),
    ("sad", "3x3"),
    ("opencv", "none"),
    ("sad", "none"),
    ("sad", "region4"),
    ("sad", "region8"),
]


# make test: each NMS once (region4 in test_axi_robustness); every variant in make test-full.
QUICK_VARIANTS = {("opencv", "3x3"), ("sad", "none"), ("sad", "region8")}
FRAME_CASES = [
    pytest.param(s, n, id=f"{s}-{n}", marks=[] if (s, n) in QUICK_VARIANTS else [pytest.mark.slow])
    for s, n in VARIANTS
]
FRAME_TESTS = ["registers", "generated_frames", "empty_frame", "score_video", "region_filter"]


@pytest.mark.parametrize(("score", "nms", "testcase"), each(FRAME_CASES, FRAME_TESTS))
def test_axi_frames(request, score, nms, testcase):
    """Registers, generated images back to back with AXI-Lite reconfiguration, the
    empty frame, the score video and MIN_AREA, with input idles and output stalls."""
    run_axi(
        request,
        {**SMALL, "SCORE": score, "NMS": nms},
        testcase,
        env={"TB_IDLE": "0.2", "TB_STALL": "0.3"},
    )


# opencv + 3x3 in `make test`; sad + region4 (the region NMS) in `make test-full`.
ROBUSTNESS_CASES = [
    pytest.param("opencv", "3x3", id="opencv-3x3"),
    pytest.param("sad", "region4", marks=pytest.mark.slow, id="sad-region4"),
]
ROBUSTNESS_TESTS = [
    "malformed_then_good",
    "reset_mid_frame",
    "interrupt_and_enable",
    "fifo_full",
    "valids_low_in_reset",
    "live_mode",
    "live_config_writes",
]


@pytest.mark.parametrize(("score", "nms", "testcase"), each(ROBUSTNESS_CASES, ROBUSTNESS_TESTS))
def test_axi_robustness(request, score, nms, testcase):
    """Malformed frames, aresetn and soft reset mid-frame, interrupt, enable,
    the corner FIFO filling, VALIDs low in reset, the live-camera mode. With the
    region NMS too: it relies on the detector's stream being well formed
    whatever the input (its in_sof assertion would stop the simulation)."""
    run_axi(
        request,
        {**SMALL, "SCORE": score, "NMS": nms},
        testcase,
        env={"TB_IDLE": "0.1", "TB_STALL": "0.2"},
    )


# All in `make test-full`: in `make test` the fast engine runs the budget through the
# top at PPC 4 and 1920x1080 (sim/tests/test_engines.py::test_budget_at_full_hd), the
# command line at PPC 1 on both engines (cli/tests/test_sim_cli.py), and ORB's test here
# runs it through the top under cocotb (test_axi_orb).
BUDGET_CASES = [
    pytest.param("opencv", "3x3", 1, 15, marks=pytest.mark.slow, id="opencv-3x3-ppc1-k15"),
    pytest.param("sad", "none", 1, 4, marks=pytest.mark.slow, id="sad-none-ppc1-k4"),
    pytest.param("opencv", "3x3", 4, 15, marks=pytest.mark.slow, id="opencv-3x3-ppc4-k15"),
]
BUDGET_TESTS = ["registers", "budget_frames", "live_config_writes"]


@pytest.mark.parametrize(("score", "nms", "ppc", "k", "testcase"), each(BUDGET_CASES, BUDGET_TESTS))
def test_axi_budget(request, score, nms, ppc, k, testcase):
    """The keypoint budget in the top (MAX_PER_CELL = k): the BUDGET register's
    clamping, budgeted frames back to back with every CELL and several K, photograph
    crops, LIVE mode with noise at t = 0 at full width, aresetn mid-frame; input
    idles and output stalls."""
    run_axi(
        request,
        {**PHOTO_BUDGET, "SCORE": score, "NMS": nms, "PPC": ppc, "MAX_PER_CELL": k},
        testcase,
        env={
            "TB_IDLE": "0.1",
            "TB_STALL": "0.2",
            "TB_CROPS": json.dumps(testimages.photo_crops([20])[:1]),
        },
    )


def test_axi_registers_random(request):
    """Random AXI4-Lite writes (any address, random byte strobes) and concurrent
    reads against a model of the register file, with B and R back-pressure."""
    run_axi(request, {**SMALL, "SCORE": "opencv", "NMS": "3x3"}, "registers_random")


# opencv + 3x3 in `make test`; the sad score and `none` in `make test-full`
# (in `make test` the sad score runs at PPC 4 through the top on both engines,
# sim/tests/test_engines.py, and with `none` at PPC 2 through the core).
PPC_CASES = [
    pytest.param("opencv", "3x3", 2, id="opencv-3x3-ppc2"),
    pytest.param("opencv", "3x3", 4, id="opencv-3x3-ppc4"),
    pytest.param("sad", "3x3", 2, marks=pytest.mark.slow, id="sad-3x3-ppc2"),
    pytest.param("sad", "3x3", 4, marks=pytest.mark.slow, id="sad-3x3-ppc4"),
    pytest.param("opencv", "none", 4, marks=pytest.mark.slow, id="opencv-none-ppc4"),
]
PPC_TESTS = ["registers", "generated_frames", "empty_frame", "score_video", "malformed_then_good"]


@pytest.mark.parametrize(("score", "nms", "ppc", "testcase"), each(PPC_CASES, PPC_TESTS))
def test_axi_ppc(request, score, nms, ppc, testcase):
    """2 and 4 pixels per clock (PPC), 3x3 NMS and none: the registers (MODE.PPC,
    WIDTH rounded to whole beats), generated images back to back, the empty
    frame, the score video (PPC scores per beat), malformed lines counted in
    beats, with input idles and output stalls."""
    run_axi(
        request,
        {**SMALL, "SCORE": score, "NMS": nms, "PPC": ppc},
        testcase,
        env={"TB_IDLE": "0.2", "TB_STALL": "0.3"},
    )


@pytest.mark.parametrize("ppc", [2, 4])
def test_axi_ppc_throughput(request, tmp_path, ppc):
    """Clocks per frame at 2 and 4 pixels per clock: W x H / PPC clocks per
    frame back to back (within the bound of the throughput test)."""
    results = tmp_path / "throughput.json"
    run_axi(
        request,
        {**SMALL, "SCORE": "opencv", "NMS": "3x3", "PPC": ppc},
        "throughput",
        env={"TB_FRAMES": "3", "TB_RESULTS": str(results)},
    )
    print("clocks to each frame's last record:", json.loads(results.read_text()))


def test_axi_throughput(request, tmp_path):
    """Clocks per frame without idles or stalls: one 64x48 frame, then three
    back to back."""
    results = tmp_path / "throughput.json"
    run_axi(
        request,
        {**SMALL, "SCORE": "opencv", "NMS": "3x3"},
        "throughput",
        env={"TB_FRAMES": "3", "TB_RESULTS": str(results)},
    )
    print("clocks to each frame's last record:", json.loads(results.read_text()))


# One crop in `make test`, three in `make test-full`.
PHOTO_CASES = [pytest.param(1, id="crops1"), pytest.param(3, marks=pytest.mark.slow, id="crops3")]


@pytest.mark.parametrize(("crops", "testcase"), each(PHOTO_CASES, ["registers", "real_images"]))
def test_axi_photos(request, crops, testcase):
    """Photograph crops through the top (no score video, default FIFO), against
    the golden and cv2.FastFeatureDetector; the registers of this build."""
    run_axi(
        request,
        {**PHOTO, "SCORE": "opencv", "NMS": "3x3"},
        testcase,
        env={
            "TB_IDLE": "0.05",
            "TB_STALL": "0.2",
            "TB_CROPS": json.dumps(testimages.photo_crops([20, 10, 40])[:crops]),
        },
    )


@pytest.mark.slow
def test_axi_throughput_1920(request, tmp_path):
    """One 1920x1080 frame, then two back to back, at the default generics."""
    results = tmp_path / "throughput.json"
    run_axi(
        request,
        {"MAX_WIDTH": 1920, "MAX_HEIGHT": 1080, "SCORE": "opencv", "NMS": "3x3"},
        "throughput",
        env={"TB_FRAMES": "2", "TB_RESULTS": str(results)},
    )
    print("clocks to each frame's last record:", json.loads(results.read_text()))


@pytest.mark.slow
def test_axi_live_1920(request):
    """The live-camera mode at full width: three 1920x40 noise frames at t = 0 into
    the default 512-record FIFO with the corner sink stopped (no input stall,
    DROPPED exact, OVERFLOW flags), then exact frames."""
    run_axi(
        request,
        {"MAX_WIDTH": 1920, "MAX_HEIGHT": 40, "SCORE": "opencv", "NMS": "3x3"},
        "live_mode",
        env={"TB_STALL": "0.2"},
    )


# DESCRIPTOR "orb": 128x80 frames (ORB's 31-pixel border leaves a 66x18 interior), a
# corner FIFO of 8 records (48 beats), K up to 4 (the queue of a cell row's records
# is small enough that K = 0 on noise overflows it).
ORB_SMALL = {
    "MAX_WIDTH": 128,
    "MAX_HEIGHT": 80,
    "CORNER_FIFO_DEPTH": 8,
    "MAX_PER_CELL": 4,
    "DESCRIPTOR": "orb",
    "ORB_MAX_CELL": 32,
}


@pytest.mark.parametrize(
    ("score", "nms"),
    [
        pytest.param("opencv", "3x3", id="opencv-3x3"),
        pytest.param("sad", "none", marks=pytest.mark.slow, id="sad-none"),
    ],
)
def test_axi_orb(request, tmp_path, score, nms):
    """DESCRIPTOR "orb" through the top: record format 2 decoded by the Python decoder
    equal to orb_features (x, y, score, angle bits, descriptor) frame by frame, each
    with its CELL and K; keypoints dropped with K = 0 counted and flagged
    (tb/top/axi_orb_tb.py). Then the C decoder on the same words: the same keypoints."""
    words_file = tmp_path / "words.json"
    run_cocotb(
        "fastnms_axi",
        "axi_orb_tb",
        {**ORB_SMALL, "SCORE": score, "NMS": nms},
        name=request.node.nodeid,
        env={
            "TB_IDLE": "0.1",
            "TB_STALL": "0.2",
            "TB_OUT": str(words_file),
            "TB_FULL": "1" if nms == "none" else "0",
        },
    )
    words = [w for frame in json.loads(words_file.read_text()) for w in frame]
    frames = decode_records(words)
    assert sum(len(f.corners) for f in frames) >= 10, "too few keypoints for a test"
    want = [
        f"{x} {y} {s} {a:08x} {d.hex()}"
        for f in frames
        for (x, y, s), a, d in zip(f.corners, f.angle_bits, f.descriptors, strict=True)
    ]
    records = tmp_path / "records.bin"
    np.asarray(words, dtype="<u8").tofile(records)
    program = c_decoder(tmp_path)
    out = subprocess.run([program, records], capture_output=True, text=True, timeout=30)
    assert out.returncode == 0, out.stderr
    got = [line for line in out.stdout.splitlines() if not line.startswith("frame ")]
    assert got == want, "the C decoder's keypoints differ from the Python decoder's"


# The internal errors, each forced by a test-only fault (TEST_FAULT): ORB's at 128 wide
# and 160 tall (the rows' fault needs a frame taller than ORB's rows at CELL 16), the
# configuration queue's with the budget and no ORB. ORB's three (2-3 min each) in make
# test-full; make test has the configuration queue's (the same reset, flag and interrupt).
ORB_FAULTY = {
    **ORB_SMALL,
    "MAX_HEIGHT": 160,
    "ORB_MAX_CELL": 16,
    "SCORE": "opencv",
    "NMS": "3x3",
}
BUDGET_FAULTY = {
    "MAX_WIDTH": 64,
    "MAX_HEIGHT": 48,
    "CORNER_FIFO_DEPTH": 64,
    "MAX_PER_CELL": 4,
    "SCORE": "opencv",
    "NMS": "3x3",
}


@pytest.mark.parametrize(
    ("generics", "fault"),
    [
        pytest.param(ORB_FAULTY, "rows", marks=pytest.mark.slow, id="orb-rows"),
        pytest.param(ORB_FAULTY, "tags", marks=pytest.mark.slow, id="orb-tags"),
        pytest.param(ORB_FAULTY, "count", marks=pytest.mark.slow, id="orb-count"),
        pytest.param(BUDGET_FAULTY, "config", id="budget-config"),
    ],
)
def test_axi_internal_error(request, generics, fault):
    """Each internal error, forced: its STATUS bit, the interrupt, ERROR on one frame's
    last record, the pipeline reset, and the next frames exact (tb/top/axi_errors_tb.py)."""
    run_axi(
        request,
        {**generics, "TEST_FAULT": fault},
        "internal_error",
        env={"TB_IDLE": "0.1", "TB_STALL": "0.2"},
    )


@pytest.mark.slow
def test_axi_orb_resets_mid_frame(request):
    """ORB: CMD.SOFT_RESET and aresetn while keypoints are in ORB; the next frames exact
    (tb/top/axi_errors_tb.py)."""
    generics = {**ORB_FAULTY, "MAX_HEIGHT": 80}
    run_axi(request, generics, "resets_mid_frame", env={"TB_IDLE": "0.1", "TB_STALL": "0.2"})


def test_axi_orb_live(request):
    """ORB in LIVE mode: back-to-back frames without blanking, tready high on every
    clock, register writes around each start of frame, every frame exact
    (tb/top/axi_orb_live_tb.py)."""
    run_axi(request, ORB_SMALL | {"SCORE": "opencv", "NMS": "3x3"}, "orb_live_back_to_back")


def c_decoder(where: Path) -> Path:
    """sw/tests/decode_records built with sw/fastnms.c (sw/tests/cbuild.py)."""
    spec = importlib.util.spec_from_file_location("cbuild", REPO / "sw" / "tests" / "cbuild.py")
    cbuild = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(cbuild)
    return cbuild.build_programs(where)["decode_records"]
