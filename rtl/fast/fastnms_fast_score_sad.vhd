-- The paper's corner score (eq. 1) with the threshold taken off each term:
-- max(sum over brighter pixels of (c - v - t), sum over darker pixels of
-- (v - c - t)). 0 .. 4080, 12 bits. For a non-corner the value is
-- meaningless (the detector masks it).
--
-- Seven register stages under the shared advance enable `en`:
--   1. the 32 terms brighter(k) - t, darker(k) - t, or 0 where the pixel is
--      not brighter than centre + t (darker than centre - t);
--   2.-5. a pipelined adder tree per polarity, 16 -> 8 -> 4 -> 2 -> 1;
--   6. the comparison of the two sums;
--   7. the larger sum.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_fast_pkg.all;

entity fastnms_fast_score_sad is
  port (
    clk       : in    std_logic;
    en        : in    std_logic;
    threshold : in    byte_t;
    above     : in    circle_flags_t;
    below     : in    circle_flags_t;
    brighter  : in    circle_bytes_t;
    darker    : in    circle_bytes_t;
    score     : out   unsigned(11 downto 0)
  );
end entity fastnms_fast_score_sad;

architecture rtl of fastnms_fast_score_sad is

  subtype sum_t is unsigned(11 downto 0);

  -- Partial sums of both polarities: entries 0..n-1 brighter, n..2n-1 darker.
  type sums_t is array (natural range <>) of sum_t;

  function saturated_term (valid : std_logic; x : byte_t; t : byte_t) return sum_t is
  begin

    if valid = '1' and x > t then
      return resize(x - t, sum_t'length);
    end if;

    return (others => '0');

  end function saturated_term;

  -- Adds neighbouring pairs: entry i of the result is x(2i) + x(2i + 1).
  function pair_sums (x : sums_t) return sums_t is

    variable sums : sums_t(0 to x'length / 2 - 1);

  begin

    for i in sums'range loop
      sums(i) := x(x'low + 2 * i) + x(x'low + 2 * i + 1);
    end loop;
    return sums;

  end function pair_sums;

  signal terms      : sums_t(0 to 2 * CIRCLE_SIZE - 1);
  signal sums_8     : sums_t(0 to 15);
  signal sums_4     : sums_t(0 to 7);
  signal sums_2     : sums_t(0 to 3);
  signal sums_1     : sums_t(0 to 1);
  signal sum_bright : sum_t;
  signal sum_dark   : sum_t;
  signal bright_ge  : std_logic;

begin

  stages : process (clk) is
  begin

    if rising_edge(clk) then
      if en = '1' then
        for k in 0 to CIRCLE_SIZE - 1 loop
          terms(k)               <= saturated_term(above(k), brighter(k), threshold);
          terms(CIRCLE_SIZE + k) <= saturated_term(below(k), darker(k), threshold);
        end loop;

        sums_8 <= pair_sums(terms);
        sums_4 <= pair_sums(sums_8);
        sums_2 <= pair_sums(sums_4);
        sums_1 <= pair_sums(sums_2);

        sum_bright <= sums_1(0);
        sum_dark   <= sums_1(1);
        bright_ge  <= '1' when sums_1(0) >= sums_1(1) else '0';

        score <= sum_bright when bright_ge = '1' else sum_dark;
      end if;
    end if;

  end process stages;

end architecture rtl;
