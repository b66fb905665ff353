-- Walks one axis of a resize: from the taps of fastnms_resize_taps (each a
-- distance from the one before), a flag that says whether the position
-- reached is a tap, and that tap's weight, on registers only: the pixel
-- pipeline takes them without logic between its decision and the FIFO.
-- Datasheet: docs/fastnms_resize.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_resize_walk is
  generic (
    SIZE_BITS : positive := 12
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- A pulse: forget the taps held; ready rises once the first two are in.
    start : in    std_logic;
    ready : out   std_logic;
    -- Go to the next position (ignored before ready).
    step : in    std_logic;
    -- The position reached is a tap; its weight c0; it is the axis's last.
    hit  : out   std_logic;
    c0   : out   unsigned(7 downto 0);
    last : out   std_logic;
    -- The taps (fastnms_resize_taps).
    in_valid : in    std_logic;
    in_ready : out   std_logic;
    -- Distance from the tap before, minus 2 (fastnms_resize_taps).
    in_delta : in    unsigned(SIZE_BITS - 1 downto 0);
    in_c0    : in    unsigned(7 downto 0);
    in_last  : in    std_logic;
    -- A step onto a tap found no tap filled it (the taps came too late).
    starved : out   std_logic
  );
end entity fastnms_resize_walk;

architecture rtl of fastnms_resize_walk is

  -- The next taps, a queue of three fed with a registered pop (nothing from
  -- step reaches the FIFO): slot 0 is the tap filled the one walked to.
  constant SLOTS : positive := 3;

  type deltas_t is array (0 to SLOTS - 1) of unsigned(SIZE_BITS - 1 downto 0);

  type weights_t is array (0 to SLOTS - 1) of unsigned(7 downto 0);

  signal q_delta : deltas_t;
  signal q_c0    : weights_t;
  signal q_last  : std_logic_vector(SLOTS - 1 downto 0);
  signal q_one   : std_logic_vector(SLOTS - 1 downto 0);
  signal q_valid : std_logic_vector(SLOTS - 1 downto 0);
  signal fill    : natural range 0 to SLOTS;
  signal pop_r   : std_logic;
  signal arrive  : std_logic;
  -- Positions to go to the next tap.
  signal count   : unsigned(SIZE_BITS - 1 downto 0);
  signal target  : unsigned(SIZE_BITS - 1 downto 0);
  signal hit_r   : std_logic;
  signal c0_r    : unsigned(7 downto 0);
  signal last_r  : std_logic;
  signal ready_r : std_logic;
  signal load    : std_logic;
  signal moving  : std_logic;

begin

  -- Load the next tap: at a step onto a tap, or once to begin.
  load     <= (ready_r and step and hit_r) or (not ready_r and q_valid(0));
  moving   <= load or (ready_r and step);
  arrive   <= pop_r and in_valid;
  in_ready <= pop_r;
  hit      <= hit_r;
  c0       <= c0_r;
  last     <= last_r;
  ready    <= ready_r;

  walking : process (clk) is

    variable filled : natural range 0 to SLOTS;

  begin

    if rising_edge(clk) then
      starved <= '0';
      -- Positions walked since the tap loaded: cleared by a load; the next
      -- position is a tap when it reaches the tap's distance - 2.
      if moving = '1' then
        if load = '1' then
          count  <= (others => '0');
          target <= q_delta(0);
          hit_r  <= q_one(0);
        else
          count <= count + 1;
          hit_r <= to_sl(count = target);
        end if;
      end if;
      if load = '1' then
        c0_r    <= q_c0(0);
        last_r  <= q_last(0);
        ready_r <= '1';
        starved <= not q_valid(0);
      end if;

      -- The queue: shift out slot 0 on a load, put an arriving tap behind.
      filled := fill;
      if load = '1' then
        for k in 0 to SLOTS - 2 loop

          q_delta(k) <= q_delta(k + 1);
          q_c0(k)    <= q_c0(k + 1);
          q_last(k)  <= q_last(k + 1);
          q_one(k)   <= q_one(k + 1);
          q_valid(k) <= q_valid(k + 1);

        end loop;

        q_valid(SLOTS - 1) <= '0';
        if fill > 0 then
          filled := fill - 1;
        end if;
      end if;
      if arrive = '1' then
        for k in 0 to SLOTS - 1 loop

          if filled = k then
            q_delta(k) <= in_delta;
            q_c0(k)    <= in_c0;
            q_last(k)  <= in_last;
            q_one(k)   <= and in_delta;
            q_valid(k) <= '1';
          end if;

        end loop;

        filled := filled + 1;
      end if;
      fill <= filled;
      -- Pop when the queue keeps room even if nothing leaves it.
      pop_r <= not (to_sl(fill = SLOTS) or (to_sl(fill = SLOTS - 1) and arrive));

      if rst = '1' or start = '1' then
        q_valid <= (others => '0');
        fill    <= 0;
        pop_r   <= '0';
        ready_r <= '0';
        hit_r   <= '0';
      end if;
    end if;

  end process walking;

end architecture rtl;
