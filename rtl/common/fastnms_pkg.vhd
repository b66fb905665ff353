-- Shared helpers: clog2, bits_for, fifo_words, to_sl, at_least, greater.
-- Datasheet: docs/README.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

package fastnms_pkg is

  -- Bits needed to hold the values 0 .. n-1 (at least 1).
  function clog2 (n : positive) return positive;

  -- Bits needed to hold the value n itself.
  function bits_for (n : natural) return positive;

  -- The RAM words of a fastnms_fifo of `depth` words: depth rounded up to a
  -- power of two, at least 4 (its ALMOST_FULL_LEVEL counts from them).
  function fifo_words (depth : positive) return positive;

  -- '1' for true.
  function to_sl (b : boolean) return std_logic;

  -- '1' when x >= c, as a chain of gates rather than a subtractor, so that it
  -- maps to two levels of LUTs instead of a carry chain.
  function at_least (x : unsigned; c : natural) return std_logic;

  -- '1' when a > b (same length), as a chain of gates: it maps to LUTs only,
  -- leaving the carry chains to the subtractors beside it.
  function greater (a : unsigned; b : unsigned) return std_logic;

  -- The power-up value of a data register or memory word: zeros in
  -- simulation, as FPGA flip-flops and RAM start, so that compares made every
  -- clock on not yet written data raise no metavalue warnings; 'U' (none) in
  -- synthesis. No logic depends on it: the fast engine simulates the netlist
  -- from random power-up values (sim/tests/test_engines.py).
  function sim_zeros (n : positive) return std_logic_vector;

  -- The lines after which an NMS built with ROW_MARKS sends a row-end beat:
  -- y mod 16 = 15, the last lines of the keypoint budget's smallest cells.
  function is_mark_line (y : unsigned) return boolean;

end package fastnms_pkg;

package body fastnms_pkg is

  function clog2 (n : positive) return positive is
    variable bits : positive := 1;
  begin
    while 2 ** bits < n loop
      bits := bits + 1;
    end loop;
    return bits;
  end function clog2;

  function bits_for (n : natural) return positive is
  begin
    return clog2(n + 1);
  end function bits_for;

  function fifo_words (depth : positive) return positive is
  begin

    return 2 ** maximum(2, clog2(depth));

  end function fifo_words;

  function to_sl (b : boolean) return std_logic is
  begin

    if b then
      return '1';
    end if;

    return '0';
  end function to_sl;

  function at_least (x : unsigned; c : natural) return std_logic is
    constant CV : unsigned(x'length downto 0) := to_unsigned(c, x'length + 1);
    variable ge : std_logic                   := '1'; -- x(-1 downto 0) >= c(-1 downto 0)
    variable xv : unsigned(x'length - 1 downto 0);
  begin

    if CV(x'length) = '1' then
      return '0';
    end if;

    xv := x;
    for i in 0 to x'length - 1 loop

      if CV(i) = '1' then
        ge := xv(i) and ge;
      else
        ge := xv(i) or ge;
      end if;

    end loop;
    return ge;
  end function at_least;

  function greater (a : unsigned; b : unsigned) return std_logic is
    variable av : unsigned(a'length - 1 downto 0);
    variable bv : unsigned(b'length - 1 downto 0);
    variable gt : std_logic := '0'; -- a(i-1 downto 0) > b(i-1 downto 0)
  begin
    av := a;
    bv := b;
    for i in 0 to a'length - 1 loop
      gt := (av(i) and not bv(i)) or (not (av(i) xor bv(i)) and gt);
    end loop;
    return gt;
  end function greater;

  function sim_zeros (n : positive) return std_logic_vector is
    variable v : std_logic_vector(n - 1 downto 0);
  begin

    -- synthesis translate_off
    v := (others => '0');
    -- synthesis translate_on

    return v;

  end function sim_zeros;

  function is_mark_line (y : unsigned) return boolean is
    variable wide : unsigned(15 downto 0);
  begin
    wide := resize(y, 16);
    return wide(3 downto 0) = "1111";
  end function is_mark_line;

end package body fastnms_pkg;
