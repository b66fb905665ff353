"""pytest entry: the ORB units under GHDL (float32 multiplier and adder, angle, blur, moments,
sampling) against the golden model."""

import pytest

from tb.harness import run_cocotb


@pytest.mark.parametrize("unit", ["mul", "add"])
def test_f32_unit(request, unit):
    run_cocotb(
        f"fastnms_f32_{unit}",
        "f32_tb",
        {},
        env={"TB_UNIT": unit, "TB_COUNT": "100000"},
        name=request.node.nodeid,
    )


@pytest.mark.parametrize(
    "count", [1000, pytest.param(20000, marks=pytest.mark.slow)], ids=["1000", "20000"]
)
def test_orb_angle(request, count):
    run_cocotb(
        "fastnms_orb_angle",
        "angle_tb",
        {},
        env={"TB_COUNT": str(count)},
        name=request.node.nodeid,
    )


def test_orb_blur(request):
    run_cocotb(
        "fastnms_orb_blur",
        "blur_tb",
        {},
        env={"TB_COUNT": "20000"},
        name=request.node.nodeid,
    )


def test_orb_moments(request):
    run_cocotb(
        "fastnms_orb_moments",
        "moments_tb",
        {},
        env={"TB_COUNT": "400"},
        name=request.node.nodeid,
    )


@pytest.mark.parametrize(
    ("lanes", "count"),
    [
        (8, 150),
        pytest.param(16, 60, marks=pytest.mark.slow),
        pytest.param(2, 20, marks=pytest.mark.slow),
    ],
    ids=["lanes8", "lanes16", "lanes2"],
)
def test_orb_sample(request, lanes, count):
    run_cocotb(
        "fastnms_orb_sample",
        "sample_tb",
        {"LANES": lanes},
        env={"TB_COUNT": str(count)},
        name=request.node.nodeid,
    )


@pytest.mark.parametrize(
    ("lanes", "count"),
    [(8, 60), pytest.param(4, 30, marks=pytest.mark.slow)],
    ids=["lanes8", "lanes4"],
)
def test_orb_describe(request, lanes, count):
    run_cocotb(
        "fastnms_orb_describe",
        "describe_tb",
        {"LANES": lanes},
        env={"TB_COUNT": str(count)},
        name=request.node.nodeid,
    )


@pytest.mark.parametrize(("height", "slots"), [(37, 2), (31, 3)], ids=["blurred", "plain"])
def test_orb_rows(request, height, slots):
    run_cocotb(
        "fastnms_orb_rows",
        "rows_tb",
        {"MAX_WIDTH": 48, "HEIGHT": height, "SLOTS": slots},
        name=request.node.nodeid,
    )


# Under slow: tb/core/test_core.py::test_core_orb runs the feed inside the core in `make test`.
@pytest.mark.slow
def test_orb_feed(request):
    run_cocotb(
        "fastnms_orb_feed",
        "feed_tb",
        {"MAX_WIDTH": 128, "MAX_HEIGHT": 96},
        name=request.node.nodeid,
    )
