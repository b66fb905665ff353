-- Half the weighted sum of seven values under ORB's 7-tap Gaussian kernel
-- (18 34 48 56 48 34 18), exact, in 5 stages of short carry chains.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_orb_kernel7 is
  port (
    clk      : in    std_logic;
    en       : in    std_logic;
    in_x     : in    std_logic_vector(7 * 8 - 1 downto 0); -- x_i in bits 8 i + 7 .. 8 i
    out_half : out   unsigned(14 downto 0)
  );
end entity fastnms_orb_kernel7;

architecture rtl of fastnms_orb_kernel7 is

  function x (v : std_logic_vector; i : natural) return unsigned is
  begin

    return unsigned(v(8 * i + 7 downto 8 * i));

  end function x;

  signal p1 : unsigned(8 downto 0);  -- x0 + x6
  signal q1 : unsigned(8 downto 0);  -- x1 + x5
  signal r1 : unsigned(8 downto 0);  -- x2 + x4
  signal c1 : unsigned(7 downto 0);  -- x3
  signal a2 : unsigned(9 downto 0);  -- p + q
  signal b2 : unsigned(10 downto 0); -- p + 2 q
  signal u2 : unsigned(9 downto 0);  -- r + c
  signal c2 : unsigned(7 downto 0);
  signal a3 : unsigned(10 downto 0); -- A = p + q + 4 c
  signal b3 : unsigned(10 downto 0);
  signal t3 : unsigned(11 downto 0); -- 3 (r + c)
  signal a4 : unsigned(10 downto 0);
  signal b4 : unsigned(11 downto 0); -- B = p + 2 q + 3 (r + c)
  signal h5 : unsigned(14 downto 0); -- A + 8 B

begin

  stages : process (clk) is
  begin

    if rising_edge(clk) then
      if en = '1' then
        p1 <= resize(x(in_x, 0), 9) + x(in_x, 6);
        q1 <= resize(x(in_x, 1), 9) + x(in_x, 5);
        r1 <= resize(x(in_x, 2), 9) + x(in_x, 4);
        c1 <= x(in_x, 3);

        a2 <= resize(p1, 10) + q1;
        b2 <= resize(p1, 11) + shift_left(resize(q1, 11), 1);
        u2 <= resize(r1, 10) + c1;
        c2 <= c1;

        a3 <= resize(a2, 11) + shift_left(resize(c2, 11), 2);
        b3 <= b2;
        t3 <= resize(u2, 12) + shift_left(resize(u2, 12), 1);

        a4 <= a3;
        b4 <= resize(b3, 12) + t3;

        h5 <= resize(a4, 15) + shift_left(resize(b4, 15), 3);
      end if;
    end if;

  end process stages;

  out_half <= h5;

end architecture rtl;
