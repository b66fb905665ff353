-- ORB's cos and sin of the keypoint angle in radians, correctly rounded
-- float32 bits equal to golden/trig.py's cos_sin, in integer arithmetic;
-- one angle at a time, 58 clocks.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_orb_cos_sin is
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_x      : in    std_logic_vector(31 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_cos   : out   std_logic_vector(31 downto 0);
    out_sin   : out   std_logic_vector(31 downto 0)
  );
end entity fastnms_orb_cos_sin;

architecture rtl of fastnms_orb_cos_sin is

  subtype word_t is unsigned(63 downto 0);

  type word_array_t is array (natural range <>) of word_t;

  type nat_array_t is array (natural range <>) of natural;

  type l_array_t is array (1 to 4) of unsigned(95 downto 0);

  type a_array_t is array (1 to 4) of unsigned(26 downto 0);

  type flags_t is array (0 to 3) of std_logic_vector(5 downto 0);

  type piece_t is array (1 to 4) of unsigned(9 downto 0);

  constant X_MAX    : unsigned(31 downto 0)         := x"40C90FDB";
  constant ONE_BITS : std_logic_vector(31 downto 0) := x"3F800000";

  -- The constants of golden/trig.py, printed from its _THRESHOLDS, _A, _L_HI,
  -- _L_LO, _SIN_C and _COS_C.
  -- k = the number of thresholds below x: the largest floats below (j + 1/2) * pi/2.
  constant THRESHOLD : nat_array_t(0 to 3) :=
  (
    16#3F490FDA#, 16#4016CBE3#, 16#407B53D1#, 16#40AFEDDF#
  );
  -- A_k + 1, A_k the top 27 bits of round(k * pi/2 * 2**120): d - 1 = X - (A_k + 1).
  constant A_PLUS_1 : a_array_t :=
  (
    27x"1921FB6", 27x"3243F6B", 27x"4B65F20", 27x"6487ED6"
  );
  -- L for r < 0 (B_k, the low 96 bits of round(k * pi/2 * 2**120)) and r > 0 (2**96 - B_k).
  constant L_NEG : l_array_t :=
  (
    x"4442D18469898CC51701B83A", x"8885A308D313198A2E037073",
    x"CCC8748D3C9CA64F450528AD", x"110B4611A62633145C06E0E7"
  );
  constant L_POS : l_array_t :=
  (
    x"BBBD2E7B9676733AE8FE47C6", x"777A5CF72CECE675D1FC8F8D",
    x"33378B72C36359B0BAFAD753", x"EEF4B9EE59D9CCEBA3F91F19"
  );
  -- S_n = round(2**64 / (2n + 1)!) and C_n = round(2**64 / (2n)!), n = 1 .. 9.
  constant SIN_C : word_array_t(1 to 9) :=
  (
    x"2AAAAAAAAAAAAAAB", x"0222222222222222", x"000D00D00D00D00D",
    x"00002E3BC74AAD8E", x"0000006B99159FD5", x"00000000B092309D",
    x"0000000000D73F9F", x"000000000000CA96", x"0000000000000098"
  );
  constant COS_C : word_array_t(1 to 9) :=
  (
    x"8000000000000000", x"0AAAAAAAAAAAAAAB", x"005B05B05B05B05B",
    x"0001A01A01A01A02", x"0000049F93EDDE28", x"00000008F76C77FC",
    x"000000000C9CBA54", x"00000000000D73FA", x"0000000000000B41"
  );

  -- The schedule: tick = n on the clock that ends with the n-th rising edge after
  -- the angle was taken.
  constant T_M     : natural := 7;          -- M, t, k and the sign of r held from here
  constant T_Z     : natural := T_M + 1;    -- the operands of mulhi(M, M)
  constant T_ZS    : natural := T_Z + 5;    -- Z = mulhi(M, M) >> 2t
  constant T_SIN   : natural := T_ZS + 1;   -- the sine's 10 products, one every 4 clocks
  constant T_COS   : natural := T_SIN + 1;  -- the cosine's 9, on the clocks after them
  constant T_MC    : natural := T_COS + 36; -- 2**64 - Yc, the cosine's last result
  constant T_ROUND : natural := T_SIN + 41; -- M - mulhi(M, Y), the sine's last, rounded
  constant T_OUT   : natural := T_ROUND + 2;
  constant DONE    : natural := T_OUT + 1;  -- 58: the result offered

  -- The comparisons with the thresholds in pieces of 6 bits: piece p is bits
  -- PIECE_AT(p) .. PIECE_AT(p + 1) - 1 of x(30:0).
  constant PIECE_AT : nat_array_t(0 to 6) := (0, 1, 7, 13, 19, 25, 31);

  -- A product is issued on clock `tick`.
  function issues (tick : natural) return boolean is
    variable found : boolean := tick = T_Z;
  begin

    for i in 1 to 10 loop

      if tick = T_SIN + 4 * (i - 1) or (i <= 9 and tick = T_COS + 4 * (i - 1)) then
        found := true;
      end if;

    end loop;

    return found;

  end function issues;

  -- The coefficient S of the product issued on clock `tick` (S - mulhi(a, b)).
  function coefficient (tick : natural) return word_t is
    variable s : word_t := (others => '0');
  begin

    for i in 1 to 8 loop

      -- (Bit 63 apart: GHDL 2.0's synthesis turned the whole of
      -- x"8000000000000000", COS_C(1), into 0.)
      if tick = T_SIN + 4 * (i - 1) then
        s(62 downto 0) := SIN_C(9 - i)(62 downto 0);
        s(63)          := SIN_C(9 - i)(63);
      elsif tick = T_COS + 4 * (i - 1) then
        s(62 downto 0) := COS_C(9 - i)(62 downto 0);
        s(63)          := COS_C(9 - i)(63);
      end if;

    end loop;

    return s;

  end function coefficient;

  -- Control: 0 idle, 1 .. DONE - 1 computing, DONE the result offered.
  signal tick : natural range 0 to DONE;

  -- The angle, held while it is in the unit.
  signal x_r : std_logic_vector(31 downto 0) := sim_zeros(32);

  -- Reduction, a pipeline on the held angle (its registers settle by clock T_M).
  signal f1_gt    : flags_t;                      -- x > THRESHOLD(j), piece by piece
  signal f1_eq    : flags_t;                      -- x = THRESHOLD(j), piece by piece
  signal f1_tiny  : std_logic;                    -- x < 2**-12
  signal f2_above : std_logic_vector(3 downto 0); -- x > THRESHOLD(j)
  signal f2_lo    : piece_t;                      -- X(8:0) - (A + 1)(8:0), the borrow at 9
  signal f2_mid0  : piece_t;                      -- X(17:9) - (A + 1)(17:9), the borrow at 9
  signal f2_mid1  : piece_t;                      -- the same minus 1
  signal f2_hi0   : piece_t;                      -- X(26:18) - (A + 1)(26:18)
  signal f2_hi1   : piece_t;                      -- the same minus 1
  signal f2_m0    : unsigned(23 downto 0);        -- the mantissa (k = 0), 2**-12 if tiny
  signal f3_k     : natural range 0 to 4;
  signal f4_neg   : std_logic;                    -- r < 0
  signal f5_cz    : unsigned(1 downto 0);         -- the leading zero bytes of h (0 .. 3)
  signal f5_w1    : unsigned(70 downto 0);        -- w shifted by them: its leading one in the top byte
  signal f6_fz    : natural range 0 to 7;         -- the leading zeros of that byte
  signal m_r      : word_t;                       -- M

  -- X = x * 2**24 (x >= pi/4); 126 - the biased exponent (k = 0); d - 1 = X - (A_k + 1);
  -- |r| * 2**120 = h * 2**96 + L; t; mulhi(M, M) >> 8 * (t / 4).
  signal f1_xx : unsigned(26 downto 0)  := unsigned(sim_zeros(27));
  signal f2_t0 : unsigned(4 downto 0)   := unsigned(sim_zeros(5));
  signal f3_d1 : unsigned(26 downto 0)  := unsigned(sim_zeros(27));
  signal f4_w  : unsigned(119 downto 0) := unsigned(sim_zeros(120));
  signal t_r   : unsigned(4 downto 0)   := unsigned(sim_zeros(5));
  signal z_r   : word_t                 := unsigned(sim_zeros(64));

  -- Multiplier: operands (the clock of issue), products, two rows, group sums.
  signal a_is_m   : std_logic;        -- the next op_a is M (else Z)
  signal b_is_res : std_logic;        -- the next op_b is the result
  signal b_is_m   : std_logic;        -- else M, or else S9 or C9
  signal b_is_s9  : std_logic;
  signal op_a     : word_t    := unsigned(sim_zeros(64));
  signal op_b     : word_t    := unsigned(sim_zeros(64));
  signal op_s     : word_t    := unsigned(sim_zeros(64));
  signal op_neg   : std_logic := '0'; -- S - mulhi(a, b) rather than mulhi(a, b)
  signal op_valid : std_logic;        -- a product issued (the stages' clock enables)
  signal result   : word_t;           -- mulhi, 4 clocks after its operands
  signal res      : word_t;
  signal mc_r     : word_t    := unsigned(sim_zeros(64));

  -- Rounding: 31-bit words (the exponent field + 1 and 23 fraction bits), the
  -- bits that decide the rounding, then the increment in pieces of 12, 11 and 8 bits.
  signal field_hi : unsigned(7 downto 0);         -- 126 - t: the field of sin|r| + 1
  signal field_lo : unsigned(7 downto 0);         -- 125 - t: the same, renormalised
  signal b1_sw    : unsigned(30 downto 0);
  signal b1_slow  : std_logic;                    -- sin|r| renormalised
  signal b1_sbits : unsigned(40 downto 36);
  signal b1_sors  : std_logic_vector(5 downto 0); -- or of bits 6i + 5 .. 6i
  signal b1_cw    : unsigned(30 downto 0);
  signal b1_cbits : unsigned(40 downto 36);
  signal b1_cors  : std_logic_vector(5 downto 0);
  signal b2_sw    : unsigned(30 downto 0);
  signal b2_sinc  : unsigned(30 downto 0);        -- each piece plus 1
  signal b2_sones : std_logic_vector(1 downto 0); -- pieces 0, 1 all ones
  signal b2_sup   : std_logic;
  signal b2_cw    : unsigned(30 downto 0);
  signal b2_cinc  : unsigned(30 downto 0);
  signal b2_cones : std_logic_vector(1 downto 0);
  signal b2_cup   : std_logic;
  signal cos_sign : std_logic;
  signal sin_sign : std_logic;
  signal q_odd    : std_logic;                    -- k odd: cos x and sin x from sin r and cos r
  signal cos_r    : std_logic_vector(31 downto 0);
  signal sin_r    : std_logic_vector(31 downto 0);

begin

  -- ---- control --------------------------------------------------------------------

  control : process (clk) is
  begin

    if rising_edge(clk) then
      if tick = 0 then
        if in_valid = '1' then
          x_r  <= in_x;
          tick <= 1;
        end if;
      elsif tick = DONE then
        if out_ready = '1' then
          tick <= 0;
        end if;
      else
        tick <= tick + 1;
      end if;

      if rst = '1' then
        tick <= 0;
      end if;
    end if;

  end process control;

  in_ready  <= to_sl(tick = 0);
  out_valid <= to_sl(tick = DONE);
  out_cos   <= cos_r;
  out_sin   <= sin_r;

  -- ---- reduction: k, M, t, the sign of r ------------------------------------------

  reduction : process (clk) is

    variable e    : unsigned(7 downto 0);
    variable c    : unsigned(30 downto 0);
    variable gt   : std_logic;
    variable k    : natural range 0 to 4;
    variable b    : std_logic;
    variable mid  : unsigned(9 downto 0);
    variable hi   : unsigned(9 downto 0);
    variable pos  : std_logic;
    variable h    : unsigned(23 downto 0);
    variable lead : natural range 0 to 7;

  begin

    if rising_edge(clk) then
      -- Clocks 1 .. T_M after the angle was taken; the registers hold after.
      if at_least(to_unsigned(tick, 6), 1) = '1' and at_least(to_unsigned(tick, 6), T_M + 1) = '0' then
        -- 1. The comparisons, piece by piece; X; tiny.
        e := unsigned(x_r(30 downto 23));
        for j in 0 to 3 loop
          c := to_unsigned(THRESHOLD(j), 31);
          for p in 0 to 5 loop
            f1_gt(j)(p) <= to_sl(unsigned(x_r(PIECE_AT(p + 1) - 1 downto PIECE_AT(p))) >
                                 c(PIECE_AT(p + 1) - 1 downto PIECE_AT(p)));
            f1_eq(j)(p) <= to_sl(unsigned(x_r(PIECE_AT(p + 1) - 1 downto PIECE_AT(p))) =
                                 c(PIECE_AT(p + 1) - 1 downto PIECE_AT(p)));
          end loop;
        end loop;
        f1_tiny <= not at_least(e, 115);
        -- x >= pi/4 has a biased exponent of 126 .. 129: X = mantissa << (e - 126).
        f1_xx <= shift_left(resize(unsigned('1' & x_r(22 downto 0)), 27),
                            to_integer(unsigned'(not e(1), e(0))));

        -- 2. x > THRESHOLD(j); d - 1 = X - (A_j + 1) for every j in three pieces of 9
        -- bits (the upper two without and with a borrow in); the k = 0 word.
        for j in 0 to 3 loop
          gt := '0';
          for p in 0 to 5 loop
            gt := f1_gt(j)(p) or (f1_eq(j)(p) and gt);
          end loop;
          f2_above(j) <= gt;
        end loop;
        for j in 1 to 4 loop
          f2_lo(j)   <= ('0' & f1_xx(8 downto 0)) - ('0' & A_PLUS_1(j)(8 downto 0));
          f2_mid0(j) <= ('0' & f1_xx(17 downto 9)) - ('0' & A_PLUS_1(j)(17 downto 9));
          f2_mid1(j) <= ('0' & f1_xx(17 downto 9)) - (('0' & A_PLUS_1(j)(17 downto 9)) + 1);
          f2_hi0(j)  <= ('0' & f1_xx(26 downto 18)) - ('0' & A_PLUS_1(j)(26 downto 18));
          f2_hi1(j)  <= ('0' & f1_xx(26 downto 18)) - (('0' & A_PLUS_1(j)(26 downto 18)) + 1);
        end loop;
        if f1_tiny = '1' then
          f2_m0 <= x"800000";
          f2_t0 <= to_unsigned(11, 5);
        else
          f2_m0 <= unsigned('1' & x_r(22 downto 0));
          f2_t0 <= resize(to_unsigned(126, 8) - e, 5);
        end if;

        -- 3. k, and d - 1 for it.
        k := 0;
        for j in 0 to 3 loop
          if f2_above(j) = '1' then
            k := j + 1;
          end if;
        end loop;
        f3_k  <= k;
        f3_d1 <= (others => '0');
        for j in 1 to 4 loop
          if k = j then
            b := f2_lo(j)(9);
            if b = '1' then
              mid := f2_mid1(j);
            else
              mid := f2_mid0(j);
            end if;
            if mid(9) = '1' then
              hi := f2_hi1(j);
            else
              hi := f2_hi0(j);
            end if;
            f3_d1 <= hi(8 downto 0) & mid(8 downto 0) & f2_lo(j)(8 downto 0);
          end if;
        end loop;

        -- 4. r > 0 iff d >= 1: then h = d - 1 and L = 2**96 - B, else h = -d =
        -- not (d - 1) and L = B; |r| * 2**120 = h * 2**96 + L, h < 2**24.
        pos    := not f3_d1(26);
        h      := f3_d1(23 downto 0) xor (23 downto 0 => f3_d1(26));
        f4_neg <= to_sl(f3_k /= 0) and f3_d1(26);
        f4_w   <= h & L_NEG(1);
        for j in 1 to 4 loop
          if f3_k = j then
            if pos = '1' then
              f4_w <= h & L_POS(j);
            else
              f4_w <= h & L_NEG(j);
            end if;
          end if;
        end loop;

        -- 5. The leading zero bytes of h (the leading one is in bits 119 .. 93 of w:
        -- golden/trig.py's c in 8 .. 34 over the domain), and w shifted by them.
        if f4_w(119 downto 112) /= 0 then
          f5_cz <= "00";
          f5_w1 <= f4_w(119 downto 49);
        elsif f4_w(111 downto 104) /= 0 then
          f5_cz <= "01";
          f5_w1 <= f4_w(111 downto 41);
        elsif f4_w(103 downto 96) /= 0 then
          f5_cz <= "10";
          f5_w1 <= f4_w(103 downto 33);
        else
          f5_cz <= "11";
          f5_w1 <= f4_w(95 downto 25);
        end if;

        -- 6. The leading zeros of the top byte.
        lead := 7;
        for i in 0 to 7 loop
          if f5_w1(63 + i) = '1' then
            lead := 7 - i;
          end if;
        end loop;
        f6_fz <= lead;

        -- 7. M and t: the normalised |r|, or for k = 0 the mantissa (r = x).
        if f3_k = 0 then
          m_r <= f2_m0 & (39 downto 0 => '0');
          t_r <= f2_t0;
        else
          m_r <= shift_left(f5_w1, f6_fz)(70 downto 7);
          t_r <= f5_cz & to_unsigned(f6_fz, 3);
        end if;
      end if;
    end if;

  end process reduction;

  -- ---- multiplier: mulhi(op_a, op_b), or op_s - mulhi(op_a, op_b) -----------------

  issue : process (clk) is
  begin

    if rising_edge(clk) then
      -- The operands' sources, decided a clock ahead: by default the next product
      -- of a Horner chain, Z times the last result.
      a_is_m   <= to_sl(tick = T_Z - 1 or tick = T_SIN + 35);
      b_is_res <= to_sl(tick /= T_Z - 1 and tick /= T_SIN - 1 and tick /= T_COS - 1);
      b_is_m   <= to_sl(tick = T_Z - 1);
      b_is_s9  <= to_sl(tick = T_SIN - 1);

      if a_is_m = '1' then
        op_a <= m_r;
      else
        op_a <= shift_right(z_r, 2 * to_integer(t_r(1 downto 0)));
      end if;
      if b_is_res = '1' then
        op_b <= result;
      elsif b_is_m = '1' then
        op_b <= m_r;
      elsif b_is_s9 = '1' then
        op_b <= SIN_C(9);
      else
        op_b <= COS_C(9);
      end if;
      -- Y = mulhi(Z, T) and mulhi(M, M) plain, M - mulhi(M, Y); the cosine's last,
      -- 0 - mulhi(Z, T), is 2**64 - Yc.
      op_neg <= to_sl(tick /= T_Z and tick /= T_SIN + 32);
      if tick = T_SIN + 36 then
        op_s <= m_r;
      else
        op_s <= coefficient(tick);
      end if;
      op_valid <= to_sl(issues(tick));

      -- Z = mulhi(M, M) >> 2t: by 8 * (t / 4) here, by 2 * (t mod 4) into op_a.
      if tick = T_ZS then
        z_r <= shift_right(res, 8 * to_integer(t_r(4 downto 2)));
      end if;
      if tick = T_MC then
        mc_r <= result;
      end if;
      res <= result;

      if rst = '1' then
        op_valid <= '0';
      end if;
    end if;

  end process issue;

  multiplier : entity work.fastnms_mulhi64
    port map (
      clk        => clk,
      rst        => rst,
      in_valid   => op_valid,
      in_a       => op_a,
      in_b       => op_b,
      in_s       => op_s,
      in_negate  => op_neg,
      out_result => result
    );

  -- ---- rounding and the quadrant map ----------------------------------------------

  rounding : process (clk) is

    variable ms   : word_t;
    variable q    : natural range 0 to 3;
    variable up   : std_logic;
    variable c    : std_logic;
    variable cw   : unsigned(30 downto 0);
    variable sw   : unsigned(30 downto 0);
    variable cmag : std_logic_vector(30 downto 0);
    variable smag : std_logic_vector(30 downto 0);

  begin

    if rising_edge(clk) then
      -- The exponent fields and the signs (t, k and the sign of r are held).
      field_hi <= to_unsigned(126, 8) - resize(t_r, 8);
      field_lo <= to_unsigned(125, 8) - resize(t_r, 8);
      q        := f3_k mod 4;
      q_odd    <= to_sl(q mod 2 = 1);
      -- cos x: +cos r, -sin r, -cos r, +sin r; sin x: +sin r, +cos r, -sin r, -cos r
      -- (q = k mod 4 = 0 .. 3); sin r has the sign of r.
      cos_sign <= to_sl(q = 1 or q = 2) xor (to_sl(q mod 2 = 1) and f4_neg);
      sin_sign <= to_sl(q >= 2) xor (to_sl(q mod 2 = 0) and f4_neg);

      -- 1. sin|r| with its leading one at bit 63 (one left shift at most) and cos r
      -- as words (the field + 1 and the 23 fraction bits), with the bits that decide
      -- the rounding: bits 40 .. 36 and the or of each 6 below.
      ms      := res;
      b1_slow <= not ms(63);
      if ms(63) = '0' then
        b1_sw <= field_lo & ms(61 downto 39);
      else
        b1_sw <= field_hi & ms(62 downto 40);
      end if;
      b1_sbits <= ms(40 downto 36);
      b1_cw    <= to_unsigned(126, 8) & mc_r(62 downto 40);
      b1_cbits <= mc_r(40 downto 36);
      for i in 0 to 5 loop
        b1_sors(i) <= or ms(6 * i + 5 downto 6 * i);
        b1_cors(i) <= or mc_r(6 * i + 5 downto 6 * i);
      end loop;

      -- 2. The round-up bit (nearest, ties to even), and each piece plus 1.
      if b1_slow = '1' then
        b2_sup <= b1_sbits(38) and ((or b1_sors) or b1_sbits(36) or b1_sbits(37) or b1_sbits(39));
      else
        b2_sup <= b1_sbits(39) and ((or b1_sors) or b1_sbits(36) or b1_sbits(37) or b1_sbits(38) or
                                    b1_sbits(40));
      end if;
      b2_cup      <= b1_cbits(39) and ((or b1_cors) or b1_cbits(36) or b1_cbits(37) or b1_cbits(38) or
                                       b1_cbits(40));
      b2_sinc     <= (b1_sw(30 downto 23) + 1) & (b1_sw(22 downto 12) + 1) & (b1_sw(11 downto 0) + 1);
      b2_cinc     <= (b1_cw(30 downto 23) + 1) & (b1_cw(22 downto 12) + 1) & (b1_cw(11 downto 0) + 1);
      b2_sones(0) <= and b1_sw(11 downto 0);
      b2_sones(1) <= and b1_sw(22 downto 12);
      b2_cones(0) <= and b1_cw(11 downto 0);
      b2_cones(1) <= and b1_cw(22 downto 12);
      b2_sw       <= b1_sw;
      b2_cw       <= b1_cw;

      -- 3. The rounded words (the carry out of the fraction adds to the field), the
      -- quadrant map.
      if tick = T_OUT then
        sw := b2_sw;
        up := b2_sup;
        if up = '1' then
          sw(11 downto 0) := b2_sinc(11 downto 0);
        end if;
        c := up and b2_sones(0);
        if c = '1' then
          sw(22 downto 12) := b2_sinc(22 downto 12);
        end if;
        if (c and b2_sones(1)) = '1' then
          sw(30 downto 23) := b2_sinc(30 downto 23);
        end if;
        cw := b2_cw;
        up := b2_cup;
        if up = '1' then
          cw(11 downto 0) := b2_cinc(11 downto 0);
        end if;
        c := up and b2_cones(0);
        if c = '1' then
          cw(22 downto 12) := b2_cinc(22 downto 12);
        end if;
        if (c and b2_cones(1)) = '1' then
          cw(30 downto 23) := b2_cinc(30 downto 23);
        end if;
        if q_odd = '1' then
          cmag := std_logic_vector(sw);
          smag := std_logic_vector(cw);
        else
          cmag := std_logic_vector(cw);
          smag := std_logic_vector(sw);
        end if;
        cos_r <= cos_sign & cmag;
        sin_r <= sin_sign & smag;
        if f1_tiny = '1' then
          cos_r <= ONE_BITS;
          sin_r <= x_r;
        end if;
      end if;
    end if;

  end process rounding;

  -- pragma translate_off
  domain : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' and tick = 0 then
        assert unsigned(in_x) <= X_MAX
          report "fastnms_orb_cos_sin: angle outside 0 .. 2*pi (0 .. 0x40C90FDB)"
          severity error;
      end if;
    end if;

  end process domain;

-- pragma translate_on

end architecture rtl;
