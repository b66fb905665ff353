-- Region NMS, part 1: the raster scan. One pixel per clock.
--
-- Keeps the label line (the paper's RAM index: one label per column, columns
-- left of x from the current row, the others from the row above) and the
-- current run of corners in registers, and turns the pixel stream into
-- events for fastnms_nms_region_table, which owns the regions:
--
--   new    a run starts touching no labelled pixel: it takes the spare label
--   union  the run touches a run of the row above with another label
--   end    the run ends: its label, its best pixel and `credit` ('1' when
--          the run is already counted for its label, see below)
--   pass   the scan has left a run of the row above behind for good
--   eof    the frame is over (after the flush pass)
--
-- Labels are never resolved here: a run takes the label of the first run
-- above it that it touches, so every run of the line holds one label, and
-- runs with the same label are in the same region. The table counts, per
-- label, the runs of the line holding it. A run is counted at its end unless
-- it was counted earlier: a new run is counted by `new`, and a run whose own
-- label's run above passes while the run goes on takes that count over (the
-- pass is not sent; credit = '1').
--
-- All of one pixel's events travel in one event beat, in the order new,
-- union, end, pass, eof. After the frame's last pixel the scan runs one
-- flush pass of W pixels without corners, so every run of the last row
-- passes and every region closes before the eof event.
--
-- Timing: every decision starts at a flip-flop. The label line is read three
-- columns ahead into a register (frames 2 or 3 wide take the label from the
-- last ones written instead), and the frame's first pixel is known from a
-- register (the input is well formed), not from in_sof.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_nms_region_scan is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE_BITS   : positive := 8;
    CONNECTIVITY : positive := 8;
    LABEL_BITS   : positive := 10
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- Frame width, 1 .. MAX_WIDTH, stable when the start-of-frame pixel is accepted.
    cfg_width : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_corner : in    std_logic;
    in_score  : in    unsigned(SCORE_BITS - 1 downto 0);
    in_sof    : in    std_logic;
    in_eol    : in    std_logic;
    in_eof    : in    std_logic;
    -- The label a new run takes (from the table's free list).
    spare_valid : in    std_logic;
    spare_label : in    unsigned(LABEL_BITS - 1 downto 0);
    spare_take  : out   std_logic;
    -- One event beat per pixel that has any event.
    -- ev_room: the queue takes two more beats; ev_valid is then never refused.
    ev_valid       : out   std_logic;
    ev_room        : in    std_logic;
    ev_new         : out   std_logic;
    ev_union       : out   std_logic;
    ev_union_label : out   unsigned(LABEL_BITS - 1 downto 0);
    ev_end         : out   std_logic;
    ev_credit      : out   std_logic;
    ev_pass        : out   std_logic;
    ev_pass_label  : out   unsigned(LABEL_BITS - 1 downto 0);
    ev_label       : out   unsigned(LABEL_BITS - 1 downto 0);
    ev_score       : out   unsigned(SCORE_BITS - 1 downto 0);
    ev_x           : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    ev_y           : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    ev_eof         : out   std_logic
  );
end entity fastnms_nms_region_scan;

architecture rtl of fastnms_nms_region_scan is

  constant EIGHT : boolean := CONNECTIVITY = 8;

  subtype label_t is unsigned(LABEL_BITS - 1 downto 0);

  constant NONE : label_t := (others => '0');

  -- Frame position of the pixel (or flush step) deciding now.
  signal x          : unsigned(ev_x'range);
  signal y          : unsigned(ev_y'range);
  signal x_clear    : std_logic;
  signal y_clear    : std_logic;
  signal y_step     : std_logic;
  signal first_row  : std_logic;
  signal first_col  : std_logic;
  signal width_m1   : unsigned(cfg_width'range);
  signal width_m2   : unsigned(cfg_width'range);
  signal flushing   : std_logic;
  signal flush_last : std_logic;
  -- The label line and the labels around the pixel in the row above:
  -- line_a = column x-1, line_b = column x, line_c = column x+1, all three
  -- in registers (the RAM is read one column further ahead, so that no
  -- decision starts at a RAM output).
  signal rd_ptr  : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal rd_addr : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal rd_data : std_logic_vector(LABEL_BITS downto 0);
  signal line_a  : label_t;
  signal line_b  : label_t;
  signal a_on    : std_logic;
  signal b_on    : std_logic;
  signal c_lab   : label_t;
  signal c_reg   : std_logic_vector(LABEL_BITS downto 0);
  signal wr_data : std_logic_vector(LABEL_BITS downto 0);
  -- Frames 1 to 3 pixels wide would read a column before it is written:
  -- its label comes from the last one written instead (W = 2, and W = 3 one
  -- clock earlier), or from the pixel itself (W = 1).
  signal narrow  : std_logic;
  signal single  : std_logic;
  signal three   : std_logic;
  signal last_wr : std_logic_vector(LABEL_BITS downto 0);
  signal line_c  : std_logic_vector(LABEL_BITS downto 0);
  -- The current run (the pixel to the left, when it is a corner).
  signal run_on     : std_logic;
  signal run_label  : label_t;
  signal run_score  : unsigned(SCORE_BITS - 1 downto 0);
  signal run_x      : unsigned(ev_x'range);
  signal run_y      : unsigned(ev_y'range);
  signal run_credit : std_logic;
  -- This step.
  signal advance     : std_logic;
  signal pixel_ready : std_logic;
  signal corner      : std_logic;
  signal last_col    : std_logic;
  signal above       : std_logic;
  signal nb_a        : std_logic;
  signal nb_c        : std_logic;
  signal has_a       : std_logic;
  signal has_b       : std_logic;
  signal has_c       : std_logic;
  signal eq_cr       : std_logic;
  signal eq_ca       : std_logic;
  signal eq_ar       : std_logic;
  signal eq_br       : std_logic;
  signal pass_a      : std_logic;
  signal same_label  : std_logic;
  signal is_new      : std_logic;
  signal lab         : label_t;
  signal union_label : label_t;
  signal do_union    : std_logic;
  signal pass_label  : label_t;
  signal pass_raw    : std_logic;
  signal suppress    : std_logic;
  signal do_pass     : std_logic;
  signal credit_in   : std_logic;
  signal credit_now  : std_logic;
  signal better      : std_logic;
  signal best_score  : unsigned(SCORE_BITS - 1 downto 0);
  signal best_x      : unsigned(ev_x'range);
  signal best_y      : unsigned(ev_y'range);
  signal do_end      : std_logic;
  signal do_eof      : std_logic;
  signal start       : std_logic;
  signal expect_sof  : std_logic;
  signal px          : unsigned(ev_x'range);
  signal py          : unsigned(ev_y'range);

begin

  assert CONNECTIVITY = 4 or CONNECTIVITY = 8
    report "fastnms_nms_region_scan: CONNECTIVITY must be 4 or 8"
    severity failure;
  assert MAX_WIDTH >= 2
    report "fastnms_nms_region_scan: MAX_WIDTH must be at least 2"
    severity failure;

  assert LABEL_BITS >= 2
    report "fastnms_nms_region_scan: LABEL_BITS must be at least 2"
    severity failure;

  -- Pixels are taken while the event queue has room for two beats (one may
  -- sit in the event register) and a spare label is ready; the flush pass
  -- steps whenever the queue has room. The input is well formed, so the
  -- first pixel after reset or after a flush pass starts a frame: a register
  -- (expect_sof) says so, and in_sof only checks it (in simulation). The
  -- position (x, y) restarts at the end of a frame, so it is (0, 0) there.
  pixel_ready <= ev_room and spare_valid and not flushing;
  in_ready    <= pixel_ready;
  advance     <= (in_valid and pixel_ready) or (flushing and ev_room);
  corner      <= in_corner and not flushing;
  start       <= expect_sof and not flushing;
  px          <= x;
  py          <= y;
  last_col    <= flush_last when flushing = '1' else
                 in_eol;

  -- The labels above: A = column x-1 and B = column x in registers, C =
  -- column x+1 from the RAM; each with a flag "a corner is there" (the RAM
  -- word's top bit), so that no label needs comparing with zero.
  line_c <= last_wr when narrow = '1' else
            c_reg;
  above  <= not (first_row or start);
  -- A pixel is next to a run above: flags masked at the frame's first row
  -- and at both ends of a row; A and C only under 8-connectivity.
  nb_a  <= a_on and above and not first_col and not start;
  has_a <= nb_a and to_sl(EIGHT);
  has_b <= b_on and above;
  nb_c  <= line_c(LABEL_BITS) and above and not last_col;
  has_c <= nb_c and to_sl(EIGHT);
  c_lab <= unsigned(line_c(LABEL_BITS - 1 downto 0));

  eq_cr <= to_sl(c_lab = run_label);
  eq_ca <= to_sl(c_lab = line_a);
  eq_ar <= to_sl(line_a = run_label);
  eq_br <= to_sl(line_b = run_label);

  -- The pixel's label: the run's, else the first run above it touches, else a new one.
  is_new <= corner and not run_on and not (has_a or has_b or has_c);
  lab    <= run_label when run_on = '1' else
            line_a when has_a = '1' else
            line_b when has_b = '1' else
            c_lab when has_c = '1' else
            spare_label;

  connectivity_8 : if EIGHT generate
    -- A run first touches a run above when C enters with B empty; a run
    -- starting beside two runs above (A and C, B empty) touches both. Runs
    -- above left behind: the one ending at column x-1 (A, B empty), and at
    -- the end of a row the one ending there (B).
    do_union    <= corner and has_c and not has_b and
                   ((run_on and not eq_cr) or (not run_on and has_a and not eq_ca));
    union_label <= c_lab;
    pass_a      <= has_a and not has_b;
    pass_raw    <= pass_a or (has_b and last_col);
    pass_label  <= line_a when pass_a = '1' else
                   line_b;
    -- pass label = the run's label (when not running, the pixel took the
    -- passing run's label).
    same_label <= not run_on or (eq_ar and pass_a) or (eq_br and not pass_a);
  end generate connectivity_8;

  connectivity_4 : if not EIGHT generate
    -- A run first touches a run above when B enters with A empty; the run
    -- above left behind is B's when C is empty or the row ends.
    do_union    <= corner and run_on and has_b and not nb_a and not eq_br;
    union_label <= line_b;
    pass_a      <= '0';
    pass_raw    <= has_b and (not nb_c or last_col);
    pass_label  <= line_b;
    same_label  <= not run_on or eq_br;
  end generate connectivity_4;

  credit_in <= run_credit when run_on = '1' else
               is_new;
  -- The run's own label passing above while the run goes on: the run takes
  -- over that count.
  suppress   <= pass_raw and corner and not credit_in and same_label;
  do_pass    <= pass_raw and not suppress;
  credit_now <= credit_in or suppress;

  -- Best pixel of the run: the larger score, the first in raster order on a tie.
  better     <= not run_on or greater(in_score, run_score);
  best_score <= in_score when corner = '1' and better = '1' else
                run_score;
  best_x     <= px when corner = '1' and better = '1' else
                run_x;
  best_y     <= py when corner = '1' and better = '1' else
                run_y;

  do_end <= (run_on and not corner) or (corner and last_col);
  do_eof <= flushing and flush_last;

  spare_take <= advance and is_new;
  wr_data    <= corner & std_logic_vector(lab) when corner = '1' else
                (others => '0');

  -- One register between the decision and the event queue.
  event_register : process (clk) is
  begin

    if rising_edge(clk) then
      ev_valid <= advance and (is_new or do_union or do_end or do_pass or do_eof);
      if advance = '1' then
        ev_new         <= is_new;
        ev_union       <= do_union;
        ev_union_label <= union_label;
        ev_end         <= do_end;
        ev_credit      <= credit_now when corner = '1' else run_credit;
        ev_pass        <= do_pass;
        ev_pass_label  <= pass_label;
        ev_label       <= lab;
        ev_score       <= best_score;
        ev_x           <= best_x;
        ev_y           <= best_y;
        ev_eof         <= do_eof;
      end if;
      if rst = '1' then
        ev_valid <= '0';
      end if;
    end if;

  end process event_register;

  -- Read column x+3 while column x decides: it reaches c_reg one step later
  -- and is column x+1 two steps later. At the start of a frame: column 3 mod W.
  rd_addr <= rd_ptr when start = '0' else
             to_unsigned(3, rd_addr'length) when cfg_width > 3 else
             to_unsigned(1, rd_addr'length) when cfg_width = 2 else
             (others => '0');

  state : process (clk) is
  begin

    if rising_edge(clk) then
      if advance = '1' then
        line_a <= line_b;
        a_on   <= b_on;
        line_b <= unsigned(line_c(LABEL_BITS - 1 downto 0));
        b_on   <= line_c(LABEL_BITS);
        if single = '1' or (start = '1' and cfg_width = 1) then
          line_b <= unsigned(wr_data(LABEL_BITS - 1 downto 0));
          b_on   <= wr_data(LABEL_BITS);
        end if;
        last_wr <= wr_data;
        if three = '1' then
          c_reg <= last_wr;
        else
          c_reg <= rd_data;
        end if;

        if start = '1' then
          width_m1 <= cfg_width - 1;
          width_m2 <= cfg_width - 2;
          narrow   <= to_sl(cfg_width <= 2);
          single   <= to_sl(cfg_width = 1);
          three    <= to_sl(cfg_width = 3);
          -- Column 4 mod W.
          if cfg_width > 4 then
            rd_ptr <= to_unsigned(4, rd_ptr'length);
          elsif cfg_width = 3 then
            rd_ptr <= to_unsigned(1, rd_ptr'length);
          else
            rd_ptr <= (others => '0');
          end if;
        elsif rd_ptr = width_m1 then
          rd_ptr <= (others => '0');
        else
          rd_ptr <= rd_ptr + 1;
        end if;

        run_on     <= corner and not last_col;
        run_label  <= lab;
        run_score  <= best_score;
        run_x      <= best_x;
        run_y      <= best_y;
        run_credit <= credit_now;

        first_col <= last_col;
        if start = '1' then
          first_row <= '1';
        end if;
        if last_col = '1' and flushing = '0' then
          first_row <= '0';
        end if;
        flush_last <= to_sl(x = width_m2) and flushing;

        if flushing = '1' and flush_last = '1' then
          flushing <= '0';
        elsif in_eof = '1' and flushing = '0' then
          flushing   <= '1';
          flush_last <= to_sl(width_m1 = 0);
          if start = '1' then
            flush_last <= to_sl(cfg_width = 1);
          end if;
        end if;
      end if;
      if advance = '1' then
        if flushing = '1' then
          expect_sof <= flush_last;
        else
          expect_sof <= '0';
        end if;
      end if;
      if rst = '1' then
        expect_sof <= '1';
        run_on     <= '0';
        flushing   <= '0';
        flush_last <= '0';
        first_row  <= '1';
        first_col  <= '1';
        rd_ptr     <= (others => '0');
        width_m1   <= (others => '0');
        narrow     <= '0';
        single     <= '0';
        three      <= '0';
      end if;
    end if;

  end process state;

  -- The position: the increments start from the registers (short paths).
  x_clear <= rst or (advance and last_col);
  y_clear <= rst or (advance and last_col and flushing);
  y_step  <= advance and last_col;

  position : entity work.fastnms_position
    generic map (
      X_BITS => ev_x'length,
      Y_BITS => ev_y'length
    )
    port map (
      clk     => clk,
      x_clear => x_clear,
      x_start => '0',
      x_step  => advance,
      y_clear => y_clear,
      y_start => '0',
      y_step  => y_step,
      x       => x,
      y       => y
    );

  -- The input contract, checked in simulation: in_sof on exactly the pixel
  -- the scan expects to start a frame.
  -- pragma translate_off
  contract : process (clk) is
  begin

    if rising_edge(clk) then
      if rst = '0' and in_valid = '1' and pixel_ready = '1' then
        assert in_sof = start
          report "fastnms_nms_region_scan: in_sof where no frame starts, or missing where one does"
          severity error;
      end if;
    end if;

  end process contract;

  -- pragma translate_on

  label_line : entity work.fastnms_ram_sdp
    generic map (
      DEPTH        => MAX_WIDTH,
      WIDTH        => LABEL_BITS + 1,
      READ_LATENCY => 1
    )
    port map (
      clk     => clk,
      wr_en   => advance,
      wr_addr => px,
      wr_data => wr_data,
      rd_en   => advance,
      rd_addr => rd_addr,
      rd_data => rd_data
    );

end architecture rtl;
