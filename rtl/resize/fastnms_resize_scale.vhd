-- The scale of one resize axis as OpenCV's INTER_LINEAR_EXACT computes it,
-- in integers: inv = RN(dst / src), scale = RN(1 / inv) in IEEE double
-- (round to nearest, ties to even, 53-bit significand), given out as
-- m = scale * 2**52 (an integer, since scale >= 1). Two restoring divisions
-- whose 56-bit subtract is cut into 7-bit chunks, one per clock.
-- Datasheet: docs/fastnms_resize.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_resize_scale is
  generic (
    -- Sizes up to 2**SIZE_BITS - 1 pixels.
    SIZE_BITS : positive := 12
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- A pulse: takes src and dst (1 <= dst <= src) and starts.
    start : in    std_logic;
    src   : in    unsigned(SIZE_BITS - 1 downto 0);
    dst   : in    unsigned(SIZE_BITS - 1 downto 0);
    busy  : out   std_logic;
    -- A pulse with m valid (m holds until the next start).
    done : out   std_logic;
    m    : out   unsigned(52 + SIZE_BITS - 1 downto 0)
  );
end entity fastnms_resize_scale;

architecture rtl of fastnms_resize_scale is

  constant CHUNK  : positive := 7;
  constant CHUNKS : positive := 8;
  -- The remainder: below twice a 53-bit divisor.
  constant RW : positive := CHUNK * CHUNKS;
  -- Significand bits taken: 53 and the round bit.
  constant TAKEN : positive := 54;

  -- The states, one-hot (a state is one flip-flop: no decoding).
  constant IDLE       : natural := 0;
  constant SUBTRACT   : natural := 1;
  constant DECIDE     : natural := 2;
  constant SETTLE     : natural := 3;
  constant STICKY     : natural := 4;
  constant ROUND      : natural := 5;
  constant NEXT_PHASE : natural := 6;
  constant SHIFT      : natural := 7;
  constant FINISH     : natural := 8;

  signal state  : std_logic_vector(8 downto 0);
  signal phase2 : std_logic;
  signal rem_r  : unsigned(RW - 1 downto 0);
  -- 2R and the divisor, rotated by a chunk per clock: the chunk being
  -- subtracted is always bits CHUNK - 1 .. 0.
  signal twice_rot   : unsigned(RW - 1 downto 0);
  signal divisor     : unsigned(RW - 1 downto 0);
  signal diff        : unsigned(RW - 1 downto 0);
  signal borrow      : std_logic;
  signal chunk_left  : natural range 0 to CHUNKS - 1;
  signal chunk_final : std_logic;
  -- The number of this step in its phase (from 1), and of the first one bit.
  signal steps : unsigned(6 downto 0);
  signal first : unsigned(6 downto 0);
  -- Significand bits taken; flags of it for the next decision.
  signal got      : natural range 0 to TAKEN;
  signal got_any  : std_logic;
  signal got_last : std_logic;
  signal rem_nz   : std_logic;
  -- The 53-bit significand in bits 52..0, a rounding carry in bit 53.
  signal sig       : unsigned(RW - 1 downto 0);
  signal round_bit : std_logic;
  signal round_up  : std_logic;
  signal carry     : std_logic;
  -- inv = mi * 2**(-52 - j); j + 1 kept.
  signal j_plus1 : unsigned(6 downto 0);
  signal shift_n : unsigned(6 downto 0);
  -- The shift is done as shifts by 8, 4, 2 and 1 (bits 3 .. 0 of shift_n).
  signal shift_bit : natural range 0 to 3;
  signal m_r       : unsigned(52 + SIZE_BITS - 1 downto 0);

  -- The chunk rotation of a word: its bits CHUNK - 1 .. 0 go to the top.
  function rotate (w : unsigned) return unsigned is
  begin

    return w(CHUNK - 1 downto 0) & w(w'high downto CHUNK);

  end function rotate;

begin

  assert SIZE_BITS <= 12
    report "fastnms_resize_scale: SIZE_BITS must be at most 12 (m has 64 bits at most)"
    severity failure;

  busy <= not state(IDLE);
  m    <= m_r;

  divide : process (clk) is

    variable part : unsigned(CHUNK downto 0);
    variable q    : std_logic;
    variable nxt  : unsigned(RW - 1 downto 0);

  begin

    if rising_edge(clk) then
      done     <= '0';
      q        := not borrow;
      got_any  <= to_sl(got > 0);
      got_last <= to_sl(got = TAKEN - 1);
      rem_nz   <= or rem_r;

      if state(IDLE) = '1' then
        if start = '1' then
          -- Phase 1: dst / src.
          phase2    <= '0';
          rem_r     <= resize(dst, RW);
          twice_rot <= shift_left(resize(dst, RW), 1);
          divisor   <= resize(src, RW);
          steps     <= to_unsigned(1, 7);
          got       <= 0;
          sig       <= (others => '0');
          state     <= (SUBTRACT => '1', others => '0');
        end if;
        chunk_left  <= CHUNKS - 1;
        chunk_final <= '0';
        borrow      <= '0';
      elsif state(SUBTRACT) = '1' then
        -- One chunk of 2R - divisor per clock, from bit 0 up.
        -- a - b - borrow as a + not b + not borrow: one carry chain.
        part := ('0' & twice_rot(CHUNK - 1 downto 0)) +
                ('0' & not divisor(CHUNK - 1 downto 0)) + unsigned'(0 => not borrow);

        diff      <= part(CHUNK - 1 downto 0) & diff(RW - 1 downto CHUNK);
        borrow    <= not part(CHUNK);
        twice_rot <= rotate(twice_rot);
        divisor   <= rotate(divisor);
        if chunk_final = '1' then
          state <= (DECIDE => '1', others => '0');
        else
          chunk_left  <= chunk_left - 1;
          chunk_final <= to_sl(chunk_left = 1);
        end if;
      elsif state(DECIDE) = '1' then
        -- 2R >= divisor: the quotient bit is 1 and R becomes 2R - divisor.
        if q = '1' then
          nxt := diff;
        else
          nxt := shift_left(rem_r, 1);
        end if;
        rem_r       <= nxt;
        twice_rot   <= shift_left(nxt, 1);
        steps       <= steps + 1;
        chunk_left  <= CHUNKS - 1;
        chunk_final <= '0';
        borrow      <= '0';
        if got_any = '1' or q = '1' then
          if got_any = '0' then
            first <= steps;
          end if;
          if got_last = '0' then
            sig <= sig(RW - 2 downto 0) & q;
          else
            round_bit <= q;
          end if;
          got <= got + 1;
        end if;
        if got_last = '1' then
          state <= (SETTLE => '1', others => '0');
        else
          state <= (SUBTRACT => '1', others => '0');
        end if;
      elsif state(SETTLE) = '1' then
        -- rem_nz follows rem_r a clock late.
        state <= (STICKY => '1', others => '0');
      elsif state(STICKY) = '1' then
        -- Round to nearest, ties to even: up on the round bit with any
        -- remainder or an odd significand.
        round_up    <= round_bit and (rem_nz or sig(0));
        carry       <= '0';
        chunk_left  <= CHUNKS - 1;
        chunk_final <= '0';
        state       <= (ROUND => '1', others => '0');
      elsif state(ROUND) = '1' then
        -- sig + round_up, a chunk per clock (rotated).
        part := ('0' & sig(CHUNK - 1 downto 0)) + unsigned'(0 => carry or round_up);

        sig      <= part(CHUNK - 1 downto 0) & sig(RW - 1 downto CHUNK);
        carry    <= part(CHUNK);
        round_up <= '0';
        if chunk_final = '1' then
          state <= (NEXT_PHASE => '1', others => '0');
        else
          chunk_left  <= chunk_left - 1;
          chunk_final <= to_sl(chunk_left = 1);
        end if;
      elsif state(NEXT_PHASE) = '1' then
        chunk_left  <= CHUNKS - 1;
        chunk_final <= '0';
        borrow      <= '0';
        if phase2 = '0' then
          -- inv = sig * 2**(-52 - first), or 2**(1 - first) when the
          -- rounding carried into bit 53 (j = first - 1).
          if sig(53) = '1' then
            divisor <= shift_left(to_unsigned(1, RW), 52);
            j_plus1 <= first;
          else
            divisor <= resize(sig(52 downto 0), RW);
            j_plus1 <= first + 1;
          end if;
          -- Phase 2: 2**(104 + j) / mi, from 2**52 (the first step
          -- doubles 2**51).
          phase2    <= '1';
          rem_r     <= shift_left(to_unsigned(1, RW), 51);
          twice_rot <= shift_left(to_unsigned(1, RW), 52);
          steps     <= to_unsigned(1, 7);
          got       <= 0;
          sig       <= (others => '0');
          state     <= (SUBTRACT => '1', others => '0');
        else
          -- m = sig << (j + 1 - first); a carry into bit 53 is the same
          -- significand with bit 53 alone.
          m_r       <= resize(sig(53 downto 0), m_r'length);
          shift_n   <= j_plus1 - first;
          shift_bit <= 3;
          state     <= (SHIFT => '1', others => '0');
        end if;
      elsif state(SHIFT) = '1' then
        for k in 0 to 3 loop

          if shift_bit = k and shift_n(k) = '1' then
            m_r <= shift_left(m_r, 2 ** k);
          end if;

        end loop;

        if shift_bit = 0 then
          state <= (FINISH => '1', others => '0');
        else
          shift_bit <= shift_bit - 1;
        end if;
      elsif state(FINISH) = '1' then
        done  <= '1';
        state <= (IDLE => '1', others => '0');
      end if;

      if rst = '1' then
        state <= (IDLE => '1', others => '0');
        done  <= '0';
      end if;
    end if;

  end process divide;

end architecture rtl;
