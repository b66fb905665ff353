-- Probe, not part of the core: the key selection of one column of the region
-- NMS's data path (rtl/nms/fastnms_nms_region.vhd, process apply: the merge
-- into the top's class of its base, the class merging in and the pixel; the
-- current class's key; the pop's choice; the data table's write), with its
-- comparisons made easier than the block can make them, to measure what
-- the selection itself costs:
--   COMPARED_AHEAD false: order flags. Two classes are compared on their
--     scores, and which of their best pixels comes first in raster order
--     (the tie rule) is a register beside them, one per pair of classes
--     that can merge (the top's and the current one, a pushed one and the
--     current one, a pushed one and the top's).
--   COMPARED_AHEAD true: every comparison of the column is a register,
--     as if all were made a clock ahead.
-- The flags and comparisons come in as registers; keeping them up to date
-- is left out, so the probe measures a lower bound on such a data path's
-- depth. flows/synth/test_synth.py maps it with the same flow as the core
-- and records its logic levels (docs/fastnms_nms_region.md, Depth and clock).
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity key_step is
  generic (
    SCORE_BITS     : positive := 12;
    POS_BITS       : positive := 22;
    COMPARED_AHEAD : boolean  := false
  );
  port (
    clk : in    std_logic;
    -- Keys: score, then the inverted row and column (larger is better).
    in_top    : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_second : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_cur    : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_word   : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_land   : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_pix    : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    -- The operation's bits, as the block's control registers them.
    in_op : in    std_logic_vector(12 downto 0);
    -- Order flags: the first class's best pixel is before the second's;
    -- with COMPARED_AHEAD, the comparisons: the base against the class
    -- merging in and against the pixel, the class merging in and the
    -- current class against the pixel.
    in_top_first_cur  : in    std_logic;
    in_word_first_cur : in    std_logic;
    in_word_first_top : in    std_logic;
    in_compared       : in    std_logic_vector(3 downto 0);
    out_top           : out   unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    out_cur           : out   unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    out_write         : out   unsigned(SCORE_BITS + POS_BITS - 1 downto 0)
  );
end entity key_step;

architecture rtl of key_step is

  constant KB : positive := SCORE_BITS + POS_BITS;

  subtype key_t is unsigned(KB - 1 downto 0);

  function score_of (k : key_t) return unsigned is
  begin

    return k(KB - 1 downto POS_BITS);

  end function score_of;

  signal top            : key_t;
  signal second         : key_t;
  signal cur_key        : key_t;
  signal word           : key_t;
  signal land           : key_t;
  signal pix            : key_t;
  signal op             : std_logic_vector(12 downto 0);
  signal top_first_cur  : std_logic;
  signal word_first_cur : std_logic;
  signal word_first_top : std_logic;
  signal compared       : std_logic_vector(3 downto 0);
  signal write_key      : key_t;

begin

  step : process (clk) is

    variable base_pushed   : boolean;
    variable landing       : boolean;
    variable merge_cur     : boolean;
    variable merge_pix     : boolean;
    variable merge_top     : boolean;
    variable pix_joins     : boolean;
    variable keep_top      : boolean;
    variable take_second   : boolean;
    variable cur_start     : boolean;
    variable cur_pix       : boolean;
    variable detach        : boolean;
    variable final         : boolean;
    variable spare         : boolean;
    variable base          : key_t;
    variable merge         : key_t;
    variable best          : key_t;
    variable cur           : key_t;
    variable first         : std_logic;
    variable pix_in        : unsigned(SCORE_BITS - 1 downto 0);
    variable base_ge_merge : boolean;
    variable base_ge_pix   : boolean;
    variable merge_ge_pix  : boolean;
    variable cur_ge_pix    : boolean;

  begin

    if rising_edge(clk) then
      base_pushed := op(0) = '1';
      landing     := op(1) = '1';
      merge_cur   := op(2) = '1';
      merge_pix   := op(3) = '1';
      merge_top   := op(4) = '1';
      pix_joins   := op(5) = '1';
      keep_top    := op(6) = '1';
      take_second := op(7) = '1';
      cur_start   := op(8) = '1';
      cur_pix     := op(9) = '1';
      detach      := op(10) = '1';
      final       := op(11) = '1';
      spare       := op(12) = '1';

      if not base_pushed then
        base := top;
      elsif landing then
        base := land;
      else
        base := word;
      end if;
      merge := (others => '0');
      first := '1';
      if merge_cur then
        merge := cur_key;
        first := top_first_cur;
        if base_pushed then
          first := word_first_cur;
        end if;
      elsif merge_pix then
        merge := pix;
      elsif merge_top then
        merge := top;
        first := word_first_top;
      end if;
      pix_in := (others => '0');
      if pix_joins then
        pix_in := score_of(pix);
      end if;
      -- Scores, the order flag deciding a tie.
      base_ge_merge := (score_of(base) & first) >= (score_of(merge) & '1');
      base_ge_pix   := score_of(base) >= pix_in;
      merge_ge_pix  := (merge_cur or merge_pix or merge_top) and score_of(merge) >= pix_in;
      cur_ge_pix    := score_of(cur_key) >= score_of(pix);
      if COMPARED_AHEAD then
        base_ge_merge := compared(0) = '1';
        base_ge_pix   := compared(1) = '1';
        merge_ge_pix  := compared(2) = '1';
        cur_ge_pix    := compared(3) = '1';
      end if;
      if base_ge_merge and base_ge_pix then
        best := base;
      elsif merge_ge_pix then
        best := merge;
      else
        best := pix;
      end if;
      if cur_start or (cur_pix and not cur_ge_pix) then
        cur := pix;
      else
        cur := cur_key;
      end if;

      if keep_top then
        out_top <= top;
      elsif take_second then
        out_top <= second;
      else
        out_top <= best;
      end if;
      if detach then
        out_cur <= best;
      else
        out_cur <= cur;
      end if;
      if spare then
        write_key <= cur_key;
      elsif final then
        write_key <= best;
      else
        write_key <= cur;
      end if;

      top            <= in_top;
      second         <= in_second;
      cur_key        <= in_cur;
      word           <= in_word;
      land           <= in_land;
      pix            <= in_pix;
      op             <= in_op;
      top_first_cur  <= in_top_first_cur;
      word_first_cur <= in_word_first_cur;
      word_first_top <= in_word_first_top;
      compared       <= in_compared;
    end if;

  end process step;

  out_write <= write_key;

end architecture rtl;
