-- ORB in the core: the budget's records in, each with its angle and
-- descriptor out, then the frame's end-of-frame beat; a queue of a cell
-- row's records in front of fastnms_orb_feed; flags the internal errors
-- that would corrupt a record (err_rows, err_tags, err_count).
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_orb_stage is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 1080;
    SCORE_BITS   : positive := 8;
    LANES        : positive := 8;
    MAX_CELL     : positive := 16;
    MAX_PER_CELL : positive := 15;
    -- Tests only: "none"; "rows" and "tags" (fastnms_orb_feed); "count": a
    -- keypoint that comes in while two are in flight is not counted (err_count
    -- fires when a keypoint leaves that was not counted).
    TEST_FAULT : string := "none"
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- The image and its blur, one pixel of each per beat, raster order.
    img_valid   : in    std_logic;
    img_ready   : out   std_logic;
    img_first   : in    std_logic;
    img_x       : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    img_pixel   : in    std_logic_vector(7 downto 0);
    img_blurred : in    std_logic_vector(7 downto 0);
    -- The frame's budget, with its first pixel (img_first): log2(CELL) - 4
    -- and K = 0; in use until its end-of-frame beat leaves.
    cfg_cell_log   : in    unsigned(2 downto 0);
    cfg_drop       : in    std_logic;
    in_valid       : in    std_logic;
    in_ready       : out   std_logic;
    in_x           : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    in_y           : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    in_score       : in    unsigned(SCORE_BITS - 1 downto 0);
    in_eof         : in    std_logic;
    out_valid      : out   std_logic;
    out_ready      : in    std_logic;
    out_x          : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y          : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_score      : out   unsigned(SCORE_BITS - 1 downto 0);
    out_eof        : out   std_logic;
    out_angle      : out   std_logic_vector(31 downto 0);
    out_descriptor : out   std_logic_vector(255 downto 0);
    dropped        : out   std_logic;
    -- Internal errors, one-clock pulses (registered): fastnms_orb_feed's,
    -- and a keypoint left that the count of keypoints in flight did not hold.
    err_rows  : out   std_logic;
    err_tags  : out   std_logic;
    err_count : out   std_logic
  );
end entity fastnms_orb_stage;

architecture rtl of fastnms_orb_stage is

  constant X_BITS      : positive := clog2(MAX_WIDTH);
  constant Y_BITS      : positive := bits_for(MAX_HEIGHT);
  constant RECORD_BITS : positive := X_BITS + Y_BITS + SCORE_BITS;
  -- A cell row's records at most: ceil(MAX_WIDTH / 16) cells of MAX_PER_CELL.
  constant ROW_RECORDS : positive := (MAX_WIDTH + 15) / 16 * MAX_PER_CELL;
  -- (fastnms_fifo takes DEPTH - 2 words at least.)
  constant QUEUE_DEPTH : positive := maximum(16, ROW_RECORDS + 2);
  -- Records in the queue and the feed: the queue's words, the feed's two
  -- queues of 16 and what its engine holds.
  constant MAX_PENDING : positive := 2 ** clog2(QUEUE_DEPTH) + 256;

  -- The feed's own faults.
  function feed_fault return string is
  begin

    if TEST_FAULT = "count" then
      return "none";
    end if;

    return TEST_FAULT;

  end function feed_fault;

  signal plain_ready   : std_logic;
  signal blurred_ready : std_logic;
  signal img_go        : std_logic;
  -- The budgets of the open frames (two at most, as in the feed): of the
  -- frame whose records come in (frame_log, frame_drop), and of the next.
  signal frames     : natural range 0 to 2;
  signal frame_room : std_logic;
  signal frame_log  : unsigned(2 downto 0);
  signal frame_drop : std_logic;
  signal next_log   : unsigned(2 downto 0);
  signal next_drop  : std_logic;
  signal eof_leaves : std_logic;

  signal is_record : std_logic;
  signal push      : std_logic;
  signal q_ready   : std_logic;
  signal q_valid   : std_logic;
  signal q_taken   : std_logic;
  signal q_data    : std_logic_vector(RECORD_BITS - 1 downto 0);
  signal key_ready : std_logic;
  signal f_valid   : std_logic;
  signal f_ready   : std_logic;
  signal f_x       : unsigned(out_x'range);
  signal f_y       : unsigned(out_y'range);
  signal f_score   : unsigned(out_score'range);
  signal f_angle   : std_logic_vector(31 downto 0);
  signal f_desc    : std_logic_vector(255 downto 0);
  signal pending   : natural range 0 to MAX_PENDING;
  signal none_left : std_logic;
  signal eof_held  : std_logic;
  signal eof_x     : unsigned(out_x'range);
  signal eof_y     : unsigned(out_y'range);

begin

  assert MAX_PER_CELL <= 15
    report "fastnms_orb_stage: MAX_PER_CELL must be 1 .. 15"
    severity failure;
  assert TEST_FAULT = "none" or TEST_FAULT = "rows" or TEST_FAULT = "tags" or TEST_FAULT = "count"
    report "fastnms_orb_stage: TEST_FAULT must be ""none"", ""rows"", ""tags"" or ""count"""
    severity failure;

  -- One image stream into the feed's two: a beat goes when both take it, a
  -- frame's first pixel while fewer than two frames are open.
  img_go    <= img_valid and (frame_room or not img_first);
  img_ready <= plain_ready and blurred_ready and (frame_room or not img_first);

  -- A record goes into the queue; with cfg_drop it is dropped when the
  -- queue is full. The end of frame waits until every record has left, and
  -- nothing passes while it waits to leave.
  is_record <= in_valid and not in_eof and not eof_held;
  push      <= is_record and q_ready;
  dropped   <= is_record and not q_ready and frame_drop;
  none_left <= to_sl(pending = 0);
  in_ready  <= '0' when eof_held = '1' else
               none_left when in_eof = '1' else
               q_ready or frame_drop;

  queue : entity work.fastnms_fifo
    generic map (
      DEPTH => QUEUE_DEPTH,
      WIDTH => RECORD_BITS,
      STYLE => "block"
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => push,
      in_ready  => q_ready,
      in_data   => std_logic_vector(in_x) & std_logic_vector(in_y) & std_logic_vector(in_score),
      out_valid => q_valid,
      out_ready => key_ready,
      out_data  => q_data,
      busy      => open
    );

  q_taken <= q_valid and key_ready;

  feed : entity work.fastnms_orb_feed
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT,
      SCORE_BITS => SCORE_BITS,
      LANES      => LANES,
      MAX_CELL   => MAX_CELL,
      TEST_FAULT => feed_fault
    )
    port map (
      clk            => clk,
      rst            => rst,
      plain_valid    => img_go and blurred_ready,
      plain_ready    => plain_ready,
      plain_first    => img_first,
      plain_x        => img_x,
      plain_pixel    => img_pixel,
      blurred_valid  => img_go and plain_ready,
      blurred_ready  => blurred_ready,
      blurred_first  => img_first,
      blurred_x      => img_x,
      blurred_pixel  => img_blurred,
      key_valid      => q_valid,
      key_ready      => key_ready,
      key_x          => unsigned(q_data(RECORD_BITS - 1 downto Y_BITS + SCORE_BITS)),
      key_y          => unsigned(q_data(Y_BITS + SCORE_BITS - 1 downto SCORE_BITS)),
      key_score      => unsigned(q_data(SCORE_BITS - 1 downto 0)),
      cell_log       => frame_log,
      key_frame_end  => eof_leaves,
      out_valid      => f_valid,
      out_ready      => f_ready,
      out_x          => f_x,
      out_y          => f_y,
      out_score      => f_score,
      out_angle      => f_angle,
      out_descriptor => f_desc,
      err_rows       => err_rows,
      err_tags       => err_tags
    );

  -- The feed's records, then the held end of frame (none is in the feed
  -- while it is held).
  f_ready        <= out_ready and not eof_held;
  out_valid      <= eof_held or f_valid;
  out_eof        <= eof_held;
  eof_leaves     <= eof_held and out_ready;
  out_x          <= eof_x when eof_held = '1' else
                    f_x;
  out_y          <= eof_y when eof_held = '1' else
                    f_y;
  out_score      <= (others => '0') when eof_held = '1' else
                    f_score;
  out_angle      <= (others => '0') when eof_held = '1' else
                    f_angle;
  out_descriptor <= (others => '0') when eof_held = '1' else
                    f_desc;

  counts : process (clk) is

    variable count : natural range 0 to MAX_PENDING;
    variable n     : natural range 0 to 2;

  begin

    if rising_edge(clk) then
      count := pending;
      if push = '1' and not (TEST_FAULT = "count" and pending >= 2) then
        count := count + 1;
      end if;
      -- (A keypoint taken by the feed or leaving it that was not counted:
      -- err_count; the count stays at 0.)
      err_count <= q_taken and to_sl(pending = 0);
      if f_valid = '1' and f_ready = '1' then
        if count = 0 then
          err_count <= '1';
        else
          count := count - 1;
        end if;
      end if;
      pending <= count;

      -- The open frames' budgets: the next one's taken with its first pixel,
      -- the oldest one's dropped when its end of frame leaves.
      n := frames;
      if eof_leaves = '1' and n > 0 then
        frame_log  <= next_log;
        frame_drop <= next_drop;
        n          := n - 1;
      end if;
      if img_valid = '1' and img_ready = '1' and img_first = '1' and n < 2 then
        if n = 0 then
          frame_log  <= cfg_cell_log;
          frame_drop <= cfg_drop;
        else
          next_log  <= cfg_cell_log;
          next_drop <= cfg_drop;
        end if;
        n := n + 1;
      end if;
      frames     <= n;
      frame_room <= to_sl(n < 2);

      if in_valid = '1' and in_eof = '1' and eof_held = '0' and none_left = '1' then
        eof_held <= '1';
        eof_x    <= in_x;
        eof_y    <= in_y;
      elsif out_ready = '1' then
        eof_held <= '0';
      end if;

      if rst = '1' then
        pending    <= 0;
        eof_held   <= '0';
        err_count  <= '0';
        frames     <= 0;
        frame_room <= '1';
      end if;
    end if;

  end process counts;

  -- pragma translate_off
  checks : process (clk) is
  begin

    if rising_edge(clk) then
      if rst = '0' then
        assert not (q_taken = '1' and pending = 0) or TEST_FAULT /= "none"
          report "fastnms_orb_stage: a record left that was never counted"
          severity failure;
      end if;
    end if;

  end process checks;

-- pragma translate_on

end architecture rtl;
