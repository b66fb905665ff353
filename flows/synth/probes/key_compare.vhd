-- Probe, not part of the core: a region key comparison made a stage of its
-- own, from two key registers to a registered result, as a region NMS that
-- precomputes its comparisons a clock ahead would make them.
-- flows/synth/test_synth.py maps it with the same flow as the core and
-- records its logic levels (docs/fastnms_nms_region.md, Depth and clock).
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity key_compare is
  generic (
    KEY_BITS : positive := 34
  );
  port (
    clk    : in    std_logic;
    in_a   : in    unsigned(KEY_BITS - 1 downto 0);
    in_b   : in    unsigned(KEY_BITS - 1 downto 0);
    a_ge_b : out   std_logic
  );
end entity key_compare;

architecture rtl of key_compare is

  signal a : unsigned(KEY_BITS - 1 downto 0);
  signal b : unsigned(KEY_BITS - 1 downto 0);

begin

  compare : process (clk) is
  begin

    if rising_edge(clk) then
      a      <= in_a;
      b      <= in_b;
      a_ge_b <= '0';
      if a >= b then
        a_ge_b <= '1';
      end if;
    end if;

  end process compare;

end architecture rtl;
