-- Skid buffer: a two-entry pipeline register whose in_ready is a flip-flop,
-- the one way the core cuts a ready path. Full throughput: one beat per clock
-- while out_ready stays high; when out_ready drops, the beat already on its
-- way is parked in the skid register.
library ieee;
  use ieee.std_logic_1164.all;

entity fastnms_skid_buffer is
  generic (
    WIDTH : positive := 8
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_data   : in    std_logic_vector(WIDTH - 1 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(WIDTH - 1 downto 0)
  );
end entity fastnms_skid_buffer;

architecture rtl of fastnms_skid_buffer is

  signal main_valid : std_logic;
  signal main_data  : std_logic_vector(WIDTH - 1 downto 0);
  signal skid_valid : std_logic;
  signal skid_data  : std_logic_vector(WIDTH - 1 downto 0);

begin

  registers : process (clk) is
  begin

    if rising_edge(clk) then
      if skid_valid = '0' then
        if main_valid = '0' or out_ready = '1' then
          main_valid <= in_valid;
          main_data  <= in_data;
        else
          skid_valid <= in_valid;
          skid_data  <= in_data;
        end if;
      elsif out_ready = '1' then
        main_data  <= skid_data;
        skid_valid <= '0';
      end if;

      if rst = '1' then
        main_valid <= '0';
        skid_valid <= '0';
      end if;
    end if;

  end process registers;

  in_ready  <= not skid_valid;
  out_valid <= main_valid;
  out_data  <= main_data;

end architecture rtl;
