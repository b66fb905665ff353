-- The paper's sum-of-absolute-differences corner score, 8 register stages
-- under the shared advance enable `en`.
-- Datasheet: docs/fastnms_fast_detector.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_fast_pkg.all;

entity fastnms_fast_score_sad is
  port (
    clk       : in    std_logic;
    en        : in    std_logic;
    threshold : in    byte_t;
    above     : in    circle_flags_t;
    below     : in    circle_flags_t;
    diff      : in    circle_bytes_t;
    score     : out   unsigned(11 downto 0)
  );
end entity fastnms_fast_score_sad;

architecture rtl of fastnms_fast_score_sad is

  subtype sum_t is unsigned(11 downto 0);

  -- Terms and partial sums of both sides: entries 0..n-1 brighter, n..2n-1
  -- darker.
  type bytes_t is array (natural range <>) of byte_t;

  type sums_t is array (natural range <>) of sum_t;

  -- Entry i: x(2i) + x(2i + 1), widened.
  function byte_pair_sums (x : bytes_t) return sums_t is
    variable sums : sums_t(0 to x'length / 2 - 1);
  begin
    for i in sums'range loop
      sums(i) := resize(x(x'low + 2 * i), sum_t'length) + resize(x(x'low + 2 * i + 1), sum_t'length);
    end loop;
    return sums;
  end function byte_pair_sums;

  -- Adds neighbouring pairs: entry i of the result is x(2i) + x(2i + 1).
  function pair_sums (x : sums_t) return sums_t is

    variable sums : sums_t(0 to x'length / 2 - 1);

  begin

    for i in sums'range loop
      sums(i) := x(x'low + 2 * i) + x(x'low + 2 * i + 1);
    end loop;
    return sums;

  end function pair_sums;

  signal excess      : circle_bytes_t; -- diff(k) - t
  signal terms       : bytes_t(0 to 2 * CIRCLE_SIZE - 1);
  signal is_brighter : circle_flags_t;
  signal is_darker   : circle_flags_t;
  signal sums_8      : sums_t(0 to 15);
  signal sums_4      : sums_t(0 to 7);
  signal sums_2      : sums_t(0 to 3);
  signal sums_1      : sums_t(0 to 1);
  signal sum_bright  : sum_t;
  signal sum_dark    : sum_t;
  signal bright_ge   : std_logic;

begin

  stages : process (clk) is
  begin

    if rising_edge(clk) then
      if en = '1' then
        for k in 0 to CIRCLE_SIZE - 1 loop
          excess(k)      <= diff(k) - threshold;
          is_brighter(k) <= above(k) and to_sl(diff(k) > threshold);
          is_darker(k)   <= below(k) and to_sl(diff(k) > threshold);
        end loop;

        for k in 0 to CIRCLE_SIZE - 1 loop
          terms(k)               <= excess(k) when is_brighter(k) = '1' else
                                    (others => '0');
          terms(CIRCLE_SIZE + k) <= excess(k) when is_darker(k) = '1' else
                                    (others => '0');
        end loop;

        sums_8 <= byte_pair_sums(terms);
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
