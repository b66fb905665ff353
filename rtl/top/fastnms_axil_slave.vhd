-- AXI4-Lite slave, the protocol only: the five channels turned into one
-- register access at a time, addresses decoded in full.
-- Datasheet: docs/fastnms_axi.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_axil_slave is
  generic (
    ADDR_WIDTH : positive := 12;
    DATA_WIDTH : positive := 32;
    WORDS      : positive := 16
  );
  port (
    clk    : in    std_logic;
    rst    : in    std_logic;
    active : in    std_logic;
    -- AXI4-Lite
    s_axi_awaddr  : in    std_logic_vector(ADDR_WIDTH - 1 downto 0);
    s_axi_awvalid : in    std_logic;
    s_axi_awready : out   std_logic;
    s_axi_wdata   : in    std_logic_vector(DATA_WIDTH - 1 downto 0);
    s_axi_wstrb   : in    std_logic_vector(DATA_WIDTH / 8 - 1 downto 0);
    s_axi_wvalid  : in    std_logic;
    s_axi_wready  : out   std_logic;
    s_axi_bresp   : out   std_logic_vector(1 downto 0);
    s_axi_bvalid  : out   std_logic;
    s_axi_bready  : in    std_logic;
    s_axi_araddr  : in    std_logic_vector(ADDR_WIDTH - 1 downto 0);
    s_axi_arvalid : in    std_logic;
    s_axi_arready : out   std_logic;
    s_axi_rdata   : out   std_logic_vector(DATA_WIDTH - 1 downto 0);
    s_axi_rresp   : out   std_logic_vector(1 downto 0);
    s_axi_rvalid  : out   std_logic;
    s_axi_rready  : in    std_logic;
    -- register file
    wr_en    : out   std_logic;
    wr_index : out   unsigned(ADDR_WIDTH - 3 downto 0);
    wr_data  : out   std_logic_vector(DATA_WIDTH - 1 downto 0);
    wr_strb  : out   std_logic_vector(DATA_WIDTH / 8 - 1 downto 0);
    wr_done  : in    std_logic;
    rd_en    : out   std_logic;
    rd_index : out   unsigned(ADDR_WIDTH - 3 downto 0);
    rd_data  : in    std_logic_vector(DATA_WIDTH - 1 downto 0);
    rd_done  : in    std_logic
  );
end entity fastnms_axil_slave;

architecture rtl of fastnms_axil_slave is

  constant OKAY   : std_logic_vector(1 downto 0) := "00";
  constant SLVERR : std_logic_vector(1 downto 0) := "10";

  subtype index_t is unsigned(ADDR_WIDTH - 3 downto 0);

  -- Write: both halves in (full), the index decoded (checked), waiting for the
  -- register file (busy), the response out (b_valid).
  signal aw_full   : std_logic;
  signal w_full    : std_logic;
  signal w_checked : std_logic;
  signal w_mapped  : std_logic;
  signal w_busy    : std_logic;
  signal b_valid   : std_logic;
  signal b_resp    : std_logic_vector(1 downto 0);
  signal w_index   : index_t;
  signal aw_ready  : std_logic;
  signal w_ready   : std_logic;

  -- Read: the same steps.
  signal ar_full   : std_logic;
  signal r_checked : std_logic;
  signal r_mapped  : std_logic;
  signal r_busy    : std_logic;
  signal r_valid   : std_logic;
  signal r_resp    : std_logic_vector(1 downto 0);
  signal r_data    : std_logic_vector(DATA_WIDTH - 1 downto 0);
  signal r_index   : index_t;
  signal ar_ready  : std_logic;

begin

  assert DATA_WIDTH = 32 or DATA_WIDTH = 64
    report "fastnms_axil_slave: DATA_WIDTH must be 32 or 64 (AXI4-Lite)"
    severity failure;
  assert ADDR_WIDTH >= 3 and WORDS <= 2 ** (ADDR_WIDTH - 2)
    report "fastnms_axil_slave: WORDS must fit in the ADDR_WIDTH space"
    severity failure;

  aw_ready      <= not aw_full and active;
  w_ready       <= not w_full and active;
  ar_ready      <= not ar_full and active;
  s_axi_awready <= aw_ready;
  s_axi_wready  <= w_ready;
  s_axi_arready <= ar_ready;
  s_axi_bvalid  <= b_valid and active;
  s_axi_bresp   <= b_resp;
  s_axi_rvalid  <= r_valid and active;
  s_axi_rresp   <= r_resp;
  s_axi_rdata   <= r_data;

  wr_index <= w_index;
  rd_index <= r_index;

  write_channel : process (clk) is
  begin

    if rising_edge(clk) then
      wr_en <= '0';

      if s_axi_awvalid = '1' and aw_ready = '1' then
        aw_full <= '1';
        w_index <= unsigned(s_axi_awaddr(ADDR_WIDTH - 1 downto 2));
      end if;
      if s_axi_wvalid = '1' and w_ready = '1' then
        w_full  <= '1';
        wr_data <= s_axi_wdata;
        wr_strb <= s_axi_wstrb;
      end if;

      -- Both halves in: check the address, then write (mapped) or answer.
      w_mapped <= not at_least(w_index, WORDS);
      if aw_full = '1' and w_full = '1' and w_checked = '0' then
        w_checked <= '1';
      elsif w_checked = '1' and w_busy = '0' and b_valid = '0' then
        if w_mapped = '1' then
          wr_en  <= '1';
          w_busy <= '1';
        else
          b_valid <= '1';
          b_resp  <= SLVERR;
        end if;
      end if;
      if w_busy = '1' and wr_done = '1' then
        w_busy  <= '0';
        b_valid <= '1';
        b_resp  <= OKAY;
      end if;
      if b_valid = '1' and s_axi_bready = '1' and active = '1' then
        b_valid   <= '0';
        w_checked <= '0';
        aw_full   <= '0';
        w_full    <= '0';
      end if;

      if rst = '1' then
        aw_full   <= '0';
        w_full    <= '0';
        w_checked <= '0';
        w_busy    <= '0';
        b_valid   <= '0';
        wr_en     <= '0';
      end if;
    end if;

  end process write_channel;

  read_channel : process (clk) is
  begin

    if rising_edge(clk) then
      rd_en <= '0';

      if s_axi_arvalid = '1' and ar_ready = '1' then
        ar_full <= '1';
        r_index <= unsigned(s_axi_araddr(ADDR_WIDTH - 1 downto 2));
      end if;

      r_mapped <= not at_least(r_index, WORDS);
      if ar_full = '1' and r_checked = '0' then
        r_checked <= '1';
      elsif r_checked = '1' and r_busy = '0' and r_valid = '0' then
        if r_mapped = '1' then
          rd_en  <= '1';
          r_busy <= '1';
        else
          r_valid <= '1';
          r_resp  <= SLVERR;
          r_data  <= (others => '0');
        end if;
      end if;
      if r_busy = '1' and rd_done = '1' then
        r_busy  <= '0';
        r_valid <= '1';
        r_resp  <= OKAY;
        r_data  <= rd_data;
      end if;
      if r_valid = '1' and s_axi_rready = '1' and active = '1' then
        r_valid   <= '0';
        r_checked <= '0';
        ar_full   <= '0';
      end if;

      if rst = '1' then
        ar_full   <= '0';
        r_checked <= '0';
        r_busy    <= '0';
        r_valid   <= '0';
        rd_en     <= '0';
      end if;
    end if;

  end process read_channel;

end architecture rtl;
