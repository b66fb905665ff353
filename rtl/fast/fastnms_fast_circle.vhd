-- FAST front stage: from a 7x7 window to the 16 circle pixels' sides
-- (above, below) and absolute differences from the centre.
-- Datasheet: docs/fastnms_fast_detector.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_fast_pkg.all;

entity fastnms_fast_circle is
  port (
    clk    : in    std_logic;
    en     : in    std_logic;
    window : in    std_logic_vector(WINDOW_SIZE * WINDOW_SIZE * 8 - 1 downto 0);
    above  : out   circle_flags_t;
    below  : out   circle_flags_t;
    diff   : out   circle_bytes_t
  );
end entity fastnms_fast_circle;

architecture rtl of fastnms_fast_circle is

  constant CENTRE : natural := RADIUS * WINDOW_SIZE + RADIUS;

  signal up      : circle_bytes_t; -- c_k - v, wrapped
  signal down    : circle_bytes_t; -- v - c_k, wrapped
  signal above_1 : circle_flags_t;
  signal below_1 : circle_flags_t;

begin

  differences : process (clk) is

    variable v       : byte_t;
    variable c       : byte_t;
    variable slice_k : natural;

  begin

    if rising_edge(clk) then
      if en = '1' then
        v := unsigned(window(CENTRE * 8 + 7 downto CENTRE * 8));
        for k in 0 to CIRCLE_SIZE - 1 loop
          slice_k    := circle_slice(k);
          c          := unsigned(window(slice_k * 8 + 7 downto slice_k * 8));
          above_1(k) <= greater(c, v);
          below_1(k) <= greater(v, c);
          up(k)      <= c - v;
          down(k)    <= v - c;
        end loop;

        for k in 0 to CIRCLE_SIZE - 1 loop
          diff(k) <= up(k) when above_1(k) = '1' else down(k);
        end loop;
        above <= above_1;
        below <= below_1;
      end if;
    end if;

  end process differences;

end architecture rtl;
