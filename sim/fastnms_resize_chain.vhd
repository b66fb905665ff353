-- Simulation only: LEVELS - 1 fastnms_resize in a chain (an image pyramid), each
-- level's sizes from flat vectors, each link's handshake and data shown on
-- flat ports to record (tb/resize/resize_chain_tb.py; the pyramid engine,
-- sim/pyramid.py).
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_resize_chain is
  generic (
    LEVELS     : positive := 8;
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 1080
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- Level k's width and height at bits 12k + 11 .. 12k (level 0: the input).
    cfg_widths  : in    std_logic_vector(12 * LEVELS - 1 downto 0);
    cfg_heights : in    std_logic_vector(12 * LEVELS - 1 downto 0);
    in_valid    : in    std_logic;
    in_ready    : out   std_logic;
    in_data     : in    std_logic_vector(7 downto 0);
    in_sof      : in    std_logic;
    in_eol      : in    std_logic;
    -- Link k (0: the input, 1 .. LEVELS - 1: level k's pixels), at bit k (data:
    -- bits 8k + 7 .. 8k).
    link_valid : out   std_logic_vector(LEVELS - 1 downto 0);
    link_ready : out   std_logic_vector(LEVELS - 1 downto 0);
    link_data  : out   std_logic_vector(8 * LEVELS - 1 downto 0);
    link_sof   : out   std_logic_vector(LEVELS - 1 downto 0);
    link_eol   : out   std_logic_vector(LEVELS - 1 downto 0);
    -- The last level's output is always taken; the error pulses of all.
    errors : out   std_logic_vector(3 * LEVELS - 1 downto 0)
  );
end entity fastnms_resize_chain;

architecture tb of fastnms_resize_chain is

  signal valid : std_logic_vector(LEVELS - 1 downto 0);
  -- ready(k): link k is taken (link 0: the input; the last: always).
  signal ready : std_logic_vector(LEVELS - 1 downto 0);
  signal data  : std_logic_vector(8 * LEVELS - 1 downto 0);
  signal sof   : std_logic_vector(LEVELS - 1 downto 0);
  signal eol   : std_logic_vector(LEVELS - 1 downto 0);

begin

  valid(0)           <= in_valid;
  in_ready           <= ready(0);
  data(7 downto 0)   <= in_data;
  sof(0)             <= in_sof;
  eol(0)             <= in_eol;
  ready(LEVELS - 1)  <= '1';
  errors(2 downto 0) <= (others => '0');

  steps : for k in 1 to LEVELS - 1 generate

    step : entity work.fastnms_resize
      generic map (
        MAX_WIDTH  => MAX_WIDTH,
        MAX_HEIGHT => MAX_HEIGHT
      )
      port map (
        clk            => clk,
        rst            => rst,
        cfg_src_width  => unsigned(cfg_widths(12 * k - 1 downto 12 * k - 12)),
        cfg_src_height => unsigned(cfg_heights(12 * k - 1 downto 12 * k - 12)),
        cfg_dst_width  => unsigned(cfg_widths(12 * k + 11 downto 12 * k)),
        cfg_dst_height => unsigned(cfg_heights(12 * k + 11 downto 12 * k)),
        in_valid       => valid(k - 1),
        in_ready       => ready(k - 1),
        in_data        => data(8 * k - 1 downto 8 * k - 8),
        in_sof         => sof(k - 1),
        in_eol         => eol(k - 1),
        out_valid      => valid(k),
        out_ready      => ready(k),
        out_data       => data(8 * k + 7 downto 8 * k),
        out_sof        => sof(k),
        out_eol        => eol(k),
        err_size       => errors(3 * k),
        err_frame      => errors(3 * k + 1),
        err_line       => errors(3 * k + 2)
      );

  end generate steps;

  link_valid <= valid;
  link_ready <= ready;
  link_data  <= data;
  link_sof   <= sof;
  link_eol   <= eol;

end architecture tb;
