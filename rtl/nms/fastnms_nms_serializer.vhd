-- Beats of PPC pixels in, records out: the survivors of a beat (keep flags,
-- scores, the beat's first column and its row), one record per clock in
-- lane order, then, on a frame's last beat, the end-of-frame record. It lets
-- an NMS that sees PPC pixels per clock keep the core's output interface of
-- one record per clock.
--
-- Input: beats; those without a survivor, an end of frame or a row end are
-- dropped. in_x is the column of pixel 0 of the beat, a multiple of PPC.
-- Output: out_x, out_y, out_score of a survivor with out_eof = '0'; the
-- end-of-frame record has out_eof = '1', out_x, out_y the frame's last pixel
-- (in_x + PPC - 1) and out_score 0. A beat's in_row_end (never with in_eof)
-- gives, after its survivors, a row-end beat: out_row_end = '1', out_eof =
-- '0', out_x, out_y the beat's last pixel, out_score 0.
--
-- Pipeline: a FIFO of DEPTH beats, an output stage that holds one beat and
-- hands out its lanes lowest first (a beat with n records takes n clocks,
-- and the next beat follows without a gap), a skid buffer. in_ready is the
-- FIFO's registered in_ready. While the output is ready, the FIFO fills only
-- when beats bring more than one record per clock; DEPTH sizes that burst
-- (fastnms_nms_3x3: at most two survivors per beat of four pixels, and two
-- rows never more than one record per beat on average).
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

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
  constant REC_BITS  : positive := 2 + X_BITS + Y_BITS + SCORE_BITS;

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
  signal rec_data  : std_logic_vector(REC_BITS - 1 downto 0);
  signal rec_out   : std_logic_vector(REC_BITS - 1 downto 0);

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
      in_room2  => open,
      in_room3  => open,
      in_spare  => open,
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
          rec_data <= "00" & std_logic_vector(cur_x(X_BITS - 1 downto LANE_BITS)) &
                      std_logic_vector(to_unsigned(item, LANE_BITS)) & std_logic_vector(cur_y) &
                      std_logic_vector(cur_scores((item + 1) * SCORE_BITS - 1 downto item * SCORE_BITS));
        else
          rec_data <= cur_eof & not cur_eof & std_logic_vector(cur_x(X_BITS - 1 downto LANE_BITS)) &
                      (LANE_BITS - 1 downto 0  => '1') & std_logic_vector(cur_y) &
                      (SCORE_BITS - 1 downto 0 => '0');
        end if;
        cur_items <= rest;
        cur_last  <= single(rest);
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

  output_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => REC_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => rec_valid,
      in_ready  => rec_ready,
      in_data   => rec_data,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => rec_out
    );

  out_eof     <= rec_out(REC_BITS - 1);
  out_row_end <= rec_out(REC_BITS - 2);
  out_x       <= unsigned(rec_out(REC_BITS - 3 downto Y_BITS + SCORE_BITS));
  out_y       <= unsigned(rec_out(Y_BITS + SCORE_BITS - 1 downto SCORE_BITS));
  out_score   <= unsigned(rec_out(SCORE_BITS - 1 downto 0));

end architecture rtl;
