-- Probe, not part of the core: a chain of key merges with a deferred select
-- (issue 37), to measure whether it keeps every full-key comparison a stage
-- of its own (key_compare: 4 levels) and every choice one LUT per bit.
--
-- One operand o(s) per clock from an input register (x), with a merge bit:
-- the accumulator acc(s) is the best of the operands since the last one
-- without it (a new class starts), the accumulator winning on equal keys
-- (keys are unsigned, larger is better, and encode the raster order). Both
-- variants hold acc(s - 2) in the register r while o(s) is in x, and output
-- r: acc(s) two clocks after o(s) is in x. They differ in how far back the
-- resolved accumulator is that a choice starts from:
--   LAG 1: acc(s - 1) = best(acc(s - 2), o(s - 1)), the pending pair (r, y)
--     and its flag. The flag of the next pair, acc(s - 1) >= o(s), must be
--     made while acc(s - 1) is still pending: x is compared with both r and
--     y and the pending flag chooses between the two results, a multiplexer
--     after the comparators.
--   LAG 2: acc(s) = best(acc(s - 2), o(s - 1), o(s)): the three are in
--     registers (r, y, x) in the same clock, so their three comparisons are
--     register to register, and a clock later one LUT per bit (three data
--     bits, three flags) chooses acc(s) from their copies (rd, z, y).
-- A new class starts by clearing the flags of the operand that starts it
-- (its flip-flops' synchronous reset, not a level of logic).
-- flows/synth/test_probes_deferred.py maps it with the core's flow;
-- tb/probes/key_deferred_tb.py simulates it against a model.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity key_deferred_chain is
  generic (
    KEY_BITS : positive := 34;
    LAG      : positive := 2
  );
  port (
    clk      : in    std_logic;
    in_key   : in    unsigned(KEY_BITS - 1 downto 0);
    in_merge : in    std_logic;
    out_key  : out   unsigned(KEY_BITS - 1 downto 0)
  );
end entity key_deferred_chain;

architecture rtl of key_deferred_chain is

  -- o(s) and whether it starts a class (not in_merge); o(s - 1); o(s - 2).
  signal x       : unsigned(KEY_BITS - 1 downto 0) := (others => '0');
  signal x_start : std_logic                       := '1';
  signal y       : unsigned(KEY_BITS - 1 downto 0) := (others => '0');
  signal y_start : std_logic                       := '1';
  signal z       : unsigned(KEY_BITS - 1 downto 0) := (others => '0');
  -- The resolved accumulator acc(s - 2), and its copy a clock later.
  signal r  : unsigned(KEY_BITS - 1 downto 0) := (others => '0');
  signal rd : unsigned(KEY_BITS - 1 downto 0) := (others => '0');
  -- LAG 1: f = r >= y, the pending pair's flag. LAG 2, a clock after the
  -- comparisons (rd, z and y then hold what r, y and x held): r_ge_y
  -- (acc(s - 2) keeps against o(s - 1)), r_ge_x, y_ge_x (o(s - 1) keeps
  -- against o(s)), each '0' when the later operand starts a class.
  signal f      : std_logic := '0';
  signal r_ge_y : std_logic := '0';
  signal r_ge_x : std_logic := '0';
  signal y_ge_x : std_logic := '0';

begin

  assert LAG = 1 or LAG = 2
    report "key_deferred_chain: LAG is 1 or 2"
    severity failure;

  operands : process (clk) is
  begin

    if rising_edge(clk) then
      x       <= in_key;
      x_start <= not in_merge;
      y       <= x;
      y_start <= x_start;
      z       <= y;
      rd      <= r;
    end if;

  end process operands;

  lag_one : if LAG = 1 generate

    chain : process (clk) is
    begin

      if rising_edge(clk) then
        -- acc(s - 1), then the next pending pair (acc(s - 1), o(s)) and its
        -- flag: acc(s - 1) is r or y, so its comparison with x is one of two.
        if f = '1' then
          r <= r;
        else
          r <= y;
        end if;
        f <= '0';
        if x_start = '0' then
          if f = '1' and r >= x then
            f <= '1';
          elsif f = '0' and y >= x then
            f <= '1';
          end if;
        end if;
      end if;

    end process chain;

  end generate lag_one;

  lag_two : if LAG = 2 generate

    compare : process (clk) is
    begin

      if rising_edge(clk) then
        -- Register to register: acc(s - 2), o(s - 1) and o(s).
        r_ge_y <= '0';
        if y_start = '0' then
          if r >= y then
            r_ge_y <= '1';
          end if;
        end if;
        r_ge_x <= '0';
        y_ge_x <= '0';
        if x_start = '0' then
          if r >= x then
            r_ge_x <= '1';
          end if;
          if y >= x then
            y_ge_x <= '1';
          end if;
        end if;
      end if;

    end process compare;

    resolve : process (clk) is
    begin

      if rising_edge(clk) then
        -- acc(s) from acc(s - 2) (rd), o(s - 1) (z) and o(s) (y): when
        -- acc(s - 2) keeps against o(s - 1) but not against o(s), o(s) is
        -- better than both and y_ge_x is '0'.
        if r_ge_y = '1' and r_ge_x = '1' then
          r <= rd;
        elsif y_ge_x = '1' then
          r <= z;
        else
          r <= y;
        end if;
      end if;

    end process resolve;

  end generate lag_two;

  out_key <= r;

end architecture rtl;
