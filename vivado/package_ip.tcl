# Packages fastnms_axi as a Vivado IP (IP-XACT component.xml, the sources,
# the customisation GUI) for the IP catalog and IP integrator.
#
#   vivado -mode batch -nojournal -nolog -source vivado/package_ip.tcl \
#          [-tclargs [--out DIR]]
#
# Output (never committed: build/ is in .gitignore):
#   build/vivado/ip/                      the IP repository: component.xml,
#                                         src/ (the RTL, copied), xgui/
#   build/vivado/fastnms_vision_fastnms_axi_0.2.zip   the same as an archive
#   build/vivado/package_ip_project/      the throw-away packaging project
#   build/vivado/ip_wrapper/fastnms_axi_ip.vhd   the generated VHDL-93 top level
# With --out DIR the IP goes to DIR and the others beside it.
#
# The IP's top-level entity is fastnms_axi_ip, a VHDL-93 wrapper generated
# here from fastnms_axi's entity declaration (fastnms::ip_wrapper): the IP
# packager reads the top-level file as VHDL-93 (UG1118, "Top-Level HDL
# Requirements"), the RTL is VHDL-2008. Its generics, ports and interface
# attributes are fastnms_axi's, word for word; the IP is still named
# fastnms_axi (VLNV fastnms:vision:fastnms_axi:0.2).
#
# Written for Vivado 2020.2 or later; not run where this project is
# developed (no Vivado there). flows/vivado_check/test_vivado_tcl.py runs it under plain Tcl
# with every Vivado command stubbed out, which checks its Tcl, its arguments
# and the file list, not Vivado's answers.

source [file join [file dirname [info script]] fastnms_common.tcl]

set opts [fastnms::parse_args $argv [dict create --out [fastnms::path build vivado ip]]]
set out_dir   [file normalize [dict get $opts --out]]
set build_dir [file dirname $out_dir]
set proj_dir  [file join $build_dir package_ip_project]
set zip_file  [file join $build_dir \
    "${fastnms::vendor}_${fastnms::library}_${fastnms::name}_${fastnms::version}.zip"]

set top_file [fastnms::path rtl top "$fastnms::top.vhd"]
if {![file exists $top_file]} {
    error "package_ip: $top_file does not exist: the AXI top-level entity is needed to package the IP"
}
set wrapper_name "${fastnms::top}_ip"
set wrapper_file [file join $build_dir ip_wrapper "$wrapper_name.vhd"]

# ---- the packaging project ----------------------------------------------------
file delete -force $out_dir $proj_dir [file dirname $wrapper_file]
file mkdir $out_dir [file dirname $wrapper_file]
set f [open $wrapper_file w]
puts -nonewline $f [fastnms::ip_wrapper $top_file $fastnms::top $wrapper_name]
close $f

create_project -force fastnms_package_ip $proj_dir -part $fastnms::part
set_property target_language VHDL [current_project]

# Every rtl/**/*.vhd in compile order (fastnms::rtl_files), VHDL-2008; the
# wrapper, VHDL(-93), is the top level. flows/vivado_check/test_vivado_tcl.py checks that the
# wrapper is VHDL-93 and elaborates with the RTL.
set rtl_files [fastnms::rtl_files]
add_files -norecurse [concat $rtl_files [list $wrapper_file]]
set_property file_type {VHDL 2008} [get_files $rtl_files]
set_property file_type VHDL [get_files $wrapper_file]
set_property top $wrapper_name [current_fileset]
update_compile_order -fileset sources_1

# ---- package ----------------------------------------------------------------
ipx::package_project -root_dir $out_dir -vendor $fastnms::vendor -library $fastnms::library \
    -taxonomy {/Video_&_Image_Processing} -import_files -set_current true -force
set core [ipx::current_core]

set_property name                $fastnms::name $core
set_property version             $fastnms::version $core
set_property core_revision       1 $core
set_property display_name        {fastnms: FAST-9/16 corners with non-maxima suppression} $core
set_property description         {Streaming FAST-9/16 corner detector with non-maxima suppression, bit-exact with OpenCV cv::FAST. AXI4-Stream 8-bit video in, 64-bit corner records out, AXI4-Lite control.} $core
set_property vendor_display_name {fastnms contributors} $core
set_property supported_families  {
    artix7 Production kintex7 Production virtex7 Production spartan7 Production
    zynq Production zynquplus Production kintexu Production kintexuplus Production
} $core

# The packager may not keep the projects' file types: set them again in the
# IP's own file groups (VHDL-2008 everywhere except the wrapper).
foreach group_name {xilinx_anylanguagesynthesis xilinx_anylanguagebehavioralsimulation} {
    foreach f [ipx::get_files -of_objects [ipx::get_file_groups $group_name -of_objects $core]] {
        set f_name [get_property NAME $f]
        if {[file extension $f_name] ne ".vhd"} {
            continue
        }
        if {[file tail $f_name] eq [file tail $wrapper_file]} {
            set_property type vhdlSource $f
        } else {
            set_property type vhdlSource-2008 $f
        }
    }
}

# ---- bus interfaces ---------------------------------------------------------
# The X_INTERFACE_INFO and X_INTERFACE_PARAMETER attributes of fastnms_axi
# (copied into the wrapper) define them, parameters included; the packager
# takes them from there (flows/vivado_check/xinterface.py checks the
# attributes against the ports). Only if one is missing are they inferred
# from the port names, a fallback that loses the parameters the attributes
# carry: the log says which path was taken, and the parameters the block
# design needs are checked below on either path.
set interfaces {s_axis_video m_axis_corners m_axis_score s_axi_ctrl aclk aresetn interrupt}

proc fastnms::missing_interfaces {core names} {
    set missing {}
    foreach busif $names {
        if {![llength [ipx::get_bus_interfaces -quiet $busif -of_objects $core]]} {
            lappend missing $busif
        }
    }
    return $missing
}

set missing [fastnms::missing_interfaces $core $interfaces]
if {![llength $missing]} {
    puts "package_ip: bus interfaces from the X_INTERFACE attributes: [join $interfaces {, }]"
} else {
    puts "package_ip: WARNING: bus interfaces [join $missing {, }] not in the packaged\
        component: INFERRING them from the port names (ipx::infer_bus_interfaces)"
    foreach definition {
        xilinx.com:interface:axis_rtl:1.0
        xilinx.com:interface:aximm_rtl:1.0
        xilinx.com:signal:clock_rtl:1.0
        xilinx.com:signal:reset_rtl:1.0
        xilinx.com:signal:interrupt_rtl:1.0
    } {
        ipx::infer_bus_interfaces $definition $core
    }
    set missing [fastnms::missing_interfaces $core $interfaces]
    if {[llength $missing]} {
        error "package_ip: no bus interface $missing on $fastnms::top (check its X_INTERFACE_INFO attributes)"
    }
    puts "package_ip: bus interfaces inferred: [join $interfaces {, }]"
}

# The bus parameters the block design relies on and inference may not set:
# an error, not a warning, when one is missing or differs.
proc fastnms::require_bus_parameter {core busif name value} {
    set param [ipx::get_bus_parameters -quiet $name \
        -of_objects [ipx::get_bus_interfaces $busif -of_objects $core]]
    set actual [expr {[llength $param] ? [get_property VALUE $param] : "(missing)"}]
    if {$actual ne $value} {
        error "package_ip: bus interface $busif: $name is $actual, must be $value\
            (the X_INTERFACE_PARAMETER attributes of $fastnms::top did not reach the component)"
    }
}
fastnms::require_bus_parameter $core aresetn      POLARITY    ACTIVE_LOW
fastnms::require_bus_parameter $core s_axis_video TUSER_WIDTH 1
fastnms::require_bus_parameter $core m_axis_score TUSER_WIDTH 1

# All four buses run on aclk.
set aclk_busif [ipx::get_bus_interfaces aclk -of_objects $core]
set associated {}
set param [ipx::get_bus_parameters -quiet ASSOCIATED_BUSIF -of_objects $aclk_busif]
if {[llength $param]} {
    set associated [split [get_property VALUE $param] :]
}
foreach busif {s_axis_video m_axis_corners m_axis_score s_axi_ctrl} {
    if {$busif ni $associated} {
        ipx::associate_bus_interfaces -busif $busif -clock aclk $core
    }
}

# The AXI4-Lite register block: 12 address bits (ADDR_WIDTH 12, docs/fastnms_axi.md),
# 4 KiB, also the smallest block the Zynq address map assigns.
set memory_map [ipx::get_memory_maps -quiet s_axi_ctrl -of_objects $core]
if {![llength $memory_map]} {
    set memory_map [ipx::add_memory_map s_axi_ctrl $core]
    set_property slave_memory_map_ref s_axi_ctrl [ipx::get_bus_interfaces s_axi_ctrl -of_objects $core]
}
set blocks [ipx::get_address_blocks -quiet -of_objects $memory_map]
if {![llength $blocks]} {
    set blocks [ipx::add_address_block reg0 $memory_map]
}
set block [lindex $blocks 0]
set_property range 4096 $block
set_property width 32 $block
set_property usage register $block

# m_axis_score exists only with SCORE_VIDEO: without it the interface and its
# ports disappear from the block, and the unconnected tready reads 1.
set_property enablement_dependency {$SCORE_VIDEO} [ipx::get_bus_interfaces m_axis_score -of_objects $core]
set_property enablement_dependency {$SCORE_VIDEO} [ipx::get_ports m_axis_score_* -of_objects $core]
set_property driver_value 1 [ipx::get_ports m_axis_score_tready -of_objects $core]

# ---- customisation GUI --------------------------------------------------------
proc fastnms::gui_param {core name display_name tooltip} {
    set spec [ipgui::get_guiparamspec -name $name -component $core]
    set_property display_name $display_name $spec
    set_property tooltip $tooltip $spec
    return [ipx::get_user_parameters $name -of_objects $core]
}

proc fastnms::gui_range {core name min max} {
    set param [ipx::get_user_parameters $name -of_objects $core]
    set_property value_validation_type range_long $param
    set_property value_validation_range_minimum $min $param
    set_property value_validation_range_maximum $max $param
}

proc fastnms::gui_list {core name values} {
    set param [ipx::get_user_parameters $name -of_objects $core]
    set_property value_validation_type list $param
    set_property value_validation_list $values $param
    set_property widget comboBox [ipgui::get_guiparamspec -name $name -component $core]
}

fastnms::gui_param $core MAX_WIDTH {Maximum frame width} \
    {Widest frame in pixels (a multiple of PPC); the runtime width (register WIDTH) is 7 (8 with PPC 2 or 4) .. MAX_WIDTH. Sets the line-buffer size.}
fastnms::gui_range $core MAX_WIDTH 7 8192
fastnms::gui_param $core MAX_HEIGHT {Maximum frame height} \
    {Tallest frame in lines; the runtime height (register HEIGHT) is 7 .. MAX_HEIGHT.}
fastnms::gui_range $core MAX_HEIGHT 7 8192
fastnms::gui_param $core SCORE {Corner score} \
    {opencv: OpenCV's FAST response (8 bits); sad: sum of absolute differences over the threshold (12 bits).}
fastnms::gui_list $core SCORE {opencv sad}
fastnms::gui_param $core NMS {Non-maxima suppression} \
    {3x3: OpenCV's rule; none: every corner; region4 / region8: one corner per 4- or 8-connected region.}
fastnms::gui_list $core NMS {3x3 none region4 region8}
fastnms::gui_param $core SCORE_VIDEO {Score video output} \
    {Build m_axis_score, the per-pixel score as 8-bit video.}
set_property widget checkBox [ipgui::get_guiparamspec -name SCORE_VIDEO -component $core]
fastnms::gui_param $core PPC {Pixels per clock} \
    {Pixels per beat of s_axis_video and m_axis_score (1, 2 or 4; pixel 0 in the low byte). 2 and 4 need NMS 3x3 (an elaboration assert says so otherwise) and a frame width that is a multiple of PPC.}
fastnms::gui_list $core PPC {1 2 4}
fastnms::gui_param $core CORNER_FIFO_DEPTH {Corner FIFO depth} \
    {Corner records buffered ahead of m_axis_corners.}
fastnms::gui_list $core CORNER_FIFO_DEPTH {16 32 64 128 256 512 1024 2048 4096 8192 16384}
fastnms::gui_param $core MAX_PER_CELL {Keypoint budget (largest K)} \
    {0: no budget. 1 .. 15: keep at most K records per grid cell (register BUDGET: K and the cell size, 16 .. 256), the best scores; needs NMS 3x3 or none (an elaboration assert says so otherwise); with ORB at most ORB_MAX_CELL * ORB_MAX_CELL / 64 (4 at 16), the ORB engine's rate. At 15 it costs 26 BRAM18.}
fastnms::gui_range $core MAX_PER_CELL 0 15
fastnms::gui_param $core DESCRIPTOR {Descriptor} \
    {none: corner records of one beat. orb: each keypoint's ORB angle and 256-bit descriptor, equal to OpenCV's, in records of 6 beats (record format 2); needs PPC 1, NMS 3x3 or none and MAX_PER_CELL > 0 (an elaboration assert says so otherwise).}
fastnms::gui_list $core DESCRIPTOR {none orb}
fastnms::gui_param $core ORB_MAX_CELL {Largest ORB cell} \
    {With ORB, the largest cell side of register BUDGET (a larger write is clamped to it); it sizes the rows kept for ORB: each doubling doubles them.}
fastnms::gui_list $core ORB_MAX_CELL {16 32 64 128 256}
fastnms::gui_param $core TEST_FAULT {Test fault (tests only)} \
    {none. The other values build a deliberate internal error for the project's own tests; never in a design.}
fastnms::gui_list $core TEST_FAULT {none}

# ---- save -------------------------------------------------------------------
ipx::create_xgui_files $core
ipx::update_checksums $core
ipx::check_integrity $core
ipx::save_core $core
ipx::archive_core $zip_file $core
close_project

puts "package_ip: [fastnms::vlnv] in $out_dir (archive $zip_file)"
