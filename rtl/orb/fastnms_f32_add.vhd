-- IEEE-754 binary32 add, round to nearest even (golden/float32.py, add),
-- one sum per clock, 7 clocks; +-0 and normal operands and results only.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_f32_pkg.all;

entity fastnms_f32_add is
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_a      : in    std_logic_vector(31 downto 0);
    in_b      : in    std_logic_vector(31 downto 0);
    out_valid : out   std_logic;
    out_s     : out   std_logic_vector(31 downto 0)
  );
end entity fastnms_f32_add;

architecture rtl of fastnms_f32_add is

  constant ALIGN_MAX : natural := 26; -- 24 significand bits and 2 guard bits

  -- The biased exponent of a zero operand counts as 1 (IEEE's subnormal scale).
  function exponent (f : std_logic_vector(31 downto 0)) return unsigned is
  begin

    if f(30 downto 23) = x"00" then
      return to_unsigned(1, 8);
    end if;

    return unsigned(f(30 downto 23));

  end function exponent;

  function significand (f : std_logic_vector(31 downto 0)) return unsigned is
  begin

    return unsigned((or f(30 downto 23)) & f(22 downto 0));

  end function significand;

  -- The leading zeros of a 27-bit word (27 for zero).
  function leading_zeros (q : unsigned(26 downto 0)) return natural is
  begin

    for i in 26 downto 0 loop

      if q(i) = '1' then
        return 26 - i;
      end if;

    end loop;

    return 27;

  end function leading_zeros;

  -- Stage 1: the larger magnitude first.
  signal s1_valid : std_logic;
  signal s1_large : std_logic_vector(31 downto 0);
  signal s1_small : std_logic_vector(31 downto 0);
  signal s1_zero  : std_logic; -- the sign of an exact zero sum: (-0) + (-0) only

  -- Stage 2: the operands' exponent difference.
  signal s2_valid : std_logic;
  signal s2_sign  : std_logic;
  signal s2_sub   : std_logic;
  signal s2_zero  : std_logic;
  signal s2_exp   : unsigned(7 downto 0);
  signal s2_big   : unsigned(23 downto 0);
  signal s2_small : unsigned(23 downto 0);
  signal s2_shift : natural range 0 to ALIGN_MAX;

  -- Stage 3: the smaller significand aligned.
  signal s3_valid   : std_logic;
  signal s3_sign    : std_logic;
  signal s3_sub     : std_logic;
  signal s3_zero    : std_logic;
  signal s3_exp     : unsigned(7 downto 0);
  signal s3_big     : unsigned(25 downto 0);
  signal s3_aligned : unsigned(25 downto 0);
  signal s3_sticky  : std_logic;

  -- Stage 4: the sum, q * 2**(exp - 152) (plus a fraction below q when sticky).
  signal s4_valid  : std_logic;
  signal s4_sign   : std_logic;
  signal s4_exp    : unsigned(7 downto 0);
  signal s4_q      : unsigned(26 downto 0);
  signal s4_sticky : std_logic;

  -- Stage 5: its leading zeros.
  signal s5_valid  : std_logic;
  signal s5_sign   : std_logic;
  signal s5_exp    : unsigned(7 downto 0);
  signal s5_q      : unsigned(26 downto 0);
  signal s5_sticky : std_logic;
  signal s5_lz     : natural range 0 to 27;

  -- Stage 6: normalised, the rounding decided.
  signal s6_valid : std_logic;
  signal s6_sign  : std_logic;
  signal s6_zero  : std_logic;
  signal s6_field : signed(9 downto 0); -- the exponent field before the hidden one adds in
  signal s6_kept  : unsigned(23 downto 0);
  signal s6_up    : std_logic;

  -- Stage 7: packed.
  signal s7_valid : std_logic;
  signal s7_s     : std_logic_vector(31 downto 0);

begin

  stages : process (clk) is

    variable swap  : boolean;
    variable large : std_logic_vector(31 downto 0);
    variable small : std_logic_vector(31 downto 0);
    variable d     : unsigned(7 downto 0);
    variable wide  : unsigned(25 downto 0);
    variable lost  : unsigned(25 downto 0);
    variable q     : unsigned(26 downto 0);
    variable norm  : unsigned(26 downto 0);

  begin

    if rising_edge(clk) then
      swap     := unsigned(in_a(30 downto 0)) < unsigned(in_b(30 downto 0));
      s1_valid <= in_valid;
      if swap then
        s1_large <= in_b;
        s1_small <= in_a;
      else
        s1_large <= in_a;
        s1_small <= in_b;
      end if;
      s1_zero <= in_a(31) and in_b(31);

      d        := exponent(s1_large) - exponent(s1_small);
      s2_valid <= s1_valid;
      s2_sign  <= s1_large(31);
      s2_sub   <= s1_large(31) xor s1_small(31);
      s2_zero  <= s1_zero;
      s2_exp   <= exponent(s1_large);
      s2_big   <= significand(s1_large);
      s2_small <= significand(s1_small);
      if d > ALIGN_MAX then
        s2_shift <= ALIGN_MAX;
      else
        s2_shift <= to_integer(d);
      end if;

      wide       := s2_small & "00";
      lost       := wide and not shift_left((25 downto 0 => '1'), s2_shift);
      s3_valid   <= s2_valid;
      s3_sign    <= s2_sign;
      s3_sub     <= s2_sub;
      s3_zero    <= s2_zero;
      s3_exp     <= s2_exp;
      s3_big     <= s2_big & "00";
      s3_aligned <= shift_right(wide, s2_shift);
      s3_sticky  <= or lost;

      -- Bits lost to the sticky bit borrow one from a difference: the rest is a
      -- nonzero fraction below q.
      if s3_sub = '1' then
        q := resize(s3_big, 27) - s3_aligned - unsigned'(0 => s3_sticky);
      else
        q := resize(s3_big, 27) + s3_aligned;
      end if;
      s4_valid  <= s3_valid;
      s4_exp    <= s3_exp;
      s4_q      <= q;
      s4_sticky <= s3_sticky;
      if q = 0 then
        s4_sign <= s3_zero;
      else
        s4_sign <= s3_sign;
      end if;

      s5_valid  <= s4_valid;
      s5_sign   <= s4_sign;
      s5_exp    <= s4_exp;
      s5_q      <= s4_q;
      s5_sticky <= s4_sticky;
      s5_lz     <= leading_zeros(s4_q);

      -- The leading one of q at 26 - lz: value = q * 2**(exp - 152), so the biased
      -- exponent is exp + 1 - lz and the word (exp - lz) << 23 + kept. Lost bits
      -- (sticky) leave q with 25 bits or more, so guard and round stay in q.
      norm     := shift_left(s5_q, minimum(s5_lz, 26));
      s6_valid <= s5_valid;
      s6_sign  <= s5_sign;
      s6_zero  <= '0';
      if s5_lz = 27 then
        s6_zero <= '1';
      end if;
      s6_field <= signed(resize(s5_exp, 10)) - s5_lz;
      s6_kept  <= norm(26 downto 3);
      s6_up    <= norm(2) and (norm(1) or norm(0) or s5_sticky or norm(3));

      s7_valid <= s6_valid;
      s7_s     <= packed(s6_sign, s6_zero, unsigned(s6_field(7 downto 0)), s6_kept, s6_up);

      if rst = '1' then
        s1_valid <= '0';
        s2_valid <= '0';
        s3_valid <= '0';
        s4_valid <= '0';
        s5_valid <= '0';
        s6_valid <= '0';
        s7_valid <= '0';
      end if;
    end if;

  end process stages;

  -- pragma translate_off
  domain : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' then
        assert in_domain(in_a) and in_domain(in_b)
          report "fastnms_f32_add: subnormal, infinite or NaN operand (not an ORB value)"
          severity error;
      end if;
      if s6_valid = '1' and s6_zero = '0' then
        assert s6_field >= 0 and s6_field <= 253
          report "fastnms_f32_add: sum outside the normal range (not an ORB value)"
          severity error;
      end if;
    end if;

  end process domain;

  -- pragma translate_on

  out_valid <= s7_valid;
  out_s     <= s7_s;

end architecture rtl;
