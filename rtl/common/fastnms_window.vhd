-- Window generator: turns a raster stream of pixels into a stream of
-- WINDOW x WINDOW neighbourhoods, one output beat per pixel of the frame.
--
-- Output beat k of a frame is the window centred on pixel k (raster order),
-- with out_sof on pixel (0, 0) and out_eol on the last pixel of each row.
-- out_inside = '1' when the whole window lies in the frame (R <= x <= W-1-R,
-- R <= y <= H-1-R, R = WINDOW/2); out_window is meaningful only then.
-- The output runs R rows and R pixels behind the input (lockstep): the window
-- centred on pixel k leaves when pixel k + R*W + R has entered. The last
-- R*W + R beats of a frame are border beats that need no pixel: they leave
-- while the next frame's first pixels enter, or on their own when the input is
-- idle, so back-to-back frames of equal width run at one pixel per clock.
--
-- Geometry comes from cfg_width/cfg_height, sampled when the start-of-frame
-- pixel is accepted (they must be stable from the clock before). in_sof starts
-- a frame; in_eol is only checked. Malformed input never stalls the block:
--   err_line  pulses when in_eol is missing on the last pixel of a line or
--             present elsewhere (the frame keeps its configured geometry);
--   err_frame pulses on a start of frame before the previous frame ended (the
--             cut frame is completed with border beats), a pixel outside any
--             frame (dropped) or a start of frame with a size outside
--             WINDOW..MAX_WIDTH x WINDOW..MAX_HEIGHT (the frame is dropped).
--
-- Handshake: the whole pipeline advances when out_ready = '1' or no output is
-- held, so in_ready depends on out_ready through one gate. Put a skid buffer
-- behind this block if its consumer's ready is not a register.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_window is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    WINDOW       : positive := 7;
    DATA_WIDTH   : positive := 8;
    READ_LATENCY : positive := 1
  );
  port (
    clk        : in    std_logic;
    rst        : in    std_logic;
    cfg_width  : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    cfg_height : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    in_valid   : in    std_logic;
    in_ready   : out   std_logic;
    in_data    : in    std_logic_vector(DATA_WIDTH - 1 downto 0);
    in_sof     : in    std_logic;
    in_eol     : in    std_logic;
    out_valid  : out   std_logic;
    out_ready  : in    std_logic;
    out_window : out   std_logic_vector(WINDOW * WINDOW * DATA_WIDTH - 1 downto 0);
    out_inside : out   std_logic;
    out_sof    : out   std_logic;
    out_eol    : out   std_logic;
    err_line   : out   std_logic;
    err_frame  : out   std_logic
  );
end entity fastnms_window;

architecture rtl of fastnms_window is

  constant R : natural := WINDOW / 2;
  -- Token pipeline: the line buffer's read latency, then the window register.
  constant TOKEN_LAST : positive := READ_LATENCY + 1;

  subtype x_t is unsigned(clog2(MAX_WIDTH) - 1 downto 0);

  subtype y_t is unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);

  subtype pixel_t is std_logic_vector(DATA_WIDTH - 1 downto 0);

  type window_t is array (0 to WINDOW - 1, 0 to WINDOW - 1) of pixel_t;

  type out_state_t is (idle, lockstep, flush);

  -- One output beat in flight beside the window.
  type token_t is record
    valid  : std_logic;
    inside : std_logic;
    sof    : std_logic;
    eol    : std_logic;
  end record token_t;

  type token_pipe_t is array (1 to TOKEN_LAST) of token_t;

  -- Frame geometry, as limits that the counters compare against.
  type limits_t is record
    w_last : x_t; -- W - 1
    h_last : y_t; -- H - 1
    x_hi   : x_t; -- W - 1 - R: last inside column
    y_hi   : y_t; -- H - 1 - R: last inside row
  end record limits_t;

  signal cfg_ok     : std_logic;
  signal cfg_limits : limits_t;

  -- Input side: position of the next pixel of the frame being received.
  signal in_active : std_logic;
  signal in_x      : x_t;
  signal in_y      : y_t;
  signal in_limits : limits_t;
  -- The next pixel is (R, R): the one whose window is the frame's first.
  signal at_start : std_logic;

  -- Output side: position of the next beat of the frame being emitted.
  signal out_state  : out_state_t;
  signal out_x      : x_t;
  signal out_y      : y_t;
  signal out_x_in   : std_logic;
  signal out_y_in   : std_logic;
  signal out_limits : limits_t;

  signal advance   : std_logic;
  signal ready     : std_logic;
  signal accept    : std_logic;
  signal lb_valid  : std_logic;
  signal lb_col    : x_t;
  signal col_valid : std_logic;
  signal column    : std_logic_vector((WINDOW * DATA_WIDTH) - 1 downto 0);
  signal win_regs  : window_t;
  signal tokens    : token_pipe_t;

begin

  assert WINDOW mod 2 = 1 and WINDOW >= 3
    report "fastnms_window: WINDOW must be odd and at least 3"
    severity failure;
  assert MAX_WIDTH >= WINDOW and MAX_HEIGHT >= WINDOW
    report "fastnms_window: MAX_WIDTH and MAX_HEIGHT must be at least WINDOW"
    severity failure;

  advance <= out_ready or not tokens(TOKEN_LAST).valid;
  -- The pixel that starts a frame's output must wait until the previous
  -- frame's last border beats have left.
  ready  <= advance and not (at_start and not in_sof and to_sl(out_state /= idle));
  accept <= in_valid and ready;

  lb_valid <= accept and ((in_sof and cfg_ok) or (not in_sof and in_active));
  lb_col   <= (others => '0') when in_sof = '1' else
              in_x;

  config : process (clk) is
  begin

    if rising_edge(clk) then
      cfg_ok <= '0';
      if cfg_width >= WINDOW and cfg_width <= MAX_WIDTH and
         cfg_height >= WINDOW and cfg_height <= MAX_HEIGHT then
        cfg_ok <= '1';
      end if;
      cfg_limits.w_last <= resize(cfg_width - 1, x_t'length);
      cfg_limits.h_last <= resize(cfg_height - 1, y_t'length);
      cfg_limits.x_hi   <= resize(cfg_width - 1 - R, x_t'length);
      cfg_limits.y_hi   <= resize(cfg_height - 1 - R, y_t'length);
    end if;

  end process config;

  control : process (clk) is

    variable token  : token_t;
    variable last   : std_logic;
    variable x_last : boolean;

  begin

    if rising_edge(clk) then
      err_line  <= '0';
      err_frame <= '0';

      if advance = '1' then
        -- Input side --------------------------------------------------------
        last := '0';
        if accept = '1' then
          -- (R, R) follows (R - 1, R); registered so that in_ready stays shallow.
          at_start <= in_active and not in_sof and to_sl(in_x = R - 1 and in_y = R);
          if in_sof = '1' then
            err_frame <= in_active or not cfg_ok;
            err_line  <= in_eol;
            in_active <= cfg_ok;
            in_limits <= cfg_limits;
            in_x      <= to_unsigned(1, x_t'length);
            in_y      <= (others => '0');
          elsif in_active = '1' then
            x_last := in_x = in_limits.w_last;
            if x_last /= (in_eol = '1') then
              err_line <= '1';
            end if;
            if x_last then
              in_x <= (others => '0');
              in_y <= in_y + 1;
              if in_y = in_limits.h_last then
                in_active <= '0';
                last      := '1';
              end if;
            else
              in_x <= in_x + 1;
            end if;
          else
            err_frame <= '1';
          end if;
        end if;

        -- Output side -------------------------------------------------------
        token := (valid => '0', inside => '0', sof => '0', eol => '0');

        if out_state = idle then
          if accept = '1' and in_sof = '0' and at_start = '1' then
            token      := (valid => '1', inside => '0', sof => '1', eol => '0');
            out_state  <= lockstep;
            out_limits <= in_limits;
            out_x      <= to_unsigned(1, x_t'length);
            out_x_in   <= '1' when R = 1 else '0';
          end if;
        elsif out_state = flush or accept = '1' then
          token.valid  := '1';
          token.inside := out_x_in and out_y_in and not in_sof and
                          to_sl(out_state = lockstep);
          token.eol    := '1' when out_x = out_limits.w_last else '0';

          if token.eol = '1' then
            out_x    <= (others => '0');
            out_x_in <= '0';
            out_y    <= out_y + 1;
            out_y_in <= (out_y_in and not to_sl(out_y = out_limits.y_hi)) or
                        to_sl(out_y = R - 1);
            if out_y = out_limits.h_last then
              out_state <= idle;
              out_y     <= (others => '0');
              out_y_in  <= '0';
            end if;
          else
            out_x    <= out_x + 1;
            out_x_in <= (out_x_in and not to_sl(out_x = out_limits.x_hi)) or
                        to_sl(out_x = R - 1);
          end if;

          -- The frame's last pixel (or a cut) ends the lockstep part.
          if out_state = lockstep and (last = '1' or in_sof = '1') then
            out_state <= flush;
          end if;
        end if;

        tokens(1) <= token;
        for stage in 2 to TOKEN_LAST loop
          tokens(stage) <= tokens(stage - 1);
        end loop;

        -- Window: shift left by one column when a column arrives.
        if col_valid = '1' then
          for row in 0 to WINDOW - 1 loop
            for col in 0 to WINDOW - 2 loop
              win_regs(row, col) <= win_regs(row, col + 1);
            end loop;
            win_regs(row, WINDOW - 1) <= column((row + 1) * DATA_WIDTH - 1 downto row * DATA_WIDTH);
          end loop;
        end if;
      end if;

      if rst = '1' then
        in_active <= '0';
        at_start  <= '0';
        in_x      <= (others => '0');
        in_y      <= (others => '0');
        out_state <= idle;
        out_x     <= (others => '0');
        out_y     <= (others => '0');
        out_x_in  <= '0';
        out_y_in  <= '0';
        err_line  <= '0';
        err_frame <= '0';
        for stage in 1 to TOKEN_LAST loop
          tokens(stage).valid <= '0';
        end loop;
      end if;
    end if;

  end process control;

  lines : entity work.fastnms_line_buffer
    generic map (
      MAX_WIDTH    => MAX_WIDTH,
      LINES        => WINDOW - 1,
      DATA_WIDTH   => DATA_WIDTH,
      READ_LATENCY => READ_LATENCY
    )
    port map (
      clk        => clk,
      rst        => rst,
      en         => advance,
      in_valid   => lb_valid,
      in_col     => lb_col,
      in_data    => in_data,
      out_valid  => col_valid,
      out_column => column
    );

  -- Pixel (row r, column c) of the window is slice r * WINDOW + c.

  flatten : for index in 0 to WINDOW * WINDOW - 1 generate
    out_window((index + 1) * DATA_WIDTH - 1 downto index * DATA_WIDTH) <= win_regs(index / WINDOW, index mod WINDOW);
  end generate flatten;

  in_ready   <= ready;
  out_valid  <= tokens(TOKEN_LAST).valid;
  out_inside <= tokens(TOKEN_LAST).inside;
  out_sof    <= tokens(TOKEN_LAST).sof;
  out_eol    <= tokens(TOKEN_LAST).eol;

end architecture rtl;
