-- OpenCV's FAST corner score (cornerScore<16>), 7 register stages under the
-- shared advance enable `en`.
-- Datasheet: docs/fastnms_fast_detector.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_fast_pkg.all;

entity fastnms_fast_score_opencv is
  port (
    clk   : in    std_logic;
    en    : in    std_logic;
    above : in    circle_flags_t;
    below : in    circle_flags_t;
    diff  : in    circle_bytes_t;
    score : out   byte_t
  );
end entity fastnms_fast_score_opencv;

architecture rtl of fastnms_fast_score_opencv is

  type bytes_t is array (natural range <>) of byte_t;

  -- Minima of the triples (k, k + step, k + 2 * step), k = 0..15, cyclic.
  -- Pair (k, k + step) is compared once and serves triples k and k - step.
  function triple_minima (x : circle_bytes_t; step : positive) return circle_bytes_t is

    variable near   : std_logic_vector(0 to CIRCLE_SIZE - 1); -- x(k) <= x(k + step)
    variable far    : std_logic_vector(0 to CIRCLE_SIZE - 1); -- x(k) <= x(k + 2 * step)
    variable minima : circle_bytes_t;

  begin

    for k in 0 to CIRCLE_SIZE - 1 loop
      near(k) := '1' when x(k) <= x(wrap(k, step)) else '0';
      far(k)  := '1' when x(k) <= x(wrap(k, 2 * step)) else '0';
    end loop;

    for k in 0 to CIRCLE_SIZE - 1 loop

      if near(k) = '1' and far(k) = '1' then
        minima(k) := x(k);
      elsif near(k) = '0' and near(wrap(k, step)) = '1' then
        minima(k) := x(wrap(k, step));
      else
        minima(k) := x(wrap(k, 2 * step));
      end if;

    end loop;

    return minima;

  end function triple_minima;

  function max3 (a : byte_t; b : byte_t; c : byte_t) return byte_t is
  begin

    if a >= b and a >= c then
      return a;
    elsif b >= c then
      return b;
    end if;

    return c;

  end function max3;

  signal above_3  : circle_flags_t;
  signal below_3  : circle_flags_t;
  signal above_9  : circle_flags_t;
  signal below_9  : circle_flags_t;
  signal minima_3 : circle_bytes_t;
  signal minima_9 : circle_bytes_t;
  signal arcs     : circle_bytes_t;
  signal max_6    : bytes_t(0 to 5);
  signal max_2    : bytes_t(0 to 1);
  signal max_1    : byte_t;

begin

  stages : process (clk) is
  begin

    if rising_edge(clk) then
      if en = '1' then
        above_3 <= triple_and(above, 1);
        below_3 <= triple_and(below, 1);
        above_9 <= triple_and(above_3, 3);
        below_9 <= triple_and(below_3, 3);

        minima_3 <= triple_minima(diff, 1);
        minima_9 <= triple_minima(minima_3, 3);

        for k in 0 to CIRCLE_SIZE - 1 loop
          arcs(k) <= minima_9(k) when above_9(k) = '1' or below_9(k) = '1' else (others => '0');
        end loop;

        for g in 0 to 4 loop
          max_6(g) <= max3(arcs(3 * g), arcs(3 * g + 1), arcs(3 * g + 2));
        end loop;
        max_6(5) <= arcs(15);

        max_2(0) <= max3(max_6(0), max_6(1), max_6(2));
        max_2(1) <= max3(max_6(3), max_6(4), max_6(5));

        max_1 <= max_2(0) when max_2(0) >= max_2(1) else max_2(1);

        score <= max_1 - 1;
      end if;
    end if;

  end process stages;

end architecture rtl;
