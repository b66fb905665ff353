-- The keypoint budget's insertion pipeline (fastnms_cell_budget): one record
-- per clock into its cell's word (fastnms_budget_pkg), which keeps the cell's
-- best in_keep entries sorted, a tie to the earlier record.
--
-- The parent reads the record's cell (in_cell) in its bank (in_bank) at the
-- clock the record comes in (in_valid); the banks' words come back two clocks
-- later (rd_data_0/1, READ_LATENCY 2). Stage A holds the record during the
-- read, stage B compares it with every entry of the word, stage C inserts it
-- and writes the word back (wr_*). The words of the three records before it
-- are forwarded, so records of the same cell follow each other every clock.
-- in_open marks the first record of a cell row in its bank: last_cell_0/1
-- restart there and then follow the highest cell written (the drain's end).
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

  -- Stage C's word: the record e inserted where the entries stop beating it, the
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
  -- registers cut the block RAM's clock-to-output from the comparisons).
  signal a_valid : std_logic;
  signal a_open  : std_logic;
  signal a_bank  : bank_t;
  signal a_cell  : addr_t;
  signal a_entry : entry_t;
  signal a_mask  : flags_t;

  -- Stage B: the word read (or forwarded), compared.
  signal b_valid  : std_logic;
  signal b_open   : std_logic;
  signal b_bank   : bank_t;
  signal b_cell   : addr_t;
  signal b_entry  : entry_t;
  signal b_mask   : flags_t;
  signal b_from_c : std_logic; -- the record in stage C has the same cell
  signal b_from_w : std_logic; -- the record written last clock has the same cell
  signal b_from_v : std_logic; -- the record written two clocks ago has the same cell
  signal b_read   : word_t;
  signal b_word   : word_t;
  signal b_beats  : flags_t;

  -- Stage C: the record inserted, the word written.
  signal c_valid : std_logic;
  signal c_bank  : bank_t;
  signal c_cell  : addr_t;
  signal c_entry : entry_t;
  signal c_mask  : flags_t;
  signal c_word  : word_t;
  signal c_beats : flags_t;
  signal c_new   : word_t;
  signal w_valid : std_logic; -- stage C wrote last clock: its cell and word
  signal w_bank  : bank_t;
  signal w_cell  : addr_t;
  signal w_word  : word_t;
  signal v_word  : word_t;    -- the word stage C wrote two clocks ago

  signal last_0 : addr_t;
  signal last_1 : addr_t;

begin

  assert K_MAX <= 15
    report "fastnms_budget_insert: K_MAX must be 1 .. 15"
    severity failure;

  stages : process (clk) is
  begin

    if rising_edge(clk) then
      -- A: the record, its word being read.
      a_valid <= in_valid;
      a_open  <= in_open;
      a_bank  <= in_bank;
      a_cell  <= in_cell;
      a_entry <= in_entry;

      for j in 0 to K_MAX - 1 loop

        a_mask(j) <= to_sl(j < in_keep);

      end loop;

      -- B: the record, and where its word comes from (the three records before it
      -- write their words at or after this one's read).
      b_valid  <= a_valid;
      b_open   <= a_open;
      b_bank   <= a_bank;
      b_cell   <= a_cell;
      b_entry  <= a_entry;
      b_mask   <= a_mask;
      b_from_c <= b_valid and to_sl(b_bank = a_bank and b_cell = a_cell);
      b_from_w <= c_valid and to_sl(c_bank = a_bank and c_cell = a_cell);
      b_from_v <= w_valid and to_sl(w_bank = a_bank and w_cell = a_cell);

      -- C: the word and the comparisons.
      c_valid <= b_valid;
      c_bank  <= b_bank;
      c_cell  <= b_cell;
      c_entry <= b_entry;
      c_mask  <= b_mask;
      c_word  <= b_word;
      c_beats <= b_beats;
      w_valid <= c_valid;
      w_bank  <= c_bank;
      w_cell  <= c_cell;
      w_word  <= c_new;
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
        w_valid <= '0';
      end if;
    end if;

  end process stages;

  b_read <= rd_data_0 when b_bank = 0 else
            rd_data_1;

  b_word <= c_new when b_from_c = '1' else
            w_word when b_from_w = '1' else
            v_word when b_from_v = '1' else
            b_read;

  -- The comparisons of stage B against the word stage C is making are made on that
  -- word's sources (C's registers), then chosen as C chooses its entries.
  compare : process (all) is

    variable s : unsigned(SCORE_BITS - 1 downto 0);

  begin

    s := score_of(b_entry);

    for j in 0 to K_MAX - 1 loop

      if b_from_c = '1' then
        if c_beats(j) = '1' then
          b_beats(j) <= c_mask(j) and beats(entry(c_word, j, E_BITS), s);
        elsif j = 0 then
          b_beats(j) <= c_mask(j) and beats(c_entry, s);
        elsif c_beats(j - 1) = '1' then
          b_beats(j) <= c_mask(j) and beats(c_entry, s);
        else
          b_beats(j) <= c_mask(j) and beats(entry(c_word, j - 1, E_BITS), s);
        end if;
      elsif b_from_w = '1' then
        b_beats(j) <= beats(entry(w_word, j, E_BITS), s);
      elsif b_from_v = '1' then
        b_beats(j) <= beats(entry(v_word, j, E_BITS), s);
      else
        b_beats(j) <= beats(entry(b_read, j, E_BITS), s);
      end if;

    end loop;

  end process compare;

  c_new <= inserted(c_word, c_entry, c_beats, c_mask);

  wr_valid    <= c_valid;
  wr_bank     <= c_bank;
  wr_cell     <= c_cell;
  wr_word     <= c_new;
  last_cell_0 <= last_0;
  last_cell_1 <= last_1;

end architecture rtl;
