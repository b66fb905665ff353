-- The region NMS's head, last and data tables, read ahead of the reader so
-- that the control takes a run's bits from registers; a read in flight
-- takes the writes that land on its word.
-- Datasheet: docs/fastnms_nms_region.md
-- Contract: docs/design/region_nms_pipeline.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_nms_region_pkg.all;

entity fastnms_nms_region_tables is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 4095;
    SCORE_BITS : positive := 8
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- The schedule's step (fastnms_nms_region_schedule): the reader's step,
    -- its bits (for the assertions), where it is, the slot it reads ahead.
    step : in    step_t(cx(clog2(MAX_WIDTH) - 1 downto 0), cy(bits_for(MAX_HEIGHT) - 1 downto 0),
                        ahead_slot(slot_bits(MAX_WIDTH) - 1 downto 0));
    -- The operation a clock after the control's step: the data word's read
    -- (op.rv, slot).
    cmd : in    command_t(slot(slot_bits(MAX_WIDTH) - 1 downto 0), score(SCORE_BITS - 1 downto 0),
                          cx(clog2(MAX_WIDTH) - 1 downto 0), cy(bits_for(MAX_HEIGHT) - 1 downto 0),
                          ram_wa(clog2(stack_ram_words(MAX_WIDTH)) - 1 downto 0),
                          ram_ra(clog2(stack_ram_words(MAX_WIDTH)) - 1 downto 0));
    -- The writes (registered by the key data path).
    writes : in    writes_t(data(slot(slot_bits(MAX_WIDTH) - 1 downto 0),
                                 word(data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS) - 1 downto 0)),
                            head(addr(slot_bits(MAX_WIDTH) downto 0)),
                            head_spare(addr(slot_bits(MAX_WIDTH) downto 0)),
                            last(addr(slot_bits(MAX_WIDTH) downto 0)));
    -- The previous-row run at the reader's column, and the data word.
    run : out   run_t(data(data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS) - 1 downto 0))
  );
end entity fastnms_nms_region_tables;

architecture rtl of fastnms_nms_region_tables is

  constant DB : positive := data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS);
  -- A data word's area: its count and saturation flag, the low bits.
  constant AREA_WORD_BITS : positive := AREA_BITS + 1;
  constant SLOTS          : positive := slot_count(MAX_WIDTH);
  constant SB             : positive := slot_bits(MAX_WIDTH);

  -- A bit table's word address: the slot, then the bank (the row's parity;
  -- '0' in the last table, which has one bank).
  subtype bit_addr_t is unsigned(SB downto 0);

  -- A table's reads, two columns ahead of the reader: the read in the RAM
  -- (its address, and a write to it since, which the RAM may not show), and
  -- the word of the reader's column, a register. Writes after a read update
  -- it: the previous row's last writes land while the next row's first
  -- columns are read. Words are data words (key and area); the bit tables use bit 0.
  subtype word_t is std_logic_vector(DB - 1 downto 0);

  type ahead_t is record
    addr1 : bit_addr_t;
    fwd_v : std_logic;
    fwd   : word_t;
    addr2 : bit_addr_t;
    word2 : word_t;
  end record ahead_t;

  constant AHEAD_RESET : ahead_t :=
  (
    addr1 => (others => '0'),
    fwd_v => '0',
    fwd   => (others => '0'),
    addr2 => (others => '0'),
    word2 => (others => '0')
  );

  -- The reads after one clock: they move on with a reader step (reading ra),
  -- and take the write (w_en, w_addr, w_data) that lands at the clock's end.
  function ahead_next (
    p      : ahead_t;
    w_en   : std_logic;
    w_addr : bit_addr_t;
    w_data : word_t;
    moves  : std_logic;
    ra     : bit_addr_t;
    rdata  : word_t
  ) return ahead_t is
    variable n : ahead_t;
  begin

    n := p;

    if moves = '1' then
      n.addr2 := p.addr1;
      if w_en = '1' and w_addr = p.addr1 then
        n.word2 := w_data;
      elsif p.fwd_v = '1' then
        n.word2 := p.fwd;
      else
        n.word2 := rdata;
      end if;
      n.addr1 := ra;
      n.fwd_v := w_en and to_sl(w_addr = ra);
      n.fwd   := w_data;
    else
      if w_en = '1' and w_addr = p.addr2 then
        n.word2 := w_data;
      end if;
      if w_en = '1' and w_addr = p.addr1 then
        n.fwd_v := '1';
        n.fwd   := w_data;
      end if;
    end if;

    return n;

  end function ahead_next;

  function word (b : std_logic) return word_t is
  begin

    return (DB - 1 downto 1 => '0') & b;

  end function word;

  signal op_r       : op_t;
  signal data_rd    : std_logic_vector(DB - 1 downto 0);
  signal head_rd    : std_logic_vector(0 downto 0);
  signal last_rd    : std_logic_vector(0 downto 0);
  signal data_ahead : ahead_t;
  signal head_ahead : ahead_t;
  signal last_ahead : ahead_t;
  -- The head bit of the previous-row run at rcol (the first of its class).
  signal run_head_r   : std_logic;
  signal run_last_now : std_logic;
  -- The last write lands on the word the reader takes now (slot 0 at
  -- columns 0 and 1, slot 1 at column 2).
  signal fwd_last0 : std_logic;
  signal fwd_last1 : std_logic;
  signal checks_on : boolean; -- false until the first reset: the invariants hold from then on

begin

  assert MAX_WIDTH >= 3
    report "fastnms_nms_region_tables: MAX_WIDTH must be at least 3"
    severity failure;

  op_r <= cmd.op;

  fwd_last0    <= writes.last.en and writes.last.s0 and step.r_slot0;
  fwd_last1    <= writes.last.en and writes.last.s1 and step.r_col2;
  run_last_now <= writes.last.data when (fwd_last0 or fwd_last1) = '1' else
                  last_ahead.word2(0);
  run          <= (head => run_head_r, last => run_last_now, data => unsigned(data_ahead.word2));

  reads_ahead : process (clk) is

    variable p_start    : boolean;
    variable fwd_head1  : boolean;
    variable next_head  : ahead_t;
    variable next_slot0 : std_logic;
    variable next_col2  : std_logic;

  begin

    if rising_edge(clk) then
      p_start := step.p0 = '1' and step.pm = '0';

      -- synthesis translate_off
      if rst = '1' then
        checks_on <= true;
      end if;
      -- The write a registered head bit (run_head_r) took a clock ahead.
      fwd_head1 := writes.head.en = '1' and writes.head.s1 = '1' and step.r_col2 = '1' and
                   writes.head.addr(0) = step.r_bank;
      assert not (step.rstep = '1' and p_start and step.r_slot0 = '0' and writes.head.en = '1' and
                  writes.head.addr = head_ahead.addr2 and not fwd_head1)
        report "fastnms_nms_region: a head bit written as the reader takes it"
        severity failure;
      assert not (step.rstep = '1' and p_start and writes.last.en = '1' and
                  writes.last.addr = last_ahead.addr2 and (fwd_last0 or fwd_last1) = '0')
        report "fastnms_nms_region: a last bit written as the reader takes it"
        severity failure;
      assert not ((fwd_last0 or fwd_last1) = '1' and writes.last.addr /= last_ahead.addr2)
        report "fastnms_nms_region: last_w_s0 or last_w_s1 out of step"
        severity failure;
      assert not (fwd_head1 and writes.head.addr /= head_ahead.addr2)
        report "fastnms_nms_region: head_w_s1 out of step"
        severity failure;
      assert not checks_on or rst = '1' or
             (fwd_head1 and run_head_r = writes.head.data) or
             (not fwd_head1 and run_head_r = (head_ahead.word2(0) or step.r_slot0))
        report "fastnms_nms_region: run_head_r out of step"
        severity failure;
      assert not (op_r.push = '1' and op_r.rv = '1' and writes.data.en = '1' and
                  (writes.data.slot & '0') = data_ahead.addr2 and (op_r.r_col0 = '0' or writes.data.s0 = '0'))
        report "fastnms_nms_region: a key written as the reader takes it"
        severity failure;
      -- synthesis translate_on

      next_head  := ahead_next(head_ahead, writes.head.en, writes.head.addr, word(writes.head.data),
                               step.rstep, step.ahead_slot & step.r_bank, word(head_rd(0)));
      head_ahead <= next_head;
      -- The head bit of the run the reader takes next, a register: the word
      -- it reads ahead, or the row's first run, or the previous row's last
      -- column's second write (from the spare register: slot 1, taken at
      -- column 2) when it lands as the reader takes that word.
      next_slot0 := step.r_slot0;
      next_col2  := step.r_col2;
      if step.rstep = '1' then
        next_slot0 := step.r_last or step.r_col0;
        next_col2  := step.r_col1;
      end if;
      -- The RAM's output is the last input of the choice (one LUT after the
      -- block RAM, whose clock-to-output is long on ECP5).
      if writes.head_spare.en = '1' and writes.head_spare.s1 = '1' and next_col2 = '1' and
         writes.head_spare.addr(0) = (step.r_bank xor (step.rstep and step.r_last)) then
        run_head_r <= writes.head_spare.data;
      elsif next_slot0 = '1' then
        run_head_r <= '1';
      elsif step.rstep = '1' and not (writes.head.en = '1' and writes.head.addr = head_ahead.addr1) and
            head_ahead.fwd_v = '0' then
        run_head_r <= head_rd(0);
      else
        run_head_r <= next_head.word2(0);
      end if;
      last_ahead <= ahead_next(last_ahead, writes.last.en, writes.last.addr, word(writes.last.data),
                               step.rstep, step.ahead_slot & '0', word(last_rd(0)));
      data_ahead <= ahead_next(data_ahead, writes.data.en, writes.data.slot & '0', word_t(writes.data.word),
                               op_r.rv, cmd.slot & '0', data_rd);

      if rst = '1' then
        run_head_r <= '1';
        head_ahead <= AHEAD_RESET;
        last_ahead <= AHEAD_RESET;
        data_ahead <= AHEAD_RESET;
      end if;
    end if;

  end process reads_ahead;

  -- The data words' keys in block RAM; their areas (AREA_BITS + 1, the low
  -- bits) in LUT RAM beside them, at the same address and enables: in the
  -- block RAM the areas would take the words past two BRAM18 side by side
  -- (36 bits) into a third (docs/design/region_nms_memory.md).
  data_keys : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => SLOTS,
      WIDTH => DB - AREA_WORD_BITS
    )
    port map (
      clk     => clk,
      wr_en   => writes.data.en,
      wr_addr => resize(writes.data.slot, clog2(SLOTS)),
      wr_data => std_logic_vector(writes.data.word(DB - 1 downto AREA_WORD_BITS)),
      rd_en   => op_r.rv,
      rd_addr => resize(cmd.slot, clog2(SLOTS)),
      rd_data => data_rd(DB - 1 downto AREA_WORD_BITS)
    );

  data_areas : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => SLOTS,
      WIDTH => AREA_WORD_BITS,
      STYLE => "distributed"
    )
    port map (
      clk     => clk,
      wr_en   => writes.data.en,
      wr_addr => resize(writes.data.slot, clog2(SLOTS)),
      wr_data => std_logic_vector(writes.data.word(AREA_WORD_BITS - 1 downto 0)),
      rd_en   => op_r.rv,
      rd_addr => resize(cmd.slot, clog2(SLOTS)),
      rd_data => data_rd(AREA_WORD_BITS - 1 downto 0)
    );

  -- One bit per word: LUT RAM.
  head_table : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => 2 * SLOTS,
      WIDTH => 1,
      STYLE => "distributed"
    )
    port map (
      clk     => clk,
      wr_en   => writes.head.en,
      wr_addr => resize(writes.head.addr, clog2(2 * SLOTS)),
      wr_data => (0 => writes.head.data),
      rd_en   => step.rstep,
      rd_addr => resize(step.ahead_slot & step.r_bank, clog2(2 * SLOTS)),
      rd_data => head_rd
    );

  last_table : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => SLOTS,
      WIDTH => 1,
      STYLE => "distributed"
    )
    port map (
      clk     => clk,
      wr_en   => writes.last.en,
      wr_addr => resize(writes.last.addr(SB downto 1), clog2(SLOTS)),
      wr_data => (0 => writes.last.data),
      rd_en   => step.rstep,
      rd_addr => resize(step.ahead_slot, clog2(SLOTS)),
      rd_data => last_rd
    );

end architecture rtl;
