"""The Vivado scripts (vivado/*.tcl) and constraints, checked without Vivado.

Every command of every script is complete Tcl; each script is dry-run under a
real Tcl interpreter with the Vivado commands stubbed (tclcheck.dry_run), so
its own logic, options, paths and file lists run for real; the RTL file list it
builds covers rtl/ in compile order; and the names it uses exist in
rtl/top/fastnms_axi.vhd once that file exists. What Vivado itself would say
about the commands is not checked here (no Vivado).
"""

from __future__ import annotations

import re
import shutil
import subprocess
import tomllib
from pathlib import Path

import pytest
from fastnms.sim.sources import REPO, all_rtl_files, order_problems

from flows.vivado_check import tclcheck

VIVADO = REPO / "vivado"
SCRIPTS = sorted(VIVADO.glob("*.tcl"))
XDC = REPO / "constraints" / "fastnms_ooc.xdc"
TOP = REPO / "rtl" / "top" / "fastnms_axi.vhd"
WORK = REPO / "build" / "test_vivado_tcl"
PART = "xc7z020clg484-1"

needs_tcl = pytest.mark.skipif(
    tclcheck.backend() is None, reason="no Tcl interpreter (neither tkinter nor tclsh)"
)


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
    session that sources the script), no path of one machine."""
    code = "\n".join(
        line.split("#", 1)[0] if line.lstrip().startswith("#") else line
        for line in path.read_text().splitlines()
    )
    for command in tclcheck.TCL86_ONLY:
        assert not re.search(rf"(^|[\[;{{\s]){command}\s", code), f"Tcl 8.6 only: {command}"
    assert not re.search(r"(^|[\[;{\s])exit(\s|$|\])", code), "the script calls exit"
    text = path.read_text()
    assert not re.search(r"(/home/|/work/|/tmp/|/opt/|[A-Za-z]:\\)", text), "absolute path"


# ---- the RTL file list -----------------------------------------------------------


def tcl_rtl_files() -> list[Path]:
    out = tclcheck.run_tcl(
        f"source {{{VIVADO / 'fastnms_common.tcl'}}}\nreturn [join [fastnms::rtl_files] \\n]"
    )
    return [Path(line) for line in out.splitlines()]


@needs_tcl
def test_rtl_list_is_every_rtl_file_in_compile_order() -> None:
    files = tcl_rtl_files()
    assert sorted(files) == all_rtl_files(), (
        "fastnms::rtl_files (vivado/fastnms_common.tcl) differs from rtl/**/*.vhd: "
        "a file in a folder outside fastnms::areas?"
    )
    assert not order_problems(files)


@needs_tcl
def test_ooc_period_is_the_bd_clock() -> None:
    period = float(
        tclcheck.run_tcl(f"source {{{VIVADO / 'fastnms_common.tcl'}}}\nfastnms::ooc_period")
    )
    assert period == pytest.approx(1000 / 150, abs=0.001)
    assert re.search(r"--fclk-mhz\s+150\b", (VIVADO / "create_bd_zc7z20.tcl").read_text())
    assert re.search(r"\[get_ports aclk\]", XDC.read_text())


def test_ip_version_follows_the_project_version() -> None:
    project = tomllib.loads((REPO / "pyproject.toml").read_text())["project"]["version"]
    tcl = (VIVADO / "fastnms_common.tcl").read_text()
    version = re.search(r"variable version\s+(\S+)", tcl).group(1)
    assert version == ".".join(project.split(".")[:2])


def test_build_outputs_are_ignored() -> None:
    if not (REPO / ".git").exists() or shutil.which("git") is None:
        pytest.skip("not a git checkout")
    paths = ["build/vivado/ip/component.xml", "build/fusesoc/sim/Makefile", "vivado.jou", ".Xil/x"]
    out = subprocess.run(
        ["git", "check-ignore", *paths], cwd=REPO, capture_output=True, text=True
    ).stdout.split()
    assert out == paths


# ---- dry runs --------------------------------------------------------------------


def sandbox(name: str, *, with_top: bool = True) -> Path:
    """A copy of vivado/, constraints/ and rtl/ under build/; with a placeholder
    rtl/top/fastnms_axi.vhd (instantiating fastnms_core) when the real one does
    not exist yet."""
    root = WORK / name
    shutil.rmtree(root, ignore_errors=True)
    for folder in ("vivado", "constraints", "rtl"):
        shutil.copytree(REPO / folder, root / folder)
    top = root / "rtl" / "top" / "fastnms_axi.vhd"
    if with_top and not top.exists():
        top.write_text(
            "entity fastnms_axi is\nend entity fastnms_axi;\n\n"
            "architecture rtl of fastnms_axi is\nbegin\n\n"
            "  core : entity work.fastnms_core;\n\nend architecture rtl;\n"
        )
    if not with_top:
        top.unlink(missing_ok=True)
    return root


def calls_of(calls: list[list[str]], command: str) -> list[list[str]]:
    return [c for c in calls if c[0] == command]


def words(call: list[str]) -> str:
    return " ".join(call)


@needs_tcl
def test_package_ip() -> None:
    root = sandbox("package_ip")
    out = root / "out" / "ip"
    calls, error = tclcheck.dry_run(root / "vivado" / "package_ip.tcl", ["--out", str(out)])
    assert error is None, error
    (create,) = calls_of(calls, "create_project")
    assert create[-2:] == ["-part", PART]
    assert Path(create[3]) == out.parent / "package_ip_project"

    (add,) = calls_of(calls, "add_files")
    *files, wrapper = [Path(f) for f in add[-1].split()]
    rtl = root / "rtl"
    assert sorted(files) == sorted(rtl.rglob("*.vhd")), "not every rtl/**/*.vhd is packaged"
    assert files[-1] == rtl / "top" / "fastnms_axi.vhd"
    assert wrapper == out.parent / "ip_wrapper" / "fastnms_axi_ip.vhd"
    assert "entity fastnms_axi_ip is" in wrapper.read_text()
    types = {c[2]: c[3] for c in calls if c[:2] == ["set_property", "file_type"]}
    rtl_list = " ".join(str(f) for f in files)
    assert types == {"VHDL 2008": f"{{get_files {rtl_list}}}", "VHDL": f"{{get_files {wrapper}}}"}
    assert ["set_property", "top", "fastnms_axi_ip", "{current_fileset }"] in calls

    (package,) = calls_of(calls, "ipx::package_project")
    assert package[package.index("-root_dir") + 1] == str(out)
    assert package[package.index("-vendor") + 1] == "fastnms"
    assert "-import_files" in package
    props = {c[1]: c[2] for c in calls if c[0] == "set_property" and c[-1] == "{current_core }"}
    assert props["name"] == "fastnms_axi" and props["version"] == "0.1"
    assert "zynq Production" in " ".join(props["supported_families"].split())
    assert "artix7 Production" in " ".join(props["supported_families"].split())

    # No inference needed: the stubs find every interface.
    assert not calls_of(calls, "ipx::infer_bus_interfaces")
    text = "\n".join(words(c) for c in calls)
    assert (
        "set_property enablement_dependency $SCORE_VIDEO {get_bus_interfaces m_axis_score" in text
    )
    assert "set_property driver_value 1 {get_ports m_axis_score_tready" in text
    assert "value_validation_list opencv sad" in text
    assert "value_validation_list 3x3 none region4 region8" in text
    assert "value_validation_type range_long {get_user_parameters MAX_WIDTH" in text
    assert "widget checkBox {get_guiparamspec SCORE_VIDEO" in text
    assert "value_validation_type list {get_user_parameters CORNER_FIFO_DEPTH" in text
    for command in ("ipx::create_xgui_files", "ipx::save_core", "ipx::archive_core"):
        assert calls_of(calls, command), command
    assert calls[-1] == ["close_project"]


@needs_tcl
def test_package_ip_infers_missing_interfaces_then_gives_up() -> None:
    root = sandbox("package_ip_infer")
    calls, error = tclcheck.dry_run(
        root / "vivado" / "package_ip.tcl",
        ["--out", str(root / "out" / "ip")],
        {"ipx::get_bus_interfaces": ""},
    )
    assert error and "no bus interface s_axis_video m_axis_corners" in error
    inferred = [c[1] for c in calls_of(calls, "ipx::infer_bus_interfaces")]
    assert "xilinx.com:interface:axis_rtl:1.0" in inferred
    assert "xilinx.com:interface:aximm_rtl:1.0" in inferred


@needs_tcl
def test_package_ip_needs_the_top_level() -> None:
    root = sandbox("package_ip_no_top", with_top=False)
    calls, error = tclcheck.dry_run(root / "vivado" / "package_ip.tcl", [])
    assert error and "fastnms_axi.vhd does not exist" in error
    assert not calls


def fake_ip_repo(root: Path) -> Path:
    repo = root / "ip"
    repo.mkdir(parents=True, exist_ok=True)
    (repo / "component.xml").write_text("<placeholder/>\n")
    return repo


BD_RESULTS = {"get_property CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ": "151.515"}


@needs_tcl
def test_create_bd() -> None:
    root = sandbox("create_bd")
    out = root / "out"
    calls, error = tclcheck.dry_run(
        root / "vivado" / "create_bd_zc7z20.tcl",
        ["--ip-repo", str(fake_ip_repo(root)), "--out", str(out)],
        BD_RESULTS,
    )
    assert error is None, error
    (create,) = calls_of(calls, "create_project")
    assert create[-2:] == ["-part", PART] and Path(create[3]) == out
    # A board part is found (the stub answers), so it is used with its preset.
    assert any(c[:2] == ["set_property", "board_part"] for c in calls)
    text = "\n".join(words(c) for c in calls)
    assert "apply_board_preset 1" in text

    cells = {c[-1]: c[c.index("-vlnv") + 1] for c in calls_of(calls, "create_bd_cell")}
    assert cells == {
        "ps7": "xilinx.com:ip:processing_system7",
        "fastnms": "fastnms:vision:fastnms_axi:0.1",
        "vdma": "xilinx.com:ip:axi_vdma",
        "dma": "xilinx.com:ip:axi_dma",
        "ctrl_smc": "xilinx.com:ip:smartconnect",
        "mem_smc": "xilinx.com:ip:smartconnect",
        "rst": "xilinx.com:ip:proc_sys_reset",
        "irq_concat": "xilinx.com:ip:xlconcat",
    }

    def config(cell: str) -> dict[str, str]:
        target = next(c for c in calls_of(calls, "create_bd_cell") if c[-1] == cell)
        obj = (
            "{" + "create_bd_cell " + " ".join(w for w in target[1:] if not w.startswith("-")) + "}"
        )
        settings: dict[str, str] = {}
        for c in calls:
            if c[0] == "set_property" and c[-1] == obj:
                pairs = c[2].split() if c[1] == "-dict" else c[1:3]
                settings.update(zip(pairs[::2], pairs[1::2], strict=True))
        return settings

    ps = config("ps7")
    for key, value in {
        "CONFIG.PCW_USE_M_AXI_GP0": "1",
        "CONFIG.PCW_USE_S_AXI_HP0": "1",
        "CONFIG.PCW_S_AXI_HP0_DATA_WIDTH": "64",
        "CONFIG.PCW_EN_CLK0_PORT": "1",
        "CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ": "150",
        "CONFIG.PCW_USE_FABRIC_INTERRUPT": "1",
        "CONFIG.PCW_IRQ_F2P_INTR": "1",
    }.items():
        assert ps[key] == value, key
    vdma = config("vdma")
    assert vdma["CONFIG.c_include_s2mm"] == "0" and vdma["CONFIG.c_include_mm2s"] == "1"
    assert vdma["CONFIG.c_m_axis_mm2s_tdata_width"] == "8"
    dma = config("dma")
    assert dma["CONFIG.c_include_mm2s"] == "0" and dma["CONFIG.c_include_s2mm"] == "1"
    assert dma["CONFIG.c_include_sg"] == "0"
    assert dma["CONFIG.c_s_axis_s2mm_tdata_width"] == "64"
    assert config("fastnms")["CONFIG.SCORE_VIDEO"] == "false"
    assert config("irq_concat")["CONFIG.NUM_PORTS"] == "3"

    def pins(call: list[str]) -> set[str]:
        return {w.strip("{}").split()[-1] for w in call[1:]}

    intf = [pins(c) for c in calls_of(calls, "connect_bd_intf_net")]
    for pair in (
        {"ps7/M_AXI_GP0", "ctrl_smc/S00_AXI"},
        {"ctrl_smc/M00_AXI", "fastnms/s_axi_ctrl"},
        {"vdma/M_AXIS_MM2S", "fastnms/s_axis_video"},
        {"fastnms/m_axis_corners", "dma/S_AXIS_S2MM"},
        {"mem_smc/M00_AXI", "ps7/S_AXI_HP0"},
    ):
        assert pair in intf, pair
    nets = [pins(c) for c in calls_of(calls, "connect_bd_net")]
    clock = next(n for n in nets if "ps7/FCLK_CLK0" in n)
    assert {"fastnms/aclk", "vdma/m_axis_mm2s_aclk", "dma/m_axi_s2mm_aclk"} <= clock
    assert {"ps7/M_AXI_GP0_ACLK", "ps7/S_AXI_HP0_ACLK"} <= clock
    assert {"fastnms/interrupt", "irq_concat/In0"} in nets
    assert {"dma/s2mm_introut", "irq_concat/In1"} in nets
    assert {"vdma/mm2s_introut", "irq_concat/In2"} in nets
    assert {"irq_concat/dout", "ps7/IRQ_F2P"} in nets
    assert any("fastnms/aresetn" in n and "rst/peripheral_aresetn" in n for n in nets)

    order = [c[0] for c in calls]
    for earlier, later in (
        ("assign_bd_address", "validate_bd_design"),
        ("validate_bd_design", "make_wrapper"),
    ):
        assert order.index(earlier) < order.index(later)
    assert (out / "address_map.txt").exists()
    assert not calls_of(calls, "launch_runs")


@needs_tcl
def test_create_bd_without_board_files() -> None:
    root = sandbox("create_bd_no_board")
    repo = fake_ip_repo(root)
    results = {**BD_RESULTS, "get_board_parts": ""}
    calls, error = tclcheck.dry_run(
        root / "vivado" / "create_bd_zc7z20.tcl", ["--ip-repo", str(repo)], results
    )
    assert error is None, error
    text = "\n".join(words(c) for c in calls)
    assert "apply_board_preset 0" in text
    assert "CONFIG.PCW_UIPARAM_DDR_PARTNO MT41K128M16 JT-125" in text
    assert not any(c[:2] == ["set_property", "board_part"] for c in calls)

    # An explicit board without its files is an error.
    calls, error = tclcheck.dry_run(
        root / "vivado" / "create_bd_zc7z20.tcl",
        ["--ip-repo", str(repo), "--board", "zc702"],
        results,
    )
    assert error and "no board files for zc702" in error


@needs_tcl
def test_create_bd_with_implementation() -> None:
    root = sandbox("create_bd_impl")
    results = {
        **BD_RESULTS,
        "get_property PROGRESS": "100%",
        "get_property SLACK": "0.412",
    }
    calls, error = tclcheck.dry_run(
        root / "vivado" / "create_bd_zc7z20.tcl",
        ["--ip-repo", str(fake_ip_repo(root)), "--impl", "--jobs", "8", "--fclk-mhz", "125"],
        results,
    )
    assert error is None, error
    runs = calls_of(calls, "launch_runs")
    assert [r[1] for r in runs] == ["synth_1", "impl_1"]
    assert runs[1][runs[1].index("-to_step") + 1] == "write_bitstream"
    assert all(r[r.index("-jobs") + 1] == "8" for r in runs)
    assert calls_of(calls, "write_hw_platform")
    assert "CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ 125" in "\n".join(words(c) for c in calls)

    # A failed run stops the script.
    _, error = tclcheck.dry_run(
        root / "vivado" / "create_bd_zc7z20.tcl",
        ["--ip-repo", str(fake_ip_repo(WORK / "create_bd_impl_fail")), "--impl"],
        {**results, "get_property PROGRESS": "0%"},
    )
    assert error and "synthesis failed" in error


@needs_tcl
@pytest.mark.parametrize(
    ("argv", "message"),
    [
        (["--board", "zcu102"], "--board must be"),
        (["--fclk-mhz", "fast"], "--fclk-mhz must be"),
        (["--bogus", "1"], "unknown option '--bogus'"),
        (["--out"], "option --out needs a value"),
    ],
)
def test_create_bd_rejects_bad_options(argv: list[str], message: str) -> None:
    root = sandbox(f"create_bd_options{argv[0]}{len(argv)}")
    calls, error = tclcheck.dry_run(
        root / "vivado" / "create_bd_zc7z20.tcl",
        ["--ip-repo", str(fake_ip_repo(root)), *argv],
        BD_RESULTS,
    )
    assert error and message in error
    assert not calls


@needs_tcl
def test_create_bd_needs_the_packaged_ip() -> None:
    root = sandbox("create_bd_no_ip")
    _, error = tclcheck.dry_run(
        root / "vivado" / "create_bd_zc7z20.tcl", ["--ip-repo", str(root / "nothing")]
    )
    assert error and "run vivado/package_ip.tcl first" in error


@needs_tcl
def test_synth_ooc() -> None:
    root = sandbox("synth_ooc")
    out = root / "out"
    calls, error = tclcheck.dry_run(
        root / "vivado" / "synth_ooc.tcl",
        ["--out", str(out), "--generics", "SCORE=sad NMS=none"],
        {"get_property SLACK": "0.5"},
    )
    assert error is None, error
    read = [Path(c[-1]) for c in calls_of(calls, "read_vhdl")]
    assert all(c[1] == "-vhdl2008" for c in calls_of(calls, "read_vhdl"))
    assert sorted(read) == sorted((root / "rtl").rglob("*.vhd"))
    assert not order_problems_in(read, root)
    assert calls_of(calls, "read_xdc") == [
        ["read_xdc", "-mode", "out_of_context", str(root / "constraints" / "fastnms_ooc.xdc")]
    ]
    (synth,) = calls_of(calls, "synth_design")
    assert synth[synth.index("-top") + 1] == "fastnms_axi"
    assert synth[synth.index("-part") + 1] == PART
    assert synth[synth.index("-mode") + 1] == "out_of_context"
    assert synth[-4:] == ["-generic", "SCORE=sad", "-generic", "NMS=none"]
    assert calls_of(calls, "route_design")
    order = [c[0] for c in calls]
    assert order.index("read_xdc") < order.index("synth_design") < order.index("route_design")
    summary = (out / "summary.txt").read_text()
    assert "worst setup slack 0.5 ns" in summary and "met at 162.2 MHz" in summary


def order_problems_in(files: list[Path], root: Path) -> list[str]:
    """order_problems for files of a sandbox copy, checked on the originals."""
    return order_problems([REPO / f.relative_to(root) for f in files if f.name != TOP.name])


@needs_tcl
def test_synth_ooc_options() -> None:
    root = sandbox("synth_ooc_options")
    script = root / "vivado" / "synth_ooc.tcl"
    calls, error = tclcheck.dry_run(
        script,
        ["--top", "fastnms_core", "--clock-port", "clk", "--synth-only", "--out", str(root / "o")],
        {"get_property SLACK": "1.0"},
    )
    assert error is None, error
    assert not calls_of(calls, "route_design")
    (xdc,) = calls_of(calls, "read_xdc")
    clock_xdc = Path(xdc[-1]).read_text()
    assert "create_clock -period 6.667 -name clk [get_ports clk]" in clock_xdc

    _, error = tclcheck.dry_run(
        script, ["--require-timing", "--out", str(root / "t")], {"get_property SLACK": "-0.1"}
    )
    assert error and "worst setup slack -0.1 ns" in error
    _, error = tclcheck.dry_run(script, ["--generics", "SCORE"], {"get_property SLACK": "1"})
    assert error and "a generic is NAME=VALUE" in error


# ---- the top level, once it exists ---------------------------------------------------

# The names create_bd_zc7z20.tcl and package_ip.tcl use on the IP.
BUS_PORTS = {
    "s_axis_video": ["tdata", "tuser", "tlast", "tvalid", "tready"],
    "m_axis_corners": ["tdata", "tlast", "tvalid", "tready"],
    "m_axis_score": ["tdata", "tuser", "tlast", "tvalid", "tready"],
    "s_axi_ctrl": [
        "awaddr", "awprot", "awvalid", "awready", "wdata", "wstrb", "wvalid", "wready",
        "bresp", "bvalid", "bready", "araddr", "arprot", "arvalid", "arready",
        "rdata", "rresp", "rvalid", "rready",
    ],
}  # fmt: skip

needs_top = pytest.mark.skipif(
    not TOP.exists(), reason="rtl/top/fastnms_axi.vhd does not exist yet"
)


def top_ports() -> set[str]:
    text = re.sub(r"--[^\n]*", "", TOP.read_text()).lower()
    entity = re.search(r"\bentity\s+fastnms_axi\s+is(.*?)\bend\b", text, re.DOTALL)
    assert entity, "no entity fastnms_axi in rtl/top/fastnms_axi.vhd"
    return set(re.findall(r"(\w+)\s*:\s*(?:in|out|inout)\b", entity.group(1)))


@needs_top
def test_top_has_the_ports_the_scripts_use() -> None:
    ports = top_ports()
    expected = {"aclk", "aresetn", "interrupt"} | {
        f"{bus}_{signal}" for bus, signals in BUS_PORTS.items() for signal in signals
    }
    assert not expected - ports, f"missing in fastnms_axi: {sorted(expected - ports)}"


@needs_top
def test_top_names_its_bus_interfaces() -> None:
    """X_INTERFACE_INFO names the interfaces as the scripts do."""
    text = TOP.read_text()
    infos = re.findall(r'"xilinx\.com:(?:interface|signal):(\w+):1\.0\s+(\w+)', text)
    names = {name for _, name in infos}
    assert {"s_axis_video", "m_axis_corners", "m_axis_score", "s_axi_ctrl"} <= names
    assert {"aclk", "aresetn", "interrupt"} <= names


def ghdl(*args: str, cwd: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run(["ghdl", *args], cwd=cwd, capture_output=True, text=True)


@needs_tcl
@needs_top
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
    wrapper.write_text(
        tclcheck.run_tcl(
            f"source {{{VIVADO / 'fastnms_common.tcl'}}}\n"
            f"fastnms::ip_wrapper {{{TOP}}} fastnms_axi fastnms_axi_ip"
        )
    )
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
