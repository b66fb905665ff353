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
  -- From a step taken to its bits in (stages 1 .. 6; the lanes' stages).
  constant LATENCY : positive := 6;

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
  -- The column taken on the last clock, written now.
  signal column_taken : std_logic_vector(37 * 8 - 1 downto 0);

  -- The points: the bank they read and the next step.
  signal read_bank  : std_logic;
  signal step       : natural range 0 to STEPS - 1;
  signal step_last  : std_logic; -- step = STEPS - 1
  signal read_full  : std_logic;
  signal take_point : std_logic;
  signal held       : std_logic;

  -- Valid and last step along the stages 1 (addresses) .. 6 (bits).
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
      column_taken <= patch_column;

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

      if valid(LATENCY) = '1' and last(LATENCY) = '1' then
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
  -- of ROWS pixels per column, two banks of ROWS columns (bank 1 at ROWS).
  -- A copy of more than 32 rows is block RAM (its 2 x ROWS words would take
  -- 128-word LUT RAM, too much of an ECP5's; docs/design/orb_sampling.md),
  -- read with its output register; the others are LUT RAM and delay their
  -- pixel by one clock instead, so every lane's pixel lands at stage 5.

  lane : for l in 0 to LANES - 1 generate
    constant REACH    : natural  := orb_lane_reach(l, LANES);
    constant ROWS     : positive := 2 * REACH + 1;
    constant GROUPS   : positive := (ROWS + 7) / 8;
    constant IN_BLOCK : boolean  := ROWS > 32;
    constant ADDRESS  : positive := clog2(2 * ROWS);

    type groups_t is array (0 to GROUPS - 1) of std_logic_vector(7 downto 0);

    -- fastnms_ram_sdp's style and read latency for this copy.
    function style return string is
    begin

      if IN_BLOCK then
        return "block";
      end if;

      return "distributed";

    end function style;

    constant READ_LATENCY : positive := 1 + boolean'pos(IN_BLOCK);

    signal in_window : boolean;
    signal wr_en     : std_logic;
    signal wr_addr   : unsigned(ADDRESS - 1 downto 0);
    signal rd_addr   : unsigned(ADDRESS - 1 downto 0);
    signal word      : std_logic_vector(8 * ROWS - 1 downto 0);

    type rows_t is array (0 to READ_LATENCY) of unsigned(5 downto 0);

    -- The point's row from stage 1 (index 0) to the stage its word is read at.
    signal row_at     : rows_t;
    signal row_group  : unsigned(2 downto 0);
    signal in_group   : groups_t;
    signal pixel_read : std_logic_vector(7 downto 0);
    signal pixel_late : std_logic_vector(7 downto 0);
  begin

    -- Column `column - HALF` of the patch is this copy's column `column - HALF + REACH`;
    -- a copy takes ROWS columns a patch, so its written words count on
    -- modulo 2 x ROWS through bank 0, then bank 1. The write is a clock
    -- after the take, its enable a register of its own (it reaches every
    -- LUT RAM of the copy); a bank's first read is two clocks after its last
    -- column was taken.
    in_window <= column >= HALF - REACH and column <= HALF + REACH;

    write_address : process (clk) is
    begin

      if rising_edge(clk) then
        wr_en <= take_patch when in_window else
                 '0';
        if wr_en = '1' then
          if wr_addr = 2 * ROWS - 1 then
            wr_addr <= (others => '0');
          else
            wr_addr <= wr_addr + 1;
          end if;
        end if;
        if rst = '1' then
          wr_en   <= '0';
          wr_addr <= (others => '0');
        end if;
      end if;

    end process write_address;

    copy : entity work.fastnms_ram_sdp
      generic map (
        DEPTH        => 2 * ROWS,
        WIDTH        => 8 * ROWS,
        READ_LATENCY => READ_LATENCY,
        STYLE        => style
      )
      port map (
        clk     => clk,
        wr_en   => wr_en,
        wr_addr => wr_addr,
        wr_data => column_taken(8 * (HALF + REACH) + 7 downto 8 * (HALF - REACH)),
        rd_en   => '1',
        rd_addr => rd_addr,
        rd_data => word
      );

    stages : process (clk) is

      variable col   : signed(7 downto 0);
      variable row   : signed(6 downto 0);
      variable pixel : std_logic_vector(7 downto 0);

    begin

      if rising_edge(clk) then
        -- 1: the point's column (its address in the keypoint's bank) and row.
        -- (Taken points only: the copy's 2 x ROWS words need not fill the
        -- address range.)
        if read_bank = '1' then
          col := resize(signed(point_dx(6 * l + 5 downto 6 * l)), 8) + (REACH + ROWS);
        else
          col := resize(signed(point_dx(6 * l + 5 downto 6 * l)), 8) + REACH;
        end if;
        row := resize(signed(point_dy(6 * l + 5 downto 6 * l)), 7) + REACH;
        if take_point = '1' then
          rd_addr <= unsigned(col(ADDRESS - 1 downto 0));
        end if;
        row_at(0)                 <= unsigned(row(5 downto 0));
        row_at(1 to READ_LATENCY) <= row_at(0 to READ_LATENCY - 1);

        -- 2 + READ_LATENCY: the row within each group of 8 of the word read.
        for g in 0 to GROUPS - 1 loop

          in_group(g) <= word(64 * g + 7 downto 64 * g);

          for k in 1 to 7 loop

            if row_at(READ_LATENCY)(2 downto 0) = k and 8 * g + k < ROWS then
              in_group(g) <= word(8 * (8 * g + k) + 7 downto 8 * (8 * g + k));
            end if;

          end loop;

        end loop;

        row_group <= row_at(READ_LATENCY)(5 downto 3);

        -- 3 + READ_LATENCY: the pixel (LUT RAM: delayed to stage 5 below).
        pixel := in_group(0);

        for g in 1 to GROUPS - 1 loop

          if row_group = g then
            pixel := in_group(g);
          end if;

        end loop;

        pixel_read <= pixel;
        pixel_late <= pixel_read;
      end if;

    end process stages;

    pixels(8 * l + 7 downto 8 * l) <= pixel_read when IN_BLOCK else
                                      pixel_late;

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

  -- 6: the comparisons; then the bits shifted in and, at a keypoint's last
  -- step, the descriptor loaded.
  compare : process (clk) is
  begin

    if rising_edge(clk) then

      for j in 0 to PAIR_LANES - 1 loop

        bits(j) <= to_sl(unsigned(pixels(16 * j + 7 downto 16 * j)) <
                         unsigned(pixels(16 * j + 15 downto 16 * j + 8)));

      end loop;

      if valid(LATENCY) = '1' then
        shifted <= next_bits;
        if last(LATENCY) = '1' then
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
