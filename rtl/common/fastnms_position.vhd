-- The column x and row y of a pixel stream, one counter each (clear, start,
-- step): the one way the blocks count where a pixel is.
-- Datasheet: docs/fastnms_position.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_position is
  generic (
    X_BITS : positive := 11;
    Y_BITS : positive := 12
  );
  port (
    clk     : in    std_logic;
    x_clear : in    std_logic;
    x_start : in    std_logic;
    x_step  : in    std_logic;
    y_clear : in    std_logic;
    y_start : in    std_logic;
    y_step  : in    std_logic;
    x       : out   unsigned(X_BITS - 1 downto 0);
    y       : out   unsigned(Y_BITS - 1 downto 0)
  );
end entity fastnms_position;

architecture rtl of fastnms_position is

  signal x_count : unsigned(X_BITS - 1 downto 0);
  signal y_count : unsigned(Y_BITS - 1 downto 0);

begin

  assert X_BITS <= 16 and Y_BITS <= 16
    report "fastnms_position: X_BITS and Y_BITS must be at most 16"
    severity failure;

  counting : process (clk) is
  begin

    if rising_edge(clk) then
      if x_clear = '1' then
        x_count <= (others => '0');
      elsif x_start = '1' then
        x_count <= to_unsigned(1, X_BITS);
      elsif x_step = '1' then
        x_count <= x_count + 1;
      end if;
      if y_clear = '1' then
        y_count <= (others => '0');
      elsif y_start = '1' then
        y_count <= to_unsigned(1, Y_BITS);
      elsif y_step = '1' then
        y_count <= y_count + 1;
      end if;
    end if;

  end process counting;

  x <= x_count;
  y <= y_count;

end architecture rtl;
