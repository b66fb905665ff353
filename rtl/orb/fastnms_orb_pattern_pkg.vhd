-- ORB's sampling pattern, OpenCV's bit_pattern_31_, as data: entries
-- 4i .. 4i + 3 of ORB_PATTERN are bit i's x0, y0, x1, y1 (each in -13 .. 12),
-- checked against golden/orb_pattern.py; and the order golden/sample_order.py
-- gives the points (orb_point_at, orb_lane_reach).
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;

package fastnms_orb_pattern_pkg is

  constant ORB_POINTS    : positive := 512;
  constant ORB_COORD_MIN : integer  := -13;
  constant ORB_COORD_MAX : integer  := 12;

  type orb_pattern_t is array (0 to 2 * ORB_POINTS - 1) of integer range ORB_COORD_MIN to ORB_COORD_MAX;

  constant ORB_PATTERN : orb_pattern_t :=
  (
    8,  -3,   9,   5,   4,   2,   7, -12,
    -11,   9,  -8,   2,   7, -12,  12, -13,
    2, -13,   2,  12,   1,  -7,   1,   6,
    -2, -10,  -2,  -4, -13, -13, -11,  -8,
    -13,  -3, -12,  -9,  10,   4,  11,   9,
    -13,  -8,  -8,  -9, -11,   7,  -9,  12,
    7,   7,  12,   6,  -4,  -5,  -3,   0,
    -13,   2, -12,  -3,  -9,   0,  -7,   5,
    12,  -6,  12,  -1,  -3,   6,  -2,  12,
    -6, -13,  -4,  -8,  11, -13,  12,  -8,
    4,   7,   5,   1,   5,  -3,  10,  -3,
    3,  -7,   6,  12,  -8,  -7,  -6,  -2,
    -2,  11,  -1, -10, -13,  12,  -8,  10,
    -7,   3,  -5,  -3,  -4,   2,  -3,   7,
    -10, -12,  -6,  11,   5, -12,   6,  -7,
    5,  -6,   7,  -1,   1,   0,   4,  -5,
    9,  11,  11, -13,   4,   7,   4,  12,
    2,  -1,   4,   4,  -4, -12,  -2,   7,
    -8,  -5,  -7, -10,   4,  11,   9,  12,
    0,  -8,   1, -13, -13,  -2,  -8,   2,
    -3,  -2,  -2,   3,  -6,   9,  -4,  -9,
    8,  12,  10,   7,   0,   9,   1,   3,
    7,  -5,  11, -10, -13,  -6, -11,   0,
    10,   7,  12,   1,  -6,  -3,  -6,  12,
    10,  -9,  12,  -4, -13,   8,  -8, -12,
    -13,   0,  -8,  -4,   3,   3,   7,   8,
    5,   7,  10,  -7,  -1,   7,   1, -12,
    3, -10,   5,   6,   2,  -4,   3, -10,
    -13,   0, -13,   5, -13,  -7, -12,  12,
    -13,   3, -11,   8,  -7,  12,  -4,   7,
    6, -10,  12,   8,  -9,  -1,  -7,  -6,
    -2,  -5,   0,  12, -12,   5,  -7,   5,
    3, -10,   8, -13,  -7,  -7,  -4,   5,
    -3,  -2,  -1,  -7,   2,   9,   5, -11,
    -11, -13,  -5, -13,  -1,   6,   0,  -1,
    5,  -3,   5,   2,  -4, -13,  -4,  12,
    -9,  -6,  -9,   6, -12, -10,  -8,  -4,
    10,   2,  12,  -3,   7,  12,  12,  12,
    -7, -13,  -6,   5,  -4,   9,  -3,   4,
    7,  -1,  12,   2,  -7,   6,  -5,   1,
    -13,  11, -12,   5,  -3,   7,  -2,  -6,
    7,  -8,  12,  -7, -13,  -7, -11, -12,
    1,  -3,  12,  12,   2,  -6,   3,   0,
    -4,   3,  -2, -13,  -1, -13,   1,   9,
    7,   1,   8,  -6,   1,  -1,   3,  12,
    9,   1,  12,   6,  -1,  -9,  -1,   3,
    -13, -13, -10,   5,   7,   7,  10,  12,
    12,  -5,  12,   9,   6,   3,   7,  11,
    5, -13,   6,  10,   2, -12,   2,   3,
    3,   8,   4,  -6,   2,   6,  12, -13,
    9, -12,  10,   3,  -8,   4,  -7,   9,
    -11,  12,  -4,  -6,   1,  12,   2,  -8,
    6,  -9,   7,  -4,   2,   3,   3,  -2,
    6,   3,  11,   0,   3,  -3,   8,  -8,
    7,   8,   9,   3, -11,  -5,  -6,  -4,
    -10,  11,  -5,  10,  -5,  -8,  -3,  12,
    -10,   5,  -9,   0,   8,  -1,  12,  -6,
    4,  -6,   6, -11, -10,  12,  -8,   7,
    4,  -2,   6,   7,  -2,   0,  -2,  12,
    -5,  -8,  -5,   2,   7,  -6,  10,  12,
    -9, -13,  -8,  -8,  -5, -13,  -5,  -2,
    8,  -8,   9, -13,  -9, -11,  -9,   0,
    1,  -8,   1,  -2,   7,  -4,   9,   1,
    -2,   1,  -1,  -4,  11,  -6,  12, -11,
    -12,  -9,  -6,   4,   3,   7,   7,  12,
    5,   5,  10,   8,   0,  -4,   2,   8,
    -9,  12,  -5, -13,   0,   7,   2,  12,
    -1,   2,   1,   7,   5,  11,   7,  -9,
    3,   5,   6,  -8, -13,  -4,  -8,   9,
    -5,   9,  -3,  -3,  -4,  -7,  -3, -12,
    6,   5,   8,   0,  -7,   6,  -6,  12,
    -13,   6,  -5,  -2,   1, -10,   3,  10,
    4,   1,   8,  -4,  -2,  -2,   2, -13,
    2, -12,  12,  12,  -2, -13,   0,  -6,
    4,   1,   9,   3,  -6, -10,  -3,  -5,
    -3, -13,  -1,   1,   7,   5,  12, -11,
    4,  -2,   5,  -7, -13,   9,  -9,  -5,
    7,   1,   8,   6,   7,  -8,   7,   6,
    -7,  -4,  -7,   1,  -8,  11,  -7,  -8,
    -13,   6, -12,  -8,   2,   4,   3,   9,
    10,  -5,  12,   3,  -6,  -5,  -6,   7,
    8,  -3,   9,  -8,   2, -12,   2,   8,
    -11,  -2, -10,   3, -12, -13,  -7,  -9,
    -11,   0, -10,  -5,   5,  -3,  11,   8,
    -2, -13,  -1,  12,  -1,  -8,   0,   9,
    -13, -11, -12,  -5, -10,  -2, -10,  11,
    -3,   9,  -2, -13,   2,  -3,   3,   2,
    -9, -13,  -4,   0,  -4,   6,  -3, -10,
    -4,  12,  -2,  -7,  -6, -11,  -4,   9,
    6,  -3,   6,  11, -13,  11,  -5,   5,
    11,  11,  12,   6,   7,  -5,  12,  -2,
    -1,  12,   0,   7,  -4,  -8,  -3,  -2,
    -7,   1,  -6,   7, -13, -12,  -8, -13,
    -7,  -2,  -6,  -8,  -8,   5,  -6,  -9,
    -5,  -1,  -4,   5, -13,   7,  -8,  10,
    1,   5,   5, -13,   1,   0,  10, -13,
    9,  12,  10,  -1,   5,  -8,  10,  -9,
    -1,  11,   1, -13,  -9,  -3,  -6,   2,
    -1, -10,   1,  12, -13,   1,  -8, -10,
    8, -11,  10,  -6,   2, -13,   3,  -6,
    7, -13,  12,  -9, -10, -10,  -5,  -7,
    -10,  -8,  -8, -13,   4,  -6,   8,   5,
    3,  12,   8, -13,  -4,   2,  -3,  -3,
    5, -13,  10, -12,   4, -13,   5,  -1,
    -9,   9,  -4,   3,   0,   3,   3,  -9,
    -12,   1,  -6,   1,   3,   2,   4,  -8,
    -10, -10, -10,   9,   8, -13,  12,  12,
    -8, -12,  -6,  -5,   2,   2,   3,   7,
    10,   6,  11,  -8,   6,   8,   8, -12,
    -7,  10,  -6,   5,  -3,  -9,  -3,   9,
    -1, -13,  -1,   5,  -3,  -7,  -3,   4,
    -8,  -2,  -8,   3,   4,   2,  12,  12,
    2,  -5,   3,  11,   6,  -9,  11, -13,
    3,  -1,   7,  12,  11,  -1,  12,   4,
    -3,   0,  -3,   6,   4, -11,   4,  12,
    2,  -4,   2,   1, -10,  -6,  -8,   1,
    -13,   7, -11,   1, -13,  12, -11, -13,
    6,   0,  11, -13,   0,  -1,   1,   4,
    -13,   3,  -9,  -2,  -9,   8,  -6,  -3,
    -13,  -6,  -8,  -2,   5,  -9,   8,  10,
    2,   7,   3,  -9,  -1,  -6,  -1,  -1,
    9,   5,  11,  -2,  11,  -3,  12,  -8,
    3,   0,   3,   5,  -1,   4,   0,  10,
    3,  -6,   4,   5, -13,   0, -10,   5,
    5,   8,  12,  11,   8,   9,   9,  -6,
    7,  -4,   8, -12, -10,   4, -10,   9,
    7,   3,  12,   4,   9,  -7,  10,  -2,
    7,   0,  12,  -2,  -1,  -6,   0, -11
  );

  constant ORB_PAIRS : positive := ORB_POINTS / 2;

  -- A point's reach: the smallest R with (2R + 1)**2 > 4 (px**2 + py**2).
  function orb_point_reach (p : natural) return natural;

  -- The pattern point in lane `lane` at step `step` (0 .. 512 / lanes - 1):
  -- lanes = 1, the pattern's order; otherwise lanes 2j and 2j + 1 carry the two
  -- ends of pair ORB_PAIRS_BY_REACH(j * 512 / lanes + step).
  function orb_point_at (step : natural; lane : natural; lanes : positive) return natural;

  -- The largest reach among the points of lane `lane`.
  function orb_lane_reach (lane : natural; lanes : positive) return natural;

  type orb_pair_order_t is array (0 to ORB_PAIRS - 1) of natural range 0 to ORB_PAIRS - 1;

  -- The pairs sorted by reach (the larger of their two points'), ties in pattern order.
  constant ORB_PAIRS_BY_REACH : orb_pair_order_t;

end package fastnms_orb_pattern_pkg;

package body fastnms_orb_pattern_pkg is

  function orb_point_reach (p : natural) return natural is
    variable rho2 : natural;
    variable r    : natural := 0;
  begin

    rho2 := ORB_PATTERN(2 * p) ** 2 + ORB_PATTERN(2 * p + 1) ** 2;

    while (2 * r + 1) ** 2 <= 4 * rho2 loop

      r := r + 1;

    end loop;

    return r;

  end function orb_point_reach;

  function orb_pair_reach (i : natural) return natural is
  begin

    return maximum(orb_point_reach(2 * i), orb_point_reach(2 * i + 1));

  end function orb_pair_reach;

  function sort_pairs_by_reach return orb_pair_order_t is
    variable order : orb_pair_order_t;
    variable n     : natural := 0;
  begin

    -- A counting sort over the reaches (0 .. 18): stable.
    for r in 0 to 18 loop

      for i in 0 to ORB_PAIRS - 1 loop

        if orb_pair_reach(i) = r then
          order(n) := i;
          n        := n + 1;
        end if;

      end loop;

    end loop;

    assert n = ORB_PAIRS
      report "fastnms_orb_pattern_pkg: a pair reaches beyond 18"
      severity failure;
    return order;

  end function sort_pairs_by_reach;

  constant ORB_PAIRS_BY_REACH : orb_pair_order_t := sort_pairs_by_reach;

  function orb_point_at (step : natural; lane : natural; lanes : positive) return natural is
  begin

    -- LANES 1, or a value the entities refuse (their assertions need the
    -- elaboration to get that far): the pattern's order.
    if lanes /= 2 and lanes /= 4 and lanes /= 8 and lanes /= 16 then
      return step mod ORB_POINTS;
    end if;

    return 2 * ORB_PAIRS_BY_REACH((lane / 2) * (ORB_POINTS / lanes) + step) + lane mod 2;

  end function orb_point_at;

  function orb_lane_reach (lane : natural; lanes : positive) return natural is
    variable r : natural := 0;
  begin

    for s in 0 to ORB_POINTS / lanes - 1 loop

      r := maximum(r, orb_point_reach(orb_point_at(s, lane, lanes)));

    end loop;

    return r;

  end function orb_lane_reach;

end package body fastnms_orb_pattern_pkg;
