-- Region NMS (the paper's streaming NMS): one record per 4- or 8-connected
-- region of corner pixels, its maximum score, a tie going to the region's
-- first pixel in raster order, and its area (out_area: its corner pixels,
-- saturating at 2 ** AREA_BITS - 1; 0 on the end-of-frame beat). One pixel
-- per clock whatever the content.
--
-- The algorithm is golden/region_stream.py, step for step; the design, its
-- invariants and the clock schedule are in docs/fastnms_nms_region.md. In
-- short: the classes of one row's runs never cross, so the previous row's open
-- classes nest and live on a stack; per run (slot = start column / 2) a bit
-- says whether it is the first run of its class in its row (head table, one
-- bank per row parity) and one whether it is the last (last table): a first
-- run pushes its class, a later run continues the top, a last run pops it. A
-- data table holds each class's best key and area at its first run's slot, and every
-- column changes only the stack's top two entries, the current run's class
-- and one word of each table.
--
-- The block is this entity's parts, one job each (docs/fastnms_nms_region.md,
-- Parts), wired here:
--   fastnms_nms_region_schedule  which side steps each clock: the current
--                                row, the previous row's reader (with the
--                                row memory, read two columns ahead), the
--                                flush and the PRIME clocks;
--   fastnms_nms_region_tables    the head, last and data tables, read ahead
--                                of the reader, taking the writes that land
--                                on a word being read;
--   fastnms_nms_region_control   the column's decisions on flags only (the
--                                stack entries' flags, attached, active),
--                                registered as the column's operation (op);
--   fastnms_nms_region_keys      the key data path, carrying op out on the
--                                next clock: slots, keys, the stack's slots
--                                and keys, table writes, records;
-- then the record FIFO. Their shared types and widths are in
-- fastnms_nms_region_pkg.
--
-- Clocks: the current row steps one column per accepted pixel; rows >= 1 step
-- the previous row's reader with it. After a frame's last pixel the reader
-- flushes that row alone, one column per clock, while the next frame's first
-- row (which has no previous row) comes in; then the end-of-frame beat.
-- in_ready drops only when the record FIFO has no room, and, for a frame
-- narrower than the one before it, from its first row's last pixel until
-- the flush's last column, then two PRIME clocks (after a one-row frame, the
-- next frame waits instead).
--
-- The input is the detector's per-pixel stream: well formed (every line
-- cfg_width pixels ending with in_eol, the frame's last pixel with in_eof, the
-- next pixel the next frame's first); in_sof is only checked, in simulation.
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

  -- The schedule: this clock's steps, the current row, the reader.
  signal cstep      : std_logic;
  signal rstep      : std_logic;
  signal lock       : std_logic;
  signal flush_ends : std_logic;
  signal first_row  : std_logic;
  signal cm         : std_logic;
  signal cx         : unsigned(XB - 1 downto 0);
  signal cy         : unsigned(YB - 1 downto 0);
  signal cur_bank   : std_logic;
  signal pm         : std_logic;
  signal p0         : std_logic;
  signal r_last     : std_logic;
  signal r_col0     : std_logic;
  signal r_col1     : std_logic;
  signal r_col2     : std_logic;
  signal r_slot0    : std_logic;
  signal r_bank     : std_logic;
  signal ahead_slot : unsigned(SB - 1 downto 0);

  -- The tables' words at the reader's column.
  signal run_head  : std_logic;
  signal run_last  : std_logic;
  signal data_word : unsigned(DB - 1 downto 0);

  -- The column's operation.
  signal op        : std_logic_vector(OP_BITS - 1 downto 0);
  signal op_slot   : unsigned(SB - 1 downto 0);
  signal op_score  : unsigned(SCORE_BITS - 1 downto 0);
  signal op_cx     : unsigned(XB - 1 downto 0);
  signal op_cy     : unsigned(YB - 1 downto 0);
  signal op_ram_wa : unsigned(RB - 1 downto 0);
  signal op_ram_ra : unsigned(RB - 1 downto 0);

  -- The table writes, registered by the key data path.
  signal data_w_en       : std_logic;
  signal data_w_slot     : unsigned(SB - 1 downto 0);
  signal data_w_key      : unsigned(DB - 1 downto 0);
  signal data_w_s0       : std_logic;
  signal head_w_en       : std_logic;
  signal head_w_addr     : unsigned(SB downto 0);
  signal head_w_bit      : std_logic;
  signal head_w_s1       : std_logic;
  signal head_spare_en   : std_logic;
  signal head_spare_addr : unsigned(SB downto 0);
  signal head_spare_bit  : std_logic;
  signal head_spare_s1   : std_logic;
  signal last_w_en       : std_logic;
  signal last_w_addr     : unsigned(SB downto 0);
  signal last_w_bit      : std_logic;
  signal last_w_s0       : std_logic;
  signal last_w_s1       : std_logic;

  -- Records.
  signal rec_valid : std_logic;
  signal rec_eof   : std_logic;
  signal rec_x     : unsigned(XB - 1 downto 0);
  signal rec_y     : unsigned(YB - 1 downto 0);
  signal rec_score : unsigned(SCORE_BITS - 1 downto 0);
  signal rec_area  : unsigned(AREA_BITS - 1 downto 0);
  signal rec_room  : std_logic;
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
      clk        => clk,
      rst        => rst,
      px_valid   => px_valid,
      px_ready   => px_ready,
      px_corner  => px_corner,
      px_width   => px_width,
      px_sof     => px_sof,
      px_eol     => px_eol,
      px_eof     => px_eof,
      rec_room   => rec_room,
      cstep      => cstep,
      rstep      => rstep,
      lock       => lock,
      flush_ends => flush_ends,
      first_row  => first_row,
      cm         => cm,
      cx         => cx,
      cy         => cy,
      cur_bank   => cur_bank,
      pm         => pm,
      p0         => p0,
      r_last     => r_last,
      r_col0     => r_col0,
      r_col1     => r_col1,
      r_col2     => r_col2,
      r_slot0    => r_slot0,
      r_bank     => r_bank,
      ahead_slot => ahead_slot
    );

  tables : entity work.fastnms_nms_region_tables
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT,
      SCORE_BITS => SCORE_BITS
    )
    port map (
      clk             => clk,
      rst             => rst,
      rstep           => rstep,
      pm              => pm,
      p0              => p0,
      r_last          => r_last,
      r_col0          => r_col0,
      r_col1          => r_col1,
      r_col2          => r_col2,
      r_slot0         => r_slot0,
      r_bank          => r_bank,
      ahead_slot      => ahead_slot,
      op              => op,
      op_slot         => op_slot,
      data_w_en       => data_w_en,
      data_w_slot     => data_w_slot,
      data_w_key      => data_w_key,
      data_w_s0       => data_w_s0,
      head_w_en       => head_w_en,
      head_w_addr     => head_w_addr,
      head_w_bit      => head_w_bit,
      head_w_s1       => head_w_s1,
      head_spare_en   => head_spare_en,
      head_spare_addr => head_spare_addr,
      head_spare_bit  => head_spare_bit,
      head_spare_s1   => head_spare_s1,
      last_w_en       => last_w_en,
      last_w_addr     => last_w_addr,
      last_w_bit      => last_w_bit,
      last_w_s0       => last_w_s0,
      last_w_s1       => last_w_s1,
      run_head        => run_head,
      run_last        => run_last,
      data_word       => data_word
    );

  control : entity work.fastnms_nms_region_control
    generic map (
      MAX_WIDTH    => MAX_WIDTH,
      MAX_HEIGHT   => MAX_HEIGHT,
      SCORE_BITS   => SCORE_BITS,
      CONNECTIVITY => CONNECTIVITY
    )
    port map (
      clk        => clk,
      rst        => rst,
      rstep      => rstep,
      cstep      => cstep,
      lock       => lock,
      flush_ends => flush_ends,
      first_row  => first_row,
      c0         => px_corner,
      cm         => cm,
      c_eol      => px_eol,
      score      => px_score,
      cx         => cx,
      cy         => cy,
      cur_bank   => cur_bank,
      pm         => pm,
      p0         => p0,
      r_last     => r_last,
      r_col0     => r_col0,
      ahead_slot => ahead_slot,
      run_head   => run_head,
      run_last   => run_last,
      last_w_en  => last_w_en,
      last_w_s0  => last_w_s0,
      last_w_bit => last_w_bit,
      op         => op,
      op_slot    => op_slot,
      op_score   => op_score,
      op_cx      => op_cx,
      op_cy      => op_cy,
      op_ram_wa  => op_ram_wa,
      op_ram_ra  => op_ram_ra
    );

  keys : entity work.fastnms_nms_region_keys
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT,
      SCORE_BITS => SCORE_BITS
    )
    port map (
      clk             => clk,
      rst             => rst,
      op              => op,
      op_score        => op_score,
      op_cx           => op_cx,
      op_cy           => op_cy,
      op_ram_wa       => op_ram_wa,
      op_ram_ra       => op_ram_ra,
      r_col0          => r_col0,
      data_word       => data_word,
      data_w_en       => data_w_en,
      data_w_slot     => data_w_slot,
      data_w_key      => data_w_key,
      data_w_s0       => data_w_s0,
      head_w_en       => head_w_en,
      head_w_addr     => head_w_addr,
      head_w_bit      => head_w_bit,
      head_w_s1       => head_w_s1,
      head_spare_en   => head_spare_en,
      head_spare_addr => head_spare_addr,
      head_spare_bit  => head_spare_bit,
      head_spare_s1   => head_spare_s1,
      last_w_en       => last_w_en,
      last_w_addr     => last_w_addr,
      last_w_bit      => last_w_bit,
      last_w_s0       => last_w_s0,
      last_w_s1       => last_w_s1,
      rec_room        => rec_room,
      rec_valid       => rec_valid,
      rec_eof         => rec_eof,
      rec_x           => rec_x,
      rec_y           => rec_y,
      rec_score       => rec_score,
      rec_area        => rec_area
    );

  records : entity work.fastnms_fifo
    generic map (
      DEPTH => 8,
      WIDTH => OUT_BITS,
      STYLE => "distributed"
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => rec_valid,
      in_ready  => open,
      in_room2  => open,
      in_room3  => rec_room,
      in_spare  => open,
      in_data   => rec_eof & std_logic_vector(rec_x) & std_logic_vector(rec_y) &
                   std_logic_vector(rec_score) & std_logic_vector(rec_area),
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => q_data,
      busy      => open
    );

  out_eof   <= q_data(OUT_BITS - 1);
  out_x     <= unsigned(q_data(OUT_BITS - 2 downto YB + SCORE_BITS + AREA_BITS));
  out_y     <= unsigned(q_data(YB + SCORE_BITS + AREA_BITS - 1 downto SCORE_BITS + AREA_BITS));
  out_score <= unsigned(q_data(SCORE_BITS + AREA_BITS - 1 downto AREA_BITS));
  out_area  <= unsigned(q_data(AREA_BITS - 1 downto 0));

end architecture rtl;
