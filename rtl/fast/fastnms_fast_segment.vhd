-- FAST-9/16 segment test: corner = '1' when 9 cyclically contiguous circle
-- pixels are all brighter than centre + t, or all darker than centre - t.
--
-- Three register stages under the shared advance enable `en`:
--   1. the 32 tests above(k) and brighter(k) > t, below(k) and darker(k) > t;
--   2. for each of the 16 arc starts and both polarities, the AND of 9 flags;
--   3. the OR of the 32 arcs.
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
    brighter  : in    circle_bytes_t;
    darker    : in    circle_bytes_t;
    corner    : out   std_logic
  );
end entity fastnms_fast_segment;

architecture rtl of fastnms_fast_segment is

  signal is_brighter : circle_flags_t;
  signal is_darker   : circle_flags_t;
  signal arc_bright  : circle_flags_t;
  signal arc_dark    : circle_flags_t;

begin

  stages : process (clk) is

    variable all_bright : std_logic;
    variable all_dark   : std_logic;

  begin

    if rising_edge(clk) then
      if en = '1' then
        for k in 0 to CIRCLE_SIZE - 1 loop
          is_brighter(k) <= above(k) and to_sl(brighter(k) > threshold);
          is_darker(k)   <= below(k) and to_sl(darker(k) > threshold);
        end loop;

        for k in 0 to CIRCLE_SIZE - 1 loop
          all_bright := '1';
          all_dark   := '1';
          for n in 0 to ARC_LENGTH - 1 loop
            all_bright := all_bright and is_brighter(wrap(k, n));
            all_dark   := all_dark and is_darker(wrap(k, n));
          end loop;
          arc_bright(k) <= all_bright;
          arc_dark(k)   <= all_dark;
        end loop;

        corner <= or arc_bright or (or arc_dark);
      end if;
    end if;

  end process stages;

end architecture rtl;
