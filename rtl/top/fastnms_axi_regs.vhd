-- The register file of fastnms_axi (the map is fastnms_regs_pkg, generated
-- from rtl/top/fastnms_regs.toml): one access at a time from
-- fastnms_axil_slave, the per-frame configuration, status, counters and the
-- interrupt.
-- Datasheet: docs/fastnms_axi.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_regs_pkg.all;

entity fastnms_axi_regs is
  generic (
    MAX_WIDTH         : positive := 1920;
    MAX_HEIGHT        : positive := 1080;
    SCORE             : string   := "opencv";
    NMS               : string   := "3x3";
    SCORE_VIDEO       : boolean  := false;
    CORNER_FIFO_DEPTH : positive := 512;
    PPC               : positive := 1;
    MAX_PER_CELL      : natural  := 0;
    DESCRIPTOR        : string   := "none";
    ORB_MAX_CELL      : positive := 256
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- register accesses (fastnms_axil_slave)
    wr_en    : in    std_logic;
    wr_index : in    unsigned(REG_ADDR_WIDTH - 3 downto 0);
    wr_data  : in    std_logic_vector(REG_DATA_WIDTH - 1 downto 0);
    wr_strb  : in    std_logic_vector(REG_DATA_WIDTH / 8 - 1 downto 0);
    wr_done  : out   std_logic;
    rd_en    : in    std_logic;
    rd_index : in    unsigned(REG_ADDR_WIDTH - 3 downto 0);
    rd_data  : out   std_logic_vector(REG_DATA_WIDTH - 1 downto 0);
    rd_done  : out   std_logic;
    -- control
    enable        : out   std_logic;
    live          : out   std_logic;
    soft_reset    : out   std_logic; -- one-clock pulse
    soft_busy     : in    std_logic; -- read back as CMD.SOFT_RESET
    cfg_apply     : in    std_logic;
    cfg_width     : out   unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    cfg_height    : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    cfg_threshold : out   unsigned(7 downto 0);
    cfg_cell_log  : out   unsigned(2 downto 0);
    cfg_per_cell  : out   unsigned(3 downto 0);
    cfg_min_area  : out   unsigned(MIN_AREA_VALUE_WIDTH - 1 downto 0);
    -- status
    busy            : in    std_logic;
    evt_eol_early   : in    std_logic;
    evt_eol_late    : in    std_logic;
    evt_sof_missing : in    std_logic;
    evt_sof_early   : in    std_logic;
    evt_overflow    : in    std_logic;
    evt_dropped     : in    std_logic;
    evt_stall       : in    std_logic;
    -- fastnms_core's internal_error (STATUS bits ORB_ROWS .. CONFIG_QUEUE)
    evt_internal : in    std_logic_vector(INTERNAL_ERRORS - 1 downto 0);
    out_record   : in    std_logic;
    out_last     : in    std_logic;
    interrupt    : out   std_logic
  );
end entity fastnms_axi_regs;

architecture rtl of fastnms_axi_regs is

  constant CMD_KEY_VALUE : natural := 16#5A#;

  subtype word_t is std_logic_vector(REG_DATA_WIDTH - 1 downto 0);

  subtype sel_t is std_logic_vector(REG_COUNT - 1 downto 0);

  type words_t is array (0 to REG_COUNT - 1) of word_t;

  subtype width_t is unsigned(cfg_width'range);

  subtype height_t is unsigned(cfg_height'range);

  function score_code (s : string) return natural is
  begin

    if s = "sad" then
      return MODE_SCORE_SAD;
    end if;

    return MODE_SCORE_OPENCV;
  end function score_code;

  function nms_code (s : string) return natural is
  begin

    if s = "none" then
      return MODE_NMS_NONE;
    elsif s = "region4" then
      return MODE_NMS_REGION4;
    elsif s = "region8" then
      return MODE_NMS_REGION8;
    end if;

    return MODE_NMS_3X3;
  end function nms_code;

  function field (value : natural; lsb : natural; width : positive) return word_t is
    variable w : word_t := (others => '0');
  begin
    w(lsb + width - 1 downto lsb) := std_logic_vector(to_unsigned(value, width));
    return w;
  end function field;

  -- v placed at bit lsb of a word.
  function place (v : std_logic_vector; lsb : natural) return word_t is
    variable w : word_t := (others => '0');
  begin
    w(lsb + v'length - 1 downto lsb) := v;
    return w;
  end function place;

  function place (b : std_logic; pos : natural) return word_t is
    variable w : word_t := (others => '0');
  begin
    w(pos) := b;
    return w;
  end function place;

  -- The OR of the words whose select bit is set.
  function selected (w : words_t; sel : sel_t) return word_t is
    variable r : word_t := (others => '0');
  begin

    for i in w'range loop

      if sel(i) = '1' then
        r := r or w(i);
      end if;

    end loop;

    return r;
  end function selected;

  constant ORB : boolean := DESCRIPTOR = "orb";

  -- The largest log2(CELL) - 4 BUDGET takes.
  function largest_cell_log return natural is
  begin

    if ORB then
      return minimum(4, maximum(4, clog2(ORB_MAX_CELL)) - 4);
    end if;

    return 4;

  end function largest_cell_log;

  constant MAX_CELL_LOG : natural := largest_cell_log;

  -- The read-only constants.
  constant VERSION_WORD : word_t := place(VERSION_MAJOR_RESET, VERSION_MAJOR_LSB) or
                                    place(VERSION_MINOR_RESET, VERSION_MINOR_LSB) or
                                    place(VERSION_PATCH_RESET, VERSION_PATCH_LSB);
  constant MODE_WORD    : word_t := field(score_code(SCORE), MODE_SCORE_LSB, MODE_SCORE_WIDTH) or
                                    field(nms_code(NMS), MODE_NMS_LSB, MODE_NMS_WIDTH) or
                                    field(PPC, MODE_PPC_LSB, MODE_PPC_WIDTH) or
                                    field(boolean'pos(ORB), MODE_DESCRIPTOR_LSB, MODE_DESCRIPTOR_WIDTH);
  constant MAX_WORD     : word_t := field(MAX_WIDTH, MAX_SIZE_WIDTH_LSB, MAX_SIZE_WIDTH_WIDTH) or
                                    field(MAX_HEIGHT, MAX_SIZE_HEIGHT_LSB, MAX_SIZE_HEIGHT_WIDTH);
  constant BUILD_WORD   : word_t := field(CORNER_FIFO_DEPTH, BUILD_FIFO_DEPTH_LSB, BUILD_FIFO_DEPTH_WIDTH) or
                                    field(boolean'pos(SCORE_VIDEO), BUILD_SCORE_VIDEO, 1) or
                                    field(MAX_PER_CELL, BUILD_MAX_PER_CELL_LSB, BUILD_MAX_PER_CELL_WIDTH);

  -- The narrowest frame (fastnms_window with READ_LATENCY 1): 7 pixels in
  -- whole beats of PPC, at least two beats.
  constant MIN_WIDTH : positive := ((maximum(7, 2 * PPC) + PPC - 1) / PPC) * PPC;

  -- Write pipeline: decoded (w_sel, every clock from the stable index), then
  -- wr_en -> merged -> flags1 -> execute (= wr_done).
  signal w_sel    : sel_t;
  signal w_merged : std_logic;
  signal w_flags1 : std_logic;
  signal do_write : std_logic;
  signal w_data   : word_t; -- the write's data, strobed bytes only
  signal w_byte   : std_logic_vector(3 downto 0);
  signal w_width  : word_t; -- WIDTH and HEIGHT after the merge
  signal w_height : word_t;
  signal w_budget : word_t;
  -- BUDGET after the merge, clamped.
  signal bu_cell_log : unsigned(2 downto 0);
  signal bu_per_cell : unsigned(3 downto 0);
  -- Clamping flags of the merged WIDTH and HEIGHT, in two steps.
  signal wd_high      : std_logic;
  signal wd_low_min   : std_logic;
  signal wd_above     : std_logic;
  signal ht_high      : std_logic;
  signal ht_low_7     : std_logic;
  signal ht_above     : std_logic;
  signal wd_below_min : std_logic;
  signal wd_over      : std_logic;
  signal ht_below_7   : std_logic;
  signal ht_over      : std_logic;

  -- Read: decoded every clock from the stable index.
  signal r_sel : sel_t;
  signal words : words_t;

  -- Registers.
  signal enable_r      : std_logic;
  signal irq_enable    : std_logic;
  signal live_r        : std_logic;
  signal soft_pulse    : std_logic;
  signal thr_shadow    : unsigned(7 downto 0);
  signal width_shadow  : width_t;
  signal height_shadow : height_t;
  signal thr_active    : unsigned(7 downto 0);
  signal width_active  : width_t;
  signal height_active : height_t;
  signal cell_shadow   : unsigned(2 downto 0);
  signal k_shadow      : unsigned(3 downto 0);
  signal cell_active   : unsigned(2 downto 0);
  signal k_active      : unsigned(3 downto 0);
  signal area_shadow   : unsigned(MIN_AREA_VALUE_WIDTH - 1 downto 0);
  signal area_active   : unsigned(MIN_AREA_VALUE_WIDTH - 1 downto 0);
  signal sticky        : std_logic_vector(STATUS_CONFIG_QUEUE downto STATUS_FRAME_DONE);
  signal events        : std_logic_vector(STATUS_CONFIG_QUEUE downto STATUS_FRAME_DONE);
  signal clear_mask    : std_logic_vector(STATUS_CONFIG_QUEUE downto STATUS_FRAME_DONE);
  signal busy_r        : std_logic;
  signal key_ok        : std_logic;

  -- Frame statistics.
  signal   rec_pulse     : std_logic;
  signal   last_pulse    : std_logic;
  signal   done_pulse    : std_logic; -- the clock after last_pulse
  signal   drop_pulse    : std_logic;
  signal   stall_pulse   : std_logic;
  constant COUNT_CORNERS : natural := 0;
  constant COUNT_FRAMES  : natural := 1;
  constant COUNT_DROPPED : natural := 2;
  constant COUNT_STALLS  : natural := 3;

  type counts_t is array (0 to 3) of unsigned(31 downto 0);

  signal counts       : counts_t;
  signal count_steps  : std_logic_vector(0 to 3);
  signal count_clears : std_logic_vector(0 to 3);
  signal corners      : unsigned(31 downto 0);
  signal frames       : unsigned(31 downto 0);
  signal corner_count : unsigned(31 downto 0);
  signal dropped      : unsigned(31 downto 0);
  signal stalls       : unsigned(31 downto 0);

begin

  assert MAX_WIDTH >= 7 and MAX_WIDTH < 2 ** 16 and MAX_HEIGHT >= 7 and MAX_HEIGHT < 2 ** 16
    report "fastnms_axi_regs: MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"
    severity failure;
  assert MAX_PER_CELL <= 15
    report "fastnms_axi_regs: MAX_PER_CELL must be 0 .. 15"
    severity failure;
  assert DESCRIPTOR = "none" or DESCRIPTOR = "orb"
    report "fastnms_axi_regs: DESCRIPTOR must be ""none"" or ""orb"""
    severity failure;
  assert not ORB or orb_rate_per_cell(1) = 15
    report "fastnms_axi_regs: the K clamp takes the ORB rate below 15 at CELL 16 only"
    severity failure;
  assert ORB_MAX_CELL >= 16
    report "fastnms_axi_regs: ORB_MAX_CELL must be at least 16"
    severity failure;
  assert CORNER_FIFO_DEPTH < 2 ** 16
    report "fastnms_axi_regs: CORNER_FIFO_DEPTH must be below 65536"
    severity failure;

  -- ---- write pipeline ----------------------------------------------------------

  write_pipeline : process (clk) is
  begin

    if rising_edge(clk) then
      for i in 0 to REG_COUNT - 1 loop
        w_sel(i) <= to_sl(wr_index = i);
        r_sel(i) <= to_sl(rd_index = i);
      end loop;

      -- The bytes not strobed: zero in w_data, the old value in WIDTH,
      -- HEIGHT and BUDGET (whose other bits read 0).
      w_merged <= wr_en;
      if wr_en = '1' then
        for b in 0 to 3 loop
          w_byte(b) <= wr_strb(b);
          if wr_strb(b) = '1' then
            w_data(8 * b + 7 downto 8 * b)   <= wr_data(8 * b + 7 downto 8 * b);
            w_width(8 * b + 7 downto 8 * b)  <= wr_data(8 * b + 7 downto 8 * b);
            w_height(8 * b + 7 downto 8 * b) <= wr_data(8 * b + 7 downto 8 * b);
            w_budget(8 * b + 7 downto 8 * b) <= wr_data(8 * b + 7 downto 8 * b);
          else
            w_data(8 * b + 7 downto 8 * b)   <= (others => '0');
            w_width(8 * b + 7 downto 8 * b)  <= words(REG_WIDTH)(8 * b + 7 downto 8 * b);
            w_height(8 * b + 7 downto 8 * b) <= words(REG_HEIGHT)(8 * b + 7 downto 8 * b);
            w_budget(8 * b + 7 downto 8 * b) <= words(REG_BUDGET)(8 * b + 7 downto 8 * b);
          end if;
        end loop;
      end if;

      w_flags1   <= w_merged;
      wd_high    <= or w_width(REG_DATA_WIDTH - 1 downto 16);
      wd_low_min <= not at_least(unsigned(w_width(15 downto 0)), MIN_WIDTH);
      wd_above   <= at_least(unsigned(w_width(15 downto 0)), MAX_WIDTH + 1);
      ht_high    <= or w_height(REG_DATA_WIDTH - 1 downto 16);
      ht_low_7   <= not at_least(unsigned(w_height(15 downto 0)), 7);
      ht_above   <= at_least(unsigned(w_height(15 downto 0)), MAX_HEIGHT + 1);
      -- CELL: 256 and above, then the highest of bits 23 .. 21, else 16.
      if (or w_budget(31 downto BUDGET_CELL_LSB + 8)) = '1' then
        bu_cell_log <= to_unsigned(minimum(4, MAX_CELL_LOG), 3);
      elsif w_budget(BUDGET_CELL_LSB + 7) = '1' then
        bu_cell_log <= to_unsigned(minimum(3, MAX_CELL_LOG), 3);
      elsif w_budget(BUDGET_CELL_LSB + 6) = '1' then
        bu_cell_log <= to_unsigned(minimum(2, MAX_CELL_LOG), 3);
      elsif w_budget(BUDGET_CELL_LSB + 5) = '1' then
        bu_cell_log <= to_unsigned(minimum(1, MAX_CELL_LOG), 3);
      else
        bu_cell_log <= to_unsigned(0, 3);
      end if;
      if unsigned(w_budget(BUDGET_PER_CELL_LSB + 3 downto BUDGET_PER_CELL_LSB)) > MAX_PER_CELL then
        bu_per_cell <= to_unsigned(MAX_PER_CELL, 4);
      else
        bu_per_cell <= unsigned(w_budget(BUDGET_PER_CELL_LSB + 3 downto BUDGET_PER_CELL_LSB));
      end if;

      do_write     <= w_flags1;
      wd_below_min <= wd_low_min and not wd_high;
      wd_over      <= wd_above or wd_high;
      ht_below_7   <= ht_low_7 and not ht_high;
      ht_over      <= ht_above or ht_high;
      key_ok       <= to_sl(unsigned(w_data(CMD_KEY_LSB + CMD_KEY_WIDTH - 1 downto CMD_KEY_LSB)) = CMD_KEY_VALUE);

      rd_done <= rd_en;
      if rd_en = '1' then
        rd_data <= selected(words, r_sel);
      end if;

      if rst = '1' then
        w_merged <= '0';
        w_flags1 <= '0';
        do_write <= '0';
        rd_done  <= '0';
      end if;
    end if;

  end process write_pipeline;

  wr_done <= do_write;

  -- ---- registers -------------------------------------------------------------

  clear_mask <= w_data(clear_mask'range) when do_write = '1' and w_sel(REG_STATUS) = '1' else
                (others => '0');
  events     <=
  (
    STATUS_FRAME_DONE   => done_pulse,
    STATUS_EOL_EARLY    => evt_eol_early,
    STATUS_EOL_LATE     => evt_eol_late,
    STATUS_SOF_MISSING  => evt_sof_missing,
    STATUS_SOF_EARLY    => evt_sof_early,
    STATUS_OVERFLOW     => evt_overflow,
    STATUS_ORB_ROWS     => evt_internal(INTERNAL_ORB_ROWS),
    STATUS_ORB_TAGS     => evt_internal(INTERNAL_ORB_TAGS),
    STATUS_ORB_COUNT    => evt_internal(INTERNAL_ORB_COUNT),
    STATUS_CONFIG_QUEUE => evt_internal(INTERNAL_CONFIG_QUEUE)
  );

  registers : process (clk) is
  begin

    if rising_edge(clk) then
      soft_pulse <= '0';

      if do_write = '1' then
        if w_sel(REG_CTRL) = '1' and w_byte(0) = '1' then
          enable_r   <= w_data(CTRL_ENABLE);
          irq_enable <= w_data(CTRL_IRQ_ENABLE);
          live_r     <= w_data(CTRL_LIVE);
        end if;
        if w_sel(REG_CMD) = '1' then
          soft_pulse <= w_data(CMD_SOFT_RESET) and key_ok;
        end if;
        if w_sel(REG_THRESHOLD) = '1' and w_byte(0) = '1' then
          thr_shadow <= unsigned(w_data(THRESHOLD_VALUE_WIDTH - 1 downto THRESHOLD_VALUE_LSB));
        end if;
        if w_sel(REG_WIDTH) = '1' then
          if wd_below_min = '1' then
            width_shadow <= to_unsigned(MIN_WIDTH, width_t'length);
          elsif wd_over = '1' then
            width_shadow <= to_unsigned(MAX_WIDTH, width_t'length);
          else
            -- Whole beats: the low bits cleared.
            width_shadow <= unsigned(w_width(width_t'range)) and not to_unsigned(PPC - 1, width_t'length);
          end if;
        end if;
        if w_sel(REG_HEIGHT) = '1' then
          if ht_below_7 = '1' then
            height_shadow <= to_unsigned(7, height_t'length);
          elsif ht_over = '1' then
            height_shadow <= to_unsigned(MAX_HEIGHT, height_t'length);
          else
            height_shadow <= unsigned(w_height(height_t'range));
          end if;
        end if;
        if w_sel(REG_BUDGET) = '1' then
          cell_shadow <= bu_cell_log;
          k_shadow    <= bu_per_cell;
          -- With ORB, K no higher than the engine's rate at this CELL (4 at 16).
          if ORB and bu_per_cell > orb_rate_per_cell(0) and bu_cell_log = 0 then
            k_shadow <= to_unsigned(orb_rate_per_cell(0), 4);
          end if;
        end if;
        if w_sel(REG_MIN_AREA) = '1' then
          for i in area_shadow'range loop
            if w_byte((MIN_AREA_VALUE_LSB + i) / 8) = '1' then
              area_shadow(i) <= w_data(MIN_AREA_VALUE_LSB + i);
            end if;
          end loop;
        end if;
      end if;

      -- A write on the clock of an apply is for the next frame.
      if cfg_apply = '1' then
        thr_active    <= thr_shadow;
        width_active  <= width_shadow;
        height_active <= height_shadow;
        cell_active   <= cell_shadow;
        k_active      <= k_shadow;
        area_active   <= area_shadow;
      end if;

      sticky    <= (sticky and not clear_mask) or events;
      busy_r    <= busy;
      interrupt <= irq_enable and (sticky(STATUS_FRAME_DONE) or
                                   (or sticky(STATUS_CONFIG_QUEUE downto STATUS_ORB_ROWS)));

      if rst = '1' then
        enable_r      <= CTRL_ENABLE_RESET;
        irq_enable    <= CTRL_IRQ_ENABLE_RESET;
        live_r        <= CTRL_LIVE_RESET;
        soft_pulse    <= '0';
        thr_shadow    <= unsigned(THRESHOLD_VALUE_RESET);
        thr_active    <= unsigned(THRESHOLD_VALUE_RESET);
        width_shadow  <= to_unsigned(MAX_WIDTH, width_t'length);
        width_active  <= to_unsigned(MAX_WIDTH, width_t'length);
        height_shadow <= to_unsigned(MAX_HEIGHT, height_t'length);
        height_active <= to_unsigned(MAX_HEIGHT, height_t'length);
        cell_shadow   <= to_unsigned(0, 3);
        cell_active   <= to_unsigned(0, 3);
        k_shadow      <= unsigned(BUDGET_PER_CELL_RESET);
        k_active      <= unsigned(BUDGET_PER_CELL_RESET);
        area_shadow   <= unsigned(MIN_AREA_VALUE_RESET);
        area_active   <= unsigned(MIN_AREA_VALUE_RESET);
        sticky        <= (others => '0');
        interrupt     <= '0';
      end if;
    end if;

  end process registers;

  enable        <= enable_r;
  live          <= live_r;
  soft_reset    <= soft_pulse;
  cfg_threshold <= thr_active;
  cfg_width     <= width_active;
  cfg_height    <= height_active;
  cfg_cell_log  <= cell_active;
  cfg_per_cell  <= k_active;
  cfg_min_area  <= area_active;

  -- ---- frame statistics ------------------------------------------------------

  statistics : process (clk) is
  begin

    if rising_edge(clk) then
      rec_pulse   <= out_record;
      last_pulse  <= out_last;
      done_pulse  <= last_pulse;
      drop_pulse  <= evt_dropped;
      stall_pulse <= evt_stall;
      if done_pulse = '1' then
        corner_count <= corners;
      end if;

      if rst = '1' then
        rec_pulse    <= '0';
        last_pulse   <= '0';
        done_pulse   <= '0';
        drop_pulse   <= '0';
        stall_pulse  <= '0';
        corner_count <= (others => '0');
      end if;
    end if;

  end process statistics;

  -- Four 32-bit event counters. COUNT_CORNERS counts the records of the
  -- current frame (a record counts on the clock after rec_pulse); it restarts
  -- when the count is taken, on the clock after the frame's last record has
  -- been counted. The others count from reset and wrap.
  count_steps  <=
  (
    COUNT_CORNERS => rec_pulse,
    COUNT_FRAMES  => done_pulse,
    COUNT_DROPPED => drop_pulse,
    COUNT_STALLS  => stall_pulse
  );
  count_clears <= (COUNT_CORNERS => done_pulse, others => '0');

  counters : for i in counts'range generate

    counter : entity work.fastnms_counter
      generic map (
        WIDTH   => 32,
        SEGMENT => 12
      )
      port map (
        clk   => clk,
        rst   => rst,
        clear => count_clears(i),
        step  => count_steps(i),
        value => counts(i)
      );

  end generate counters;

  corners <= counts(COUNT_CORNERS);
  frames  <= counts(COUNT_FRAMES);
  dropped <= counts(COUNT_DROPPED);
  stalls  <= counts(COUNT_STALLS);

  -- ---- read values -----------------------------------------------------------

  words <=
  (
    REG_ID           => ID_MAGIC_RESET,
    REG_VERSION      => VERSION_WORD,
    REG_CTRL         => place(enable_r, CTRL_ENABLE) or place(irq_enable,
                                                               CTRL_IRQ_ENABLE) or
    place(live_r,
           CTRL_LIVE),
    REG_STATUS       => place(busy_r, STATUS_BUSY) or place(sticky,
                                                             STATUS_FRAME_DONE),
    REG_THRESHOLD    => std_logic_vector(resize(thr_shadow, REG_DATA_WIDTH)),
    REG_WIDTH        => std_logic_vector(resize(width_shadow, REG_DATA_WIDTH)),
    REG_HEIGHT       => std_logic_vector(resize(height_shadow, REG_DATA_WIDTH)),
    REG_MODE         => MODE_WORD,
    REG_CORNER_COUNT => std_logic_vector(corner_count),
    REG_FRAME_COUNT  => std_logic_vector(frames),
    REG_MAX_SIZE     => MAX_WORD,
    REG_BUILD        => BUILD_WORD,
    REG_CMD          => place(soft_busy, CMD_SOFT_RESET),
    REG_DROPPED      => std_logic_vector(dropped),
    REG_INPUT_STALLS => std_logic_vector(stalls),
    REG_BUDGET       => place(std_logic_vector(k_shadow), BUDGET_PER_CELL_LSB) or
    place(std_logic_vector(shift_left(to_unsigned(16,
                                                   BUDGET_CELL_WIDTH),
                                       to_integer(cell_shadow))),
           BUDGET_CELL_LSB),
    REG_MIN_AREA     => place(std_logic_vector(area_shadow), MIN_AREA_VALUE_LSB)
  );

end architecture rtl;
