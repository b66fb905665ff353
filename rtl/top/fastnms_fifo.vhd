-- First-word-fall-through FIFO on one fastnms_ram_sdp, with registered
-- readies on both sides.
--
-- The RAM holds 2**clog2(DEPTH) words (DEPTH rounded up to a power of two);
-- three more words sit in the output stage (the RAM's read register and a
-- skid buffer), so at least DEPTH + 3 words fit. in_ready is a register: it
-- drops when the RAM is full, or one word before when a word is written on
-- that clock (one clock of caution that costs no throughput unless the FIFO
-- is full). One word in and one out per clock. A word written into an empty
-- FIFO is presented at the output two clocks after the clock it was written on.
--
-- `busy` is '1' while any word is inside (one clock late).
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_fifo is
  generic (
    DEPTH : positive := 512;
    WIDTH : positive := 36
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_data   : in    std_logic_vector(WIDTH - 1 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(WIDTH - 1 downto 0);
    busy      : out   std_logic
  );
end entity fastnms_fifo;

architecture rtl of fastnms_fifo is

  constant ADDR_BITS : positive := clog2(DEPTH);

  -- Pointers with one wrap bit: equal when empty, equal but for the wrap
  -- bit when full. wr_next is wr_ptr + 1, rd_next rd_ptr + 1, rd_next2
  -- rd_ptr + 2 (the flags are computed one clock ahead from them).
  signal wr_ptr   : unsigned(ADDR_BITS downto 0);
  signal wr_next  : unsigned(ADDR_BITS downto 0);
  signal rd_ptr   : unsigned(ADDR_BITS downto 0);
  signal rd_next  : unsigned(ADDR_BITS downto 0);
  signal rd_next2 : unsigned(ADDR_BITS downto 0);

  signal empty   : std_logic; -- no word in the RAM (a register)
  signal single  : std_logic; -- one word in the RAM (a register)
  signal double  : std_logic; -- two words in the RAM
  signal full    : std_logic; -- 2**ADDR_BITS words in the RAM
  signal last    : std_logic; -- 2**ADDR_BITS - 1 words in the RAM
  signal ready   : std_logic;
  signal write   : std_logic;
  signal read_en : std_logic; -- the RAM's read register advances
  signal read    : std_logic; -- ... and takes a word

  signal q_valid     : std_logic;
  signal q_data      : std_logic_vector(WIDTH - 1 downto 0);
  signal skid_ready  : std_logic;
  signal out_valid_i : std_logic;

begin

  double <= to_sl(wr_ptr = rd_next2);
  full   <= to_sl(wr_ptr(ADDR_BITS) /= rd_ptr(ADDR_BITS) and
                  wr_ptr(ADDR_BITS - 1 downto 0) = rd_ptr(ADDR_BITS - 1 downto 0));
  last   <= to_sl(wr_next(ADDR_BITS) /= rd_ptr(ADDR_BITS) and
                  wr_next(ADDR_BITS - 1 downto 0) = rd_ptr(ADDR_BITS - 1 downto 0));

  write   <= in_valid and ready;
  read_en <= not q_valid or skid_ready;
  read    <= read_en and not empty;

  pointers : process (clk) is
  begin

    if rising_edge(clk) then
      if rst = '1' then
        wr_ptr  <= (others => '0');
        wr_next <= to_unsigned(1, wr_next'length);
      elsif write = '1' then
        wr_ptr  <= wr_next;
        wr_next <= wr_next + 1;
      end if;

      if rst = '1' then
        rd_ptr   <= (others => '0');
        rd_next  <= to_unsigned(1, rd_next'length);
        rd_next2 <= to_unsigned(2, rd_next2'length);
      elsif read = '1' then
        rd_ptr   <= rd_next;
        rd_next  <= rd_next2;
        rd_next2 <= rd_next2 + 1;
      end if;

      ready <= not (full or (last and write));
      -- The level after this clock: the old one, +1 on a write, -1 on a read.
      empty <= (empty or (read and single)) and not write;
      if write = read then
        single <= single;
      elsif write = '1' then
        single <= empty;
      else
        single <= double;
      end if;
      if read_en = '1' then
        q_valid <= not empty;
      end if;
      busy <= not empty or q_valid or out_valid_i;

      if rst = '1' then
        ready   <= '0';
        empty   <= '1';
        single  <= '0';
        q_valid <= '0';
        busy    <= '0';
      end if;
    end if;

  end process pointers;

  in_ready <= ready;

  ram : entity work.fastnms_ram_sdp
    generic map (
      DEPTH        => 2 ** ADDR_BITS,
      WIDTH        => WIDTH,
      READ_LATENCY => 1,
      STYLE        => "block"
    )
    port map (
      clk     => clk,
      wr_en   => write,
      wr_addr => wr_ptr(ADDR_BITS - 1 downto 0),
      wr_data => in_data,
      rd_en   => read_en,
      rd_addr => rd_ptr(ADDR_BITS - 1 downto 0),
      rd_data => q_data
    );

  output_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => WIDTH
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => q_valid,
      in_ready  => skid_ready,
      in_data   => q_data,
      out_valid => out_valid_i,
      out_ready => out_ready,
      out_data  => out_data
    );

  out_valid <= out_valid_i;

end architecture rtl;
