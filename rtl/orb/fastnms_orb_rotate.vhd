-- ORB's rotated sampling pattern: a keypoint's cos and sin in, its 512
-- points rotated as OpenCV rotates them out (golden/float32.py's rotate),
-- LANES per clock, by the fixed-point method of golden/rotate_fixed.py.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_orb_pattern_pkg.all;

entity fastnms_orb_rotate is
  generic (
    LANES : positive := 8
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_cos    : in    std_logic_vector(31 downto 0);
    in_sin    : in    std_logic_vector(31 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_first : out   std_logic;
    out_last  : out   std_logic;
    out_dx    : out   std_logic_vector(6 * LANES - 1 downto 0);
    out_dy    : out   std_logic_vector(6 * LANES - 1 downto 0)
  );
end entity fastnms_orb_rotate;

architecture rtl of fastnms_orb_rotate is

  constant STEPS    : positive              := ORB_POINTS / LANES;
  constant ENTRIES  : positive              := ORB_COORD_MAX - ORB_COORD_MIN + 1;
  constant FRACTION : natural               := 26;
  constant QUARTER  : unsigned(31 downto 0) := shift_left(to_unsigned(1, 32), FRACTION - 2);
  -- Fill: accept, then product, round, shift, entries; the last entry written.
  constant FILL_STAGES : positive := 4;
  constant FILL_CLOCKS : positive := ENTRIES + FILL_STAGES + 1;
  -- The tables' addresses registered (each drives one table's LUT RAM),
  -- fastnms_ram_sdp's read, then fastnms_orb_round_point.
  constant ROUND_LATENCY : positive := 5;
  constant READ_LATENCY  : positive := 2 + ROUND_LATENCY;

  subtype entry_t is std_logic_vector(32 downto 0); -- sticky & two's complement value

  subtype index_t is unsigned(4 downto 0);

  type index_rom_t is array (0 to STEPS - 1) of index_t;

  -- Table index k - ORB_COORD_MIN of coordinate c (0: x, 1: y) of lane l's point at
  -- each step.
  function coordinate_rom (l : natural; c : natural) return index_rom_t is
    variable rom : index_rom_t;
  begin

    for s in rom'range loop

      rom(s) := to_unsigned(ORB_PATTERN(2 * orb_point_at(s, l, LANES) + c) - ORB_COORD_MIN, 5);

    end loop;

    return rom;

  end function coordinate_rom;

  -- A float32 factor (cos or sin) taken apart for the products.
  type factor_t is record
    negative    : std_logic;
    zero        : std_logic;
    significand : unsigned(23 downto 0);
    left        : natural range 0 to 3;  -- shift onto the grid: left ...
    right       : natural range 0 to 31; -- ... or right, with a sticky bit
    dropped     : unsigned(28 downto 0); -- the bits a right shift drops
  end record factor_t;

  function factor (f : std_logic_vector(31 downto 0)) return factor_t is
    variable r : factor_t;
    variable e : integer;
  begin

    e             := to_integer(unsigned(f(30 downto 23)));
    r.negative    := f(31);
    r.zero        := '1' when e = 0 else '0';
    r.significand := unsigned('1' & f(22 downto 0));
    -- fl(k c) = rounded * 2**(e - 150): on the grid, rounded * 2**(e - 150 + 26).
    r.left  := 0;
    r.right := 0;

    if e - 150 + FRACTION >= 0 then
      r.left := minimum(e - 150 + FRACTION, 3);
    else
      r.right := minimum(150 - FRACTION - e, 31);
    end if;

    for i in r.dropped'range loop

      r.dropped(i) := '1' when i < r.right else '0';

    end loop;

    return r;

  end function factor;

  -- |k| in 4 bits (GHDL 2.0's synthesis has no integer abs).
  function magnitude (k : integer) return unsigned is
  begin

    if k < 0 then
      return to_unsigned(-k, 4);
    end if;

    return to_unsigned(k, 4);

  end function magnitude;

  -- |k| c's significand rounded to 24 significant bits (nearest even), as an
  -- integer below 2**29.
  function rounded_product (p : unsigned(27 downto 0)) return unsigned is
    variable drop  : natural range 0 to 4;
    variable kept  : unsigned(27 downto 0);
    variable guard : std_logic;
    variable rest  : boolean;
  begin

    drop := 0;

    for b in 24 to 27 loop

      if p(b) = '1' then
        drop := b - 23;
      end if;

    end loop;

    if drop = 0 then
      return '0' & p;
    end if;

    kept  := shift_right(p, drop);
    guard := p(drop - 1);
    rest  := drop >= 2 and (p and shift_right(x"FFFFFFF", 28 - (drop - 1))) /= 0;

    if guard = '1' and (rest or kept(0) = '1') then
      kept := kept + 1;
    end if;

    return shift_left('0' & kept, drop);

  end function rounded_product;

  -- 0 or a magnitude in 2**-27 .. 1 (simulation checks).
  function in_domain (f : std_logic_vector(31 downto 0)) return boolean is
    variable e : natural;
  begin

    e := to_integer(unsigned(f(30 downto 23)));
    return f(30 downto 0) = (30 downto 0 => '0') or (e >= 100 and e <= 126) or
           f(30 downto 0) = "011" & x"F800000";

  end function in_domain;

  -- The entry of fl(k c) on the grid (mag, sticky) with sign negative, plus 1/4:
  -- floor(-m) = -(floor(m) + sticky) = not floor(m) + 1 - sticky.
  function entry (negative : std_logic; mag : unsigned(31 downto 0); sticky : std_logic)
    return entry_t is
  begin

    if negative = '1' then
      return sticky & std_logic_vector(QUARTER + not mag + unsigned'(0 => not sticky));
    end if;

    return sticky & std_logic_vector(QUARTER + mag);

  end function entry;

  -- Accept and fill.
  signal filling : std_logic; -- from accept to the last write
  signal fill_k  : natural range 0 to ENTRIES - 1;
  -- |k| and k < 0 for k = fill_k + ORB_COORD_MIN, counted beside fill_k (so
  -- the products' operands come straight from registers).
  signal fill_mag  : unsigned(3 downto 0);
  signal fill_neg  : std_logic;
  signal fill_next : std_logic; -- a k enters the pipeline
  signal fill_bank : std_logic;
  signal fa        : factor_t;
  signal fb        : factor_t;
  -- Fill pipeline: product (1), rounded (2), on the grid (3), entries (4).
  signal f_valid  : std_logic_vector(1 to FILL_STAGES);
  signal f_last   : std_logic_vector(1 to FILL_STAGES);
  signal f_neg_k  : std_logic;
  signal prod_a   : unsigned(27 downto 0);
  signal prod_b   : unsigned(27 downto 0);
  signal r_neg_a  : std_logic;
  signal r_neg_b  : std_logic;
  signal round_a  : unsigned(28 downto 0);
  signal round_b  : unsigned(28 downto 0);
  signal g_neg_a  : std_logic;
  signal g_neg_b  : std_logic;
  signal mag_a    : unsigned(31 downto 0);
  signal mag_b    : unsigned(31 downto 0);
  signal sticky_a : std_logic;
  signal sticky_b : std_logic;

  type index_pipe_t is array (1 to FILL_STAGES) of index_t;

  signal f_index : index_pipe_t;
  signal wr_addr : unsigned(5 downto 0);
  signal wr_pa   : entry_t;
  signal wr_pb   : entry_t;
  signal wr_nb   : entry_t;

  -- Banks: full from the last write of a table to the last read of it (one
  -- register per bank: GHDL 2.0's synthesis drops the flip-flops of an array
  -- element indexed by a signal).
  signal full_0     : std_logic;
  signal full_1     : std_logic;
  signal fill_full  : std_logic;
  signal read_full  : std_logic;
  signal read_bank  : std_logic;
  signal step       : natural range 0 to STEPS - 1;
  signal issue      : std_logic;
  signal valid_pipe : std_logic_vector(1 to READ_LATENCY);
  signal first_pipe : std_logic_vector(1 to READ_LATENCY);
  signal last_pipe  : std_logic_vector(1 to READ_LATENCY);

  -- The read pipeline never stalls (no enable reaches the tables and the
  -- rounding units): its steps land in a FIFO, and a step is issued only
  -- while the FIFO promises room READ_LATENCY clocks later.
  constant POINT_BITS  : positive := 12 * LANES + 2;
  constant OUT_WORDS   : positive := 16;
  constant ROOM_LEVEL  : positive := OUT_WORDS - 2 - READ_LATENCY;
  signal   almost_full : std_logic;
  signal   points_room : std_logic;
  signal   points      : std_logic_vector(POINT_BITS - 1 downto 0);
  signal   points_out  : std_logic_vector(POINT_BITS - 1 downto 0);

  -- fl(k c) on the grid: its magnitude and sticky bit.

  procedure on_grid (
    r             : unsigned(28 downto 0);
    f             : factor_t;
    signal mag    : out unsigned(31 downto 0);
    signal sticky : out std_logic
  ) is
    variable dropped : unsigned(28 downto 0);
  begin

    dropped := r and f.dropped;

    if f.zero = '1' then
      mag    <= (others => '0');
      sticky <= '0';
    elsif f.right = 0 then
      mag    <= shift_left(resize(r, 32), f.left);
      sticky <= '0';
    else
      mag <= resize(shift_right(r, f.right), 32);
      sticky <= '1' when dropped /= 0 else '0';
    end if;

  end procedure on_grid;

begin

  assert LANES = 1 or LANES = 2 or LANES = 4 or LANES = 8 or LANES = 16
    report "fastnms_orb_rotate: LANES must be 1, 2, 4, 8 or 16 (a power of two dividing 512)"
    severity failure;

  fill_full <= full_1 when fill_bank = '1' else
               full_0;
  read_full <= full_1 when read_bank = '1' else
               full_0;
  in_ready  <= not filling and not fill_full;

  fill : process (clk) is
  begin

    if rising_edge(clk) then
      -- 1: |k| times the significands.
      f_valid                  <= fill_next & f_valid(1 to FILL_STAGES - 1);
      f_last(1)                <= '1' when fill_k = ENTRIES - 1 else '0';
      f_last(2 to FILL_STAGES) <= f_last(1 to FILL_STAGES - 1);
      f_index                  <= to_unsigned(fill_k, 5) & f_index(1 to FILL_STAGES - 1);
      f_neg_k                  <= fill_neg;
      prod_a                   <= resize(fill_mag * fa.significand, 28);
      prod_b                   <= resize(fill_mag * fb.significand, 28);
      -- 2: rounded to 24 significant bits.
      r_neg_a <= fa.negative xor f_neg_k;
      r_neg_b <= fb.negative xor f_neg_k;
      round_a <= rounded_product(prod_a);
      round_b <= rounded_product(prod_b);
      -- 3: onto the grid.
      g_neg_a <= r_neg_a;
      g_neg_b <= r_neg_b;
      on_grid(round_a, fa, mag_a, sticky_a);
      on_grid(round_b, fb, mag_b, sticky_b);
      -- 4: the three entries; the tables take them on the next clock.
      wr_addr <= fill_bank & f_index(3);
      wr_pa   <= entry(g_neg_a, mag_a, sticky_a);
      wr_pb   <= entry(g_neg_b, mag_b, sticky_b);
      wr_nb   <= entry(not g_neg_b, mag_b, sticky_b);

      if fill_next = '1' then
        if fill_k = ENTRIES - 1 then
          fill_next <= '0';
        else
          fill_k <= fill_k + 1;
          if fill_neg = '1' and fill_mag = 1 then
            fill_neg <= '0';
            fill_mag <= (others => '0');
          elsif fill_neg = '1' then
            fill_mag <= fill_mag - 1;
          else
            fill_mag <= fill_mag + 1;
          end if;
        end if;
      end if;
      if f_valid(FILL_STAGES) = '1' and f_last(FILL_STAGES) = '1' then
        filling   <= '0';
        fill_bank <= not fill_bank;
      end if;
      if in_valid = '1' and in_ready = '1' then
        filling   <= '1';
        fill_next <= '1';
        fill_k    <= 0;
        fill_mag  <= magnitude(ORB_COORD_MIN);
        fill_neg  <= '1' when ORB_COORD_MIN < 0 else '0';
        fa        <= factor(in_cos);
        fb        <= factor(in_sin);
      end if;

      if rst = '1' then
        filling   <= '0';
        fill_next <= '0';
        fill_bank <= '0';
        f_valid   <= (others => '0');
      end if;
    end if;

  end process fill;

  -- pragma translate_off
  domain : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' and in_ready = '1' then
        assert in_domain(in_cos) and in_domain(in_sin)
          report "fastnms_orb_rotate: cos and sin must be 0 or 2**-27 .. 1 in magnitude"
          severity error;
      end if;
    end if;

  end process domain;

  -- The FIFO's promise: a step issued finds room.
  room : process (clk) is
  begin

    if rising_edge(clk) then
      if rst = '0' and valid_pipe(READ_LATENCY) = '1' then
        assert points_room = '1'
          report "fastnms_orb_rotate: a step found the point FIFO full"
          severity failure;
      end if;
    end if;

  end process room;

  -- pragma translate_on

  issue <= read_full and not almost_full;

  read_control : process (clk) is

    variable first : std_logic;
    variable last  : std_logic;

  begin

    if rising_edge(clk) then
      first      := '1' when step = 0 else '0';
      last       := '1' when step = STEPS - 1 else '0';
      valid_pipe <= issue & valid_pipe(1 to READ_LATENCY - 1);
      first_pipe <= first & first_pipe(1 to READ_LATENCY - 1);
      last_pipe  <= last & last_pipe(1 to READ_LATENCY - 1);
      if issue = '1' then
        if step = STEPS - 1 then
          step      <= 0;
          read_bank <= not read_bank;
          if read_bank = '1' then
            full_1 <= '0';
          else
            full_0 <= '0';
          end if;
        else
          step <= step + 1;
        end if;
      end if;
      -- A bank fills only while it is not full: no conflict with the clear above.
      if f_valid(FILL_STAGES) = '1' and f_last(FILL_STAGES) = '1' then
        if fill_bank = '1' then
          full_1 <= '1';
        else
          full_0 <= '1';
        end if;
      end if;

      if rst = '1' then
        valid_pipe <= (others => '0');
        full_0     <= '0';
        full_1     <= '0';
        read_bank  <= '0';
        step       <= 0;
      end if;
    end if;

  end process read_control;

  points(1 downto 0) <= first_pipe(READ_LATENCY) & last_pipe(READ_LATENCY);

  out_points : entity work.fastnms_fifo
    generic map (
      DEPTH             => OUT_WORDS,
      WIDTH             => POINT_BITS,
      STYLE             => "distributed",
      ALMOST_FULL_LEVEL => ROOM_LEVEL
    )
    port map (
      clk         => clk,
      rst         => rst,
      in_valid    => valid_pipe(READ_LATENCY),
      in_ready    => points_room,
      almost_full => almost_full,
      in_data     => points,
      out_valid   => out_valid,
      out_ready   => out_ready,
      out_data    => points_out,
      busy        => open
    );

  out_first <= points_out(1);
  out_last  <= points_out(0);

  lane : for l in 0 to LANES - 1 generate
    constant X_ROM : index_rom_t := coordinate_rom(l, 0);
    constant Y_ROM : index_rom_t := coordinate_rom(l, 1);

    type addrs_t is array (0 to 3) of unsigned(5 downto 0);

    type entries_t is array (0 to 3) of entry_t;

    -- Read ports: x = PA[px] + NB[py] (ports 0, 1); y = PB[px] + PA[py] (2, 3).
    signal addr : addrs_t;
    signal data : entries_t;
    signal got  : entries_t;
    signal dx   : signed(5 downto 0);
    signal dy   : signed(5 downto 0);
  begin

    addresses : process (clk) is
    begin

      if rising_edge(clk) then
        addr <= (read_bank & X_ROM(step), read_bank & Y_ROM(step), read_bank & X_ROM(step), read_bank & Y_ROM(step));
      end if;

    end process addresses;

    data <= (wr_pa, wr_nb, wr_pb, wr_pa);

    table : for t in 0 to 3 generate

      port_t : entity work.fastnms_ram_sdp
        generic map (
          DEPTH => 64, WIDTH => 33, READ_LATENCY => 1, STYLE => "distributed"
        )
        port map (
          clk     => clk,
          wr_en   => f_valid(FILL_STAGES),
          wr_addr => wr_addr,
          wr_data => data(t),
          rd_en   => '1',
          rd_addr => addr(t),
          rd_data => got(t)
        );

    end generate table;

    round_x : entity work.fastnms_orb_round_point
      port map (
        clk       => clk,
        en        => '1',
        in_a      => got(0),
        in_b      => got(1),
        out_point => dx
      );

    round_y : entity work.fastnms_orb_round_point
      port map (
        clk       => clk,
        en        => '1',
        in_a      => got(2),
        in_b      => got(3),
        out_point => dy
      );

    points(12 * l + 7 downto 12 * l + 2)  <= std_logic_vector(dx);
    points(12 * l + 13 downto 12 * l + 8) <= std_logic_vector(dy);
    out_dx(6 * l + 5 downto 6 * l)        <= points_out(12 * l + 7 downto 12 * l + 2);
    out_dy(6 * l + 5 downto 6 * l)        <= points_out(12 * l + 13 downto 12 * l + 8);
  end generate lane;

end architecture rtl;
