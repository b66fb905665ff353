-- AXI4-Lite slave and register file of fastnms_axi. The map is in
-- fastnms_regs_pkg (generated from rtl/top/fastnms_regs.toml; see docs/fastnms_axi.md).
--
-- Protocol: one write and one read in flight (the address and data of a
-- write are taken in any order, each behind a registered ready). A write
-- responds three clocks after both halves are in, a read two clocks after
-- its address; BVALID/RVALID then wait for BREADY/RREADY. Responses: OKAY,
-- or SLVERR for an address outside the map or a write whose WSTRB is not
-- "1111" (such a write changes nothing). Writes to read-only registers are
-- ignored with OKAY. AWPROT/ARPROT are ignored.
--
-- Configuration: THRESHOLD, WIDTH and HEIGHT are written into shadow
-- registers and set cfg_pending; the core's values (cfg_*) take them when
-- cfg_apply pulses (the video gate does that at a start of frame, while the
-- input waits). WIDTH and HEIGHT writes are clamped to 7 .. MAX_*.
--
-- Status: the sticky STATUS bits are set by one-clock event pulses and
-- cleared by writing 1. out_record / out_last pulse on the handshakes of
-- m_axis_corners (a record that is not EMPTY / a record with tlast);
-- three clocks after the pulse of a last record, CORNER_COUNT and FRAME_COUNT
-- take their new values and FRAME_DONE is set. interrupt = IRQ_ENABLE and FRAME_DONE,
-- registered.
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
    CORNER_FIFO_DEPTH : positive := 512
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- AXI4-Lite slave
    s_axi_awaddr  : in    std_logic_vector(REG_ADDR_WIDTH - 1 downto 0);
    s_axi_awvalid : in    std_logic;
    s_axi_awready : out   std_logic;
    s_axi_wdata   : in    std_logic_vector(REG_DATA_WIDTH - 1 downto 0);
    s_axi_wstrb   : in    std_logic_vector(REG_DATA_WIDTH / 8 - 1 downto 0);
    s_axi_wvalid  : in    std_logic;
    s_axi_wready  : out   std_logic;
    s_axi_bresp   : out   std_logic_vector(1 downto 0);
    s_axi_bvalid  : out   std_logic;
    s_axi_bready  : in    std_logic;
    s_axi_araddr  : in    std_logic_vector(REG_ADDR_WIDTH - 1 downto 0);
    s_axi_arvalid : in    std_logic;
    s_axi_arready : out   std_logic;
    s_axi_rdata   : out   std_logic_vector(REG_DATA_WIDTH - 1 downto 0);
    s_axi_rresp   : out   std_logic_vector(1 downto 0);
    s_axi_rvalid  : out   std_logic;
    s_axi_rready  : in    std_logic;
    -- control
    enable        : out   std_logic;
    soft_reset    : out   std_logic; -- one-clock pulse
    soft_busy     : in    std_logic; -- read back as CTRL.SOFT_RESET
    cfg_pending   : out   std_logic;
    cfg_apply     : in    std_logic;
    cfg_width     : out   unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    cfg_height    : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    cfg_threshold : out   unsigned(7 downto 0);
    -- status
    busy            : in    std_logic;
    evt_eol_early   : in    std_logic;
    evt_eol_late    : in    std_logic;
    evt_sof_missing : in    std_logic;
    evt_sof_early   : in    std_logic;
    evt_overflow    : in    std_logic;
    out_record      : in    std_logic;
    out_last        : in    std_logic;
    interrupt       : out   std_logic
  );
end entity fastnms_axi_regs;

architecture rtl of fastnms_axi_regs is

  constant INDEX_BITS : positive                     := REG_ADDR_WIDTH - 2;
  constant OKAY       : std_logic_vector(1 downto 0) := "00";
  constant SLVERR     : std_logic_vector(1 downto 0) := "10";

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

  -- The read-only constants.
  constant VERSION_WORD : word_t := place(VERSION_MAJOR_RESET, VERSION_MAJOR_LSB) or
                                    place(VERSION_MINOR_RESET, VERSION_MINOR_LSB) or
                                    place(VERSION_PATCH_RESET, VERSION_PATCH_LSB);
  constant MODE_WORD    : word_t := field(score_code(SCORE), MODE_SCORE_LSB, MODE_SCORE_WIDTH) or
                                    field(nms_code(NMS), MODE_NMS_LSB, MODE_NMS_WIDTH);
  constant MAX_WORD     : word_t := field(MAX_WIDTH, MAX_SIZE_WIDTH_LSB, MAX_SIZE_WIDTH_WIDTH) or
                                    field(MAX_HEIGHT, MAX_SIZE_HEIGHT_LSB, MAX_SIZE_HEIGHT_WIDTH);
  constant BUILD_WORD   : word_t := field(CORNER_FIFO_DEPTH, BUILD_FIFO_DEPTH_LSB, BUILD_FIFO_DEPTH_WIDTH) or
                                    field(boolean'pos(SCORE_VIDEO), BUILD_SCORE_VIDEO, 1);

  -- Write channel.
  type write_state_t is (w_idle, w_decode, w_execute, w_respond);

  signal w_state   : write_state_t;
  signal aw_full   : std_logic;
  signal aw_index  : unsigned(INDEX_BITS - 1 downto 0);
  signal w_full    : std_logic;
  signal w_data    : word_t;
  signal w_strb_ok : std_logic;
  signal w_sel     : sel_t; -- the register addressed (one-hot)
  signal w_ok      : std_logic;
  -- Clamping flags of the written value, and the halves they come from.
  signal w_high    : std_logic;
  signal w_low_7   : std_logic;
  signal w_low_w   : std_logic;
  signal w_low_h   : std_logic;
  signal w_below_7 : std_logic;
  signal w_above_w : std_logic;
  signal w_above_h : std_logic;
  signal b_valid   : std_logic;
  signal b_resp    : std_logic_vector(1 downto 0);
  signal do_write  : std_logic;

  -- Read channel.
  type read_state_t is (r_idle, r_decode, r_respond);

  signal r_state  : read_state_t;
  signal ar_full  : std_logic;
  signal ar_index : unsigned(INDEX_BITS - 1 downto 0);
  signal r_sel    : sel_t;
  signal r_ok     : std_logic;
  signal r_valid  : std_logic;
  signal r_data   : word_t;
  signal r_resp   : std_logic_vector(1 downto 0);
  signal words    : words_t;

  -- Registers.
  signal enable_r      : std_logic;
  signal irq_enable    : std_logic;
  signal soft_pulse    : std_logic;
  signal pending       : std_logic;
  signal thr_shadow    : unsigned(7 downto 0);
  signal width_shadow  : width_t;
  signal height_shadow : height_t;
  signal thr_active    : unsigned(7 downto 0);
  signal width_active  : width_t;
  signal height_active : height_t;
  signal sticky        : std_logic_vector(STATUS_OVERFLOW downto STATUS_FRAME_DONE);
  signal events        : std_logic_vector(STATUS_OVERFLOW downto STATUS_FRAME_DONE);
  signal clear_mask    : std_logic_vector(STATUS_OVERFLOW downto STATUS_FRAME_DONE);
  signal busy_r        : std_logic;

  -- Frame statistics.
  signal rec_pulse    : std_logic;
  signal last_pulse   : std_logic;
  signal done_pulse   : std_logic; -- the clock after last_pulse
  signal corners      : unsigned(31 downto 0);
  signal frames       : unsigned(31 downto 0);
  signal corner_count : unsigned(31 downto 0);

begin

  assert MAX_WIDTH >= 7 and MAX_WIDTH < 2 ** 16 and MAX_HEIGHT >= 7 and MAX_HEIGHT < 2 ** 16
    report "fastnms_axi_regs: MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"
    severity failure;
  assert CORNER_FIFO_DEPTH < 2 ** 16
    report "fastnms_axi_regs: CORNER_FIFO_DEPTH must be below 65536"
    severity failure;

  -- ---- write channel ---------------------------------------------------------

  -- No ready during reset: a channel taken then would be lost.
  s_axi_awready <= not aw_full and not rst;
  s_axi_wready  <= not w_full and not rst;
  s_axi_bvalid  <= b_valid;
  s_axi_bresp   <= b_resp;
  do_write      <= to_sl(w_state = w_execute) and w_ok;

  write_channel : process (clk) is
  begin

    if rising_edge(clk) then
      if s_axi_awvalid = '1' and aw_full = '0' then
        aw_full  <= '1';
        aw_index <= unsigned(s_axi_awaddr(REG_ADDR_WIDTH - 1 downto 2));
      end if;
      if s_axi_wvalid = '1' and w_full = '0' then
        w_full    <= '1';
        w_data    <= s_axi_wdata;
        w_strb_ok <= and s_axi_wstrb;
      end if;

      -- (if/elsif, not case: GHDL writes a case as a latch-like Verilog mux)
      if w_state = w_idle then
        if aw_full = '1' and w_full = '1' then
          w_state <= w_decode;
        end if;
      elsif w_state = w_decode then
        w_state <= w_execute;
      elsif w_state = w_execute then
        w_state <= w_respond;
        b_valid <= '1';
        b_resp  <= SLVERR;
        if w_ok = '1' then
          b_resp <= OKAY;
        end if;
        aw_full <= '0';
        w_full  <= '0';
      elsif s_axi_bready = '1' then
        b_valid <= '0';
        w_state <= w_idle;
      end if;

      -- Decoded one clock ahead of the write itself.
      for i in 0 to REG_COUNT - 1 loop
        w_sel(i) <= to_sl(aw_index = i);
      end loop;
      w_ok <= to_sl(aw_index < REG_COUNT) and w_strb_ok;
      -- The clamping flags in two steps (ready by the execute clock).
      w_high    <= or w_data(REG_DATA_WIDTH - 1 downto 16);
      w_low_7   <= not at_least(unsigned(w_data(15 downto 0)), 7);
      w_low_w   <= at_least(unsigned(w_data(15 downto 0)), MAX_WIDTH + 1);
      w_low_h   <= at_least(unsigned(w_data(15 downto 0)), MAX_HEIGHT + 1);
      w_below_7 <= w_low_7 and not w_high;
      w_above_w <= w_low_w or w_high;
      w_above_h <= w_low_h or w_high;

      if rst = '1' then
        w_state  <= w_idle;
        aw_full  <= '0';
        aw_index <= (others => '0'); -- decoded on every clock
        w_full   <= '0';
        b_valid  <= '0';
      end if;
    end if;

  end process write_channel;

  -- ---- read channel ----------------------------------------------------------

  s_axi_arready <= not ar_full and not rst;
  s_axi_rvalid  <= r_valid;
  s_axi_rdata   <= r_data;
  s_axi_rresp   <= r_resp;

  read_channel : process (clk) is
  begin

    if rising_edge(clk) then
      if s_axi_arvalid = '1' and ar_full = '0' then
        ar_full  <= '1';
        ar_index <= unsigned(s_axi_araddr(REG_ADDR_WIDTH - 1 downto 2));
      end if;

      for i in 0 to REG_COUNT - 1 loop
        r_sel(i) <= to_sl(ar_index = i);
      end loop;
      r_ok <= to_sl(ar_index < REG_COUNT);

      if r_state = r_idle then
        if ar_full = '1' then
          r_state <= r_decode;
        end if;
      elsif r_state = r_decode then
        r_data <= selected(words, r_sel);
        r_resp <= SLVERR;
        if r_ok = '1' then
          r_resp <= OKAY;
        end if;
        r_valid <= '1';
        ar_full <= '0';
        r_state <= r_respond;
      elsif s_axi_rready = '1' then
        r_valid <= '0';
        r_state <= r_idle;
      end if;

      if rst = '1' then
        r_state  <= r_idle;
        ar_full  <= '0';
        ar_index <= (others => '0'); -- decoded on every clock
        r_valid  <= '0';
      end if;
    end if;

  end process read_channel;

  -- ---- registers -------------------------------------------------------------

  clear_mask <= w_data(clear_mask'range) when do_write = '1' and w_sel(REG_STATUS) = '1' else
                (others => '0');
  events     <=
  (
    STATUS_FRAME_DONE  => done_pulse,
    STATUS_EOL_EARLY   => evt_eol_early,
    STATUS_EOL_LATE    => evt_eol_late,
    STATUS_SOF_MISSING => evt_sof_missing,
    STATUS_SOF_EARLY   => evt_sof_early,
    STATUS_OVERFLOW    => evt_overflow
  );

  registers : process (clk) is
  begin

    if rising_edge(clk) then
      soft_pulse <= '0';

      if do_write = '1' then
        if w_sel(REG_CTRL) = '1' then
          enable_r   <= w_data(CTRL_ENABLE);
          irq_enable <= w_data(CTRL_IRQ_ENABLE);
          soft_pulse <= w_data(CTRL_SOFT_RESET);
        end if;
        if w_sel(REG_THRESHOLD) = '1' then
          thr_shadow <= unsigned(w_data(THRESHOLD_VALUE_WIDTH - 1 downto THRESHOLD_VALUE_LSB));
        end if;
        if w_sel(REG_WIDTH) = '1' then
          if w_below_7 = '1' then
            width_shadow <= to_unsigned(7, width_t'length);
          elsif w_above_w = '1' then
            width_shadow <= to_unsigned(MAX_WIDTH, width_t'length);
          else
            width_shadow <= unsigned(w_data(width_t'range));
          end if;
        end if;
        if w_sel(REG_HEIGHT) = '1' then
          if w_below_7 = '1' then
            height_shadow <= to_unsigned(7, height_t'length);
          elsif w_above_h = '1' then
            height_shadow <= to_unsigned(MAX_HEIGHT, height_t'length);
          else
            height_shadow <= unsigned(w_data(height_t'range));
          end if;
        end if;
      end if;

      if cfg_apply = '1' then
        thr_active    <= thr_shadow;
        width_active  <= width_shadow;
        height_active <= height_shadow;
        pending       <= '0';
      end if;
      -- A write on the clock of an apply stays pending for the next one.
      if do_write = '1' and (w_sel(REG_THRESHOLD) = '1' or w_sel(REG_WIDTH) = '1' or
                             w_sel(REG_HEIGHT) = '1') then
        pending <= '1';
      end if;

      sticky    <= (sticky and not clear_mask) or events;
      busy_r    <= busy;
      interrupt <= irq_enable and sticky(STATUS_FRAME_DONE);

      if rst = '1' then
        enable_r      <= CTRL_ENABLE_RESET;
        irq_enable    <= CTRL_IRQ_ENABLE_RESET;
        soft_pulse    <= '0';
        pending       <= '0';
        thr_shadow    <= unsigned(THRESHOLD_VALUE_RESET);
        thr_active    <= unsigned(THRESHOLD_VALUE_RESET);
        width_shadow  <= to_unsigned(MAX_WIDTH, width_t'length);
        width_active  <= to_unsigned(MAX_WIDTH, width_t'length);
        height_shadow <= to_unsigned(MAX_HEIGHT, height_t'length);
        height_active <= to_unsigned(MAX_HEIGHT, height_t'length);
        sticky        <= (others => '0');
        interrupt     <= '0';
      end if;
    end if;

  end process registers;

  enable        <= enable_r;
  soft_reset    <= soft_pulse;
  cfg_pending   <= pending;
  cfg_threshold <= thr_active;
  cfg_width     <= width_active;
  cfg_height    <= height_active;

  -- ---- frame statistics ------------------------------------------------------

  statistics : process (clk) is
  begin

    if rising_edge(clk) then
      rec_pulse  <= out_record;
      last_pulse <= out_last;
      done_pulse <= last_pulse;
      if done_pulse = '1' then
        corner_count <= corners;
      end if;

      if rst = '1' then
        rec_pulse    <= '0';
        last_pulse   <= '0';
        done_pulse   <= '0';
        corner_count <= (others => '0');
      end if;
    end if;

  end process statistics;

  -- corners counts the records of the current frame (a record counts on the
  -- clock after rec_pulse); it restarts when the count is taken, on the clock
  -- after the frame's last record has been counted.
  corner_counter : entity work.fastnms_counter
    generic map (
      WIDTH   => 32,
      SEGMENT => 12
    )
    port map (
      clk   => clk,
      rst   => rst,
      clear => done_pulse,
      step  => rec_pulse,
      value => corners
    );

  frame_counter : entity work.fastnms_counter
    generic map (
      WIDTH   => 32,
      SEGMENT => 12
    )
    port map (
      clk   => clk,
      rst   => rst,
      clear => '0',
      step  => done_pulse,
      value => frames
    );

  -- ---- read values -----------------------------------------------------------

  words <=
  (
    REG_ID           => ID_MAGIC_RESET,
    REG_VERSION      => VERSION_WORD,
    REG_CTRL         => place(enable_r, CTRL_ENABLE) or place(soft_busy,
                                                               CTRL_SOFT_RESET) or
    place(irq_enable,
           CTRL_IRQ_ENABLE),
    REG_STATUS       => place(busy_r, STATUS_BUSY) or place(sticky,
                                                             STATUS_FRAME_DONE),
    REG_THRESHOLD    => std_logic_vector(resize(thr_shadow, REG_DATA_WIDTH)),
    REG_WIDTH        => std_logic_vector(resize(width_shadow, REG_DATA_WIDTH)),
    REG_HEIGHT       => std_logic_vector(resize(height_shadow, REG_DATA_WIDTH)),
    REG_MODE         => MODE_WORD,
    REG_CORNER_COUNT => std_logic_vector(corner_count),
    REG_FRAME_COUNT  => std_logic_vector(frames),
    REG_MAX_SIZE     => MAX_WORD,
    REG_BUILD        => BUILD_WORD
  );

end architecture rtl;
