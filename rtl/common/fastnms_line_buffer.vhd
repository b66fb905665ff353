-- LINES previous image lines in one block RAM: for each pixel written at
-- in_col, the whole image column at in_col. A pipeline stage under the
-- shared advance enable `en`.
-- Datasheet: docs/fastnms_line_buffer.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_line_buffer is
  generic (
    MAX_WIDTH    : positive := 1920;
    LINES        : positive := 6;
    DATA_WIDTH   : positive := 8;
    READ_LATENCY : positive := 1
  );
  port (
    clk        : in    std_logic;
    rst        : in    std_logic;
    en         : in    std_logic;
    in_valid   : in    std_logic;
    in_col     : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    in_data    : in    std_logic_vector(DATA_WIDTH - 1 downto 0);
    out_valid  : out   std_logic;
    out_column : out   std_logic_vector((LINES + 1) * DATA_WIDTH - 1 downto 0)
  );
end entity fastnms_line_buffer;

architecture rtl of fastnms_line_buffer is

  type col_pipe_t is array (1 to READ_LATENCY) of unsigned(in_col'range);

  type data_pipe_t is array (1 to READ_LATENCY) of std_logic_vector(in_data'range);

  signal valid_pipe : std_logic_vector(1 to READ_LATENCY);
  signal col_pipe   : col_pipe_t;
  signal data_pipe  : data_pipe_t;
  signal rd_lines   : std_logic_vector(LINES * DATA_WIDTH - 1 downto 0);
  signal column     : std_logic_vector(out_column'range);
  signal wr_en      : std_logic;

begin

  assert MAX_WIDTH >= 2
    report "fastnms_line_buffer: MAX_WIDTH must be at least 2"
    severity failure;

  assert READ_LATENCY <= 2
    report "fastnms_line_buffer: READ_LATENCY must be 1 or 2"
    severity failure;

  -- The pixel and its column travel beside the RAM read.
  delay : process (clk) is
  begin

    if rising_edge(clk) then
      if en = '1' then
        valid_pipe(1) <= in_valid;
        col_pipe(1)   <= in_col;
        data_pipe(1)  <= in_data;

        for stage in 2 to READ_LATENCY loop
          valid_pipe(stage) <= valid_pipe(stage - 1);
          col_pipe(stage)   <= col_pipe(stage - 1);
          data_pipe(stage)  <= data_pipe(stage - 1);
        end loop;

      end if;

      if rst = '1' then
        valid_pipe <= (others => '0');
      end if;
    end if;

  end process delay;

  column <= data_pipe(READ_LATENCY) & rd_lines;

  -- Write the column back without its oldest pixel: the lines move up by one.
  wr_en <= en and valid_pipe(READ_LATENCY);

  lines_ram : entity work.fastnms_ram_sdp
    generic map (
      DEPTH        => MAX_WIDTH,
      WIDTH        => LINES * DATA_WIDTH,
      READ_LATENCY => READ_LATENCY,
      STYLE        => "block"
    )
    port map (
      clk     => clk,
      wr_en   => wr_en,
      wr_addr => col_pipe(READ_LATENCY),
      wr_data => column(column'high downto DATA_WIDTH),
      rd_en   => en,
      rd_addr => in_col,
      rd_data => rd_lines
    );

  out_valid  <= valid_pipe(READ_LATENCY);
  out_column <= column;

end architecture rtl;
