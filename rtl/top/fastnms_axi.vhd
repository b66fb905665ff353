-- The drop-in top level: AXI4-Stream video in, corner records out, optional
-- per-pixel score video out, AXI4-Lite control, interrupt; fastnms_core
-- inside.
-- Datasheet: docs/fastnms_axi.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_fast_pkg.all;
  use work.fastnms_regs_pkg.all;

entity fastnms_axi is
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
    ORB_MAX_CELL      : positive := 16;
    -- Tests only (fastnms_core's TEST_FAULT): "none" in a product.
    TEST_FAULT : string := "none"
  );
  port (
    aclk    : in    std_logic;
    aresetn : in    std_logic;
    -- video in (AXI4-Stream video, UG934: tuser = start of frame, tlast = end of line)
    s_axis_video_tdata  : in    std_logic_vector(PPC * 8 - 1 downto 0);
    s_axis_video_tuser  : in    std_logic;
    s_axis_video_tlast  : in    std_logic;
    s_axis_video_tvalid : in    std_logic;
    s_axis_video_tready : out   std_logic;
    -- corner records (tlast on the last record of each frame; tkeep all ones)
    m_axis_corners_tdata  : out   std_logic_vector(63 downto 0);
    m_axis_corners_tkeep  : out   std_logic_vector(7 downto 0);
    m_axis_corners_tlast  : out   std_logic;
    m_axis_corners_tvalid : out   std_logic;
    m_axis_corners_tready : in    std_logic;
    -- per-pixel score video (SCORE_VIDEO only)
    m_axis_score_tdata  : out   std_logic_vector(PPC * 8 - 1 downto 0);
    m_axis_score_tuser  : out   std_logic;
    m_axis_score_tlast  : out   std_logic;
    m_axis_score_tvalid : out   std_logic;
    m_axis_score_tready : in    std_logic;
    -- control (AXI4-Lite)
    s_axi_ctrl_awaddr  : in    std_logic_vector(11 downto 0);
    s_axi_ctrl_awprot  : in    std_logic_vector(2 downto 0);
    s_axi_ctrl_awvalid : in    std_logic;
    s_axi_ctrl_awready : out   std_logic;
    s_axi_ctrl_wdata   : in    std_logic_vector(31 downto 0);
    s_axi_ctrl_wstrb   : in    std_logic_vector(3 downto 0);
    s_axi_ctrl_wvalid  : in    std_logic;
    s_axi_ctrl_wready  : out   std_logic;
    s_axi_ctrl_bresp   : out   std_logic_vector(1 downto 0);
    s_axi_ctrl_bvalid  : out   std_logic;
    s_axi_ctrl_bready  : in    std_logic;
    s_axi_ctrl_araddr  : in    std_logic_vector(11 downto 0);
    s_axi_ctrl_arprot  : in    std_logic_vector(2 downto 0);
    s_axi_ctrl_arvalid : in    std_logic;
    s_axi_ctrl_arready : out   std_logic;
    s_axi_ctrl_rdata   : out   std_logic_vector(31 downto 0);
    s_axi_ctrl_rresp   : out   std_logic_vector(1 downto 0);
    s_axi_ctrl_rvalid  : out   std_logic;
    s_axi_ctrl_rready  : in    std_logic;
    interrupt          : out   std_logic
  );

  attribute x_interface_info      : string;
  attribute x_interface_parameter : string;

  attribute x_interface_info of aclk : signal is
    "xilinx.com:signal:clock:1.0 aclk CLK";
  attribute x_interface_parameter of aclk : signal is
    "XIL_INTERFACENAME aclk, ASSOCIATED_BUSIF s_axis_video:m_axis_corners:m_axis_score:s_axi_ctrl, " &
    "ASSOCIATED_RESET aresetn";
  attribute x_interface_info of aresetn : signal is
    "xilinx.com:signal:reset:1.0 aresetn RST";
  attribute x_interface_parameter of aresetn : signal is
    "XIL_INTERFACENAME aresetn, POLARITY ACTIVE_LOW";
  attribute x_interface_info of interrupt : signal is
    "xilinx.com:signal:interrupt:1.0 interrupt INTERRUPT";
  attribute x_interface_parameter of interrupt : signal is
    "XIL_INTERFACENAME interrupt, SENSITIVITY LEVEL_HIGH";

  attribute x_interface_info of s_axis_video_tdata : signal is
    "xilinx.com:interface:axis:1.0 s_axis_video TDATA";
  attribute x_interface_info of s_axis_video_tuser : signal is
    "xilinx.com:interface:axis:1.0 s_axis_video TUSER";
  attribute x_interface_info of s_axis_video_tlast : signal is
    "xilinx.com:interface:axis:1.0 s_axis_video TLAST";
  attribute x_interface_info of s_axis_video_tvalid : signal is
    "xilinx.com:interface:axis:1.0 s_axis_video TVALID";
  attribute x_interface_info of s_axis_video_tready : signal is
    "xilinx.com:interface:axis:1.0 s_axis_video TREADY";
  attribute x_interface_parameter of s_axis_video_tdata : signal is
    "XIL_INTERFACENAME s_axis_video, TDATA_NUM_BYTES " & integer'image(PPC) & ", TUSER_WIDTH 1, HAS_TLAST 1, HAS_TREADY 1, " &
    "HAS_TKEEP 0, HAS_TSTRB 0, TDEST_WIDTH 0, TID_WIDTH 0";

  attribute x_interface_info of m_axis_corners_tdata : signal is
    "xilinx.com:interface:axis:1.0 m_axis_corners TDATA";
  attribute x_interface_info of m_axis_corners_tkeep : signal is
    "xilinx.com:interface:axis:1.0 m_axis_corners TKEEP";
  attribute x_interface_info of m_axis_corners_tlast : signal is
    "xilinx.com:interface:axis:1.0 m_axis_corners TLAST";
  attribute x_interface_info of m_axis_corners_tvalid : signal is
    "xilinx.com:interface:axis:1.0 m_axis_corners TVALID";
  attribute x_interface_info of m_axis_corners_tready : signal is
    "xilinx.com:interface:axis:1.0 m_axis_corners TREADY";
  attribute x_interface_parameter of m_axis_corners_tdata : signal is
    "XIL_INTERFACENAME m_axis_corners, TDATA_NUM_BYTES 8, TUSER_WIDTH 0, HAS_TLAST 1, HAS_TREADY 1, " &
    "HAS_TKEEP 1, HAS_TSTRB 0, TDEST_WIDTH 0, TID_WIDTH 0";

  attribute x_interface_info of m_axis_score_tdata : signal is
    "xilinx.com:interface:axis:1.0 m_axis_score TDATA";
  attribute x_interface_info of m_axis_score_tuser : signal is
    "xilinx.com:interface:axis:1.0 m_axis_score TUSER";
  attribute x_interface_info of m_axis_score_tlast : signal is
    "xilinx.com:interface:axis:1.0 m_axis_score TLAST";
  attribute x_interface_info of m_axis_score_tvalid : signal is
    "xilinx.com:interface:axis:1.0 m_axis_score TVALID";
  attribute x_interface_info of m_axis_score_tready : signal is
    "xilinx.com:interface:axis:1.0 m_axis_score TREADY";
  attribute x_interface_parameter of m_axis_score_tdata : signal is
    "XIL_INTERFACENAME m_axis_score, TDATA_NUM_BYTES " & integer'image(PPC) & ", TUSER_WIDTH 1, HAS_TLAST 1, HAS_TREADY 1, " &
    "HAS_TKEEP 0, HAS_TSTRB 0, TDEST_WIDTH 0, TID_WIDTH 0";

  attribute x_interface_info of s_axi_ctrl_awaddr : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl AWADDR";
  attribute x_interface_info of s_axi_ctrl_awprot : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl AWPROT";
  attribute x_interface_info of s_axi_ctrl_awvalid : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl AWVALID";
  attribute x_interface_info of s_axi_ctrl_awready : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl AWREADY";
  attribute x_interface_info of s_axi_ctrl_wdata : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl WDATA";
  attribute x_interface_info of s_axi_ctrl_wstrb : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl WSTRB";
  attribute x_interface_info of s_axi_ctrl_wvalid : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl WVALID";
  attribute x_interface_info of s_axi_ctrl_wready : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl WREADY";
  attribute x_interface_info of s_axi_ctrl_bresp : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl BRESP";
  attribute x_interface_info of s_axi_ctrl_bvalid : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl BVALID";
  attribute x_interface_info of s_axi_ctrl_bready : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl BREADY";
  attribute x_interface_info of s_axi_ctrl_araddr : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl ARADDR";
  attribute x_interface_info of s_axi_ctrl_arprot : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl ARPROT";
  attribute x_interface_info of s_axi_ctrl_arvalid : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl ARVALID";
  attribute x_interface_info of s_axi_ctrl_arready : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl ARREADY";
  attribute x_interface_info of s_axi_ctrl_rdata : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl RDATA";
  attribute x_interface_info of s_axi_ctrl_rresp : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl RRESP";
  attribute x_interface_info of s_axi_ctrl_rvalid : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl RVALID";
  attribute x_interface_info of s_axi_ctrl_rready : signal is
    "xilinx.com:interface:aximm:1.0 s_axi_ctrl RREADY";
  attribute x_interface_parameter of s_axi_ctrl_awaddr : signal is
    "XIL_INTERFACENAME s_axi_ctrl, PROTOCOL AXI4LITE, DATA_WIDTH 32, ADDR_WIDTH 12, READ_WRITE_MODE READ_WRITE, " &
    "HAS_BURST 0, HAS_LOCK 0, HAS_PROT 1, HAS_CACHE 0, HAS_QOS 0, HAS_REGION 0, HAS_WSTRB 1, HAS_BRESP 1, " &
    "HAS_RRESP 1, NUM_READ_OUTSTANDING 1, NUM_WRITE_OUTSTANDING 1";
end entity fastnms_axi;

architecture rtl of fastnms_axi is

  constant X_BITS     : positive := clog2(MAX_WIDTH);
  constant Y_BITS     : positive := bits_for(MAX_HEIGHT);
  constant SCORE_BITS : positive := score_width(SCORE);

  -- Reset: the synchroniser chain, then the pipeline's reset (also held
  -- during a soft reset).
  signal reset_chain : std_logic_vector(2 downto 0);
  signal rst         : std_logic;
  signal ports_on    : std_logic; -- '0': every VALID and READY of the top is low
  signal soft_busy   : std_logic;
  signal soft_pulse  : std_logic;
  signal pipe_rst    : std_logic;

  attribute async_reg                : string;
  attribute async_reg of reset_chain : signal is "TRUE";

  -- Register accesses (slave to register file).
  signal wr_en    : std_logic;
  signal wr_index : unsigned(REG_ADDR_WIDTH - 3 downto 0);
  signal wr_data  : std_logic_vector(REG_DATA_WIDTH - 1 downto 0);
  signal wr_strb  : std_logic_vector(REG_DATA_WIDTH / 8 - 1 downto 0);
  signal wr_done  : std_logic;
  signal rd_en    : std_logic;
  signal rd_index : unsigned(REG_ADDR_WIDTH - 3 downto 0);
  signal rd_data  : std_logic_vector(REG_DATA_WIDTH - 1 downto 0);
  signal rd_done  : std_logic;
  signal irq      : std_logic;

  -- Configuration.
  signal enable        : std_logic;
  signal live          : std_logic;
  signal cfg_apply     : std_logic;
  signal cfg_width     : unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
  signal cfg_height    : unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
  signal cfg_threshold : unsigned(7 downto 0);
  signal cfg_cell_log  : unsigned(2 downto 0);
  signal cfg_per_cell  : unsigned(3 downto 0);
  signal cfg_min_area  : unsigned(MIN_AREA_VALUE_WIDTH - 1 downto 0);

  -- Video in: the input skid buffer, then the gate.
  signal v_in       : std_logic_vector(PPC * 8 + 1 downto 0);
  signal v_out      : std_logic_vector(PPC * 8 + 1 downto 0);
  signal v_valid    : std_logic;
  signal v_in_ready : std_logic;
  signal v_tready   : std_logic;
  signal v_tvalid   : std_logic;
  signal v_ready    : std_logic;
  signal g_valid    : std_logic; -- out of the gate
  signal g_ready    : std_logic;
  signal g_data     : std_logic_vector(PPC * 8 - 1 downto 0);
  signal g_sof      : std_logic;
  signal g_eol      : std_logic;
  signal c_beat     : std_logic_vector(PPC * 8 + 1 downto 0);
  signal c_valid    : std_logic; -- into the core
  signal c_ready    : std_logic;
  signal c_data     : std_logic_vector(PPC * 8 - 1 downto 0);
  signal c_sof      : std_logic;
  signal c_eol      : std_logic;

  -- Core output.
  signal k_valid  : std_logic;
  signal k_ready  : std_logic;
  signal k_x      : unsigned(X_BITS - 1 downto 0);
  signal k_y      : unsigned(Y_BITS - 1 downto 0);
  signal k_score  : unsigned(SCORE_BITS - 1 downto 0);
  signal k_area   : unsigned(REC_AREA_WIDTH - 1 downto 0);
  signal k_eof    : std_logic;
  signal k_angle  : std_logic_vector(31 downto 0);
  signal k_desc   : std_logic_vector(255 downto 0);
  signal orb_drop : std_logic; -- the core dropped a keypoint (ORB, K = 0)
  signal internal : std_logic_vector(INTERNAL_ERRORS - 1 downto 0);
  signal faulted  : std_logic; -- an internal error (registered): reset the pipeline

  -- Records.
  signal open_frame : std_logic;
  signal r_busy     : std_logic;
  signal r_valid    : std_logic;
  signal r_overflow : std_logic;

  -- Score tap.
  signal t_valid : std_logic;
  signal t_ready : std_logic;
  signal t_score : unsigned(PPC * SCORE_BITS - 1 downto 0);
  signal t_sof   : std_logic;
  signal t_eol   : std_logic;

  -- Status.
  signal in_frame        : std_logic;
  signal busy            : std_logic;
  signal err_eol_early   : std_logic;
  signal err_eol_late    : std_logic;
  signal err_sof_missing : std_logic;
  signal err_sof_early   : std_logic;
  signal dropped         : std_logic;
  signal stalled         : std_logic;
  signal out_record      : std_logic;
  signal out_last        : std_logic;

begin

  assert SCORE = "opencv" or SCORE = "sad"
    report "fastnms_axi: SCORE must be ""opencv"" or ""sad"""
    severity failure;
  assert MAX_WIDTH >= 7 and MAX_WIDTH < 2 ** 16 and MAX_HEIGHT >= 7 and MAX_HEIGHT < 2 ** 16
    report "fastnms_axi: MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"
    severity failure;
  -- (At least 8: with fewer RAM words the FIFO never has a spare word, and
  -- CTRL.LIVE would drop every record but the frames' last ones.)
  assert CORNER_FIFO_DEPTH >= 8 and CORNER_FIFO_DEPTH < 2 ** 16
    report "fastnms_axi: CORNER_FIFO_DEPTH must be in 8 .. 65535"
    severity failure;

  assert NMS = "3x3" or NMS = "none" or NMS = "region4" or NMS = "region8"
    report "fastnms_axi: NMS must be ""3x3"", ""region4"", ""region8"" or ""none"""
    severity failure;
  assert (PPC = 1 or PPC = 2 or PPC = 4) and MAX_WIDTH mod PPC = 0
    report "fastnms_axi: PPC must be 1, 2 or 4, and MAX_WIDTH a multiple of it"
    severity failure;
  assert PPC = 1 or NMS = "3x3" or NMS = "none"
    report "fastnms_axi: only NMS ""3x3"" and ""none"" take 2 or 4 pixels per clock (PPC); the region NMS needs PPC 1"
    severity failure;
  assert DESCRIPTOR = "none" or
         (DESCRIPTOR = "orb" and PPC = 1 and (NMS = "3x3" or NMS = "none") and MAX_PER_CELL > 0)
    report "fastnms_axi: DESCRIPTOR must be ""none"" or ""orb""; ""orb"" needs PPC 1, NMS ""3x3"" or ""none"" and MAX_PER_CELL > 0"
    severity failure;
  -- (A larger K would hold the input at any CELL: BUDGET.PER_CELL is clamped
  -- to the rate at the frame's CELL.)
  assert DESCRIPTOR /= "orb" or MAX_PER_CELL <= orb_rate_per_cell(clog2(maximum(ORB_MAX_CELL, 16)) - 4)
    report "fastnms_axi: with DESCRIPTOR ""orb"", MAX_PER_CELL must be at most ORB_MAX_CELL ** 2 / 64 (4 at ORB_MAX_CELL 16): the ORB engine's rate"
    severity failure;

  -- ---- reset ---------------------------------------------------------------

  reset_sync : process (aclk) is
  begin

    if rising_edge(aclk) then
      reset_chain <= reset_chain(reset_chain'high - 1 downto 0) & not aresetn;
    end if;

  end process reset_sync;

  rst <= reset_chain(reset_chain'high);

  -- Low from the edge that samples aresetn low until the clock after rst.
  port_mask : process (aclk) is
  begin

    if rising_edge(aclk) then
      ports_on <= aresetn and not (or reset_chain);
    end if;

  end process port_mask;

  -- A soft reset holds the pipeline in reset until the record packer has
  -- closed the frame it had open (at least one clock). An internal error
  -- resets it the same way: the core recovers at the next start of frame.
  soft_reset : process (aclk) is
  begin

    if rising_edge(aclk) then
      faulted <= (or internal) and not pipe_rst;
      if soft_pulse = '1' or faulted = '1' then
        soft_busy <= '1';
      elsif open_frame = '0' then
        soft_busy <= '0';
      end if;

      if rst = '1' then
        soft_busy <= '0';
        faulted   <= '0';
      end if;
    end if;

  end process soft_reset;

  pipe_rst <= rst or soft_busy;

  -- ---- registers -------------------------------------------------------------

  -- The AWPROT/ARPROT ports are not used (no protected registers).
  slave : entity work.fastnms_axil_slave
    generic map (
      ADDR_WIDTH => REG_ADDR_WIDTH,
      DATA_WIDTH => REG_DATA_WIDTH,
      WORDS      => REG_COUNT
    )
    port map (
      clk           => aclk,
      rst           => rst,
      active        => ports_on,
      s_axi_awaddr  => s_axi_ctrl_awaddr,
      s_axi_awvalid => s_axi_ctrl_awvalid,
      s_axi_awready => s_axi_ctrl_awready,
      s_axi_wdata   => s_axi_ctrl_wdata,
      s_axi_wstrb   => s_axi_ctrl_wstrb,
      s_axi_wvalid  => s_axi_ctrl_wvalid,
      s_axi_wready  => s_axi_ctrl_wready,
      s_axi_bresp   => s_axi_ctrl_bresp,
      s_axi_bvalid  => s_axi_ctrl_bvalid,
      s_axi_bready  => s_axi_ctrl_bready,
      s_axi_araddr  => s_axi_ctrl_araddr,
      s_axi_arvalid => s_axi_ctrl_arvalid,
      s_axi_arready => s_axi_ctrl_arready,
      s_axi_rdata   => s_axi_ctrl_rdata,
      s_axi_rresp   => s_axi_ctrl_rresp,
      s_axi_rvalid  => s_axi_ctrl_rvalid,
      s_axi_rready  => s_axi_ctrl_rready,
      wr_en         => wr_en,
      wr_index      => wr_index,
      wr_data       => wr_data,
      wr_strb       => wr_strb,
      wr_done       => wr_done,
      rd_en         => rd_en,
      rd_index      => rd_index,
      rd_data       => rd_data,
      rd_done       => rd_done
    );

  regs : entity work.fastnms_axi_regs
    generic map (
      MAX_WIDTH         => MAX_WIDTH,
      MAX_HEIGHT        => MAX_HEIGHT,
      SCORE             => SCORE,
      NMS               => NMS,
      SCORE_VIDEO       => SCORE_VIDEO,
      CORNER_FIFO_DEPTH => CORNER_FIFO_DEPTH,
      PPC               => PPC,
      MAX_PER_CELL      => MAX_PER_CELL,
      DESCRIPTOR        => DESCRIPTOR,
      ORB_MAX_CELL      => ORB_MAX_CELL
    )
    port map (
      clk             => aclk,
      rst             => rst,
      wr_en           => wr_en,
      wr_index        => wr_index,
      wr_data         => wr_data,
      wr_strb         => wr_strb,
      wr_done         => wr_done,
      rd_en           => rd_en,
      rd_index        => rd_index,
      rd_data         => rd_data,
      rd_done         => rd_done,
      enable          => enable,
      live            => live,
      soft_reset      => soft_pulse,
      soft_busy       => soft_busy,
      cfg_apply       => cfg_apply,
      cfg_width       => cfg_width,
      cfg_height      => cfg_height,
      cfg_threshold   => cfg_threshold,
      cfg_cell_log    => cfg_cell_log,
      cfg_per_cell    => cfg_per_cell,
      cfg_min_area    => cfg_min_area,
      busy            => busy,
      evt_eol_early   => err_eol_early,
      evt_eol_late    => err_eol_late,
      evt_sof_missing => err_sof_missing,
      evt_sof_early   => err_sof_early,
      evt_overflow    => r_overflow,
      evt_dropped     => dropped,
      evt_stall       => stalled,
      evt_internal    => internal,
      out_record      => out_record,
      out_last        => out_last,
      interrupt       => irq
    );

  interrupt <= irq and ports_on;

  -- ---- video in ----------------------------------------------------------------

  v_in <= s_axis_video_tuser & s_axis_video_tlast & s_axis_video_tdata;
  -- No tready during reset: a pixel taken then would be lost.
  v_tvalid            <= s_axis_video_tvalid and ports_on;
  v_tready            <= v_in_ready and ports_on;
  s_axis_video_tready <= v_tready;
  -- A frame's configuration: the registers' values when its first pixel is
  -- accepted here. That pixel reaches the core three clocks later at the
  -- earliest (three buffers), as the core asks (its window generator
  -- derives the frame's limits from the configuration in two register
  -- steps); the frame before has taken its own values with its first pixel.
  cfg_apply <= v_tvalid and v_tready and s_axis_video_tuser;

  -- Ping-pong: the gate decides from the buffered beat's start-of-frame bit,
  -- and its ready must not enable the wide data registers (with 4 pixels per
  -- clock that loop spread across the device and set the clock).
  input_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH     => PPC * 8 + 2,
      PING_PONG => true
    )
    port map (
      clk       => aclk,
      rst       => rst,
      in_valid  => v_tvalid,
      in_ready  => v_in_ready,
      in_data   => v_in,
      out_valid => v_valid,
      out_ready => v_ready,
      out_data  => v_out
    );

  gate : entity work.fastnms_video_gate
    generic map (
      DATA_WIDTH => PPC * 8
    )
    port map (
      clk       => aclk,
      rst       => rst,
      soft      => soft_busy,
      enable    => enable,
      in_valid  => v_valid,
      in_ready  => v_ready,
      in_data   => v_out(PPC * 8 - 1 downto 0),
      in_sof    => v_out(PPC * 8 + 1),
      in_eol    => v_out(PPC * 8),
      out_valid => g_valid,
      out_ready => g_ready,
      out_data  => g_data,
      out_sof   => g_sof,
      out_eol   => g_eol
    );

  -- The clock the configuration needs (above), without holding the input;
  -- after the gate, whose output buffer's ready is a register, so that no
  -- ready passes through two buffers in one clock. Cleared by a soft reset
  -- like the gate's output.
  config_delay : entity work.fastnms_skid_buffer
    generic map (
      WIDTH     => PPC * 8 + 2,
      PING_PONG => true
    )
    port map (
      clk       => aclk,
      rst       => pipe_rst,
      in_valid  => g_valid,
      in_ready  => g_ready,
      in_data   => g_sof & g_eol & g_data,
      out_valid => c_valid,
      out_ready => c_ready,
      out_data  => c_beat
    );

  c_sof  <= c_beat(PPC * 8 + 1);
  c_eol  <= c_beat(PPC * 8);
  c_data <= c_beat(PPC * 8 - 1 downto 0);

  check : entity work.fastnms_video_check
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT,
      PPC        => PPC
    )
    port map (
      clk             => aclk,
      rst             => pipe_rst,
      cfg_width       => cfg_width,
      cfg_height      => cfg_height,
      pixel           => c_valid and c_ready,
      pixel_sof       => c_sof,
      pixel_eol       => c_eol,
      err_eol_early   => err_eol_early,
      err_eol_late    => err_eol_late,
      err_sof_missing => err_sof_missing,
      err_sof_early   => err_sof_early,
      in_frame        => in_frame
    );

  -- ---- the core ------------------------------------------------------------------

  core : entity work.fastnms_core
    generic map (
      MAX_WIDTH    => MAX_WIDTH,
      MAX_HEIGHT   => MAX_HEIGHT,
      SCORE        => SCORE,
      NMS          => NMS,
      READ_LATENCY => 1,
      SCORE_TAP    => SCORE_VIDEO,
      PPC          => PPC,
      MAX_PER_CELL => MAX_PER_CELL,
      DESCRIPTOR   => DESCRIPTOR,
      ORB_MAX_CELL => ORB_MAX_CELL,
      TEST_FAULT   => TEST_FAULT
    )
    port map (
      clk            => aclk,
      rst            => pipe_rst,
      cfg_width      => cfg_width,
      cfg_height     => cfg_height,
      cfg_threshold  => cfg_threshold,
      cfg_cell_log   => cfg_cell_log,
      cfg_per_cell   => cfg_per_cell,
      cfg_min_area   => cfg_min_area,
      in_valid       => c_valid,
      in_ready       => c_ready,
      in_data        => c_data,
      in_sof         => c_sof,
      in_eol         => c_eol,
      out_valid      => k_valid,
      out_ready      => k_ready,
      out_x          => k_x,
      out_y          => k_y,
      out_score      => k_score,
      out_area       => k_area,
      out_eof        => k_eof,
      out_angle      => k_angle,
      out_descriptor => k_desc,
      orb_dropped    => orb_drop,
      tap_valid      => t_valid,
      tap_ready      => t_ready,
      tap_score      => t_score,
      tap_sof        => t_sof,
      tap_eol        => t_eol,
      err_line       => open,
      err_frame      => open,
      internal_error => internal
    );

  -- ---- corner records ----------------------------------------------------------

  records : entity work.fastnms_record_output
    generic map (
      X_BITS     => X_BITS,
      Y_BITS     => Y_BITS,
      SCORE_BITS => SCORE_BITS,
      FIFO_DEPTH => CORNER_FIFO_DEPTH,
      DESCRIPTOR => DESCRIPTOR,
      AREA       => NMS = "region4" or NMS = "region8"
    )
    port map (
      clk           => aclk,
      rst           => rst,
      pipe_rst      => pipe_rst,
      abort         => soft_busy,
      live          => live,
      in_valid      => k_valid,
      in_ready      => k_ready,
      in_x          => k_x,
      in_y          => k_y,
      in_score      => k_score,
      in_area       => k_area,
      in_eof        => k_eof,
      in_angle      => k_angle,
      in_descriptor => k_desc,
      in_dropped    => orb_drop,
      in_error      => faulted,
      out_valid     => r_valid,
      out_ready     => m_axis_corners_tready and ports_on,
      out_data      => m_axis_corners_tdata,
      out_last      => m_axis_corners_tlast,
      open_frame    => open_frame,
      busy          => r_busy,
      overflow      => r_overflow,
      dropped       => dropped,
      sent_record   => out_record,
      sent_last     => out_last
    );

  m_axis_corners_tkeep  <= (others => '1');
  m_axis_corners_tvalid <= r_valid and ports_on;

  -- ---- status ----------------------------------------------------------------------

  status : process (aclk) is
  begin

    if rising_edge(aclk) then
      busy    <= in_frame or r_busy;
      stalled <= s_axis_video_tvalid and not v_tready and ports_on;
    end if;

  end process status;

  -- ---- score video -------------------------------------------------------------------

  score_stream : if SCORE_VIDEO generate
    signal t_in        : std_logic_vector(PPC * 8 + 1 downto 0);
    signal t_out       : std_logic_vector(PPC * 8 + 1 downto 0);
    signal t_sat       : std_logic_vector(PPC * 8 - 1 downto 0);
    signal t_out_valid : std_logic;
    signal t_out_ready : std_logic;
  begin

    -- Each pixel's score as 8 bits, saturated (the sad score has 12).

    saturate : for lane in 0 to PPC - 1 generate
      constant LSB : natural := lane * SCORE_BITS;
    begin
      t_sat(lane * 8 + 7 downto lane * 8) <=
                                             (others => '1') when resize(t_score(LSB + SCORE_BITS - 1 downto LSB), 8) /=
                                                                  t_score(LSB + SCORE_BITS - 1 downto LSB) else
                                             std_logic_vector(resize(t_score(LSB + SCORE_BITS - 1 downto LSB), 8));
    end generate saturate;

    t_in <= t_sof & t_eol & t_sat;

    score_buffer : entity work.fastnms_skid_buffer
      generic map (
        WIDTH => PPC * 8 + 2
      )
      port map (
        clk       => aclk,
        rst       => rst,
        in_valid  => t_valid,
        in_ready  => t_ready,
        in_data   => t_in,
        out_valid => t_out_valid,
        out_ready => t_out_ready,
        out_data  => t_out
      );

    t_out_ready         <= m_axis_score_tready and ports_on;
    m_axis_score_tvalid <= t_out_valid and ports_on;
    m_axis_score_tuser  <= t_out(PPC * 8 + 1);
    m_axis_score_tlast  <= t_out(PPC * 8);
    m_axis_score_tdata  <= t_out(PPC * 8 - 1 downto 0);

  end generate score_stream;

  no_score_stream : if not SCORE_VIDEO generate
    t_ready             <= '1';
    m_axis_score_tvalid <= '0';
    m_axis_score_tuser  <= '0';
    m_axis_score_tlast  <= '0';
    m_axis_score_tdata  <= (others => '0');
  end generate no_score_stream;

end architecture rtl;
