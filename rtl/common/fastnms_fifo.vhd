-- First-word-fall-through FIFO on one fastnms_ram_sdp, with registered
-- readies on both sides: the project's one FIFO (the AXI top's corner FIFO,
-- the region NMS's record FIFO, the serializer's beat FIFO).
--
-- The RAM has WORDS = 2**clog2(DEPTH) words (DEPTH rounded up to a power of
-- two, at least 4); three more words sit in the output stage (the RAM's read
-- register and a skid buffer, so out_data comes from flip-flops). One word
-- in and one out per clock. A word written into an empty FIFO is on the
-- output on the fourth clock after the clock it was written on.
--
-- Capacity, stated as guarantees (tb/common/fifo_tb.py checks them on every
-- clock of random traffic):
--   in_ready is '1' on every clock on which fewer than WORDS - 2 words are
--     inside (so at least DEPTH - 2); a producer that never holds more than
--     WORDS - 3 words in it can push without looking at in_ready;
--   with the output stalled it takes WORDS + 3 words (at least DEPTH);
--   in_room2 = '1' on a clock means in_ready = '1' on the next clock too:
--     room for this clock's word and the next one, for a producer with one
--     register stage after its decision;
--   in_room3 = '1' on a clock means in_ready = '1' on the next two clocks
--     too, for a producer with two register stages after its decision;
--   in_spare = '1' on a clock means that after a word written on it, in_ready
--     stays '1' on every later clock until the next write: room for this
--     word and one that may come any time later (never with WORDS < 8).
-- A write while in_ready = '0' is ignored.
--
-- Logic depth: the pointers only address the RAM, and no two registers are
-- ever compared. The flags come from a level register compared with
-- constants; the level is counted one clock late, from the registered write
-- and read of the clock before (so its update is an adder with a registered
-- operand: one LUT and the carry chain). Both flags are conservative for that
-- clock: a word is read only if it is in the RAM even without the last
-- clock's write (so a word written into an empty FIFO waits one more clock),
-- and in_ready drops while the RAM may have fewer than three free words
-- (in_room2 while it may have fewer than four, in_room3 fewer than five).
--
-- Up to 2048 words the level has at most 12 bits and the logic at most 4
-- levels. `busy` is '1' while any word is inside (one clock late).
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
    STYLE : string := "block"
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_room2  : out   std_logic;
    in_room3  : out   std_logic;
    in_spare  : out   std_logic;
    in_data   : in    std_logic_vector(WIDTH - 1 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(WIDTH - 1 downto 0);
    busy      : out   std_logic
  );
end entity fastnms_fifo;

architecture rtl of fastnms_fifo is

  constant ADDR_BITS : positive := maximum(2, clog2(DEPTH));
  constant WORDS     : positive := 2 ** ADDR_BITS;

  signal wr_ptr : unsigned(ADDR_BITS - 1 downto 0);
  signal rd_ptr : unsigned(ADDR_BITS - 1 downto 0);
  -- Words in the RAM one clock ago, and that clock's write and read.
  signal level   : unsigned(ADDR_BITS downto 0);
  signal wrote   : std_logic;
  signal took    : std_logic;
  signal delta   : unsigned(ADDR_BITS downto 0); -- wrote - took
  signal filled  : std_logic;                    -- a word is in the RAM for sure
  signal ready   : std_logic;
  signal room2   : std_logic;
  signal room3   : std_logic;
  signal spare   : std_logic;
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
      -- Room for the words of this clock and the next two: level <= WORDS - 4.
      room2 <= to_sl(level <= WORDS - 4);
      -- ... and the next three: level <= WORDS - 5 (never with WORDS = 4).
      room3 <= to_sl(WORDS >= 5 and level <= maximum(WORDS - 5, 0));
      -- A write now leaves level <= WORDS - 3 (in_ready) once the two writes
      -- the level does not show yet are in: level <= WORDS - 6.
      spare <= to_sl(to_integer(level) <= WORDS - 6);
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
        room2   <= '0';
        room3   <= '0';
        spare   <= '0';
        q_valid <= '0';
        busy    <= '0';
      end if;
    end if;

  end process pointers;

  in_ready <= ready;
  in_room2 <= room2;
  in_room3 <= room3;
  in_spare <= spare;

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
