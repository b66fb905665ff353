-- The region NMS's clock schedule: which side steps each clock (the current
-- row, the previous row's reader, the flush, the PRIME clocks) and where each
-- side is; the row memory, read two columns ahead.
-- Datasheet: docs/fastnms_nms_region.md
-- Contract: docs/design/region_nms_pipeline.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_nms_region_pkg.all;

entity fastnms_nms_region_schedule is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 4095
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- The pixel after the input buffer; px_ready says the current row steps.
    px_valid  : in    std_logic;
    px_ready  : out   std_logic;
    px_corner : in    std_logic;
    px_width  : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    px_sof    : in    std_logic;
    px_eol    : in    std_logic;
    px_eof    : in    std_logic;
    -- The record FIFO has room for the records in flight: every step waits for it.
    rec_room : in    std_logic;
    -- This clock's steps and where both sides are (step_t).
    step : out   step_t(cx(clog2(MAX_WIDTH) - 1 downto 0), cy(bits_for(MAX_HEIGHT) - 1 downto 0),
                        ahead_slot(slot_bits(MAX_WIDTH) - 1 downto 0))
  );
end entity fastnms_nms_region_schedule;

architecture rtl of fastnms_nms_region_schedule is

  constant XB : positive := clog2(MAX_WIDTH);
  constant YB : positive := bits_for(MAX_HEIGHT);
  constant WB : positive := bits_for(MAX_WIDTH);
  constant SB : positive := slot_bits(MAX_WIDTH);

  -- Current row.
  signal cx_r        : unsigned(XB - 1 downto 0);
  signal cy_r        : unsigned(YB - 1 downto 0);
  signal cw          : unsigned(WB - 1 downto 0);
  signal first_row_r : std_logic;
  signal frame_start : std_logic;
  signal cm_r        : std_logic;

  -- Reader of the previous row: its column, its row's last column, the
  -- prefetched bits (pm at rcol - 1, p0 at rcol; the row memory's output is
  -- the bit at rcol + 1, or at column 0 of the next row after the last) and
  -- the row memory address it reads next, (rcol + 2) mod its width.
  signal rcol          : unsigned(XB - 1 downto 0);
  signal r_lastcol     : unsigned(XB - 1 downto 0);
  signal r_ahead       : unsigned(XB - 1 downto 0);
  signal pm_r          : std_logic;
  signal p0_r          : std_logic;
  signal flushing      : std_logic;
  signal flush_pending : std_logic;
  signal flush_w       : unsigned(WB - 1 downto 0);
  signal primed        : std_logic;
  signal prime_st      : unsigned(1 downto 0);
  -- cx is the row's penultimate column, and r_ahead >= 2, as registers
  -- (the row memory's read address is chosen on registers only); c_prepen
  -- is the column before the penultimate.
  signal c_prepen    : unsigned(XB - 1 downto 0);
  signal c_at_penult : std_logic;
  signal r_reads     : std_logic;
  signal r_slot0_r   : std_logic;
  signal r_col0_r    : std_logic; -- rcol = 0
  signal r_col1_r    : std_logic; -- rcol = 1
  signal r_col2_r    : std_logic; -- rcol = 2
  signal cur_bank_r  : std_logic;
  signal r_bank_r    : std_logic;

  -- The row memory: its write (the current pixel, in its own clock) and its
  -- read. It holds two columns per word (yosys maps a one-bit LUT RAM to
  -- RAM64M cells using one of their three bits): the even column's bit of
  -- the pair being written, and the column of the word being read.
  signal row_we    : std_logic;
  signal row_wa    : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal row_wd    : std_logic;
  signal row_re    : std_logic;
  signal row_ra    : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal row_rd    : std_logic;
  signal row_wdata : std_logic_vector(1 downto 0);
  signal row_word  : std_logic_vector(1 downto 0);
  signal row_even  : std_logic;
  signal row_lane  : std_logic;

  -- This clock's steps: the flush, the current row, both in lock-step (a row
  -- >= 1), the reader (lock-step or flush), a first row's last two columns
  -- priming the reader.
  signal flush_go  : std_logic;
  signal cur_go    : std_logic;
  signal cstep_i   : std_logic;
  signal lock_i    : std_logic;
  signal rstep_i   : std_logic;
  signal r_last_r  : std_logic; -- r_ahead = 1, predicted
  signal checks_on : boolean;   -- false until the first reset: the invariants hold from then on
  -- The row memory's last column written (simulation only: the order is asserted).
  signal row_last_wa : integer range -1 to MAX_WIDTH := -1;
  signal r_next      : unsigned(XB - 1 downto 0);
  signal f_prime     : std_logic;
  signal row_next0   : std_logic; -- this clock reads the next row's column 0
  signal holds0      : std_logic; -- the row memory's output is that bit
  signal ahead_slot  : unsigned(SB - 1 downto 0);

begin

  assert MAX_WIDTH >= 3
    report "fastnms_nms_region_schedule: MAX_WIDTH must be at least 3"
    severity failure;

  step <=
  (
    cstep      => cstep_i,
    rstep      => rstep_i,
    lock       => lock_i,
    flush_ends => flush_go and r_last_r,
    first_row  => first_row_r,
    cm         => cm_r,
    cx         => cx_r,
    cy         => cy_r,
    cur_bank   => cur_bank_r,
    pm         => pm_r,
    p0         => p0_r,
    r_last     => r_last_r,
    r_col0     => r_col0_r,
    r_col1     => r_col1_r,
    r_col2     => r_col2_r,
    r_slot0    => r_slot0_r,
    r_bank     => r_bank_r,
    ahead_slot => ahead_slot
  );

  -- The flush steps whenever the record FIFO has room. The current row steps
  -- with room too; rows >= 1 need the reader free and primed; a first row
  -- steps with the flush, so it never overtakes it, and its last column
  -- waits for the flush's last (it writes the slot of the next column, which
  -- a wider flush still reads).
  flush_go <= flushing and rec_room;

  current_row_may_step : process (all) is
  begin

    if first_row_r = '1' then
      if flush_pending = '1' then
        cur_go <= '0';
      elsif flushing = '0' then
        cur_go <= rec_room;
      elsif px_eol = '0' or r_last_r = '1' then
        -- In step with the flush, which started first and steps whenever
        -- the row can: the row stays at or behind it (asserted below).
        cur_go <= rec_room;
      else
        cur_go <= '0';
      end if;
    else
      cur_go <= rec_room and primed and not flushing and not flush_pending;
    end if;

  end process current_row_may_step;

  px_ready <= cur_go;
  -- The current pixel goes into the row memory in its own clock, so a read
  -- two columns later (the next row's first columns) finds it there.
  row_we  <= cstep_i;
  row_wa  <= cx_r;
  row_wd  <= px_corner;
  cstep_i <= cur_go and px_valid;
  -- Written out from registers (the same as cstep and not first_row, and
  -- lock or flush_go), one LUT each: every reader register and operation
  -- bit depends on them.
  lock_i  <= rec_room and px_valid and primed and not flushing and not flush_pending and
             not first_row_r;
  rstep_i <= rec_room and (flushing or
                           (px_valid and primed and not flush_pending and not first_row_r));
  r_next  <= (others => '0') when r_last_r = '1' else
             rcol + 1;
  -- A first row reads the next row's first two columns in its last two (the
  -- row memory then holds them); PRIME does the same when a flush held the
  -- port then.
  f_prime <= cstep_i and first_row_r and (c_at_penult or px_eol) and not flushing;
  -- The tables are read at the row memory's column, two ahead of the reader;
  -- in its row's last two columns that is slot 0 of the next row (whose head
  -- bit is never read: r_slot0).
  ahead_slot <= slot_of(r_ahead, SB);

  reads : process (all) is
  begin

    -- The address is from registers only (the enable says whether a read
    -- happens): the reader's read two columns ahead (a lock-step row, or a
    -- flush still inside its row), or a read of the next row's column 0
    -- (a first row's penultimate column, PRIME's first clock) or 1.
    row_next0 <= '0';
    row_ra    <= resize(r_ahead, row_ra'length);

    if prime_st = 1 then
      row_ra    <= (others => '0');
      row_next0 <= '1';
    elsif prime_st = 2 then
      row_ra <= to_unsigned(1, row_ra'length);
    elsif first_row_r = '1' and (flushing = '0' or r_reads = '0') then
      if c_at_penult = '1' then
        row_ra    <= (others => '0');
        row_next0 <= '1';
      else
        row_ra <= to_unsigned(1, row_ra'length);
      end if;
    end if;

    row_re <= '0';

    if rstep_i = '1' then
      -- A flush does not read past its row.
      row_re <= lock_i or r_reads;
    elsif f_prime = '1' or prime_st /= 0 then
      row_re <= '1';
    end if;

    -- The same clock's first row step, when the flush's own read is over.
    if rstep_i = '1' and lock_i = '0' and r_reads = '0' and cstep_i = '1' and
       first_row_r = '1' and (c_at_penult = '1' or px_eol = '1') then
      row_re <= '1';
    end if;

  end process reads;

  -- The positions of both sides, the flush and the priming of the reader.
  positions : process (clk) is

    variable c_eol      : boolean;
    variable flush_last : boolean;
    variable eof_step   : boolean;
    variable v_primed   : std_logic;

  begin

    if rising_edge(clk) then
      c_eol := px_eol = '1';

      -- synthesis translate_off
      if rst = '1' then
        checks_on <= true;
      end if;
      assert not checks_on or rst = '1' or
             (r_last_r = to_sl(r_ahead = 1) and r_col0_r = to_sl(rcol = 0) and
              r_slot0_r = to_sl(rcol < 2) and r_col1_r = to_sl(rcol = 1) and r_col2_r = to_sl(rcol = 2))
        report "fastnms_nms_region: r_last, r_col0, r_col1, r_col2 or r_slot0 out of step"
        severity failure;
      assert not checks_on or rst = '1' or
             (r_reads = to_sl(r_ahead >= 2) and (frame_start = '1' or c_at_penult = to_sl(cx_r = c_prepen + 1)))
        report "fastnms_nms_region: r_reads or c_at_penult out of step"
        severity failure;
      assert not (cstep_i = '1' and first_row_r = '1' and flushing = '1' and cx_r > rcol)
        report "fastnms_nms_region: a first row overtaking the flush"
        severity failure;
      assert not (lock_i = '1' and rcol /= cx_r)
        report "fastnms_nms_region: reader and current row out of step"
        severity failure;
      assert not (lock_i = '1' and rstep_i /= cstep_i)
        report "fastnms_nms_region: a lock-step row with one side stepping"
        severity failure;
      assert lock_i = (cstep_i and not first_row_r) and rstep_i = (lock_i or flush_go)
        report "fastnms_nms_region: lock or rstep out of step"
        severity failure;
      -- synthesis translate_on

      -- Current row position.
      if cstep_i = '1' then
        if frame_start = '1' then
          cw       <= px_width;
          c_prepen <= resize(px_width - 3, XB);
        end if;
        -- Widths are at least 3: column 0 is never the penultimate.
        if c_eol then
          c_at_penult <= '0';
        elsif frame_start = '1' then
          c_at_penult <= to_sl(px_width = 3);
        else
          c_at_penult <= to_sl(cx_r = c_prepen);
        end if;
        frame_start <= px_eof;
        if c_eol then
          cm_r <= '0';
          cx_r <= (others => '0');
          if px_eof = '1' then
            cy_r        <= (others => '0');
            first_row_r <= '1';
          else
            cy_r        <= cy_r + 1;
            first_row_r <= '0';
          end if;
        else
          cm_r <= px_corner;
          cx_r <= cx_r + 1;
        end if;
      end if;

      if cstep_i = '1' and c_eol then
        cur_bank_r <= not cur_bank_r;
      end if;
      if rstep_i = '1' and r_last_r = '1' then
        r_bank_r <= not r_bank_r;
      end if;

      -- The reader's next column, and its prefetched bits.
      if rstep_i = '1' then
        rcol      <= r_next;
        r_slot0_r <= r_last_r or r_col0_r;
        r_col0_r  <= r_last_r;
        r_col1_r  <= r_col0_r;
        r_col2_r  <= r_col1_r;
        if r_ahead = r_lastcol then
          r_ahead <= (others => '0');
        else
          r_ahead <= r_ahead + 1;
        end if;
        r_reads <= to_sl(r_ahead /= r_lastcol and r_ahead /= 0);
        -- Rows are at least 3 wide: after r_ahead = 0 comes 1.
        r_last_r <= to_sl(r_ahead = 0);
        p0_r     <= row_rd;
        if r_last_r = '1' then
          pm_r <= '0';
        else
          pm_r <= p0_r;
        end if;
      elsif (f_prime = '1' and px_eol = '1') or prime_st = 2 then
        -- The next reader row (lock-step or flush) starts at column 0,
        -- where the reader already is (asserted below): a reader row ends
        -- at its last column, and its step there moves it to column 0 two
        -- ahead; only the bits are loaded.
        p0_r      <= row_rd;
        pm_r      <= '0';
        r_lastcol <= resize(cw - 1, XB);
      end if;

      -- synthesis translate_off
      assert not (rstep_i = '0' and ((f_prime = '1' and px_eol = '1') or prime_st = 2) and
                  (rcol /= 0 or r_ahead /= 2))
        report "fastnms_nms_region: the reader primed away from column 0"
        severity failure;
      assert not (checks_on and rst = '0' and flushing = '0' and first_row_r = '1' and
                  (rcol /= 0 or r_ahead /= 2))
        report "fastnms_nms_region: the reader idle away from column 0"
        severity failure;
      -- The row memory's two columns per word rely on this order.
      if row_we = '1' then
        assert not checks_on or rst = '1' or row_wa = 0 or to_integer(row_wa) = row_last_wa + 1
          report "fastnms_nms_region: the row memory written out of column order"
          severity failure;
        row_last_wa <= to_integer(row_wa);
      end if;
      -- synthesis translate_on

      -- Primed: the reader's prefetch is valid for its next row (lock-step
      -- rows keep it so). A flush spends it; a first row's last column sets it
      -- when its read of column 0 was the last read and no flush moves the
      -- prefetch after it; PRIME sets it.
      flush_last := flush_go = '1' and r_last_r = '1';
      if row_re = '1' then
        holds0 <= row_next0;
      end if;
      v_primed := primed;
      if flush_go = '1' then
        v_primed := '0';
      end if;
      if prime_st = 2 then
        v_primed := '1';
      end if;
      if cstep_i = '1' and c_eol and first_row_r = '1' and (flushing = '0' or flush_last) then
        v_primed := holds0;
      end if;
      primed <= v_primed;
      if flush_last then
        -- The next reader row is a lock-step row of the current frame.
        r_lastcol <= resize(cw - 1, XB);
      end if;
      if lock_i = '1' and c_eol then
        r_lastcol <= resize(cw - 1, XB);
      end if;
      prime_st <= (others => '0');
      if prime_st = 1 then
        prime_st <= to_unsigned(2, 2);
      end if;

      -- Flush: after a frame's last row, once the reader is free and primed;
      -- on the next clock when frames come back to back.
      eof_step := cstep_i = '1' and px_eof = '1';
      if flush_last then
        flushing <= '0';
      end if;

      -- synthesis translate_off
      assert not (eof_step and (flushing = '0' or flush_last) and
                  v_primed /= (not first_row_r or holds0))
        report "fastnms_nms_region: the flush's start out of step with primed"
        severity failure;
      -- synthesis translate_on

      if eof_step then
        -- The reader is primed after a lock-step row (it steps only
        -- primed), and after a first row if its read of column 0 was the
        -- last (v_primed, written out).
        if (flushing = '0' or flush_last) and (first_row_r = '0' or holds0 = '1') then
          flushing  <= '1';
          r_lastcol <= resize(cw - 1, XB);
        else
          flush_pending <= '1';
          flush_w       <= cw;
        end if;
      elsif flush_pending = '1' and (flushing = '0' or flush_last) and primed = '1' then
        flushing      <= '1';
        flush_pending <= '0';
        r_lastcol     <= resize(flush_w - 1, XB);
      end if;
      if flushing = '0' and primed = '0' and prime_st = 0 and cstep_i = '0' and
         ((px_valid = '1' and first_row_r = '0') or flush_pending = '1') then
        prime_st <= to_unsigned(1, 2);
      end if;

      -- synthesis translate_off
      assert not (cstep_i = '1' and frame_start = '1' and px_sof = '0')
        report "fastnms_nms_region: a frame's first pixel without in_sof"
        severity error;
      -- synthesis translate_on

      if rst = '1' then
        cm_r          <= '0';
        cx_r          <= (others => '0');
        cy_r          <= (others => '0');
        first_row_r   <= '1';
        frame_start   <= '1';
        rcol          <= (others => '0');
        r_ahead       <= to_unsigned(2, XB);
        r_reads       <= '1';
        c_at_penult   <= '0';
        r_last_r      <= '0';
        r_lastcol     <= (others => '0');
        p0_r          <= '0';
        pm_r          <= '0';
        flushing      <= '0';
        flush_pending <= '0';
        primed        <= '0';
        holds0        <= '0';
        prime_st      <= (others => '0');
        r_slot0_r     <= '1';
        r_col0_r      <= '1';
        r_col1_r      <= '0';
        r_col2_r      <= '0';
        cur_bank_r    <= '0';
        r_bank_r      <= '0';
      end if;
    end if;

  end process positions;

  -- Two columns per word. A row is written in column order, so a word is
  -- written at its even column (both bits that column's: the odd one is
  -- written next) and again at its odd column, with the even column's bit
  -- kept from then. Every bit is read after the clock that writes it, and
  -- the previous row's bits of a word are all read before the current row
  -- writes it (the reader is two columns ahead of the writer, or further
  -- during a flush); a read in the clock of a write to its word gets the
  -- word before it.
  row_pairs : process (clk) is
  begin

    if rising_edge(clk) then
      if row_we = '1' and row_wa(0) = '0' then
        row_even <= row_wd;
      end if;
      if row_re = '1' then
        row_lane <= row_ra(0);
      end if;
    end if;

  end process row_pairs;

  row_memory : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => (MAX_WIDTH + 1) / 2,
      WIDTH => 2
    )
    port map (
      clk     => clk,
      wr_en   => row_we,
      wr_addr => resize(shift_right(row_wa, 1), clog2((MAX_WIDTH + 1) / 2)),
      wr_data => row_wdata,
      rd_en   => row_re,
      rd_addr => resize(shift_right(row_ra, 1), clog2((MAX_WIDTH + 1) / 2)),
      rd_data => row_word
    );

  row_wdata <= row_wd & row_even when row_wa(0) = '1' else
               row_wd & row_wd;
  row_rd    <= row_word(1) when row_lane = '1' else
               row_word(0);

end architecture rtl;
