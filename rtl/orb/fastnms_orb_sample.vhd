-- ORB's 256 comparisons (golden/orb.py's descriptors): a keypoint's blurred
-- patch and rotated points in, its descriptor out, LANES points per clock
-- from a private patch copy per lane.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_orb_pattern_pkg.all;

entity fastnms_orb_sample is
  generic (
    LANES : positive := 8
  );
  port (
    clk            : in    std_logic;
    rst            : in    std_logic;
    patch_valid    : in    std_logic;
    patch_ready    : out   std_logic;
    patch_column   : in    std_logic_vector(37 * 8 - 1 downto 0);
    point_valid    : in    std_logic;
    point_ready    : out   std_logic;
    point_first    : in    std_logic;
    point_last     : in    std_logic;
    point_dx       : in    std_logic_vector(6 * LANES - 1 downto 0);
    point_dy       : in    std_logic_vector(6 * LANES - 1 downto 0);
    out_valid      : out   std_logic;
    out_ready      : in    std_logic;
    out_descriptor : out   std_logic_vector(255 downto 0)
  );
end entity fastnms_orb_sample;

architecture rtl of fastnms_orb_sample is

  constant HALF       : natural  := 18;
  constant COLUMNS    : positive := 2 * HALF + 1;
  constant STEPS      : positive := ORB_POINTS / LANES;
  constant PAIR_LANES : positive := maximum(LANES / 2, 1);
  -- From a step taken to the descriptor loaded (the stages above).
  constant LATENCY : positive := 5;

  type lane_bits_t is array (0 to PAIR_LANES - 1) of std_logic_vector(STEPS - 1 downto 0);

  -- Each lane's pixel and each pair-lane's bit, along the last stages.
  signal pixels  : std_logic_vector(8 * LANES - 1 downto 0);
  signal bits    : std_logic_vector(PAIR_LANES - 1 downto 0);
  signal shifted : lane_bits_t;

  -- The patch being written: its bank and the next column (0 .. 36).
  signal write_bank  : std_logic;
  signal column      : natural range 0 to COLUMNS - 1;
  signal column_last : std_logic; -- column = COLUMNS - 1
  signal full        : std_logic_vector(0 to 1);
  signal take_patch  : std_logic;

  -- The points: the bank they read and the next step.
  signal read_bank  : std_logic;
  signal step       : natural range 0 to STEPS - 1;
  signal step_last  : std_logic; -- step = STEPS - 1
  signal read_full  : std_logic;
  signal take_point : std_logic;
  signal held       : std_logic;

  -- Valid and last step along the stages 1 (addresses) .. 5 (bits).
  signal valid      : std_logic_vector(1 to LATENCY);
  signal last       : std_logic_vector(1 to LATENCY);
  signal read_bank1 : std_logic;

  -- The pair-lanes' bits with this clock's shifted in, and the same bits in
  -- descriptor order: the bit of pair-lane j at step s sits at
  -- next_bits(j)(STEPS - 1 - s) once the keypoint's last bit is in. (As
  -- concurrent assignments: GHDL 2.0's synthesis of the same permutation as
  -- a function's loop lost one bit; measured on its netlist.)
  signal next_bits : lane_bits_t;
  signal gathered  : std_logic_vector(255 downto 0);

begin

  assert LANES = 2 or LANES = 4 or LANES = 8 or LANES = 16
    report "fastnms_orb_sample: LANES must be 2, 4, 8 or 16 (two ends of a bit per step)"
    severity failure;

  patch_ready <= not full(0) when write_bank = '0' else
                 not full(1);
  take_patch  <= patch_valid and patch_ready;

  -- The descriptor register is free again before a keypoint's last bit lands:
  -- the previous keypoint's landed STEPS > LATENCY + 1 clocks earlier.
  read_full   <= full(0) when read_bank = '0' else
                 full(1);
  point_ready <= read_full and not (held and step_last);
  take_point  <= point_valid and point_ready;

  control : process (clk) is
  begin

    if rising_edge(clk) then
      if take_patch = '1' then
        column_last <= to_sl(column = COLUMNS - 2);
        if column_last = '1' then
          column     <= 0;
          write_bank <= not write_bank;
        else
          column <= column + 1;
        end if;
      end if;

      valid      <= take_point & valid(1 to LATENCY - 1);
      last       <= step_last & last(1 to LATENCY - 1);
      read_bank1 <= read_bank;

      if take_point = '1' then
        step_last <= to_sl(step = STEPS - 2);
        if step_last = '1' then
          step      <= 0;
          read_bank <= not read_bank;
        else
          step <= step + 1;
        end if;
      end if;

      -- A bank fills with its last column and empties once its last step's
      -- words are read (stage 1's addresses, read on this edge).
      for b in 0 to 1 loop

        if take_patch = '1' and column_last = '1' and write_bank = to_sl(b = 1) then
          full(b) <= '1';
        elsif valid(1) = '1' and last(1) = '1' and read_bank1 = to_sl(b = 1) then
          full(b) <= '0';
        end if;

      end loop;

      if valid(5) = '1' and last(5) = '1' then
        held <= '1';
      elsif out_ready = '1' then
        held <= '0';
      end if;

      if rst = '1' then
        column      <= 0;
        column_last <= '0';
        write_bank  <= '0';
        full        <= "00";
        step        <= 0;
        step_last   <= '0';
        read_bank   <= '0';
        valid       <= (others => '0');
        held        <= '0';
      end if;
    end if;

  end process control;

  out_valid <= held;

  -- Each lane's copy of the patch: rows and columns -REACH .. REACH, one word
  -- of ROWS pixels per column, a bank of SLOT columns per keypoint.

  lane : for l in 0 to LANES - 1 generate
    constant REACH  : natural  := orb_lane_reach(l, LANES);
    constant ROWS   : positive := 2 * REACH + 1;
    constant SLOT   : positive := 32 * ((ROWS + 31) / 32);
    constant GROUPS : positive := (ROWS + 7) / 8;

    type groups_t is array (0 to GROUPS - 1) of std_logic_vector(7 downto 0);

    constant SLOT_BITS : positive := clog2(SLOT);

    signal wr_en    : std_logic;
    signal wr_addr  : unsigned(SLOT_BITS downto 0);
    signal rd_addr  : unsigned(SLOT_BITS downto 0);
    signal word     : std_logic_vector(8 * ROWS - 1 downto 0);
    signal row1     : unsigned(5 downto 0);
    signal row2     : unsigned(5 downto 0);
    signal group3   : unsigned(2 downto 0);
    signal in_group : groups_t;
  begin

    -- Column `column - HALF` of the patch is this copy's column `column - HALF + REACH`.
    wr_en   <= take_patch when column >= HALF - REACH and column <= HALF + REACH else
               '0';
    wr_addr <= write_bank & to_unsigned(column + REACH + SLOT - HALF, SLOT_BITS + 2)(SLOT_BITS - 1 downto 0);

    copy : entity work.fastnms_ram_sdp
      generic map (
        DEPTH        => 2 * SLOT,
        WIDTH        => 8 * ROWS,
        READ_LATENCY => 1,
        STYLE        => "distributed"
      )
      port map (
        clk     => clk,
        wr_en   => wr_en,
        wr_addr => wr_addr,
        wr_data => patch_column(8 * (HALF + REACH) + 7 downto 8 * (HALF - REACH)),
        rd_en   => '1',
        rd_addr => rd_addr,
        rd_data => word
      );

    stages : process (clk) is

      variable col   : signed(6 downto 0);
      variable row   : signed(6 downto 0);
      variable pixel : std_logic_vector(7 downto 0);

    begin

      if rising_edge(clk) then
        -- 1: the point's column (the address in the keypoint's bank) and row.
        col     := resize(signed(point_dx(6 * l + 5 downto 6 * l)), 7) + REACH;
        row     := resize(signed(point_dy(6 * l + 5 downto 6 * l)), 7) + REACH;
        rd_addr <= read_bank & unsigned(col(SLOT_BITS - 1 downto 0));
        row1    <= unsigned(row(5 downto 0));

        -- 2: the word read; 3: the row within each group of 8.
        row2 <= row1;

        for g in 0 to GROUPS - 1 loop

          in_group(g) <= word(64 * g + 7 downto 64 * g);

          for k in 1 to 7 loop

            if row2(2 downto 0) = k and 8 * g + k < ROWS then
              in_group(g) <= word(8 * (8 * g + k) + 7 downto 8 * (8 * g + k));
            end if;

          end loop;

        end loop;

        group3 <= row2(5 downto 3);

        -- 4: the pixel.
        pixel := in_group(0);

        for g in 1 to GROUPS - 1 loop

          if group3 = g then
            pixel := in_group(g);
          end if;

        end loop;

        pixels(8 * l + 7 downto 8 * l) <= pixel;
      end if;

    end process stages;

    -- pragma translate_off
    reach_check : process (clk) is
    begin

      if rising_edge(clk) then
        if take_point = '1' then
          assert abs(to_integer(signed(point_dx(6 * l + 5 downto 6 * l)))) <= REACH and
                 abs(to_integer(signed(point_dy(6 * l + 5 downto 6 * l)))) <= REACH
            report "fastnms_orb_sample: lane " & integer'image(l) & " point beyond its reach " &
                   integer'image(REACH)
            severity error;
        end if;
      end if;

    end process reach_check;

  -- pragma translate_on

  end generate lane;

  pair_lane : for j in 0 to PAIR_LANES - 1 generate

    next_bits(j) <= shifted(j)(STEPS - 2 downto 0) & bits(j);

    per_step : for s in 0 to STEPS - 1 generate
      gathered(ORB_PAIRS_BY_REACH(j * STEPS + s)) <= next_bits(j)(STEPS - 1 - s);
    end generate per_step;

  end generate pair_lane;

  -- 5: the comparisons; then the bits shifted in and, at a keypoint's last
  -- step, the descriptor loaded.
  compare : process (clk) is
  begin

    if rising_edge(clk) then

      for j in 0 to PAIR_LANES - 1 loop

        bits(j) <= to_sl(unsigned(pixels(16 * j + 7 downto 16 * j)) <
                         unsigned(pixels(16 * j + 15 downto 16 * j + 8)));

      end loop;

      if valid(5) = '1' then
        shifted <= next_bits;
        if last(5) = '1' then
          out_descriptor <= gathered;
        end if;
      end if;
    end if;

  end process compare;

  -- pragma translate_off
  order_check : process (clk) is
  begin

    if rising_edge(clk) then
      if rst = '0' and take_point = '1' then
        assert point_first = to_sl(step = 0) and point_last = to_sl(step = STEPS - 1)
          report "fastnms_orb_sample: point_first/point_last disagree with the step count"
          severity error;
      end if;
    end if;

  end process order_check;

-- pragma translate_on

end architecture rtl;
