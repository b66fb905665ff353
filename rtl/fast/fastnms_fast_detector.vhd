-- FAST-9/16 corner detector: PPC 8-bit pixels per beat in, one result per
-- pixel out (corner flag and score, SCORE "opencv" or "sad"), bit-exact
-- with OpenCV's cv::FAST; with PIXELS also the pixels and ORB's blur.
-- Datasheet: docs/fastnms_fast_detector.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_fast_pkg.all;

entity fastnms_fast_detector is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE        : string   := "opencv";
    READ_LATENCY : positive := 1;
    PPC          : positive := 1;
    TAG_BITS     : positive := 1;
    PIXELS       : boolean  := false
  );
  port (
    clk           : in    std_logic;
    rst           : in    std_logic;
    cfg_width     : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    cfg_height    : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    cfg_threshold : in    unsigned(7 downto 0);
    cfg_tag       : in    std_logic_vector(TAG_BITS - 1 downto 0);
    in_valid      : in    std_logic;
    in_ready      : out   std_logic;
    in_data       : in    std_logic_vector(PPC * 8 - 1 downto 0);
    in_sof        : in    std_logic;
    in_eol        : in    std_logic;
    out_valid     : out   std_logic;
    out_ready     : in    std_logic;
    out_corner    : out   std_logic_vector(PPC - 1 downto 0);
    out_score     : out   unsigned(PPC * score_width(SCORE) - 1 downto 0);
    out_sof       : out   std_logic;
    out_eol       : out   std_logic;
    out_eof       : out   std_logic;
    out_pixel     : out   std_logic_vector(PPC * 8 - 1 downto 0);
    out_blurred   : out   std_logic_vector(PPC * 8 - 1 downto 0);
    out_width     : out   unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    out_height    : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_tag       : out   std_logic_vector(TAG_BITS - 1 downto 0);
    err_line      : out   std_logic;
    err_frame     : out   std_logic
  );
end entity fastnms_fast_detector;

architecture rtl of fastnms_fast_detector is

  constant CIRCLE_STAGES  : positive := 2;
  constant SEGMENT_STAGES : positive := 3;
  constant SCORE_STAGES   : positive := score_latency(SCORE);
  constant BLUR_STAGES    : positive := 13;
  -- Stages after the window generator: circle differences, then the score
  -- (then, with PIXELS, a wait for the blur).
  constant SCORED : positive := CIRCLE_STAGES + SCORE_STAGES;

  function stages_for (pixels : boolean) return positive is
  begin

    if pixels then
      return maximum(SCORED, BLUR_STAGES);
    end if;

    return SCORED;

  end function stages_for;

  function pixel_bits (pixels : boolean) return natural is
  begin

    if pixels then
      return 2 * PPC * 8;
    end if;

    return 0;

  end function pixel_bits;

  constant STAGES     : positive := stages_for(PIXELS);
  constant SCORE_BITS : positive := score_width(SCORE);
  -- The window generator's block: WINDOW_SIZE rows of BLOCK_COLS pixels.
  constant BLOCK_COLS : positive := WINDOW_SIZE - 1 + PPC;

  -- One flag per pixel of a beat.
  subtype lanes_t is std_logic_vector(PPC - 1 downto 0);

  type corners_t is array (CIRCLE_STAGES + SEGMENT_STAGES + 1 to STAGES) of lanes_t;

  -- The result without, then with, the pixels and their blur.
  constant RESULT_BITS : positive := PPC * (SCORE_BITS + 1) + 3;
  constant SKID_BITS   : positive := RESULT_BITS + pixel_bits(PIXELS);

  -- Markers of a beat in flight beside its data.
  type token_t is record
    valid  : std_logic;
    inside : lanes_t;
    sof    : std_logic;
    eol    : std_logic;
    eof    : std_logic;
  end record token_t;

  type tokens_t is array (1 to STAGES) of token_t;

  signal advance  : std_logic;
  signal ready    : std_logic;
  signal w_valid  : std_logic;
  signal w_window : std_logic_vector(WINDOW_SIZE * BLOCK_COLS * 8 - 1 downto 0);
  signal w_inside : lanes_t;
  signal w_sof    : std_logic;
  signal w_eol    : std_logic;
  signal w_eof    : std_logic;

  -- Threshold and size of the frame being received, and of the frame being
  -- scored.
  signal threshold_in  : byte_t;
  signal threshold_cur : byte_t;
  signal width_in      : unsigned(cfg_width'range);
  signal height_in     : unsigned(cfg_height'range);
  signal tag_in        : std_logic_vector(cfg_tag'range);

  signal corner  : lanes_t;
  signal corners : corners_t;
  signal tokens  : tokens_t;

  signal result_corner : lanes_t;
  signal result_score  : unsigned(PPC * SCORE_BITS - 1 downto 0);
  signal result        : std_logic_vector(SKID_BITS - 1 downto 0);
  signal skid_out      : std_logic_vector(SKID_BITS - 1 downto 0);
  -- With PIXELS: each lane's centre pixel and blur, level with the result.
  signal result_pixel   : std_logic_vector(PPC * 8 - 1 downto 0);
  signal result_blurred : std_logic_vector(PPC * 8 - 1 downto 0);

begin

  assert SCORE = OPENCV_SCORE or SCORE = SAD_SCORE
    report "fastnms_fast_detector: SCORE must be ""opencv"" or ""sad"""
    severity failure;

  assert MAX_WIDTH >= 7 and MAX_WIDTH < 2 ** 16 and MAX_HEIGHT >= 7 and MAX_HEIGHT < 2 ** 16
    report "fastnms_fast_detector: MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"
    severity failure;
  assert READ_LATENCY <= 2
    report "fastnms_fast_detector: READ_LATENCY must be 1 or 2"
    severity failure;

  window : entity work.fastnms_window
    generic map (
      MAX_WIDTH    => MAX_WIDTH,
      MAX_HEIGHT   => MAX_HEIGHT,
      WINDOW       => WINDOW_SIZE,
      DATA_WIDTH   => 8,
      READ_LATENCY => READ_LATENCY,
      PPC          => PPC
    )
    port map (
      clk        => clk,
      rst        => rst,
      cfg_width  => cfg_width,
      cfg_height => cfg_height,
      in_valid   => in_valid,
      in_ready   => ready,
      in_data    => in_data,
      in_sof     => in_sof,
      in_eol     => in_eol,
      out_valid  => w_valid,
      out_ready  => advance,
      out_window => w_window,
      out_inside => w_inside,
      out_sof    => w_sof,
      out_eol    => w_eol,
      out_eof    => w_eof,
      out_x      => open,
      out_y      => open,
      err_line   => err_line,
      err_frame  => err_frame
    );

  in_ready <= ready;

  -- A frame's threshold is taken with its first pixel and applies from its
  -- first result on (the previous frame's results have all left the
  -- comparisons by then). It is copied on every clock the first pixel is
  -- offered, the last copy on the clock it is taken: the same value as a copy
  -- at the handshake (an offered pixel and the configuration stay put until
  -- it is taken), without ready, which depends on the window's state, in the
  -- enable of these registers.
  thresholds : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' and in_sof = '1' then
        threshold_in <= cfg_threshold;
        width_in     <= cfg_width;
        height_in    <= cfg_height;
        tag_in       <= cfg_tag;
      end if;
      if advance = '1' and w_valid = '1' and w_sof = '1' then
        threshold_cur <= threshold_in;
        out_width     <= width_in;
        out_height    <= height_in;
        out_tag       <= tag_in;
      end if;
    end if;

  end process thresholds;

  -- One lane per pixel of a beat: its 7x7 window is columns lane ..
  -- lane + 6 of the block.

  lanes : for lane in 0 to PPC - 1 generate

    signal lane_window : std_logic_vector(WINDOW_SIZE * WINDOW_SIZE * 8 - 1 downto 0);
    signal above       : circle_flags_t;
    signal below       : circle_flags_t;
    signal diff        : circle_bytes_t;
    signal lane_score  : unsigned(SCORE_BITS - 1 downto 0);
    signal score_out   : unsigned(SCORE_BITS - 1 downto 0);

  begin

    rows : for row in 0 to WINDOW_SIZE - 1 generate
      lane_window((row + 1) * WINDOW_SIZE * 8 - 1 downto row * WINDOW_SIZE * 8) <= w_window((row * BLOCK_COLS + lane + WINDOW_SIZE) * 8 - 1 downto (row * BLOCK_COLS + lane) * 8);
    end generate rows;

    circle : entity work.fastnms_fast_circle
      port map (
        clk    => clk,
        en     => advance,
        window => lane_window,
        above  => above,
        below  => below,
        diff   => diff
      );

    segment : entity work.fastnms_fast_segment
      port map (
        clk       => clk,
        en        => advance,
        threshold => threshold_cur,
        above     => above,
        below     => below,
        diff      => diff,
        corner    => corner(lane)
      );

    opencv : if SCORE = OPENCV_SCORE generate

      score_block : entity work.fastnms_fast_score_opencv
        port map (
          clk   => clk,
          en    => advance,
          above => above,
          below => below,
          diff  => diff,
          score => lane_score
        );

    end generate opencv;

    sad : if SCORE = SAD_SCORE generate

      score_block : entity work.fastnms_fast_score_sad
        port map (
          clk       => clk,
          en        => advance,
          threshold => threshold_cur,
          above     => above,
          below     => below,
          diff      => diff,
          score     => lane_score
        );

    end generate sad;

    -- The score, level with the markers (later than SCORED with PIXELS).

    score_level : if STAGES = SCORED generate
      score_out <= lane_score;
    end generate score_level;

    score_wait : if STAGES > SCORED generate

      type scores_t is array (SCORED + 1 to STAGES) of unsigned(SCORE_BITS - 1 downto 0);

      signal waiting : scores_t;

    begin

      wait_stages : process (clk) is
      begin

        if rising_edge(clk) then
          if advance = '1' then
            waiting(SCORED + 1) <= lane_score;
            for stage in SCORED + 2 to STAGES loop
              waiting(stage) <= waiting(stage - 1);
            end loop;
          end if;
        end if;

      end process wait_stages;

      score_out <= waiting(STAGES);

    end generate score_wait;

    -- The mask: a pixel outside the border or not a corner scores 0.
    result_corner(lane)                                                <= corners(STAGES)(lane) and tokens(STAGES).inside(lane);
    result_score((lane + 1) * SCORE_BITS - 1 downto lane * SCORE_BITS) <=
                                                                          score_out when result_corner(lane) = '1' else
                                                                          (others => '0');

    blurs : if PIXELS generate

      type pixels_t is array (1 to STAGES) of std_logic_vector(7 downto 0);

      -- The centre's place in the window, row by row.
      constant CENTRE : natural := (WINDOW_SIZE / 2) * (WINDOW_SIZE + 1);

      signal centres : pixels_t;

    begin

      blur : entity work.fastnms_orb_blur
        port map (
          clk     => clk,
          en      => advance,
          window  => lane_window,
          blurred => result_blurred(8 * lane + 7 downto 8 * lane)
        );

      -- The centre pixel waits beside the blur (BLUR_STAGES = STAGES).
      centre_stages : process (clk) is
      begin

        if rising_edge(clk) then
          if advance = '1' then
            centres(1) <= lane_window(CENTRE * 8 + 7 downto CENTRE * 8);
            for stage in 2 to STAGES loop
              centres(stage) <= centres(stage - 1);
            end loop;
          end if;
        end if;

      end process centre_stages;

      result_pixel(8 * lane + 7 downto 8 * lane) <= centres(STAGES);

    end generate blurs;

  end generate lanes;

  -- Markers and the corner flag wait for the score.
  delays : process (clk) is
  begin

    if rising_edge(clk) then
      if advance = '1' then
        tokens(1) <= (valid => w_valid, inside => w_inside, sof => w_sof, eol => w_eol, eof => w_eof);
        for stage in 2 to STAGES loop
          tokens(stage) <= tokens(stage - 1);
        end loop;
        -- corner is level with tokens(CIRCLE_STAGES + SEGMENT_STAGES).
        corners(CIRCLE_STAGES + SEGMENT_STAGES + 1) <= corner;
        for stage in CIRCLE_STAGES + SEGMENT_STAGES + 2 to STAGES loop
          corners(stage) <= corners(stage - 1);
        end loop;
      end if;

      if rst = '1' then
        for stage in 1 to STAGES loop
          tokens(stage).valid <= '0';
        end loop;
      end if;
    end if;

  end process delays;

  result(RESULT_BITS - 1 downto 0) <= tokens(STAGES).eof & tokens(STAGES).sof & tokens(STAGES).eol &
                                      result_corner & std_logic_vector(result_score);

  with_pixels : if PIXELS generate
    result(SKID_BITS - 1 downto RESULT_BITS) <= result_blurred & result_pixel;
    out_pixel                                <= skid_out(RESULT_BITS + PPC * 8 - 1 downto RESULT_BITS);
    out_blurred                              <= skid_out(SKID_BITS - 1 downto RESULT_BITS + PPC * 8);
  end generate with_pixels;

  without_pixels : if not PIXELS generate
    out_pixel   <= (others => '0');
    out_blurred <= (others => '0');
  end generate without_pixels;

  output_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => SKID_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => tokens(STAGES).valid,
      in_ready  => advance,
      in_data   => result,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => skid_out
    );

  out_eof    <= skid_out(PPC * (SCORE_BITS + 1) + 2);
  out_sof    <= skid_out(PPC * (SCORE_BITS + 1) + 1);
  out_eol    <= skid_out(PPC * (SCORE_BITS + 1));
  out_corner <= skid_out(PPC * (SCORE_BITS + 1) - 1 downto PPC * SCORE_BITS);
  out_score  <= unsigned(skid_out(PPC * SCORE_BITS - 1 downto 0));

end architecture rtl;
