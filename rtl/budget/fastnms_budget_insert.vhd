-- The keypoint budget's insertion: one record per clock into its cell's
-- sorted word (read, choose the base word, compare, insert, write back).
-- Datasheet: docs/fastnms_cell_budget.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_budget_pkg.all;

entity fastnms_budget_insert is
  generic (
    CELLS      : positive := 120;
    SCORE_BITS : positive := 8;
    K_MAX      : positive := 15
  );
  port (
    clk         : in    std_logic;
    rst         : in    std_logic;
    in_valid    : in    std_logic;
    in_open     : in    std_logic;
    in_bank     : in    natural range 0 to 1;
    in_cell     : in    unsigned(clog2(CELLS) - 1 downto 0);
    in_entry    : in    std_logic_vector(entry_width(SCORE_BITS) - 1 downto 0);
    in_keep     : in    natural range 0 to K_MAX;
    rd_data_0   : in    std_logic_vector(K_MAX * entry_width(SCORE_BITS) - 1 downto 0);
    rd_data_1   : in    std_logic_vector(K_MAX * entry_width(SCORE_BITS) - 1 downto 0);
    wr_valid    : out   std_logic;
    wr_bank     : out   natural range 0 to 1;
    wr_cell     : out   unsigned(clog2(CELLS) - 1 downto 0);
    wr_word     : out   std_logic_vector(K_MAX * entry_width(SCORE_BITS) - 1 downto 0);
    last_cell_0 : out   unsigned(clog2(CELLS) - 1 downto 0);
    last_cell_1 : out   unsigned(clog2(CELLS) - 1 downto 0)
  );
end entity fastnms_budget_insert;

architecture rtl of fastnms_budget_insert is

  constant E_BITS : positive := entry_width(SCORE_BITS);

  subtype word_t is std_logic_vector(K_MAX * E_BITS - 1 downto 0);

  subtype entry_t is std_logic_vector(E_BITS - 1 downto 0);

  subtype addr_t is unsigned(clog2(CELLS) - 1 downto 0);

  subtype bank_t is natural range 0 to 1;

  subtype flags_t is std_logic_vector(0 to K_MAX - 1);

  -- A same-cell compare in two clocks: its parts (3 bits of the cells each, then the
  -- banks and the valid bit) registered, then their and.
  constant PARTS : positive := (clog2(CELLS) + 2) / 3 + 1;

  subtype parts_t is std_logic_vector(0 to PARTS - 1);

  type parts_4_t is array (0 to 3) of parts_t;

  -- The parts of (valid and bank = other_bank and cell = other_cell).
  function same_parts (cell : addr_t; bank : bank_t; valid : std_logic; other_cell : addr_t;
    other_bank : bank_t) return parts_t is
    variable result : parts_t;
  begin

    result := (others => '1');

    for i in 0 to cell'length - 1 loop

      if cell(i) /= other_cell(i) then
        result(i / 3) := '0';
      end if;

    end loop;

    result(PARTS - 1) := valid and to_sl(bank = other_bank);
    return result;

  end function same_parts;

  -- Stage D's word: the record e inserted where the entries stop beating it, the
  -- entries after it moved down, entries from index k on (mask) invalid.
  function inserted (w : word_t; e : entry_t; b : flags_t; mask : flags_t) return word_t is
    variable result : word_t;
    variable pick   : entry_t;
  begin

    for j in 0 to K_MAX - 1 loop

      if b(j) = '1' then
        pick := entry(w, j, E_BITS);
      elsif j = 0 then
        pick := e;
      elsif b(j - 1) = '1' then
        pick := e;
      else
        pick := entry(w, j - 1, E_BITS);
      end if;

      pick(E_BITS - 1)                               := pick(E_BITS - 1) and mask(j);
      result((j + 1) * E_BITS - 1 downto j * E_BITS) := pick;

    end loop;

    return result;

  end function inserted;

  -- Stage A: the record while its word is read (two clocks: the memories' output
  -- registers cut the block RAM's clock-to-output from the logic).
  signal a_valid : std_logic;
  signal a_open  : std_logic;
  signal a_bank  : bank_t;
  signal a_cell  : addr_t;
  signal a_entry : entry_t;
  signal a_mask  : flags_t;
  signal a_same  : parts_4_t; -- the parts of b_from_w, b_from_v, b_near_1, b_near_2

  -- Stage B: the record, the base word chosen.
  signal b_valid  : std_logic;
  signal b_open   : std_logic;
  signal b_bank   : bank_t;
  signal b_cell   : addr_t;
  signal b_entry  : entry_t;
  signal b_mask   : flags_t;
  signal b_from_w : std_logic; -- the record written last clock has the same cell
  signal b_from_v : std_logic; -- the record written two clocks ago has the same cell
  signal b_base   : word_t;
  signal b_near_1 : std_logic; -- the record one ahead (now in stage C) has the same cell
  signal b_near_2 : std_logic; -- the record two ahead (now in stage D) has the same cell

  -- Stage C: the record, its base word, compared.
  signal c_valid  : std_logic;
  signal c_bank   : bank_t;
  signal c_cell   : addr_t;
  signal c_entry  : entry_t;
  signal c_mask   : flags_t;
  signal c_base   : word_t;
  signal c_same_1 : std_logic; -- the record before (now in stage D) has the same cell
  signal c_same_2 : std_logic; -- the record two before (written last clock) has the same cell

  -- Stage D: the comparisons, the record inserted, the word written.
  signal d_valid  : std_logic;
  signal d_bank   : bank_t;
  signal d_cell   : addr_t;
  signal d_entry  : entry_t;
  signal d_mask   : flags_t;
  signal d_word   : word_t;    -- the cell's word unless the record before has the same cell
  signal d_same_1 : std_logic; -- the record before has the same cell: its word is w_word
  signal d_base   : flags_t;   -- the entries of the base word that beat the record
  signal d_beat_1 : std_logic; -- the record before: same cell, and it beats the record
  signal d_beat_2 : std_logic; -- the same for the record two before
  signal d_beats  : flags_t;
  signal d_new    : word_t;
  signal w_valid  : std_logic; -- stage D wrote last clock: its record and word
  signal w_entry  : entry_t;
  signal w_word   : word_t;
  signal v_word   : word_t;    -- the word stage D wrote two clocks ago

  signal last_0 : addr_t;
  signal last_1 : addr_t;

begin

  assert K_MAX <= 15
    report "fastnms_budget_insert: K_MAX must be 1 .. 15"
    severity failure;

  stages : process (clk) is

    variable s : unsigned(SCORE_BITS - 1 downto 0);

  begin

    if rising_edge(clk) then
      -- A: the record, its word being read.
      a_valid <= in_valid;
      a_open  <= in_open;
      a_bank  <= in_bank;
      a_cell  <= in_cell;
      a_entry <= in_entry;
      -- The same-cell compares of stage B a clock ahead: the record against the ones
      -- that will be in stage D, written last clock, in stage B and in stage C then.
      a_same(0) <= same_parts(c_cell, c_bank, c_valid, in_cell, in_bank);
      a_same(1) <= same_parts(d_cell, d_bank, d_valid, in_cell, in_bank);
      a_same(2) <= same_parts(a_cell, a_bank, a_valid, in_cell, in_bank);
      a_same(3) <= same_parts(b_cell, b_bank, b_valid, in_cell, in_bank);

      for j in 0 to K_MAX - 1 loop

        a_mask(j) <= to_sl(j < in_keep);

      end loop;

      -- B: the record, and whether the read missed the word of the record in stage D
      -- or of the one written last clock (the read saw the words written before).
      b_valid  <= a_valid;
      b_open   <= a_open;
      b_bank   <= a_bank;
      b_cell   <= a_cell;
      b_entry  <= a_entry;
      b_mask   <= a_mask;
      b_from_w <= and a_same(0);
      b_from_v <= and a_same(1);
      b_near_1 <= and a_same(2);
      b_near_2 <= and a_same(3);

      -- C: the base word (the newest of the two forwarded words and the read), and
      -- which of the two records after the base's are in the same cell.
      c_valid  <= b_valid;
      c_bank   <= b_bank;
      c_cell   <= b_cell;
      c_entry  <= b_entry;
      c_mask   <= b_mask;
      c_base   <= b_base;
      c_same_1 <= b_near_1;
      c_same_2 <= b_near_2;

      -- D: the comparisons, the word to insert into without the record before's.
      s := score_of(c_entry);

      for j in 0 to K_MAX - 1 loop

        d_base(j) <= beats(entry(c_base, j, E_BITS), s);

      end loop;

      d_beat_1 <= c_same_1 and beats(d_entry, s);
      d_beat_2 <= c_same_2 and beats(w_entry, s);
      d_same_1 <= c_same_1;
      if c_same_2 = '1' then
        d_word <= w_word;
      else
        d_word <= c_base;
      end if;
      d_valid <= c_valid;
      d_bank  <= c_bank;
      d_cell  <= c_cell;
      d_entry <= c_entry;
      d_mask  <= c_mask;

      w_valid <= d_valid;
      w_entry <= d_entry;
      w_word  <= d_new;
      v_word  <= w_word;

      -- The last cell written of each bank (one register each: GHDL 2.0's synthesis
      -- drops the flip-flops of an array element indexed by a signal here).
      if b_valid = '1' and b_bank = 0 and (b_open = '1' or b_cell > last_0) then
        last_0 <= b_cell;
      end if;
      if b_valid = '1' and b_bank = 1 and (b_open = '1' or b_cell > last_1) then
        last_1 <= b_cell;
      end if;

      if rst = '1' then
        a_valid <= '0';
        b_valid <= '0';
        c_valid <= '0';
        d_valid <= '0';
        w_valid <= '0';
      end if;
    end if;

  end process stages;

  b_base <= w_word when b_from_w = '1' else
            v_word when b_from_v = '1' else
            rd_data_0 when b_bank = 0 else
            rd_data_1;

  -- The record's place: the cell's word is the base word plus the records before it
  -- in the same cell (one or two), kept to the best in_keep. Its entries that beat
  -- the record are the base's that do (a prefix: the word is sorted) and those
  -- records that do, at most in_keep: flag j is set when j is below that count.
  place : process (all) is

    variable t1 : std_logic;
    variable t2 : std_logic;

  begin

    for j in 0 to K_MAX - 1 loop

      t1 := '1';
      t2 := '1';

      if j >= 1 then
        t1 := d_base(j - 1);
      end if;

      if j >= 2 then
        t2 := d_base(j - 2);
      end if;

      if d_beat_1 = '1' and d_beat_2 = '1' then
        d_beats(j) <= d_mask(j) and t2;
      elsif (d_beat_1 or d_beat_2) = '1' then
        d_beats(j) <= d_mask(j) and t1;
      else
        d_beats(j) <= d_mask(j) and d_base(j);
      end if;

    end loop;

  end process place;

  d_new <= inserted(w_word, d_entry, d_beats, d_mask) when d_same_1 = '1' else
           inserted(d_word, d_entry, d_beats, d_mask);

  wr_valid    <= d_valid;
  wr_bank     <= d_bank;
  wr_cell     <= d_cell;
  wr_word     <= d_new;
  last_cell_0 <= last_0;
  last_cell_1 <= last_1;

end architecture rtl;
