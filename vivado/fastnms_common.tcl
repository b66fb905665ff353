# Settings shared by the Vivado scripts of this folder: paths, the IP's VLNV,
# the target part, the RTL file list and a small option parser.
#
# Plain Tcl 8.5 with no Vivado command, so flows/vivado_check/test_vivado_tcl.py runs it as it
# is under tclsh (or Python's tkinter). Every path is derived from this
# file's own location: the scripts work from any directory.

namespace eval fastnms {
    variable script_dir [file normalize [file dirname [info script]]]
    variable repo       [file dirname $script_dir]

    # The packaged IP: vendor:library:name:version. The version is the
    # major.minor of the file VERSION (checked by flows/docs_check/test_version.py).
    variable vendor  fastnms
    variable library vision
    variable name    fastnms_axi
    variable version 0.2
    variable top     fastnms_axi

    # ZedBoard and ZC702 both carry this Zynq-7020.
    variable part xc7z020clg484-1

    # FCLK_CLK0, the one clock of the block design (and of the out-of-context
    # constraint): the PS's IO PLL divided by two 6-bit dividers (UG585,
    # "PL Clocks": FPGA0_CLK_CTRL DIVISOR0 and DIVISOR1, 1 to 63 each). With
    # the 33.333 MHz PS_CLK of both boards the IO PLL runs at 1000 MHz (the
    # presets' PCW_IOPLL_CTRL_FBDIV 30), so 150 MHz is out of reach: the PS
    # would give 142.857 MHz (1000 / 7) for a 150 MHz request. The design
    # asks for 1000 / 7 on purpose, and constraints/fastnms_ooc.xdc uses its
    # period, 7.000 ns.
    variable io_pll_mhz  1000.0
    variable fclk_divide 7
    # With a region NMS: 1000 / 9 = 111.111 MHz (fastnms::fclk_mhz).
    variable region_fclk_divide 9

    # RTL folders, lowest layer first.
    variable areas {common fast nms budget orb resize core top}

    # The out-of-context clock constraint (aclk).
    variable ooc_xdc [file join $repo constraints fastnms_ooc.xdc]
}

proc fastnms::vlnv {} {
    variable vendor
    variable library
    variable name
    variable version
    return "$vendor:$library:$name:$version"
}

# A path under the repository.
proc fastnms::path {args} {
    variable repo
    return [file join $repo {*}$args]
}

proc fastnms::read_text {path} {
    set f [open $path r]
    set text [read $f]
    close $f
    return $text
}

# Every rtl/<area>/*.vhd in compile order: each file after the files that
# define the packages it uses (use work.X) and the entities it instantiates
# (entity work.X); otherwise in folder order, then by name. The same rule as
# sim/sources.py, so a new file under rtl/ is picked up with no edit here.
proc fastnms::rtl_files {} {
    variable areas
    set files {}
    foreach area $areas {
        foreach f [lsort [glob -nocomplain -directory [path rtl $area] *.vhd]] {
            lappend files $f
        }
    }
    set defined_in [dict create]
    set uses [dict create]
    foreach f $files {
        # Lower case, comments removed.
        set text [string tolower [read_text $f]]
        regsub -all -- {--[^\n]*} $text {} text
        foreach {- unit} [regexp -all -inline -- {(?:^|\n)\s*(?:entity|package)\s+(\w+)\s+is\M} $text] {
            dict set defined_in $unit $f
        }
        set used {}
        foreach {- unit} [regexp -all -inline -- {\m(?:entity|use)\s+work\.(\w+)} $text] {
            if {$unit ni $used} {
                lappend used $unit
            }
        }
        dict set uses $f $used
    }
    set ordered {}
    set pending $files
    while {[llength $pending]} {
        set ready {}
        set waiting {}
        foreach f $pending {
            set ok 1
            foreach unit [dict get $uses $f] {
                if {![dict exists $defined_in $unit]} {
                    error "fastnms: $f uses work.$unit, which no file under rtl/ defines"
                }
                set dep [dict get $defined_in $unit]
                if {$dep ne $f && $dep ni $ordered} {
                    set ok 0
                }
            }
            if {$ok} {
                lappend ready $f
            } else {
                lappend waiting $f
            }
        }
        if {![llength $ready]} {
            error "fastnms: circular dependency among $waiting"
        }
        set ordered [concat $ordered $ready]
        set pending $waiting
    }
    return $ordered
}

# The packaging wrapper: the IP packager reads the top-level file as VHDL-93
# (UG1118, "Top-Level HDL Requirements": a VHDL-2008 top level needs a VHDL or
# Verilog wrapper), while rtl/ is VHDL-2008. The wrapper is entity `name`,
# with the entity declaration of `top_entity` copied word for word (generics,
# ports, X_INTERFACE attributes: VHDL-93 there), and an architecture that
# instantiates work.`top_entity` with every generic and port mapped by name.
proc fastnms::ip_wrapper {top_file top_entity name} {
    set text [read_text $top_file]
    set lower [string tolower $text]
    set start [string first "entity [string tolower $top_entity] is" $lower]
    set end_at [string first "end entity [string tolower $top_entity]" $lower $start]
    if {$start < 0 || $end_at < 0} {
        error "fastnms: no 'entity $top_entity is ... end entity $top_entity' in $top_file"
    }
    set end_at [string first ";" $text $end_at]
    set entity [string range $text $start $end_at]

    # Generic and port names, from the declaration without its comments.
    regsub -all -- {--[^\n]*} $entity {} code
    set generics {}
    set ports {}
    set port_at [lindex [regexp -nocase -indices -inline -- {\mport\s*\(} $code] 0 0]
    if {$port_at eq ""} {
        set port_at [string length $code]
    }
    set generic_at [lindex [regexp -nocase -indices -inline -- {\mgeneric\s*\(} $code] 0 0]
    if {$generic_at ne "" && $generic_at < $port_at} {
        set clause [string range $code $generic_at [expr {$port_at - 1}]]
        set clause [string range $clause [expr {[string first "(" $clause] + 1}] end]
        foreach {- names} [regexp -all -inline -- {(\w+(?:\s*,\s*\w+)*)\s*:[^=]} $clause] {
            foreach n [split $names ,] {
                lappend generics [string trim $n]
            }
        }
    }
    set clause [string range $code $port_at end]
    foreach {- names} [regexp -all -nocase -inline -- \
            {(\w+(?:\s*,\s*\w+)*)\s*:\s*(?:in|out|inout|buffer)\M} $clause] {
        foreach n [split $names ,] {
            lappend ports [string trim $n]
        }
    }

    set map_lines {}
    foreach {kind names} [list generic $generics port $ports] {
        if {![llength $names]} {
            continue
        }
        set width 0
        foreach n $names {
            set width [expr {max($width, [string length $n])}]
        }
        set items {}
        foreach n $names {
            lappend items [format "      %-*s => %s" $width $n $n]
        }
        lappend map_lines "    $kind map (\n[join $items ,\n]\n    )"
    }

    set renamed [regsub -nocase -all -- "\\m$top_entity\\M" $entity $name]
    return [join [list \
        "-- Generated by vivado/package_ip.tcl (fastnms::ip_wrapper) from $top_entity's" \
        "-- entity declaration: the VHDL-93 top level the Vivado IP packager needs." \
        "library ieee;" \
        "  use ieee.std_logic_1164.all;" \
        "" \
        $renamed \
        "" \
        "architecture wrapper of $name is" \
        "begin" \
        "" \
        "  ip : entity work.$top_entity" \
        "[join $map_lines \n];" \
        "" \
        "end architecture wrapper;" \
        ""] \n]
}

# FCLK_CLK0 for a request of `mhz` MHz: a dict with mhz (io_pll_mhz / N, to
# 6 decimals), divide (N), divisor0 and divisor1 (N = divisor0 * divisor1,
# each 1 to 63). An error when no N gives `mhz` within 1 kHz: the PS would
# quietly give another frequency, and every timing figure would be for a
# clock the board does not have.
proc fastnms::fclk_setting {mhz} {
    variable io_pll_mhz
    if {![string is double -strict $mhz] || $mhz <= 0} {
        error "fastnms: FCLK_CLK0 must be a frequency in MHz, not '$mhz'"
    }
    set n [expr {max(1, round($io_pll_mhz / $mhz))}]
    set candidates {}
    foreach divide [list [expr {$n - 1}] $n [expr {$n + 1}]] {
        if {$divide < 1} {
            continue
        }
        set pair [fastnms::divisor_pair $divide]
        if {[llength $pair]} {
            lappend candidates $divide $pair
        }
    }
    foreach {divide pair} $candidates {
        set actual [expr {$io_pll_mhz / $divide}]
        if {abs($actual - $mhz) <= 0.001} {
            return [dict create mhz [format %.6f $actual] divide $divide \
                divisor0 [lindex $pair 0] divisor1 [lindex $pair 1]]
        }
    }
    set nearest {}
    foreach {divide pair} $candidates {
        lappend nearest "[format %.6f [expr {$io_pll_mhz / $divide}]] (/$divide)"
    }
    error "fastnms: FCLK_CLK0 of $mhz MHz is not [format %g $io_pll_mhz] MHz (IO PLL) divided\
        by an integer: the PS would give another frequency; nearest: [join $nearest {, }]"
}

# Two 6-bit dividers (1 to 63) whose product is `divide`, the first as small
# as possible; {} when there are none.
proc fastnms::divisor_pair {divide} {
    for {set d0 1} {$d0 <= 63} {incr d0} {
        if {$divide % $d0 == 0 && $divide / $d0 <= 63} {
            return [list $d0 [expr {$divide / $d0}]]
        }
    }
    return {}
}

# The default FCLK_CLK0 in MHz (io_pll_mhz / fclk_divide, 6 decimals). With
# `nms` region4 or region8, io_pll_mhz / region_fclk_divide: the fastest IO PLL
# clock at most 0.90 of the slower region top's ECP5-8 Fmax in docs/results.md,
# as the 3x3's default was chosen (flows/vivado_check/test_vivado_tcl.py checks
# it against results.md). Not timed by Vivado; 1080p60 needs 124.4 Mpixel/s.
proc fastnms::fclk_mhz {{nms 3x3}} {
    variable io_pll_mhz
    variable fclk_divide
    variable region_fclk_divide
    set divide $fclk_divide
    if {$nms in {region4 region8}} {
        set divide $region_fclk_divide
    }
    return [format %.6f [expr {$io_pll_mhz / $divide}]]
}

# The board part of the newest version among `parts` (vendor:board:part0:X.Y
# names, as get_board_parts returns them): versions compared number by number
# (1.10 after 1.4), not as strings, and not sorted by vendor. {} for none.
proc fastnms::latest_board_part {parts} {
    set best {}
    set best_version {}
    foreach part $parts {
        set version [split [lindex [split $part :] end] .]
        if {$best eq "" || [fastnms::version_compare $version $best_version] > 0} {
            set best $part
            set best_version $version
        }
    }
    return $best
}

# -1, 0 or 1 as version list `a` is older, the same or newer than `b`; a
# missing or non-numeric field counts as 0.
proc fastnms::version_compare {a b} {
    set n [expr {max([llength $a], [llength $b])}]
    for {set i 0} {$i < $n} {incr i} {
        set x [lindex $a $i]
        set y [lindex $b $i]
        if {![string is integer -strict $x]} {
            set x 0
        }
        if {![string is integer -strict $y]} {
            set y 0
        }
        if {$x != $y} {
            return [expr {$x < $y ? -1 : 1}]
        }
    }
    return 0
}

# The clock period (ns) of the out-of-context constraint file.
proc fastnms::ooc_period {} {
    variable ooc_xdc
    if {![regexp -- {create_clock\s+-period\s+([0-9.]+)} [read_text $ooc_xdc] - period]} {
        error "fastnms: no create_clock -period in $ooc_xdc"
    }
    return $period
}

# Command-line options (the words after -tclargs): `defaults` maps each
# --option to its default value; the options listed in `flags` take no value
# and are 0 unless given.
proc fastnms::parse_args {argv defaults {flags {}}} {
    set opts $defaults
    foreach flag $flags {
        dict set opts $flag 0
    }
    set i 0
    while {$i < [llength $argv]} {
        set arg [lindex $argv $i]
        if {$arg in $flags} {
            dict set opts $arg 1
            incr i
            continue
        }
        if {![dict exists $defaults $arg]} {
            set known [lsort [concat [dict keys $defaults] $flags]]
            error "unknown option '$arg' (options: [join $known {, }])"
        }
        if {$i + 1 >= [llength $argv]} {
            error "option $arg needs a value"
        }
        dict set opts $arg [lindex $argv [expr {$i + 1}]]
        incr i 2
    }
    return $opts
}
