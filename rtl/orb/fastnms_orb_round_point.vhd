-- One coordinate of a rotated pattern point from two entries of
-- fastnms_orb_rotate's tables (golden/rotate_fixed.py, round_point).
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_orb_round_point is
  port (
    clk       : in    std_logic;
    en        : in    std_logic;
    in_a      : in    std_logic_vector(32 downto 0);
    in_b      : in    std_logic_vector(32 downto 0);
    out_point : out   signed(5 downto 0)
  );
end entity fastnms_orb_round_point;

architecture rtl of fastnms_orb_round_point is

  -- Three add stages, the near flags, the result.
  constant LATENCY : positive := 5;

  -- Fraction bits of the grid (golden/rotate_fixed.py, FRACTION_BITS).
  constant FRACTION : natural := 26;
  constant P_MAX    : natural := 6;

  type flags_t is array (1 to P_MAX) of std_logic;

  type p_table_t is array (-32 to 31) of natural range 1 to P_MAX;

  -- p with 2**p grid units = half an ulp of h = m / 2 (m odd, |h| >= 1/2): the bit
  -- length of |m|. Clamped to P_MAX: |h| <= 26.5 in the domain.
  function half_ulp_exponent (m : integer) return natural is
    variable v : natural;
    variable p : natural;
  begin

    v := abs(m);
    p := 0;

    while v > 0 loop

      v := v / 2;
      p := p + 1;

    end loop;

    if p > P_MAX then
      return P_MAX;
    end if;

    return p;

  end function half_ulp_exponent;

  -- p of h = n - 1/2 (below) and h = n + 1/2 (above), for each n.
  function p_table (side : integer) return p_table_t is
    variable t : p_table_t;
  begin

    for n in t'range loop

      t(n) := half_ulp_exponent(2 * n + side);

    end loop;

    return t;

  end function p_table;

  constant P_BELOW : p_table_t := p_table(-1);
  constant P_ABOVE : p_table_t := p_table(1);

  -- Add stages.
  signal s0       : unsigned(12 downto 0);
  signal s1       : unsigned(12 downto 0);
  signal s2       : unsigned(7 downto 0);
  signal sticky_1 : std_logic;
  signal t0       : unsigned(11 downto 0);
  signal t1       : unsigned(12 downto 0);
  signal t2       : unsigned(7 downto 0);
  signal sticky_2 : std_logic;
  signal sum      : unsigned(31 downto 0);
  signal sticky_3 : std_logic;

  -- Near flags.
  signal n_lo     : signed(5 downto 0); -- n - 1
  signal n_mid    : signed(5 downto 0); -- n
  signal n_hi     : signed(5 downto 0); -- n + 1
  signal odd      : std_logic;
  signal p_low    : natural range 1 to P_MAX;
  signal p_high   : natural range 1 to P_MAX;
  signal below    : flags_t;            -- g < 2**p
  signal at       : flags_t;            -- g = 2**p
  signal above    : flags_t;            -- g >= 2**26 - 2**p
  signal sticky_4 : std_logic;

begin

  assert LATENCY = 5
    report "fastnms_orb_round_point: the stages below are five"
    severity failure;

  stages : process (clk) is

    variable n         : integer;
    variable g         : unsigned(FRACTION - 1 downto 0);
    variable zero      : boolean;
    variable ones      : boolean;
    variable tie       : boolean;
    variable near_low  : std_logic;
    variable near_high : std_logic;

  begin

    if rising_edge(clk) then
      if en = '1' then
        -- 1: the three pieces, each without the carry from below.
        s0       <= unsigned('0' & in_a(11 downto 0)) + unsigned('0' & in_b(11 downto 0));
        s1       <= unsigned('0' & in_a(23 downto 12)) + unsigned('0' & in_b(23 downto 12));
        s2       <= unsigned(in_a(31 downto 24)) + unsigned(in_b(31 downto 24));
        sticky_1 <= in_a(32) or in_b(32);
        -- 2: the carry into the middle piece.
        t0       <= s0(11 downto 0);
        t1       <= s1 + s0(12 downto 12);
        t2       <= s2;
        sticky_2 <= sticky_1;
        -- 3: the carry into the top piece.
        sum      <= (t2 + t1(12 downto 12)) & t1(11 downto 0) & t0;
        sticky_3 <= sticky_2;

        -- 4: n and its neighbours, h's binade on either side, the flags of g.
        n      := to_integer(signed(sum(31 downto FRACTION)));
        g      := sum(FRACTION - 1 downto 0);
        n_mid  <= signed(sum(31 downto FRACTION));
        n_lo   <= signed(sum(31 downto FRACTION)) - 1;
        n_hi   <= signed(sum(31 downto FRACTION)) + 1;
        odd    <= sum(FRACTION);
        p_low  <= P_BELOW(n);
        p_high <= P_ABOVE(n);

        for p in 1 to P_MAX loop

          zero     := g(FRACTION - 1 downto p) = 0;
          ones     := g(FRACTION - 1 downto p) = (FRACTION - 1 downto p => '1');
          below(p) <= '1' when zero else '0';
          tie      := g(FRACTION - 1 downto p + 1) = 0 and g(p) = '1' and g(p - 1 downto 0) = 0;
          at(p)    <= '1' when tie else '0';
          above(p) <= '1' when ones else '0';

        end loop;

        sticky_4 <= sticky_3;

        -- 5: an odd n next to a half-integer goes to its even neighbour.
        near_low  := below(p_low) or (at(p_low) and not sticky_4);
        near_high := above(p_high);
        if odd = '1' and near_low = '1' then
          out_point <= n_lo;
        elsif odd = '1' and near_high = '1' then
          out_point <= n_hi;
        else
          out_point <= n_mid;
        end if;
      end if;
    end if;

  end process stages;

end architecture rtl;
