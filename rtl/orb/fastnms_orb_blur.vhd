-- ORB's blur of one pixel: OpenCV's bit-exact GaussianBlur(7x7, sigma 2) at
-- the centre of fastnms_window's 7x7 window, 13 clocks of `en`.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_orb_blur is
  port (
    clk     : in    std_logic;
    en      : in    std_logic;
    window  : in    std_logic_vector(7 * 7 * 8 - 1 downto 0);
    blurred : out   std_logic_vector(7 downto 0)
  );
end entity fastnms_orb_blur;

architecture rtl of fastnms_orb_blur is

  constant SIDE : natural := 7;

  type halves_t is array (0 to SIDE - 1) of unsigned(14 downto 0);

  signal column_half : halves_t;
  signal highs       : std_logic_vector(SIDE * 8 - 1 downto 0); -- H of each column
  signal lows        : std_logic_vector(SIDE * 8 - 1 downto 0); -- L of each column
  signal sh          : unsigned(14 downto 0);                   -- SH (at most 16 256)
  signal sl          : unsigned(14 downto 0);                   -- SL (at most 32 640)
  signal sh_1        : unsigned(13 downto 0);
  signal x_1         : unsigned(15 downto 0);                   -- SL + 2**13
  signal top_2       : unsigned(7 downto 0);                    -- SH >> 6
  signal x_top_2     : unsigned(1 downto 0);                    -- X >> 14
  signal low_2       : unsigned(6 downto 0);                    -- SH mod 64 + (X >> 8) mod 64
  signal out_3       : unsigned(7 downto 0);

begin

  columns : for col in 0 to SIDE - 1 generate
    signal taps : std_logic_vector(SIDE * 8 - 1 downto 0);
  begin

    rows : for row in 0 to SIDE - 1 generate
      taps(8 * row + 7 downto 8 * row) <= window((row * SIDE + col) * 8 + 7 downto (row * SIDE + col) * 8);
    end generate rows;

    vertical : entity work.fastnms_orb_kernel7
      port map (
        clk      => clk,
        en       => en,
        in_x     => taps,
        out_half => column_half(col)
      );

    highs(8 * col + 7 downto 8 * col) <= '0' & std_logic_vector(column_half(col)(14 downto 8));
    lows(8 * col + 7 downto 8 * col)  <= std_logic_vector(column_half(col)(7 downto 0));

  end generate columns;

  horizontal_high : entity work.fastnms_orb_kernel7
    port map (
      clk      => clk,
      en       => en,
      in_x     => highs,
      out_half => sh
    );

  horizontal_low : entity work.fastnms_orb_kernel7
    port map (
      clk      => clk,
      en       => en,
      in_x     => lows,
      out_half => sl
    );

  -- (256 SH + X) >> 14 = (SH + (X >> 8)) >> 6, X = SL + 2**13: the low six bits'
  -- carry a stage ahead of the high bits.
  rounding : process (clk) is
  begin

    if rising_edge(clk) then
      if en = '1' then
        sh_1 <= sh(13 downto 0);
        x_1  <= resize(sl, 16) + 2 ** 13;

        top_2   <= sh_1(13 downto 6);
        x_top_2 <= x_1(15 downto 14);
        low_2   <= resize(sh_1(5 downto 0), 7) + x_1(13 downto 8);

        out_3 <= top_2 + x_top_2 + unsigned'(0 => low_2(6));
      end if;
    end if;

  end process rounding;

  blurred <= std_logic_vector(out_3);

end architecture rtl;
