-- The taps of one resize axis, one per clock: for destination index i =
-- 0, 1, ... dst-1 (then 0 again), the source pixel `need` at which the
-- destination pixel can be made and the weight `c0` (0..255, of 256) of the
-- pixel before it (need itself weighs 256 - c0), exactly as OpenCV's
-- INTER_LINEAR_EXACT: t = RN(scale * (i + 0.5)) in IEEE double, done as
-- P = m * (2i + 1) accumulated in 11-bit chunks (a skewed accumulator) and
-- rounded to 53 significant bits at its leading one, then f = t - 0.5,
-- o = floor(f), c1 = RN(frac(f) * 256). A first-word-fall-through FIFO
-- hands them out, each need as its distance from the one before
-- (fastnms_resize_walk turns them into a flag per pixel).
-- Datasheet: docs/fastnms_resize.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_resize_taps is
  generic (
    SIZE_BITS : positive := 12
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- A pulse: takes m, src and dst (1 <= dst <= src, held until the next
    -- restart) and starts again from index 0; drops the taps not taken.
    restart : in    std_logic;
    m       : in    unsigned(52 + SIZE_BITS - 1 downto 0);
    src     : in    unsigned(SIZE_BITS - 1 downto 0);
    dst     : in    unsigned(SIZE_BITS - 1 downto 0);
    -- The taps, first word fall through.
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    -- need minus the need of the tap before, minus 2 (index 0: need - 1),
    -- mod 2**SIZE_BITS: all ones for consecutive pixels.
    out_delta : out   unsigned(SIZE_BITS - 1 downto 0);
    out_c0    : out   unsigned(7 downto 0);
    -- The tap of index dst - 1.
    out_last : out   std_logic
  );
end entity fastnms_resize_taps;

architecture rtl of fastnms_resize_taps is

  constant CHUNK  : positive := 11;
  constant CHUNKS : positive := 6;
  -- P < 2**65 (t <= src < 2**12).
  constant PW : positive := CHUNK * CHUNKS;
  -- The FIFO: 32 words; room promised for 12 clocks after its flag (the
  -- rounding pipeline's depth and the advance register).
  constant FIFO_DEPTH : positive := 32;
  constant ROOM       : positive := 12;

  type chunks_t is array (0 to CHUNKS - 1) of unsigned(CHUNK - 1 downto 0);
  -- skew(c)(d): chunk c delayed d + 1 advances more.
  type skew_t is array (0 to CHUNKS - 1, 0 to CHUNKS - 2) of unsigned(CHUNK - 1 downto 0);

  signal m_r     : unsigned(PW - 1 downto 0);
  signal step    : unsigned(PW - 1 downto 0);
  signal src_m1  : unsigned(SIZE_BITS - 1 downto 0);
  signal src_one : std_logic;
  signal dst_m2  : unsigned(SIZE_BITS - 1 downto 0);
  signal dst_one : std_logic;

  -- Issue side.
  signal running     : std_logic;
  signal advance     : std_logic;
  signal index       : unsigned(SIZE_BITS - 1 downto 0);
  signal index_last  : std_logic;
  signal almost_full : std_logic;

  -- The skewed accumulator: after an advance acc(c) holds chunk c of the P
  -- issued c advances before.
  signal acc      : chunks_t;
  signal carry    : std_logic_vector(CHUNKS - 1 downto 0);
  signal load     : std_logic_vector(CHUNKS - 1 downto 0);
  signal skew     : skew_t;
  signal live     : std_logic_vector(CHUNKS - 1 downto 0);
  signal last_dly : std_logic_vector(CHUNKS - 1 downto 0);
  signal adv_r    : std_logic;

  -- Rounding pipeline (valid bits, never stalls: the FIFO has room).
  signal p1         : unsigned(PW - 1 downto 0);
  signal below1     : std_logic_vector(12 downto 0);
  signal v1         : std_logic;
  signal l1         : std_logic;
  signal high2      : unsigned(20 downto 0);
  signal round2     : std_logic;
  signal lsb2       : std_logic;
  signal sticky2    : std_logic;
  signal ones2      : std_logic;
  signal any2       : std_logic;
  signal v2         : std_logic;
  signal l2         : std_logic;
  signal high3      : unsigned(20 downto 0);
  signal c44_3      : std_logic;
  signal sticky3    : std_logic;
  signal v3         : std_logic;
  signal l3         : std_logic;
  signal high4      : unsigned(20 downto 0);
  signal carry4     : std_logic;
  signal sticky4    : std_logic;
  signal v4         : std_logic;
  signal l4         : std_logic;
  signal h5         : unsigned(20 downto 0);
  signal sticky5    : std_logic;
  signal v5         : std_logic;
  signal l5         : std_logic;
  signal o6         : unsigned(SIZE_BITS - 1 downto 0);
  signal c1_6       : unsigned(8 downto 0);
  signal v6         : std_logic;
  signal l6         : std_logic;
  signal o7         : unsigned(SIZE_BITS - 1 downto 0);
  signal o7_p1      : unsigned(SIZE_BITS - 1 downto 0);
  signal c0_7       : unsigned(7 downto 0);
  signal clamp7     : std_logic;
  signal c1_zero7   : std_logic;
  signal v7         : std_logic;
  signal l7         : std_logic;
  signal need8      : unsigned(SIZE_BITS - 1 downto 0);
  signal c0_8       : unsigned(7 downto 0);
  signal v8         : std_logic;
  signal l8         : std_logic;
  signal prev_p2    : unsigned(SIZE_BITS - 1 downto 0);
  signal wr_valid   : std_logic;
  signal wr_data    : std_logic_vector(SIZE_BITS + 8 downto 0);
  signal fifo_rst   : std_logic;
  signal rd_data    : std_logic_vector(SIZE_BITS + 8 downto 0);
  signal fifo_ready : std_logic;

begin

  assert SIZE_BITS <= 12
    report "fastnms_resize_taps: SIZE_BITS must be at most 12"
    severity failure;

  -- ---- issue: one index per advance ---------------------------------------

  advance <= running and not almost_full;

  issue : process (clk) is

    variable sum     : unsigned(CHUNK downto 0);
    variable base    : unsigned(CHUNK - 1 downto 0);
    variable addend  : unsigned(CHUNK - 1 downto 0);
    variable carry_i : std_logic;

  begin

    if rising_edge(clk) then
      adv_r <= advance;
      if restart = '1' then
        m_r     <= resize(m, PW);
        step    <= shift_left(resize(m, PW), 1);
        src_m1  <= src - 1;
        src_one <= to_sl(src = 1);
        dst_m2  <= dst - 2;
        dst_one <= to_sl(dst = 1);
        -- Index 0 loads P = m: chunk 0 now, chunk c c advances later.
        index_last <= to_sl(dst = 1);
        load       <= (0 => '1', others => '0');
      elsif advance = '1' then

        for c in 0 to CHUNKS - 1 loop

          -- A load is P = m: the operands muxed before the add (a LUT in
          -- front of the carry chain, no mux after it).
          if load(c) = '1' then
            base    := (others => '0');
            addend  := m_r(c * CHUNK + CHUNK - 1 downto c * CHUNK);
            carry_i := '0';
          else
            base   := acc(c);
            addend := step(c * CHUNK + CHUNK - 1 downto c * CHUNK);
            if c = 0 then
              carry_i := '0';
            else
              carry_i := carry(c - 1);
            end if;
          end if;
          sum      := ('0' & base) + addend + unsigned'(0 => carry_i);
          acc(c)   <= sum(CHUNK - 1 downto 0);
          carry(c) <= sum(CHUNK);

          for d in 0 to CHUNKS - 2 loop

            if d = 0 then
              skew(c, d) <= acc(c);
            else
              skew(c, d) <= skew(c, d - 1);
            end if;

          end loop;

        end loop;

        load <= load(CHUNKS - 2 downto 0) & index_last;
        live <= live(CHUNKS - 2 downto 0) & '1';
        -- Which issued index was the last: travels with chunk 0.
        last_dly <= last_dly(CHUNKS - 2 downto 0) & index_last;
        if index_last = '1' then
          index_last <= dst_one;
        else
          index_last <= to_sl(index = dst_m2);
        end if;
      end if;
      -- The index: a counter cleared at a restart and after the last.
      if restart = '1' or (advance = '1' and index_last = '1') then
        index <= (others => '0');
      elsif advance = '1' then
        index <= index + 1;
      end if;
      if rst = '1' then
        running <= '0';
      elsif restart = '1' then
        running <= '1';
      end if;
      if rst = '1' or restart = '1' then
        live <= (others => '0');
      end if;
    end if;

  end process issue;

  -- ---- rounding: RN53 of P at its leading one, then o and c1 --------------

  rounding : process (clk) is

    variable p         : unsigned(PW - 1 downto 0);
    variable below     : std_logic_vector(12 downto 0);
    variable onehot    : std_logic;
    variable r_bit     : std_logic;
    variable l_bit     : std_logic;
    variable s_bit     : std_logic;
    variable all_one   : std_logic;
    variable any_one   : std_logic;
    variable h_lo      : unsigned(11 downto 0);
    variable up        : std_logic;
    variable prev_base : unsigned(SIZE_BITS - 1 downto 0);
    variable prev_inc  : unsigned(1 downto 0);

  begin

    if rising_edge(clk) then
      -- R1: P as issued CHUNKS - 1 advances ago, with below(b) = '1' when
      -- bit b lies under the rounding position (P >= 2**(53 + b)).
      v1 <= adv_r and live(CHUNKS - 1);
      l1 <= last_dly(CHUNKS - 1);

      for c in 0 to CHUNKS - 1 loop

        if c = CHUNKS - 1 then
          p(c * CHUNK + CHUNK - 1 downto c * CHUNK) := acc(c);
        else
          p(c * CHUNK + CHUNK - 1 downto c * CHUNK) := skew(c, CHUNKS - 2 - c);
        end if;

      end loop;

      p1 <= p;

      for b in 0 to 12 loop

        below(b) := or p(PW - 1 downto 53 + b);

      end loop;

      below1 <= below;

      -- R2: the round bit (position k - 1), the last kept bit (k), the
      -- sticky bits under the round bit, and over bits 43..0 with the
      -- rounded-off bits taken as zero: all kept bits ones, any kept one.
      r_bit   := '0';
      l_bit   := '0';
      s_bit   := '0';
      all_one := '1';
      any_one := '0';

      for b in 0 to 12 loop

        if b = 0 then
          onehot := not below1(0);
        else
          onehot := below1(b - 1) and not below1(b);
        end if;
        l_bit := l_bit or (p1(b) and onehot);
        if b > 0 then
          r_bit := r_bit or (p1(b - 1) and onehot);
        end if;
        if b < 12 then
          s_bit := s_bit or (p1(b) and below1(b + 1));
        end if;

      end loop;

      for b in 0 to 43 loop

        if b <= 12 then
          all_one := all_one and (p1(b) or below1(b));
          any_one := any_one or (p1(b) and not below1(b));
        else
          all_one := all_one and p1(b);
          any_one := any_one or p1(b);
        end if;

      end loop;

      high2   <= p1(64 downto 44);
      round2  <= r_bit;
      lsb2    <= l_bit;
      sticky2 <= s_bit;
      ones2   <= all_one;
      any2    <= any_one;
      v2      <= v1;
      l2      <= l1;

      -- R3: round up; its carry into bit 44; any bit left under bit 44.
      up      := round2 and (sticky2 or lsb2);
      c44_3   <= up and ones2;
      sticky3 <= not (up and ones2) and (up or any2);
      high3   <= high2;
      v3      <= v2;
      l3      <= l2;

      -- R4, R5: H = P(64..44) + c44, 11 bits then 10.
      h_lo    := ('0' & high3(10 downto 0)) + unsigned'(0 => c44_3);
      high4   <= high3(20 downto 11) & h_lo(10 downto 0);
      carry4  <= h_lo(11);
      sticky4 <= sticky3;
      v4      <= v3;
      l4      <= l3;

      h5      <= (high4(20 downto 11) + unsigned'(0 => carry4)) & high4(10 downto 0);
      sticky5 <= sticky4;
      v5      <= v4;
      l5      <= l4;

      -- R6: f = t - 0.5 is H - 2**8: o = its bits 20..9, the fraction its
      -- bits 8..1 with the round bit 0; c1 = the fraction rounded to even.
      o6   <= resize(h5(20 downto 9) - unsigned'(0 => not h5(8)), SIZE_BITS);
      c1_6 <= ('0' & not h5(8) & h5(7 downto 1)) +
              unsigned'(0 => h5(0) and (sticky5 or h5(1)));
      v6   <= v5;
      l6   <= l5;

      -- R7: the clamp to the last pixel, the candidates.
      clamp7   <= to_sl(o6 >= src_m1) or src_one;
      c1_zero7 <= to_sl(c1_6 = 0);
      o7       <= o6;
      o7_p1    <= o6 + 1;
      c0_7     <= (not c1_6(7 downto 0)) + 1;
      v7       <= v6;
      l7       <= l6;

      -- R8: (need, c0): the last pixel alone, pixel o alone, or o and o + 1.
      v8 <= v7;
      l8 <= l7;
      if clamp7 = '1' then
        need8 <= src_m1;
        c0_8  <= x"00";
      elsif c1_zero7 = '1' then
        need8 <= o7;
        c0_8  <= x"00";
      else
        need8 <= o7_p1;
        c0_8  <= c0_7;
      end if;

      -- R9: need as its distance from the tap before, minus 2 (index 0:
      -- from -1), mod 2**SIZE_BITS.
      wr_valid <= v8;
      wr_data  <= l8 & std_logic_vector(c0_8) & std_logic_vector(need8 - prev_p2);
      if v8 = '1' then
        -- prev_p2 <= need + 2, or 1 after the last: operands chosen before
        -- the add.
        if l8 = '1' then
          prev_base := (others => '0');
          prev_inc  := to_unsigned(1, 2);
        else
          prev_base := need8;
          prev_inc  := to_unsigned(2, 2);
        end if;
        prev_p2 <= prev_base + prev_inc;
      end if;

      if rst = '1' or restart = '1' then
        v1       <= '0';
        v2       <= '0';
        v3       <= '0';
        v4       <= '0';
        v5       <= '0';
        v6       <= '0';
        v7       <= '0';
        v8       <= '0';
        wr_valid <= '0';
        prev_p2  <= to_unsigned(1, SIZE_BITS);
      end if;
    end if;

  end process rounding;

  fifo_rst <= rst or restart;

  -- The FIFO's almost_full promised room for ROOM clocks after an advance.
  -- pragma translate_off
  no_overflow : process (clk) is
  begin

    if rising_edge(clk) then
      assert rst = '1' or restart = '1' or wr_valid = '0' or fifo_ready = '1'
        report "fastnms_resize_taps: a tap written into a full FIFO"
        severity failure;
    end if;

  end process no_overflow;

  -- pragma translate_on

  queue : entity work.fastnms_fifo
    generic map (
      DEPTH             => FIFO_DEPTH,
      WIDTH             => SIZE_BITS + 9,
      STYLE             => "distributed",
      ALMOST_FULL_LEVEL => FIFO_DEPTH - 2 - ROOM
    )
    port map (
      clk         => clk,
      rst         => fifo_rst,
      in_valid    => wr_valid,
      in_ready    => fifo_ready,
      almost_full => almost_full,
      in_data     => wr_data,
      out_valid   => out_valid,
      out_ready   => out_ready,
      out_data    => rd_data,
      busy        => open
    );

  out_delta <= unsigned(rd_data(SIZE_BITS - 1 downto 0));
  out_c0    <= unsigned(rd_data(SIZE_BITS + 7 downto SIZE_BITS));
  out_last  <= rd_data(SIZE_BITS + 8);

end architecture rtl;
