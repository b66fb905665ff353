-- Probe, not part of the core: the least logic a one-clock merge of two
-- region keys needs. Two key registers load new keys, or the first takes the
-- better of the two (a merge) in one clock, the choice itself a register.
-- With ORDER_FLAG the keys are scores only, and which of the two pixels comes
-- first in raster order (the tie rule) is a register beside them instead of
-- their row and column. flows/synth/test_synth.py maps it with the same flow
-- as the core and records its logic levels (docs/fastnms_nms_region.md,
-- Limits).
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity key_merge is
  generic (
    KEY_BITS   : positive := 34;
    ORDER_FLAG : boolean  := false
  );
  port (
    clk        : in    std_logic;
    merge      : in    std_logic;
    in_a       : in    unsigned(KEY_BITS - 1 downto 0);
    in_b       : in    unsigned(KEY_BITS - 1 downto 0);
    in_b_first : in    std_logic;
    out_key    : out   unsigned(KEY_BITS - 1 downto 0)
  );
end entity key_merge;

architecture rtl of key_merge is

  signal merge_r : std_logic;
  signal a_r     : unsigned(KEY_BITS - 1 downto 0);
  signal b_r     : unsigned(KEY_BITS - 1 downto 0);
  signal a       : unsigned(KEY_BITS - 1 downto 0);
  signal b       : unsigned(KEY_BITS - 1 downto 0);
  -- ORDER_FLAG: b's pixel comes before a's in raster order.
  signal b_first_r : std_logic;
  signal b_first   : std_logic;

begin

  keys : process (clk) is
  begin

    if rising_edge(clk) then
      merge_r   <= merge;
      a_r       <= in_a;
      b_r       <= in_b;
      b_first_r <= in_b_first;
      if merge_r = '1' then
        if b > a or (ORDER_FLAG and b = a and b_first = '1') then
          a <= b;
        end if;
      else
        a       <= a_r;
        b       <= b_r;
        b_first <= b_first_r;
      end if;
    end if;

  end process keys;

  out_key <= a;

end architecture rtl;
