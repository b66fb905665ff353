-- First-word-fall-through FIFO on one fastnms_ram_sdp, with registered
-- readies on both sides and an almost_full flag: the project's one FIFO.
-- Datasheet: docs/fastnms_fifo.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_fifo is
  generic (
    DEPTH : positive := 512;
    WIDTH : positive := 36;
    -- ram_style of the RAM (see fastnms_ram_sdp): "distributed" for a few words.
    STYLE : string := "block";
    -- almost_full is '1' when the RAM held at least this many words three clocks
    -- before; '0' on a clock promises in_ready on it and on the next
    -- WORDS - 2 - ALMOST_FULL_LEVEL clocks. 1 .. DEPTH (GHDL keeps 512 when
    -- -gDEPTH alone is given).
    ALMOST_FULL_LEVEL : positive := DEPTH
  );
  port (
    clk         : in    std_logic;
    rst         : in    std_logic;
    in_valid    : in    std_logic;
    in_ready    : out   std_logic;
    almost_full : out   std_logic;
    in_data     : in    std_logic_vector(WIDTH - 1 downto 0);
    out_valid   : out   std_logic;
    out_ready   : in    std_logic;
    out_data    : out   std_logic_vector(WIDTH - 1 downto 0);
    busy        : out   std_logic
  );
end entity fastnms_fifo;

architecture rtl of fastnms_fifo is

  constant WORDS     : positive := fifo_words(DEPTH);
  constant ADDR_BITS : positive := clog2(WORDS);

  signal wr_ptr : unsigned(ADDR_BITS - 1 downto 0);
  signal rd_ptr : unsigned(ADDR_BITS - 1 downto 0);
  -- Words in the RAM one clock ago, and that clock's write and read.
  signal level   : unsigned(ADDR_BITS downto 0);
  signal wrote   : std_logic;
  signal took    : std_logic;
  signal delta   : unsigned(ADDR_BITS downto 0); -- wrote - took
  signal filled  : std_logic;                    -- a word is in the RAM for sure
  signal ready   : std_logic;
  signal almost  : std_logic;
  signal write   : std_logic;
  signal read_en : std_logic;                    -- the RAM's read register advances
  signal read    : std_logic;                    -- ... and takes a word

  signal q_valid     : std_logic;
  signal q_data      : std_logic_vector(WIDTH - 1 downto 0);
  signal skid_ready  : std_logic;
  signal out_valid_i : std_logic;

begin

  assert DEPTH <= 2 ** 16
    report "fastnms_fifo: DEPTH must be at most 65536"
    severity failure;
  assert ALMOST_FULL_LEVEL <= DEPTH
    report "fastnms_fifo: ALMOST_FULL_LEVEL must be within 1 .. DEPTH"
    severity failure;

  -- level - took >= 1: level >= 2, or level = 1 without a read.
  filled <= (or level(ADDR_BITS downto 1)) or (level(0) and not took);

  write   <= in_valid and ready;
  read_en <= not q_valid or skid_ready;
  read    <= read_en and filled;

  pointers : process (clk) is
  begin

    if rising_edge(clk) then
      if rst = '1' then
        wr_ptr <= (others => '0');
      elsif write = '1' then
        wr_ptr <= wr_ptr + 1;
      end if;

      if rst = '1' then
        rd_ptr <= (others => '0');
      elsif read = '1' then
        rd_ptr <= rd_ptr + 1;
      end if;

      -- delta: +1, -1 or 0, a register, so that the adder has one LUT.
      wrote <= write;
      took  <= read;
      if read = '1' and write = '0' then
        delta <= (others => '1');
      elsif write = '1' and read = '0' then
        delta <= to_unsigned(1, delta'length);
      else
        delta <= (others => '0');
      end if;
      level <= level + delta;
      -- Room for the words of this clock and the next: level <= WORDS - 3
      -- (WORDS is a power of two, so level >= WORDS - 2 is a gate, not a compare).
      ready <= not (level(ADDR_BITS) or (and level(ADDR_BITS - 1 downto 1)));
      -- Below ALMOST_FULL_LEVEL, the level m clocks later is at most
      -- ALMOST_FULL_LEVEL - 1 + m: in_ready (level <= WORDS - 3) while
      -- m <= WORDS - 2 - ALMOST_FULL_LEVEL.
      almost <= to_sl(level >= ALMOST_FULL_LEVEL);
      if read_en = '1' then
        q_valid <= filled;
      end if;
      busy <= (or level) or wrote or q_valid or out_valid_i;

      if rst = '1' then
        wrote   <= '0';
        took    <= '0';
        delta   <= (others => '0');
        level   <= (others => '0');
        ready   <= '0';
        almost  <= '1';
        q_valid <= '0';
        busy    <= '0';
      end if;
    end if;

  end process pointers;

  in_ready    <= ready;
  almost_full <= almost;

  ram : entity work.fastnms_ram_sdp
    generic map (
      DEPTH        => WORDS,
      WIDTH        => WIDTH,
      READ_LATENCY => 1,
      STYLE        => STYLE
    )
    port map (
      clk     => clk,
      wr_en   => write,
      wr_addr => wr_ptr,
      wr_data => in_data,
      rd_en   => read_en,
      rd_addr => rd_ptr,
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
