-- OpenCV's FAST corner score (cornerScore<16>): over the 16 arcs of 9
-- contiguous circle pixels, the largest arc minimum of (c - v) or of (v - c),
-- minus 1. For a corner it lies in t .. 254; for a non-corner the value is
-- meaningless (the detector masks it).
--
-- A corner's score comes from an arc whose pixels are all on one side of the
-- centre (the arc minimum of the other side is negative). So the minima are
-- taken over the raw differences brighter(k) = c_k - v and darker(k) =
-- v - c_k, and an arc counts only when all its pixels are above (below) v:
-- there the differences are exact, and an arc cannot be both, so one OR
-- merges the two sides.
--
-- Seven register stages under the shared advance enable `en`; each is at
-- most a comparison and a selection (at most 4 levels of logic):
--   1. minima of the 16 cyclic triples (k, k+1, k+2), per polarity; the
--      comparisons of neighbouring pairs are shared between triples;
--   2. arc minima: min of the triples k, k+3, k+6, again sharing pairs;
--   3. the two sides merged (stages 1-2 also find, the same way, the arcs
--      whose pixels are all above or all below v);
--   4.-6. maximum over the 16 arcs, three at a time (16 -> 6 -> 2 -> 1);
--   7. minus 1.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_fast_pkg.all;

entity fastnms_fast_score_opencv is
  port (
    clk      : in    std_logic;
    en       : in    std_logic;
    above    : in    circle_flags_t;
    below    : in    circle_flags_t;
    brighter : in    circle_bytes_t;
    darker   : in    circle_bytes_t;
    score    : out   byte_t
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

  -- AND of the triples (k, k + step, k + 2 * step): with step 1 and then 3,
  -- arc k's pixels all above (below) v, alongside the minima.
  function triple_and (x : circle_flags_t; step : positive) return circle_flags_t is

    variable all_set : circle_flags_t;

  begin

    for k in 0 to CIRCLE_SIZE - 1 loop
      all_set(k) := x(k) and x(wrap(k, step)) and x(wrap(k, 2 * step));
    end loop;
    return all_set;

  end function triple_and;

  signal above_3  : circle_flags_t;
  signal below_3  : circle_flags_t;
  signal above_9  : circle_flags_t;
  signal below_9  : circle_flags_t;
  signal bright_3 : circle_bytes_t;
  signal dark_3   : circle_bytes_t;
  signal bright_9 : circle_bytes_t;
  signal dark_9   : circle_bytes_t;
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

        bright_3 <= triple_minima(brighter, 1);
        dark_3   <= triple_minima(darker, 1);

        bright_9 <= triple_minima(bright_3, 3);
        dark_9   <= triple_minima(dark_3, 3);

        for k in 0 to CIRCLE_SIZE - 1 loop
          arcs(k) <= (bright_9(k) and (7 downto 0 => above_9(k))) or
                     (dark_9(k) and (7 downto 0   => below_9(k)));
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
