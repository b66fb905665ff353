-- A wide event counter built from SEGMENT-bit segments with short carry
-- chains, exact on every clock; clear restarts the count.
-- Datasheet: docs/fastnms_counter.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_counter is
  generic (
    WIDTH   : positive := 32;
    SEGMENT : positive := 12
  );
  port (
    clk   : in    std_logic;
    rst   : in    std_logic;
    clear : in    std_logic;
    step  : in    std_logic;
    value : out   unsigned(WIDTH - 1 downto 0)
  );
end entity fastnms_counter;

architecture rtl of fastnms_counter is

  constant SEGMENTS : positive := (WIDTH + SEGMENT - 1) / SEGMENT;

  signal count : unsigned(WIDTH - 1 downto 0);
  -- ones(k): segment k is all ones.
  signal ones : std_logic_vector(SEGMENTS - 1 downto 0);
  -- carry(k): segment k counts on this clock.
  signal carry : std_logic_vector(SEGMENTS - 1 downto 0);

begin

  assert SEGMENT >= 2
    report "fastnms_counter: SEGMENT must be at least 2"
    severity failure;

  carry(0) <= step;

  carries : for k in 1 to SEGMENTS - 1 generate
    carry(k) <= carry(k - 1) and ones(k - 1);
  end generate carries;

  counting : process (clk) is

    variable lo : natural;
    variable hi : natural;

  begin

    if rising_edge(clk) then

      for k in 0 to SEGMENTS - 1 loop

        lo := k * SEGMENT;
        hi := minimum(WIDTH, lo + SEGMENT) - 1;
        if clear = '1' or rst = '1' then
          count(hi downto lo) <= (others => '0');
          ones(k)             <= '0';
        elsif carry(k) = '1' then
          count(hi downto lo) <= count(hi downto lo) + 1;
          -- The segment becomes all ones when it is all ones but bit 0.
          ones(k) <= (and count(hi downto lo + 1)) and not count(lo);
        end if;

      end loop;

      if clear = '1' and rst = '0' then
        count(0) <= step;
      end if;
    end if;

  end process counting;

  value <= count;

end architecture rtl;
