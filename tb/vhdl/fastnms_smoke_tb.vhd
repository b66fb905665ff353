-- Self-checking smoke test of fastnms_core (opencv score, 3x3 NMS) for the
-- FuseSoC sim target: plain VHDL-2008, no cocotb.
--
-- Sends the frames of fastnms_smoke_vectors_pkg (generated from the golden
-- model by gen_smoke_vectors.py) back to back, with random input gaps and
-- output stalls from an LFSR, and checks every record (x, y, score) in order,
-- the number of records of each frame at its end-of-frame beat, that nothing
-- follows the last frame, and that no error pulse occurs. Any mismatch or a
-- time-out stops the simulation with severity failure (non-zero exit status);
-- success prints one line starting with "fastnms_smoke_tb: PASS".
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library std;
  use std.env.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_fast_pkg.all;
  use work.fastnms_smoke_vectors_pkg.all;

entity fastnms_smoke_tb is
end entity fastnms_smoke_tb;

architecture sim of fastnms_smoke_tb is

  constant MAX_WIDTH  : positive := 32;
  constant MAX_HEIGHT : positive := 32;
  constant SCORE      : string   := "opencv";
  constant CLK_PERIOD : time     := 10 ns;
  -- Generous: the frames need about 1.5 clocks per pixel with the gaps and
  -- stalls below.
  constant TIMEOUT : natural := 10 * SMOKE_FRAMES * SMOKE_WIDTH * SMOKE_HEIGHT + 1000;
  -- Clocks checked for stray beats after the last end-of-frame beat.
  constant TAIL_CLOCKS : natural := 4 * SMOKE_WIDTH;

  signal clk           : std_logic;
  signal rst           : std_logic;
  signal lfsr          : std_logic_vector(15 downto 0);
  signal cfg_width     : unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
  signal cfg_height    : unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
  signal cfg_threshold : unsigned(7 downto 0);
  signal in_valid      : std_logic;
  signal in_ready      : std_logic;
  signal in_data       : std_logic_vector(7 downto 0);
  signal in_sof        : std_logic;
  signal in_eol        : std_logic;
  signal out_valid     : std_logic;
  signal out_ready     : std_logic;
  signal out_x         : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal out_y         : unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
  signal out_score     : unsigned(score_width(SCORE) - 1 downto 0);
  signal out_eof       : std_logic;
  signal err_line      : std_logic;
  signal err_frame     : std_logic;

begin

  clock : process is
  begin

    clk <= '0';
    wait for CLK_PERIOD / 2;
    clk <= '1';
    wait for CLK_PERIOD / 2;

  end process clock;

  reset : process is
  begin

    rst <= '1';

    for i in 1 to 5 loop

      wait until rising_edge(clk);

    end loop;

    rst <= '0';
    wait;

  end process reset;

  cfg_width  <= to_unsigned(SMOKE_WIDTH, cfg_width'length);
  cfg_height <= to_unsigned(SMOKE_HEIGHT, cfg_height'length);

  dut : entity work.fastnms_core
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT,
      SCORE      => SCORE,
      NMS        => "3x3"
    )
    port map (
      clk           => clk,
      rst           => rst,
      cfg_width     => cfg_width,
      cfg_height    => cfg_height,
      cfg_threshold => cfg_threshold,
      cfg_cell_log  => (others => '0'),
      cfg_per_cell  => (others => '0'),
      cfg_min_area  => (others => '0'),
      in_valid      => in_valid,
      in_ready      => in_ready,
      in_data       => in_data,
      in_sof        => in_sof,
      in_eol        => in_eol,
      out_valid     => out_valid,
      out_ready     => out_ready,
      out_x         => out_x,
      out_y         => out_y,
      out_score     => out_score,
      out_eof       => out_eof,
      tap_valid     => open,
      tap_ready     => '1',
      tap_score     => open,
      tap_sof       => open,
      tap_eol       => open,
      err_line      => err_line,
      err_frame     => err_frame
    );

  -- The pseudo-random pattern (x^16 + x^14 + x^13 + x^11 + 1) and the output
  -- stalls (out_ready low about one clock in four).
  control : process (clk) is
  begin

    if rising_edge(clk) then
      lfsr      <= lfsr(14 downto 0) & (lfsr(15) xor lfsr(13) xor lfsr(12) xor lfsr(10));
      out_ready <= lfsr(4) or lfsr(9);

      if rst = '1' then
        lfsr      <= x"ACE1";
        out_ready <= '0';
      end if;
    end if;

  end process control;

  -- The frames, back to back, with an input gap about one clock in four.
  drive : process is
  begin

    cfg_threshold <= (others => '0');
    in_valid      <= '0';
    in_data       <= (others => '0');
    in_sof        <= '0';
    in_eol        <= '0';
    wait until rising_edge(clk) and rst = '0';

    for frame in 0 to SMOKE_FRAMES - 1 loop

      cfg_threshold <= to_unsigned(SMOKE_THRESHOLD(frame), 8);

      for k in 0 to SMOKE_WIDTH * SMOKE_HEIGHT - 1 loop

        while lfsr(2) = '1' and lfsr(7) = '1' loop
          in_valid <= '0';
          wait until rising_edge(clk);
        end loop;

        in_valid <= '1';
        in_data  <= std_logic_vector(to_unsigned(SMOKE_IMAGE(k), 8));
        in_sof   <= to_sl(k = 0);
        in_eol   <= to_sl(k mod SMOKE_WIDTH = SMOKE_WIDTH - 1);

        loop
          wait until rising_edge(clk);
          exit when in_ready = '1';
        end loop;

      end loop;

    end loop;

    in_valid <= '0';
    wait;

  end process drive;

  -- The scoreboard.
  check : process (clk) is

    variable clocks : natural := 0;
    variable frame  : natural := 0;
    variable count  : natural := 0; -- records of the current frame so far
    variable rec    : natural := 0; -- records of all frames so far
    variable tail   : natural := 0;

  begin

    if rising_edge(clk) and rst = '0' then
      clocks := clocks + 1;
      assert clocks < TIMEOUT
        report "fastnms_smoke_tb: time-out in frame " & integer'image(frame)
               & " after " & integer'image(count) & " records"
        severity failure;
      assert err_line = '0' and err_frame = '0'
        report "fastnms_smoke_tb: error pulse (err_line or err_frame)"
        severity failure;

      if out_valid = '1' and out_ready = '1' then
        assert frame < SMOKE_FRAMES
          report "fastnms_smoke_tb: output beat after the last frame"
          severity failure;

        if out_eof = '1' then
          assert count = SMOKE_COUNT(frame)
            report "fastnms_smoke_tb: frame " & integer'image(frame) & " ended after "
                   & integer'image(count) & " records, expected "
                   & integer'image(SMOKE_COUNT(frame))
            severity failure;
          frame := frame + 1;
          count := 0;
        else
          assert count < SMOKE_COUNT(frame)
            report "fastnms_smoke_tb: frame " & integer'image(frame)
                   & ": more records than the " & integer'image(SMOKE_COUNT(frame)) & " expected"
            severity failure;
          assert to_integer(out_x) = SMOKE_RECORDS(3 * rec)
                 and to_integer(out_y) = SMOKE_RECORDS(3 * rec + 1)
                 and to_integer(out_score) = SMOKE_RECORDS(3 * rec + 2)
            report "fastnms_smoke_tb: frame " & integer'image(frame) & " record "
                   & integer'image(count) & ": got (" & integer'image(to_integer(out_x)) & ", "
                   & integer'image(to_integer(out_y)) & ", "
                   & integer'image(to_integer(out_score)) & "), expected ("
                   & integer'image(SMOKE_RECORDS(3 * rec)) & ", "
                   & integer'image(SMOKE_RECORDS(3 * rec + 1)) & ", "
                   & integer'image(SMOKE_RECORDS(3 * rec + 2)) & ")"
            severity failure;
          count := count + 1;
          rec   := rec + 1;
        end if;
      end if;

      if frame = SMOKE_FRAMES then
        tail := tail + 1;

        if tail = TAIL_CLOCKS then
          report "fastnms_smoke_tb: PASS, " & integer'image(SMOKE_FRAMES) & " frames, "
                 & integer'image(rec) & " records, " & integer'image(clocks) & " clocks";
          finish;
        end if;
      end if;
    end if;

  end process check;

end architecture sim;
