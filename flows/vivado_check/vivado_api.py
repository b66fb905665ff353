"""What the Tcl stub knows of Vivado: the commands the scripts may call, with
their options; the properties of the objects they set; the IP cores, their
CONFIG keys and their pin names; the automation rules and bus definitions.

The stub (tclcheck.dry_run) answers any command; stubcheck.check then
replays the recorded calls against these lists, so a misspelt command,
option, property, CONFIG key, pin name or VLNV fails the test. A name the
scripts need that is missing here is added here, with its source. Each list
says where it comes from; none of it was checked against a Vivado
installation (there is none where this project is developed): the first real
run (vivado/README.md) is the test of these lists too.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, field

# ---- Tcl commands ------------------------------------------------------------------
# The Syntax line of each command, word for word, from UG835 (v2020.2, November
# 18, 2020), Vivado Design Suite Tcl Command Reference Guide, the command's own
# section. "[-x]" is an optional flag, "[-x <arg>]" an optional option with a
# value ("<args>": a list, may be repeated), "-x <arg>" a required option;
# "<name>" a required argument, "[<name>]" an optional one, "...": repeated.
UG835_SYNTAX: tuple[str, ...] = (
    (
        "add_files [-fileset <arg>] [-of_objects <args>] [-norecurse] [-copy_to <arg>] "
        "[-force] [-scan_for_includes] [-quiet] [-verbose] [<files>...]"
    ),
    (
        "apply_bd_automation -rule <arg> [-config <args>] -dict <arg> -opts <arg> [-quiet] "
        "[-verbose] <objects>..."
    ),
    (
        "assign_bd_address [-target_address_space <arg>] [-boundary] [-master_boundary] "
        "[-external] -dict <arg> [-import_from_file <arg>] [-export_to_file <arg>] "
        "[-export_gui_to_file <arg>] [-offset <arg>] [-range <arg>] [-base_high <arg>] "
        "[-force] [-quiet] [-verbose] [<objects>...]"
    ),
    "close_project [-delete] [-quiet] [-verbose]",
    (
        "connect_bd_intf_net [-intf_net <arg>] [-boundary_type <arg>] [-quiet] [-verbose] "
        "<object1> <object2> [<auto>]"
    ),
    "connect_bd_net [-net <arg>] [-boundary_type <arg>] [-quiet] [-verbose] <objects>...",
    (
        "create_bd_cell [-vlnv <arg>] [-type <arg>] [-reference <arg>] [-revision <arg>] "
        "[-quiet] [-verbose] <name>"
    ),
    "create_bd_design [-dir <arg>] [-cell <arg>] [-quiet] [-verbose] <name>",
    (
        "create_project [-part <arg>] [-force] [-in_memory] [-ip] [-rtl_kernel] [-quiet] "
        "[-verbose] [<name>] [<dir>]"
    ),
    "current_fileset [-constrset] [-simset] [-quiet] [-verbose] [<fileset>...]",
    "current_project [-quiet] [-verbose] [<project>]",
    (
        "get_bd_addr_segs [-regexp] [-hierarchical] [-filter <arg>] [-of_objects <args>] "
        "[-excluded] [-addressed] [-unaddressed] [-addressing] [-addressables] [-quiet] "
        "[-verbose] [<patterns>]"
    ),
    (
        "get_bd_addr_spaces [-regexp] [-hierarchical] [-filter <arg>] [-of_objects <args>] "
        "[-quiet] [-verbose] [<patterns>]"
    ),
    (
        "get_bd_cells [-regexp] [-hierarchical] [-filter <arg>] [-of_objects <args>] [-quiet] "
        "[-verbose] [<patterns>]"
    ),
    (
        "get_bd_intf_pins [-regexp] [-hierarchical] [-filter <arg>] [-of_objects <args>] "
        "[-quiet] [-verbose] [<patterns>]"
    ),
    (
        "get_bd_pins [-regexp] [-hierarchical] [-filter <arg>] [-of_objects <args>] [-quiet] "
        "[-verbose] [<patterns>]"
    ),
    (
        "get_board_parts [-regexp] [-nocase] [-latest_file_version] [-latest_hw_revision] "
        "[-filter <arg>] [-quiet] [-verbose] [<patterns>...]"
    ),
    (
        "get_cells [-hsc <arg>] [-hierarchical] [-regexp] [-nocase] [-filter <arg>] "
        "[-of_objects <args>] [-match_style <arg>] [-include_replicated_objects] [-quiet] "
        "[-verbose] [<patterns>]"
    ),
    (
        "get_files [-regexp] [-nocase] [-filter <arg>] [-compile_order <arg>] [-used_in "
        "<arg>] [-references] [-all] [-of_objects <args>] [-quiet] [-verbose] [<patterns>]"
    ),
    (
        "get_ipdefs [-name] [-regexp] [-nocase] [-filter <arg>] [-of_objects <args>] [-all] "
        "[-quiet] [-verbose] [<patterns>...]"
    ),
    "get_property [-min] [-max] [-quiet] [-verbose] <name> <object>",
    (
        "get_runs [-regexp] [-nocase] [-filter <arg>] [-of_objects <args>] [-quiet] "
        "[-verbose] [<patterns>]"
    ),
    (
        "get_timing_paths [-from <args>] [-rise_from <args>] [-fall_from <args>] [-to <args>] "
        "[-rise_to <args>] [-fall_to <args>] [-through <args>] [-rise_through <args>] "
        "[-fall_through <args>] [-delay_type <arg>] [-setup] [-hold] [-max_paths <arg>] "
        "[-nworst <arg>] [-unique_pins] [-slack_lesser_than <arg>] [-slack_greater_than "
        "<arg>] [-group <args>] [-no_report_unconstrained] [-user_ignored] [-routable_nets] "
        "[-sort_by <arg>] [-filter <arg>] [-regexp] [-nocase] [-cell <args>] [-quiet] "
        "[-verbose]"
    ),
    (
        "launch_runs [-jobs <arg>] [-scripts_only] [-lsf <arg>] [-sge <arg>] "
        "[-cluster_configuration <arg>] [-dir <arg>] [-to_step <arg>] [-next_step] [-host "
        "<args>] [-remote_cmd <arg>] [-email_to <args>] [-email_all] [-pre_launch_script "
        "<arg>] [-post_launch_script <arg>] [-custom_script <arg>] [-force] [-quiet] "
        "[-verbose] <runs>..."
    ),
    (
        "make_wrapper [-top] [-testbench] [-inst_template] [-fileset <arg>] [-import] "
        "[-force] [-quiet] [-verbose] <files>"
    ),
    "open_run [-name <arg>] [-pr_config <arg>] [-quiet] [-verbose] <run>",
    (
        "opt_design [-retarget] [-propconst] [-sweep] [-bram_power_opt] [-remap] "
        "[-aggressive_remap] [-resynth_area] [-resynth_seq_area] [-directive <arg>] "
        "[-muxf_remap] [-hier_fanout_limit <arg>] [-bufg_opt] [-shift_register_opt] "
        "[-dsp_register_opt] [-srl_remap_modes <arg>] [-control_set_merge] "
        "[-merge_equivalent_drivers] [-carry_remap] [-debug_log] [-property_opt_only] "
        "[-quiet] [-verbose]"
    ),
    (
        "phys_opt_design [-fanout_opt] [-placement_opt] [-routing_opt] [-slr_crossing_opt] "
        "[-rewire] [-insert_negative_edge_ffs] [-critical_cell_opt] [-dsp_register_opt] "
        "[-bram_register_opt] [-uram_register_opt] [-bram_enable_opt] [-shift_register_opt] "
        "[-hold_fix] [-aggressive_hold_fix] [-retime] [-force_replication_on_nets <args>] "
        "[-directive <arg>] [-critical_pin_opt] [-clock_opt] [-path_groups <args>] "
        "[-tns_cleanup] [-sll_reg_hold_fix] [-quiet] [-verbose]"
    ),
    (
        "place_design [-directive <arg>] [-no_timing_driven] [-timing_summary] [-unplace] "
        "[-post_place_opt] [-no_psip] [-no_bufg_opt] [-quiet] [-verbose]"
    ),
    "read_vhdl -library <arg> [-vhdl2008] [-quiet] [-verbose] <files>",
    (
        "read_xdc [-cells <args>] [-ref <arg>] [-quiet_diff_pairs] [-mode <arg>] [-unmanaged] "
        "[-no_add] [-quiet] [-verbose] <files>"
    ),
    (
        "report_timing_summary [-check_timing_verbose] [-delay_type <arg>] "
        "[-no_detailed_paths] [-setup] [-hold] [-max_paths <arg>] [-nworst <arg>] "
        "[-unique_pins] [-path_type <arg>] [-no_reused_label] [-input_pins] "
        "[-no_pr_attribute] [-routable_nets] [-slack_lesser_than <arg>] "
        "[-report_unconstrained] [-significant_digits <arg>] [-no_header] [-file <arg>] "
        "[-append] [-name <arg>] [-return_string] [-warn_on_violation] [-datasheet] [-cells "
        "<args>] [-rpx <arg>] [-quiet] [-verbose]"
    ),
    (
        "report_utilization [-file <arg>] [-append] [-pblocks <args>] [-evaluate_pblock] "
        "[-exclude_child_pblocks] [-exclude_non_assigned] [-cells <args>] [-return_string] "
        "[-slr] [-packthru] [-name <arg>] [-no_primitives] [-omit_locs] [-hierarchical] "
        "[-spreadsheet_file <arg>] [-spreadsheet_table <arg>] [-spreadsheet_depth <arg>] "
        "[-hierarchical_depth <arg>] [-hierarchical_percentages] [-quiet] [-verbose]"
    ),
    (
        "route_design [-unroute] [-release_memory] [-nets <args>] [-physical_nets] [-pins "
        "<arg>] [-directive <arg>] [-tns_cleanup] [-no_timing_driven] [-preserve] [-delay] "
        "[-auto_delay] -max_delay <arg> -min_delay <arg> [-timing_summary] [-finalize] "
        "[-ultrathreads] [-eco] [-quiet] [-verbose]"
    ),
    "save_bd_design [-quiet] [-verbose] [<name>]",
    "set_property [-dict <args>] [-quiet] [-verbose] <name> <value> <objects>...",
    (
        "synth_design [-name <arg>] [-part <arg>] [-constrset <arg>] [-top <arg>] "
        "[-include_dirs <args>] [-generic <args>] [-verilog_define <args>] "
        "[-flatten_hierarchy <arg>] [-gated_clock_conversion <arg>] [-directive <arg>] [-rtl] "
        "[-bufg <arg>] [-no_lc] [-shreg_min_size <arg>] [-mode <arg>] [-fsm_extraction <arg>] "
        "[-rtl_skip_mlo] [-rtl_skip_ip] [-rtl_skip_constraints] [-srl_style <arg>] "
        "[-keep_equivalent_registers] [-resource_sharing <arg>] [-cascade_dsp <arg>] "
        "[-control_set_opt_threshold <arg>] [-incremental <arg>] [-max_bram <arg>] [-max_uram "
        "<arg>] [-max_dsp <arg>] [-max_bram_cascade_height <arg>] [-max_uram_cascade_height "
        "<arg>] [-retiming] [-no_srlextract] [-assert] [-no_timing_driven] [-sfcu] "
        "[-debug_log] [-quiet] [-verbose]"
    ),
    "update_compile_order [-force_gui] [-fileset <arg>] [-quiet] [-verbose]",
    (
        "update_ip_catalog [-rebuild] [-add_ip <arg>] [-delete_ip <arg>] [-delete_mult_ip "
        "<args>] [-disable_ip <arg>] [-enable_ip <arg>] [-add_interface <arg>] "
        "[-create_index] [-repo_path <arg>] [-update_module_ref] [-quiet] [-verbose]"
    ),
    "validate_bd_design [-force] [-design <arg>] [-include_pfm] [-quiet] [-verbose]",
    "wait_on_run [-timeout <arg>] [-quiet] [-verbose] <run>",
    (
        "write_checkpoint [-force] [-cell <arg>] [-logic_function_stripped] [-encrypt] [-key "
        "<arg>] [-incremental_synth] [-quiet] [-verbose] [<file>]"
    ),
    (
        "write_hw_platform [-fixed] [-force] [-include_bit] [-include_sim_content] [-minimal] "
        "[-hw] [-hw_emu] [-quiet] [-verbose] [<file>]"
    ),
)

# UG835 prints these options without brackets (required), but the commands run
# without them: read_vhdl's -library defaults to xil_defaultlib (its Arguments
# section says "(Optional)"); apply_bd_automation's -dict and -opts,
# assign_bd_address's -dict and route_design's -max_delay/-min_delay are
# alternatives to other arguments, as the Arguments sections of those commands say.
NOT_REQUIRED: dict[str, frozenset[str]] = {
    "read_vhdl": frozenset({"-library"}),
    "apply_bd_automation": frozenset({"-dict", "-opts"}),
    "assign_bd_address": frozenset({"-dict"}),
    "route_design": frozenset({"-max_delay", "-min_delay"}),
}

# The ipx:: and ipgui:: commands of the IP packager are not in UG835: Vivado
# documents them only through `help ipx::<command>`. These lines hold the
# options seen in the AMD UG1118 (Creating and Packaging Custom IP) examples
# and in public packaging scripts that run in Vivado: AMD's Vitis RTL-kernel
# packaging templates (ipx::add_memory_map -quiet ...), analogdevicesinc/hdl
# library/scripts/adi_ip_xilinx.tcl (ipx::infer_bus_interfaces,
# ipx::associate_bus_interfaces -clear), packaging scripts written by
# Vivado's own Package IP wizard (ipx::package_project ... -set_current
# false, ipx::check_integrity -quiet). Not every option Vivado accepts is
# here; a first real run should compare them with `help ipx::<command>`.
IPX_SYNTAX: tuple[str, ...] = (
    (
        "ipx::package_project [-root_dir <arg>] [-vendor <arg>] [-library <arg>] "
        "[-taxonomy <arg>] [-module <arg>] [-import_files] [-set_current <arg>] "
        "[-generated_files] [-force] [-quiet] [-verbose] [<component>]"
    ),
    "ipx::current_core [-quiet] [-verbose] [<component>]",
    *(
        f"ipx::get_{kind} [-regexp] [-nocase] [-filter <arg>] -of_objects <args> "
        "[-quiet] [-verbose] [<patterns>...]"
        for kind in (
            "file_groups", "files", "bus_interfaces", "bus_parameters", "memory_maps",
            "address_blocks", "ports", "user_parameters",
        )
    ),
    "ipx::infer_bus_interfaces [-quiet] [-verbose] <bus_definition_vlnv> <component>",
    "ipx::infer_bus_interface [-quiet] [-verbose] <ports> <bus_definition_vlnv> <component>",
    (
        "ipx::associate_bus_interfaces [-busif <arg>] [-clock <arg>] [-reset <arg>] "
        "[-remove] [-clear] [-quiet] [-verbose] <component>"
    ),
    "ipx::add_bus_parameter [-quiet] [-verbose] <name> <bus_interface>",
    "ipx::add_memory_map [-quiet] [-verbose] <name> <component>",
    "ipx::add_address_block [-quiet] [-verbose] <name> <memory_map>",
    "ipgui::get_guiparamspec -name <arg> -component <arg> [-quiet] [-verbose]",
    "ipx::create_xgui_files [-quiet] [-verbose] <component>",
    "ipx::update_checksums [-quiet] [-verbose] <component>",
    "ipx::check_integrity [-kernel] [-xrt] [-quiet] [-verbose] <component>",
    "ipx::save_core [-quiet] [-verbose] <component>",
    "ipx::archive_core [-quiet] [-verbose] <file> [<component>]",
)  # fmt: skip

# ---- properties of the objects the scripts set or read -------------------------------
# By the command that made the object (the stub's handle names it): UG912
# (Vivado Design Suite Properties Reference Guide, v2020.2), sections PROJECT,
# FILESET, FILE, RUN, TIMING_PATH, BD_ADDR_SEG, BD_CELL; for the IP packager's
# objects (not in UG912), the properties that UG1118 and the packaging scripts
# named above set. Vivado's property names are case-insensitive.
OBJECT_KINDS: dict[str, str] = {
    "current_project": "project",
    "current_fileset": "fileset",
    "get_files": "file",
    "get_runs": "run",
    "get_timing_paths": "timing_path",
    "get_bd_addr_segs": "bd_addr_seg",
    "ipx::current_core": "ipx_core",
    "ipx::get_files": "ipx_file",
    "ipx::get_bus_interfaces": "ipx_bus_interface",
    "ipx::get_bus_parameters": "ipx_bus_parameter",
    "ipx::get_ports": "ipx_port",
    "ipx::get_memory_maps": "ipx_memory_map",
    "ipx::add_memory_map": "ipx_memory_map",
    "ipx::get_address_blocks": "ipx_address_block",
    "ipx::add_address_block": "ipx_address_block",
    "ipx::get_user_parameters": "ipx_user_parameter",
    "ipgui::get_guiparamspec": "ipgui_param",
}
PROPERTIES: dict[str, frozenset[str]] = {
    "project": frozenset({"board_part", "ip_repo_paths", "target_language", "part"}),
    "fileset": frozenset({"top"}),
    "file": frozenset({"file_type", "library", "is_enabled"}),
    "run": frozenset({"progress", "status"}),
    "timing_path": frozenset({"slack"}),
    "bd_addr_seg": frozenset({"name", "offset", "range"}),
    "bd_cell": frozenset({"name", "vlnv"}),  # and CONFIG.<key> of its IP, below
    "ipx_core": frozenset({
        "name", "version", "core_revision", "display_name", "description",
        "vendor_display_name", "company_url", "supported_families", "taxonomy",
    }),
    "ipx_file": frozenset({"name", "type"}),
    "ipx_bus_interface": frozenset({
        "enablement_dependency", "slave_memory_map_ref", "interface_mode",
        "abstraction_type_vlnv", "bus_type_vlnv",
    }),
    "ipx_bus_parameter": frozenset({"name", "value"}),
    "ipx_port": frozenset({"enablement_dependency", "driver_value"}),
    "ipx_memory_map": frozenset({"name"}),
    "ipx_address_block": frozenset({"range", "width", "usage", "base_address"}),
    "ipx_user_parameter": frozenset({
        "value", "value_validation_type", "value_validation_list",
        "value_validation_range_minimum", "value_validation_range_maximum",
    }),
    "ipgui_param": frozenset({"display_name", "tooltip", "widget"}),
}  # fmt: skip

# The bus definitions ipx::infer_bus_interface(s) may name, and the bus
# parameters the scripts read: UG994 (Designing IP Subsystems Using IP
# Integrator) "List of Supported X_ Attributes" and its interface parameter
# tables (FREQ_HZ, ASSOCIATED_BUSIF, ...); UG1037 for AXI4-Stream/AXI4-Lite.
BUS_DEFINITIONS = frozenset(
    {
        "xilinx.com:interface:axis_rtl:1.0",
        "xilinx.com:interface:aximm_rtl:1.0",
        "xilinx.com:signal:clock_rtl:1.0",
        "xilinx.com:signal:reset_rtl:1.0",
        "xilinx.com:signal:interrupt_rtl:1.0",
    }
)
BUS_PARAMETERS = frozenset({
    "ASSOCIATED_BUSIF", "ASSOCIATED_RESET", "FREQ_HZ", "PHASE", "CLK_DOMAIN",
    "POLARITY", "SENSITIVITY",
    "TDATA_NUM_BYTES", "TUSER_WIDTH", "TID_WIDTH", "TDEST_WIDTH",
    "HAS_TREADY", "HAS_TSTRB", "HAS_TKEEP", "HAS_TLAST",
    "PROTOCOL", "DATA_WIDTH", "ADDR_WIDTH", "READ_WRITE_MODE", "HAS_WSTRB", "HAS_PROT",
    "HAS_BRESP", "HAS_RRESP",
})  # fmt: skip

# ---- block-automation rules ----------------------------------------------------------
# -config keys of `apply_bd_automation -rule ...`, as Vivado writes them in its
# journal when the "Run Block Automation" dialog runs (public scripts replaying
# it: `-config {make_external "FIXED_IO, DDR" apply_board_preset "1" Master
# "Disable" Slave "Disable" }`).
AUTOMATION_RULES: dict[str, frozenset[str]] = {
    "xilinx.com:bd_rule:processing_system7": frozenset(
        {"make_external", "apply_board_preset", "Master", "Slave", "Trigger_In", "Trigger_Out"}
    ),
}

# ---- IP cores ----------------------------------------------------------------------
Config = dict[str, str]  # the cell's CONFIG values, keys upper case
Condition = Callable[[Config, int], bool]


@dataclass(frozen=True)
class IP:
    """An IP core of the catalog as the block design sees it.

    `config`: every CONFIG key (upper case, Vivado compares them so) with the
    default the pin conditions need ("" when none needs it); `values`: the
    values a key allows (a set of strings or a range of integers). `pins` and
    `intf_pins`: pin names, or templates with "{n}" (n = 0..63), each with the
    condition under which the pin exists (None: always), called with the
    cell's configuration and n.
    """

    vlnv: str  # vendor:library:name
    versions: tuple[str, ...]
    source: str
    config: dict[str, str]
    values: dict[str, frozenset[str] | range] = field(default_factory=dict)
    pins: dict[str, Condition | None] = field(default_factory=dict)
    intf_pins: dict[str, Condition | None] = field(default_factory=dict)


def _on(key: str) -> Condition:
    return lambda c, n: c.get(key, "0") == "1"


def _below(key: str) -> Condition:
    return lambda c, n: n < int(c[key])


BOOL01 = frozenset({"0", "1"})
STREAM_WIDTHS = frozenset(str(8 << i) for i in range(8))  # 8 .. 1024
MM_WIDTHS = frozenset(str(32 << i) for i in range(6))  # 32 .. 1024
BURSTS = frozenset(str(2 << i) for i in range(8))  # 2 .. 256

_PS7_FAMILIES = (
    "PCW_FPGA{n}_PERIPHERAL_FREQMHZ", "PCW_ACT_FPGA{n}_PERIPHERAL_FREQMHZ",
    "PCW_FCLK{n}_PERIPHERAL_CLKSRC", "PCW_FCLK{n}_PERIPHERAL_DIVISOR0",
    "PCW_FCLK{n}_PERIPHERAL_DIVISOR1", "PCW_FCLK_CLK{n}_BUF", "PCW_CLK{n}_FREQ",
    "PCW_EN_CLK{n}_PORT", "PCW_EN_RST{n}_PORT", "PCW_FPGA_FCLK{n}_ENABLE",
    "PCW_USE_S_AXI_HP{n}", "PCW_S_AXI_HP{n}_DATA_WIDTH",
)  # fmt: skip

IPS: dict[str, IP] = {
    # PG082 (Processing System 7 v5.5, "Port Descriptions" and "Customizing
    # and Generating the Core") for the pins; the CONFIG keys as public
    # write_bd_tcl output of processing_system7:5.5 lists them (e.g.
    # CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ {142.857132} next to
    # CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ {150}, CONFIG.PCW_FCLK0_PERIPHERAL_CLKSRC
    # {IO PLL}, CONFIG.PCW_FCLK0_PERIPHERAL_DIVISOR0, CONFIG.PCW_FCLK_CLK0_BUF,
    # and with the ZC702 preset CONFIG.PCW_IOPLL_CTRL_FBDIV {30},
    # CONFIG.PCW_IO_IO_PLL_FREQMHZ {1000.000}).
    # Defaults: a processing_system7 without preset shows M_AXI_GP0,
    # FCLK_CLK0 and FCLK_RESET0_N, no HP port and no IRQ_F2P.
    "xilinx.com:ip:processing_system7": IP(
        vlnv="xilinx.com:ip:processing_system7",
        versions=("5.5",),
        source="PG082; public write_bd_tcl output",
        config={
            **{f.format(n=n): "" for f in _PS7_FAMILIES for n in range(4)},
            "PCW_EN_CLK0_PORT": "1", "PCW_EN_RST0_PORT": "1", "PCW_USE_M_AXI_GP0": "1",
            "PCW_USE_M_AXI_GP1": "0", "PCW_USE_S_AXI_GP0": "0", "PCW_USE_S_AXI_GP1": "0",
            "PCW_USE_S_AXI_ACP": "0", "PCW_USE_S_AXI_HP0": "0", "PCW_USE_S_AXI_HP1": "0",
            "PCW_USE_S_AXI_HP2": "0", "PCW_USE_S_AXI_HP3": "0",
            "PCW_USE_FABRIC_INTERRUPT": "0", "PCW_IRQ_F2P_INTR": "0",
            "PCW_UIPARAM_DDR_PARTNO": "", "PCW_UIPARAM_ACT_DDR_FREQ_MHZ": "",
            "PCW_CRYSTAL_PERIPHERAL_FREQMHZ": "", "PCW_APU_PERIPHERAL_FREQMHZ": "",
            "PCW_ACT_APU_PERIPHERAL_FREQMHZ": "", "PCW_DDR_RAM_HIGHADDR": "",
            "PCW_USE_DMA0": "", "PCW_UART1_PERIPHERAL_ENABLE": "",
            "PCW_IOPLL_CTRL_FBDIV": "", "PCW_IO_IO_PLL_FREQMHZ": "",
        },
        values={
            **{f"PCW_FCLK{n}_PERIPHERAL_CLKSRC": frozenset({"IO PLL", "ARM PLL", "DDR PLL"})
               for n in range(4)},
            **{f"PCW_FCLK_CLK{n}_BUF": frozenset({"TRUE", "FALSE"}) for n in range(4)},
            **{f"PCW_S_AXI_HP{n}_DATA_WIDTH": frozenset({"32", "64"}) for n in range(4)},
            **{f"PCW_USE_S_AXI_HP{n}": BOOL01 for n in range(4)},
            "PCW_USE_M_AXI_GP0": BOOL01, "PCW_USE_FABRIC_INTERRUPT": BOOL01,
            "PCW_IRQ_F2P_INTR": BOOL01,
        },
        pins={
            "FCLK_CLK{n}": lambda c, n: n < 4 and c[f"PCW_EN_CLK{n}_PORT"] == "1",
            "FCLK_RESET{n}_N": lambda c, n: n < 4 and c[f"PCW_EN_RST{n}_PORT"] == "1",
            "M_AXI_GP0_ACLK": _on("PCW_USE_M_AXI_GP0"),
            "M_AXI_GP1_ACLK": _on("PCW_USE_M_AXI_GP1"),
            "S_AXI_GP0_ACLK": _on("PCW_USE_S_AXI_GP0"),
            "S_AXI_GP1_ACLK": _on("PCW_USE_S_AXI_GP1"),
            "S_AXI_ACP_ACLK": _on("PCW_USE_S_AXI_ACP"),
            "S_AXI_HP{n}_ACLK": lambda c, n: n < 4 and c[f"PCW_USE_S_AXI_HP{n}"] == "1",
            "IRQ_F2P": lambda c, n: c["PCW_USE_FABRIC_INTERRUPT"] == "1"
            and c["PCW_IRQ_F2P_INTR"] == "1",
        },
        intf_pins={
            "DDR": None, "FIXED_IO": None,
            "M_AXI_GP0": _on("PCW_USE_M_AXI_GP0"), "M_AXI_GP1": _on("PCW_USE_M_AXI_GP1"),
            "S_AXI_GP0": _on("PCW_USE_S_AXI_GP0"), "S_AXI_GP1": _on("PCW_USE_S_AXI_GP1"),
            "S_AXI_ACP": _on("PCW_USE_S_AXI_ACP"),
            "S_AXI_HP{n}": lambda c, n: n < 4 and c[f"PCW_USE_S_AXI_HP{n}"] == "1",
        },
    ),
    # PG020 (AXI VDMA v6.3): "Port Descriptions" for the pins; the user
    # parameters (c_*) as the "Customizing and Generating the Core" options
    # appear in public write_bd_tcl output of axi_vdma:6.3 (c_include_mm2s,
    # c_m_axis_mm2s_tdata_width, c_mm2s_linebuffer_depth, c_use_mm2s_fsync,
    # c_mm2s_genlock_mode, c_num_fstores, ...).
    "xilinx.com:ip:axi_vdma": IP(
        vlnv="xilinx.com:ip:axi_vdma",
        versions=("6.3",),
        source="PG020; public write_bd_tcl output",
        config={
            "C_INCLUDE_MM2S": "1", "C_INCLUDE_S2MM": "1", "C_NUM_FSTORES": "",
            "C_M_AXI_MM2S_DATA_WIDTH": "", "C_M_AXIS_MM2S_TDATA_WIDTH": "",
            "C_INCLUDE_MM2S_DRE": "", "C_MM2S_MAX_BURST_LENGTH": "",
            "C_MM2S_LINEBUFFER_DEPTH": "", "C_MM2S_GENLOCK_MODE": "", "C_USE_MM2S_FSYNC": "",
            "C_M_AXI_S2MM_DATA_WIDTH": "", "C_S_AXIS_S2MM_TDATA_WIDTH": "",
            "C_INCLUDE_S2MM_DRE": "", "C_S2MM_MAX_BURST_LENGTH": "",
            "C_S2MM_LINEBUFFER_DEPTH": "", "C_S2MM_GENLOCK_MODE": "", "C_USE_S2MM_FSYNC": "",
        },
        values={
            "C_INCLUDE_MM2S": BOOL01, "C_INCLUDE_S2MM": BOOL01,
            "C_INCLUDE_MM2S_DRE": BOOL01, "C_INCLUDE_S2MM_DRE": BOOL01,
            "C_M_AXIS_MM2S_TDATA_WIDTH": STREAM_WIDTHS, "C_S_AXIS_S2MM_TDATA_WIDTH": STREAM_WIDTHS,
            "C_M_AXI_MM2S_DATA_WIDTH": MM_WIDTHS, "C_M_AXI_S2MM_DATA_WIDTH": MM_WIDTHS,
            "C_MM2S_MAX_BURST_LENGTH": BURSTS, "C_S2MM_MAX_BURST_LENGTH": BURSTS,
            "C_NUM_FSTORES": range(1, 33),
        },
        pins={
            "s_axi_lite_aclk": None, "axi_resetn": None,
            "m_axi_mm2s_aclk": _on("C_INCLUDE_MM2S"), "m_axis_mm2s_aclk": _on("C_INCLUDE_MM2S"),
            "mm2s_introut": _on("C_INCLUDE_MM2S"),
            "m_axi_s2mm_aclk": _on("C_INCLUDE_S2MM"), "s_axis_s2mm_aclk": _on("C_INCLUDE_S2MM"),
            "s2mm_introut": _on("C_INCLUDE_S2MM"),
        },
        intf_pins={
            "S_AXI_LITE": None,
            "M_AXI_MM2S": _on("C_INCLUDE_MM2S"), "M_AXIS_MM2S": _on("C_INCLUDE_MM2S"),
            "M_AXI_S2MM": _on("C_INCLUDE_S2MM"), "S_AXIS_S2MM": _on("C_INCLUDE_S2MM"),
        },
    ),
    # PG021 (AXI DMA v7.1): "Port Descriptions" for the pins, S2MM_LENGTH for
    # c_sg_length_width ("minimum width is 8 bits and maximum width is 26
    # bits"); the user parameters as public write_bd_tcl output of axi_dma:7.1
    # lists them (c_include_sg, c_sg_include_stscntrl_strm, c_sg_length_width,
    # c_s2mm_burst_size, c_include_mm2s_sf, c_micro_dma, c_addr_width, ...).
    "xilinx.com:ip:axi_dma": IP(
        vlnv="xilinx.com:ip:axi_dma",
        versions=("7.1",),
        source="PG021; public write_bd_tcl output",
        config={
            "C_INCLUDE_SG": "1", "C_SG_INCLUDE_STSCNTRL_STRM": "", "C_SG_USE_STSAPP_LENGTH": "",
            "C_SG_LENGTH_WIDTH": "", "C_ADDR_WIDTH": "", "C_MICRO_DMA": "",
            "C_INCLUDE_MM2S": "1", "C_INCLUDE_MM2S_DRE": "", "C_INCLUDE_MM2S_SF": "",
            "C_M_AXI_MM2S_DATA_WIDTH": "", "C_M_AXIS_MM2S_TDATA_WIDTH": "",
            "C_MM2S_BURST_SIZE": "",
            "C_INCLUDE_S2MM": "1", "C_INCLUDE_S2MM_DRE": "", "C_INCLUDE_S2MM_SF": "",
            "C_M_AXI_S2MM_DATA_WIDTH": "", "C_S_AXIS_S2MM_TDATA_WIDTH": "",
            "C_S2MM_BURST_SIZE": "",
        },
        values={
            "C_INCLUDE_SG": BOOL01, "C_SG_INCLUDE_STSCNTRL_STRM": BOOL01,
            "C_SG_LENGTH_WIDTH": range(8, 27),
            "C_INCLUDE_MM2S": BOOL01, "C_INCLUDE_S2MM": BOOL01,
            "C_INCLUDE_MM2S_DRE": BOOL01, "C_INCLUDE_S2MM_DRE": BOOL01,
            "C_M_AXIS_MM2S_TDATA_WIDTH": STREAM_WIDTHS, "C_S_AXIS_S2MM_TDATA_WIDTH": STREAM_WIDTHS,
            "C_M_AXI_MM2S_DATA_WIDTH": MM_WIDTHS, "C_M_AXI_S2MM_DATA_WIDTH": MM_WIDTHS,
            "C_MM2S_BURST_SIZE": BURSTS, "C_S2MM_BURST_SIZE": BURSTS,
        },
        pins={
            "s_axi_lite_aclk": None, "axi_resetn": None,
            "m_axi_sg_aclk": _on("C_INCLUDE_SG"),
            "m_axi_mm2s_aclk": _on("C_INCLUDE_MM2S"), "mm2s_introut": _on("C_INCLUDE_MM2S"),
            "mm2s_prmry_reset_out_n": _on("C_INCLUDE_MM2S"),
            "m_axi_s2mm_aclk": _on("C_INCLUDE_S2MM"), "s2mm_introut": _on("C_INCLUDE_S2MM"),
            "s2mm_prmry_reset_out_n": _on("C_INCLUDE_S2MM"),
        },
        intf_pins={
            "S_AXI_LITE": None, "M_AXI_SG": _on("C_INCLUDE_SG"),
            "M_AXI_MM2S": _on("C_INCLUDE_MM2S"), "M_AXIS_MM2S": _on("C_INCLUDE_MM2S"),
            "M_AXI_S2MM": _on("C_INCLUDE_S2MM"), "S_AXIS_S2MM": _on("C_INCLUDE_S2MM"),
        },
    ),
    # PG247 (SmartConnect v1.0), "Port Descriptions" and "User Parameters":
    # NUM_SI, NUM_MI (1 to 16), NUM_CLKS, HAS_ARESETN; S00_AXI .. M00_AXI ..,
    # aclk, aclk1 .., aresetn.
    "xilinx.com:ip:smartconnect": IP(
        vlnv="xilinx.com:ip:smartconnect",
        versions=("1.0",),
        source="PG247",
        config={"NUM_SI": "1", "NUM_MI": "1", "NUM_CLKS": "1", "HAS_ARESETN": "1"},
        values={"NUM_SI": range(1, 17), "NUM_MI": range(1, 17), "NUM_CLKS": range(1, 11)},
        pins={
            "aclk": None,
            "aclk{n}": lambda c, n: 1 <= n < int(c["NUM_CLKS"]),
            "aresetn": _on("HAS_ARESETN"),
        },
        intf_pins={"S{n:02}_AXI": _below("NUM_SI"), "M{n:02}_AXI": _below("NUM_MI")},
    ),
    # PG164 (Processor System Reset v5.0), "Port Descriptions" and "User
    # Parameters".
    "xilinx.com:ip:proc_sys_reset": IP(
        vlnv="xilinx.com:ip:proc_sys_reset",
        versions=("5.0",),
        source="PG164",
        config={
            "C_EXT_RST_WIDTH": "", "C_AUX_RST_WIDTH": "", "C_EXT_RESET_HIGH": "",
            "C_AUX_RESET_HIGH": "", "C_NUM_BUS_RST": "", "C_NUM_PERP_RST": "",
            "C_NUM_INTERCONNECT_ARESETN": "", "C_NUM_PERP_ARESETN": "",
            "RESET_BOARD_INTERFACE": "", "USE_BOARD_FLOW": "",
        },
        values={"C_EXT_RESET_HIGH": BOOL01, "C_AUX_RESET_HIGH": BOOL01},
        pins={
            name: None
            for name in (
                "slowest_sync_clk", "ext_reset_in", "aux_reset_in", "mb_debug_sys_rst",
                "dcm_locked", "mb_reset", "bus_struct_reset", "peripheral_reset",
                "interconnect_aresetn", "peripheral_aresetn",
            )
        },
    ),
    # Concat (xlconcat v2.1), a utility IP without a product guide: its
    # parameters and pins as its customisation dialog and public write_bd_tcl
    # output show them (CONFIG.NUM_PORTS, CONFIG.IN0_WIDTH ..; In0 .., dout).
    "xilinx.com:ip:xlconcat": IP(
        vlnv="xilinx.com:ip:xlconcat",
        versions=("2.1",),
        source="public write_bd_tcl output",
        config={"NUM_PORTS": "2", "DOUT_WIDTH": "", **{f"IN{n}_WIDTH": "" for n in range(32)}},
        values={"NUM_PORTS": range(1, 33)},
        pins={"In{n}": _below("NUM_PORTS"), "dout": None},
    ),
}  # fmt: skip
