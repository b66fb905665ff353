-- Shared helpers for the fastnms core.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

package fastnms_pkg is

  -- Bits needed to hold the values 0 .. n-1 (at least 1).
  function clog2 (n : positive) return positive;

  -- Bits needed to hold the value n itself.
  function bits_for (n : natural) return positive;

  -- '1' for true.
  function to_sl (b : boolean) return std_logic;

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

  function to_sl (b : boolean) return std_logic is
  begin

    if b then
      return '1';
    end if;

    return '0';
  end function to_sl;

end package body fastnms_pkg;
