-- OpenCV's 3x3 non-maxima suppression on the detector's per-pixel score
-- stream: one record per survivor in raster order, then an end-of-frame
-- beat (with ROW_MARKS, row-end beats for the keypoint budget).
-- Datasheet: docs/fastnms_nms_3x3.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_corner_pkg.all;

entity fastnms_nms_3x3 is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE_BITS   : positive := 8;
    READ_LATENCY : positive := 1;
    PPC          : positive := 1;
    ROW_MARKS    : boolean  := false
  );
  port (
    clk         : in    std_logic;
    rst         : in    std_logic;
    cfg_width   : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    cfg_height  : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    in_valid    : in    std_logic;
    in_ready    : out   std_logic;
    in_score    : in    unsigned(PPC * SCORE_BITS - 1 downto 0);
    in_sof      : in    std_logic;
    in_eol      : in    std_logic;
    out_valid   : out   std_logic;
    out_ready   : in    std_logic;
    out_x       : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y       : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_score   : out   unsigned(SCORE_BITS - 1 downto 0);
    out_eof     : out   std_logic;
    out_row_end : out   std_logic;
    err_line    : out   std_logic;
    err_frame   : out   std_logic
  );
end entity fastnms_nms_3x3;

architecture rtl of fastnms_nms_3x3 is

  subtype score_t is unsigned(SCORE_BITS - 1 downto 0);

  subtype x_t is unsigned(out_x'range);

  subtype y_t is unsigned(out_y'range);

  -- The window generator's block: 3 rows of BLOCK_COLS scores; pixel i of a
  -- beat is at row 1, column i + 1.
  constant BLOCK_COLS : positive := 2 + PPC;

  subtype lanes_t is std_logic_vector(PPC - 1 downto 0);

  type above_t is array (0 to PPC - 1) of std_logic_vector(0 to 7);

  function block_slice (row : natural; col : natural) return natural is
  begin

    return row * BLOCK_COLS + col;

  end function block_slice;

  signal advance  : std_logic;
  signal w_valid  : std_logic;
  signal w_window : std_logic_vector(3 * BLOCK_COLS * SCORE_BITS - 1 downto 0);
  signal w_inside : lanes_t;
  signal w_eof    : std_logic;
  signal w_eol    : std_logic;
  signal w_x      : x_t;
  signal w_y      : y_t;

  -- Stage 1: each centre is above each of its neighbours.
  signal s1_valid  : std_logic;
  signal s1_inside : lanes_t;
  signal s1_eof    : std_logic;
  signal s1_mark   : std_logic; -- a row-end beat follows the beat's records
  signal s1_above  : above_t;
  signal s1_score  : unsigned(PPC * SCORE_BITS - 1 downto 0);
  signal s1_x      : x_t;
  signal s1_y      : y_t;

  -- Stage 2: survivors or end of frame.
  signal s2_valid : std_logic;
  signal s2_keep  : lanes_t;
  signal s2_eof   : std_logic;
  signal s2_mark  : std_logic;
  signal s2_score : unsigned(PPC * SCORE_BITS - 1 downto 0);
  signal s2_x     : x_t;
  signal s2_y     : y_t;

  signal s2_any : std_logic;

begin

  assert MAX_WIDTH >= 3 and MAX_WIDTH < 2 ** 16 and MAX_HEIGHT >= 3 and MAX_HEIGHT < 2 ** 16
    report "fastnms_nms_3x3: MAX_WIDTH and MAX_HEIGHT must be in 3 .. 65535"
    severity failure;
  assert READ_LATENCY <= 2
    report "fastnms_nms_3x3: READ_LATENCY must be 1 or 2"
    severity failure;

  window : entity work.fastnms_window
    generic map (
      MAX_WIDTH    => MAX_WIDTH,
      MAX_HEIGHT   => MAX_HEIGHT,
      WINDOW       => 3,
      DATA_WIDTH   => SCORE_BITS,
      READ_LATENCY => READ_LATENCY,
      PPC          => PPC
    )
    port map (
      clk        => clk,
      rst        => rst,
      cfg_width  => cfg_width,
      cfg_height => cfg_height,
      in_valid   => in_valid,
      in_ready   => in_ready,
      in_data    => std_logic_vector(in_score),
      in_sof     => in_sof,
      in_eol     => in_eol,
      out_valid  => w_valid,
      out_ready  => advance,
      out_window => w_window,
      out_inside => w_inside,
      out_sof    => open,
      out_eol    => w_eol,
      out_eof    => w_eof,
      out_x      => w_x,
      out_y      => w_y,
      err_line   => err_line,
      err_frame  => err_frame
    );

  stages : process (clk) is

    variable centre : score_t;
    variable other  : score_t;
    variable n      : natural;

  begin

    if rising_edge(clk) then
      if advance = '1' then
        for lane in 0 to PPC - 1 loop
          centre := unsigned(w_window(block_slice(1, lane + 1) * SCORE_BITS + SCORE_BITS - 1 downto
                                      block_slice(1, lane + 1) * SCORE_BITS));
          n      := 0;
          for row in 0 to 2 loop
            for col in lane to lane + 2 loop
              if row /= 1 or col /= lane + 1 then
                other             := unsigned(w_window(block_slice(row, col) * SCORE_BITS + SCORE_BITS - 1 downto
                                                       block_slice(row, col) * SCORE_BITS));
                s1_above(lane)(n) <= to_sl(centre > other);
                n                 := n + 1;
              end if;
            end loop;
          end loop;
          s1_score((lane + 1) * SCORE_BITS - 1 downto lane * SCORE_BITS) <= centre;
          s2_keep(lane)                                                  <= s1_inside(lane) and
                                                                            (and s1_above(lane));
        end loop;
        s1_valid  <= w_valid;
        s1_inside <= w_inside;
        s1_eof    <= w_eof;
        if ROW_MARKS then
          s1_mark <= to_sl(is_mark_line(w_y)) and w_eol and not w_eof;
        else
          s1_mark <= '0';
        end if;
        s1_x <= w_x;
        s1_y <= w_y;

        s2_valid <= s1_valid;
        s2_eof   <= s1_eof;
        s2_mark  <= s1_mark;
        s2_score <= s1_score;
        s2_x     <= s1_x;
        s2_y     <= s1_y;
      end if;

      if rst = '1' then
        s1_valid <= '0';
        s2_valid <= '0';
      end if;
    end if;

  end process stages;

  s2_any <= or s2_keep;

  -- One pixel per beat: survivors, row ends and the end of frame straight
  -- out through a skid buffer. A line's last pixel is never a survivor (its
  -- window is not inside the image), so a row end has a beat of its own.

  single_lane : if PPC = 1 generate

    subtype corner_rec_t is corner_t(x(x_t'range), y(y_t'range), score(score_t'range));

    constant CORNER_BITS : positive := corner_width(x_t'length, y_t'length, SCORE_BITS);

    signal record_in  : corner_rec_t;
    signal record_vec : std_logic_vector(CORNER_BITS - 1 downto 0);
    signal record_out : std_logic_vector(CORNER_BITS - 1 downto 0);
    signal out_rec    : corner_rec_t;

  begin

    record_in <= (eof => s2_eof, row_end => '0', x => s2_x, y => s2_y,
                   score => s2_score(score_t'range)) when s2_keep(0) = '1' else
                 (eof => s2_eof, row_end => s2_mark, x => s2_x, y => s2_y,
                   score => (score_t'range => '0'));

    -- (A signal: GHDL 2.0's synthesis fails on pack() in a port map.)
    record_vec <= pack(record_in);

    output_buffer : entity work.fastnms_skid_buffer
      generic map (
        WIDTH => CORNER_BITS
      )
      port map (
        clk       => clk,
        rst       => rst,
        in_valid  => s2_valid and (s2_any or s2_eof or s2_mark),
        in_ready  => advance,
        in_data   => record_vec,
        out_valid => out_valid,
        out_ready => out_ready,
        out_data  => record_out
      );

    out_rec     <= unpack(record_out, x_t'length, y_t'length, SCORE_BITS);
    out_eof     <= out_rec.eof;
    out_row_end <= out_rec.row_end;
    out_x       <= out_rec.x;
    out_y       <= out_rec.y;
    out_score   <= out_rec.score;

  end generate single_lane;

  -- Several pixels per beat: the serializer hands the survivors out one
  -- per clock.

  several_lanes : if PPC > 1 generate

    serializer : entity work.fastnms_nms_serializer
      generic map (
        PPC        => PPC,
        X_BITS     => x_t'length,
        Y_BITS     => y_t'length,
        SCORE_BITS => SCORE_BITS,
        DEPTH      => MAX_WIDTH / (2 * PPC) + 16
      )
      port map (
        clk         => clk,
        rst         => rst,
        in_valid    => s2_valid,
        in_ready    => advance,
        in_keep     => s2_keep,
        in_scores   => s2_score,
        in_x        => s2_x,
        in_y        => s2_y,
        in_eof      => s2_eof,
        in_row_end  => s2_mark,
        out_valid   => out_valid,
        out_ready   => out_ready,
        out_x       => out_x,
        out_y       => out_y,
        out_score   => out_score,
        out_eof     => out_eof,
        out_row_end => out_row_end
      );

  end generate several_lanes;

end architecture rtl;
