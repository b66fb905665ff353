-- Window generator: a raster stream of PPC pixels per beat in, one beat of
-- WINDOW x WINDOW neighbourhoods per input beat out, with frame checking and
-- recovery from malformed input.
-- Datasheet: docs/fastnms_window.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_window is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    WINDOW       : positive := 7;
    DATA_WIDTH   : positive := 8;
    READ_LATENCY : positive := 1;
    PPC          : positive := 1
  );
  port (
    clk        : in    std_logic;
    rst        : in    std_logic;
    cfg_width  : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    cfg_height : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    in_valid   : in    std_logic;
    in_ready   : out   std_logic;
    in_data    : in    std_logic_vector(PPC * DATA_WIDTH - 1 downto 0);
    in_sof     : in    std_logic;
    in_eol     : in    std_logic;
    out_valid  : out   std_logic;
    out_ready  : in    std_logic;
    out_window : out   std_logic_vector(WINDOW * (WINDOW - 1 + PPC) * DATA_WIDTH - 1 downto 0);
    out_inside : out   std_logic_vector(PPC - 1 downto 0);
    out_sof    : out   std_logic;
    out_eol    : out   std_logic;
    out_eof    : out   std_logic;
    out_x      : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y      : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    err_line   : out   std_logic;
    err_frame  : out   std_logic
  );
end entity fastnms_window;

architecture rtl of fastnms_window is

  constant R : natural := WINDOW / 2;
  -- Beats: PPC pixels each, B = W / PPC of them per row. The output runs LB
  -- beats behind the input; the window register holds 2 LB + 1 beat columns,
  -- of which the output block uses WINDOW - 1 + PPC pixel columns.
  constant LB        : positive := (R + PPC - 1) / PPC;
  constant MAX_BEATS : positive := MAX_WIDTH / PPC;
  constant PB        : natural  := PPC / 2; -- log2(PPC) for 1, 2, 4
  constant REG_COLS  : positive := (2 * LB + 1) * PPC;
  constant OUT_COLS  : positive := WINDOW - 1 + PPC;
  -- Register column of the output block's column 0.
  constant COL0 : natural := PPC * LB - R;
  -- The narrowest frame: WINDOW pixels, whole beats, and more beats than the
  -- line buffer's read latency (it reads a column back one row after writing
  -- it, which must be later than the write) and than LB.
  constant MIN_WIDTH : positive := ((maximum(WINDOW, (READ_LATENCY + 1) * PPC) + PPC - 1) / PPC) * PPC;
  -- Token pipeline: the line buffer's read latency, then the window register.
  constant TOKEN_LAST : positive := READ_LATENCY + 1;

  -- Beat columns.
  subtype x_t is unsigned(clog2(MAX_BEATS) - 1 downto 0);

  subtype y_t is unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);

  subtype pixel_t is std_logic_vector(DATA_WIDTH - 1 downto 0);

  subtype beat_t is std_logic_vector(PPC * DATA_WIDTH - 1 downto 0);

  type window_t is array (0 to WINDOW - 1, 0 to REG_COLS - 1) of pixel_t;

  type x_per_lane_t is array (0 to PPC - 1) of x_t;

  -- First beat whose pixel `lane` is at least R columns from the left edge.
  function first_inside_beat (lane : natural) return natural is
  begin

    if lane >= R then
      return 0;
    end if;

    return (R - lane + PPC - 1) / PPC;

  end function first_inside_beat;

  type out_state_t is (idle, lockstep, flush);

  -- One output beat in flight beside the window.
  type token_t is record
    valid  : std_logic;
    border : std_logic; -- a beat of the flush, with no beat of its own behind it
    inside : std_logic_vector(PPC - 1 downto 0);
    sof    : std_logic;
    eol    : std_logic;
    eof    : std_logic;
    x      : x_t;
    y      : y_t;
  end record token_t;

  type token_pipe_t is array (1 to TOKEN_LAST) of token_t;

  -- Frame geometry, as the values the position counters compare against.
  type limits_t is record
    w_last_m1 : x_t;                                -- B - 2: the beat before the last
    w_two     : std_logic;                          -- B = 2: a row's first beat is its last but one
    hi_zero   : std_logic_vector(PPC - 1 downto 0); -- x_hi = 0, per pixel of a beat
    h_last_m1 : y_t;                                -- H - 2: the row before the last
    x_hi      : x_per_lane_t;                       -- per pixel of a beat, the last beat it is inside
    y_hi      : y_t;                                -- H - 1 - R: the last inside row
  end record limits_t;

  -- Configuration: the range checks (each separately, to keep the logic
  -- shallow) one clock after the ports, the limits two (from a copy).
  signal cfg_w      : unsigned(cfg_width'range);
  signal cfg_h      : unsigned(cfg_height'range);
  signal cfg_ok     : std_logic_vector(4 downto 0);
  signal cfg_limits : limits_t;

  -- Input buffer (beats waiting for the input side); the configuration is
  -- sampled with a start of frame.
  signal in_flags : std_logic_vector(2 downto 0);
  signal in_taken : std_logic; -- the buffer's registered ready
  signal a_flags  : std_logic_vector(2 downto 0);
  signal a_ready  : std_logic;
  signal a_valid  : std_logic;
  signal a_data   : beat_t;
  signal a_sof    : std_logic;
  signal a_eol    : std_logic;
  signal a_start  : std_logic; -- a start of frame with a valid size
  signal a_limits : limits_t;

  -- Input side: position of the next pixel of the frame being received.
  signal in_active : std_logic;
  signal in_x      : x_t;
  signal in_y      : y_t;
  signal in_x_last : std_logic; -- in_x is the row's last beat, B - 1
  signal in_y_last : std_logic; -- in_y = H - 1
  signal in_last   : std_logic; -- in_x_last and in_y_last: the frame's last beat
  signal at_start  : std_logic; -- (in_x, in_y) = (LB, R): the first window's beat
  -- at_start and out_busy: the first window's beat waits for the previous
  -- frame's border beats. Kept as a register of its own (its next value
  -- predicted from the same updates) so that the decisions below take few
  -- inputs.
  signal blocked : std_logic;
  -- min(in_x, LB) and min(in_y, R + 1): small counters that find (LB, R)
  -- without comparing the wide ones.
  signal near_x    : unsigned(bits_for(LB + 1) - 1 downto 0);
  signal near_y    : unsigned(bits_for(R + 1) - 1 downto 0);
  signal pre_start : std_logic; -- (near_x, near_y) = (LB - 1, R): the next beat is at_start
  signal in_limits : limits_t;

  -- synthesis translate_off
  signal checks_on : boolean; -- false until the first reset: the invariants hold from then on
  -- synthesis translate_on

  -- Output side: position (beat_x, beat_y) of the next beat of the frame
  -- being emitted.
  signal out_state  : out_state_t;
  signal out_busy   : std_logic;                          -- out_state /= idle
  signal beat_x     : x_t;
  signal beat_y     : y_t;
  signal out_x_last : std_logic;
  signal out_y_last : std_logic;
  signal y_at_last  : std_logic;                          -- beat_y = H - 2, a clock late
  signal out_last   : std_logic;                          -- out_x_last and out_y_last (only in the flush)
  signal out_x_in   : std_logic_vector(PPC - 1 downto 0); -- per pixel: R <= x <= W - 1 - R
  signal out_y_in   : std_logic;                          -- R <= beat_y <= H - 1 - R
  signal out_cut    : std_logic;                          -- the flush of a cut frame
  signal out_limits : limits_t;

  signal advance : std_logic;
  signal restart : std_logic;
  signal hold    : std_logic;
  signal take    : std_logic;
  signal counted : std_logic;
  signal emit    : std_logic;
  -- Counter controls: a clear beats a step, so that both map onto the
  -- flip-flops' reset and enable pins and the next value is the carry chain.
  -- The four counters are written here rather than as fastnms_position
  -- instances: the same logic behind an entity boundary let yosys's abc map
  -- the shared controls one level deeper (5 levels in the detector at
  -- MAX_WIDTH 1920; measured with flows/synth/synth.py), where this maps in 4.
  signal in_x_clear  : std_logic;
  signal in_x_step   : std_logic;
  signal in_y_clear  : std_logic;
  signal in_y_step   : std_logic;
  signal out_x_clear : std_logic;
  signal out_x_step  : std_logic;
  signal out_y_clear : std_logic;
  signal out_y_step  : std_logic;
  signal col_valid   : std_logic;
  signal shift       : std_logic;
  signal column      : std_logic_vector((WINDOW * PPC * DATA_WIDTH) - 1 downto 0);
  signal win_regs    : window_t;
  signal tokens      : token_pipe_t;

begin

  assert WINDOW mod 2 = 1 and WINDOW >= 3
    report "fastnms_window: WINDOW must be odd and at least 3"
    severity failure;
  assert MAX_WIDTH >= WINDOW and MAX_HEIGHT >= WINDOW
    report "fastnms_window: MAX_WIDTH and MAX_HEIGHT must be at least WINDOW"
    severity failure;

  assert READ_LATENCY <= 2
    report "fastnms_window: READ_LATENCY must be 1 or 2"
    severity failure;
  assert MAX_WIDTH < 2 ** 16 and MAX_HEIGHT < 2 ** 16
    report "fastnms_window: MAX_WIDTH and MAX_HEIGHT must be below 65536"
    severity failure;
  assert PPC = 1 or PPC = 2 or PPC = 4
    report "fastnms_window: PPC must be 1, 2 or 4"
    severity failure;
  assert MAX_WIDTH mod PPC = 0 and MAX_WIDTH >= MIN_WIDTH
    report "fastnms_window: MAX_WIDTH must be a multiple of PPC and at least WINDOW, " &
           "raised to whole beats and to READ_LATENCY + 1 beats"
    severity failure;

  -- The pipeline moves whenever the consumer is ready: out_ready is the
  -- advance enable (no bubble is squeezed out while it is low).
  advance <= out_ready;

  -- The decisions, each from a few registers. The states of the two sides
  -- imply one another (checked in simulation, in input_side), which keeps their inputs
  -- few: at_start implies in_active; in lockstep the input is inside the frame
  -- past its first window's beat (in_active = '1', blocked = '0'); when idle
  -- the output is not busy (blocked = '0').
  --
  -- A start of frame inside a frame first resets the input side (one clock).
  restart <= a_valid and a_sof and in_active;
  -- The pixel that starts a frame's output waits until the previous frame's
  -- last border beats have left.
  hold <= a_valid and ((a_sof and in_active) or (not a_sof and blocked));
  take <= a_valid and not hold;
  -- A taken pixel that belongs to a frame (in_active, or a start of frame
  -- with a valid size) and so moves the input position.
  counted <= a_valid and ((a_start and not in_active) or (not a_sof and in_active and not blocked));
  -- An output beat: every clock while flushing, with each pixel in lockstep
  -- (take, which is a_valid and not a_sof there), and with the first window's
  -- pixel when idle (take and at_start, the same there).
  emit <= '1' when out_state = flush else
          a_valid and not a_sof when out_state = lockstep else
          a_valid and not a_sof and at_start;

  -- Counter controls (a clear beats a step: the flip-flops' reset and enable).
  in_x_clear  <= rst or (advance and (restart or (counted and in_x_last)));
  in_x_step   <= advance and counted;
  in_y_clear  <= rst or (advance and (restart or (counted and in_last)));
  in_y_step   <= advance and counted and in_x_last;
  out_x_clear <= rst or (advance and emit and out_x_last);
  out_x_step  <= advance and emit;
  -- The frame's last output beat (out_last) is always a border beat of the
  -- flush, where every clock emits.
  out_y_clear <= rst or (advance and out_last);
  out_y_step  <= advance and emit and out_x_last;

  counters : process (clk) is
  begin

    if rising_edge(clk) then
      if in_x_clear = '1' then
        in_x <= (others => '0');
      elsif in_x_step = '1' then
        in_x <= in_x + 1;
      end if;
      if in_y_clear = '1' then
        in_y <= (others => '0');
      elsif in_y_step = '1' then
        in_y <= in_y + 1;
      end if;
      if out_x_clear = '1' then
        beat_x <= (others => '0');
      elsif out_x_step = '1' then
        beat_x <= beat_x + 1;
      end if;
      if out_y_clear = '1' then
        beat_y <= (others => '0');
      elsif out_y_step = '1' then
        beat_y <= beat_y + 1;
      end if;
    end if;

  end process counters;

  config : process (clk) is
  begin

    if rising_edge(clk) then
      cfg_w <= cfg_width;
      cfg_h <= cfg_height;
      -- The range checks read the ports, not cfg_w: yosys's abc9 otherwise
      -- finds cfg_w >= MIN_WIDTH in the carry out of cfg_w - 2 PPC below and
      -- takes the whole carry chain into the path.
      cfg_ok(0) <= at_least(cfg_width, MIN_WIDTH);
      cfg_ok(1) <= not at_least(cfg_width, MAX_WIDTH + 1);
      cfg_ok(2) <= at_least(cfg_height, WINDOW);
      cfg_ok(3) <= not at_least(cfg_height, MAX_HEIGHT + 1);
      cfg_ok(4) <= to_sl((cfg_width and to_unsigned(PPC - 1, cfg_width'length)) = 0);

      -- In beats: B = W / PPC (the low bits are checked to be 0); the
      -- subtraction comes first, so the shift is wiring after the carry chain.
      cfg_limits.w_last_m1 <= resize(shift_right(cfg_w - 2 * PPC, PB), x_t'length);
      cfg_limits.w_two     <= to_sl(cfg_w = 2 * PPC);
      for lane in 0 to PPC - 1 loop
        cfg_limits.hi_zero(lane) <= to_sl(cfg_w = PPC * ((R + lane + PPC) / PPC));
      end loop;
      cfg_limits.h_last_m1 <= resize(cfg_h - 2, y_t'length);
      cfg_limits.y_hi      <= resize(cfg_h - (R + 1), y_t'length);
      for lane in 0 to PPC - 1 loop
        -- The last beat b with PPC b + lane <= W - 1 - R.
        cfg_limits.x_hi(lane) <= resize(shift_right(cfg_w - PPC * ((R + lane + PPC) / PPC), PB), x_t'length);
      end loop;
    end if;

  end process config;

  -- Input buffer, two entries, so that in_ready is a register: the pixels in
  -- the ping-pong style (the decision to take the waiting beat, from this
  -- block's state, moves its pointers and enables none of the PPC pixels'
  -- registers), the flags beside them in the main/skid style, whose outputs
  -- are registers (the position logic decides from them). Both styles have
  -- the same cycle behaviour, so the two buffers stay in step.
  in_flags <= in_sof & in_eol & (in_sof and to_sl(cfg_ok = "11111"));
  a_ready  <= advance and not hold;

  input_pixels : entity work.fastnms_skid_buffer
    generic map (
      WIDTH     => PPC * DATA_WIDTH,
      PING_PONG => true
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => in_valid,
      in_ready  => open,
      in_data   => in_data,
      out_valid => open,
      out_ready => a_ready,
      out_data  => a_data
    );

  input_flags : entity work.fastnms_skid_buffer
    generic map (
      WIDTH     => 3,
      PING_PONG => false
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => in_valid,
      in_ready  => in_taken,
      in_data   => in_flags,
      out_valid => a_valid,
      out_ready => a_ready,
      out_data  => a_flags
    );

  in_ready <= in_taken;
  a_sof    <= a_flags(2);
  a_eol    <= a_flags(1);
  a_start  <= a_flags(0);

  -- A frame's limits, sampled with its start of frame. Two starts of frame in
  -- the buffer at once (a frame of one beat, malformed) give the first the
  -- second's limits: that frame is cut at its next beat and never output.
  input_limits : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' and in_taken = '1' and in_sof = '1' then
        a_limits <= cfg_limits;
      end if;
    end if;

  end process input_limits;

  input_side : process (clk) is
  begin

    if rising_edge(clk) then
      err_line  <= '0';
      err_frame <= '0';

      if advance = '1' then
        if restart = '1' then
          err_frame <= '1';
          in_active <= '0';
          in_x_last <= '0';
          in_y_last <= '0';
          in_last   <= '0';
          at_start  <= '0';
          pre_start <= '0';
          near_x    <= (others => '0');
          near_y    <= (others => '0');
        elsif take = '1' and counted = '0' then
          -- A pixel outside any frame, or of a frame with a bad size.
          err_frame <= '1';
        elsif counted = '1' then
          -- At a start of frame the position is already (0, 0).
          if a_sof = '1' then
            in_active <= '1';
            in_limits <= a_limits;
          end if;
          err_line <= in_x_last xor a_eol;
          at_start <= pre_start;
          if in_x_last = '1' then
            in_x_last <= '0';
            in_last   <= '0';
            near_x    <= (others => '0');
            in_y_last <= to_sl(in_y = in_limits.h_last_m1);
            -- The next beat is at x = 0 of row near_y + 1 (of row 0 after
            -- the last row, where pre_start is never set: R >= 1).
            pre_start <= to_sl(LB = 1 and to_integer(near_y) = R - 1) and not in_y_last;
            if near_y /= R + 1 then
              near_y <= near_y + 1;
            end if;
            if in_y_last = '1' then
              in_active <= '0';
              in_y_last <= '0';
              near_y    <= (others => '0');
            end if;
          else
            -- The next beat is at min(near_x + 1, LB) of the same row.
            pre_start <= to_sl(to_integer(near_x) = LB - 2 and near_y = R);
            -- At a start of frame in_limits are the previous frame's (and
            -- the first row is never the last: H >= WINDOW).
            in_x_last <= (to_sl(in_x = in_limits.w_last_m1) and not a_sof) or
                         (a_sof and a_limits.w_two);
            in_last   <= to_sl(in_x = in_limits.w_last_m1) and not a_sof and in_y_last;
            if near_x /= LB then
              near_x <= near_x + 1;
            end if;
          end if;
        end if;

        -- at_start and out_busy, one clock ahead: a restart clears at_start;
        -- a counted beat sets it on the beat before the first window's
        -- (whose own beat sets out_busy, and clears at_start); the end of a
        -- flush clears out_busy.
        if restart = '1' then
          blocked <= '0';
        elsif counted = '1' then
          blocked <= pre_start and out_busy and not out_last;
        else
          blocked <= blocked and not out_last;
        end if;
      end if;

      -- synthesis translate_off
      -- The invariants the decisions rely on.
      if rst = '1' then
        checks_on <= true;
      end if;
      assert not checks_on or rst = '1' or blocked = (at_start and out_busy)
        report "fastnms_window: blocked is not at_start and out_busy"
        severity failure;
      assert not checks_on or rst = '1' or in_last = (in_x_last and in_y_last)
        report "fastnms_window: in_last is not in_x_last and in_y_last"
        severity failure;
      assert not checks_on or rst = '1' or at_start = '0' or in_active = '1'
        report "fastnms_window: at_start outside a frame"
        severity failure;
      assert not checks_on or rst = '1' or out_state /= lockstep or (in_active = '1' and at_start = '0')
        report "fastnms_window: lockstep outside the input's frame"
        severity failure;
      assert not checks_on or rst = '1' or
             (out_last = (out_x_last and out_y_last) and (out_last = '0' or out_state = flush))
        report "fastnms_window: out_last is not out_x_last and out_y_last in the flush"
        severity failure;
      assert not checks_on or rst = '1' or (out_state = idle) = (out_busy = '0')
        report "fastnms_window: out_busy is not out_state /= idle"
        severity failure;
      -- synthesis translate_on

      if rst = '1' then
        in_active <= '0';
        in_x_last <= '0';
        in_y_last <= '0';
        in_last   <= '0';
        at_start  <= '0';
        blocked   <= '0';
        pre_start <= '0';
        near_x    <= (others => '0');
        near_y    <= (others => '0');
        err_line  <= '0';
        err_frame <= '0';
      end if;
    end if;

  end process input_side;

  output_side : process (clk) is
  begin

    if rising_edge(clk) then
      -- Compared a clock ahead, out of the row-end logic: beat_y and the
      -- limits change only on a frame's first beat (idle: the limits it
      -- loads are in_limits) or a row's last one, and a row has at least
      -- two beats, so at a row's last beat the comparison is up to date.
      if out_state = idle then
        y_at_last <= to_sl(beat_y = in_limits.h_last_m1);
      else
        y_at_last <= to_sl(beat_y = out_limits.h_last_m1);
      end if;
      if advance = '1' then
        tokens(1).valid  <= emit;
        tokens(1).border <= to_sl(out_state = flush);
        tokens(1).sof    <= to_sl(out_state = idle);
        tokens(1).eol    <= out_x_last;
        tokens(1).eof    <= out_last;
        tokens(1).x      <= beat_x;
        tokens(1).y      <= beat_y;
        -- The first LB beats of a flush end the last inside row: with
        -- PPC > 1 some of their pixels are inside (not after a cut).
        for lane in 0 to PPC - 1 loop
          tokens(1).inside(lane) <= out_x_in(lane) and out_y_in and
                                    to_sl(out_state = lockstep or (out_state = flush and out_cut = '0'));
        end loop;
        for stage in 2 to TOKEN_LAST loop
          tokens(stage) <= tokens(stage - 1);
        end loop;

        if emit = '1' then
          if out_state = idle then
            out_state  <= lockstep;
            out_busy   <= '1';
            out_limits <= in_limits;
          end if;
          if out_x_last = '1' then
            out_x_last <= '0';
            out_last   <= '0';
            for lane in 0 to PPC - 1 loop
              out_x_in(lane) <= to_sl(first_inside_beat(lane) = 0);
            end loop;
            out_y_last <= y_at_last;
            out_y_in   <= (out_y_in and not to_sl(beat_y = out_limits.y_hi)) or to_sl(beat_y = R - 1);
            if out_y_last = '1' then
              out_state  <= idle;
              out_busy   <= '0';
              out_cut    <= '0';
              out_y_last <= '0';
              out_y_in   <= '0';
            end if;
          elsif out_state = idle then
            -- A frame's first beat: out_limits are still the previous
            -- frame's (they load now), so beat 1's flags come from flags
            -- of in_limits (only two-beat rows make them differ).
            out_x_last <= in_limits.w_two;
            for lane in 0 to PPC - 1 loop
              out_x_in(lane) <= to_sl(first_inside_beat(lane) <= 1) and not in_limits.hi_zero(lane);
            end loop;
          else
            out_x_last <= to_sl(beat_x = out_limits.w_last_m1);
            out_last   <= to_sl(beat_x = out_limits.w_last_m1) and out_y_last;
            for lane in 0 to PPC - 1 loop
              -- Inside from its first inside beat to x_hi (never, when
              -- x_hi is the beat before the first).
              if first_inside_beat(lane) > 0 then
                out_x_in(lane) <= (out_x_in(lane) or to_sl(beat_x = first_inside_beat(lane) - 1)) and
                                  not to_sl(beat_x = out_limits.x_hi(lane));
              else
                out_x_in(lane) <= out_x_in(lane) and not to_sl(beat_x = out_limits.x_hi(lane));
              end if;
            end loop;
          end if;
        end if;

        -- The frame's last beat, or a cut (a start of frame), ends the
        -- lockstep part (in lockstep the input is inside its frame).
        if out_state = lockstep and a_valid = '1' and (a_sof = '1' or in_last = '1') then
          out_state <= flush;
          out_cut   <= a_sof;
        end if;
      end if;

      if rst = '1' then
        out_state  <= idle;
        out_busy   <= '0';
        out_cut    <= '0';
        out_x_last <= '0';
        out_y_last <= '0';
        out_last   <= '0';
        for lane in 0 to PPC - 1 loop
          out_x_in(lane) <= to_sl(first_inside_beat(lane) = 0);
        end loop;
        out_y_in <= '0';
        for stage in 1 to TOKEN_LAST loop
          tokens(stage).valid <= '0';
        end loop;
      end if;
    end if;

  end process output_side;

  lines : entity work.fastnms_line_buffer
    generic map (
      MAX_WIDTH    => MAX_BEATS,
      LINES        => WINDOW - 1,
      DATA_WIDTH   => PPC * DATA_WIDTH,
      READ_LATENCY => READ_LATENCY
    )
    port map (
      clk        => clk,
      rst        => rst,
      en         => advance,
      in_valid   => counted,
      in_col     => in_x,
      in_data    => a_data,
      out_valid  => col_valid,
      out_column => column
    );

  -- Window: shift left by one beat column when a column arrives, and with
  -- each border beat of a flush (whose column, if any, is not used), so
  -- that a beat's window is always the LB beat columns either side of it.
  shift <= advance and (col_valid or (tokens(TOKEN_LAST - 1).valid and tokens(TOKEN_LAST - 1).border));

  window_shift : process (clk) is
  begin

    if rising_edge(clk) then
      if shift = '1' then
        for row in 0 to WINDOW - 1 loop
          for col in 0 to REG_COLS - PPC - 1 loop
            win_regs(row, col) <= win_regs(row, col + PPC);
          end loop;
          for lane in 0 to PPC - 1 loop
            win_regs(row, REG_COLS - PPC + lane) <= column((row * PPC + lane + 1) * DATA_WIDTH - 1 downto (row * PPC + lane) * DATA_WIDTH);
          end loop;
        end loop;
      end if;
    end if;

  end process window_shift;

  -- Pixel (row r, column c) of the output block is slice r * OUT_COLS + c.

  flatten : for index in 0 to WINDOW * OUT_COLS - 1 generate
    out_window((index + 1) * DATA_WIDTH - 1 downto index * DATA_WIDTH) <= win_regs(index / OUT_COLS, COL0 + index mod OUT_COLS);
  end generate flatten;

  out_valid  <= tokens(TOKEN_LAST).valid;
  out_inside <= tokens(TOKEN_LAST).inside;
  out_sof    <= tokens(TOKEN_LAST).sof;
  out_eol    <= tokens(TOKEN_LAST).eol;
  out_eof    <= tokens(TOKEN_LAST).eof;
  out_x      <= shift_left(resize(tokens(TOKEN_LAST).x, out_x'length), PB);
  out_y      <= tokens(TOKEN_LAST).y;

end architecture rtl;
