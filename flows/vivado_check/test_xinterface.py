"""The X_INTERFACE_INFO / X_INTERFACE_PARAMETER attributes of
rtl/top/fastnms_axi.vhd agree with its ports (xinterface.problems), and the
check fails on copies of the VHDL text with one thing broken."""

from __future__ import annotations

import re

import pytest

from flows.vivado_check import xinterface
from flows.vivado_check.harness import TOP


def test_attributes_agree_with_the_ports() -> None:
    top = xinterface.load(TOP)
    found, _ = xinterface.interfaces(top)
    assert set(found) == {
        "aclk", "aresetn", "interrupt", "s_axis_video", "m_axis_corners", "m_axis_score",
        "s_axi_ctrl",
    }  # fmt: skip
    assert sum(len(b.ports) for b in found.values()) == len(top.ports)
    assert found["m_axis_corners"].parameters["HAS_TKEEP"] == "1"
    assert found["m_axis_corners"].ports["TKEEP"].width == 8
    assert found["s_axi_ctrl"].parameters["ADDR_WIDTH"] == str(
        found["s_axi_ctrl"].ports["AWADDR"].width
    )
    problems = xinterface.problems(top)
    assert not problems, "\n".join(problems)


# (pattern, replacement, a problem it must cause): each pattern matches the
# VHDL text exactly once.
MUTATIONS = {
    "port without attribute": (
        r'attribute x_interface_info of m_axis_corners_tkeep : signal is\s*"[^"]*";',
        "",
        "port m_axis_corners_tkeep: no X_INTERFACE_INFO",
    ),
    "port in two interfaces": (
        r'"xilinx.com:interface:axis:1.0 m_axis_corners TKEEP"',
        '"xilinx.com:interface:axis:1.0 m_axis_corners TKEEP, '
        'xilinx.com:interface:axis:1.0 m_axis_score TKEEP"',
        "port m_axis_corners_tkeep: belongs to 2 interfaces",
    ),
    "unknown logical name": (
        r"m_axis_corners TKEEP\"",
        'm_axis_corners TKEPP"',
        "TKEPP is not a logical port of xilinx.com:interface:axis:1.0",
    ),
    "logical name twice": (
        r"m_axis_corners TKEEP\"",
        'm_axis_corners TDATA"',
        "interface m_axis_corners: TDATA on two ports",
    ),
    "unknown bus definition": (
        r"xilinx.com:signal:reset:1.0 aresetn RST",
        "xilinx.com:signal:rst:1.0 aresetn RST",
        "unknown bus definition xilinx.com:signal:rst:1.0",
    ),
    "address width": (
        r"s_axi_ctrl_awaddr(\s*):(\s*)in(\s*)std_logic_vector\(11 downto 0\)",
        r"s_axi_ctrl_awaddr\1:\2in\3std_logic_vector(7 downto 0)",
        "ADDR_WIDTH 12 but AWADDR is 8",
    ),
    "data width": (r"DATA_WIDTH 32", "DATA_WIDTH 64", "DATA_WIDTH 64 but WDATA is 32"),
    "tdata bytes": (
        r"m_axis_corners, TDATA_NUM_BYTES 8",
        "m_axis_corners, TDATA_NUM_BYTES 4",
        "TDATA_NUM_BYTES 4 but TDATA is 64 bits",
    ),
    "tkeep width": (
        r"m_axis_corners_tkeep(\s*):(\s*)out(\s*)std_logic_vector\(7 downto 0\)",
        r"m_axis_corners_tkeep\1:\2out\3std_logic_vector(3 downto 0)",
        "TKEEP is 4 bits for 64 bits of TDATA",
    ),
    "has_tkeep": (
        r"(m_axis_corners, TDATA_NUM_BYTES 8, TUSER_WIDTH 0, HAS_TLAST 1, HAS_TREADY 1, "
        r'"\s*&\s*"HAS_TKEEP) 1',
        r"\1 0",
        "HAS_TKEEP 0 but the port is present",
    ),
    "tuser width": (
        r"(s_axis_video, TDATA_NUM_BYTES \" & integer'image\(PPC\) & \", )TUSER_WIDTH 1",
        r"\1TUSER_WIDTH 2",
        "interface s_axis_video: TUSER_WIDTH 2 but TUSER is 1 bits",
    ),
    "has_prot": (r"HAS_PROT 1", "HAS_PROT 0", "HAS_PROT 0 but the port is present"),
    "polarity": (
        r"POLARITY ACTIVE_LOW",
        "POLARITY ACTIVE_HIGH",
        "reset aresetn: POLARITY ACTIVE_HIGH, must be ACTIVE_LOW",
    ),
    "bus not associated": (
        r"ASSOCIATED_BUSIF s_axis_video:m_axis_corners:m_axis_score:s_axi_ctrl",
        "ASSOCIATED_BUSIF s_axis_video:m_axis_corners:s_axi_ctrl",
        "clock aclk: ASSOCIATED_BUSIF lacks m_axis_score",
    ),
    "bus associated twice": (
        r"ASSOCIATED_BUSIF s_axis_video:m_axis_corners:m_axis_score:s_axi_ctrl",
        "ASSOCIATED_BUSIF s_axis_video:m_axis_corners:m_axis_score:s_axi_ctrl:s_axi_ctrl",
        "ASSOCIATED_BUSIF names s_axi_ctrl twice",
    ),
    "reset not associated": (
        r"ASSOCIATED_RESET aresetn",
        "ASSOCIATED_RESET rst",
        "clock aclk: ASSOCIATED_RESET rst, the resets are aresetn",
    ),
    "direction": (
        r"s_axis_video_tready(\s*):(\s*)out",
        r"s_axis_video_tready\1:\2in ",
        "port s_axis_video_tready: TREADY of slave interface s_axis_video must be 'out'",
    ),
    "parameters of another interface": (
        r"XIL_INTERFACENAME m_axis_score,",
        "XIL_INTERFACENAME m_axis_corners,",
        "port m_axis_score_tdata: parameters of m_axis_corners, a port of another interface",
    ),
}


@pytest.mark.parametrize("name", MUTATIONS)
def test_a_broken_attribute_fails(name: str) -> None:
    pattern, replacement, expected = MUTATIONS[name]
    text, count = re.subn(pattern, replacement, TOP.read_text())
    assert count == 1, f"the mutation '{name}' matches {count} times: update it to the VHDL"
    problems = xinterface.problems(xinterface.parse(text))
    assert any(expected in p for p in problems), "\n".join(problems) or "no problem found"


@pytest.mark.parametrize("ppc", ["2", "4"])
def test_pixels_per_clock_follow_the_generic(ppc: str) -> None:
    """With PPC 2 or 4 the video and score TDATA are PPC bytes and so are their
    TDATA_NUM_BYTES (integer'image(PPC) in the attribute); a constant there fails."""
    top = xinterface.parse(TOP.read_text(), generics_override={"PPC": ppc})
    assert top.ports["s_axis_video_tdata"].width == 8 * int(ppc)
    assert top.ports["m_axis_score_tdata"].width == 8 * int(ppc)
    assert xinterface.problems(top) == []
    text, count = re.subn(
        r"s_axis_video, TDATA_NUM_BYTES \" & integer'image\(PPC\) & \"",
        "s_axis_video, TDATA_NUM_BYTES 1",
        TOP.read_text(),
    )
    assert count == 1
    problems = xinterface.problems(xinterface.parse(text, generics_override={"PPC": ppc}))
    assert any(f"TDATA_NUM_BYTES 1 but TDATA is {8 * int(ppc)} bits" in p for p in problems)
