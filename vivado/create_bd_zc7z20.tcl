# A Zynq-7020 system around fastnms_axi (ZedBoard / ZC702, xc7z020clg484-1):
#
#   DDR --HP0--> AXI VDMA (MM2S, 8-bit video) --s_axis_video--> fastnms_axi
#   fastnms_axi --m_axis_corners (64-bit records)--> AXI DMA (S2MM) --HP0--> DDR
#   PS GP0 --> SmartConnect --> fastnms s_axi_ctrl, VDMA and DMA registers
#   fastnms interrupt, DMA s2mm_introut, VDMA mm2s_introut --> xlconcat --> IRQ_F2P
#   everything on FCLK_CLK0 (142.857 MHz: the IO PLL's 1000 MHz / 7), one
#   proc_sys_reset
#
#   vivado -mode batch -nojournal -nolog -source vivado/package_ip.tcl
#   vivado -mode batch -nojournal -nolog -source vivado/create_bd_zc7z20.tcl \
#          -tclargs --board zedboard|zc702|none [options]
#
# Options (after -tclargs):
#   --board NAME     required: zedboard, zc702 or none. With a board, the PS
#                    takes the board preset (DDR, MIO) of the newest installed
#                    version of that board's files, and a board without
#                    installed files is an error (Vivado 2022.1 and later ship
#                    ZC702's board files but not ZedBoard's: install Avnet's,
#                    github.com/Avnet/bdf, from the Vivado Store or by
#                    set_param board.repoPaths). With none, only the DDR part
#                    is set (ZedBoard's): fine for synthesis and timing
#                    figures, not for booting a board.
#   --out DIR        project directory (default build/vivado/zc7z20)
#   --ip-repo DIR    the IP repository of package_ip.tcl (default build/vivado/ip)
#   --fclk-mhz F     FCLK_CLK0 in MHz (default 142.857143; 100 with --nms
#                    region4 or region8, whose tops reach 121 to 136 MHz on
#                    ECP5-8, docs/results.md): must be the IO PLL's 1000 MHz
#                    divided by an integer (an error otherwise, with the
#                    nearest values), and the script stops if the PS reports
#                    another frequency.
#   --score S, --nms N   the IP's SCORE and NMS generics (default opencv, 3x3)
#   --max-width W, --max-height H   (default 1920, 1080)
#   --orb            ORB descriptors in the records (DESCRIPTOR orb, with the
#                    budget MAX_PER_CELL 15 and ORB_MAX_CELL 32; --nms 3x3 or
#                    none): 6 beats of 8 bytes per keypoint for the DMA
#   --impl           also run synthesis, implementation and the bitstream,
#                    reports in DIR/reports, the hardware platform DIR/*.xsa
#   --jobs N         parallel jobs for --impl (default 4)
#
# Interrupt lines: IRQ_F2P[0] fastnms (IRQ 61), [1] DMA S2MM (IRQ 62),
# [2] VDMA MM2S (IRQ 63). The address map is written to DIR/address_map.txt.
# SCORE_VIDEO stays false here: m_axis_score would need its own DMA.
#
# Written for Vivado 2020.2 or later; not run where this project is developed
# (no Vivado there). flows/vivado_check/test_vivado_tcl.py runs it under plain Tcl with every
# Vivado command stubbed out.

source [file join [file dirname [info script]] fastnms_common.tcl]

set opts [fastnms::parse_args $argv [dict create \
    --board      {} \
    --out        [fastnms::path build vivado zc7z20] \
    --ip-repo    [fastnms::path build vivado ip] \
    --fclk-mhz   auto \
    --score      opencv \
    --nms        3x3 \
    --max-width  1920 \
    --max-height 1080 \
    --jobs       4 \
] {--impl --orb}]
if {[dict get $opts --orb] && [dict get $opts --nms] ni {3x3 none}} {
    error "create_bd: --orb needs --nms 3x3 or none (ORB runs behind the budget)"
}
set out_dir  [file normalize [dict get $opts --out]]
set ip_repo  [file normalize [dict get $opts --ip-repo]]
set board    [dict get $opts --board]

if {$board eq ""} {
    error "create_bd: --board is required: zedboard, zc702 or none (make vivado-bd BOARD=...)"
}
if {$board ni {zedboard zc702 none}} {
    error "create_bd: --board must be zedboard, zc702 or none, not '$board'"
}
if {[dict get $opts --fclk-mhz] eq "auto"} {
    dict set opts --fclk-mhz [fastnms::fclk_mhz [dict get $opts --nms]]
}
if {[catch {fastnms::fclk_setting [dict get $opts --fclk-mhz]} fclk]} {
    error "create_bd: --fclk-mhz: $fclk"
}
set fclk_mhz [dict get $fclk mhz]
if {![file exists [file join $ip_repo component.xml]]} {
    error "create_bd: no component.xml in $ip_repo: run vivado/package_ip.tcl first"
}

# ---- project ----------------------------------------------------------------
set project fastnms_zc7z20
set design  fastnms_system
file mkdir $out_dir
create_project -force $project $out_dir -part $fastnms::part

# The board parts of `board` (ZedBoard's are avnet.com:zedboard:part0:X.Y
# from Avnet, em.avnet.com:zed:part0:X.Y in Vivado releases before 2022.1,
# digilentinc.com:zedboard:part0:X.Y from Digilent; ZC702's
# xilinx.com:zc702:part0:X.Y), newest file version of each.
proc fastnms::board_parts {board} {
    set patterns [dict create zedboard {*:zedboard:part0:* *:zed:part0:*} zc702 {*:zc702:part0:*}]
    set parts {}
    foreach pattern [dict get $patterns $board] {
        foreach part [get_board_parts -quiet -latest_file_version $pattern] {
            if {$part ni $parts} {
                lappend parts $part
            }
        }
    }
    return $parts
}

set board_part ""
if {$board ne "none"} {
    set parts [fastnms::board_parts $board]
    if {![llength $parts]} {
        error "create_bd: no board files for $board in this Vivado (get_board_parts finds\
            none): Vivado 2022.1 and later ship ZC702's but not ZedBoard's; install\
            Avnet's (github.com/Avnet/bdf, or the Vivado Store), or run with --board none"
    }
    set board_part [fastnms::latest_board_part $parts]
    set_property board_part $board_part [current_project]
    puts "create_bd: board part $board_part (of: [join $parts {, }])"
}

set_property ip_repo_paths [list $ip_repo] [current_project]
update_ip_catalog -rebuild
if {![llength [get_ipdefs -all -quiet [fastnms::vlnv]]]} {
    error "create_bd: [fastnms::vlnv] is not in $ip_repo: run vivado/package_ip.tcl again"
}

create_bd_design $design

# ---- Zynq PS ----------------------------------------------------------------
set ps [create_bd_cell -type ip -vlnv xilinx.com:ip:processing_system7 ps7]
apply_bd_automation -rule xilinx.com:bd_rule:processing_system7 -config [list \
    make_external {FIXED_IO, DDR} \
    apply_board_preset [expr {$board_part ne "" ? 1 : 0}] \
    Master Disable Slave Disable] $ps
if {$board_part eq ""} {
    # The ZedBoard's DDR3 (two MT41K128M16 JT-125); ZC702 has MT41J256M8 HX-15E.
    # Board trace delays and MIO stay at their defaults.
    set_property CONFIG.PCW_UIPARAM_DDR_PARTNO {MT41K128M16 JT-125} $ps
}
# FCLK_CLK0 from the IO PLL (1000 MHz with both boards' presets) through a
# global buffer; the PS computes the two dividers from the frequency.
set_property -dict [list \
    CONFIG.PCW_USE_M_AXI_GP0             {1} \
    CONFIG.PCW_USE_S_AXI_HP0             {1} \
    CONFIG.PCW_S_AXI_HP0_DATA_WIDTH      {64} \
    CONFIG.PCW_EN_CLK0_PORT              {1} \
    CONFIG.PCW_EN_RST0_PORT              {1} \
    CONFIG.PCW_FCLK0_PERIPHERAL_CLKSRC   {IO PLL} \
    CONFIG.PCW_FPGA0_PERIPHERAL_FREQMHZ  $fclk_mhz \
    CONFIG.PCW_FCLK_CLK0_BUF             {TRUE} \
    CONFIG.PCW_USE_FABRIC_INTERRUPT      {1} \
    CONFIG.PCW_IRQ_F2P_INTR              {1} \
] $ps
# What the PS gives, read back at once: another frequency (an IO PLL not at
# 1000 MHz in some preset) would make every timing figure wrong.
set fclk_actual [get_property CONFIG.PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ $ps]
if {![string is double -strict $fclk_actual] || abs($fclk_actual - $fclk_mhz) > 0.001} {
    error "create_bd: FCLK_CLK0: requested $fclk_mhz MHz, the PS gives '$fclk_actual' MHz\
        (PCW_ACT_FPGA0_PERIPHERAL_FREQMHZ): check the IO PLL of the board preset"
}
puts "create_bd: FCLK_CLK0 $fclk_actual MHz (IO PLL [format %g $fastnms::io_pll_mhz] MHz\
    / [dict get $fclk divide])"

# ---- the IP, the DMAs, the interconnects --------------------------------------
set fastnms [create_bd_cell -type ip -vlnv [fastnms::vlnv] fastnms]
set_property -dict [list \
    CONFIG.MAX_WIDTH   [dict get $opts --max-width] \
    CONFIG.MAX_HEIGHT  [dict get $opts --max-height] \
    CONFIG.SCORE       [dict get $opts --score] \
    CONFIG.NMS         [dict get $opts --nms] \
    CONFIG.SCORE_VIDEO {false} \
] $fastnms
if {[dict get $opts --orb]} {
    set_property -dict [list \
        CONFIG.DESCRIPTOR   {orb} \
        CONFIG.MAX_PER_CELL {15} \
        CONFIG.ORB_MAX_CELL {32} \
    ] $fastnms
}

# Frames from DDR: MM2S only, 8-bit video stream (tuser = start of frame,
# tlast = end of line), 64-bit memory side; the realignment engine lets
# software use any line stride.
set vdma [create_bd_cell -type ip -vlnv xilinx.com:ip:axi_vdma vdma]
set_property -dict [list \
    CONFIG.c_include_mm2s            {1} \
    CONFIG.c_include_s2mm            {0} \
    CONFIG.c_m_axis_mm2s_tdata_width {8} \
    CONFIG.c_m_axi_mm2s_data_width   {64} \
    CONFIG.c_include_mm2s_dre        {1} \
    CONFIG.c_mm2s_max_burst_length   {16} \
    CONFIG.c_num_fstores             {1} \
    CONFIG.c_use_mm2s_fsync          {0} \
    CONFIG.c_mm2s_genlock_mode       {0} \
] $vdma

# Corner records to DDR: S2MM only, simple (register) mode, one transfer per
# frame (tlast on the frame's last record, tkeep all ones). The length
# register has 26 bits, the maximum (PG021, S2MM_LENGTH): 64 MiB - 1 per
# transfer. --nms none at 1920x1080 can emit up to about 2 M records of 8
# bytes, 16 MB; 23 bits (8 MiB) would not do.
set dma [create_bd_cell -type ip -vlnv xilinx.com:ip:axi_dma dma]
set_property -dict [list \
    CONFIG.c_include_sg                {0} \
    CONFIG.c_sg_include_stscntrl_strm  {0} \
    CONFIG.c_include_mm2s              {0} \
    CONFIG.c_include_s2mm              {1} \
    CONFIG.c_s_axis_s2mm_tdata_width   {64} \
    CONFIG.c_m_axi_s2mm_data_width     {64} \
    CONFIG.c_s2mm_burst_size           {16} \
    CONFIG.c_sg_length_width           {26} \
] $dma

set ctrl_smc [create_bd_cell -type ip -vlnv xilinx.com:ip:smartconnect ctrl_smc]
set_property -dict [list CONFIG.NUM_SI {1} CONFIG.NUM_MI {3}] $ctrl_smc
set mem_smc [create_bd_cell -type ip -vlnv xilinx.com:ip:smartconnect mem_smc]
set_property -dict [list CONFIG.NUM_SI {2} CONFIG.NUM_MI {1}] $mem_smc

set rst [create_bd_cell -type ip -vlnv xilinx.com:ip:proc_sys_reset rst]
set irq [create_bd_cell -type ip -vlnv xilinx.com:ip:xlconcat irq_concat]
set_property CONFIG.NUM_PORTS {3} $irq

# ---- connections --------------------------------------------------------------
# (In namespace fastnms: a global proc could hide a Vivado command, as a
# `connect_net` proc once hid Vivado's own connect_net.)
proc fastnms::connect_intf {from to} {
    connect_bd_intf_net [get_bd_intf_pins $from] [get_bd_intf_pins $to]
}

# One net from `driver` to every pin of `loads`.
proc fastnms::connect_pins {driver loads} {
    set pins [list [get_bd_pins $driver]]
    foreach load $loads {
        lappend pins [get_bd_pins $load]
    }
    connect_bd_net {*}$pins
}

fastnms::connect_intf ps7/M_AXI_GP0          ctrl_smc/S00_AXI
fastnms::connect_intf ctrl_smc/M00_AXI       fastnms/s_axi_ctrl
fastnms::connect_intf ctrl_smc/M01_AXI       vdma/S_AXI_LITE
fastnms::connect_intf ctrl_smc/M02_AXI       dma/S_AXI_LITE
fastnms::connect_intf vdma/M_AXI_MM2S        mem_smc/S00_AXI
fastnms::connect_intf dma/M_AXI_S2MM         mem_smc/S01_AXI
fastnms::connect_intf mem_smc/M00_AXI        ps7/S_AXI_HP0
fastnms::connect_intf vdma/M_AXIS_MM2S       fastnms/s_axis_video
fastnms::connect_intf fastnms/m_axis_corners dma/S_AXIS_S2MM

fastnms::connect_pins ps7/FCLK_CLK0 {
    ps7/M_AXI_GP0_ACLK ps7/S_AXI_HP0_ACLK
    ctrl_smc/aclk mem_smc/aclk rst/slowest_sync_clk
    fastnms/aclk
    vdma/s_axi_lite_aclk vdma/m_axi_mm2s_aclk vdma/m_axis_mm2s_aclk
    dma/s_axi_lite_aclk dma/m_axi_s2mm_aclk
}
fastnms::connect_pins ps7/FCLK_RESET0_N     {rst/ext_reset_in}
fastnms::connect_pins rst/peripheral_aresetn {fastnms/aresetn vdma/axi_resetn dma/axi_resetn}
fastnms::connect_pins rst/interconnect_aresetn {ctrl_smc/aresetn mem_smc/aresetn}

fastnms::connect_pins fastnms/interrupt  {irq_concat/In0}
fastnms::connect_pins dma/s2mm_introut   {irq_concat/In1}
fastnms::connect_pins vdma/mm2s_introut  {irq_concat/In2}
fastnms::connect_pins irq_concat/dout    {ps7/IRQ_F2P}

# ---- addresses, checks, wrapper ------------------------------------------------
assign_bd_address
validate_bd_design
save_bd_design

set map [open [file join $out_dir address_map.txt] w]
puts $map "# $design: slave segments seen from the PS (GP0) and the DMAs (HP0)"
foreach space [get_bd_addr_spaces -quiet -of_objects [get_bd_cells {ps7 vdma dma}]] {
    foreach seg [get_bd_addr_segs -quiet -of_objects $space] {
        puts $map [format "%-24s %-40s offset %s range %s" $space \
            [get_property NAME $seg] [get_property OFFSET $seg] [get_property RANGE $seg]]
    }
}
close $map

set bd_file [get_files "$design.bd"]
set wrapper [make_wrapper -files $bd_file -top]
add_files -norecurse $wrapper
set_property top "${design}_wrapper" [current_fileset]
update_compile_order -fileset sources_1

puts "create_bd: [file join $out_dir $project.xpr], addresses in [file join $out_dir address_map.txt]"

# ---- optional: synthesis, implementation, bitstream ---------------------------------
if {[dict get $opts --impl]} {
    set jobs [dict get $opts --jobs]
    set reports [file join $out_dir reports]
    file mkdir $reports

    launch_runs synth_1 -jobs $jobs
    wait_on_run synth_1
    if {[get_property PROGRESS [get_runs synth_1]] ne "100%"} {
        error "create_bd: synthesis failed (see [file join $out_dir $project.runs synth_1])"
    }
    launch_runs impl_1 -to_step write_bitstream -jobs $jobs
    wait_on_run impl_1
    if {[get_property PROGRESS [get_runs impl_1]] ne "100%"} {
        error "create_bd: implementation failed (see [file join $out_dir $project.runs impl_1])"
    }

    open_run impl_1
    report_utilization -file [file join $reports utilization.rpt]
    report_utilization -hierarchical -file [file join $reports utilization_hierarchical.rpt]
    report_timing_summary -max_paths 10 -file [file join $reports timing_summary.rpt]
    write_hw_platform -fixed -include_bit -force -file [file join $out_dir "$design.xsa"]
    set wns [get_property SLACK [get_timing_paths -max_paths 1 -nworst 1 -setup]]
    puts "create_bd: implemented, worst setup slack $wns ns; reports in $reports"
}
