-- Beats of PPC pixels' survivors in, one record per clock out, then the
-- end-of-frame record: an NMS that sees PPC pixels per clock keeps the
-- core's output of one record per clock.
-- Datasheet: docs/fastnms_nms_serializer.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_corner_pkg.all;

entity fastnms_nms_serializer is
  generic (
    PPC        : positive := 4;
    X_BITS     : positive := 12;
    Y_BITS     : positive := 12;
    SCORE_BITS : positive := 8;
    DEPTH      : positive := 512
  );
  port (
    clk         : in    std_logic;
    rst         : in    std_logic;
    in_valid    : in    std_logic;
    in_ready    : out   std_logic;
    in_keep     : in    std_logic_vector(PPC - 1 downto 0);
    in_scores   : in    unsigned(PPC * SCORE_BITS - 1 downto 0);
    in_x        : in    unsigned(X_BITS - 1 downto 0);
    in_y        : in    unsigned(Y_BITS - 1 downto 0);
    in_eof      : in    std_logic;
    in_row_end  : in    std_logic;
    out_valid   : out   std_logic;
    out_ready   : in    std_logic;
    out_x       : out   unsigned(X_BITS - 1 downto 0);
    out_y       : out   unsigned(Y_BITS - 1 downto 0);
    out_score   : out   unsigned(SCORE_BITS - 1 downto 0);
    out_eof     : out   std_logic;
    out_row_end : out   std_logic
  );
end entity fastnms_nms_serializer;

architecture rtl of fastnms_nms_serializer is

  constant LANE_BITS : positive := clog2(PPC);
  constant BEAT_BITS : positive := 2 + Y_BITS + X_BITS + PPC + PPC * SCORE_BITS;
  constant REC_BITS  : positive := corner_width(X_BITS, Y_BITS, SCORE_BITS);

  subtype corner_rec_t is corner_t(x(X_BITS - 1 downto 0), y(Y_BITS - 1 downto 0), score(SCORE_BITS - 1 downto 0));

  -- A beat's records still to hand out: its survivors (bits 0 .. PPC - 1)
  -- and its end of frame or row end (bit PPC), lowest first.
  subtype items_t is std_logic_vector(PPC downto 0);

  -- The lowest set item of a non-zero set.
  function lowest (items : items_t) return natural is
  begin

    for item in 0 to PPC loop

      if items(item) = '1' then
        return item;
      end if;

    end loop;

    return 0;

  end function lowest;

  -- The set without its lowest item (gates, no carry chain).
  function without_lowest (items : items_t) return items_t is
    variable rest  : items_t   := items;
    variable found : std_logic := '0';
  begin

    for item in 0 to PPC loop

      rest(item) := items(item) and found;
      found      := found or items(item);

    end loop;

    return rest;

  end function without_lowest;

  -- Exactly one item set.
  function single (items : items_t) return std_logic is
    variable ones : natural := 0;
  begin

    for item in 0 to PPC loop

      if items(item) = '1' then
        ones := ones + 1;
      end if;

    end loop;

    return to_sl(ones = 1);

  end function single;

  signal q_valid : std_logic;
  signal q_ready : std_logic;
  signal q_data  : std_logic_vector(BEAT_BITS - 1 downto 0);

  -- The beat being handed out: its records left, and whether that is one.
  signal cur_valid  : std_logic;
  signal cur_items  : items_t;
  signal cur_last   : std_logic;
  signal cur_scores : unsigned(PPC * SCORE_BITS - 1 downto 0);
  signal cur_eof    : std_logic; -- bit PPC is the end of frame (else a row end)
  signal cur_x      : unsigned(X_BITS - 1 downto 0);
  signal cur_y      : unsigned(Y_BITS - 1 downto 0);
  signal q_items    : items_t;
  signal rest       : items_t;
  signal emit       : std_logic;
  signal done       : std_logic;

  signal rec_valid : std_logic;
  signal rec_ready : std_logic;
  signal rec_data  : corner_rec_t;
  signal rec_word  : std_logic_vector(REC_BITS - 1 downto 0);
  signal rec_out   : std_logic_vector(REC_BITS - 1 downto 0);
  signal out_rec   : corner_rec_t;

begin

  assert PPC = 2 or PPC = 4
    report "fastnms_nms_serializer: PPC must be 2 or 4"
    severity failure;
  assert DEPTH >= 4
    report "fastnms_nms_serializer: DEPTH must be at least 4"
    severity failure;

  beats : entity work.fastnms_fifo
    generic map (
      DEPTH => DEPTH,
      WIDTH => BEAT_BITS,
      STYLE => "auto"
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => in_valid and (or in_keep or in_eof or in_row_end),
      in_ready  => in_ready,
      in_data   => (in_eof or in_row_end) & in_eof & std_logic_vector(in_y) & std_logic_vector(in_x) & in_keep &
                   std_logic_vector(in_scores),
      out_valid => q_valid,
      out_ready => q_ready,
      out_data  => q_data,
      busy      => open
    );

  -- A record leaves the stage on every clock the skid buffer has room; the
  -- beat is done with its last record (a registered flag: the FIFO's read
  -- depends on registers through one gate).
  emit    <= cur_valid and rec_ready;
  done    <= emit and cur_last;
  q_ready <= not cur_valid or done;
  -- Bit PPC of a beat's items: its end of frame or row end, stored as one bit.
  q_items <= q_data(BEAT_BITS - 1) &
             q_data(PPC + PPC * SCORE_BITS - 1 downto PPC * SCORE_BITS);
  rest    <= without_lowest(cur_items);

  hand_out : process (clk) is

    variable item : natural range 0 to PPC;

  begin

    if rising_edge(clk) then
      if rec_ready = '1' then
        rec_valid <= '0';
      end if;

      if emit = '1' then
        rec_valid <= '1';
        item      := lowest(cur_items);
        if item < PPC then
          rec_data.eof     <= '0';
          rec_data.row_end <= '0';
          rec_data.x       <= cur_x(X_BITS - 1 downto LANE_BITS) & to_unsigned(item, LANE_BITS);
          rec_data.score   <= cur_scores((item + 1) * SCORE_BITS - 1 downto item * SCORE_BITS);
        else
          -- At the beat's last pixel.
          rec_data.eof     <= cur_eof;
          rec_data.row_end <= not cur_eof;
          rec_data.x       <= cur_x(X_BITS - 1 downto LANE_BITS) & to_unsigned(PPC - 1, LANE_BITS);
          rec_data.score   <= (others => '0');
        end if;
        rec_data.y <= cur_y;
        cur_items  <= rest;
        cur_last   <= single(rest);
        if cur_last = '1' then
          cur_valid <= '0';
        end if;
      end if;

      if q_valid = '1' and q_ready = '1' then
        cur_valid  <= '1';
        cur_items  <= q_items;
        cur_last   <= single(q_items);
        cur_eof    <= q_data(BEAT_BITS - 2);
        cur_y      <= unsigned(q_data(BEAT_BITS - 3 downto BEAT_BITS - 2 - Y_BITS));
        cur_x      <= unsigned(q_data(X_BITS + PPC + PPC * SCORE_BITS - 1 downto PPC + PPC * SCORE_BITS));
        cur_scores <= unsigned(q_data(PPC * SCORE_BITS - 1 downto 0));
      end if;

      if rst = '1' then
        cur_valid <= '0';
        rec_valid <= '0';
      end if;
    end if;

  end process hand_out;

  -- (A signal: GHDL 2.0's synthesis fails on pack() in a port map.)
  rec_word <= pack(rec_data);

  output_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => REC_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => rec_valid,
      in_ready  => rec_ready,
      in_data   => rec_word,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => rec_out
    );

  out_rec     <= unpack(rec_out, X_BITS, Y_BITS, SCORE_BITS);
  out_eof     <= out_rec.eof;
  out_row_end <= out_rec.row_end;
  out_x       <= out_rec.x;
  out_y       <= out_rec.y;
  out_score   <= out_rec.score;

end architecture rtl;
