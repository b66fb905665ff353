# Out-of-context synthesis and implementation of fastnms_axi (or another
# entity of rtl/) on the xc7z020, with constraints/fastnms_ooc.xdc; reports
# utilization and timing. Non-project mode: nothing but build/ is written.
#
#   vivado -mode batch -nojournal -nolog -source vivado/synth_ooc.tcl \
#          [-tclargs [options]]
#
# Options (after -tclargs):
#   --out DIR          output directory (default build/vivado/ooc)
#   --top NAME         entity (default fastnms_axi)
#   --clock-port P     the clock port of --top (default aclk); for another
#                      port the period of the .xdc is applied to P instead
#   --generics LIST    generics of --top, e.g. "SCORE=sad NMS=none MAX_WIDTH=1280"
#                      (synth_design -generic NAME=VALUE each; default: the
#                      entity's defaults)
#   --part PART        (default xc7z020clg484-1)
#   --synth-only       stop after synthesis
#   --require-timing   exit with an error when the worst setup slack is negative
#
# Output: DIR/utilization_synth.rpt, utilization_route.rpt (and
# _hierarchical), timing_summary.rpt, post_route.dcp and summary.txt (LUT,
# FF, BRAM, DSP, worst slack, the clock it would meet).
#
# Written for Vivado 2020.2 or later; not run where this project is developed
# (no Vivado there). flows/vivado_check/test_vivado_tcl.py runs it under plain Tcl with every
# Vivado command stubbed out.

source [file join [file dirname [info script]] fastnms_common.tcl]

set opts [fastnms::parse_args $argv [dict create \
    --out        [fastnms::path build vivado ooc] \
    --top        $fastnms::top \
    --clock-port aclk \
    --generics   {} \
    --part       $fastnms::part \
] {--synth-only --require-timing}]
set out_dir    [file normalize [dict get $opts --out]]
set top        [dict get $opts --top]
set clock_port [dict get $opts --clock-port]
set period     [fastnms::ooc_period]

set generic_args {}
foreach assignment [dict get $opts --generics] {
    if {![regexp -- {^\w+=\S+$} $assignment]} {
        error "synth_ooc: a generic is NAME=VALUE, not '$assignment'"
    }
    lappend generic_args -generic $assignment
}

file mkdir $out_dir

foreach f [fastnms::rtl_files] {
    read_vhdl -vhdl2008 $f
}
if {$clock_port eq "aclk"} {
    read_xdc -mode out_of_context $fastnms::ooc_xdc
} else {
    # The same constraint on another port, written beside the reports.
    set xdc [file join $out_dir "clock_$clock_port.xdc"]
    set f [open $xdc w]
    puts $f "create_clock -period $period -name $clock_port \[get_ports $clock_port\]"
    puts $f "set_property HD.CLK_SRC BUFGCTRL_X0Y0 \[get_ports $clock_port\]"
    close $f
    read_xdc -mode out_of_context $xdc
}

synth_design -top $top -part [dict get $opts --part] -mode out_of_context {*}$generic_args
report_utilization -file [file join $out_dir utilization_synth.rpt]
write_checkpoint -force [file join $out_dir post_synth.dcp]

set stage synthesis
if {![dict get $opts --synth-only]} {
    opt_design
    place_design
    phys_opt_design
    route_design
    report_utilization -file [file join $out_dir utilization_route.rpt]
    report_utilization -hierarchical -file [file join $out_dir utilization_route_hierarchical.rpt]
    write_checkpoint -force [file join $out_dir post_route.dcp]
    set stage route
}
report_timing_summary -max_paths 10 -file [file join $out_dir timing_summary.rpt]

# ---- summary ----------------------------------------------------------------
proc fastnms::count_cells {filter} {
    return [llength [get_cells -quiet -hierarchical -filter $filter]]
}

set wns [get_property SLACK [get_timing_paths -max_paths 1 -nworst 1 -setup]]
if {$wns eq ""} {
    error "synth_ooc: no timed path: is $clock_port the clock port of $top?"
}
set summary [list \
    "top $top ($stage, [dict get $opts --part]) generics {[dict get $opts --generics]}" \
    "LUT [fastnms::count_cells {PRIMITIVE_GROUP == LUT}]" \
    "FF [fastnms::count_cells {PRIMITIVE_GROUP == FLOP_LATCH}]" \
    "SRL [fastnms::count_cells {REF_NAME =~ SRL*}]" \
    "LUTRAM+SRL [fastnms::count_cells {PRIMITIVE_GROUP == DMEM}]" \
    "RAMB36 [fastnms::count_cells {REF_NAME =~ RAMB36*}]" \
    "RAMB18 [fastnms::count_cells {REF_NAME =~ RAMB18*}]" \
    "DSP [fastnms::count_cells {REF_NAME =~ DSP48*}]" \
    "clock $clock_port period $period ns, worst setup slack $wns ns, met at [format %.1f [expr {1000.0 / ($period - $wns)}]] MHz" \
]
set f [open [file join $out_dir summary.txt] w]
puts $f [join $summary \n]
close $f
puts "synth_ooc: [join $summary {; }]"
puts "synth_ooc: reports in $out_dir"

if {$wns < 0} {
    puts "synth_ooc: TIMING NOT MET at $period ns"
    if {[dict get $opts --require-timing]} {
        error "synth_ooc: worst setup slack $wns ns at $period ns"
    }
}
