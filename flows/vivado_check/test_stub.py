"""The stub rejects what Vivado would reject: each case dry-runs a copy of a
script with one name misspelt (a command, an option, a property, a CONFIG
key or value, a pin, a VLNV, an automation key, a bus parameter, a name of
the top level) and expects stubcheck to report it. The unmodified scripts run
clean (test_vivado_tcl.py)."""

from __future__ import annotations

import pytest

from flows.vivado_check import stubcheck, tclcheck, vivado_api
from flows.vivado_check.harness import (
    BD_RESULTS,
    PACKAGE_RESULTS,
    dry_run,
    fake_ip_repo,
    mutate,
    sandbox,
)

needs_tcl = pytest.mark.skipif(tclcheck.backend() is None, reason="no Tcl interpreter")

BD = "create_bd_zc7z20.tcl"
PACKAGE = "package_ip.tcl"
OOC = "synth_ooc.tcl"

# script, the text replaced, its replacement, a problem (or error) it must cause.
MUTATIONS = {
    "config key": (
        BD,
        "CONFIG.c_sg_length_width           {26}",
        "CONFIG.c_sg_lenght_width           {26}",
        "xilinx.com:ip:axi_dma has no CONFIG.C_SG_LENGHT_WIDTH",
    ),
    "config value": (
        BD,
        "CONFIG.c_sg_length_width           {26}",
        "CONFIG.c_sg_length_width           {27}",
        "CONFIG.C_SG_LENGTH_WIDTH 27 not in range(8, 27)",
    ),
    "ps7 config key": (
        BD,
        "CONFIG.PCW_FCLK_CLK0_BUF             {TRUE}",
        "CONFIG.PCW_FCLK0_BUF                 {TRUE}",
        "processing_system7 has no CONFIG.PCW_FCLK0_BUF",
    ),
    "config key of the packaged ip": (
        BD,
        "CONFIG.SCORE_VIDEO {false}",
        "CONFIG.SCORE_VIDE {false}",
        "fastnms:vision:fastnms_axi has no CONFIG.SCORE_VIDE",
    ),
    "vlnv": (
        BD,
        "xilinx.com:ip:axi_dma dma]",
        "xilinx.com:ip:axi_dmaa dma]",
        "unknown VLNV 'xilinx.com:ip:axi_dmaa'",
    ),
    "vlnv version": (
        BD,
        "xilinx.com:ip:proc_sys_reset rst]",
        "xilinx.com:ip:proc_sys_reset:5.1 rst]",
        "unknown VLNV 'xilinx.com:ip:proc_sys_reset:5.1'",
    ),
    "interface pin": (
        BD,
        "fastnms/m_axis_corners dma/S_AXIS_S2MM",
        "fastnms/m_axis_corners dma/S_AXIS_S2M",
        "(dma) has no interface pin S_AXIS_S2M",
    ),
    "pin of the packaged ip": (
        BD,
        "fastnms/aclk",
        "fastnms/clk",
        "(fastnms) has no pin clk",
    ),
    "pin its configuration removes": (
        BD,
        "set_property CONFIG.NUM_PORTS {3} $irq",
        "set_property CONFIG.NUM_PORTS {2} $irq",
        "(irq_concat) has no pin In2 as configured",
    ),
    "cell": (BD, "ctrl_smc/aclk", "ctrl_sm/aclk", "no cell ctrl_sm"),
    "option": (
        BD,
        "launch_runs impl_1 -to_step",
        "launch_runs impl_1 -to_stepp",
        "launch_runs: no option -to_stepp",
    ),
    "command": (
        BD,
        "\nvalidate_bd_design\n",
        "\nvalidate_bd_desing\n",
        "validate_bd_desing: not a Vivado command",
    ),
    "required option": (
        BD,
        "apply_bd_automation -rule xilinx.com:bd_rule:processing_system7 -config",
        "apply_bd_automation -config",
        "apply_bd_automation: the required option -rule is missing",
    ),
    "too many arguments": (
        BD,
        "create_bd_design $design",
        "create_bd_design $design $project",
        "create_bd_design: 2 arguments",
    ),
    "automation key": (
        BD,
        "apply_board_preset [expr",
        "apply_board_presets [expr",
        "has no -config key apply_board_presets",
    ),
    "property": (
        BD,
        "set_property ip_repo_paths",
        "set_property ip_repo_path",
        "project objects have no property ip_repo_path",
    ),
    "global proc": (
        BD,
        "proc fastnms::connect_pins {driver loads}",
        "proc connect_net {driver loads}",
        "proc 'connect_net' in the global namespace could hide a Vivado",
    ),
    "packager option": (
        PACKAGE,
        "ipx::package_project -root_dir",
        "ipx::package_project -root",
        "ipx::package_project: no option -root (an abbreviation of -root_dir)",
    ),
    "port of the top": (
        PACKAGE,
        "ipx::get_ports m_axis_score_tready",
        "ipx::get_ports m_axis_score_trdy",
        "fastnms_axi has no port m_axis_score_trdy",
    ),
    "generic of the top": (
        PACKAGE,
        "fastnms::gui_list $core NMS {",
        "fastnms::gui_list $core NSM {",
        "fastnms_axi has no generic NSM",
    ),
    "bus parameter": (
        PACKAGE,
        "aresetn      POLARITY    ACTIVE_LOW",
        "aresetn      POLARTY     ACTIVE_LOW",
        "unknown bus parameter POLARTY",
    ),
    "packager property": (
        PACKAGE,
        "set_property usage register $block",
        "set_property usage_type register $block",
        "ipx_address_block objects have no property usage_type",
    ),
    "synthesis option": (
        OOC,
        "-mode out_of_context {*}$generic_args",
        "-mod out_of_context {*}$generic_args",
        "synth_design: no option -mod (an abbreviation of -mode)",
    ),
}


def arguments(script: str, root) -> tuple[list[str], dict[str, str]]:
    if script == BD:
        return ["--board", "zedboard", "--impl", "--ip-repo", str(fake_ip_repo(root)), "--out",
                str(root / "out")], {**BD_RESULTS, "get_property PROGRESS": "100%",
                                     "get_property SLACK": "1"}  # fmt: skip
    if script == PACKAGE:
        return ["--out", str(root / "out" / "ip")], PACKAGE_RESULTS
    return ["--out", str(root / "out")], {"get_property SLACK": "1"}


@needs_tcl
@pytest.mark.parametrize("name", MUTATIONS)
def test_a_misspelt_name_fails(name: str) -> None:
    script, old, new, expected = MUTATIONS[name]
    root = sandbox("stub_" + name.replace(" ", "_"))
    mutate(root / "vivado" / script, old, new)
    argv, results = arguments(script, root)
    run = dry_run(root, script, argv, results)
    found = run.problems + ([run.error] if run.error else [])
    assert any(expected in p for p in found), "\n".join(found) or "the stub accepted it"


def test_every_command_has_one_syntax() -> None:
    names = [line.split()[0] for line in vivado_api.UG835_SYNTAX + vivado_api.IPX_SYNTAX]
    assert len(names) == len(set(names))
    assert set(vivado_api.NOT_REQUIRED) <= set(names)
    for name, options in vivado_api.NOT_REQUIRED.items():
        assert options <= set(stubcheck.SYNTAX[name].options), name


def test_parse_call() -> None:
    problems: list[str] = []
    options, args = stubcheck.parse_call(
        ["make_wrapper", "-files", "{get_files a.bd}", "-top"], problems
    )
    assert not problems and args == ["{get_files a.bd}"] and options == {"-top": []}
    stubcheck.parse_call(["synth_design", "-generic", "A=1", "-generic", "B=2"], problems)
    assert not problems  # <args> options may repeat
    stubcheck.parse_call(["launch_runs", "-jobs", "2", "-jobs", "4", "x"], problems)
    assert problems == ["launch_runs: option -jobs given twice"]
    assert stubcheck.tcl_split('a {b c} "d e" {f {g}}') == ["a", "b c", "d e", "f {g}"]
