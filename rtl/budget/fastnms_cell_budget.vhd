-- Keypoint budget per grid cell (golden/budget.py): of a frame's records, at
-- most K per CELL x CELL cell, the best scores, a tie to the record first in
-- raster order. Cells start at the image origin; CELL is 16 .. 256, K 0 .. 15
-- (0: every record passes, in order).
--
-- Input: records (in_x, in_y, in_score, in_eof = '0') in raster order (the
-- 3x3 NMS and "none" emit them so; not the region NMS), then one end-of-frame
-- beat (in_eof = '1', in_x/in_y the frame's last pixel). Every beat carries
-- the configuration, in_cell_log (log2(CELL) - 4, above 4 read as 4) and
-- in_per_cell (K, above MAX_PER_CELL read as MAX_PER_CELL); the values of a
-- frame's first beat apply to the whole frame. Optional row-end beats
-- (in_row_end = '1', in_eof = '0', not records) promise that every record of
-- the lines up to in_y has come: the one at a cell row's last line starts
-- that row's drain then (the core's NMS sends one every 16 lines).
--
-- Output: with K > 0, a cell row's kept records once the row is complete (at
-- its last line's row-end beat, the first record of a later cell row, or the
-- end of frame): cells left to right, best first within a cell; then the
-- end-of-frame beat. With K = 0 the records and end of frame pass in order.
-- Row-end beats never leave the block.
--
-- How (docs/fastnms_cell_budget.md): the best K of each cell of the cell row
-- being filled are kept sorted in one memory word per cell (K entries of a
-- valid bit, score and position in the cell, fastnms_budget_pkg), updated at
-- one record per clock by fastnms_budget_insert (read, compare, insert, write
-- back). Two banks: a complete cell row drains from one
-- (which also empties its words) while the next fills the other. Jobs (drain a
-- bank, emit an end of frame) queue in order, four at most.
--
-- The input waits (a) while the memory is cleared after reset
-- (ceil(MAX_WIDTH / 16) clocks); (b) when a record opens a cell row while the
-- other bank still drains (a drain takes 5 + 4 clocks per cell up to the last cell
-- written plus one per record; without row-end beats it starts at the first
-- record of the next cell row: the output held back, sparse rows without
-- row-end beats, or frames back to back), or the job queue is full; (c) with
-- K = 0, while the previous frame's jobs are not done.
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
    -- The input beat after decoding, as the input buffer holds it.
    constant D_BITS : positive := BEAT_BITS + 3 + 4 + 4 + Y_BITS + ADDR_BITS + 16;

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

    -- The bits of a coordinate inside a cell of 16 << log pixels.
    function cell_mask (log : log_t) return unsigned is
    begin

      return shift_right(to_unsigned(255, 16), 4 - log);

    end function cell_mask;

    -- Input side: the frame's configuration (its first beat's), the last record's line.
    signal i_take    : std_logic;
    signal i_ready   : std_logic;
    signal i_started : std_logic;
    signal i_open    : std_logic; -- a record went in since the frame's start or the last close
    signal i_close   : std_logic; -- the beat is a row-end beat that closes the open cell row
    signal i_log     : log_t;
    signal i_k       : natural range 0 to K_MAX;
    signal i_in_cell : unsigned(15 downto 0); -- cell_mask(i_log), registered with it
    signal i_last_y  : unsigned(Y_BITS - 1 downto 0);
    signal i_data    : std_logic_vector(D_BITS - 1 downto 0);

    -- The decoded beat, out of the input buffer.
    signal s_valid  : std_logic;
    signal s_ready  : std_logic;
    signal s_data   : std_logic_vector(D_BITS - 1 downto 0);
    signal s_beat   : beat_t;
    signal s_eof    : std_logic;
    signal s_x      : unsigned(X_BITS - 1 downto 0);
    signal s_y      : unsigned(Y_BITS - 1 downto 0);
    signal s_score  : unsigned(SCORE_BITS - 1 downto 0);
    signal s_log    : log_t;
    signal s_k      : natural range 0 to K_MAX;
    signal s_pass   : std_logic;       -- K = 0: the beat passes
    signal s_switch : std_logic;       -- a record of a later cell row than the last record
    signal s_open   : std_logic;       -- a record with no cell row open (the frame's first, or after a close)
    signal s_marker : std_logic;       -- a row-end beat
    signal s_close  : std_logic;       -- a row-end beat that closes the open cell row
    signal s_y0     : unsigned(Y_BITS - 1 downto 0); -- the first line of the record's cell row
    signal s_cell   : addr_t;
    signal s_offset : std_logic_vector(15 downto 0); -- y and x inside the cell

    -- Decision.
    signal take       : std_logic;
    signal pass       : std_logic;
    signal target     : bank_t;
    signal insert_now : std_logic;

    -- Banks.
    signal row_open  : std_logic;                -- a record of this frame went in
    signal fill_bank : bank_t;
    signal busy      : std_logic_vector(0 to 1); -- a drain of the bank is queued or running
    signal bank_y0   : y_pair_t;
    signal bank_log  : log_pair_t;

    -- Jobs.
    signal jobs      : jobs_t;
    signal job_head  : natural range 0 to JOB_SLOTS - 1;
    signal job_tail  : natural range 0 to JOB_SLOTS - 1;
    signal job_count : natural range 0 to JOB_SLOTS;
    signal job_push  : std_logic;
    signal job_new   : job_t;
    signal job_pop   : std_logic;
    signal jobs_idle : std_logic; -- registered: no job queued or running, none pushed

    -- The insertion pipeline's record, its write and the banks' last cells written.
    signal s_first : std_logic; -- the record opens a cell row
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

    -- Reset clear.
    signal clearing : std_logic;
    signal clear_at : addr_t;

    -- Drain.
    type drain_state_t is (st_idle, st_settle, st_read, st_wait, st_load, st_emit, st_eof);

    signal d_state : drain_state_t;
    signal d_job   : job_t;
    signal d_cell  : addr_t;
    signal d_x0    : unsigned(X_BITS - 1 downto 0); -- the first column of the cell
    signal d_word  : word_t;
    signal d_last  : std_logic;                     -- d_cell is the bank's last cell

  begin

    -- ---- input side: decode each beat with its frame's configuration --------------------

    i_take <= in_valid and i_ready;

    decode : process (all) is

      variable log      : log_t;
      variable k        : natural range 0 to K_MAX;
      variable mask     : unsigned(15 downto 0);
      variable y_wide   : unsigned(15 downto 0);
      variable x_wide   : unsigned(15 downto 0);
      variable a_record : std_logic;
      variable later    : std_logic;
      variable closed   : std_logic;

    begin

      if i_started = '1' then
        log := i_log;
        k   := i_k;
      else
        log := minimum(4, to_integer(in_cell_log));
        k   := minimum(K_MAX, to_integer(in_per_cell));
      end if;

      mask     := cell_mask(log);
      y_wide   := resize(in_y, 16);
      x_wide   := resize(in_x, 16);
      a_record := not in_eof and not in_row_end;
      -- A later cell row than the last record's: a differing bit of y above the cell's
      -- (raster order: never before).
      -- (A cell row is open only after the frame's first beat: the registered mask holds.)
      later := i_open and to_sl(((y_wide xor resize(i_last_y, 16)) and not i_in_cell) /= 0);
      -- A row-end beat closes the open cell row at its last line (or past it).
      closed  := i_open and in_row_end and
                 (later or to_sl((y_wide(7 downto 0) or not i_in_cell(7 downto 0)) = x"FF"));
      i_close <= closed;
      i_data  <= pack(in_eof, in_x, in_y, in_score)
                 & std_logic_vector(to_unsigned(log, 3)) & std_logic_vector(to_unsigned(k, 4))
                 & (later and a_record) & (not i_open and a_record) & in_row_end & closed
                 & std_logic_vector(resize(y_wide and not mask, Y_BITS))
                 & std_logic_vector(resize(shift_right(x_wide, log + 4), ADDR_BITS))
                 & std_logic_vector(y_wide(7 downto 0) and mask(7 downto 0))
                 & std_logic_vector(x_wide(7 downto 0) and mask(7 downto 0));

    end process decode;

    input_side : process (clk) is
    begin

      if rising_edge(clk) then
        if i_take = '1' then
          i_started <= not in_eof;
          if in_eof = '0' and in_row_end = '0' then
            i_open   <= '1';
            i_last_y <= in_y;
          end if;
          if in_eof = '1' or i_close = '1' then
            i_open <= '0';
          end if;
          if i_started = '0' then
            i_log     <= minimum(4, to_integer(in_cell_log));
            i_in_cell <= cell_mask(minimum(4, to_integer(in_cell_log)));
            i_k       <= minimum(K_MAX, to_integer(in_per_cell));
          end if;
        end if;
        if rst = '1' then
          i_started <= '0';
          i_open    <= '0';
        end if;
      end if;

    end process input_side;

    input_buffer : entity work.fastnms_skid_buffer
      generic map (
        WIDTH => D_BITS
      )
      port map (
        clk       => clk,
        rst       => rst,
        in_valid  => in_valid,
        in_ready  => i_ready,
        in_data   => i_data,
        out_valid => s_valid,
        out_ready => s_ready,
        out_data  => s_data
      );

    in_ready <= i_ready;

    s_beat   <= s_data(D_BITS - 1 downto D_BITS - BEAT_BITS);
    s_eof    <= s_beat(BEAT_BITS - 1);
    s_x      <= unsigned(s_beat(BEAT_BITS - 2 downto Y_BITS + SCORE_BITS));
    s_y      <= unsigned(s_beat(Y_BITS + SCORE_BITS - 1 downto SCORE_BITS));
    s_score  <= unsigned(s_beat(SCORE_BITS - 1 downto 0));
    s_log    <= to_integer(unsigned(s_data(D_BITS - BEAT_BITS - 1 downto D_BITS - BEAT_BITS - 3)));
    s_k      <= to_integer(unsigned(s_data(D_BITS - BEAT_BITS - 4 downto D_BITS - BEAT_BITS - 7)));
    s_switch <= s_data(D_BITS - BEAT_BITS - 8);
    s_open   <= s_data(D_BITS - BEAT_BITS - 9);
    s_marker <= s_data(D_BITS - BEAT_BITS - 10);
    s_close  <= s_data(D_BITS - BEAT_BITS - 11);
    s_y0     <= unsigned(s_data(Y_BITS + ADDR_BITS + 15 downto ADDR_BITS + 16));
    s_cell   <= unsigned(s_data(ADDR_BITS + 15 downto 16));
    s_offset <= s_data(15 downto 0);
    s_pass   <= to_sl(s_k = 0);

    -- ---- decision ---------------------------------------------------------------------------

    target <= 1 - fill_bank when s_switch = '1' else
              fill_bank;

    -- A row-end beat goes, closing its row needs a place in the queue; K = 0 passes
    -- the beat once no job is left; a record needs its bank free (and, opening a cell
    -- row, a place in the queue); an end of frame a place in the queue.
    decide : process (all) is
    begin

      pass <= '0';
      take <= '0';

      if s_valid = '1' and clearing = '0' then
        if s_marker = '1' then
          take <= not s_close or s_pass or to_sl(job_count < JOB_SLOTS);
        elsif s_pass = '1' then
          pass <= jobs_idle;
          take <= jobs_idle and o_ready;
        elsif s_eof = '1' then
          take <= to_sl(job_count < JOB_SLOTS);
        else
          take <= not busy(target) and to_sl(s_switch = '0' or job_count < JOB_SLOTS);
        end if;
      end if;

    end process decide;

    s_ready    <= take;
    insert_now <= take and not s_pass and not s_eof and not s_marker;

    -- The job a beat queues: a later cell row, or a row-end beat that closes the row,
    -- drains the bank filled so far; an end of frame drains the open row's bank, if a
    -- record opened one, then emits itself.
    job_new.drain <= s_switch when s_eof = '0' and s_marker = '0' else
                     row_open;
    job_new.bank  <= fill_bank;
    job_new.eof   <= s_eof;
    job_new.x     <= s_x;
    job_new.y     <= s_y;
    job_push      <= take and not s_pass and (s_switch or s_eof or s_close);

    control : process (clk) is
    begin

      if rising_edge(clk) then
        if insert_now = '1' and (s_open or s_switch) = '1' then
          fill_bank <= target;
        end if;
        -- A record about to open a cell row: its bank is free, so its row may be set
        -- before the record is taken (and is set again when it is).
        if s_valid = '1' and s_pass = '0' and s_eof = '0' and s_marker = '0' and (s_open or s_switch) = '1'
           and busy(target) = '0' then
          bank_y0(target)  <= s_y0;
          bank_log(target) <= s_log;
        end if;
        jobs_idle <= to_sl(job_count = 0 and d_state = st_idle) and not job_push;
        if insert_now = '1' then
          row_open <= '1';
        end if;
        if take = '1' and (s_eof or s_close) = '1' then
          row_open <= '0';
          if s_pass = '0' and row_open = '1' then
            fill_bank <= 1 - fill_bank;
          end if;
        end if;

        if job_push = '1' then
          jobs(job_tail) <= job_new;
          job_tail       <= (job_tail + 1) mod JOB_SLOTS;
          if job_new.drain = '1' then
            busy(job_new.bank) <= '1';
          end if;
        end if;
        if job_pop = '1' then
          job_head <= (job_head + 1) mod JOB_SLOTS;
          if d_job.drain = '1' then
            busy(d_job.bank) <= '0';
          end if;
        end if;
        if job_push = '1' and job_pop = '0' then
          job_count <= job_count + 1;
        elsif job_push = '0' and job_pop = '1' then
          job_count <= job_count - 1;
        end if;

        if rst = '1' then
          fill_bank <= 0;
          row_open  <= '0';
          jobs_idle <= '0';
          busy      <= "00";
          job_head  <= 0;
          job_tail  <= 0;
          job_count <= 0;
        end if;
      end if;

    end process control;

    -- ---- stages A to C: read, compare, insert, write back -------------------------------

    s_first <= s_open or s_switch;
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
        in_open     => s_first,
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
          if clear_at = CELLS - 1 then
            clearing <= '0';
          end if;
          clear_at <= clear_at + 1;
        end if;
        if rst = '1' then
          clearing <= '1';
          clear_at <= (others => '0');
        end if;
      end if;

    end process clear;

    -- ---- drain: the head job's bank cell by cell (read, wait for the output register,
    -- load and empty, entries one per clock), then its end of frame. A drain starts a
    -- clock after its job (settle): the bank's last record, three stages behind the
    -- beat that queued the job, has written its word by the first read --------------

    d_last <= to_sl(d_cell = bank_hi(d_job.bank));

    drain : process (clk) is
    begin

      if rising_edge(clk) then
        -- An if chain, not a case: GHDL's netlist of a case on an enumeration maps to latches.
        if d_state = st_idle then
          if job_count /= 0 then
            d_job  <= jobs(job_head);
            d_cell <= (others => '0');
            d_x0   <= (others => '0');
            if jobs(job_head).drain = '1' then
              d_state <= st_settle;
            else
              d_state <= st_eof;
            end if;
          end if;
        elsif d_state = st_settle then
          d_state <= st_read;
        elsif d_state = st_read then
          d_state <= st_wait;
        elsif d_state = st_wait then
          d_state <= st_load;
        elsif d_state = st_load then
          d_word  <= rd_data(d_job.bank);
          d_state <= st_emit;
        elsif d_state = st_emit then
          if valid_of(entry(d_word, 0, ENTRY_BITS)) = '0' then
            if d_last = '1' then
              if d_job.eof = '1' then
                d_state <= st_eof;
              else
                d_state <= st_idle;
              end if;
            else
              d_cell  <= d_cell + 1;
              d_x0    <= d_x0 + shift_left(to_unsigned(16, X_BITS), bank_log(d_job.bank));
              d_state <= st_read;
            end if;
          elsif o_ready = '1' then
            d_word <= drop_first(d_word, ENTRY_BITS);
          end if;
        elsif o_ready = '1' then -- st_eof
          d_state <= st_idle;
        end if;

        if rst = '1' then
          d_state <= st_idle;
        end if;
      end if;

    end process drain;

    -- A job ends with its end-of-frame beat, or (without one) after its last cell.
    job_pop <= (to_sl(d_state = st_eof) and o_ready)
               or (to_sl(d_state = st_emit) and not valid_of(entry(d_word, 0, ENTRY_BITS))
                   and d_last and not d_job.eof);

    outputs : process (all) is

      variable e : entry_t;

    begin

      e := entry(d_word, 0, ENTRY_BITS);

      if pass = '1' then
        o_valid <= '1';
        o_beat  <= s_beat;
      elsif d_state = st_eof then
        o_valid <= '1';
        o_beat  <= pack('1', d_job.x, d_job.y, to_unsigned(0, SCORE_BITS));
      else
        o_valid <= to_sl(d_state = st_emit) and valid_of(e);
        o_beat  <= pack('0', d_x0 or resize(unsigned(e(7 downto 0)), X_BITS),
                        bank_y0(d_job.bank) or resize(unsigned(e(15 downto 8)), Y_BITS), score_of(e));
      end if;

    end process outputs;

    -- ---- memories: each bank is filled (stages A to C), drained, or cleared ------------

    ports : process (all) is

      variable owns : std_logic;

    begin

      for b in 0 to 1 loop

        -- (While the drain settles, the bank's last record writes its word.)
        owns := to_sl(d_state /= st_idle and d_state /= st_settle and d_job.drain = '1' and d_job.bank = b);

        -- Reads run every clock (the read pipeline's enable): a read has no effect.
        rd_en(b) <= '1';

        if owns = '1' then
          rd_addr(b) <= d_cell;
          wr_en(b)   <= to_sl(d_state = st_load);
          wr_addr(b) <= d_cell;
        else
          rd_addr(b) <= s_cell;
          wr_en(b)   <= (c_valid and to_sl(c_bank = b)) or clearing;
          wr_addr(b) <= clear_at when clearing = '1' else
                        c_cell;
        end if;

        -- Draining and clearing write an empty word: only its valid bits matter.
        if owns = '1' or clearing = '1' then
          wr_data(b) <= emptied(c_new, ENTRY_BITS);
        else
          wr_data(b) <= c_new;
        end if;

      end loop;

    end process ports;

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
