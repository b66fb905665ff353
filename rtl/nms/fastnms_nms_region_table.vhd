-- Region NMS, part 2: the region table. Takes the events of
-- fastnms_nms_region_scan one at a time and emits a region's record when the
-- region closes.
--
-- Per label (block RAM, one word per label and field):
--   region       the region the label belongs to (a flat table: always one look-up)
--   runs         runs of the label line holding the label
--   next, prev   the region's labels as a doubly linked list
-- Per region (the paper's RAM score):
--   best         the maximum, as the key {score, not y, not x}: the larger
--                key is the larger score, then the first pixel in raster order
--   head, tail   its list of labels
-- Labels and regions are recycled through free lists (FIFOs); labels also go
-- to the scan as its spare label. Both are handed out through skid buffers.
--
-- Timing: the label tables are read through the block RAMs' output
-- registers (two clocks per read), so every decision starts at a flip-flop;
-- "runs = 1", "has next" and "has prev" are flag bits stored in the words; a
-- maximum is compared from registers and written one clock after it is read.
-- The region tables (read once per step, into registers or straight into a
-- write) keep one-clock reads.
--
-- Events, in this order within one beat:
--   new    label l starts with one run, in a fresh region whose best is the run's first pixel
--   union  the regions of l and u merge: the best of both, and the labels of
--          u's region re-pointed at l's region (3 clocks per label)
--   end    the run of l ends: its best enters l's region; l counts one more
--          run unless credit = '1'
--   pass   one run of p has left the line: when p holds no run any more it
--          leaves its region's list and returns to the free list; a region
--          whose list is empty is closed and its record goes out
--   eof    the end-of-frame beat goes out
-- Clocks per event beat: 1, plus 1 for new, 5 + 3 per label moved for a
-- union (4 when both labels are already in one region), 4 for end, 3 for
-- pass (4 and the output handshake when a region closes); a step whose label
-- read the step before issued is one clock shorter.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_nms_region_table is
  generic (
    LABELS     : positive := 963;
    LABEL_BITS : positive := 10;
    RUN_BITS   : positive := 10;
    SCORE_BITS : positive := 8;
    X_BITS     : positive := 11;
    Y_BITS     : positive := 12
  );
  port (
    clk            : in    std_logic;
    rst            : in    std_logic;
    ev_valid       : in    std_logic;
    ev_ready       : out   std_logic;
    ev_new         : in    std_logic;
    ev_union       : in    std_logic;
    ev_union_label : in    unsigned(LABEL_BITS - 1 downto 0);
    ev_end         : in    std_logic;
    ev_credit      : in    std_logic;
    ev_pass        : in    std_logic;
    ev_pass_label  : in    unsigned(LABEL_BITS - 1 downto 0);
    ev_label       : in    unsigned(LABEL_BITS - 1 downto 0);
    ev_score       : in    unsigned(SCORE_BITS - 1 downto 0);
    ev_x           : in    unsigned(X_BITS - 1 downto 0);
    ev_y           : in    unsigned(Y_BITS - 1 downto 0);
    ev_eof         : in    std_logic;
    spare_valid    : out   std_logic;
    spare_label    : out   unsigned(LABEL_BITS - 1 downto 0);
    spare_take     : in    std_logic;
    out_valid      : out   std_logic;
    out_ready      : in    std_logic;
    out_x          : out   unsigned(X_BITS - 1 downto 0);
    out_y          : out   unsigned(Y_BITS - 1 downto 0);
    out_score      : out   unsigned(SCORE_BITS - 1 downto 0);
    out_eof        : out   std_logic
  );
end entity fastnms_nms_region_table;

architecture rtl of fastnms_nms_region_table is

  constant KEY_BITS : positive := SCORE_BITS + Y_BITS + X_BITS;
  -- The free lists push without looking at in_ready: they never hold more
  -- than the LABELS - 1 ids, and fastnms_fifo's in_ready is '1' while it
  -- holds fewer than DEPTH - 2 words (see its header).
  constant FREE_DEPTH : positive := LABELS + 2;

  subtype label_t is unsigned(LABEL_BITS - 1 downto 0);

  subtype key_t is unsigned(KEY_BITS - 1 downto 0);

  constant NONE : label_t := (others => '0');

  type state_t is (
    fetch, new_run, union_a, union_b, union_wait, union_cmp, union_link, walk, walk_wait,
    walk_next, end_read, end_wait, end_count, end_best, pass_read, pass_wait, pass_count,
    pass_emit, eof_emit
  );

  -- The steps of an event beat, in order.
  constant STEP_NEW   : natural := 0;
  constant STEP_UNION : natural := 1;
  constant STEP_END   : natural := 2;
  constant STEP_PASS  : natural := 3;
  constant STEP_EOF   : natural := 4;

  signal state : state_t;
  -- Label RAMs: one read address for all fields.
  signal lab_rd_addr : label_t;
  signal lab_region  : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal lab_runs    : std_logic_vector(RUN_BITS - 1 downto 0);
  signal lab_next    : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal lab_prev    : std_logic_vector(LABEL_BITS - 1 downto 0);
  -- Flags stored beside the counts and links, decoded when written, so that
  -- no decision compares a RAM output: runs = 1, next /= none, prev /= none.
  signal lab_one      : std_logic;
  signal lab_has_next : std_logic;
  signal lab_has_prev : std_logic;
  signal runs_word    : std_logic_vector(RUN_BITS downto 0);
  signal next_word    : std_logic_vector(LABEL_BITS downto 0);
  signal prev_word    : std_logic_vector(LABEL_BITS downto 0);
  signal runs_one     : std_logic;
  signal next_has     : std_logic;
  signal prev_has     : std_logic;
  signal closes       : std_logic;
  signal region_we    : std_logic;
  signal region_addr  : label_t;
  signal region_data  : label_t;
  signal runs_we      : std_logic;
  signal runs_addr    : label_t;
  signal runs_data    : unsigned(RUN_BITS - 1 downto 0);
  signal next_we      : std_logic;
  signal next_addr    : label_t;
  signal next_data    : label_t;
  signal prev_we      : std_logic;
  signal prev_addr    : label_t;
  signal prev_data    : label_t;
  -- Region RAMs: one read address for all fields.
  signal reg_rd_addr : label_t;
  signal reg_best    : std_logic_vector(KEY_BITS - 1 downto 0);
  signal reg_head    : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal reg_tail    : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal best_we     : std_logic;
  signal best_addr   : label_t;
  signal best_data   : key_t;
  signal head_we     : std_logic;
  signal head_addr   : label_t;
  signal head_data   : label_t;
  signal tail_we     : std_logic;
  signal tail_addr   : label_t;
  signal tail_data   : label_t;
  -- Working registers.
  signal region_a : label_t;
  signal region_b : label_t;
  signal best_a   : key_t;
  signal best_b   : key_t;
  -- The clock after end_best: its maximum is written.
  signal end_pending : std_logic;
  signal tail_a      : label_t;
  signal cursor      : label_t;
  signal event_key   : key_t;
  -- The event beat being worked on.
  signal e_new         : std_logic;
  signal e_union       : std_logic;
  signal e_end         : std_logic;
  signal e_credit      : std_logic;
  signal e_pass        : std_logic;
  signal e_eof         : std_logic;
  signal e_union_label : label_t;
  signal e_pass_label  : label_t;
  signal e_label       : label_t;
  signal e_score       : unsigned(SCORE_BITS - 1 downto 0);
  signal e_x           : unsigned(X_BITS - 1 downto 0);
  signal e_y           : unsigned(Y_BITS - 1 downto 0);
  -- Free lists, and the spare label and region handed out from them: each
  -- through a skid buffer, so that taking one pops no FIFO in the same clock.
  -- Ids never handed out yet come from a counter first (`fresh`).
  signal lab_fresh     : unsigned(LABEL_BITS - 1 downto 0);
  signal lab_fresh_ok  : std_logic;
  signal lab_free_in   : std_logic;
  signal lab_free_out  : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal lab_free_ok   : std_logic;
  signal lab_free_pop  : std_logic;
  signal lab_supply    : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal lab_supply_ok : std_logic;
  signal lab_supplied  : std_logic;
  signal lab_ready     : std_logic;
  signal spare_data    : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal reg_fresh     : unsigned(LABEL_BITS - 1 downto 0);
  signal reg_fresh_ok  : std_logic;
  signal reg_free_in   : std_logic;
  signal reg_free_lab  : label_t;
  signal reg_free_out  : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal reg_free_ok   : std_logic;
  signal reg_free_pop  : std_logic;
  signal reg_supply    : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal reg_supply_ok : std_logic;
  signal reg_supplied  : std_logic;
  signal reg_ready     : std_logic;
  signal new_region    : label_t;
  signal new_region_v  : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal new_ok        : std_logic;
  signal take_region   : std_logic;
  -- Output.
  signal emit       : std_logic;
  signal emit_ready : std_logic;
  signal emit_data  : std_logic_vector(KEY_BITS downto 0);
  signal out_data   : std_logic_vector(KEY_BITS downto 0);
  signal out_key    : key_t;

  function larger (a : key_t; b : key_t) return key_t is
  begin

    if a > b then
      return a;
    end if;

    return b;

  end function larger;

  -- The first step at or after `from` that the event beat asks for.
  function first_step (
    from : natural; f_new, f_union, f_end, f_pass, f_eof : std_logic) return state_t is
  begin

    if from = STEP_NEW and f_new = '1' then
      return NEW_RUN;
    elsif from <= STEP_UNION and f_union = '1' then
      return UNION_A;
    elsif from <= STEP_END and f_end = '1' then
      return END_READ;
    elsif from <= STEP_PASS and f_pass = '1' then
      return PASS_READ;
    elsif f_eof = '1' then
      return EOF_EMIT;
    end if;

    return FETCH;

  end function first_step;

  -- A step whose label read was issued in the previous state skips its read state.
  function launch (next_state : state_t) return state_t is
  begin

    if next_state = union_a then
      return union_b;
    elsif next_state = end_read then
      return end_wait;
    elsif next_state = pass_read then
      return pass_wait;
    end if;

    return next_state;

  end function launch;

begin

  assert LABEL_BITS = clog2(LABELS)
    report "fastnms_nms_region_table: LABEL_BITS must be clog2(LABELS)"
    severity failure;

  assert LABELS >= 3
    report "fastnms_nms_region_table: LABELS must be at least 3"
    severity failure;

  event_key <= e_score & not e_y & not e_x;

  lab_runs     <= runs_word(RUN_BITS - 1 downto 0);
  lab_one      <= runs_word(RUN_BITS);
  lab_next     <= next_word(LABEL_BITS - 1 downto 0);
  lab_has_next <= next_word(LABEL_BITS);
  lab_prev     <= prev_word(LABEL_BITS - 1 downto 0);
  lab_has_prev <= prev_word(LABEL_BITS);
  -- The label's last run passes and it is its region's only label.
  closes <= lab_one and not lab_has_prev and not lab_has_next;

  -- ---- the event sequencer --------------------------------------------------
  sequencer : process (clk) is
  begin

    if rising_edge(clk) then
      if state = fetch then
        if ev_valid = '1' then
          state <= launch(first_step(STEP_NEW, ev_new, ev_union, ev_end, ev_pass, ev_eof));
        end if;
      elsif state = new_run then
        if new_ok = '1' then
          state <= first_step(STEP_UNION, e_new, e_union, e_end, e_pass, e_eof);
        end if;
      elsif state = union_a then
        state <= union_b;
      elsif state = union_b then
        state <= union_wait;
      elsif state = union_wait then
        region_a <= unsigned(lab_region);
        state    <= union_cmp;
      elsif state = union_cmp then
        region_b <= unsigned(lab_region);
        best_a   <= unsigned(reg_best);
        tail_a   <= unsigned(reg_tail);
        if unsigned(lab_region) = region_a then
          state <= launch(first_step(STEP_END, e_new, e_union, e_end, e_pass, e_eof));
        else
          state <= union_link;
        end if;
      elsif state = union_link then
        best_b <= unsigned(reg_best);
        cursor <= unsigned(reg_head);
        state  <= walk;
      elsif state = walk then
        state <= walk_wait;
      elsif state = walk_wait then
        state <= walk_next;
      elsif state = walk_next then
        cursor <= unsigned(lab_next);
        if lab_has_next = '0' then
          state <= launch(first_step(STEP_END, e_new, e_union, e_end, e_pass, e_eof));
        else
          state <= walk;
        end if;
      elsif state = end_read then
        state <= end_wait;
      elsif state = end_wait then
        state <= end_count;
      elsif state = end_count then
        region_a <= unsigned(lab_region);
        state    <= end_best;
      elsif state = end_best then
        best_b <= unsigned(reg_best);
        state  <= launch(first_step(STEP_PASS, e_new, e_union, e_end, e_pass, e_eof));
      elsif state = pass_read then
        state <= pass_wait;
      elsif state = pass_wait then
        state <= pass_count;
      elsif state = pass_count then
        region_a <= unsigned(lab_region);
        if closes = '1' then
          state <= pass_emit;
        else
          state <= first_step(STEP_EOF, e_new, e_union, e_end, e_pass, e_eof);
        end if;
      elsif state = pass_emit then
        if emit_ready = '1' then
          state <= first_step(STEP_EOF, e_new, e_union, e_end, e_pass, e_eof);
        end if;
      elsif state = eof_emit then
        if emit_ready = '1' then
          state <= fetch;
        end if;
      end if;

      end_pending <= to_sl(state = end_best);

      if rst = '1' then
        state       <= fetch;
        end_pending <= '0';
      end if;
    end if;

  end process sequencer;

  -- The table takes an event beat into its own registers (e_*) in `fetch`:
  -- the queue's pop never waits for a decision made from RAM outputs.
  ev_ready <= to_sl(state = fetch);

  event_register : process (clk) is
  begin

    if rising_edge(clk) then
      if state = fetch then
        e_new         <= ev_new;
        e_union       <= ev_union;
        e_end         <= ev_end;
        e_credit      <= ev_credit;
        e_pass        <= ev_pass;
        e_eof         <= ev_eof;
        e_union_label <= ev_union_label;
        e_pass_label  <= ev_pass_label;
        e_label       <= ev_label;
        e_score       <= ev_score;
        e_x           <= ev_x;
        e_y           <= ev_y;
      end if;
    end if;

  end process event_register;

  -- ---- RAM addresses and writes per state -----------------------------------
  ports : process (all) is
  begin

    lab_rd_addr  <= e_label;
    reg_rd_addr  <= region_a;
    region_we    <= '0';
    region_addr  <= e_label;
    region_data  <= new_region;
    runs_we      <= '0';
    runs_addr    <= e_label;
    runs_data    <= to_unsigned(1, RUN_BITS);
    runs_one     <= '1';
    next_we      <= '0';
    next_addr    <= e_label;
    next_data    <= NONE;
    next_has     <= '0';
    prev_we      <= '0';
    prev_addr    <= e_label;
    prev_data    <= NONE;
    prev_has     <= '0';
    best_we      <= '0';
    best_addr    <= new_region;
    best_data    <= event_key;
    head_we      <= '0';
    head_addr    <= new_region;
    head_data    <= e_label;
    tail_we      <= '0';
    tail_addr    <= new_region;
    tail_data    <= e_label;
    take_region  <= '0';
    reg_free_in  <= '0';
    reg_free_lab <= region_b;
    lab_free_in  <= '0';
    emit         <= '0';
    emit_data    <= '0' & reg_best;

    if state = new_run then
      -- One run, a fresh region whose list is the label alone.
      region_we   <= new_ok;
      runs_we     <= new_ok;
      next_we     <= new_ok;
      prev_we     <= new_ok;
      best_we     <= new_ok;
      head_we     <= new_ok;
      tail_we     <= new_ok;
      take_region <= new_ok;
    elsif state = union_a then
      lab_rd_addr <= e_label;
    elsif state = union_b then
      lab_rd_addr <= e_union_label;
    elsif state = union_wait then
      reg_rd_addr <= unsigned(lab_region);
    elsif state = union_cmp then
      reg_rd_addr <= unsigned(lab_region);
      if first_step(STEP_END, e_new, e_union, e_end, e_pass, e_eof) = pass_read then
        lab_rd_addr <= e_pass_label;
      end if;
    elsif state = union_link then
      -- Region b's list goes after region a's (a's maximum: see walk).
      tail_we     <= '1';
      tail_addr   <= region_a;
      tail_data   <= unsigned(reg_tail);
      next_we     <= '1';
      next_addr   <= tail_a;
      next_data   <= unsigned(reg_head);
      next_has    <= '1';
      prev_we     <= '1';
      prev_addr   <= unsigned(reg_head);
      prev_data   <= tail_a;
      prev_has    <= '1';
      reg_free_in <= '1';
    elsif state = walk then
      -- Region a keeps the better maximum, compared from registers (written
      -- on every walk step, the same word each time).
      best_we     <= '1';
      best_addr   <= region_a;
      best_data   <= larger(best_a, best_b);
      region_we   <= '1';
      region_addr <= cursor;
      region_data <= region_a;
      lab_rd_addr <= cursor;
    elsif state = walk_next then
      if first_step(STEP_END, e_new, e_union, e_end, e_pass, e_eof) = pass_read then
        lab_rd_addr <= e_pass_label;
      end if;
    elsif state = fetch then
      -- The first step's label read (see launch).
      if first_step(STEP_NEW, ev_new, ev_union, ev_end, ev_pass, ev_eof) = pass_read then
        lab_rd_addr <= ev_pass_label;
      else
        lab_rd_addr <= ev_label;
      end if;
    elsif state = end_read then
      lab_rd_addr <= e_label;
    elsif state = end_count then
      runs_we     <= not e_credit;
      runs_data   <= unsigned(lab_runs) + 1;
      runs_one    <= to_sl(unsigned(lab_runs) = 0);
      reg_rd_addr <= unsigned(lab_region);
    elsif state = end_best then
      if first_step(STEP_PASS, e_new, e_union, e_end, e_pass, e_eof) = pass_read then
        lab_rd_addr <= e_pass_label;
      end if;
    elsif state = pass_read then
      lab_rd_addr <= e_pass_label;
    elsif state = pass_count then
      runs_addr   <= e_pass_label;
      runs_data   <= unsigned(lab_runs) - 1;
      runs_one    <= to_sl(unsigned(lab_runs) = 2);
      reg_rd_addr <= unsigned(lab_region);
      if lab_one = '0' then
        runs_we <= '1';
      else
        -- The label leaves its region's list and is free again.
        lab_free_in <= '1';
        next_addr   <= unsigned(lab_prev);
        next_data   <= unsigned(lab_next);
        next_has    <= lab_has_next;
        next_we     <= lab_has_prev;
        head_addr   <= unsigned(lab_region);
        head_data   <= unsigned(lab_next);
        head_we     <= not lab_has_prev;
        prev_addr   <= unsigned(lab_next);
        prev_data   <= unsigned(lab_prev);
        prev_has    <= lab_has_prev;
        prev_we     <= lab_has_next;
        tail_addr   <= unsigned(lab_region);
        tail_data   <= unsigned(lab_prev);
        tail_we     <= not lab_has_next;
      end if;
    elsif state = pass_emit then
      -- The list is empty: the region is closed.
      reg_rd_addr  <= region_a;
      emit         <= '1';
      reg_free_in  <= emit_ready;
      reg_free_lab <= region_a;
    elsif state = eof_emit then
      emit                <= '1';
      emit_data           <= (others => '0');
      emit_data(KEY_BITS) <= '1';
    end if;

    -- The run's best enters its region on the clock after end_best, compared
    -- from registers. That clock (pass_count, eof_emit or fetch) writes no
    -- other maximum, and the region pass_count may read is never this one
    -- when it closes: the ended run keeps one run of the region in the line.
    if end_pending = '1' then
      best_we   <= '1';
      best_addr <= region_a;
      best_data <= larger(best_b, event_key);
    end if;

  end process ports;

  -- ---- spare label and region ----------------------------------------------
  lab_supply_ok <= lab_fresh_ok or lab_free_ok;
  lab_supply    <= std_logic_vector(lab_fresh) when lab_fresh_ok = '1' else
                   lab_free_out;
  lab_free_pop  <= lab_supplied and lab_free_ok and not lab_fresh_ok;
  reg_supply_ok <= reg_fresh_ok or reg_free_ok;
  reg_supply    <= std_logic_vector(reg_fresh) when reg_fresh_ok = '1' else
                   reg_free_out;
  reg_free_pop  <= reg_supplied and reg_free_ok and not reg_fresh_ok;
  spare_label   <= unsigned(spare_data);
  new_region    <= unsigned(new_region_v);

  -- Ids 1 .. LABELS - 1 that were never handed out.
  fresh_ids : process (clk) is
  begin

    if rising_edge(clk) then
      if lab_supplied = '1' and lab_fresh_ok = '1' then
        lab_fresh    <= lab_fresh + 1;
        lab_fresh_ok <= to_sl(lab_fresh /= LABELS - 1);
      end if;
      if reg_supplied = '1' and reg_fresh_ok = '1' then
        reg_fresh    <= reg_fresh + 1;
        reg_fresh_ok <= to_sl(reg_fresh /= LABELS - 1);
      end if;
      if rst = '1' then
        lab_fresh    <= to_unsigned(1, LABEL_BITS);
        lab_fresh_ok <= '1';
        reg_fresh    <= to_unsigned(1, LABEL_BITS);
        reg_fresh_ok <= '1';
      end if;
    end if;

  end process fresh_ids;

  -- The scan's spare label.
  spare_out : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => LABEL_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => lab_supply_ok,
      in_ready  => lab_ready,
      in_data   => lab_supply,
      out_valid => spare_valid,
      out_ready => spare_take,
      out_data  => spare_data
    );

  lab_supplied <= lab_ready and lab_supply_ok;

  -- The region a new run's region takes.
  region_out : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => LABEL_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => reg_supply_ok,
      in_ready  => reg_ready,
      in_data   => reg_supply,
      out_valid => new_ok,
      out_ready => take_region,
      out_data  => new_region_v
    );

  reg_supplied <= reg_ready and reg_supply_ok;

  label_free_list : entity work.fastnms_fifo
    generic map (
      DEPTH => FREE_DEPTH,
      WIDTH => LABEL_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => lab_free_in,
      in_ready  => open,
      in_room2  => open,
      in_data   => std_logic_vector(e_pass_label),
      out_valid => lab_free_ok,
      out_ready => lab_free_pop,
      out_data  => lab_free_out,
      busy      => open
    );

  region_free_list : entity work.fastnms_fifo
    generic map (
      DEPTH => FREE_DEPTH,
      WIDTH => LABEL_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => reg_free_in,
      in_ready  => open,
      in_room2  => open,
      in_data   => std_logic_vector(reg_free_lab),
      out_valid => reg_free_ok,
      out_ready => reg_free_pop,
      out_data  => reg_free_out,
      busy      => open
    );

  -- ---- the tables ------------------------------------------------------------
  label_region : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => LABELS, WIDTH => LABEL_BITS, READ_LATENCY => 2
    )
    port map (
      clk     => clk,
      wr_en   => region_we,
      wr_addr => region_addr,
      wr_data => std_logic_vector(region_data),
      rd_en   => '1',
      rd_addr => lab_rd_addr,
      rd_data => lab_region
    );

  label_runs : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => LABELS, WIDTH => RUN_BITS + 1, READ_LATENCY => 2
    )
    port map (
      clk     => clk,
      wr_en   => runs_we,
      wr_addr => runs_addr,
      wr_data => runs_one & std_logic_vector(runs_data),
      rd_en   => '1',
      rd_addr => lab_rd_addr,
      rd_data => runs_word
    );

  label_next : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => LABELS, WIDTH => LABEL_BITS + 1, READ_LATENCY => 2
    )
    port map (
      clk     => clk,
      wr_en   => next_we,
      wr_addr => next_addr,
      wr_data => next_has & std_logic_vector(next_data),
      rd_en   => '1',
      rd_addr => lab_rd_addr,
      rd_data => next_word
    );

  label_prev : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => LABELS, WIDTH => LABEL_BITS + 1, READ_LATENCY => 2
    )
    port map (
      clk     => clk,
      wr_en   => prev_we,
      wr_addr => prev_addr,
      wr_data => prev_has & std_logic_vector(prev_data),
      rd_en   => '1',
      rd_addr => lab_rd_addr,
      rd_data => prev_word
    );

  region_best : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => LABELS, WIDTH => KEY_BITS
    )
    port map (
      clk     => clk,
      wr_en   => best_we,
      wr_addr => best_addr,
      wr_data => std_logic_vector(best_data),
      rd_en   => '1',
      rd_addr => reg_rd_addr,
      rd_data => reg_best
    );

  region_head : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => LABELS, WIDTH => LABEL_BITS
    )
    port map (
      clk     => clk,
      wr_en   => head_we,
      wr_addr => head_addr,
      wr_data => std_logic_vector(head_data),
      rd_en   => '1',
      rd_addr => reg_rd_addr,
      rd_data => reg_head
    );

  region_tail : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => LABELS, WIDTH => LABEL_BITS
    )
    port map (
      clk     => clk,
      wr_en   => tail_we,
      wr_addr => tail_addr,
      wr_data => std_logic_vector(tail_data),
      rd_en   => '1',
      rd_addr => reg_rd_addr,
      rd_data => reg_tail
    );

  -- ---- output ------------------------------------------------------------------
  record_out : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => KEY_BITS + 1
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => emit,
      in_ready  => emit_ready,
      in_data   => emit_data,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => out_data
    );

  out_eof   <= out_data(KEY_BITS);
  out_key   <= unsigned(out_data(KEY_BITS - 1 downto 0));
  out_score <= out_key(KEY_BITS - 1 downto Y_BITS + X_BITS);
  out_y     <= not out_key(Y_BITS + X_BITS - 1 downto X_BITS);
  out_x     <= not out_key(X_BITS - 1 downto 0);

end architecture rtl;
