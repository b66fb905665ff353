-- fastnms_nms_region_schedule with flat ports, for its cocotb testbench
-- (tb/nms/region_schedule_tb.py): GHDL's VPI does not show record ports.
-- The outputs are step_t's fields, under their names.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_nms_region_pkg.all;

entity fastnms_nms_region_schedule_flat is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 4095
  );
  port (
    clk        : in    std_logic;
    rst        : in    std_logic;
    px_valid   : in    std_logic;
    px_ready   : out   std_logic;
    px_corner  : in    std_logic;
    px_width   : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    px_sof     : in    std_logic;
    px_eol     : in    std_logic;
    px_eof     : in    std_logic;
    rec_room   : in    std_logic;
    cstep      : out   std_logic;
    rstep      : out   std_logic;
    lock       : out   std_logic;
    flush_ends : out   std_logic;
    first_row  : out   std_logic;
    cm         : out   std_logic;
    cx         : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    cy         : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    cur_bank   : out   std_logic;
    pm         : out   std_logic;
    p0         : out   std_logic;
    r_last     : out   std_logic;
    r_col0     : out   std_logic;
    r_col1     : out   std_logic;
    r_col2     : out   std_logic;
    r_slot0    : out   std_logic;
    r_bank     : out   std_logic;
    ahead_slot : out   unsigned(slot_bits(MAX_WIDTH) - 1 downto 0)
  );
end entity fastnms_nms_region_schedule_flat;

architecture wrapper of fastnms_nms_region_schedule_flat is

  signal step : step_t(cx(cx'range), cy(cy'range), ahead_slot(ahead_slot'range));

begin

  schedule : entity work.fastnms_nms_region_schedule
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT
    )
    port map (
      clk       => clk,
      rst       => rst,
      px_valid  => px_valid,
      px_ready  => px_ready,
      px_corner => px_corner,
      px_width  => px_width,
      px_sof    => px_sof,
      px_eol    => px_eol,
      px_eof    => px_eof,
      rec_room  => rec_room,
      step      => step
    );

  cstep      <= step.cstep;
  rstep      <= step.rstep;
  lock       <= step.lock;
  flush_ends <= step.flush_ends;
  first_row  <= step.first_row;
  cm         <= step.cm;
  cx         <= step.cx;
  cy         <= step.cy;
  cur_bank   <= step.cur_bank;
  pm         <= step.pm;
  p0         <= step.p0;
  r_last     <= step.r_last;
  r_col0     <= step.r_col0;
  r_col1     <= step.r_col1;
  r_col2     <= step.r_col2;
  r_slot0    <= step.r_slot0;
  r_bank     <= step.r_bank;
  ahead_slot <= step.ahead_slot;

end architecture wrapper;
