-- The corner pipeline without bus interfaces: the FAST detector, then one
-- NMS (3x3, region4, region8 or none), optionally the keypoint budget and
-- ORB's angle and descriptor. Pixels in, corner records out.
-- Datasheet: docs/fastnms_core.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_fast_pkg.all;
  use work.fastnms_nms_region_pkg.area_bits;

entity fastnms_core is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE        : string   := "opencv";
    NMS          : string   := "3x3";
    READ_LATENCY : positive := 1;
    SCORE_TAP    : boolean  := false;
    PPC          : positive := 1;
    MAX_PER_CELL : natural  := 0;
    DESCRIPTOR   : string   := "none";
    ORB_MAX_CELL : positive := 16;
    -- Tests only: "none"; "rows", "tags", "count" (fastnms_orb_stage);
    -- "config": the configuration queue holds one frame's (internal_error
    -- fires when two frames are in flight).
    TEST_FAULT : string := "none"
  );
  port (
    clk            : in    std_logic;
    rst            : in    std_logic;
    cfg_width      : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    cfg_height     : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    cfg_threshold  : in    unsigned(7 downto 0);
    cfg_cell_log   : in    unsigned(2 downto 0);
    cfg_per_cell   : in    unsigned(3 downto 0);
    cfg_min_area   : in    unsigned(AREA_BITS - 1 downto 0);
    in_valid       : in    std_logic;
    in_ready       : out   std_logic;
    in_data        : in    std_logic_vector(PPC * 8 - 1 downto 0);
    in_sof         : in    std_logic;
    in_eol         : in    std_logic;
    out_valid      : out   std_logic;
    out_ready      : in    std_logic;
    out_x          : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y          : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_score      : out   unsigned(score_width(SCORE) - 1 downto 0);
    out_area       : out   unsigned(AREA_BITS - 1 downto 0);
    out_eof        : out   std_logic;
    out_angle      : out   std_logic_vector(31 downto 0);
    out_descriptor : out   std_logic_vector(255 downto 0);
    orb_dropped    : out   std_logic;
    tap_valid      : out   std_logic;
    tap_ready      : in    std_logic;
    tap_score      : out   unsigned(PPC * score_width(SCORE) - 1 downto 0);
    tap_sof        : out   std_logic;
    tap_eol        : out   std_logic;
    err_line       : out   std_logic;
    err_frame      : out   std_logic;
    -- Errors that would corrupt or misalign records, one-clock pulses
    -- (registered), bits INTERNAL_* of fastnms_pkg; a reset recovers.
    internal_error : out   std_logic_vector(INTERNAL_ERRORS - 1 downto 0)
  );
end entity fastnms_core;

architecture rtl of fastnms_core is

  constant SCORE_BITS : positive := score_width(SCORE);

  function connectivity_of (nms_name : string) return positive is
  begin

    if nms_name = "region4" then
      return 4;
    end if;

    return 8;

  end function connectivity_of;

  constant REGION_CONNECTIVITY : positive := connectivity_of(NMS);
  constant REGION              : boolean  := NMS = "region4" or NMS = "region8";
  constant ORB                 : boolean  := DESCRIPTOR = "orb";
  -- ORB's border: keypoints 31 pixels or more inside the frame.
  constant EDGE : positive := 31;

  -- log2(CELL) - 4 of the largest CELL ORB's rows are sized for.
  function cell_log_of (cell : positive) return natural is
  begin

    for k in 0 to 4 loop

      if 2 ** (k + 4) >= cell then
        return k;
      end if;

    end loop;

    return 4;

  end function cell_log_of;

  constant ORB_CELL_LOG : natural := cell_log_of(ORB_MAX_CELL);

  -- The ORB stage's own faults.
  function orb_fault return string is
  begin

    if TEST_FAULT = "config" then
      return "none";
    end if;

    return TEST_FAULT;

  end function orb_fault;

  signal d_valid   : std_logic;
  signal d_ready   : std_logic;
  signal d_score   : unsigned(PPC * SCORE_BITS - 1 downto 0);
  signal d_sof     : std_logic;
  signal d_eol     : std_logic;
  signal d_eof     : std_logic;
  signal d_corner  : std_logic_vector(PPC - 1 downto 0);
  signal d_width   : unsigned(cfg_width'range);
  signal d_height  : unsigned(cfg_height'range);
  signal d_pixel   : std_logic_vector(PPC * 8 - 1 downto 0); -- (ORB: PPC 1)
  signal d_blurred : std_logic_vector(PPC * 8 - 1 downto 0);
  -- The frame's configuration after the detector, through it with the
  -- frame: the region filter's MIN_AREA, the budget's CELL and K.
  signal cfg_tag : std_logic_vector(AREA_BITS + 6 downto 0);
  signal d_tag   : std_logic_vector(AREA_BITS + 6 downto 0);
  -- That configuration at the NMS's output, from the frame's first record
  -- to its end-of-frame beat (a queue, with the budget or the region NMS),
  -- with ORB's border in the frame (its first x and y past it; a synthesis
  -- tool removes them without ORB).
  signal q_valid : std_logic;
  signal q_tag   : std_logic_vector(d_tag'range);
  signal x_end   : unsigned(cfg_width'range);
  signal y_end   : unsigned(cfg_height'range);
  signal q_x_end : unsigned(cfg_width'range);
  signal q_y_end : unsigned(cfg_height'range);
  -- The NMS's output, before the budget.
  signal s_valid : std_logic;
  signal s_ready : std_logic;
  signal s_x     : unsigned(out_x'range);
  signal s_y     : unsigned(out_y'range);
  signal s_score : unsigned(out_score'range);
  signal s_area  : unsigned(out_area'range);
  signal s_eof   : std_logic;
  -- A row-end beat (with the budget only): every record of the lines up to s_y has come.
  signal s_row_end : std_logic;
  -- The fork between the NMS and the score tap.
  signal n_valid : std_logic;
  signal n_ready : std_logic;
  signal t_ready : std_logic;
  -- With ORB: its image stream (the third side of the fork), the NMS's
  -- records inside ORB's border, and the budget's output.
  signal i_valid   : std_logic;
  signal i_ready   : std_logic;
  signal keep      : std_logic;
  signal k_valid   : std_logic;
  signal k_ready   : std_logic;
  signal k_x       : unsigned(out_x'range);
  signal k_y       : unsigned(out_y'range);
  signal k_score   : unsigned(out_score'range);
  signal k_area    : unsigned(out_area'range);
  signal k_eof     : std_logic;
  signal cell_log  : unsigned(2 downto 0);
  signal below_min : std_logic; -- a region smaller than the frame's MIN_AREA

begin

  assert NMS = "3x3" or NMS = "none" or NMS = "region4" or NMS = "region8"
    report "fastnms_core: NMS must be ""3x3"", ""region4"", ""region8"" or ""none"""
    severity failure;

  assert SCORE = "opencv" or SCORE = "sad"
    report "fastnms_core: SCORE must be ""opencv"" or ""sad"""
    severity failure;
  assert MAX_WIDTH >= 7 and MAX_WIDTH < 2 ** 16 and MAX_HEIGHT >= 7 and MAX_HEIGHT < 2 ** 16
    report "fastnms_core: MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"
    severity failure;
  assert READ_LATENCY <= 2
    report "fastnms_core: READ_LATENCY must be 1 or 2"
    severity failure;
  assert PPC = 1 or PPC = 2 or PPC = 4
    report "fastnms_core: PPC must be 1, 2 or 4"
    severity failure;
  assert MAX_PER_CELL = 0 or NMS = "3x3" or NMS = "none"
    report "fastnms_core: the budget (MAX_PER_CELL > 0) takes records in raster order: " &
           "NMS ""3x3"" or ""none"" only"
    severity failure;
  assert MAX_PER_CELL <= 15
    report "fastnms_core: MAX_PER_CELL must be 0 .. 15"
    severity failure;
  assert PPC = 1 or NMS = "3x3" or NMS = "none"
    report "fastnms_core: NMS """ & NMS & """ takes one pixel per clock: PPC must be 1 (""3x3"" and ""none"" take 2 or 4)"
    severity failure;

  assert DESCRIPTOR = "none" or DESCRIPTOR = "orb"
    report "fastnms_core: DESCRIPTOR must be ""none"" or ""orb"""
    severity failure;
  assert not ORB or (PPC = 1 and MAX_PER_CELL > 0 and (NMS = "3x3" or NMS = "none"))
    report "fastnms_core: DESCRIPTOR ""orb"" takes PPC 1, NMS ""3x3"" or ""none"" and a budget (MAX_PER_CELL > 0)"
    severity failure;
  assert not ORB or ORB_MAX_CELL = 2 ** (ORB_CELL_LOG + 4)
    report "fastnms_core: ORB_MAX_CELL must be 16, 32, 64, 128 or 256"
    severity failure;
  assert TEST_FAULT = "none" or TEST_FAULT = "config" or
         (ORB and (TEST_FAULT = "rows" or TEST_FAULT = "tags" or TEST_FAULT = "count"))
    report "fastnms_core: TEST_FAULT must be ""none"" or ""config"" (with ORB also ""rows"", ""tags"" or ""count"")"
    severity failure;

  -- With ORB, CELL no larger than ORB_MAX_CELL.
  cell_log <= to_unsigned(ORB_CELL_LOG, 3) when ORB and cfg_cell_log > ORB_CELL_LOG else
              cfg_cell_log;
  cfg_tag  <= std_logic_vector(cfg_min_area) & std_logic_vector(cell_log) &
              std_logic_vector(cfg_per_cell);

  detector : entity work.fastnms_fast_detector
    generic map (
      MAX_WIDTH    => MAX_WIDTH,
      MAX_HEIGHT   => MAX_HEIGHT,
      SCORE        => SCORE,
      READ_LATENCY => READ_LATENCY,
      PPC          => PPC,
      TAG_BITS     => d_tag'length,
      PIXELS       => ORB
    )
    port map (
      clk           => clk,
      rst           => rst,
      cfg_width     => cfg_width,
      cfg_height    => cfg_height,
      cfg_threshold => cfg_threshold,
      cfg_tag       => cfg_tag,
      in_valid      => in_valid,
      in_ready      => in_ready,
      in_data       => in_data,
      in_sof        => in_sof,
      in_eol        => in_eol,
      out_valid     => d_valid,
      out_ready     => d_ready,
      out_corner    => d_corner,
      out_score     => d_score,
      out_sof       => d_sof,
      out_eol       => d_eol,
      out_eof       => d_eof,
      out_pixel     => d_pixel,
      out_blurred   => d_blurred,
      out_width     => d_width,
      out_height    => d_height,
      out_tag       => d_tag,
      err_line      => err_line,
      err_frame     => err_frame
    );

  -- The fork: a result goes when the NMS, the tap and ORB's image stream all
  -- take it (each side's valid waits for the others' readies).
  t_ready   <= tap_ready when SCORE_TAP else
               '1';
  d_ready   <= n_ready and t_ready and i_ready;
  n_valid   <= d_valid and t_ready and i_ready;
  i_valid   <= d_valid and n_ready and t_ready;
  tap_valid <= d_valid and n_ready and i_ready when SCORE_TAP else
               '0';
  -- Without SCORE_TAP the tap outputs are constant.
  tap_score <= d_score when SCORE_TAP else
               (others => '0');
  tap_sof   <= d_sof and to_sl(SCORE_TAP);
  tap_eol   <= d_eol and to_sl(SCORE_TAP);

  suppress_3x3 : if NMS = "3x3" generate

    nms_3x3 : entity work.fastnms_nms_3x3
      generic map (
        MAX_WIDTH    => MAX_WIDTH,
        MAX_HEIGHT   => MAX_HEIGHT,
        SCORE_BITS   => SCORE_BITS,
        READ_LATENCY => READ_LATENCY,
        PPC          => PPC,
        ROW_MARKS    => MAX_PER_CELL > 0
      )
      port map (
        clk         => clk,
        rst         => rst,
        cfg_width   => d_width,
        cfg_height  => d_height,
        in_valid    => n_valid,
        in_ready    => n_ready,
        in_score    => d_score,
        in_sof      => d_sof,
        in_eol      => d_eol,
        out_valid   => s_valid,
        out_ready   => s_ready,
        out_x       => s_x,
        out_y       => s_y,
        out_score   => s_score,
        out_eof     => s_eof,
        out_row_end => s_row_end,
        err_line    => open,
        err_frame   => open
      );

    s_area <= (others => '0');

  end generate suppress_3x3;

  suppress_region : if NMS = "region4" or NMS = "region8" generate

    nms_region : entity work.fastnms_nms_region
      generic map (
        MAX_WIDTH    => MAX_WIDTH,
        MAX_HEIGHT   => MAX_HEIGHT,
        SCORE_BITS   => SCORE_BITS,
        CONNECTIVITY => REGION_CONNECTIVITY
      )
      port map (
        clk       => clk,
        rst       => rst,
        cfg_width => d_width,
        in_valid  => n_valid,
        in_ready  => n_ready,
        in_corner => d_corner(0),
        in_score  => d_score(SCORE_BITS - 1 downto 0),
        in_sof    => d_sof,
        in_eol    => d_eol,
        in_eof    => d_eof,
        out_valid => s_valid,
        out_ready => s_ready,
        out_x     => s_x,
        out_y     => s_y,
        out_score => s_score,
        out_area  => s_area,
        out_eof   => s_eof
      );

    s_row_end <= '0';

  end generate suppress_region;

  suppress_none : if NMS = "none" generate

    nms_none : entity work.fastnms_nms_none
      generic map (
        MAX_WIDTH  => MAX_WIDTH,
        MAX_HEIGHT => MAX_HEIGHT,
        SCORE_BITS => SCORE_BITS,
        PPC        => PPC,
        ROW_MARKS  => MAX_PER_CELL > 0
      )
      port map (
        clk         => clk,
        rst         => rst,
        in_valid    => n_valid,
        in_ready    => n_ready,
        in_corner   => d_corner,
        in_score    => d_score,
        in_eol      => d_eol,
        in_eof      => d_eof,
        out_valid   => s_valid,
        out_ready   => s_ready,
        out_x       => s_x,
        out_y       => s_y,
        out_score   => s_score,
        out_eof     => s_eof,
        out_row_end => s_row_end
      );

    s_area <= (others => '0');

  end generate suppress_none;

  -- ---- the frame's configuration at the NMS's output ---------------------------

  no_config_queue : if MAX_PER_CELL = 0 and not REGION generate
    q_valid                               <= '1';
    q_tag                                 <= (others => '0');
    q_x_end                               <= (others => '0');
    q_y_end                               <= (others => '0');
    internal_error(INTERNAL_CONFIG_QUEUE) <= '0';
  end generate no_config_queue;

  with_config_queue : if MAX_PER_CELL > 0 or REGION generate
    -- Each frame's configuration: taken by the detector with the frame's
    -- first pixel (d_tag), queued at the frame's first score beat, consumed
    -- at the frame's end-of-frame record. Every frame the detector emits
    -- gives one end-of-frame record, so queue and frames stay in step.
    -- Frames between the detector's output and the NMS's output: two, a few
    -- more when frames without records pile up behind a stalled output; the
    -- queue has room for 6 at least (a refusal raises internal_error, and a
    -- simulation assertion stops).
    signal q_push  : std_logic;
    signal q_ready : std_logic;
    signal q_taken : std_logic;
    signal q_out   : std_logic_vector(x_end'length + y_end'length + d_tag'length - 1 downto 0);
  begin

    q_push <= d_valid and d_ready and d_sof;
    -- (TEST_FAULT "config": a queue of one configuration.)
    q_taken <= q_push and q_ready and not (to_sl(TEST_FAULT = "config") and q_valid);

    refused : process (clk) is
    begin

      if rising_edge(clk) then
        internal_error(INTERNAL_CONFIG_QUEUE) <= q_push and not q_taken and not rst;
      end if;

    end process refused;

    config_queue : entity work.fastnms_fifo
      generic map (
        DEPTH => 8,
        WIDTH => q_out'length,
        STYLE => "distributed"
      )
      port map (
        clk       => clk,
        rst       => rst,
        in_valid  => q_taken,
        in_ready  => q_ready,
        in_data   => std_logic_vector(x_end) & std_logic_vector(y_end) & d_tag,
        out_valid => q_valid,
        out_ready => s_valid and s_ready and s_eof,
        out_data  => q_out,
        busy      => open
      );

    q_tag   <= q_out(d_tag'range);
    q_y_end <= unsigned(q_out(y_end'length + d_tag'length - 1 downto d_tag'length));
    q_x_end <= unsigned(q_out(q_out'high downto y_end'length + d_tag'length));

    -- pragma translate_off
    queue_check : process (clk) is
    begin

      if rising_edge(clk) then
        assert not (rst = '0' and q_push = '1' and q_ready = '0' and TEST_FAULT = "none")
          report "fastnms_core: the configuration queue is full"
          severity failure;
      end if;

    end process queue_check;

  -- pragma translate_on

  end generate with_config_queue;

  -- ---- the region filter and the budget -----------------------------------------

  -- A frame's records wait for its configuration (never long: the NMS takes
  -- several clocks from a frame's first score beat to its first record).
  -- The region filter takes a record smaller than MIN_AREA and passes it on
  -- to nothing.
  below_min <= '1' when REGION and s_eof = '0' and
                        s_area < unsigned(q_tag(q_tag'high downto q_tag'high - AREA_BITS + 1)) else
               '0';

  no_budget : if MAX_PER_CELL = 0 generate
    k_valid <= s_valid and q_valid and not below_min;
    s_ready <= q_valid and (k_ready or below_min);
    k_x     <= s_x;
    k_y     <= s_y;
    k_score <= s_score;
    k_area  <= s_area;
    k_eof   <= s_eof;
  end generate no_budget;

  with_budget : if MAX_PER_CELL > 0 generate
    signal b_valid : std_logic;
    signal b_ready : std_logic;
  begin

    b_valid <= s_valid and q_valid and keep;
    s_ready <= q_valid and (b_ready or not keep);
    k_area  <= (others => '0'); -- (no region NMS with the budget)

    budget : entity work.fastnms_cell_budget
      generic map (
        MAX_WIDTH    => MAX_WIDTH,
        MAX_HEIGHT   => MAX_HEIGHT,
        SCORE_BITS   => SCORE_BITS,
        MAX_PER_CELL => MAX_PER_CELL
      )
      port map (
        clk         => clk,
        rst         => rst,
        in_valid    => b_valid,
        in_ready    => b_ready,
        in_x        => s_x,
        in_y        => s_y,
        in_score    => s_score,
        in_eof      => s_eof,
        in_row_end  => s_row_end,
        in_cell_log => unsigned(q_tag(6 downto 4)),
        in_per_cell => unsigned(q_tag(3 downto 0)),
        out_valid   => k_valid,
        out_ready   => k_ready,
        out_x       => k_x,
        out_y       => k_y,
        out_score   => k_score,
        out_eof     => k_eof
      );

  end generate with_budget;

  -- ---- ORB ----------------------------------------------------------------------

  no_orb : if not ORB generate
    i_ready        <= '1';
    keep           <= '1';
    x_end          <= (others => '0');
    y_end          <= (others => '0');
    out_valid      <= k_valid;
    k_ready        <= out_ready;
    out_x          <= k_x;
    out_y          <= k_y;
    out_score      <= k_score;
    out_area       <= k_area;
    out_eof        <= k_eof;
    out_angle      <= (others => '0');
    out_descriptor <= (others => '0');
    orb_dropped    <= '0';

    internal_error(INTERNAL_ORB_ROWS)  <= '0';
    internal_error(INTERNAL_ORB_TAGS)  <= '0';
    internal_error(INTERNAL_ORB_COUNT) <= '0';
  end generate no_orb;

  with_orb : if ORB generate
    -- The image's column, and the ORB stage's output.
    signal column  : unsigned(out_x'range);
    signal img_x   : unsigned(out_x'range);
    signal o_valid : std_logic;
    signal o_eof   : std_logic;
  begin

    img_x <= (others => '0') when d_sof = '1' else
             column;
    -- ORB's border, from the frame's own size at the NMS's output (the next
    -- frame may be in the detector meanwhile).
    keep <= s_eof or s_row_end or
            to_sl(s_x >= EDGE and s_y >= EDGE and s_x < q_x_end and s_y < q_y_end);

    frames : process (clk) is
    begin

      if rising_edge(clk) then
        if d_valid = '1' and d_ready = '1' then
          column <= img_x + 1;
          if d_eol = '1' then
            column <= (others => '0');
          end if;
        end if;
        -- The border of the detector's frame, queued with its first pixel
        -- (d_width and d_height hold 10 clocks before it). A frame no wider
        -- or taller than 2 EDGE has no keypoint inside.
        x_end <= to_unsigned(EDGE, x_end'length);
        if d_width > 2 * EDGE then
          x_end <= d_width - EDGE;
        end if;
        y_end <= to_unsigned(EDGE, y_end'length);
        if d_height > 2 * EDGE then
          y_end <= d_height - EDGE;
        end if;

        if rst = '1' then
          column <= (others => '0');
        end if;
      end if;

    end process frames;

    orb_keypoints : entity work.fastnms_orb_stage
      generic map (
        MAX_WIDTH    => MAX_WIDTH,
        MAX_HEIGHT   => MAX_HEIGHT,
        SCORE_BITS   => SCORE_BITS,
        LANES        => ORB_LANES,
        MAX_CELL     => 2 ** (ORB_CELL_LOG + 4),
        MAX_PER_CELL => maximum(MAX_PER_CELL, 1),
        TEST_FAULT   => orb_fault
      )
      port map (
        clk            => clk,
        rst            => rst,
        img_valid      => i_valid,
        img_ready      => i_ready,
        img_first      => d_sof,
        img_x          => img_x,
        img_pixel      => d_pixel(7 downto 0),
        img_blurred    => d_blurred(7 downto 0),
        cfg_cell_log   => unsigned(d_tag(6 downto 4)),
        cfg_drop       => to_sl(unsigned(d_tag(3 downto 0)) = 0),
        in_valid       => k_valid,
        in_ready       => k_ready,
        in_x           => k_x,
        in_y           => k_y,
        in_score       => k_score,
        in_eof         => k_eof,
        out_valid      => o_valid,
        out_ready      => out_ready,
        out_x          => out_x,
        out_y          => out_y,
        out_score      => out_score,
        out_eof        => o_eof,
        out_angle      => out_angle,
        out_descriptor => out_descriptor,
        dropped        => orb_dropped,
        err_rows       => internal_error(INTERNAL_ORB_ROWS),
        err_tags       => internal_error(INTERNAL_ORB_TAGS),
        err_count      => internal_error(INTERNAL_ORB_COUNT)
      );

    out_valid <= o_valid;
    out_eof   <= o_eof;
    out_area  <= (others => '0');

  end generate with_orb;

end architecture rtl;
