-- No suppression: one record per corner of the detector's stream, in raster
-- order, then an end-of-frame beat (with ROW_MARKS, row-end beats).
-- Datasheet: docs/fastnms_nms_none.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_corner_pkg.all;

entity fastnms_nms_none is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 4095;
    SCORE_BITS : positive := 8;
    PPC        : positive := 1;
    ROW_MARKS  : boolean  := false
  );
  port (
    clk         : in    std_logic;
    rst         : in    std_logic;
    in_valid    : in    std_logic;
    in_ready    : out   std_logic;
    in_corner   : in    std_logic_vector(PPC - 1 downto 0);
    in_score    : in    unsigned(PPC * SCORE_BITS - 1 downto 0);
    in_eol      : in    std_logic;
    in_eof      : in    std_logic;
    out_valid   : out   std_logic;
    out_ready   : in    std_logic;
    out_x       : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y       : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_score   : out   unsigned(SCORE_BITS - 1 downto 0);
    out_eof     : out   std_logic;
    out_row_end : out   std_logic
  );
end entity fastnms_nms_none;

architecture rtl of fastnms_nms_none is

  signal advance : std_logic;
  signal accept  : std_logic;

  -- Position of the next beat (x in beats): both counters clear through the
  -- flip-flops' reset, so the frame's first beat finds them at (0, 0).
  signal x       : unsigned(out_x'range);
  signal x_pixel : unsigned(out_x'range); -- the column of the beat's pixel 0
  signal y       : unsigned(out_y'range);
  signal x_clear : std_logic;
  signal y_clear : std_logic;
  signal y_step  : std_logic;
  signal mark    : std_logic;             -- a row-end beat follows the beat's records

begin

  assert MAX_WIDTH >= 2 and MAX_WIDTH < 2 ** 16 and MAX_HEIGHT < 2 ** 16
    report "fastnms_nms_none: MAX_WIDTH must be in 2 .. 65535 and MAX_HEIGHT below 65536"
    severity failure;
  assert (PPC = 1 or PPC = 2 or PPC = 4) and MAX_WIDTH mod PPC = 0
    report "fastnms_nms_none: PPC must be 1, 2 or 4, and MAX_WIDTH a multiple of it"
    severity failure;

  accept   <= in_valid and advance;
  in_ready <= advance;

  x_clear <= rst or (accept and in_eol);
  y_clear <= rst or (accept and in_eof);
  y_step  <= accept and in_eol;

  position : entity work.fastnms_position
    generic map (
      X_BITS => out_x'length,
      Y_BITS => out_y'length
    )
    port map (
      clk     => clk,
      x_clear => x_clear,
      x_start => '0',
      x_step  => accept,
      y_clear => y_clear,
      y_start => '0',
      y_step  => y_step,
      x       => x,
      y       => y
    );

  x_pixel <= shift_left(x, PPC / 2);
  mark    <= to_sl(ROW_MARKS and is_mark_line(y)) and in_eol and not in_eof;

  -- One pixel per beat: the corner and the end of frame straight out.

  single_lane : if PPC = 1 generate

    subtype corner_rec_t is corner_t(x(out_x'range), y(out_y'range), score(SCORE_BITS - 1 downto 0));

    constant CORNER_BITS : positive := corner_width(out_x'length, out_y'length, SCORE_BITS);

    signal s1_valid : std_logic;
    signal s1       : corner_rec_t;
    signal s1_data  : std_logic_vector(CORNER_BITS - 1 downto 0);
    signal s1_out   : std_logic_vector(CORNER_BITS - 1 downto 0);
    signal out_rec  : corner_rec_t;

  begin

    records : process (clk) is
    begin

      if rising_edge(clk) then
        if advance = '1' then
          s1_valid   <= in_valid and (in_corner(0) or in_eof or mark);
          s1.eof     <= in_eof;
          s1.row_end <= mark and not in_corner(0);
          s1.x       <= x;
          s1.y       <= y;
          s1.score   <= in_score(SCORE_BITS - 1 downto 0);
        end if;
        if rst = '1' then
          s1_valid <= '0';
        end if;
      end if;

    end process records;

    -- (A signal: GHDL 2.0's synthesis fails on pack() in a port map.)
    s1_data <= pack(s1);

    output_buffer : entity work.fastnms_skid_buffer
      generic map (
        WIDTH => CORNER_BITS
      )
      port map (
        clk       => clk,
        rst       => rst,
        in_valid  => s1_valid,
        in_ready  => advance,
        in_data   => s1_data,
        out_valid => out_valid,
        out_ready => out_ready,
        out_data  => s1_out
      );

    out_rec     <= unpack(s1_out, out_x'length, out_y'length, SCORE_BITS);
    out_eof     <= out_rec.eof;
    out_row_end <= out_rec.row_end;
    out_x       <= out_rec.x;
    out_y       <= out_rec.y;
    out_score   <= out_rec.score;

  end generate single_lane;

  -- Several pixels per beat: the beat, registered, to the serializer.

  several_lanes : if PPC > 1 generate

    signal s1_valid  : std_logic;
    signal s1_corner : std_logic_vector(PPC - 1 downto 0);
    signal s1_scores : unsigned(PPC * SCORE_BITS - 1 downto 0);
    signal s1_x      : unsigned(out_x'range);
    signal s1_y      : unsigned(out_y'range);
    signal s1_eof    : std_logic;
    signal s1_mark   : std_logic;

  begin

    beats : process (clk) is
    begin

      if rising_edge(clk) then
        if advance = '1' then
          s1_valid  <= in_valid;
          s1_corner <= in_corner;
          s1_scores <= in_score;
          s1_x      <= x_pixel;
          s1_y      <= y;
          s1_eof    <= in_eof;
          s1_mark   <= mark;
        end if;
        if rst = '1' then
          s1_valid <= '0';
        end if;
      end if;

    end process beats;

    serializer : entity work.fastnms_nms_serializer
      generic map (
        PPC        => PPC,
        X_BITS     => out_x'length,
        Y_BITS     => out_y'length,
        SCORE_BITS => SCORE_BITS,
        DEPTH      => MAX_WIDTH / PPC
      )
      port map (
        clk         => clk,
        rst         => rst,
        in_valid    => s1_valid,
        in_ready    => advance,
        in_keep     => s1_corner,
        in_scores   => s1_scores,
        in_x        => s1_x,
        in_y        => s1_y,
        in_eof      => s1_eof,
        in_row_end  => s1_mark,
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
