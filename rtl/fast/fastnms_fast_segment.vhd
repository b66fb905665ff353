-- FAST-9/16 segment test: 9 contiguous circle pixels all brighter than
-- centre + t or all darker than centre - t; 3 register stages.
-- Datasheet: docs/fastnms_fast_detector.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_fast_pkg.all;

entity fastnms_fast_segment is
  port (
    clk       : in    std_logic;
    en        : in    std_logic;
    threshold : in    byte_t;
    above     : in    circle_flags_t;
    below     : in    circle_flags_t;
    diff      : in    circle_bytes_t;
    corner    : out   std_logic
  );
end entity fastnms_fast_segment;

architecture rtl of fastnms_fast_segment is

  signal is_brighter : circle_flags_t;
  signal is_darker   : circle_flags_t;
  signal bright_3    : circle_flags_t;
  signal dark_3      : circle_flags_t;

begin

  stages : process (clk) is
  begin

    if rising_edge(clk) then
      if en = '1' then
        for k in 0 to CIRCLE_SIZE - 1 loop
          is_brighter(k) <= above(k) and to_sl(diff(k) > threshold);
          is_darker(k)   <= below(k) and to_sl(diff(k) > threshold);
        end loop;

        bright_3 <= triple_and(is_brighter, 1);
        dark_3   <= triple_and(is_darker, 1);

        corner <= or (triple_and(bright_3, 3) or triple_and(dark_3, 3));
      end if;
    end if;

  end process stages;

end architecture rtl;
