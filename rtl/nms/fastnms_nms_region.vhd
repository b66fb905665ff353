-- Region NMS (the paper's streaming NMS): one record per 4- or 8-connected
-- region of corner pixels, its maximum score, a tie going to the region's
-- first pixel in raster order.
--
-- fastnms_nms_region_scan follows the raster at one pixel per clock with the
-- label line and turns it into events (a run starts, two regions touch, a run
-- ends, a run of the row above is left behind); an event queue carries them
-- to fastnms_nms_region_table, which keeps the regions, merges them and emits
-- a region's record when it closes. Records leave in the order regions close,
-- not in raster order; the end-of-frame beat (out_eof = '1', x = y = all ones,
-- score 0) follows the frame's last record, also for a frame without corners.
--
-- The input is the detector's per-pixel stream: well formed (every line
-- cfg_width pixels ending with in_eol, the frame's last pixel with in_eof,
-- the next pixel the next frame's first). The scan knows where a frame
-- starts from that; in_sof is only checked, in simulation (an assertion of
-- severity error when it disagrees).
-- When the table falls behind (dense corners, long merges) the queue fills
-- and in_ready drops: nothing is dropped.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_nms_region is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE_BITS   : positive := 8;
    CONNECTIVITY : positive := 8;
    -- Labels (and regions) in the tables, label 0 meaning none. At least
    -- MAX_WIDTH / 2 + 3 (the default): see the assertion below.
    LABELS      : positive := MAX_WIDTH / 2 + 3;
    EVENT_DEPTH : positive := 512
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
    out_eof   : out   std_logic
  );
end entity fastnms_nms_region;

architecture rtl of fastnms_nms_region is

  constant LABEL_BITS : positive := clog2(LABELS);
  constant RUN_BITS   : positive := bits_for(MAX_WIDTH / 2 + 1);
  constant X_BITS     : positive := clog2(MAX_WIDTH);
  constant Y_BITS     : positive := bits_for(MAX_HEIGHT);
  -- Event beat: flags, three labels, the run's best pixel.
  constant EV_BITS : positive := 6 + 3 * LABEL_BITS + SCORE_BITS + X_BITS + Y_BITS;

  subtype label_t is unsigned(LABEL_BITS - 1 downto 0);

  signal spare_valid : std_logic;
  signal spare_label : label_t;
  signal spare_take  : std_logic;

  -- Scan side of the event queue (s_*) and table side (t_*).
  signal s_valid       : std_logic;
  signal s_room        : std_logic;
  signal s_new         : std_logic;
  signal s_union       : std_logic;
  signal s_union_label : label_t;
  signal s_end         : std_logic;
  signal s_credit      : std_logic;
  signal s_pass        : std_logic;
  signal s_pass_label  : label_t;
  signal s_label       : label_t;
  signal s_score       : unsigned(SCORE_BITS - 1 downto 0);
  signal s_x           : unsigned(X_BITS - 1 downto 0);
  signal s_y           : unsigned(Y_BITS - 1 downto 0);
  signal s_eof         : std_logic;
  signal s_data        : std_logic_vector(EV_BITS - 1 downto 0);
  signal t_valid       : std_logic;
  signal t_ready       : std_logic;
  signal t_data        : std_logic_vector(EV_BITS - 1 downto 0);

begin

  -- LABELS: the scan takes a pixel only with a spare label ready. While
  -- it decides a pixel, up to MAX_WIDTH / 2 + 1 labels hold runs of the label
  -- line whose pass it has not yet sent (the row above from the pixel on,
  -- the row so far: a 4-connected checkerboard holds that many distinct
  -- labels at its second pixel of a row); with ids 1 .. LABELS - 1, one more
  -- must remain for the spare. Labels already passed come back through the
  -- table without the scan's help, so they only slow it down. With
  -- MAX_WIDTH / 2 + 2 labels that checkerboard stalls in_ready forever.
  assert LABELS >= MAX_WIDTH / 2 + 3
    report "fastnms_nms_region: LABELS must be at least MAX_WIDTH / 2 + 3"
    severity failure;
  assert CONNECTIVITY = 4 or CONNECTIVITY = 8
    report "fastnms_nms_region: CONNECTIVITY must be 4 or 8"
    severity failure;
  assert EVENT_DEPTH <= 2 ** 16
    report "fastnms_nms_region: EVENT_DEPTH must be at most 65536"
    severity failure;

  scan : entity work.fastnms_nms_region_scan
    generic map (
      MAX_WIDTH    => MAX_WIDTH,
      MAX_HEIGHT   => MAX_HEIGHT,
      SCORE_BITS   => SCORE_BITS,
      CONNECTIVITY => CONNECTIVITY,
      LABEL_BITS   => LABEL_BITS
    )
    port map (
      clk            => clk,
      rst            => rst,
      cfg_width      => cfg_width,
      in_valid       => in_valid,
      in_ready       => in_ready,
      in_corner      => in_corner,
      in_score       => in_score,
      in_sof         => in_sof,
      in_eol         => in_eol,
      in_eof         => in_eof,
      spare_valid    => spare_valid,
      spare_label    => spare_label,
      spare_take     => spare_take,
      ev_valid       => s_valid,
      ev_room        => s_room,
      ev_new         => s_new,
      ev_union       => s_union,
      ev_union_label => s_union_label,
      ev_end         => s_end,
      ev_credit      => s_credit,
      ev_pass        => s_pass,
      ev_pass_label  => s_pass_label,
      ev_label       => s_label,
      ev_score       => s_score,
      ev_x           => s_x,
      ev_y           => s_y,
      ev_eof         => s_eof
    );

  s_data <= s_new & s_union & s_end & s_credit & s_pass & s_eof &
            std_logic_vector(s_union_label) & std_logic_vector(s_pass_label) &
            std_logic_vector(s_label) & std_logic_vector(s_score) &
            std_logic_vector(s_x) & std_logic_vector(s_y);

  -- The queue's head leaves from flip-flops (fastnms_fifo's output skid
  -- buffer) rather than from its block RAM: the table decides its first step
  -- and its first read address from it. The scan pushes one clock after its
  -- decision, so it looks at in_room2 (room for this clock's beat and the
  -- next one), never at in_ready.
  event_queue : entity work.fastnms_fifo
    generic map (
      DEPTH => EVENT_DEPTH,
      WIDTH => EV_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => s_valid,
      in_ready  => open,
      in_room2  => s_room,
      in_data   => s_data,
      out_valid => t_valid,
      out_ready => t_ready,
      out_data  => t_data,
      busy      => open
    );

  unpack : block is

    -- Field positions in the event beat, from the top.
    constant F_UNION_LABEL : natural := EV_BITS - 7;
    constant F_PASS_LABEL  : natural := F_UNION_LABEL - LABEL_BITS;
    constant F_LABEL       : natural := F_PASS_LABEL - LABEL_BITS;
    constant F_SCORE       : natural := F_LABEL - LABEL_BITS;
    constant F_X           : natural := F_SCORE - SCORE_BITS;
    constant F_Y           : natural := F_X - X_BITS;

  begin

    regions : entity work.fastnms_nms_region_table
      generic map (
        LABELS     => LABELS,
        LABEL_BITS => LABEL_BITS,
        RUN_BITS   => RUN_BITS,
        SCORE_BITS => SCORE_BITS,
        X_BITS     => X_BITS,
        Y_BITS     => Y_BITS
      )
      port map (
        clk            => clk,
        rst            => rst,
        ev_valid       => t_valid,
        ev_ready       => t_ready,
        ev_new         => t_data(EV_BITS - 1),
        ev_union       => t_data(EV_BITS - 2),
        ev_end         => t_data(EV_BITS - 3),
        ev_credit      => t_data(EV_BITS - 4),
        ev_pass        => t_data(EV_BITS - 5),
        ev_eof         => t_data(EV_BITS - 6),
        ev_union_label => unsigned(t_data(F_UNION_LABEL downto F_UNION_LABEL - LABEL_BITS + 1)),
        ev_pass_label  => unsigned(t_data(F_PASS_LABEL downto F_PASS_LABEL - LABEL_BITS + 1)),
        ev_label       => unsigned(t_data(F_LABEL downto F_LABEL - LABEL_BITS + 1)),
        ev_score       => unsigned(t_data(F_SCORE downto F_SCORE - SCORE_BITS + 1)),
        ev_x           => unsigned(t_data(F_X downto F_X - X_BITS + 1)),
        ev_y           => unsigned(t_data(F_Y downto F_Y - Y_BITS + 1)),
        spare_valid    => spare_valid,
        spare_label    => spare_label,
        spare_take     => spare_take,
        out_valid      => out_valid,
        out_ready      => out_ready,
        out_x          => out_x,
        out_y          => out_y,
        out_score      => out_score,
        out_eof        => out_eof
      );

  end block unpack;

end architecture rtl;
