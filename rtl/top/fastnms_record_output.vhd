-- The core's keypoints as m_axis_corners records: pack, the CTRL.LIVE drop
-- policy and its accounting, the corner FIFO, the beats.
-- Datasheet: docs/fastnms_axi.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_regs_pkg.all;

entity fastnms_record_output is
  generic (
    X_BITS     : positive := 11;
    Y_BITS     : positive := 11;
    SCORE_BITS : positive := 8;
    FIFO_DEPTH : positive := 512;
    DESCRIPTOR : string   := "none";
    AREA       : boolean  := false
  );
  port (
    clk      : in    std_logic;
    rst      : in    std_logic;
    pipe_rst : in    std_logic; -- the core's reset: clears the ORB drop flag
    abort    : in    std_logic; -- a soft reset: the open frame closes as ABORTED
    live     : in    std_logic; -- CTRL.LIVE: drop records instead of holding the core
    -- the core's keypoints; in_eof alone (in_valid) is the end-of-frame beat
    in_valid      : in    std_logic;
    in_ready      : out   std_logic;
    in_x          : in    unsigned(X_BITS - 1 downto 0);
    in_y          : in    unsigned(Y_BITS - 1 downto 0);
    in_score      : in    unsigned(SCORE_BITS - 1 downto 0);
    in_area       : in    unsigned(REC_AREA_WIDTH - 1 downto 0);
    in_eof        : in    std_logic;
    in_angle      : in    std_logic_vector(31 downto 0);
    in_descriptor : in    std_logic_vector(255 downto 0);
    in_dropped    : in    std_logic; -- the core's ORB stage dropped a keypoint
    in_error      : in    std_logic; -- an internal error: ERROR on the next last record
    -- the records' beats (m_axis_corners; out_last on a frame's last beat)
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(63 downto 0);
    out_last  : out   std_logic;
    -- status
    open_frame  : out   std_logic; -- the packer holds a record of an open frame
    busy        : out   std_logic; -- records held: open_frame, or records in the FIFO
    overflow    : out   std_logic; -- (registered) the core was held, or a record dropped
    dropped     : out   std_logic; -- (registered) one pulse per dropped keypoint
    sent_record : out   std_logic; -- a keypoint's record left (its last beat)
    sent_last   : out   std_logic  -- a frame's last record left
  );
end entity fastnms_record_output;

architecture rtl of fastnms_record_output is

  constant ORB : boolean := DESCRIPTOR = "orb";

  -- The payload: ORB's angle (32 bits) and descriptor (256), or the area.
  function payload_width return natural is
  begin

    if ORB then
      return 288;
    elsif AREA then
      return REC_AREA_WIDTH;
    end if;

    return 0;

  end function payload_width;

  function record_beats return positive is
  begin

    if ORB then
      return REC_ORB_BEATS;
    end if;

    return 1;

  end function record_beats;

  constant PAYLOAD_BITS : natural  := payload_width;
  constant EXTRA_BITS   : positive := maximum(1, PAYLOAD_BITS);
  constant FIELD_BITS   : positive := X_BITS + Y_BITS + SCORE_BITS;
  -- A record from the packer: kind (2 bits, see fastnms_corner_pack), lost,
  -- x, y, score, extra; in the FIFO: error, overflow, kind, x, y, score,
  -- payload.
  constant PACKED_BITS : positive := 3 + FIELD_BITS + EXTRA_BITS;
  constant FIFO_BITS   : positive := 4 + FIELD_BITS + PAYLOAD_BITS;
  constant BEATS       : positive := record_beats;
  -- The FIFO's RAM words, all asked for; almost_full = '0' promises room for
  -- this record and one more whenever it comes (fastnms_fifo: R - 1 = 2).
  constant FIFO_RAM_WORDS : positive := fifo_words(FIFO_DEPTH);
  constant SPARE_LEVEL    : positive := maximum(1, FIFO_RAM_WORDS - 5);

  signal k_ready   : std_logic;
  signal k_extra   : std_logic_vector(EXTRA_BITS - 1 downto 0);
  signal orb_lost  : std_logic; -- the core's ORB stage dropped a keypoint of the frame it sends
  signal drop_owed : std_logic; -- a drop to count on the next clock
  signal p_open    : std_logic;

  signal p_valid : std_logic;
  signal p_ready : std_logic;
  signal p_data  : std_logic_vector(PACKED_BITS - 1 downto 0);
  signal p_last  : std_logic;                     -- a frame's last record (LAST, EMPTY or ABORTED)
  signal p_kind  : std_logic_vector(1 downto 0);
  signal p_lost  : std_logic;
  signal p_over  : std_logic;
  signal q_valid : std_logic;
  signal q_ready : std_logic;
  signal q_full  : std_logic;                     -- almost full: no spare word
  signal q_fits  : std_logic;
  signal q_data  : std_logic_vector(FIFO_BITS - 1 downto 0);
  signal drop    : std_logic;
  signal lost    : std_logic;                     -- records dropped since the last LAST record stored
  signal errored : std_logic;                     -- an internal error since the last LAST record stored
  signal p_error : std_logic;
  signal f_error : std_logic;
  signal f_valid : std_logic;
  signal f_ready : std_logic;
  signal f_data  : std_logic_vector(FIFO_BITS - 1 downto 0);
  signal f_over  : std_logic;
  signal f_busy  : std_logic;
  signal f_kind  : std_logic_vector(1 downto 0);
  signal f_x     : std_logic_vector(X_BITS - 1 downto 0);
  signal f_y     : std_logic_vector(Y_BITS - 1 downto 0);
  signal f_score : std_logic_vector(SCORE_BITS - 1 downto 0);
  signal f_empty : std_logic;
  signal f_last  : std_logic;
  signal f_word  : std_logic_vector(63 downto 0); -- beat 0
  signal f_beats : std_logic_vector(BEATS * 64 - 1 downto 0);

begin

  assert DESCRIPTOR = "none" or DESCRIPTOR = "orb"
    report "fastnms_record_output: DESCRIPTOR must be ""none"" or ""orb"""
    severity failure;
  -- (With fewer RAM words the FIFO never has a spare word, and live = '1'
  -- would drop every record but the frames' last ones.)
  assert FIFO_DEPTH >= 8
    report "fastnms_record_output: FIFO_DEPTH must be at least 8"
    severity failure;
  assert X_BITS <= REC_X_WIDTH and Y_BITS <= REC_Y_WIDTH and SCORE_BITS <= REC_SCORE_WIDTH
    report "fastnms_record_output: X_BITS, Y_BITS and SCORE_BITS must fit the record's fields"
    severity failure;
  assert not (ORB and AREA)
    report "fastnms_record_output: AREA (the region NMS) and DESCRIPTOR ""orb"" do not go together"
    severity failure;

  -- ---- packer ------------------------------------------------------------------

  -- A keypoint dropped by the core's ORB stage (K = 0) belongs to the frame
  -- the core is sending: it is flagged on that frame's last record.
  orb_frame : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' and k_ready = '1' and in_eof = '1' then
        orb_lost <= '0';
      elsif in_dropped = '1' then
        orb_lost <= '1';
      end if;

      if pipe_rst = '1' then
        orb_lost <= '0';
      end if;
    end if;

  end process orb_frame;

  with_payload : if ORB generate
    k_extra <= in_angle & in_descriptor;
  end generate with_payload;

  with_area : if AREA generate
    k_extra <= std_logic_vector(in_area);
  end generate with_area;

  without_payload : if PAYLOAD_BITS = 0 generate
    k_extra <= "0";
  end generate without_payload;

  pack : entity work.fastnms_corner_pack
    generic map (
      X_BITS     => X_BITS,
      Y_BITS     => Y_BITS,
      SCORE_BITS => SCORE_BITS,
      EXTRA_BITS => EXTRA_BITS
    )
    port map (
      clk        => clk,
      rst        => rst,
      abort      => abort,
      in_valid   => in_valid,
      in_ready   => k_ready,
      in_x       => in_x,
      in_y       => in_y,
      in_score   => in_score,
      in_extra   => k_extra,
      in_eof     => in_eof,
      in_lost    => orb_lost or in_dropped,
      out_valid  => p_valid,
      out_ready  => p_ready,
      out_data   => p_data,
      open_frame => p_open
    );

  in_ready   <= k_ready;
  open_frame <= p_open;

  -- ---- the drop policy -----------------------------------------------------------

  -- live = '0': every record waits for room. live = '1': the packer is never
  -- stalled; a record that does not fit is dropped. A frame's last record
  -- needs q_ready, any other record a spare word (room for it and for a last
  -- record whenever it comes), so the last record of a frame whose records
  -- were dropped still finds a word unless that frame's last record came
  -- after another frame's had taken the spare word; it carries OVERFLOW for
  -- every record dropped since the last LAST record stored, and for the
  -- keypoints the core's ORB stage dropped in its frame (p_lost).
  p_kind  <= p_data(PACKED_BITS - 1 downto PACKED_BITS - 2);
  p_lost  <= p_data(PACKED_BITS - 3);
  p_last  <= p_kind(1) or p_kind(0);
  q_fits  <= q_ready when p_last = '1' else
             not q_full;
  p_ready <= '1' when live = '1' else
             q_ready;
  q_valid <= p_valid and (q_fits or not live);
  drop    <= p_valid and live and not q_fits;
  p_over  <= p_last and (lost or drop or p_lost);
  p_error <= p_last and errored;

  fifo_in_payload : if PAYLOAD_BITS > 0 generate
    q_data <= p_error & p_over & p_kind & p_data(FIELD_BITS + EXTRA_BITS - 1 downto 0);
  end generate fifo_in_payload;

  fifo_in_fields : if PAYLOAD_BITS = 0 generate
    q_data <= p_error & p_over & p_kind & p_data(FIELD_BITS + EXTRA_BITS - 1 downto EXTRA_BITS);
  end generate fifo_in_fields;

  drops : process (clk) is
  begin

    if rising_edge(clk) then
      if q_valid = '1' and q_ready = '1' and p_last = '1' then
        lost    <= '0';
        errored <= '0';
      end if;
      if in_error = '1' then
        errored <= '1';
      end if;
      if drop = '1' then
        lost <= '1';
      end if;
      -- One count per clock: a second drop in the same clock (the core's
      -- ORB stage and the FIFO) is counted on the next. (Pack drops with ORB
      -- are a keypoint's sampling time apart, so one owed count is enough.)
      dropped   <= drop or in_dropped or drop_owed;
      drop_owed <= (drop and in_dropped) or (drop_owed and (drop or in_dropped));
      overflow  <= (in_valid and not k_ready and not abort) or drop;

      if rst = '1' then
        lost      <= '0';
        errored   <= '0';
        dropped   <= '0';
        drop_owed <= '0';
      end if;
    end if;

  end process drops;

  -- pragma translate_off
  -- One owed count is enough when in_dropped pulses are a keypoint's ORB
  -- time apart (as the core's ORB stage makes them): checked.
  owed_check : process (clk) is
  begin

    if rising_edge(clk) then
      if rst = '0' then
        assert not (drop_owed = '1' and drop = '1' and in_dropped = '1')
          report "fastnms_record_output: a drop count lost (in_dropped and a FIFO drop with one owed)"
          severity failure;
      end if;
    end if;

  end process owed_check;

  -- pragma translate_on

  -- ---- FIFO ----------------------------------------------------------------------

  fifo : entity work.fastnms_fifo
    generic map (
      DEPTH             => FIFO_RAM_WORDS,
      WIDTH             => FIFO_BITS,
      ALMOST_FULL_LEVEL => SPARE_LEVEL
    )
    port map (
      clk         => clk,
      rst         => rst,
      in_valid    => q_valid,
      in_ready    => q_ready,
      almost_full => q_full,
      in_data     => q_data,
      out_valid   => f_valid,
      out_ready   => f_ready,
      out_data    => f_data,
      busy        => f_busy
    );

  busy <= p_open or f_busy;

  -- ---- record format -------------------------------------------------------------

  f_error <= f_data(FIFO_BITS - 1);
  f_over  <= f_data(FIFO_BITS - 2);
  f_kind  <= f_data(FIFO_BITS - 3 downto FIFO_BITS - 4);
  f_empty <= f_kind(1) and f_kind(0);
  f_last  <= f_kind(1) or f_kind(0);

  f_x     <= f_data(PAYLOAD_BITS + FIELD_BITS - 1 downto PAYLOAD_BITS + Y_BITS + SCORE_BITS);
  f_y     <= f_data(PAYLOAD_BITS + Y_BITS + SCORE_BITS - 1 downto PAYLOAD_BITS + SCORE_BITS);
  f_score <= f_data(PAYLOAD_BITS + SCORE_BITS - 1 downto PAYLOAD_BITS);

  beat0 : process (all) is
  begin

    f_word                                                      <= (others => '0');
    f_word(REC_X_LSB + X_BITS - 1 downto REC_X_LSB)             <= f_x;
    f_word(REC_Y_LSB + Y_BITS - 1 downto REC_Y_LSB)             <= f_y;
    f_word(REC_SCORE_LSB + SCORE_BITS - 1 downto REC_SCORE_LSB) <= f_score;
    f_word(REC_EMPTY)                                           <= f_empty;
    f_word(REC_LAST)                                            <= f_last;
    f_word(REC_ABORTED)                                         <= f_kind(1) and not f_kind(0);
    f_word(REC_OVERFLOW)                                        <= f_over;
    f_word(REC_ERROR)                                           <= f_error;
    f_word(REC_ORB)                                             <= to_sl(ORB) and not f_empty;

    if AREA then
      f_word(REC_AREA_LSB + REC_AREA_WIDTH - 1 downto REC_AREA_LSB) <= f_data(REC_AREA_WIDTH - 1 downto 0);
    end if;

  end process beat0;

  -- Beat 1: the angle in bits 31:0; beats 2 .. 5: the descriptor, byte 0
  -- (pairs 0 .. 7) in bits 7:0 of beat 2.

  beats_payload : if ORB generate
    f_beats <= f_data(255 downto 0) & x"00000000" & f_data(287 downto 256) & f_word;
  end generate beats_payload;

  beats_word : if not ORB generate
    f_beats <= f_word;
  end generate beats_word;

  serializer : entity work.fastnms_record_beats
    generic map (
      BEATS => BEATS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => f_valid,
      in_ready  => f_ready,
      in_data   => f_beats,
      in_single => f_empty,
      in_last   => f_last,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => out_data,
      out_last  => out_last
    );

  sent_record <= f_valid and f_ready and not f_empty;
  sent_last   <= f_valid and f_ready and f_last;

end architecture rtl;
