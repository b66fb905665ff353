-- ORB after the budget: the image and its blur in, kept keypoints in, each
-- with its angle and descriptor out; keeps the rows a keypoint's columns are
-- read from (numbered on across frames, so the next frame's rows come in
-- while a frame's last keypoints are read) and never overwrites one unread;
-- flags the internal errors that would corrupt a record (err_rows, err_tags).
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_orb_feed is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 1080;
    SCORE_BITS : positive := 8;
    LANES      : positive := 8;
    -- The largest CELL of the budget in front (16 .. 256, a power of two):
    -- sizes the rows kept, 2 MAX_CELL + 2 HALF each side.
    MAX_CELL : positive := 16;
    -- Tests only: "none"; "rows": the input never waits for room in the rows
    -- (err_rows fires when the engine falls behind); "tags": the tag queue
    -- holds one record (err_tags fires when two keypoints are in flight).
    TEST_FAULT : string := "none"
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- The image, and the blurred image, each one pixel per beat in raster
    -- order (first: a frame's first pixel).
    plain_valid   : in    std_logic;
    plain_ready   : out   std_logic;
    plain_first   : in    std_logic;
    plain_x       : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    plain_pixel   : in    std_logic_vector(7 downto 0);
    blurred_valid : in    std_logic;
    blurred_ready : out   std_logic;
    blurred_first : in    std_logic;
    blurred_x     : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    blurred_pixel : in    std_logic_vector(7 downto 0);
    -- Keypoints in, and out with their angle (float32 bits, degrees) and
    -- descriptor (bit i: byte i / 8, bit i mod 8).
    key_valid : in    std_logic;
    key_ready : out   std_logic;
    key_x     : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    key_y     : in    unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    key_score : in    unsigned(SCORE_BITS - 1 downto 0);
    -- log2(CELL) - 4 of the budget the keypoints come from (0: CELL 16 .. 4: 256).
    cell_log : in    unsigned(2 downto 0);
    -- A pulse after a frame's last keypoint is taken, at least a clock before
    -- the next frame's first: the keypoints after it are the next frame's.
    -- A frame's keypoints come after its first pixel on both streams; the
    -- first pixel of a third frame waits for the pulse of the first (two
    -- frames open at most).
    key_frame_end  : in    std_logic;
    out_valid      : out   std_logic;
    out_ready      : in    std_logic;
    out_x          : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y          : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_score      : out   unsigned(SCORE_BITS - 1 downto 0);
    out_angle      : out   std_logic_vector(31 downto 0);
    out_descriptor : out   std_logic_vector(255 downto 0);
    -- Internal errors, one-clock pulses (registered): a keypoint's rows were
    -- overwritten before it was read; the tag queue refused a record.
    err_rows : out   std_logic;
    err_tags : out   std_logic
  );
end entity fastnms_orb_feed;

architecture rtl of fastnms_orb_feed is

  constant X_BITS      : positive := clog2(MAX_WIDTH);
  constant Y_BITS      : positive := bits_for(MAX_HEIGHT);
  constant RECORD_BITS : positive := X_BITS + Y_BITS + SCORE_BITS;
  constant QUEUE_DEPTH : positive := 16;

  type side_t is record
    half  : positive; -- rows above and below the keypoint
    slots : positive;
  end record side_t;

  type sides_t is array (0 to 1) of side_t;

  -- Rows kept: a cell row's keypoints are read within the next cell row, and
  -- the first ones need HALF rows above it: 2 MAX_CELL + 2 HALF rows, in slots
  -- of 2 HALF + 1 (docs/design/orb_rows.md).
  function slots_for (half : positive) return positive is
  begin

    return (2 * MAX_CELL + 2 * half + 2 * half) / (2 * half + 1);

  end function slots_for;

  -- 0: the unblurred image (the moments' 31 rows), 1: the blurred one (37).
  constant SIDES : sides_t := ((half => 15, slots => slots_for(15)), (half => 18, slots => slots_for(18)));

  type columns_t is array (0 to 1) of std_logic_vector(37 * 8 - 1 downto 0);

  -- Ring numbers of rows: modulo 2 ** RING_BITS, more than twice the rows a
  -- frame and the rows kept span, so that a difference's sign bit tells
  -- which of two rows in play comes first.
  constant RING_BITS : positive := maximum(Y_BITS, clog2(37 * SIDES(1).slots)) + 2;

  subtype ring_t is unsigned(RING_BITS - 1 downto 0);

  -- The keypoint queues' words: the row and the cell row's first row in the
  -- ring, then the record.
  constant QUEUE_BITS : positive := 2 * RING_BITS + RECORD_BITS;

  type records_t is array (0 to 1) of std_logic_vector(QUEUE_BITS - 1 downto 0);

  function ring_row (word : std_logic_vector) return ring_t is
  begin

    return unsigned(word(QUEUE_BITS - 1 downto RECORD_BITS + RING_BITS));

  end function ring_row;

  function ring_top (word : std_logic_vector) return ring_t is
  begin

    return unsigned(word(RECORD_BITS + RING_BITS - 1 downto RECORD_BITS));

  end function ring_top;

  -- a is row b or a row after it (both rows in play).
  function not_below (a : ring_t; b : ring_t) return boolean is
    variable d : ring_t;
  begin

    d := a - b;
    return d(RING_BITS - 1) = '0';

  end function not_below;

  -- y rounded down to the budget's CELL (16 << log).
  function cell_top (y : unsigned; log : unsigned(2 downto 0)) return unsigned is
    variable r : unsigned(y'length - 1 downto 0);
  begin

    r := y;

    for k in 0 to minimum(y'length, 8) - 1 loop

      if k < 4 or to_integer(log) > k - 4 then
        r(k) := '0';
      end if;

    end loop;

    return r;

  end function cell_top;

  signal in_valid : std_logic_vector(0 to 1);
  signal in_ready : std_logic_vector(0 to 1);
  signal in_first : std_logic_vector(0 to 1);
  signal in_x     : unsigned(2 * X_BITS - 1 downto 0);
  signal in_pixel : std_logic_vector(15 downto 0);

  signal key_record               : std_logic_vector(RECORD_BITS - 1 downto 0);
  signal queue_ready, queue_valid : std_logic_vector(0 to 1);
  signal queue_pop                : std_logic_vector(0 to 1);
  signal queue_head               : records_t;

  signal col_valid,   col_ready : std_logic_vector(0 to 1);
  signal columns                : columns_t;

  -- The plain columns' records, one per keypoint, taken with its last column.
  signal tag_valid,   tag_push  : std_logic;
  signal tag_room               : std_logic;
  signal tag_taken              : std_logic;
  signal overwritten            : std_logic_vector(0 to 1);
  signal tag_head               : std_logic_vector(RECORD_BITS - 1 downto 0);
  signal tag_pushed             : std_logic_vector(RECORD_BITS - 1 downto 0);
  signal plain_count            : natural range 0 to 30;
  signal plain_in,    plain_rdy : std_logic;
  signal plain_take             : std_logic;

  signal result : std_logic_vector(RECORD_BITS - 1 downto 0);

begin

  assert MAX_CELL = 16 or MAX_CELL = 32 or MAX_CELL = 64 or MAX_CELL = 128 or MAX_CELL = 256
    report "fastnms_orb_feed: MAX_CELL must be 16, 32, 64, 128 or 256"
    severity failure;
  assert TEST_FAULT = "none" or TEST_FAULT = "rows" or TEST_FAULT = "tags"
    report "fastnms_orb_feed: TEST_FAULT must be ""none"", ""rows"" or ""tags"""
    severity failure;

  in_valid <= plain_valid & blurred_valid;
  in_first <= plain_first & blurred_first;
  in_x     <= plain_x & blurred_x;
  in_pixel <= plain_pixel & blurred_pixel;

  plain_ready   <= in_ready(0);
  blurred_ready <= in_ready(1);

  -- A record goes into both queues at once.
  key_record <= std_logic_vector(key_x) & std_logic_vector(key_y) & std_logic_vector(key_score);
  key_ready  <= queue_ready(0) and queue_ready(1);

  side : for s in 0 to 1 generate
    constant HALF   : positive := SIDES(s).half;
    constant HEIGHT : positive := 2 * HALF + 1;
    constant ROWS   : positive := HEIGHT * SIDES(s).slots;

    signal x       : unsigned(X_BITS - 1 downto 0);
    signal take_px : std_logic;
    -- The row being written: its ring number (rows numbered on across frames,
    -- 0 the first after reset) and its physical number (as fastnms_orb_rows
    -- numbers them).
    signal current  : ring_t;
    signal physical : natural range 0 to ROWS - 1;
    -- The ring numbers of row 0 of the frame whose keypoints come in (base)
    -- and of the next frame (base_next): frames of them, at most 2.
    signal base       : ring_t;
    signal base_next  : ring_t;
    signal frames     : natural range 0 to 2;
    signal frame_room : std_logic;
    signal key_word   : std_logic_vector(QUEUE_BITS - 1 downto 0);
    signal rd_valid   : std_logic;
    signal rd_ready   : std_logic;
    signal rd_x       : unsigned(X_BITS - 1 downto 0);
    signal rd_top     : unsigned(clog2(ROWS) - 1 downto 0);
    -- The sequencer: the keypoint being requested (its x, its row and its
    -- cell row's first row) and its next column.
    signal busy     : std_logic;
    signal dx       : natural range 0 to HEIGHT - 1;
    signal head_x   : natural range 0 to 2 ** X_BITS - 1;
    signal head_row : ring_t;
    signal head_top : ring_t;
    -- Clocks until the keypoint's first request (its top row computed).
    signal warm   : natural range 0 to 3;
    signal back   : ring_t;
    signal phys_r : natural range 0 to ROWS - 1;
    signal top_r  : integer range -(2 ** RING_BITS) to ROWS - 1;
    -- The start condition's and the room's operands, a clock ahead.
    signal after_half : ring_t;
    signal limit      : ring_t;
    signal pending_r  : boolean;
    signal room       : std_logic;
  begin

    x <= in_x((1 - s) * X_BITS + X_BITS - 1 downto (1 - s) * X_BITS);

    -- The stream waits while its next row could overwrite a row still to be
    -- read, and at a frame's first pixel while two frames are open.
    in_ready(s) <= room and (frame_room or not in_first(s));
    take_px     <= in_valid(s) and in_ready(s);

    -- A keypoint's record with its row and its cell row's first row in the
    -- ring (the frame's base plus y, and plus y rounded down to CELL).
    key_word <= std_logic_vector(base + key_y) & std_logic_vector(base + cell_top(key_y, cell_log)) &
                key_record;

    queue : entity work.fastnms_fifo
      generic map (
        DEPTH => QUEUE_DEPTH,
        WIDTH => QUEUE_BITS,
        STYLE => "distributed"
      )
      port map (
        clk       => clk,
        rst       => rst,
        in_valid  => key_valid and key_ready,
        in_ready  => queue_ready(s),
        in_data   => key_word,
        out_valid => queue_valid(s),
        out_ready => queue_pop(s),
        out_data  => queue_head(s),
        busy      => open
      );

    row_buffer : entity work.fastnms_orb_rows
      generic map (
        MAX_WIDTH => MAX_WIDTH,
        HEIGHT    => HEIGHT,
        SLOTS     => SIDES(s).slots
      )
      port map (
        clk        => clk,
        rst        => rst,
        wr_valid   => take_px,
        wr_x       => x,
        wr_pixel   => in_pixel((1 - s) * 8 + 7 downto (1 - s) * 8),
        row_index  => open,
        rd_valid   => rd_valid,
        rd_ready   => rd_ready,
        rd_x       => rd_x,
        rd_top     => rd_top,
        out_valid  => col_valid(s),
        out_ready  => col_ready(s),
        out_column => columns(s)(8 * HEIGHT - 1 downto 0)
      );

    sequencer : process (clk) is

      variable hx      : natural range 0 to 2 ** X_BITS - 1;
      variable hr, ht  : ring_t;
      variable d       : natural range 0 to HEIGHT - 1;
      variable b, v    : std_logic;
      variable w       : natural range 0 to 3;
      variable row     : ring_t;
      variable phys    : natural range 0 to ROWS - 1;
      variable bq, bn  : ring_t;
      variable n       : natural range 0 to 2;
      variable low     : ring_t;
      variable pending : boolean;

    begin

      if rising_edge(clk) then
        queue_pop(s) <= '0';

        -- The rows written: a row's first pixel starts the next row.
        row  := current;
        phys := physical;
        if take_px = '1' and x = 0 then
          row  := current + 1;
          phys := (physical + 1) mod ROWS;
        end if;
        current  <= row;
        physical <= phys;

        -- The frames open: one more at a frame's first pixel (its row 0), one
        -- less once the keypoints of the oldest are in (key_frame_end).
        n  := frames;
        bq := base;
        bn := base_next;
        if key_frame_end = '1' and n > 0 then
          bq := base_next;
          n  := n - 1;
        end if;
        if take_px = '1' and in_first(s) = '1' and n < 2 then
          if n = 0 then
            bq := row;
          else
            bn := row;
          end if;
          n := n + 1;
        end if;
        base       <= bq;
        base_next  <= bn;
        frames     <= n;
        frame_room <= to_sl(n < 2);

        -- Rows complete below HALF + 1 rows under the current one (a clock
        -- late: a keypoint starts a clock later at most).
        after_half <= current - (HALF + 1);

        -- The request presented: the next column, or, three clocks after the
        -- head record is taken (once its last row is complete), its first.
        hx := head_x;
        hr := head_row;
        ht := head_top;
        d  := dx;
        b  := busy;
        v  := rd_valid;
        w  := warm;
        if rd_valid = '1' and rd_ready = '1' then
          if dx = HEIGHT - 1 then
            b := '0';
            v := '0';
          else
            d := dx + 1;
          end if;
        end if;
        if warm = 1 then
          v := '1';
        end if;
        if warm > 0 then
          w := warm - 1;
        end if;
        if b = '0' and queue_valid(s) = '1' and queue_pop(s) = '0' and
           not_below(after_half, ring_row(queue_head(s))) then
          b            := '1';
          d            := 0;
          w            := 3;
          hx           := to_integer(unsigned(queue_head(s)(RECORD_BITS - 1 downto Y_BITS + SCORE_BITS)));
          hr           := ring_row(queue_head(s));
          ht           := ring_top(queue_head(s));
          queue_pop(s) <= '1';
        end if;
        busy     <= b;
        rd_valid <= v;
        warm     <= w;
        dx       <= d;
        head_x   <= hx;
        head_row <= hr;
        head_top <= ht;
        -- (Wrapped like the hardware's adds when no keypoint is in.)
        rd_x <= to_unsigned((hx + d + 2 ** X_BITS - HALF) mod 2 ** X_BITS, X_BITS);

        -- The top row's physical number, a row's slot being fixed until it is
        -- overwritten: the current row's, less the rows between them (0 ..
        -- ROWS - 1 for a keypoint whose rows are kept), in three steps from
        -- registers while the keypoint warms up (warm 3, 2, 1).
        if warm = 3 then
          back   <= current + HALF - head_row;
          phys_r <= physical;
        end if;
        -- (back >= ROWS: the keypoint's top row was overwritten.)
        overwritten(s) <= '0';
        if warm = 2 then
          top_r <= phys_r;
          if back < ROWS then
            top_r <= phys_r - to_integer(back);
          else
            overwritten(s) <= '1';
          end if;
        end if;
        if warm = 1 then
          if top_r < 0 then
            rd_top <= to_unsigned(top_r + ROWS, rd_top'length);
          else
            rd_top <= to_unsigned(top_r, rd_top'length);
          end if;
        end if;

        -- A new row may start while it overwrites no row a pending keypoint
        -- needs. The keypoints come a cell row at a time, so none is above the
        -- first row of the oldest one's cell row. From registers, two clocks
        -- late: rows start a whole line apart, and a keypoint arrives long
        -- before its rows could be overwritten.
        pending := b = '1' or queue_valid(s) = '1' or (key_valid = '1' and key_ready = '1');
        low     := ring_top(key_word);
        if b = '1' then
          low := ht;
        elsif queue_valid(s) = '1' then
          low := ring_top(queue_head(s));
        end if;
        -- The next row overwrites row current + 1 - ROWS: it must stay above
        -- the rows from HALF above that line (current <= limit).
        limit     <= low + (ROWS - 2 - HALF);
        pending_r <= pending;
        room      <= to_sl(not pending_r or not_below(limit, current) or TEST_FAULT = "rows");

        if rst = '1' then
          busy           <= '0';
          rd_valid       <= '0';
          warm           <= 0;
          current        <= (others => '1');
          physical       <= ROWS - 1;
          frames         <= 0;
          frame_room     <= '1';
          room           <= '1';
          pending_r      <= false;
          overwritten(s) <= '0';
        end if;
      end if;

    end process sequencer;

    -- pragma translate_off
    kept : process (clk) is
    begin

      if rising_edge(clk) then
        if rst = '0' and queue_pop(s) = '1' then
          assert current + HALF - head_row < ROWS or TEST_FAULT /= "none"
            report "fastnms_orb_feed: a keypoint's rows were overwritten before it was read"
            severity error;
          assert 2 ** (4 + to_integer(cell_log)) <= MAX_CELL
            report "fastnms_orb_feed: the budget's CELL is above MAX_CELL"
            severity error;
        end if;
        if rst = '0' then
          assert not (key_frame_end = '1' and frames = 0)
            report "fastnms_orb_feed: key_frame_end without a frame open"
            severity error;
          assert not (take_px = '1' and in_first(s) = '1' and x /= 0)
            report "fastnms_orb_feed: a frame's first pixel must be at x = 0"
            severity error;
        end if;
      end if;

    end process kept;

  -- pragma translate_on

  end generate side;

  -- The plain columns carry their keypoint's record on the last one; the
  -- records leave the plain queue in the same order as their columns. The
  -- tag queue never refuses one: a record waits in it only while its
  -- keypoint's columns are requested or wait in the rows' 16-word FIFO, so
  -- it holds three at most (a refusal raises err_tags; simulation stops).
  tags : process (clk) is
  begin

    if rising_edge(clk) then
      tag_push   <= queue_pop(0);
      tag_pushed <= queue_head(0)(RECORD_BITS - 1 downto 0);
    end if;

  end process tags;

  -- pragma translate_off
  tag_check : process (clk) is
  begin

    if rising_edge(clk) then
      assert not (rst = '0' and tag_push = '1' and tag_room = '0' and TEST_FAULT = "none")
        report "fastnms_orb_feed: the tag queue is full"
        severity failure;
    end if;

  end process tag_check;

  -- pragma translate_on

  -- (TEST_FAULT "tags": a queue of one record.)
  tag_taken <= tag_push and tag_room and not (to_sl(TEST_FAULT = "tags") and tag_valid);

  errors : process (clk) is
  begin

    if rising_edge(clk) then
      err_rows <= overwritten(0) or overwritten(1);
      err_tags <= tag_push and not tag_taken;
      if rst = '1' then
        err_rows <= '0';
        err_tags <= '0';
      end if;
    end if;

  end process errors;

  tag_queue : entity work.fastnms_fifo
    generic map (
      DEPTH => QUEUE_DEPTH,
      WIDTH => RECORD_BITS,
      STYLE => "distributed"
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => tag_taken,
      in_ready  => tag_room,
      in_data   => tag_pushed,
      out_valid => tag_valid,
      out_ready => plain_take and to_sl(plain_count = 30),
      out_data  => tag_head,
      busy      => open
    );

  plain_in     <= col_valid(0) and tag_valid;
  col_ready(0) <= plain_rdy and tag_valid;
  plain_take   <= plain_in and plain_rdy;

  count : process (clk) is
  begin

    if rising_edge(clk) then
      if plain_take = '1' then
        if plain_count = 30 then
          plain_count <= 0;
        else
          plain_count <= plain_count + 1;
        end if;
      end if;
      if rst = '1' then
        plain_count <= 0;
      end if;
    end if;

  end process count;

  engine : entity work.fastnms_orb_describe
    generic map (
      LANES       => LANES,
      RECORD_BITS => RECORD_BITS
    )
    port map (
      clk            => clk,
      rst            => rst,
      plain_valid    => plain_in,
      plain_ready    => plain_rdy,
      plain_column   => columns(0)(31 * 8 - 1 downto 0),
      plain_record   => tag_head,
      blurred_valid  => col_valid(1),
      blurred_ready  => col_ready(1),
      blurred_column => columns(1),
      out_valid      => out_valid,
      out_ready      => out_ready,
      out_record     => result,
      out_angle      => out_angle,
      out_descriptor => out_descriptor
    );

  out_x     <= unsigned(result(RECORD_BITS - 1 downto Y_BITS + SCORE_BITS));
  out_y     <= unsigned(result(Y_BITS + SCORE_BITS - 1 downto SCORE_BITS));
  out_score <= unsigned(result(SCORE_BITS - 1 downto 0));

end architecture rtl;
