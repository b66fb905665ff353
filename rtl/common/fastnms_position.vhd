-- Position of a pixel stream: the column x and the row y, one counter each,
-- the one way the blocks count where a pixel is (the window generator's
-- input and output sides, the NMS blocks, the video checker).
--
-- Each axis has three controls, in this priority:
--   clear  the axis becomes 0 (a new line for x, a new frame for y)
--   start  the axis becomes 1 (the clock's pixel was the first one: x after
--          a start of frame that is not also the end of its line)
--   step   the axis counts one up (a pixel for x, a line for y)
-- and keeps its value otherwise. The new value is on x / y on the clock
-- after the control (registered outputs, no reset of their own: a user
-- resets them by putting rst into x_clear and y_clear).
--
-- The user decides when a line or frame wraps (from tlast/eof, from a
-- registered "last column" flag compared one pixel ahead, or from a flush
-- pass), so the flags stay with it; this block keeps the counting itself
-- short: clear is the flip-flops' reset, step their enable, and the next
-- value is the carry chain (start costs a LUT on bit 0 only, and nothing when
-- tied to '0').
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
