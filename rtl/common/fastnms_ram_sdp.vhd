-- Simple dual-port RAM (one write port, one read port, one clock): every
-- memory of the core is an instance, so RAM inference is proven once.
-- Datasheet: docs/fastnms_ram_sdp.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_ram_sdp is
  generic (
    DEPTH        : positive := 1920;
    WIDTH        : positive := 48;
    READ_LATENCY : positive := 1;
    STYLE        : string   := "block"
  );
  port (
    clk     : in    std_logic;
    wr_en   : in    std_logic;
    wr_addr : in    unsigned(clog2(DEPTH) - 1 downto 0);
    wr_data : in    std_logic_vector(WIDTH - 1 downto 0);
    rd_en   : in    std_logic;
    rd_addr : in    unsigned(clog2(DEPTH) - 1 downto 0);
    rd_data : out   std_logic_vector(WIDTH - 1 downto 0)
  );
end entity fastnms_ram_sdp;

architecture rtl of fastnms_ram_sdp is

  type mem_t is array (0 to DEPTH - 1) of std_logic_vector(WIDTH - 1 downto 0);

  signal rd_array : std_logic_vector(WIDTH - 1 downto 0);

  attribute ram_style : string;

begin

  assert READ_LATENCY <= 2
    report "fastnms_ram_sdp: READ_LATENCY must be 1 or 2"
    severity failure;

  assert STYLE = "block" or STYLE = "distributed" or STYLE = "auto"
    report "fastnms_ram_sdp: STYLE must be ""block"", ""distributed"" or ""auto"""
    severity failure;

  -- The memory, in a generate named by its style. Vivado reads ram_style;
  -- GHDL's netlist drops attributes but keeps the name (lut_style_mem),
  -- from which the synthesis flow (flows/synth/synth.py) tells yosys.

  other_style : if STYLE /= "distributed" generate
    -- Zero in simulation only (sim_zeros).
    signal mem : mem_t := (others => sim_zeros(WIDTH));

    attribute ram_style of mem : signal is STYLE;
  begin

    ports : process (clk) is
    begin

      if rising_edge(clk) then
        if wr_en = '1' then
          mem(to_integer(wr_addr)) <= wr_data;
        end if;
        if rd_en = '1' then
          rd_array <= mem(to_integer(rd_addr));
        end if;
      end if;

    end process ports;

  end generate other_style;

  lut_style : if STYLE = "distributed" generate
    signal mem : mem_t := (others => sim_zeros(WIDTH));

    attribute ram_style of mem : signal is STYLE;
  begin

    ports : process (clk) is
    begin

      if rising_edge(clk) then
        if wr_en = '1' then
          mem(to_integer(wr_addr)) <= wr_data;
        end if;
        if rd_en = '1' then
          rd_array <= mem(to_integer(rd_addr));
        end if;
      end if;

    end process ports;

  end generate lut_style;

  latency_1 : if READ_LATENCY = 1 generate
    rd_data <= rd_array;
  end generate latency_1;

  latency_2 : if READ_LATENCY = 2 generate
    signal rd_reg : std_logic_vector(WIDTH - 1 downto 0);
  begin

    output_register : process (clk) is
    begin

      if rising_edge(clk) then
        if rd_en = '1' then
          rd_reg <= rd_array;
        end if;
      end if;

    end process output_register;

    rd_data <= rd_reg;
  end generate latency_2;

end architecture rtl;
