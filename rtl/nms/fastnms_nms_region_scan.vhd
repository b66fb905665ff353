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
    clk            : in    std_logic;
    rst            : in    std_logic;
    -- Frame width, 1 .. MAX_WIDTH, stable when the start-of-frame pixel is accepted.
    cfg_width      : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    in_valid       : in    std_logic;
    in_ready       : out   std_logic;
    in_corner      : in    std_logic;
    in_score       : in    unsigned(SCORE_BITS - 1 downto 0);
    in_sof         : in    std_logic;
    in_eol         : in    std_logic;
    in_eof         : in    std_logic;
    -- The label a new run takes (from the table's free list).
    spare_valid    : in    std_logic;
    spare_label    : in    unsigned(LABEL_BITS - 1 downto 0);
    spare_take     : out   std_logic;
    -- One event beat per pixel that has any event.
    ev_valid       : out   std_logic;
    ev_ready       : in    std_logic;
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
  signal x           : unsigned(ev_x'range);
  signal y           : unsigned(ev_y'range);
  signal first_row   : std_logic;
  signal first_col   : std_logic;
  signal width_m1    : unsigned(cfg_width'range);
  signal flushing    : std_logic;
  signal flush_last  : std_logic;
  -- The label line and the labels around the pixel in the row above:
  -- line_a = column x-1, line_b = column x, rd_data = column x+1.
  signal rd_ptr      : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal rd_addr     : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal rd_data     : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal line_a      : label_t;
  signal line_b      : label_t;
  signal wr_data     : std_logic_vector(LABEL_BITS - 1 downto 0);
  -- Frames 1 or 2 pixels wide read the column written in the same clock:
  -- that label comes from a register instead (W = 2), or from the pixel
  -- itself (W = 1).
  signal narrow      : std_logic;
  signal single      : std_logic;
  signal last_wr     : std_logic_vector(LABEL_BITS - 1 downto 0);
  signal line_c      : std_logic_vector(LABEL_BITS - 1 downto 0);
  -- The current run (the pixel to the left, when it is a corner).
  signal run_on      : std_logic;
  signal run_label   : label_t;
  signal run_score   : unsigned(SCORE_BITS - 1 downto 0);
  signal run_x       : unsigned(ev_x'range);
  signal run_y       : unsigned(ev_y'range);
  signal run_credit  : std_logic;
  -- This step.
  signal advance     : std_logic;
  signal pixel_ready : std_logic;
  signal corner      : std_logic;
  signal last_col    : std_logic;
  signal above       : std_logic;
  signal nb_a        : label_t;
  signal nb_b        : label_t;
  signal nb_c        : label_t;
  signal has_a       : std_logic;
  signal has_b       : std_logic;
  signal has_c       : std_logic;
  signal has_n       : std_logic;
  signal first_nb    : label_t;
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
  signal px          : unsigned(ev_x'range);
  signal py          : unsigned(ev_y'range);

begin

  assert CONNECTIVITY = 4 or CONNECTIVITY = 8
    report "fastnms_nms_region_scan: CONNECTIVITY must be 4 or 8"
    severity failure;
  assert MAX_WIDTH >= 2
    report "fastnms_nms_region_scan: MAX_WIDTH must be at least 2"
    severity failure;

  -- Pixels are taken while the event queue and a spare label are ready; the
  -- flush pass steps whenever the event queue is ready.
  pixel_ready <= ev_ready and spare_valid and not flushing;
  in_ready    <= pixel_ready;
  advance     <= (in_valid and pixel_ready) or (flushing and ev_ready);
  corner      <= in_corner and not flushing;
  start       <= in_sof and not flushing;
  px          <= (others => '0') when start = '1' else x;
  py          <= (others => '0') when start = '1' else y;
  last_col    <= flush_last when flushing = '1' else in_eol;

  -- The row above exists from the second row on (and for the flush pass).
  above <= not (first_row or start);
  nb_a  <= line_a when above = '1' and first_col = '0' and start = '0' else NONE;
  nb_b  <= line_b when above = '1' else NONE;
  line_c <= last_wr when narrow = '1' else rd_data;
  nb_c  <= unsigned(line_c) when above = '1' and last_col = '0' else NONE;

  -- Decision for the pixel: its label, union, pass and end events.
  has_a <= (or nb_a) and to_sl(EIGHT);
  has_b <= or nb_b;
  has_c <= (or nb_c) and to_sl(EIGHT);
  has_n <= or nb_c;

  first_nb <= nb_a when has_a = '1' else
              nb_b when has_b = '1' else
              nb_c when has_c = '1' else
              NONE;

  -- A run touches a run of the row above first when that run enters the
  -- neighbourhood: C under 8-connectivity (B empty), B under 4 (A empty);
  -- a run starting beside two runs above (A and C, B empty) touches both.
  union_label <= nb_c when EIGHT and has_b = '0' and (run_on = '1' or has_a = '1') else
                 nb_b when not EIGHT and run_on = '1' and (or nb_a) = '0' else
                 NONE;

  -- The run of the row above left behind: the one ending at column x-1
  -- (8-connectivity) or x (4), and at the end of a row the one ending there.
  pass_label <= nb_a when EIGHT and has_b = '0' else
                nb_b when EIGHT and last_col = '1' else
                nb_b when not EIGHT and (has_n = '0' or last_col = '1') else
                NONE;

  is_new     <= corner and not run_on and not (has_a or has_b or has_c);
  lab        <= run_label when run_on = '1' else
                first_nb when (has_a or has_b or has_c) = '1' else
                spare_label;
  do_union   <= corner and (or union_label) and to_sl(union_label /= lab);
  pass_raw   <= or pass_label;
  credit_in  <= run_credit when run_on = '1' else is_new;
  -- The run's own label passing above while the run goes on: the run takes
  -- over that count.
  suppress   <= pass_raw and corner and not credit_in and to_sl(pass_label = lab);
  do_pass    <= pass_raw and not suppress;
  credit_now <= credit_in or suppress;

  -- Best pixel of the run: the larger score, the first in raster order on a tie.
  better     <= not run_on or greater(in_score, run_score);
  best_score <= in_score when corner = '1' and better = '1' else run_score;
  best_x     <= px when corner = '1' and better = '1' else run_x;
  best_y     <= py when corner = '1' and better = '1' else run_y;

  do_end <= (run_on and not corner) or (corner and last_col);
  do_eof <= flushing and flush_last;

  ev_valid       <= advance and (is_new or do_union or do_end or do_pass or do_eof);
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
  spare_take     <= advance and is_new;

  wr_data <= std_logic_vector(lab) when corner = '1' else (others => '0');

  -- Read column x+2 while column x decides: it is column x+1 of the next step.
  -- At the start of a frame: column 2 mod W.
  rd_addr <= rd_ptr when start = '0' else
             to_unsigned(2, rd_addr'length) when cfg_width > 2 else
             (others => '0');

  state : process (clk) is
  begin

    if rising_edge(clk) then
      if advance = '1' then
        line_a <= line_b;
        line_b <= unsigned(line_c);
        if single = '1' or (start = '1' and cfg_width = 1) then
          line_b <= unsigned(wr_data);
        end if;
        last_wr <= wr_data;

        if start = '1' then
          width_m1 <= cfg_width - 1;
          narrow   <= to_sl(cfg_width <= 2);
          single   <= to_sl(cfg_width = 1);
          -- Column 3 mod W.
          if cfg_width > 3 then
            rd_ptr <= to_unsigned(3, rd_ptr'length);
          elsif cfg_width = 2 then
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
        if last_col = '1' then
          x <= (others => '0');
          if flushing = '0' then
            y         <= py + 1;
            first_row <= '0';
          end if;
        else
          x <= px + 1;
          y <= py;
        end if;
        flush_last <= to_sl(x + 1 = width_m1) and flushing;

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
      if rst = '1' then
        run_on     <= '0';
        flushing   <= '0';
        flush_last <= '0';
        first_row  <= '1';
        first_col  <= '1';
        x          <= (others => '0');
        y          <= (others => '0');
        rd_ptr     <= (others => '0');
        width_m1   <= (others => '0');
        narrow     <= '0';
        single     <= '0';
      end if;
    end if;

  end process state;

  label_line : entity work.fastnms_ram_sdp
    generic map (
      DEPTH        => MAX_WIDTH,
      WIDTH        => LABEL_BITS,
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
