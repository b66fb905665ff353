-- ORB's keypoint orientation from its moments: cv::fastAtan2 in degrees,
-- float32 bits equal to golden/float32.py's fast_atan2; one keypoint at a
-- time, at most 104 clocks.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_f32_pkg.all;

entity fastnms_orb_angle is
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_m01    : in    signed(20 downto 0);
    in_m10    : in    signed(20 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_angle : out   std_logic_vector(31 downto 0)
  );
end entity fastnms_orb_angle;

architecture rtl of fastnms_orb_angle is

  -- atan_f32's constants, each the float literal times (float)(180/CV_PI) in float32.
  constant P1   : f32_t := x"4265226F"; -- 57.283627
  constant P3   : f32_t := x"C19556EE"; -- -18.667446
  constant P5   : f32_t := x"410E9FBF"; -- 8.9140005
  constant P7   : f32_t := x"C0228AD9"; -- -2.5397246
  constant F90  : f32_t := x"42B40000";
  constant F180 : f32_t := x"43340000";
  constant F360 : f32_t := x"43B40000";

  -- The polynomial and the quadrant, one float operation per step.
  constant LAST_STEP : natural := 10;

  type state_t is (st_idle, st_order, st_count, st_shift, st_divide, st_round, st_issue, st_wait, st_done);

  -- The bits needed to hold v (0 for 0).
  function bit_length (v : unsigned(19 downto 0)) return natural is
  begin

    for i in 19 downto 0 loop

      if v(i) = '1' then
        return i + 1;
      end if;

    end loop;

    return 0;

  end function bit_length;

  -- |m| for |m| < 2**20 (GHDL's Verilog netlist has no abs; and its synthesis of
  -- 0 - m, an integer minus a signed, gives m: measured, so vectors only).
  function magnitude (m : signed(20 downto 0)) return unsigned is
    variable v : signed(20 downto 0);
  begin

    v := m;

    if m(20) = '1' then
      v := to_signed(0, 21) - m;
    end if;

    return unsigned(v(19 downto 0));

  end function magnitude;

  signal state    : state_t;
  signal neg_x    : std_logic;             -- m10 < 0
  signal neg_y    : std_logic;             -- m01 < 0
  signal steep    : std_logic;             -- |m01| > |m10|: the angle is 90 - a
  signal ax       : unsigned(19 downto 0);
  signal ay       : unsigned(19 downto 0);
  signal num      : unsigned(19 downto 0); -- min(|m01|, |m10|)
  signal den      : unsigned(19 downto 0); -- max(|m01|, |m10|)
  signal num_bits : natural range 0 to 20;
  signal den_bits : natural range 0 to 20;
  signal divisor  : unsigned(23 downto 0);
  signal rest     : unsigned(24 downto 0); -- the division's partial remainder
  signal quotient : unsigned(25 downto 0);
  signal bit_at   : natural range 0 to 25;

  signal c    : f32_t;
  signal c2   : f32_t;
  signal t    : f32_t;
  signal step : natural range 0 to LAST_STEP;

  signal mul_valid : std_logic;
  signal mul_a     : f32_t;
  signal mul_b     : f32_t;
  signal mul_done  : std_logic;
  signal mul_p     : f32_t;
  signal add_valid : std_logic;
  signal add_a     : f32_t;
  signal add_b     : f32_t;
  signal add_done  : std_logic;
  signal add_s     : f32_t;

  -- Steps 0, 1, 3, 5, 7 multiply; the others add.
  function is_mul (k : natural) return boolean is
  begin

    return k = 0 or k = 1 or k = 3 or k = 5 or k = 7;

  end function is_mul;

begin

  sequencer : process (clk) is

    variable field     : unsigned(7 downto 0);
    variable kept      : unsigned(23 downto 0);
    variable guard     : std_logic;
    variable below     : std_logic;
    variable next_step : natural range 0 to LAST_STEP + 1;

  begin

    if rising_edge(clk) then
      -- An if chain, not a case: GHDL's netlist of a case on an enumeration maps to latches.
      if state = st_idle then
        if in_valid = '1' then
          ax    <= magnitude(in_m10);
          ay    <= magnitude(in_m01);
          neg_x <= in_m10(20);
          neg_y <= in_m01(20);
          state <= st_order;
        end if;
      elsif state = st_order then
        -- (float) of an integer below 2**24 is exact: compare the integers.
        steep <= to_sl(ay > ax);
        if ay > ax then
          num <= ax;
          den <= ay;
        else
          num <= ay;
          den <= ax;
        end if;
        state <= st_count;
      elsif state = st_count then
        num_bits <= bit_length(num);
        den_bits <= bit_length(den);
        state    <= st_shift;
      elsif state = st_shift then
        -- Both significands with their leading one at bit 23.
        rest     <= resize(shift_left(resize(num, 24), 24 - num_bits), 25);
        divisor  <= shift_left(resize(den, 24), 24 - den_bits);
        quotient <= (others => '0');
        bit_at   <= 25;
        if num_bits = 0 then
          c     <= (others => '0');
          step  <= 0;
          state <= st_issue;
        else
          state <= st_divide;
        end if;
      elsif state = st_divide then
        -- One quotient bit of (num << 25) / den per clock, most significant first.
        if rest >= divisor then
          quotient <= quotient(24 downto 0) & '1';
          rest     <= shift_left(rest - divisor, 1);
        else
          quotient <= quotient(24 downto 0) & '0';
          rest     <= shift_left(rest, 1);
        end if;
        if bit_at = 0 then
          state <= st_round;
        else
          bit_at <= bit_at - 1;
        end if;
      elsif state = st_round then
        -- c = quotient * 2**(num_bits - den_bits - 25): 25 or 26 significant bits.
        if quotient(25) = '1' then
          kept  := quotient(25 downto 2);
          guard := quotient(1);
          below := quotient(0) or to_sl(rest /= 0);
          field := to_unsigned(126 + num_bits - den_bits, 8);
        else
          kept  := quotient(24 downto 1);
          guard := quotient(0);
          below := to_sl(rest /= 0);
          field := to_unsigned(125 + num_bits - den_bits, 8);
        end if;
        c     <= packed('0', '0', field, kept, guard and (below or kept(0)));
        step  <= 0;
        state <= st_issue;
      elsif state = st_issue then
        state <= st_wait;
      elsif state = st_wait then
        if mul_done = '1' or add_done = '1' then
          if mul_done = '1' then
            if step = 0 then
              c2 <= mul_p;
            else
              t <= mul_p;
            end if;
          else
            t <= add_s;
          end if;
          -- The quadrant steps apply only to their quadrants.
          next_step := step + 1;
          if next_step = 8 and steep = '0' then
            next_step := 9;
          end if;
          if next_step = 9 and neg_x = '0' then
            next_step := 10;
          end if;
          if next_step = 10 and neg_y = '0' then
            next_step := 11;
          end if;
          if next_step > LAST_STEP then
            state <= st_done;
          else
            step  <= next_step;
            state <= st_issue;
          end if;
        end if;
      elsif out_ready = '1' then -- st_done
        state <= st_idle;
      end if;

      if rst = '1' then
        state <= st_idle;
      end if;
    end if;

  end process sequencer;

  -- The operation of the step: operands from c, c2, t and the constants.
  mul_valid <= to_sl(state = st_issue and is_mul(step));
  add_valid <= to_sl(state = st_issue and not is_mul(step));

  mul_a <= c when step = 0 else
           P7 when step = 1 else
           t;
  mul_b <= c when step = 0 or step = 7 else
           c2;

  add_a <= t when step <= 6 else
           F90 when step = 8 else
           F180 when step = 9 else
           F360;
  add_b <= P5 when step = 2 else
           P3 when step = 4 else
           P1 when step = 6 else
           (not t(31)) & t(30 downto 0);

  multiplier : entity work.fastnms_f32_mul
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => mul_valid,
      in_a      => mul_a,
      in_b      => mul_b,
      out_valid => mul_done,
      out_p     => mul_p
    );

  adder : entity work.fastnms_f32_add
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => add_valid,
      in_a      => add_a,
      in_b      => add_b,
      out_valid => add_done,
      out_s     => add_s
    );

  in_ready  <= to_sl(state = st_idle);
  out_valid <= to_sl(state = st_done);
  out_angle <= t;

end architecture rtl;
