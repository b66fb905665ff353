# Out-of-context constraint of fastnms_axi: aclk at 142.857 MHz (7.000 ns),
# the FCLK_CLK0 of vivado/create_bd_zc7z20.tcl: the Zynq IO PLL's 1000 MHz
# divided by 7 (150 MHz is not reachable with integer dividers; see
# fastnms::fclk_setting in vivado/fastnms_common.tcl). Read by
# vivado/synth_ooc.tcl (read_xdc -mode out_of_context); not part of the
# packaged IP, whose clock comes from the block design.
create_clock -period 7.000 -name aclk [get_ports aclk]

# Out of context the clock port has no driver: place and route it as if a
# global buffer drove it, as in the block design (PCW_FCLK_CLK0_BUF TRUE).
set_property HD.CLK_SRC BUFGCTRL_X0Y0 [get_ports aclk]
