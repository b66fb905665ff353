-- The paper's region NMS, exact: one record per 4- or 8-connected region of
-- corner pixels (its best pixel, score and area), one pixel per clock for any
-- content. Wires its parts (schedule, tables, control, keys), the input skid
-- buffer and the record FIFO.
-- Datasheet: docs/fastnms_nms_region.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_nms_region_pkg.all;

entity fastnms_nms_region is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE_BITS   : positive := 8;
    CONNECTIVITY : positive := 8
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    cfg_width : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_corner : in    std_logic;
    in_score  : in    unsigned(SCORE_BITS - 1 downto 0);
    in_sof    : in    std_logic;
    in_eol    : in    std_logic;
    in_eof    : in    std_logic;
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_x     : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y     : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_score : out   unsigned(SCORE_BITS - 1 downto 0);
    out_area  : out   unsigned(AREA_BITS - 1 downto 0);
    out_eof   : out   std_logic
  );
end entity fastnms_nms_region;

architecture rtl of fastnms_nms_region is

  constant XB       : positive := clog2(MAX_WIDTH);
  constant YB       : positive := bits_for(MAX_HEIGHT);
  constant WB       : positive := bits_for(MAX_WIDTH);
  constant DB       : positive := data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS);
  constant SB       : positive := slot_bits(MAX_WIDTH);
  constant RB       : positive := clog2(stack_ram_words(MAX_WIDTH));
  constant OUT_BITS : positive := 1 + XB + YB + SCORE_BITS + AREA_BITS;

  -- Input, through a skid buffer (registered in_ready).
  signal px_valid  : std_logic;
  signal px_ready  : std_logic;
  signal px_data   : std_logic_vector(WB + SCORE_BITS + 3 downto 0);
  signal px_width  : unsigned(WB - 1 downto 0);
  signal px_corner : std_logic;
  signal px_score  : unsigned(SCORE_BITS - 1 downto 0);
  signal px_sof    : std_logic;
  signal px_eol    : std_logic;
  signal px_eof    : std_logic;

  -- The records between the parts (fastnms_nms_region_pkg): the schedule's
  -- step, the tables' words at the reader's column, the column's operation,
  -- the table writes.
  signal step   : step_t(cx(XB - 1 downto 0), cy(YB - 1 downto 0), ahead_slot(SB - 1 downto 0));
  signal run    : run_t(data(DB - 1 downto 0));
  signal cmd    : command_t(slot(SB - 1 downto 0), score(SCORE_BITS - 1 downto 0), cx(XB - 1 downto 0),
                            cy(YB - 1 downto 0), ram_wa(RB - 1 downto 0), ram_ra(RB - 1 downto 0));
  signal writes : writes_t(data(slot(SB - 1 downto 0), word(DB - 1 downto 0)), head(addr(SB downto 0)),
                           head_spare(addr(SB downto 0)), last(addr(SB downto 0)));

  -- Records.
  signal rec_valid : std_logic;
  signal rec_eof   : std_logic;
  signal rec_x     : unsigned(XB - 1 downto 0);
  signal rec_y     : unsigned(YB - 1 downto 0);
  signal rec_score : unsigned(SCORE_BITS - 1 downto 0);
  signal rec_area  : unsigned(AREA_BITS - 1 downto 0);
  signal rec_room  : std_logic;
  signal rec_full  : std_logic;
  signal q_data    : std_logic_vector(OUT_BITS - 1 downto 0);

begin

  assert CONNECTIVITY = 4 or CONNECTIVITY = 8
    report "fastnms_nms_region: CONNECTIVITY must be 4 or 8"
    severity failure;
  assert MAX_WIDTH >= 3
    report "fastnms_nms_region: MAX_WIDTH must be at least 3"
    severity failure;

  pixel_input : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => WB + SCORE_BITS + 4
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => in_valid,
      in_ready  => in_ready,
      in_data   => std_logic_vector(cfg_width) & in_corner & in_sof & in_eol & in_eof &
                   std_logic_vector(in_score),
      out_valid => px_valid,
      out_ready => px_ready,
      out_data  => px_data
    );

  -- cfg_width travels with each pixel: it must hold when a frame's first
  -- pixel is accepted, which is before that pixel steps.
  px_width  <= unsigned(px_data(WB + SCORE_BITS + 3 downto SCORE_BITS + 4));
  px_corner <= px_data(SCORE_BITS + 3);
  px_sof    <= px_data(SCORE_BITS + 2);
  px_eol    <= px_data(SCORE_BITS + 1);
  px_eof    <= px_data(SCORE_BITS);
  px_score  <= unsigned(px_data(SCORE_BITS - 1 downto 0));

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

  tables : entity work.fastnms_nms_region_tables
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT,
      SCORE_BITS => SCORE_BITS
    )
    port map (
      clk    => clk,
      rst    => rst,
      step   => step,
      cmd    => cmd,
      writes => writes,
      run    => run
    );

  control : entity work.fastnms_nms_region_control
    generic map (
      MAX_WIDTH    => MAX_WIDTH,
      MAX_HEIGHT   => MAX_HEIGHT,
      SCORE_BITS   => SCORE_BITS,
      CONNECTIVITY => CONNECTIVITY
    )
    port map (
      clk    => clk,
      rst    => rst,
      step   => step,
      c0     => px_corner,
      c_eol  => px_eol,
      score  => px_score,
      run    => run,
      last_w => writes.last,
      cmd    => cmd
    );

  keys : entity work.fastnms_nms_region_keys
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT,
      SCORE_BITS => SCORE_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      cmd       => cmd,
      r_col0    => step.r_col0,
      data_word => run.data,
      writes    => writes,
      rec_room  => rec_room,
      rec_valid => rec_valid,
      rec_eof   => rec_eof,
      rec_x     => rec_x,
      rec_y     => rec_y,
      rec_score => rec_score,
      rec_area  => rec_area
    );

  -- rec_room: almost_full = '0' promises in_ready on this clock and the next
  -- two (fastnms_fifo: R = 8 - 2 - 4), for the records in flight.
  records : entity work.fastnms_fifo
    generic map (
      DEPTH             => 8,
      WIDTH             => OUT_BITS,
      STYLE             => "distributed",
      ALMOST_FULL_LEVEL => 4
    )
    port map (
      clk         => clk,
      rst         => rst,
      in_valid    => rec_valid,
      in_ready    => open,
      almost_full => rec_full,
      in_data     => rec_eof & std_logic_vector(rec_x) & std_logic_vector(rec_y) &
                     std_logic_vector(rec_score) & std_logic_vector(rec_area),
      out_valid   => out_valid,
      out_ready   => out_ready,
      out_data    => q_data,
      busy        => open
    );

  rec_room <= not rec_full;

  out_eof   <= q_data(OUT_BITS - 1);
  out_x     <= unsigned(q_data(OUT_BITS - 2 downto YB + SCORE_BITS + AREA_BITS));
  out_y     <= unsigned(q_data(YB + SCORE_BITS + AREA_BITS - 1 downto SCORE_BITS + AREA_BITS));
  out_score <= unsigned(q_data(SCORE_BITS + AREA_BITS - 1 downto AREA_BITS));
  out_area  <= unsigned(q_data(AREA_BITS - 1 downto 0));

end architecture rtl;
