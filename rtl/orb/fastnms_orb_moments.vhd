-- ORB's intensity-centroid moments m01, m10 of a keypoint's radius-15
-- circular patch (golden/orb.py's moments), one column of 31 pixels per
-- clock.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_orb_moments is
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_column : in    std_logic_vector(31 * 8 - 1 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_m01   : out   signed(20 downto 0);
    out_m10   : out   signed(20 downto 0)
  );
end entity fastnms_orb_moments;

architecture rtl of fastnms_orb_moments is

  constant HALF : natural := 15;

  -- OpenCV's umax for the radius-15 patch (golden/orb.py, UMAX): the half-width of
  -- row |v|, and so the half-height of column |u|.
  type umax_t is array (0 to HALF) of natural range 0 to HALF;

  constant UMAX : umax_t := (15, 15, 15, 15, 14, 14, 14, 13, 13, 12, 11, 10, 9, 8, 6, 3);

  -- The half-height of each column u: UMAX(|u|).
  type heights_t is array (-HALF to HALF) of natural range 0 to HALF;

  function column_heights return heights_t is
    variable h : heights_t;
  begin

    for u in h'range loop

      h(u) := UMAX(abs(u));

    end loop;

    return h;

  end function column_heights;

  constant HEIGHT : heights_t := column_heights;

  type pixels_t is array (-HALF to HALF) of unsigned(7 downto 0);

  type pairs_t is array (1 to HALF + 1) of unsigned(8 downto 0); -- pair 16 is 0

  type diffs_t is array (1 to HALF) of signed(8 downto 0);

  type u_pipe_t is array (2 to 8) of signed(4 downto 0);

  type sums_t is array (natural range <>) of unsigned(12 downto 0);

  type bit_sums_t is array (0 to 3, 0 to 3) of signed(11 downto 0); -- (bit, part)

  type bit_halves_t is array (0 to 3, 0 to 1) of signed(11 downto 0);

  type bit_totals_t is array (0 to 3) of signed(11 downto 0);

  -- The i-th (0 .. 7) v in 1 .. 15 with bit b set.
  function v_with_bit (b : natural; i : natural) return natural is
    variable n : natural;
  begin

    n := 0;

    for v in 1 to HALF loop

      if (v / 2 ** b) mod 2 = 1 then
        if n = i then
          return v;
        end if;
        n := n + 1;
      end if;

    end loop;

    return 1;

  end function v_with_bit;

  type masks_t is array (0 to 2 * HALF) of std_logic_vector(0 to 2 * HALF); -- (u + 15)(v + 15)

  -- The rows of each column inside the circle.
  function circle_masks return masks_t is
    variable m : masks_t;
  begin

    for u in -HALF to HALF loop

      for v in -HALF to HALF loop

        m(u + HALF)(v + HALF) := '0';

        if v <= HEIGHT(u) and -v <= HEIGHT(u) then
          m(u + HALF)(v + HALF) := '1';
        end if;

      end loop;

    end loop;

    return m;

  end function circle_masks;

  constant MASKS : masks_t := circle_masks;

  signal column : integer range -HALF to HALF;
  -- The next column's rows in the circle, from the count, a clock ahead.
  signal in_circle : std_logic_vector(0 to 2 * HALF);

  -- Valid, first and last column of a keypoint, and u, along the stages.
  signal valid : std_logic_vector(1 to 9);
  signal first : std_logic_vector(1 to 9);
  signal last  : std_logic_vector(1 to 9);
  signal u     : u_pipe_t;
  signal u1    : signed(4 downto 0);
  -- 1: masked pixels; 2: pair sums and differences.
  signal pix  : pixels_t;
  signal pair : pairs_t;
  signal diff : diffs_t;
  -- 3 .. 5: the pair sums by twos, fours, eights; the differences of each bit
  -- group by twos, fours, eights (Db).
  signal sum2  : sums_t(0 to 7);
  signal sum4  : sums_t(0 to 3);
  signal sum8  : sums_t(0 to 1);
  signal bits2 : bit_sums_t;
  signal bits4 : bit_halves_t;
  signal bits8 : bit_totals_t;
  -- 6, 7: S and T.
  signal sum16   : unsigned(12 downto 0);
  signal t_low   : signed(15 downto 0);
  signal t_high  : signed(15 downto 0);
  signal col_sum : unsigned(12 downto 0);
  signal col_mom : signed(15 downto 0);
  -- 8: u S; 9: the sums over the keypoint.
  signal weighted : signed(17 downto 0);
  signal mom8     : signed(15 downto 0);
  -- The sums in two parts (bits 11 .. 0 and 20 .. 12), the low part's carry
  -- added to the high part a clock later, so that no carry chain passes 12 bits.
  signal lo01    : unsigned(11 downto 0);
  signal hi01    : signed(8 downto 0);
  signal carry01 : std_logic;
  signal lo10    : unsigned(11 downto 0);
  signal hi10    : signed(8 downto 0);
  signal carry10 : std_logic;
  signal held    : std_logic;

begin

  in_ready  <= not held;
  out_valid <= held;

  stages : process (clk) is

    -- A column's term x into a split sum: restart it, or add with the carry.

    procedure accumulate (
      restart      : std_logic;
      x            : signed(20 downto 0);
      signal lo    : inout unsigned(11 downto 0);
      signal hi    : inout signed(8 downto 0);
      signal carry : inout std_logic
    ) is
      variable low     : unsigned(12 downto 0);
      variable base_lo : unsigned(11 downto 0);
      variable base_hi : signed(8 downto 0);
      variable cin     : std_logic;
    begin

      -- A restart adds to zero (the AND sits in the LUT before the carry chain).
      base_lo := lo;
      base_hi := hi;
      cin     := carry;

      if restart = '1' then
        base_lo := (others => '0');
        base_hi := (others => '0');
        cin     := '0';
      end if;

      low   := resize(base_lo, 13) + unsigned(x(11 downto 0));
      lo    <= low(11 downto 0);
      carry <= low(12);
      hi    <= base_hi + x(20 downto 12) + signed'('0' & cin);

    end procedure accumulate;

    variable take     : std_logic;
    variable p        : unsigned(7 downto 0);
    variable is_first : std_logic;
    variable is_last  : std_logic;

  begin

    if rising_edge(clk) then
      take     := in_valid and not held;
      valid    <= take & valid(1 to 8);
      is_first := '1' when column = -HALF else '0';
      is_last  := '1' when column = HALF else '0';
      first    <= is_first & first(1 to 8);
      last     <= is_last & last(1 to 8);
      u1       <= to_signed(column, 5);
      u        <= u1 & u(2 to 7);

      if take = '1' then
        if column = HALF then
          column    <= -HALF;
          in_circle <= MASKS(0);
        else
          column    <= column + 1;
          in_circle <= MASKS(column + 1 + HALF);
        end if;
      end if;

      -- 1: column u of the circle holds the rows |v| <= UMAX(|u|).
      for v in -HALF to HALF loop

        p := unsigned(in_column((v + HALF) * 8 + 7 downto (v + HALF) * 8));
        if in_circle(v + HALF) = '1' then
          pix(v) <= p;
        else
          pix(v) <= (others => '0');
        end if;

      end loop;

      -- 2

      for v in 1 to HALF loop

        pair(v) <= resize(pix(v), 9) + resize(pix(-v), 9);
        diff(v) <= signed(resize(pix(v), 9)) - signed(resize(pix(-v), 9));

      end loop;

      pair(HALF + 1) <= resize(pix(0), 9); -- the centre, summed with pair 15

      -- 3 .. 5

      for j in 0 to 7 loop

        sum2(j) <= resize(pair(2 * j + 1), 13) + resize(pair(2 * j + 2), 13);

      end loop;

      for j in 0 to 3 loop

        sum4(j) <= sum2(2 * j) + sum2(2 * j + 1);

      end loop;

      for j in 0 to 1 loop

        sum8(j) <= sum4(2 * j) + sum4(2 * j + 1);

      end loop;

      for b in 0 to 3 loop

        for j in 0 to 3 loop

          bits2(b, j) <= resize(diff(v_with_bit(b, 2 * j)), 12) +
                         resize(diff(v_with_bit(b, 2 * j + 1)), 12);

        end loop;

        for j in 0 to 1 loop

          bits4(b, j) <= bits2(b, 2 * j) + bits2(b, 2 * j + 1);

        end loop;

        bits8(b) <= bits4(b, 0) + bits4(b, 1);

      end loop;

      -- 6, 7
      t_low   <= resize(bits8(0), 16) + shift_left(resize(bits8(1), 16), 1);
      t_high  <= shift_left(resize(bits8(2), 16), 2) + shift_left(resize(bits8(3), 16), 3);
      sum16   <= sum8(0) + sum8(1);
      col_sum <= sum16;
      col_mom <= t_low + t_high;

      -- 8
      weighted <= resize(u(7) * signed('0' & col_sum), 18);
      mom8     <= col_mom;

      -- 9: the first column of a keypoint restarts the sums.
      if valid(8) = '1' then
        accumulate(first(8), resize(mom8, 21), lo01, hi01, carry01);
        accumulate(first(8), resize(weighted, 21), lo10, hi10, carry10);
      end if;

      -- 10: the last carry added in.
      if valid(9) = '1' and last(9) = '1' then
        held    <= '1';
        out_m01 <= (hi01 + signed'('0' & carry01)) & signed(lo01);
        out_m10 <= (hi10 + signed'('0' & carry10)) & signed(lo10);
      elsif out_ready = '1' then
        held <= '0';
      end if;

      if rst = '1' then
        column    <= -HALF;
        in_circle <= MASKS(0);
        held      <= '0';
        valid     <= (others => '0');
      end if;
    end if;

  end process stages;

end architecture rtl;
