"""The Vivado scripts (vivado/*.tcl) and constraints, checked without Vivado.

Every command of every script is complete Tcl; each script is dry-run under a
real Tcl interpreter with the Vivado commands stubbed (tclcheck.dry_run), so
its own logic, options, paths and file lists run for real, and every Vivado
call it makes is checked against the commands, options, properties, IP CONFIG
keys, pin names and VLNVs of vivado_api (stubcheck; test_stub.py shows that a
misspelling fails); the RTL file list it builds covers rtl/ in compile order;
the names it uses exist in rtl/top/fastnms_axi.vhd. What Vivado itself would
answer is not checked here (no Vivado): see vivado/README.md.
"""

from __future__ import annotations

import math
import re
import shutil
import subprocess
from pathlib import Path

import pytest
from fastnms.sim.sources import REPO, all_rtl_files, order_problems

from flows.vivado_check import stubcheck, tclcheck, xinterface
from flows.vivado_check.harness import (
    BD_RESULTS,
    PACKAGE_RESULTS,
    PART,
    TOP,
    VIVADO,
    WORK,
    XDC,
    dry_run,
    fake_ip_repo,
    merge,
    sandbox,
)

SCRIPTS = sorted(VIVADO.glob("*.tcl"))
# The IP's version: the major.minor of the file VERSION (flows/docs_check/test_version.py
# checks fastnms_common.tcl against it).
IP_VERSION = ".".join((REPO / "VERSION").read_text().strip().split(".")[:2])

needs_tcl = pytest.mark.skipif(
    tclcheck.backend() is None, reason="no Tcl interpreter (neither tkinter nor tclsh)"
)


def tcl(code: str) -> str:
    """`code` run after vivado/fastnms_common.tcl (plain Tcl, no stub)."""
    return tclcheck.run_tcl(f"source {{{VIVADO / 'fastnms_common.tcl'}}}\n{code}")


def test_the_scripts_exist() -> None:
    names = {p.name for p in SCRIPTS}
    assert {"package_ip.tcl", "create_bd_zc7z20.tcl", "synth_ooc.tcl"} <= names
    assert XDC.exists()


@pytest.mark.parametrize("path", [*SCRIPTS, XDC], ids=lambda p: p.name)
def test_every_command_is_complete(path: Path) -> None:
    if tclcheck.backend() is None:
        problems = tclcheck.complete_commands_fallback(path.read_text())
    else:
        problems = tclcheck.incomplete_commands(path)
    assert not problems, f"{path.name}: incomplete Tcl command(s):\n" + "\n".join(problems)


@pytest.mark.parametrize("path", SCRIPTS, ids=lambda p: p.name)
def test_portable_tcl(path: Path) -> None:
    """Tcl 8.5 (older Vivado releases), no `exit` (it would end a Vivado
    session that sources the script), no path of one machine, no proc outside
    namespace fastnms (it could hide a Vivado command; the dry runs enforce
    it too)."""
    code = "\n".join(
        line.split("#", 1)[0] if line.lstrip().startswith("#") else line
        for line in path.read_text().splitlines()
    )
    for command in tclcheck.TCL86_ONLY:
        assert not re.search(rf"(^|[\[;{{\s]){command}\s", code), f"Tcl 8.6 only: {command}"
    assert not re.search(r"(^|[\[;{\s])exit(\s|$|\])", code), "the script calls exit"
    text = path.read_text()
    assert not re.search(r"(/home/|/work/|/tmp/|/opt/|[A-Za-z]:\\)", text), "absolute path"
    procs = re.findall(r"^\s*proc\s+(\S+)", code, re.MULTILINE)
    assert all(p.startswith("fastnms::") for p in procs), procs


# ---- the RTL file list, the clock, the board ------------------------------------------


def tcl_rtl_files() -> list[Path]:
    return [Path(line) for line in tcl("return [join [fastnms::rtl_files] \\n]").splitlines()]


@needs_tcl
def test_rtl_list_is_every_rtl_file_in_compile_order() -> None:
    files = tcl_rtl_files()
    assert sorted(files) == all_rtl_files(), (
        "fastnms::rtl_files (vivado/fastnms_common.tcl) differs from rtl/**/*.vhd: "
        "a file in a folder outside fastnms::areas?"
    )
    assert not order_problems(files)


@needs_tcl
def test_fclk_is_the_io_pll_divided_by_an_integer() -> None:
    """FCLK_CLK0 = IO PLL (1000 MHz) / (DIVISOR0 * DIVISOR1), 6-bit dividers
    (UG585, PL clocks): 150 MHz is not reachable, 1000 / 7 is the default."""
    assert tcl("fastnms::fclk_mhz") == "142.857143"
    setting = tcl("fastnms::fclk_setting [fastnms::fclk_mhz]").split()
    assert dict(zip(setting[::2], setting[1::2], strict=True)) == {
        "mhz": "142.857143",
        "divide": "7",
        "divisor0": "1",
        "divisor1": "7",
    }
    assert tcl("dict get [fastnms::fclk_setting 100] divide") == "10"
    assert tcl("dict get [fastnms::fclk_setting 142.857] mhz") == "142.857143"
    with pytest.raises(tclcheck.TclError, match=r"150 MHz.*nearest: 166.666667 \(/6\), 142"):
        tcl("fastnms::fclk_setting 150")
    # 67 is prime and above 63: no pair of 6-bit dividers makes it.
    with pytest.raises(tclcheck.TclError, match="not 1000 MHz"):
        tcl(f"fastnms::fclk_setting {1000 / 67}")


@needs_tcl
def test_ooc_period_is_the_bd_clock() -> None:
    period = float(tcl("fastnms::ooc_period"))
    assert period == pytest.approx(1000 / float(tcl("fastnms::fclk_mhz")), abs=0.0005)
    script = (VIVADO / "create_bd_zc7z20.tcl").read_text()
    assert "[fastnms::fclk_mhz [dict get $opts --nms]]" in script
    assert tcl("fastnms::fclk_mhz region4") == tcl("fastnms::fclk_mhz region8")
    assert tcl("fastnms::fclk_mhz none") == tcl("fastnms::fclk_mhz 3x3") == "142.857143"
    assert re.search(r"\[get_ports aclk\]", XDC.read_text())
    assert "142.857 MHz" in XDC.read_text()


@needs_tcl
def test_latest_board_part_compares_version_numbers() -> None:
    parts = (
        "em.avnet.com:zed:part0:1.4 avnet.com:zedboard:part0:1.10 "
        "digilentinc.com:zedboard:part0:1.0 avnet.com:zedboard:part0:1.9"
    )
    # lsort would give em.avnet.com (vendor order); 1.10 is the newest.
    assert tcl(f"fastnms::latest_board_part {{{parts}}}") == "avnet.com:zedboard:part0:1.10"
    assert tcl("fastnms::latest_board_part {}") == ""
    assert tcl("fastnms::version_compare {1 4} {1 4 0}") == "0"


def test_build_outputs_are_ignored() -> None:
    if not (REPO / ".git").exists() or shutil.which("git") is None:
        pytest.skip("not a git checkout")
    paths = ["build/vivado/ip/component.xml", "build/fusesoc/sim/Makefile", "vivado.jou", ".Xil/x"]
    out = subprocess.run(
        ["git", "check-ignore", *paths], cwd=REPO, capture_output=True, text=True
    ).stdout.split()
    assert out == paths


def test_make_vivado_bd_needs_a_board() -> None:
    if shutil.which("make") is None:
        pytest.skip("no make")

    def make(*args: str) -> subprocess.CompletedProcess[str]:
        return subprocess.run(
            ["make", "-n", "VIVADO=vivado", "vivado-bd", *args],
            cwd=REPO,
            capture_output=True,
            text=True,
        )

    assert "needs BOARD=zedboard, BOARD=zc702 or BOARD=none" in make().stdout
    out = make("BOARD=zedboard", "BD_ARGS=--impl").stdout
    assert "create_bd_zc7z20.tcl -tclargs --board zedboard --impl" in out


# ---- dry runs: package_ip.tcl -----------------------------------------------------------


@needs_tcl
def test_package_ip() -> None:
    root = sandbox("package_ip")
    out = root / "out" / "ip"
    run = dry_run(root, "package_ip.tcl", ["--out", str(out)], PACKAGE_RESULTS)
    run.assert_clean()
    (create,) = run.of("create_project")
    assert create[-2:] == ["-part", PART]
    assert Path(create[3]) == out.parent / "package_ip_project"

    (add,) = run.of("add_files")
    *files, wrapper = [Path(f) for f in add[-1].split()]
    rtl = root / "rtl"
    assert sorted(files) == sorted(rtl.rglob("*.vhd")), "not every rtl/**/*.vhd is packaged"
    assert files[-1] == rtl / "top" / "fastnms_axi.vhd"
    assert wrapper == out.parent / "ip_wrapper" / "fastnms_axi_ip.vhd"
    assert "entity fastnms_axi_ip is" in wrapper.read_text()
    types = {c[2]: c[3] for c in run.calls if c[:2] == ["set_property", "file_type"]}
    rtl_list = " ".join(str(f) for f in files)
    assert types == {"VHDL 2008": f"{{get_files {rtl_list}}}", "VHDL": f"{{get_files {wrapper}}}"}
    assert ["set_property", "top", "fastnms_axi_ip", "{current_fileset }"] in run.calls

    (package,) = run.of("ipx::package_project")
    assert package[package.index("-root_dir") + 1] == str(out)
    assert package[package.index("-vendor") + 1] == "fastnms"
    assert "-import_files" in package
    props = {
        c[1]: c[2] for c in run.calls if c[0] == "set_property" and c[-1] == "{ipx::current_core }"
    }
    assert props["name"] == "fastnms_axi" and props["version"] == IP_VERSION
    assert "zynq Production" in " ".join(props["supported_families"].split())
    assert "artix7 Production" in " ".join(props["supported_families"].split())

    # The interfaces come from the attributes: no inference, and the
    # parameters the block design needs are read back.
    assert not run.of("ipx::infer_bus_interfaces")
    params = [
        [w for w in c[1:] if not w.startswith("-")][0] for c in run.of("ipx::get_bus_parameters")
    ]
    assert {"POLARITY", "TUSER_WIDTH", "ASSOCIATED_BUSIF"} <= set(params)
    text = run.text
    assert (
        "set_property enablement_dependency $SCORE_VIDEO {ipx::get_bus_interfaces m_axis_score"
        in text
    )
    assert "set_property driver_value 1 {ipx::get_ports m_axis_score_tready" in text
    assert "value_validation_list opencv sad" in text
    assert "value_validation_list 3x3 none region4 region8" in text
    assert "value_validation_type range_long {ipx::get_user_parameters MAX_WIDTH" in text
    assert "widget checkBox {ipgui::get_guiparamspec SCORE_VIDEO" in text
    assert "value_validation_type list {ipx::get_user_parameters CORNER_FIFO_DEPTH" in text
    for command in ("ipx::create_xgui_files", "ipx::save_core", "ipx::archive_core"):
        assert run.of(command), command
    assert run.calls[-1] == ["close_project"]


@needs_tcl
def test_package_ip_register_block_is_the_address_space() -> None:
    """The 4 KiB address block of s_axi_ctrl is 2**ADDR_WIDTH of the top."""
    text = (VIVADO / "package_ip.tcl").read_text()
    (range_bytes,) = re.findall(r"set_property range (\d+) \$block", text)
    found, _ = xinterface.interfaces(xinterface.load(TOP))
    assert int(range_bytes) == 2 ** int(found["s_axi_ctrl"].parameters["ADDR_WIDTH"])


@needs_tcl
def test_package_ip_logs_and_checks_inference(capfd: pytest.CaptureFixture[str]) -> None:
    root = sandbox("package_ip_infer")
    out = ["--out", str(root / "out" / "ip")]
    run = dry_run(
        root, "package_ip.tcl", out, merge({"ipx::get_bus_interfaces": ""}, PACKAGE_RESULTS)
    )
    assert run.error and "no bus interface s_axis_video m_axis_corners" in run.error
    assert not run.problems, run.problems
    inferred = [c[1] for c in run.of("ipx::infer_bus_interfaces")]
    assert "xilinx.com:interface:axis_rtl:1.0" in inferred
    assert "xilinx.com:interface:aximm_rtl:1.0" in inferred
    assert "INFERRING them from the port names" in capfd.readouterr().out

    run = dry_run(root, "package_ip.tcl", out, PACKAGE_RESULTS)
    assert run.error is None
    assert "bus interfaces from the X_INTERFACE attributes" in capfd.readouterr().out


@needs_tcl
@pytest.mark.parametrize(
    ("results", "message"),
    [
        (
            {"get_property VALUE *POLARITY*": "ACTIVE_HIGH"},
            "aresetn: POLARITY is ACTIVE_HIGH, must be ACTIVE_LOW",
        ),
        (
            {"ipx::get_bus_parameters -quiet TUSER_WIDTH*": ""},
            "s_axis_video: TUSER_WIDTH is (missing), must be 1",
        ),
    ],
    ids=["polarity", "tuser_width"],
)
def test_package_ip_fails_without_the_bus_parameters(results: dict, message: str) -> None:
    root = sandbox(f"package_ip_param_{len(message)}")
    run = dry_run(
        root, "package_ip.tcl", ["--out", str(root / "out" / "ip")], merge(results, PACKAGE_RESULTS)
    )
    assert run.error and message in run.error


@needs_tcl
def test_package_ip_needs_the_top_level() -> None:
    root = sandbox("package_ip_no_top", with_top=False)
    calls, error = tclcheck.dry_run(root / "vivado" / "package_ip.tcl", [])
    assert error and "fastnms_axi.vhd does not exist" in error
    assert not calls


# ---- dry runs: create_bd_zc7z20.tcl -------------------------------------------------------


def bd_run(name: str, argv: list[str], results: dict[str, str] | None = None):
    root = sandbox(name)
    return root, dry_run(
        root,
        "create_bd_zc7z20.tcl",
        ["--ip-repo", str(fake_ip_repo(root)), "--out", str(root / "out"), *argv],
        merge(results or {}, BD_RESULTS),
    )


def cell_config(run, cell: str) -> dict[str, str]:
    """The CONFIG values a dry run set on block-design cell `cell`."""
    settings: dict[str, str] = {}
    for c in run.of("set_property"):
        if c[-1] != f"/{cell}":
            continue
        pairs = stubcheck.tcl_split(c[2]) if c[1] == "-dict" else c[1:3]
        settings.update(zip(pairs[::2], pairs[1::2], strict=True))
    return settings


def board_parts_set(run) -> list[str]:
    return [c[2] for c in run.of("set_property") if c[1] == "board_part"]


def pins(call: list[str]) -> set[str]:
    return {w.strip("{}").split()[-1].lstrip("/") for w in call[1:]}


@needs_tcl
def test_create_bd() -> None:
    root, run = bd_run("create_bd", ["--board", "zedboard"])
    run.assert_clean()
    (create,) = run.of("create_project")
    assert create[-2:] == ["-part", PART] and Path(create[3]) == root / "out"
    assert board_parts_set(run) == ["avnet.com:zedboard:part0:1.4"]
    assert "apply_board_preset 1" in run.text

    cells = {c[-1]: c[c.index("-vlnv") + 1] for c in run.of("create_bd_cell")}
    assert cells == {
        "ps7": "xilinx.com:ip:processing_system7",
        "fastnms": f"fastnms:vision:fastnms_axi:{IP_VERSION}",
        "vdma": "xilinx.com:ip:axi_vdma",
        "dma": "xilinx.com:ip:axi_dma",
        "ctrl_smc": "xilinx.com:ip:smartconnect",
        "mem_smc": "xilinx.com:ip:smartconnect",
        "rst": "xilinx.com:ip:proc_sys_reset",
        "irq_concat": "xilinx.com:ip:xlconcat",
    }
    ps = cell_config(run, "ps7")
    for key, value in {
        "CONFIG.PCW_USE_M_AXI_GP0": "1",
        "CONFIG.PCW_USE_S_AXI_HP0": "1",
        "CONFIG.PCW_S_AXI_HP0_DATA_WIDTH": "64",
        "CONFIG.PCW_EN_CLK0_PORT": "1",
        "CONFIG.PCW_FCLK0_PERIPHERAL_CLKSRC": "IO PLL",
        "CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ": "142.857143",
        "CONFIG.PCW_FCLK_CLK0_BUF": "TRUE",
        "CONFIG.PCW_USE_FABRIC_INTERRUPT": "1",
        "CONFIG.PCW_IRQ_F2P_INTR": "1",
    }.items():
        assert ps[key] == value, key
    vdma = cell_config(run, "vdma")
    assert vdma["CONFIG.c_include_s2mm"] == "0" and vdma["CONFIG.c_include_mm2s"] == "1"
    assert vdma["CONFIG.c_m_axis_mm2s_tdata_width"] == "8"
    dma = cell_config(run, "dma")
    assert dma["CONFIG.c_include_mm2s"] == "0" and dma["CONFIG.c_include_s2mm"] == "1"
    assert dma["CONFIG.c_include_sg"] == "0"
    assert dma["CONFIG.c_s_axis_s2mm_tdata_width"] == "64"
    # 26 bits, the maximum: --nms none at 1920x1080 emits up to ~16 MB per frame.
    assert dma["CONFIG.c_sg_length_width"] == "26"
    assert 2**26 - 1 >= 1920 * 1080 * 8
    assert cell_config(run, "fastnms")["CONFIG.SCORE_VIDEO"] == "false"
    assert cell_config(run, "irq_concat")["CONFIG.NUM_PORTS"] == "3"

    intf = [pins(c) for c in run.of("connect_bd_intf_net")]
    for pair in (
        {"ps7/M_AXI_GP0", "ctrl_smc/S00_AXI"},
        {"ctrl_smc/M00_AXI", "fastnms/s_axi_ctrl"},
        {"vdma/M_AXIS_MM2S", "fastnms/s_axis_video"},
        {"fastnms/m_axis_corners", "dma/S_AXIS_S2MM"},
        {"mem_smc/M00_AXI", "ps7/S_AXI_HP0"},
    ):
        assert pair in intf, pair
    nets = [pins(c) for c in run.of("connect_bd_net")]
    clock = next(n for n in nets if "ps7/FCLK_CLK0" in n)
    assert {"fastnms/aclk", "vdma/m_axis_mm2s_aclk", "dma/m_axi_s2mm_aclk"} <= clock
    assert {"ps7/M_AXI_GP0_ACLK", "ps7/S_AXI_HP0_ACLK"} <= clock
    assert {"fastnms/interrupt", "irq_concat/In0"} in nets
    assert {"dma/s2mm_introut", "irq_concat/In1"} in nets
    assert {"vdma/mm2s_introut", "irq_concat/In2"} in nets
    assert {"irq_concat/dout", "ps7/IRQ_F2P"} in nets
    assert any("fastnms/aresetn" in n and "rst/peripheral_aresetn" in n for n in nets)

    order = [c[0] for c in run.calls]
    for earlier, later in (
        ("assign_bd_address", "validate_bd_design"),
        ("validate_bd_design", "make_wrapper"),
    ):
        assert order.index(earlier) < order.index(later)
    assert (root / "out" / "address_map.txt").exists()
    assert not run.of("launch_runs")


@needs_tcl
def test_create_bd_orb() -> None:
    """--orb: the IP with ORB descriptors (and the budget they need); refused with a
    region NMS."""
    _, run = bd_run("create_bd_orb", ["--board", "none", "--orb"])
    run.assert_clean()
    config = cell_config(run, "fastnms")
    assert (config["CONFIG.DESCRIPTOR"], config["CONFIG.MAX_PER_CELL"]) == ("orb", "15")
    assert config["CONFIG.ORB_MAX_CELL"] == "32"
    _, plain = bd_run("create_bd_plain", ["--board", "none"])
    assert "CONFIG.DESCRIPTOR" not in cell_config(plain, "fastnms")
    _, refused = bd_run("create_bd_orb_region", ["--board", "none", "--orb", "--nms", "region4"])
    assert "--orb needs --nms 3x3 or none" in (refused.error or "")


@needs_tcl
def test_create_bd_board_choice() -> None:
    # The newest version by number, whatever the vendor's name.
    parts = "em.avnet.com:zed:part0:1.4 avnet.com:zedboard:part0:1.10 avnet.com:zedboard:part0:1.9"
    root, run = bd_run("create_bd_board", ["--board", "zedboard"], {"get_board_parts": parts})
    run.assert_clean()
    assert board_parts_set(run) == ["avnet.com:zedboard:part0:1.10"]
    patterns = [c[-1] for c in run.of("get_board_parts")]
    assert patterns == ["*:zedboard:part0:*", "*:zed:part0:*"]

    # Board files missing: an error naming the board, no silent fallback.
    for board in ("zedboard", "zc702"):
        root, run = bd_run(
            f"create_bd_no_board_{board}", ["--board", board], {"get_board_parts": ""}
        )
        assert run.error and f"no board files for {board}" in run.error
        assert not board_parts_set(run)

    # --board none: no board part, no preset, the DDR part set.
    root, run = bd_run("create_bd_board_none", ["--board", "none"])
    run.assert_clean()
    assert not run.of("get_board_parts")
    assert "apply_board_preset 0" in run.text
    assert "CONFIG.PCW_UIPARAM_DDR_PARTNO MT41K128M16 JT-125" in run.text


@needs_tcl
def test_create_bd_with_implementation() -> None:
    results = {
        "get_property CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ": "125.000000",
        "get_property PROGRESS": "100%",
        "get_property SLACK": "0.412",
    }
    argv = ["--board", "zc702", "--impl", "--jobs", "8", "--fclk-mhz", "125"]
    root, run = bd_run("create_bd_impl", argv, results)
    run.assert_clean()
    runs = run.of("launch_runs")
    assert [r[1] for r in runs] == ["synth_1", "impl_1"]
    assert runs[1][runs[1].index("-to_step") + 1] == "write_bitstream"
    assert all(r[r.index("-jobs") + 1] == "8" for r in runs)
    assert run.of("write_hw_platform")
    assert "CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ 125.000000" in run.text

    # A failed run stops the script.
    root, run = bd_run(
        "create_bd_impl_fail", ["--board", "zc702", "--impl"], {"get_property PROGRESS": "0%"}
    )
    assert run.error and "synthesis failed" in run.error


def region_tops_fmax() -> dict[str, float]:
    """The region NMS's AXI tops' ECP5-8 Fmax in docs/results.md (make synth's table)."""
    rows = re.findall(
        r"^\| fastnms `fastnms_axi` \| (sad \+ region4|opencv \+ region8) \|.*?\| "
        r"(\d+) MHz on ECP5-8 \|",
        (REPO / "docs" / "results.md").read_text(),
        re.M,
    )
    return {config: float(mhz) for config, mhz in rows}


@needs_tcl
def test_region_clock_follows_the_measurements() -> None:
    """With a region NMS, FCLK_CLK0 defaults to the fastest IO PLL clock (1000 / N MHz)
    at most 0.90 of the slower region top's ECP5-8 Fmax in docs/results.md, as the
    3x3's 1000 / 7 was chosen (vivado/README.md): when make synth moves the tops, this
    test says the default must follow."""
    fmax = region_tops_fmax()
    assert sorted(fmax) == ["opencv + region8", "sad + region4"], fmax
    divide = math.ceil(1000 / (0.90 * min(fmax.values())))
    assert tcl("fastnms::fclk_mhz region8") == f"{1000 / divide:.6f}", (fmax, divide)


@needs_tcl
def test_create_bd_region_nms_default_clock() -> None:
    """With a region NMS FCLK_CLK0 defaults to fastnms::fclk_mhz region8 (above)."""
    mhz = tcl("fastnms::fclk_mhz region8")
    results = {"get_property CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ": mhz}
    root, run = bd_run("create_bd_region", ["--board", "zc702", "--nms", "region8"], results)
    run.assert_clean()
    assert f"CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ {mhz}" in run.text
    assert "CONFIG.NMS region8" in run.text


@needs_tcl
def test_create_bd_stops_when_the_ps_gives_another_clock() -> None:
    root, run = bd_run(
        "create_bd_fclk",
        ["--board", "zc702"],
        {"get_property CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ": "150.000000"},
    )
    assert run.error and "requested 142.857143 MHz, the PS gives '150.000000' MHz" in run.error
    assert not run.of("validate_bd_design")


@needs_tcl
@pytest.mark.parametrize(
    ("argv", "message"),
    [
        ([], "--board is required"),
        (["--board", "auto"], "--board must be zedboard, zc702 or none"),
        (["--board", "zc702", "--fclk-mhz", "150"], "150 MHz is not 1000 MHz (IO PLL) divided"),
        (["--board", "zc702", "--fclk-mhz", "fast"], "must be a frequency in MHz"),
        (["--board", "zc702", "--bogus", "1"], "unknown option '--bogus'"),
        (["--board", "zc702", "--out"], "option --out needs a value"),
    ],
)
def test_create_bd_rejects_bad_options(argv: list[str], message: str) -> None:
    root, run = bd_run(f"create_bd_options{len(argv)}{len(message)}", argv)
    assert run.error and message in run.error
    assert not run.calls


@needs_tcl
def test_create_bd_needs_the_packaged_ip() -> None:
    root = sandbox("create_bd_no_ip")
    calls, error = tclcheck.dry_run(
        root / "vivado" / "create_bd_zc7z20.tcl",
        ["--board", "zc702", "--ip-repo", str(root / "nothing")],
    )
    assert error and "run vivado/package_ip.tcl first" in error


# ---- dry runs: synth_ooc.tcl ------------------------------------------------------------


@needs_tcl
def test_synth_ooc() -> None:
    root = sandbox("synth_ooc")
    out = root / "out"
    run = dry_run(
        root,
        "synth_ooc.tcl",
        ["--out", str(out), "--generics", "SCORE=sad NMS=none"],
        {"get_property SLACK": "0.5"},
    )
    run.assert_clean()
    read = [Path(c[-1]) for c in run.of("read_vhdl")]
    assert all(c[1] == "-vhdl2008" for c in run.of("read_vhdl"))
    assert sorted(read) == sorted((root / "rtl").rglob("*.vhd"))
    assert not order_problems_in(read, root)
    assert run.of("read_xdc") == [
        ["read_xdc", "-mode", "out_of_context", str(root / "constraints" / "fastnms_ooc.xdc")]
    ]
    (synth,) = run.of("synth_design")
    assert synth[synth.index("-top") + 1] == "fastnms_axi"
    assert synth[synth.index("-part") + 1] == PART
    assert synth[synth.index("-mode") + 1] == "out_of_context"
    assert synth[-4:] == ["-generic", "SCORE=sad", "-generic", "NMS=none"]
    assert run.of("route_design")
    order = [c[0] for c in run.calls]
    assert order.index("read_xdc") < order.index("synth_design") < order.index("route_design")
    summary = (out / "summary.txt").read_text()
    assert "period 7.000 ns, worst setup slack 0.5 ns" in summary
    assert "met at 153.8 MHz" in summary


def order_problems_in(files: list[Path], root: Path) -> list[str]:
    """order_problems for files of a sandbox copy, checked on the originals."""
    return order_problems([REPO / f.relative_to(root) for f in files])


@needs_tcl
def test_synth_ooc_options() -> None:
    root = sandbox("synth_ooc_options")
    run = dry_run(
        root,
        "synth_ooc.tcl",
        ["--top", "fastnms_core", "--clock-port", "clk", "--synth-only", "--out", str(root / "o")],
        {"get_property SLACK": "1.0"},
    )
    run.assert_clean()
    assert not run.of("route_design")
    (xdc,) = run.of("read_xdc")
    clock_xdc = Path(xdc[-1]).read_text()
    assert "create_clock -period 7.000 -name clk [get_ports clk]" in clock_xdc

    script = root / "vivado" / "synth_ooc.tcl"
    _, error = tclcheck.dry_run(
        script, ["--require-timing", "--out", str(root / "t")], {"get_property SLACK": "-0.1"}
    )
    assert error and "worst setup slack -0.1 ns" in error
    _, error = tclcheck.dry_run(script, ["--generics", "SCORE"], {"get_property SLACK": "1"})
    assert error and "a generic is NAME=VALUE" in error


# ---- the top level ------------------------------------------------------------------------

# The names create_bd_zc7z20.tcl and package_ip.tcl use on the IP.
BUS_PORTS = {
    "s_axis_video": ["tdata", "tuser", "tlast", "tvalid", "tready"],
    "m_axis_corners": ["tdata", "tkeep", "tlast", "tvalid", "tready"],
    "m_axis_score": ["tdata", "tuser", "tlast", "tvalid", "tready"],
    "s_axi_ctrl": [
        "awaddr", "awprot", "awvalid", "awready", "wdata", "wstrb", "wvalid", "wready",
        "bresp", "bvalid", "bready", "araddr", "arprot", "arvalid", "arready",
        "rdata", "rresp", "rvalid", "rready",
    ],
}  # fmt: skip


def test_top_has_the_ports_the_scripts_use() -> None:
    ports = set(xinterface.load(TOP).ports)
    expected = {"aclk", "aresetn", "interrupt"} | {
        f"{bus}_{signal}" for bus, signals in BUS_PORTS.items() for signal in signals
    }
    assert not expected - ports, f"missing in fastnms_axi: {sorted(expected - ports)}"


def ghdl(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["ghdl", *args], cwd=cwd, capture_output=True, text=True)


@needs_tcl
def test_ip_wrapper_is_vhdl93_and_elaborates() -> None:
    """The IP packager reads the top-level file as VHDL-93 (UG1118), so
    package_ip.tcl packages a generated wrapper, fastnms_axi_ip. It must be
    VHDL-93 (analysed here against fastnms_axi's entity declaration alone, in
    a VHDL-93 library) and must elaborate with the real VHDL-2008 RTL."""
    if shutil.which("ghdl") is None:
        pytest.skip("no ghdl")
    work = WORK / "ip_wrapper"
    shutil.rmtree(work, ignore_errors=True)
    (work / "93").mkdir(parents=True)
    (work / "08").mkdir()
    wrapper = work / "fastnms_axi_ip.vhd"
    wrapper.write_text(tcl(f"fastnms::ip_wrapper {{{TOP}}} fastnms_axi fastnms_axi_ip"))
    text = wrapper.read_text()
    assert "entity fastnms_axi_ip is" in text and "ip : entity work.fastnms_axi" in text

    # VHDL-93: the wrapper against the entity declaration alone.
    declaration = text[: text.index("architecture wrapper")].replace(
        "fastnms_axi_ip", "fastnms_axi"
    )
    stub = work / "fastnms_axi_entity.vhd"
    stub.write_text(
        declaration + "\narchitecture stub of fastnms_axi is\nbegin\nend architecture stub;\n"
    )
    for step in (
        ["-a", "--std=93c", str(stub)],
        ["-a", "--std=93c", str(wrapper)],
        ["-e", "--std=93c", "fastnms_axi_ip"],
    ):
        proc = ghdl(*step, cwd=work / "93")
        assert proc.returncode == 0, f"ghdl {' '.join(step)}:\n{proc.stderr}"

    # With the RTL (compile order as package_ip.tcl gives it).
    sources = [str(f) for f in tcl_rtl_files()] + [str(wrapper)]
    for step in (
        ["-a", "--std=08", *sources],
        ["-e", "--std=08", "fastnms_axi_ip"],
        ["-r", "--std=08", "fastnms_axi_ip", "--stop-time=0ns", "--ieee-asserts=disable"],
    ):
        proc = ghdl(*step, cwd=work / "08")
        assert proc.returncode == 0, f"ghdl {step[0]}:\n{proc.stderr}"
