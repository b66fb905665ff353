-- Input checker: classifies the malformed video that enters fastnms_core
-- against the frame size in use (the STATUS error bits); it only observes.
-- Datasheet: docs/fastnms_axi.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_video_check is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 1080;
    PPC        : positive := 1
  );
  port (
    clk             : in    std_logic;
    rst             : in    std_logic;
    cfg_width       : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    cfg_height      : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    pixel           : in    std_logic; -- a pixel enters the core on this clock
    pixel_sof       : in    std_logic;
    pixel_eol       : in    std_logic;
    err_eol_early   : out   std_logic;
    err_eol_late    : out   std_logic;
    err_sof_missing : out   std_logic;
    err_sof_early   : out   std_logic;
    in_frame        : out   std_logic
  );
end entity fastnms_video_check;

architecture rtl of fastnms_video_check is

  subtype x_t is unsigned(cfg_width'range);

  subtype y_t is unsigned(cfg_height'range);

  -- The observed pixel, one clock later.
  signal p_valid : std_logic;
  signal p_sof   : std_logic;
  signal p_eol   : std_logic;

  -- Size minus 2, registered from the configuration, and the copies taken
  -- with the start of frame.
  signal cfg_w_m2 : x_t;
  signal cfg_h_m2 : y_t;
  signal w_m2     : x_t;
  signal h_m2     : y_t;

  signal active  : std_logic; -- inside a frame
  signal x       : x_t;       -- index in its line of the observed pixel
  signal y       : y_t;       -- index of its line
  signal x_last  : std_logic; -- the observed pixel should end its line
  signal late    : std_logic; -- this line is already longer than WIDTH
  signal y_last  : std_logic; -- the observed pixel's line is the last one
  signal framed  : std_logic; -- the observed pixel belongs to a frame
  signal x_clear : std_logic;
  signal x_start : std_logic;
  signal y_clear : std_logic;
  signal y_start : std_logic;
  signal y_step  : std_logic;

begin

  assert MAX_WIDTH >= 7 and MAX_WIDTH < 2 ** 16 and MAX_HEIGHT >= 7 and MAX_HEIGHT < 2 ** 16
    report "fastnms_video_check: MAX_WIDTH and MAX_HEIGHT must be in 7 .. 65535"
    severity failure;
  assert PPC = 1 or PPC = 2 or PPC = 4
    report "fastnms_video_check: PPC must be 1, 2 or 4"
    severity failure;

  framed <= p_valid and (p_sof or active);

  checks : process (clk) is
  begin

    if rising_edge(clk) then
      p_valid <= pixel;
      p_sof   <= pixel_sof;
      p_eol   <= pixel_eol;
      -- Beats per line minus 2 (the subtraction first: the shift is wiring).
      cfg_w_m2 <= shift_right(cfg_width - 2 * PPC, PPC / 2);
      cfg_h_m2 <= cfg_height - 2;

      err_eol_early   <= '0';
      err_eol_late    <= '0';
      err_sof_missing <= p_valid and not p_sof and not active;
      err_sof_early   <= p_valid and p_sof and active;

      if p_valid = '1' and p_sof = '1' then
        active <= '1';
        w_m2   <= cfg_w_m2;
        h_m2   <= cfg_h_m2;
      end if;

      if framed = '1' then
        -- At a start of frame the pixel is (0, 0): x_last, late, y_last are 0.
        if p_eol = '1' then
          err_eol_early <= not ((x_last or late) and not p_sof);
          x_last        <= '0';
          late          <= '0';
          if y_last = '1' and p_sof = '0' then
            active <= '0';
          end if;
          y_last <= to_sl(y = h_m2) and not y_last and not p_sof;
        else
          err_eol_late <= x_last and not p_sof;
          late         <= (late or x_last) and not p_sof;
          -- (With two beats per line the beat after a start of frame ends it.)
          x_last <= (to_sl(x = w_m2) and not x_last and not p_sof) or
                    (p_sof and to_sl(cfg_w_m2 = 0));
          if p_sof = '1' then
            y_last <= '0';
          end if;
        end if;
      end if;

      if rst = '1' then
        p_valid         <= '0';
        active          <= '0';
        x_last          <= '0';
        late            <= '0';
        y_last          <= '0';
        err_eol_early   <= '0';
        err_eol_late    <= '0';
        err_sof_missing <= '0';
        err_sof_early   <= '0';
      end if;
    end if;

  end process checks;

  -- x is the index of the pixel after the observed one (0 after a tlast, 1
  -- after a start of frame), y the index of its line.
  x_clear <= framed and p_eol;
  x_start <= framed and p_sof;
  y_clear <= framed and p_sof and not p_eol;
  y_start <= framed and p_sof and p_eol;
  y_step  <= framed and p_eol;

  position : entity work.fastnms_position
    generic map (
      X_BITS => x_t'length,
      Y_BITS => y_t'length
    )
    port map (
      clk     => clk,
      x_clear => x_clear,
      x_start => x_start,
      x_step  => framed,
      y_clear => y_clear,
      y_start => y_start,
      y_step  => y_step,
      x       => x,
      y       => y
    );

  in_frame <= active;

end architecture rtl;
