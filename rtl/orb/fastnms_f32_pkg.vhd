-- What the float32 units share: their domain check and the last step of a
-- rounding.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

package fastnms_f32_pkg is

  subtype f32_t is std_logic_vector(31 downto 0);

  -- +-0 or a normal number: the units' operands and results (simulation checks).
  function in_domain (f : f32_t) return boolean;

  -- The word of a rounded result: sign, then the exponent field (field, before the
  -- hidden one of kept adds in) plus the significand kept (hidden one at bit 23)
  -- plus the round-up bit, in one add, so that a carry out of the significand
  -- carries into the exponent; +-0 when zero.
  function packed (sign : std_logic; zero : std_logic; field : unsigned(7 downto 0);
    kept : unsigned(23 downto 0); up : std_logic) return f32_t;

end package fastnms_f32_pkg;

package body fastnms_f32_pkg is

  function in_domain (f : f32_t) return boolean is
  begin

    return (f(30 downto 23) /= x"00" or f(22 downto 0) = (22 downto 0 => '0')) and f(30 downto 23) /= x"FF";

  end function in_domain;

  function packed (sign : std_logic; zero : std_logic; field : unsigned(7 downto 0);
    kept : unsigned(23 downto 0); up : std_logic) return f32_t is
    variable mag : unsigned(30 downto 0);
  begin

    if zero = '1' then
      return sign & (30 downto 0 => '0');
    end if;

    mag := shift_left(resize(field, 31), 23) + kept + unsigned'(0 => up);
    return sign & std_logic_vector(mag);

  end function packed;

end package body fastnms_f32_pkg;
