-- IEEE-754 binary32 multiply, round to nearest even (golden/float32.py,
-- mul), one product per clock; +-0 and normal operands and results only.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_f32_pkg.all;

entity fastnms_f32_mul is
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_a      : in    std_logic_vector(31 downto 0);
    in_b      : in    std_logic_vector(31 downto 0);
    out_valid : out   std_logic;
    out_p     : out   std_logic_vector(31 downto 0)
  );
end entity fastnms_f32_mul;

architecture rtl of fastnms_f32_mul is

  -- Stage 1: operands unpacked.
  signal s1_valid : std_logic;
  signal s1_sign  : std_logic;
  signal s1_zero  : std_logic;
  signal s1_exp   : signed(9 downto 0); -- ea + eb
  signal s1_ma    : unsigned(23 downto 0);
  signal s1_mb    : unsigned(23 downto 0);

  -- Stage 2: the exact 48-bit product of the significands.
  signal s2_valid : std_logic;
  signal s2_sign  : std_logic;
  signal s2_zero  : std_logic;
  signal s2_exp   : signed(9 downto 0);
  signal s2_prod  : unsigned(47 downto 0);

  -- Stage 3: normalised (leading one at 47 or 46), rounding decided.
  signal s3_valid : std_logic;
  signal s3_sign  : std_logic;
  signal s3_zero  : std_logic;
  signal s3_field : signed(9 downto 0);    -- the exponent field before the hidden one adds in
  signal s3_kept  : unsigned(23 downto 0); -- the significand, hidden one included
  signal s3_up    : std_logic;

  -- Stage 4: packed.
  signal s4_valid : std_logic;
  signal s4_p     : std_logic_vector(31 downto 0);

begin

  stages : process (clk) is

    variable high   : boolean;
    variable guard  : std_logic;
    variable sticky : std_logic;
    variable kept   : unsigned(23 downto 0);

  begin

    if rising_edge(clk) then
      s1_valid <= in_valid;
      s1_sign  <= in_a(31) xor in_b(31);
      s1_zero  <= not (or in_a(30 downto 23)) or not (or in_b(30 downto 23));
      s1_exp   <= signed(resize(unsigned(in_a(30 downto 23)), 10) + unsigned(in_b(30 downto 23)));
      s1_ma    <= unsigned('1' & in_a(22 downto 0));
      s1_mb    <= unsigned('1' & in_b(22 downto 0));

      s2_valid <= s1_valid;
      s2_sign  <= s1_sign;
      s2_zero  <= s1_zero;
      s2_exp   <= s1_exp;
      s2_prod  <= s1_ma * s1_mb;

      -- value = prod * 2**(ea + eb - 300); its leading one at bit 47 or 46 gives the
      -- biased exponent E = ea + eb - 126 or - 127, and the word is (E - 1) << 23 + kept.
      high := s2_prod(47) = '1';
      if high then
        kept     := s2_prod(47 downto 24);
        guard    := s2_prod(23);
        sticky   := or s2_prod(22 downto 0);
        s3_field <= s2_exp - 127;
      else
        kept     := s2_prod(46 downto 23);
        guard    := s2_prod(22);
        sticky   := or s2_prod(21 downto 0);
        s3_field <= s2_exp - 128;
      end if;
      s3_valid <= s2_valid;
      s3_sign  <= s2_sign;
      s3_zero  <= s2_zero;
      s3_kept  <= kept;
      s3_up    <= guard and (sticky or kept(0));

      s4_valid <= s3_valid;
      s4_p     <= packed(s3_sign, s3_zero, unsigned(s3_field(7 downto 0)), s3_kept, s3_up);

      if rst = '1' then
        s1_valid <= '0';
        s2_valid <= '0';
        s3_valid <= '0';
        s4_valid <= '0';
      end if;
    end if;

  end process stages;

  -- pragma translate_off
  domain : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' then
        assert in_domain(in_a) and in_domain(in_b)
          report "fastnms_f32_mul: subnormal, infinite or NaN operand (not an ORB value)"
          severity error;
      end if;
      if s3_valid = '1' and s3_zero = '0' then
        assert s3_field >= 0 and s3_field <= 253
          report "fastnms_f32_mul: product outside the normal range (not an ORB value)"
          severity error;
      end if;
    end if;

  end process domain;

  -- pragma translate_on

  out_valid <= s4_valid;
  out_p     <= s4_p;

end architecture rtl;
