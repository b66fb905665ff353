# Out-of-context constraint of fastnms_axi: aclk at 150 MHz, the FCLK_CLK0
# that vivado/create_bd_zc7z20.tcl requests. Read by vivado/synth_ooc.tcl
# (read_xdc -mode out_of_context); not part of the packaged IP, whose clock
# comes from the block design.
create_clock -period 6.667 -name aclk [get_ports aclk]

# Out of context the clock port has no driver: place and route it as if a
# global buffer drove it, as in the block design.
set_property HD.CLK_SRC BUFGCTRL_X0Y0 [get_ports aclk]
