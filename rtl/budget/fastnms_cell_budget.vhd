-- Keypoint budget per grid cell (golden/budget.py): of a frame's records in
-- raster order, at most K per CELL x CELL cell, the best scores, each cell
-- row's kept records once the row is complete.
-- Datasheet: docs/fastnms_cell_budget.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_budget_pkg.all;

entity fastnms_cell_budget is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE_BITS   : positive := 8;
    MAX_PER_CELL : natural  := 15
  );
  port (
    clk         : in    std_logic;
    rst         : in    std_logic;
    in_valid    : in    std_logic;
    in_ready    : out   std_logic;
    in_x        : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    in_y        : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    in_score    : in    unsigned(SCORE_BITS - 1 downto 0);
    in_eof      : in    std_logic;
    in_row_end  : in    std_logic;
    in_cell_log : in    unsigned(2 downto 0);
    in_per_cell : in    unsigned(3 downto 0);
    out_valid   : out   std_logic;
    out_ready   : in    std_logic;
    out_x       : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y       : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_score   : out   unsigned(SCORE_BITS - 1 downto 0);
    out_eof     : out   std_logic
  );
end entity fastnms_cell_budget;

architecture rtl of fastnms_cell_budget is

  constant X_BITS    : positive := in_x'length;
  constant Y_BITS    : positive := in_y'length;
  constant BEAT_BITS : positive := 1 + X_BITS + Y_BITS + SCORE_BITS;

  subtype beat_t is std_logic_vector(BEAT_BITS - 1 downto 0);

  function pack (eof : std_logic; x : unsigned; y : unsigned; s : unsigned) return beat_t is
  begin

    return eof & std_logic_vector(x) & std_logic_vector(y) & std_logic_vector(s);

  end function pack;

  signal o_valid : std_logic;
  signal o_ready : std_logic;
  signal o_beat  : beat_t;
  signal o_data  : beat_t;

begin

  assert MAX_PER_CELL <= 15
    report "fastnms_cell_budget: MAX_PER_CELL must be 0 .. 15"
    severity failure;
  assert MAX_WIDTH < 2 ** 16 and MAX_HEIGHT < 2 ** 16
    report "fastnms_cell_budget: MAX_WIDTH and MAX_HEIGHT must be below 65536"
    severity failure;

  -- The output: a skid buffer, so that out_ready reaches no logic.
  output_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => BEAT_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => o_valid,
      in_ready  => o_ready,
      in_data   => o_beat,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => o_data
    );

  out_eof   <= o_data(BEAT_BITS - 1);
  out_x     <= unsigned(o_data(BEAT_BITS - 2 downto Y_BITS + SCORE_BITS));
  out_y     <= unsigned(o_data(Y_BITS + SCORE_BITS - 1 downto SCORE_BITS));
  out_score <= unsigned(o_data(SCORE_BITS - 1 downto 0));

  -- No memory: every beat passes.

  pass_only : if MAX_PER_CELL = 0 generate
    o_valid  <= in_valid and not in_row_end;
    in_ready <= o_ready;
    o_beat   <= pack(in_eof, in_x, in_y, in_score);
  end generate pass_only;

  budget : if MAX_PER_CELL > 0 generate

    constant K_MAX      : positive := MAX_PER_CELL;
    constant CELLS      : positive := (MAX_WIDTH + 15) / 16; -- cells of a row at CELL 16
    constant ADDR_BITS  : positive := clog2(CELLS);
    constant ENTRY_BITS : positive := entry_width(SCORE_BITS); -- fastnms_budget_pkg
    constant WORD_BITS  : positive := K_MAX * ENTRY_BITS;     -- entries best first
    constant JOB_SLOTS  : positive := 4;

    subtype word_t is std_logic_vector(WORD_BITS - 1 downto 0);

    subtype entry_t is std_logic_vector(ENTRY_BITS - 1 downto 0);

    subtype addr_t is unsigned(ADDR_BITS - 1 downto 0);

    subtype log_t is natural range 0 to 4;

    subtype bank_t is natural range 0 to 1;

    type addr_pair_t is array (0 to 1) of addr_t;

    type word_pair_t is array (0 to 1) of word_t;

    type y_pair_t is array (0 to 1) of unsigned(Y_BITS - 1 downto 0);

    type log_pair_t is array (0 to 1) of log_t;

    -- A job: drain a bank (then, with eof, emit the end of frame), or an end of frame alone.
    type job_t is record
      drain : std_logic;
      bank  : bank_t;
      eof   : std_logic;
      x     : unsigned(X_BITS - 1 downto 0); -- the end-of-frame beat's position
      y     : unsigned(Y_BITS - 1 downto 0);
    end record job_t;

    type jobs_t is array (0 to JOB_SLOTS - 1) of job_t;

    -- The decoded beat (fastnms_budget_decode): with its frame's CELL (log) and K,
    -- its kind as flags (F_*).
    signal s_valid  : std_logic;
    signal s_ready  : std_logic;
    signal s_beat   : beat_t;
    signal s_flags  : std_logic_vector(F_BITS - 1 downto 0);
    signal s_eof    : std_logic;
    signal s_x      : unsigned(X_BITS - 1 downto 0);
    signal s_y      : unsigned(Y_BITS - 1 downto 0);
    signal s_score  : unsigned(SCORE_BITS - 1 downto 0);
    signal s_log    : log_t;
    signal s_k      : natural range 0 to K_MAX;
    signal s_y0     : unsigned(Y_BITS - 1 downto 0); -- the first line of the record's cell row
    signal s_cell_x : unsigned(X_BITS - 1 downto 0); -- the record's cell, registered
    signal s_cell   : addr_t;
    signal s_offset : std_logic_vector(15 downto 0); -- y and x inside the cell

    -- Decision.
    signal take       : std_logic;
    signal go_other   : std_logic; -- F_OTHER with a place in the queue and the other bank free
    signal pass       : std_logic;
    signal target     : bank_t;
    signal insert_now : std_logic;

    -- Banks.
    signal row_open   : std_logic;                -- a record of this frame went in
    signal fill_bank  : bank_t;
    signal busy_fill  : std_logic; -- a drain of fill_bank is queued or running (or the clear)
    signal busy_other : std_logic; -- the same for the other bank
    signal bank_free  : std_logic; -- the record's bank (target) is not busy
    signal turn       : std_logic; -- fill_bank changes
    signal bank_y0    : y_pair_t;
    signal bank_log   : log_pair_t;

    -- Jobs.
    signal jobs      : jobs_t;
    signal job_head  : unsigned(1 downto 0);
    signal job_tail  : unsigned(1 downto 0);
    signal job_level : std_logic_vector(0 to JOB_SLOTS - 1); -- bit i: more than i jobs queued
    signal job_room  : std_logic;                            -- registered: fewer than JOB_SLOTS jobs
    signal job_push  : std_logic;
    signal job_new   : job_t;
    signal job_pop   : std_logic;
    signal jobs_idle : std_logic; -- registered: no job queued or running, none pushed

    -- The insertion pipeline's record, its write and the banks' last cells written.
    signal s_entry : entry_t;
    signal c_valid : std_logic;
    signal c_bank  : bank_t;
    signal c_cell  : addr_t;
    signal c_new   : word_t;
    signal bank_hi : addr_pair_t;

    -- Memories.
    signal rd_en   : std_logic_vector(0 to 1);
    signal rd_addr : addr_pair_t;
    signal rd_data : word_pair_t;
    signal wr_en   : std_logic_vector(0 to 1);
    signal wr_addr : addr_pair_t;
    signal wr_data : word_pair_t;
    signal empty   : std_logic_vector(0 to 1); -- registered: the bank's write empties the word

    -- Reset clear.
    signal clearing  : std_logic;
    signal clear_at  : addr_t;
    signal clear_end : std_logic; -- registered: clear_at is the last cell

    -- Drain.
    -- Its states, one flip-flop each (one of them set).
    signal d_idle     : std_logic;
    signal d_settle   : std_logic;
    signal d_settle_2 : std_logic;
    signal d_read     : std_logic;
    signal d_wait     : std_logic;
    signal d_load     : std_logic;
    signal d_emit     : std_logic;
    signal d_eof      : std_logic;
    signal d_drains   : std_logic_vector(0 to 1); -- the job drains bank 0, 1
    signal d_next     : addr_t;                   -- registered: d_cell + 1
    signal d_hi       : addr_t;                   -- the bank's last cell written
    signal d_job      : job_t;
    signal d_cell     : addr_t;
    signal d_log      : log_t;                         -- the bank's CELL
    signal d_y0       : unsigned(Y_BITS - 1 downto 0); -- the bank's cell row
    signal d_x0       : unsigned(X_BITS - 1 downto 0); -- the first column of the cell
    signal d_word     : word_t;
    signal d_last     : std_logic;                     -- registered: d_cell is the bank's last cell

  begin

    -- ---- input side: each beat decoded with its frame's configuration, in two clocks ----

    input_decode : entity work.fastnms_budget_decode
      generic map (
        X_BITS     => X_BITS,
        Y_BITS     => Y_BITS,
        SCORE_BITS => SCORE_BITS,
        K_MAX      => K_MAX
      )
      port map (
        clk         => clk,
        rst         => rst,
        in_valid    => in_valid,
        in_ready    => in_ready,
        in_x        => in_x,
        in_y        => in_y,
        in_score    => in_score,
        in_eof      => in_eof,
        in_row_end  => in_row_end,
        in_cell_log => in_cell_log,
        in_per_cell => in_per_cell,
        out_valid   => s_valid,
        out_ready   => s_ready,
        out_x       => s_x,
        out_y       => s_y,
        out_score   => s_score,
        out_eof     => s_eof,
        out_log     => s_log,
        out_k       => s_k,
        out_flags   => s_flags,
        out_cell    => s_cell_x
      );

    s_beat <= pack(s_eof, s_x, s_y, s_score);
    s_cell <= resize(s_cell_x, ADDR_BITS);

    -- The record's cell row and place in the cell, from the registered beat.
    locate : process (all) is

      variable mask   : unsigned(15 downto 0); -- the bits inside a cell of 16 << s_log
      variable y_wide : unsigned(15 downto 0);
      variable x_wide : unsigned(15 downto 0);

    begin

      mask     := shift_right(to_unsigned(255, 16), 4 - s_log);
      y_wide   := resize(s_y, 16);
      x_wide   := resize(s_x, 16);
      s_y0     <= resize(y_wide and not mask, Y_BITS);
      s_offset <= std_logic_vector(y_wide(7 downto 0) and mask(7 downto 0))
                  & std_logic_vector(x_wide(7 downto 0) and mask(7 downto 0));

    end process locate;

    -- ---- decision ---------------------------------------------------------------------------

    target <= 1 - fill_bank when s_flags(F_SWITCH) = '1' else
              fill_bank;

    -- What the beat waits for, by its class (fastnms_budget_pkg): nothing (F_FREE); no
    -- job left and the output's ready (F_OUT, K = 0); a place in the queue (F_ENDS);
    -- its bank free (F_FILL); both (F_OTHER, a record opening a row in the other bank).
    -- While the memory clears, both banks count as busy and the queue as full.
    -- (One flag per class, read by take only with its own registers: take is two
    -- levels of logic, and shares no deeper term.)
    go_other <= s_flags(F_OTHER) and job_room and not busy_other;

    -- (Without s_valid: the input buffer's output is ready or not, valid or not.)
    take <= s_flags(F_FREE) or (s_flags(F_OUT) and jobs_idle and o_ready) or (s_flags(F_ENDS) and job_room)
            or (s_flags(F_FILL) and not busy_fill) or go_other;
    pass <= s_valid and s_flags(F_OUT) and jobs_idle;

    s_ready <= take;

    bank_free <= not busy_other when s_flags(F_SWITCH) = '1' else
                 not busy_fill;

    -- take with a record, take with a job to queue, written out.
    insert_now <= s_valid and ((s_flags(F_FILL) and not busy_fill) or go_other);
    job_push   <= s_valid and ((s_flags(F_ENDS) and job_room) or go_other);

    -- The job a beat queues: a later cell row, or a row-end beat that closes the row,
    -- drains the bank filled so far; an end of frame drains the open row's bank, if a
    -- record opened one, then emits itself.
    job_new.drain <= s_flags(F_SWITCH) or row_open;
    job_new.bank  <= fill_bank;
    job_new.eof   <= s_eof;
    job_new.x     <= s_x;
    job_new.y     <= s_y;

    -- A job that drains a bank is queued with the bank being filled, and the next
    -- record then fills the other bank: the fill bank changes exactly then. (The fill
    -- bank is free while a record of its row is in: busy_fill is clear when it turns.)
    turn <= job_push and job_new.drain;

    control : process (clk) is

      variable clear_fill  : std_logic; -- the drain of the fill bank ends
      variable clear_other : std_logic; -- the drain of the other bank ends
      variable still       : std_logic; -- the clear goes on next clock
      variable level       : std_logic_vector(0 to JOB_SLOTS - 1);

    begin

      if rising_edge(clk) then
        -- A record about to open a cell row: its bank is free, so its row may be set
        -- before the record is taken (and is set again when it is).
        if s_valid = '1' and s_flags(F_INSERT) = '1' and s_flags(F_FIRST) = '1' and bank_free = '1' then
          bank_y0(target)  <= s_y0;
          bank_log(target) <= s_log;
        end if;
        if insert_now = '1' then
          row_open <= '1';
        end if;
        -- (With K = 0 no row is open.)
        if job_push = '1' and s_flags(F_ENDS) = '1' then
          row_open <= '0';
        end if;
        if turn = '1' then
          fill_bank <= 1 - fill_bank;
        end if;

        if job_push = '1' then
          jobs(to_integer(job_tail)) <= job_new;
          job_tail                   <= (job_tail(1) xor job_tail(0)) & not job_tail(0);
        end if;
        if job_pop = '1' then
          job_head <= (job_head(1) xor job_head(0)) & not job_head(0);
        end if;

        -- The busy flags, relative to the fill bank.
        clear_fill  := job_pop and d_drains(fill_bank);
        clear_other := job_pop and d_drains(1 - fill_bank);
        if turn = '1' then
          busy_fill  <= busy_other and not clear_other;
          busy_other <= '1';
        else
          busy_fill  <= busy_fill and not clear_fill;
          busy_other <= busy_other and not clear_other;
        end if;

        -- The count of jobs as a thermometer code: no carry chain.
        level := job_level;
        if job_push = '1' and job_pop = '0' then
          level := '1' & job_level(0 to JOB_SLOTS - 2);
        elsif job_push = '0' and job_pop = '1' then
          level := job_level(1 to JOB_SLOTS - 1) & '0';
        end if;
        job_level <= level;

        -- While the memory clears: the queue full, no job idle (no beat passes).
        still     := clearing and not clear_end;
        job_room  <= not level(JOB_SLOTS - 1) and not still;
        jobs_idle <= not job_level(0) and d_idle and not job_push and not still;
        if clearing = '1' and clear_end = '1' then
          busy_fill  <= '0';
          busy_other <= '0';
        end if;

        if rst = '1' then
          fill_bank  <= 0;
          row_open   <= '0';
          jobs_idle  <= '0';
          busy_fill  <= '1';
          busy_other <= '1';
          job_head   <= "00";
          job_tail   <= "00";
          job_level  <= (others => '0');
          job_room   <= '0';
        end if;
      end if;

    end process control;

    -- ---- stages A to D: read, choose the base word, compare, insert and write back ------

    s_entry <= '1' & std_logic_vector(s_score) & s_offset;

    insert : entity work.fastnms_budget_insert
      generic map (
        CELLS      => CELLS,
        SCORE_BITS => SCORE_BITS,
        K_MAX      => K_MAX
      )
      port map (
        clk         => clk,
        rst         => rst,
        in_valid    => insert_now,
        in_open     => s_flags(F_FIRST),
        in_bank     => target,
        in_cell     => s_cell,
        in_entry    => s_entry,
        in_keep     => s_k,
        rd_data_0   => rd_data(0),
        rd_data_1   => rd_data(1),
        wr_valid    => c_valid,
        wr_bank     => c_bank,
        wr_cell     => c_cell,
        wr_word     => c_new,
        last_cell_0 => bank_hi(0),
        last_cell_1 => bank_hi(1)
      );

    -- ---- reset: both banks emptied, one word of each per clock -------------------------

    clear : process (clk) is
    begin

      if rising_edge(clk) then
        if clearing = '1' then
          if clear_end = '1' then
            clearing <= '0';
          end if;
          clear_at  <= clear_at + 1;
          clear_end <= to_sl(to_integer(clear_at) = CELLS - 2);
        end if;
        if rst = '1' then
          clearing  <= '1';
          clear_at  <= (others => '0');
          clear_end <= to_sl(CELLS = 1);
        end if;
      end if;

    end process clear;

    -- ---- drain: the head job's bank cell by cell (read, wait for the output register,
    -- load and empty, entries one per clock), then its end of frame. A drain starts two
    -- clocks after its job (settle): the bank's last record, four stages behind the
    -- beat that queued the job, has written its word by the first read --------------

    drain : process (clk) is

      variable head  : job_t;
      variable spent : std_logic; -- d_emit: the cell has no entry left

    begin

      if rising_edge(clk) then
        -- Registered a clock ahead: d_cell changes three clocks before d_emit.
        d_last <= to_sl(d_cell = d_hi);
        d_next <= d_cell + 1;
        d_x0   <= shift_left(resize(d_cell, X_BITS), d_log + 4);

        head  := jobs(to_integer(job_head));
        spent := not valid_of(entry(d_word, 0, ENTRY_BITS));

        if d_idle = '1' and job_level(0) = '1' then
          d_job  <= head;
          d_cell <= (others => '0');

          for b in 0 to 1 loop

            d_drains(b) <= head.drain and to_sl(head.bank = b);

          end loop;

        end if;
        if d_settle = '1' then
          d_log <= bank_log(d_job.bank);
          d_y0  <= bank_y0(d_job.bank);
          d_hi  <= bank_hi(d_job.bank);
        end if;
        if d_load = '1' then
          d_word <= rd_data(d_job.bank);
        end if;
        if d_emit = '1' then
          if spent = '1' and d_last = '0' then
            d_cell <= d_next;
          elsif spent = '0' and o_ready = '1' then
            d_word <= drop_first(d_word, ENTRY_BITS);
          end if;
        end if;

        -- The states: idle, then for a drain settle, settle_2, and per cell read, wait,
        -- load, emit (one entry per clock the output takes); an end of frame at the end.
        d_idle     <= (d_idle and not job_level(0)) or (d_emit and spent and d_last and not d_job.eof)
                      or (d_eof and o_ready);
        d_settle   <= d_idle and job_level(0) and head.drain;
        d_settle_2 <= d_settle;
        d_read     <= d_settle_2 or (d_emit and spent and not d_last);
        d_wait     <= d_read;
        d_load     <= d_wait;
        d_emit     <= d_load or (d_emit and not spent);
        d_eof      <= (d_idle and job_level(0) and not head.drain)
                      or (d_emit and spent and d_last and d_job.eof) or (d_eof and not o_ready);

        if rst = '1' then
          d_idle     <= '1';
          d_settle   <= '0';
          d_settle_2 <= '0';
          d_read     <= '0';
          d_wait     <= '0';
          d_load     <= '0';
          d_emit     <= '0';
          d_eof      <= '0';
        end if;
      end if;

    end process drain;

    -- A job ends with its end-of-frame beat, or (without one) after its last cell.
    job_pop <= (d_eof and o_ready)
               or (d_emit and not valid_of(entry(d_word, 0, ENTRY_BITS)) and d_last and not d_job.eof);

    outputs : process (all) is

      variable e : entry_t;

    begin

      e := entry(d_word, 0, ENTRY_BITS);

      if pass = '1' then
        o_valid <= '1';
        o_beat  <= s_beat;
      elsif d_eof = '1' then
        o_valid <= '1';
        o_beat  <= pack('1', d_job.x, d_job.y, to_unsigned(0, SCORE_BITS));
      else
        o_valid <= d_emit and valid_of(e);
        o_beat  <= pack('0', d_x0 or resize(unsigned(e(7 downto 0)), X_BITS),
                        d_y0 or resize(unsigned(e(15 downto 8)), Y_BITS), score_of(e));
      end if;

    end process outputs;

    -- ---- memories: each bank is filled (stages A to D), drained, or cleared ------------

    ports : process (all) is

      variable owns : std_logic;

    begin

      for b in 0 to 1 loop

        -- (While the drain settles, the bank's last record writes its word.)
        owns := not (d_idle or d_settle or d_settle_2) and d_drains(b);

        -- Reads run every clock (the read pipeline's enable): a read has no effect.
        rd_en(b) <= '1';

        if owns = '1' then
          rd_addr(b) <= d_cell;
          wr_en(b)   <= d_load;
          wr_addr(b) <= d_cell;
        else
          rd_addr(b) <= s_cell;
          wr_en(b)   <= (c_valid and to_sl(c_bank = b)) or clearing;
          wr_addr(b) <= clear_at when clearing = '1' else
                        c_cell;
        end if;

        -- Draining and clearing write an empty word: only its valid bits matter.
        if empty(b) = '1' then
          wr_data(b) <= emptied(c_new, ENTRY_BITS);
        else
          wr_data(b) <= c_new;
        end if;

      end loop;

    end process ports;

    -- Registered a clock ahead: the drain writes its bank in d_load (after d_wait),
    -- the clear while clearing (never with a record in the pipeline).
    empty_flags : process (clk) is
    begin

      if rising_edge(clk) then

        for b in 0 to 1 loop

          empty(b) <= d_wait and d_drains(b);
          if clearing = '1' and clear_end = '0' then
            empty(b) <= '1';
          end if;

        end loop;

        if rst = '1' then
          empty <= "11";
        end if;
      end if;

    end process empty_flags;

    memories : for b in 0 to 1 generate

      bank : entity work.fastnms_ram_sdp
        generic map (
          DEPTH        => CELLS,
          WIDTH        => WORD_BITS,
          READ_LATENCY => 2,
          STYLE        => "block"
        )
        port map (
          clk     => clk,
          wr_en   => wr_en(b),
          wr_addr => wr_addr(b),
          wr_data => wr_data(b),
          rd_en   => rd_en(b),
          rd_addr => rd_addr(b),
          rd_data => rd_data(b)
        );

    end generate memories;

  end generate budget;

end architecture rtl;
