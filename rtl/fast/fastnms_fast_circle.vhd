-- FAST front stage: from a 7x7 window to the 16 circle differences, split by
-- sign. With v the centre and c_k circle pixel k (OpenCV's order):
--   above(k) = '1' when c_k > v, and then brighter(k) = c_k - v;
--   below(k) = '1' when c_k < v, and then darker(k)   = v - c_k.
-- Where the flag is '0' the difference is meaningless (8 bits, wrapped):
-- leaving the clamp to the consumers keeps this stage one subtractor deep.
-- Everything after works on these values: c_k > v + t exactly when above(k)
-- and brighter(k) > t, c_k < v - t when below(k) and darker(k) > t, so no
-- sum can wrap.
--
-- One register stage under the shared advance enable `en`.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_fast_pkg.all;

entity fastnms_fast_circle is
  port (
    clk      : in    std_logic;
    en       : in    std_logic;
    window   : in    std_logic_vector(WINDOW_SIZE * WINDOW_SIZE * 8 - 1 downto 0);
    above    : out   circle_flags_t;
    below    : out   circle_flags_t;
    brighter : out   circle_bytes_t;
    darker   : out   circle_bytes_t
  );
end entity fastnms_fast_circle;

architecture rtl of fastnms_fast_circle is

  constant CENTRE : natural := RADIUS * WINDOW_SIZE + RADIUS;

begin

  differences : process (clk) is

    variable v       : byte_t;
    variable c       : byte_t;
    variable slice_k : natural;

  begin

    if rising_edge(clk) then
      if en = '1' then
        v := unsigned(window(CENTRE * 8 + 7 downto CENTRE * 8));
        for k in 0 to CIRCLE_SIZE - 1 loop
          slice_k     := circle_slice(k);
          c           := unsigned(window(slice_k * 8 + 7 downto slice_k * 8));
          above(k)    <= '1' when c > v else '0';
          below(k)    <= '1' when c < v else '0';
          brighter(k) <= c - v;
          darker(k)   <= v - c;
        end loop;
      end if;
    end if;

  end process differences;

end architecture rtl;
