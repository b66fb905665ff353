-- The exact high half of a 64 x 64-bit product, floor(a * b / 2**64), or
-- s minus it: one product per clock, 4 clocks, on 12 DSP48E1 (the
-- multiplier of fastnms_orb_cos_sin).
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_mulhi64 is
  port (
    clk        : in    std_logic;
    rst        : in    std_logic;
    in_valid   : in    std_logic; -- operands on this clock (the stages' enables)
    in_a       : in    unsigned(63 downto 0);
    in_b       : in    unsigned(63 downto 0);
    in_s       : in    unsigned(63 downto 0);
    in_negate  : in    std_logic; -- s - mulhi(a, b) rather than mulhi(a, b)
    out_result : out   unsigned(63 downto 0)
  );
end entity fastnms_mulhi64;

architecture rtl of fastnms_mulhi64 is

  subtype word_t is unsigned(63 downto 0);

  type nat_array_t is array (natural range <>) of natural;

  subtype wide_t is unsigned(127 downto 0);

  type prod_t is array (0 to 11) of unsigned(40 downto 0);

  type count_t is array (0 to 63) of unsigned(2 downto 0);

  type blocks_t is array (0 to 18) of unsigned(6 downto 0);

  type rows_t is array (0 to 5) of wide_t;

  -- The multiplier's operand pieces (DSP48E1: 24 x 17 unsigned) and the rows
  -- that hold the 12 products side by side (no two overlap in a row).
  constant A_AT   : nat_array_t(0 to 2)  := (0, 24, 48);
  constant B_AT   : nat_array_t(0 to 3)  := (0, 17, 34, 51);
  constant ROW_OF : nat_array_t(0 to 11) := (0, 1, 3, 5, 2, 0, 1, 3, 4, 2, 0, 1);

  -- The final add: 19 blocks of 7 bits (the last of 2), in 7 groups: group g is
  -- blocks GROUP_AT(g) .. GROUP_AT(g + 1) - 1; groups 3 .. 6 hold bits 64 .. 127.
  constant SUBS     : natural             := 19;
  constant GROUP_AT : nat_array_t(0 to 7) := (0, 2, 5, 8, 11, 14, 17, 19);

  -- The number of ones in 6 bits.
  function count_table return count_t is
    variable t : count_t;
    variable n : natural;
  begin

    for i in 0 to 63 loop
      n := 0;
      for b in 0 to 5 loop

        if (i / 2 ** b) mod 2 = 1 then
          n := n + 1;
        end if;

      end loop;
      t(i) := to_unsigned(n, 3);
    end loop;

    return t;

  end function count_table;

  constant COUNT6 : count_t := count_table;

  -- a + b with its carry out (one bit wider than a).
  function add (a : unsigned; b : unsigned) return unsigned is
  begin

    return resize(a, a'length + 1) + resize(b, a'length + 1);

  end function add;

  -- a + b + 1 with its carry out, as a - not b (one carry chain, carry-in 1).
  function add_1 (a : unsigned; b : unsigned) return unsigned is
    variable d : unsigned(a'length downto 0);
  begin

    d := resize(a, a'length + 1) - resize(not b, a'length + 1);
    return (not d(a'length)) & d(a'length - 1 downto 0);

  end function add_1;

  function majority (a : wide_t; b : wide_t; c : wide_t) return wide_t is
  begin

    return (a and b) or (a and c) or (b and c);

  end function majority;

  -- The carry out of 16-bit groups lo .. hi given the carry into lo: c ? g1 : g0.
  function carry (c : std_logic; g0 : std_logic_vector; g1 : std_logic_vector;
    lo : natural; hi : natural) return std_logic is
    variable v : std_logic;
  begin

    v := c;
    for j in lo to hi loop

      if v = '1' then
        v := g1(j);
      else
        v := g0(j);
      end if;

    end loop;

    return v;

  end function carry;

  signal m1_p     : prod_t;
  signal m1_s     : word_t;
  signal m1_neg   : std_logic;
  signal m1_valid : std_logic;
  signal m2_x     : wide_t;
  signal m2_y     : wide_t;
  signal m2_neg   : std_logic;
  signal m2_valid : std_logic;
  signal m3_s0    : word_t;                       -- bits 64 .. 127 of the group sums, carry-in 0
  signal m3_s1    : word_t;                       -- the same, carry-in 1
  signal m3_g0    : std_logic_vector(5 downto 1); -- carry out of group g, carry-in 0
  signal m3_g1    : std_logic_vector(5 downto 1); -- the same, carry-in 1
  signal m3_gc    : std_logic;                    -- carry out of group 0 (its carry-in is known)

begin

  multiplier : process (clk) is

    variable rows   : rows_t;
    variable bits   : std_logic_vector(5 downto 0);
    variable cnt    : unsigned(2 downto 0);
    variable c0     : wide_t;
    variable c1     : wide_t;
    variable c2     : wide_t;
    variable u      : wide_t;
    variable v      : wide_t;
    variable kk     : wide_t;
    variable flip   : wide_t;
    variable lo     : natural;
    variable hi     : natural;
    variable sum    : unsigned(7 downto 0);
    variable blk_s0 : blocks_t;
    variable blk_s1 : blocks_t;
    variable blk_g0 : std_logic_vector(SUBS - 1 downto 0);
    variable blk_g1 : std_logic_vector(SUBS - 1 downto 0);
    variable cin    : std_logic;

  begin

    if rising_edge(clk) then
      m1_valid <= in_valid;
      m2_valid <= m1_valid;

      -- 1. The 12 products, each on a DSP48E1 (the 17-bit piece first: the
      -- simulator's multiply loops over the bits of its left operand).
      if in_valid = '1' then
        for i in 0 to 2 loop
          for j in 0 to 3 loop
            m1_p(4 * i + j) <= resize(resize(in_b(minimum(B_AT(j) + 16, 63) downto B_AT(j)), 17) *
                                      resize(in_a(A_AT(i) + 23 - 8 * (i / 2) downto A_AT(i)), 24), 41);
          end loop;
        end loop;
        m1_s   <= in_s;
        m1_neg <= in_negate;
      end if;

      -- 2. The 6 rows -> 3 (a 6:3 counter per bit) -> 2 (carry-save); then
      -- S * 2**64 + 2**64 - 1 - P = K + not u + not v + 2, K = S * 2**64 + 2**64 - 1:
      -- one more carry-save step, one 2 as the carry row's bit 0, the other the
      -- carry into the final add.
      if m1_valid = '1' then
        rows := (others => (others => '0'));
        for i in 0 to 2 loop
          for j in 0 to 3 loop
            rows(ROW_OF(4 * i + j)) := rows(ROW_OF(4 * i + j)) or
                                       shift_left(resize(m1_p(4 * i + j), 128), A_AT(i) + B_AT(j));
          end loop;
        end loop;
        for i in 0 to 127 loop
          bits  := rows(0)(i) & rows(1)(i) & rows(2)(i) & rows(3)(i) & rows(4)(i) & rows(5)(i);
          cnt   := COUNT6(to_integer(unsigned(bits)));
          c0(i) := cnt(0);
          c1(i) := cnt(1);
          c2(i) := cnt(2);
        end loop;
        c1   := shift_left(c1, 1);
        c2   := shift_left(c2, 2);
        u    := c0 xor c1 xor c2;
        v    := shift_left(majority(c0, c1, c2), 1);
        flip := (others => m1_neg);
        if m1_neg = '1' then
          kk := m1_s & (63 downto 0 => '1');
        else
          kk := (others => '0');
        end if;
        u      := u xor flip;
        v      := v xor flip;
        m2_x   <= kk xor u xor v;
        m2_y   <= shift_left(majority(kk, u, v), 1) or resize(unsigned'(0 => m1_neg), 128);
        m2_neg <= m1_neg;
      end if;

      -- 3. Sums of 7-bit blocks (bits 7b .. 7b + 6), with carry-in 0 and 1, joined
      -- into groups of 3 blocks (group 0: blocks 0 and 1 with the final carry-in):
      -- the group sums of bits 64 .. 127 and the carries out of groups 0 .. 5.
      if m2_valid = '1' then
        for b in 0 to SUBS - 1 loop
          lo        := 7 * b;
          hi        := minimum(lo + 6, 127);
          sum       := add(resize(m2_x(hi downto lo), 7), resize(m2_y(hi downto lo), 7));
          blk_s0(b) := sum(6 downto 0);
          blk_g0(b) := sum(7);
          sum       := add_1(resize(m2_x(hi downto lo), 7), resize(m2_y(hi downto lo), 7));
          blk_s1(b) := sum(6 downto 0);
          blk_g1(b) := sum(7);
        end loop;
        for g in 0 to 6 loop
          for x in 0 to 1 loop
            if g = 0 then
              cin := m2_neg;
            else
              cin := to_sl(x = 1);
            end if;
            for b in GROUP_AT(g) to GROUP_AT(g + 1) - 1 loop
              for i in 7 * b to minimum(7 * b + 6, 127) loop
                if i >= 64 then
                  if x = 0 then
                    m3_s0(i - 64) <= blk_s1(b)(i - 7 * b) when cin = '1' else blk_s0(b)(i - 7 * b);
                  else
                    m3_s1(i - 64) <= blk_s1(b)(i - 7 * b) when cin = '1' else blk_s0(b)(i - 7 * b);
                  end if;
                end if;
              end loop;
              if cin = '1' then
                cin := blk_g1(b);
              else
                cin := blk_g0(b);
              end if;
            end loop;
            if g = 0 then
              m3_gc <= cin;
            elsif g <= 5 and x = 0 then
              m3_g0(g) <= cin;
            elsif g <= 5 then
              m3_g1(g) <= cin;
            end if;
          end loop;
        end loop;
      end if;

      if rst = '1' then
        m1_valid <= '0';
        m2_valid <= '0';
      end if;
    end if;

  end process multiplier;

  -- 4. The carry into each group of the result (3 .. 6): through groups 1 .. 3 (a
  -- function of their carries for each carry-in), then through groups 4 .. g - 1.
  select_sums : process (all) is

    variable p0 : std_logic;
    variable p1 : std_logic;
    variable cl : std_logic;
    variable cg : std_logic;

  begin

    for g in 3 to 6 loop
      p0 := carry('0', m3_g0, m3_g1, 1, minimum(g - 1, 3));
      p1 := carry('1', m3_g0, m3_g1, 1, minimum(g - 1, 3));

      if m3_gc = '1' then
        cl := p1;
      else
        cl := p0;
      end if;

      cg := carry(cl, m3_g0, m3_g1, 4, g - 1);
      for i in 7 * GROUP_AT(g) to minimum(7 * GROUP_AT(g + 1) - 1, 127) loop

        if i >= 64 then
          if cg = '1' then
            out_result(i - 64) <= m3_s1(i - 64);
          else
            out_result(i - 64) <= m3_s0(i - 64);
          end if;
        end if;

      end loop;
    end loop;

  end process select_sums;

end architecture rtl;
