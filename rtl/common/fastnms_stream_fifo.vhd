-- First-word-fall-through FIFO on the project's one RAM entity.
--
-- in_ready is a flip-flop ('1' while there is room for one more beat), and
-- so is in_room2 ('1' while there is room for two: a producer with one
-- register stage after its decision pushes without looking at in_ready); the
-- head of the queue is presented on out_data with out_valid and leaves on a
-- clock with out_valid = out_ready = '1'. One beat per clock in and out; a
-- beat written into an empty FIFO appears on the output two clocks later.
-- DEPTH counts the RAM entries; the output register holds one more beat.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_stream_fifo is
  generic (
    DEPTH : positive := 512;
    WIDTH : positive := 8;
    STYLE : string   := "block"
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_room2  : out   std_logic;
    in_data   : in    std_logic_vector(WIDTH - 1 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(WIDTH - 1 downto 0)
  );
end entity fastnms_stream_fifo;

architecture rtl of fastnms_stream_fifo is

  constant PTR_BITS : positive := clog2(DEPTH);

  signal wr_ptr : unsigned(PTR_BITS - 1 downto 0);
  signal rd_ptr : unsigned(PTR_BITS - 1 downto 0);
  -- Beats in the RAM (written and not yet read), 0 .. DEPTH.
  signal stored         : unsigned(bits_for(DEPTH) - 1 downto 0);
  signal room           : std_logic;
  signal room2          : std_logic;
  signal head_full      : std_logic;
  signal push           : std_logic;
  signal level_full     : std_logic;
  signal level_full1    : std_logic;
  signal level_full2    : std_logic;
  signal going_up       : std_logic;
  signal stored_plus    : unsigned(bits_for(DEPTH) - 1 downto 0);
  signal stored_minus_n : unsigned(bits_for(DEPTH) - 1 downto 0);
  signal has_data       : std_logic;
  signal level_empty    : std_logic;
  signal level_one      : std_logic;
  signal going_down     : std_logic;
  signal load           : std_logic;

begin

  assert DEPTH >= 2
    report "fastnms_stream_fifo: DEPTH must be at least 2"
    severity failure;

  push <= in_valid and room;
  -- Read the next beat into the output register when it is empty or leaving.
  load      <= has_data and (not head_full or out_ready);
  in_ready  <= room;
  in_room2  <= room2;
  out_valid <= head_full;

  -- Fill level, and the room flags from it without an adder in front of a
  -- comparator: which of "full", "full - 1", "full - 2" the level is now,
  -- and whether it goes up or down this clock.
  level_full  <= to_sl(stored = DEPTH);
  level_full1 <= to_sl(stored = DEPTH - 1);
  level_full2 <= to_sl(stored = DEPTH - 2);
  going_up    <= push and not load;
  level_empty <= to_sl(stored = 0);
  level_one   <= to_sl(stored = 1);
  going_down  <= load and not push;

  control : process (clk) is
  begin

    if rising_edge(clk) then
      if push = '1' then
        if wr_ptr = DEPTH - 1 then
          wr_ptr <= (others => '0');
        else
          wr_ptr <= wr_ptr + 1;
        end if;
      end if;
      if load = '1' then
        if rd_ptr = DEPTH - 1 then
          rd_ptr <= (others => '0');
        else
          rd_ptr <= rd_ptr + 1;
        end if;
      end if;
      -- The level and both its neighbours are registers: no adder sits
      -- behind the up/down decision.
      -- (level - 1 is kept inverted: it then counts up as well.)
      if going_up = '1' then
        stored         <= stored_plus;
        stored_plus    <= stored_plus + 1;
        stored_minus_n <= not stored;
      elsif going_down = '1' then
        stored         <= not stored_minus_n;
        stored_plus    <= stored;
        stored_minus_n <= stored_minus_n + 1;
      end if;
      has_data <= not ((level_empty and not going_up) or (level_one and going_down));
      -- Full next clock: full and not going down, or one short and going up.
      room <= not ((level_full and not going_down) or (level_full1 and going_up));
      -- At most one place next clock.
      room2 <= not ((level_full and not going_down) or (level_full1 and not going_down) or
                    (level_full2 and going_up));
      if load = '1' then
        head_full <= '1';
      elsif out_ready = '1' then
        head_full <= '0';
      end if;
      if rst = '1' then
        wr_ptr         <= (others => '0');
        rd_ptr         <= (others => '0');
        stored         <= (others => '0');
        stored_plus    <= to_unsigned(1, stored'length);
        stored_minus_n <= (others => '0');
        has_data       <= '0';
        room           <= '0';
        room2          <= '0';
        head_full      <= '0';
      end if;
    end if;

  end process control;

  memory : entity work.fastnms_ram_sdp
    generic map (
      DEPTH        => DEPTH,
      WIDTH        => WIDTH,
      READ_LATENCY => 1,
      STYLE        => STYLE
    )
    port map (
      clk     => clk,
      wr_en   => push,
      wr_addr => wr_ptr,
      wr_data => in_data,
      rd_en   => load,
      rd_addr => rd_ptr,
      rd_data => out_data
    );

end architecture rtl;
