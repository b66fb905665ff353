-- The gate between the video input and fastnms_core: at each start of frame,
-- process the frame or discard it (CTRL.ENABLE = 0, after a soft reset).
-- Datasheet: docs/fastnms_axi.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_video_gate is
  generic (
    DATA_WIDTH : positive := 8
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    soft      : in    std_logic;
    enable    : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_data   : in    std_logic_vector(DATA_WIDTH - 1 downto 0);
    in_sof    : in    std_logic;
    in_eol    : in    std_logic;
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(DATA_WIDTH - 1 downto 0);
    out_sof   : out   std_logic;
    out_eol   : out   std_logic
  );
end entity fastnms_video_gate;

architecture rtl of fastnms_video_gate is

  signal discard    : std_logic;
  signal open_gate  : std_logic; -- no soft reset in progress
  signal pass       : std_logic; -- the pixel goes to the core
  signal drop       : std_logic; -- the pixel is consumed and dropped
  signal skid_ready : std_logic;
  signal skid_rst   : std_logic;
  signal skid_out   : std_logic_vector(DATA_WIDTH + 1 downto 0);

begin

  open_gate <= not soft;
  pass      <= open_gate and ((not in_sof and not discard) or (in_sof and enable));
  drop      <= open_gate and ((not in_sof and discard) or (in_sof and not enable));
  in_ready  <= (pass and skid_ready) or drop;

  control : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' and in_sof = '1' and open_gate = '1' then
        if enable = '0' then
          discard <= '1';
        elsif skid_ready = '1' then
          discard <= '0';
        end if;
      end if;

      if soft = '1' then
        discard <= '1';
      end if;
      if rst = '1' then
        discard <= '0';
      end if;
    end if;

  end process control;

  skid_rst <= rst or soft;

  -- Ping-pong: the core's ready comes from its window's state, and must not
  -- enable the wide data registers.
  output_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH     => DATA_WIDTH + 2,
      PING_PONG => true
    )
    port map (
      clk       => clk,
      rst       => skid_rst,
      in_valid  => in_valid and pass,
      in_ready  => skid_ready,
      in_data   => in_sof & in_eol & in_data,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => skid_out
    );

  out_sof  <= skid_out(DATA_WIDTH + 1);
  out_eol  <= skid_out(DATA_WIDTH);
  out_data <= skid_out(DATA_WIDTH - 1 downto 0);

end architecture rtl;
