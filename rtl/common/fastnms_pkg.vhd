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

  -- fastnms_core's internal_error bits (in the order of fastnms_axi's STATUS
  -- bits 7 .. 10): errors that would corrupt or misalign records.
  constant INTERNAL_ORB_ROWS     : natural  := 0;
  constant INTERNAL_ORB_TAGS     : natural  := 1;
  constant INTERNAL_ORB_COUNT    : natural  := 2;
  constant INTERNAL_CONFIG_QUEUE : natural  := 3;
  constant INTERNAL_ERRORS       : positive := 4;

  -- The ORB engine in fastnms_core: ORB_LANES points per clock, so a keypoint
  -- every 512 / ORB_LANES clocks (docs/orb_rtl.md, Throughput).
  constant ORB_LANES : positive := 8;

  -- The largest K (records per cell) the ORB engine sustains at one pixel per
  -- clock with cells of 16 * 2 ** cell_log pixels: a cell row's keypoints take
  -- no more clocks than its pixels, K <= CELL * CELL / (512 / ORB_LANES);
  -- at most 15, the budget's largest K.
  function orb_rate_per_cell (cell_log : natural) return natural;

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

  function orb_rate_per_cell (cell_log : natural) return natural is
    constant CELL : positive := 16 * 2 ** minimum(cell_log, 4);
  begin
    return minimum(15, CELL * CELL / (512 / ORB_LANES));
  end function orb_rate_per_cell;

end package body fastnms_pkg;
