-- Region NMS (the paper's streaming NMS): one record per 4- or 8-connected
-- region of corner pixels, its maximum score, a tie going to the region's
-- first pixel in raster order. One pixel per clock whatever the content.
--
-- The algorithm is golden/region_stream.py, step for step; the design, its
-- invariants and the clock schedule are in docs/fastnms_nms_region.md. In
-- short: the classes of one row's runs never cross, so the previous row's open
-- classes nest and live on a stack; per run (slot = start column / 2) a bit
-- says whether it is the first run of its class in its row (head table, one
-- bank per row parity) and one whether it is the last (last table): a first
-- run pushes its class, a later run continues the top, a last run pops it. A
-- data table holds each class's best key at its first run's slot, and every
-- column changes only the stack's top two entries, the current run's class
-- and one word of each table.
--
-- A column's step is two processes a clock apart: the control makes its
-- decisions on flags only (the stack entries', attached, active) and
-- registers them as the column's operation (op); the data path carries it
-- out on the next clock (slots, keys, table writes, records).
--
-- Clocks: the current row steps one column per accepted pixel; rows >= 1 step
-- the previous row's reader with it. After a frame's last pixel the reader
-- flushes that row alone, one column per clock, while the next frame's first
-- row (which has no previous row) comes in; then the end-of-frame beat.
-- in_ready drops only when the record FIFO has no room, and, for a frame
-- narrower than the one before it, from its first row's last pixel until
-- the flush's last column, then two PRIME clocks (after a one-row frame, the
-- next frame waits instead).
--
-- The input is the detector's per-pixel stream: well formed (every line
-- cfg_width pixels ending with in_eol, the frame's last pixel with in_eof, the
-- next pixel the next frame's first); in_sof is only checked, in simulation.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_nms_region is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE_BITS   : positive := 8;
    CONNECTIVITY : positive := 8
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    cfg_width : in    unsigned(bits_for(MAX_WIDTH) - 1 downto 0);
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_corner : in    std_logic;
    in_score  : in    unsigned(SCORE_BITS - 1 downto 0);
    in_sof    : in    std_logic;
    in_eol    : in    std_logic;
    in_eof    : in    std_logic;
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_x     : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    out_y     : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    out_score : out   unsigned(SCORE_BITS - 1 downto 0);
    out_eof   : out   std_logic
  );
end entity fastnms_nms_region;

architecture rtl of fastnms_nms_region is

  constant XB : positive := clog2(MAX_WIDTH);
  constant YB : positive := bits_for(MAX_HEIGHT);
  constant WB : positive := bits_for(MAX_WIDTH);
  -- Key: score, then the inverted row and column, so that the larger key is
  -- the better pixel (higher score, then earlier in raster order).
  constant KB : positive := SCORE_BITS + YB + XB;
  -- Slots: one per two columns (two runs of a row start at least two apart).
  -- SB holds every slot.
  constant SLOTS : positive := (MAX_WIDTH + 1) / 2;
  constant SB    : positive := bits_for(SLOTS);
  -- Open classes of the previous row at once (golden/region_stream.py,
  -- stack_depth): the top two are registers, the others in a RAM.
  constant STACK_DEPTH : positive := (MAX_WIDTH + 1) / 4 + 1;
  constant STACK_WORDS : positive := maximum(STACK_DEPTH - 2, 1);
  constant DB          : positive := bits_for(STACK_DEPTH);
  constant ENTRY_BITS  : positive := 2 * SB + KB;
  constant OUT_BITS    : positive := 1 + XB + YB + SCORE_BITS;

  subtype slot_t is unsigned(SB - 1 downto 0);

  subtype key_t is unsigned(KB - 1 downto 0);

  -- A previous-row class on the stack, in two parts: its flags, which the
  -- control (the step's decisions) keeps, and its slots and key, which the
  -- data path keeps one clock later.
  type flags_t is record
    last   : std_logic; -- its run under the reader is its last in the previous row
    runs   : std_logic; -- it has runs in the current row (head and tail are valid)
    merged : std_logic; -- also holds the class of the entry below
  end record flags_t;

  type entry_t is record
    head : slot_t; -- slot of its first run in the current row
    tail : slot_t; -- slot of its latest run in the current row
    key  : key_t;  -- best pixel (valid unless merged into the entry above)
  end record entry_t;

  constant FLAG_BITS : positive := 3;

  function pack (f : flags_t) return std_logic_vector is
  begin

    return f.last & f.runs & f.merged;

  end function pack;

  function unpack (v : std_logic_vector(FLAG_BITS - 1 downto 0)) return flags_t is
  begin

    return (last => v(2), runs => v(1), merged => v(0));

  end function unpack;

  function pack (e : entry_t) return std_logic_vector is
  begin

    return std_logic_vector(e.head) & std_logic_vector(e.tail) & std_logic_vector(e.key);

  end function pack;

  function unpack (v : std_logic_vector(ENTRY_BITS - 1 downto 0)) return entry_t is
    variable e : entry_t;
  begin

    e.head := unsigned(v(ENTRY_BITS - 1 downto ENTRY_BITS - SB));
    e.tail := unsigned(v(ENTRY_BITS - SB - 1 downto KB));
    e.key  := unsigned(v(KB - 1 downto 0));
    return e;

  end function unpack;

  -- The operation of one column, decided by the control and carried out by
  -- the data path on the next clock: every selection the data path makes
  -- is on these registered bits.
  type op_t is record
    push        : std_logic; -- a previous-row run pushes its class ...
    push_ram    : std_logic; -- ... and the second entry goes to the stack RAM
    start       : std_logic; -- a current run starts
    attach      : std_logic; -- the current run's class joins the top's ...
    attach_runs : std_logic; -- ... which already has current-row runs
    takeover    : std_logic; -- the pushed class takes over the one below
    pix_top     : std_logic; -- the pixel joins the top's class
    pix_cur     : std_logic; -- the pixel joins the current run's class
    cur_final   : std_logic; -- the current run's class ends alone: finalize
    pop         : std_logic; -- the top pops ...
    pop_ram     : std_logic; -- ... and the third entry is read from the RAM
    pop_merged  : std_logic; -- ... hands its class to the entry below
    pop_detach  : std_logic; -- ... goes on as the current run's class
    pop_final   : std_logic; -- ... is finalized
    pop_emit    : std_logic; -- ... closes: its record leaves
    -- The data path's key selections, decoded from the above and gated by
    -- the side that steps, so that its key operands are one LUT from
    -- registers (apply, Keys).
    k_base_pushed : std_logic; -- the top's class is a pushed one
    k_merge_cur   : std_logic; -- the current class merges into it
    k_merge_pix   : std_logic; -- the pixel starting a run merges into it
    k_merge_top   : std_logic; -- the top's class merges into the pushed one
    k_pix         : std_logic; -- the pixel joins it
    k_keep_top    : std_logic; -- the top's key stays on top (a push, then a pop)
    k_take_second : std_logic; -- the second's key comes on top (a pop)
    k_cur_start   : std_logic; -- the current class starts at the pixel
    k_cur_pix     : std_logic; -- the pixel joins the current class
    k_detach      : std_logic; -- the merged class goes on as the current one
    k_final       : std_logic; -- the merged class is finalized
    rv            : std_logic; -- the reader stepped: its operations count
    cv            : std_logic; -- the current row stepped: its operations count
    bank          : std_logic; -- the current row's head table bank
    r_col0        : std_logic; -- the reader is at its row's column 0
    ahead_slot    : slot_t;    -- the slot the reader reads ahead (the data table's read)
    flush_ends    : std_logic; -- a flush's last column: the end-of-frame beat is due
    score         : unsigned(SCORE_BITS - 1 downto 0);
    cx            : unsigned(XB - 1 downto 0);
    cy            : unsigned(YB - 1 downto 0);
    ram_wa        : unsigned(clog2(STACK_WORDS) - 1 downto 0);
    ram_ra        : unsigned(clog2(STACK_WORDS) - 1 downto 0);
  end record op_t;

  function score_of (k : key_t) return unsigned is
  begin

    return k(KB - 1 downto XB + YB);

  end function score_of;

  -- The slots a column's table writes are at: the top's head and tail, the
  -- current class's, the pixel's, zero; chosen by a one-hot selection
  -- (pick: a flat AND-OR, not a chain of choices).
  constant S_TOP_HEAD : natural := 0;
  constant S_TOP_TAIL : natural := 1;
  constant S_CUR_HEAD : natural := 2;
  constant S_CUR_TAIL : natural := 3;
  constant S_PIX      : natural := 4;
  constant S_ZERO     : natural := 5;

  subtype slot_sel_t is std_logic_vector(0 to 5);

  type slot_array is array (slot_sel_t'range) of slot_t;

  function one_hot (i : natural) return slot_sel_t is
    variable s : slot_sel_t := (others => '0');
  begin

    s(i) := '1';
    return s;

  end function one_hot;

  function pick (sel : slot_sel_t; cands : slot_array) return slot_t is
    variable r : slot_t := (others => '0');
  begin

    for i in sel'range loop
      r := r or (cands(i) and (slot_t'range => sel(i)));
    end loop;

    return r;

  end function pick;

  function pick (sel : slot_sel_t; flags : slot_sel_t) return std_logic is
  begin

    return or (sel and flags);

  end function pick;

  function slot_of (x : unsigned) return slot_t is
  begin

    return resize(x(x'high downto 1), SB);

  end function slot_of;

  -- Table write requests: the step's first and, at the end of a row, second.
  type data_write_t is record
    en   : std_logic;
    addr : slot_t;
    data : key_t;
  end record data_write_t;

  -- A bit table's write: the slot, then the bank (the row's parity; '0' in
  -- the last table, which has one bank).
  subtype bit_addr_t is unsigned(SB downto 0);

  type bit_write_t is record
    en   : std_logic;
    addr : bit_addr_t;
    data : std_logic;
  end record bit_write_t;

  -- (No constant wider than 32 bits: GHDL's Verilog output writes those as
  -- strings. The data of a write that is not enabled does not matter.)
  constant NO_BIT_WRITE : bit_write_t := (en => '0', addr => (others => '0'), data => '0');

  -- A table's reads, two columns ahead of the reader: the read in the RAM
  -- (its address, and a write to it since, which the RAM may not show), and
  -- the word of the reader's column, a register. Writes after a read update
  -- it: the previous row's last writes land while the next row's first
  -- columns are read. Words are key wide; the bit tables use bit 0.
  subtype word_t is std_logic_vector(KB - 1 downto 0);

  type ahead_t is record
    addr1 : bit_addr_t;
    fwd_v : std_logic;
    fwd   : word_t;
    addr2 : bit_addr_t;
    word2 : word_t;
  end record ahead_t;

  constant AHEAD_RESET : ahead_t :=
  (
    addr1 => (others => '0'),
    fwd_v => '0',
    fwd   => (others => '0'),
    addr2 => (others => '0'),
    word2 => (others => '0')
  );

  -- The reads after one clock: they move on with a reader step (reading ra),
  -- and take the write (w_en, w_addr, w_data) that lands at the clock's end.
  function ahead_next (
    p      : ahead_t;
    w_en   : std_logic;
    w_addr : bit_addr_t;
    w_data : word_t;
    step   : std_logic;
    ra     : bit_addr_t;
    rdata  : word_t
  ) return ahead_t is
    variable n : ahead_t;
  begin

    n := p;

    if step = '1' then
      n.addr2 := p.addr1;
      if w_en = '1' and w_addr = p.addr1 then
        n.word2 := w_data;
      elsif p.fwd_v = '1' then
        n.word2 := p.fwd;
      else
        n.word2 := rdata;
      end if;
      n.addr1 := ra;
      n.fwd_v := w_en and to_sl(w_addr = ra);
      n.fwd   := w_data;
    else
      if w_en = '1' and w_addr = p.addr2 then
        n.word2 := w_data;
      end if;
      if w_en = '1' and w_addr = p.addr1 then
        n.fwd_v := '1';
        n.fwd   := w_data;
      end if;
    end if;

    return n;

  end function ahead_next;

  function word (b : std_logic) return word_t is
  begin

    return (KB - 1 downto 1 => '0') & b;

  end function word;

  -- Input, through a skid buffer (registered in_ready).
  signal px_valid  : std_logic;
  signal px_ready  : std_logic;
  signal px_data   : std_logic_vector(WB + SCORE_BITS + 3 downto 0);
  signal px_width  : unsigned(WB - 1 downto 0);
  signal px_corner : std_logic;
  signal px_score  : unsigned(SCORE_BITS - 1 downto 0);
  signal px_sof    : std_logic;
  signal px_eol    : std_logic;
  signal px_eof    : std_logic;

  -- Current row.
  signal cx          : unsigned(XB - 1 downto 0);
  signal cy          : unsigned(YB - 1 downto 0);
  signal cw          : unsigned(WB - 1 downto 0);
  signal first_row   : std_logic;
  signal frame_start : std_logic;
  signal cm          : std_logic;
  signal attached    : std_logic;
  signal active      : std_logic;

  -- Reader of the previous row: its column, its row's last column, the
  -- prefetched bits (pm at rcol - 1, p0 at rcol; the row memory's output is
  -- the bit at rcol + 1, or at column 0 of the next row after the last) and
  -- the row memory address it reads next, (rcol + 2) mod its width.
  signal rcol          : unsigned(XB - 1 downto 0);
  signal r_lastcol     : unsigned(XB - 1 downto 0);
  signal r_ahead       : unsigned(XB - 1 downto 0);
  signal pm            : std_logic;
  signal p0            : std_logic;
  signal flushing      : std_logic;
  signal flush_pending : std_logic;
  signal flush_w       : unsigned(WB - 1 downto 0);
  signal primed        : std_logic;
  signal prime_st      : unsigned(1 downto 0);
  -- cx is the row's penultimate column, and r_ahead >= 2, as registers
  -- (the row memory's read address is chosen on registers only); c_prepen
  -- is the column before the penultimate.
  signal c_prepen    : unsigned(XB - 1 downto 0);
  signal c_at_penult : std_logic;
  signal r_reads     : std_logic;

  -- Stack flags (the control's): top, second, and a copy of the flag RAM's
  -- word below them (refreshed two clocks after a pop: third_rd1, third_rd2).
  signal depth : unsigned(DB - 1 downto 0);
  -- depth - 2, - 3 and - 4 beside it, so that the stack RAMs' addresses and
  -- the tests on the depth are registers (a sign bit each), not arithmetic
  -- after the step's decisions; depth itself is for the assertions.
  signal below2    : signed(DB downto 0);
  signal below3    : signed(DB downto 0);
  signal below4    : signed(DB downto 0);
  signal top       : flags_t;
  signal second    : flags_t;
  signal third     : flags_t;
  signal third_rd1 : std_logic;
  signal third_rd2 : std_logic;
  -- A last bit taken at column 0 may be rewritten by the previous row's
  -- last column one clock later (the data path writes a clock after the
  -- control decides): the next clock takes that write.
  signal fix_last : std_logic;

  -- The data path, one clock after the control: its operation, the current
  -- class's slots and key, the stack's slots and keys (top, second, third).
  -- (sim_zeros: the compares made every clock read c_key, the stack and
  -- the tables before their first write.)
  signal op         : op_t;
  signal c_key      : key_t   := unsigned(sim_zeros(KB));
  signal c_head     : slot_t  := unsigned(sim_zeros(SB));
  signal c_tail     : slot_t  := unsigned(sim_zeros(SB));
  signal d_top      : entry_t := unpack(sim_zeros(ENTRY_BITS));
  signal d_second   : entry_t := unpack(sim_zeros(ENTRY_BITS));
  signal d_third    : entry_t := unpack(sim_zeros(ENTRY_BITS));
  signal d_third_rd : std_logic;

  -- Memories. Read enables and addresses are this clock's steps; writes are
  -- registered.
  signal row_we : std_logic;
  signal row_wa : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal row_wd : std_logic;
  signal row_re : std_logic;
  signal row_ra : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal row_rd : std_logic;
  -- The row memory holds two columns per word (yosys maps a one-bit LUT RAM
  -- to RAM64M cells using one of their three bits): the even column's bit of
  -- the pair being written, and the column of the word being read.
  signal row_wdata  : std_logic_vector(1 downto 0);
  signal row_word   : std_logic_vector(1 downto 0);
  signal row_even   : std_logic;
  signal row_lane   : std_logic;
  signal data_w     : data_write_t;
  signal data_spare : data_write_t;
  signal data_rd    : std_logic_vector(KB - 1 downto 0);
  signal ahead_slot : slot_t := unsigned(sim_zeros(SB));
  signal head_w     : bit_write_t;
  signal head_spare : bit_write_t;
  signal head_rd    : std_logic_vector(0 downto 0);
  signal last_w     : bit_write_t;
  signal last_spare : bit_write_t;
  signal last_rd    : std_logic_vector(0 downto 0);
  signal data_ahead : ahead_t;
  signal head_ahead : ahead_t;
  signal last_ahead : ahead_t;
  -- data_w writes slot 0 (the previous row's last column's write, which the
  -- next row's column 0 takes as it lands).
  signal data_w0 : std_logic;
  -- The write landing now is the key of a push at column 0 (data_w0 and
  -- the reader at column 0), a register.
  signal data_landing : std_logic;
  signal spare_w0     : std_logic;
  -- The bit writes' slots, 0 or 1, flagged with them: the previous row's
  -- last writes land as the next row's first columns take those words
  -- (column 0 and 1: slot 0, last bit; column 2: slot 1, the spare).
  signal last_w_s0     : std_logic;
  signal last_w_s1     : std_logic;
  signal head_w_s1     : std_logic;
  signal last_spare_s0 : std_logic;
  signal last_spare_s1 : std_logic;
  signal head_spare_s1 : std_logic;
  -- The reader's column is in slot 0: its run is the first of the row, so
  -- the first of its class.
  signal r_slot0 : std_logic;
  -- The head bit of the previous-row run at rcol (the first of its class).
  signal run_head_r : std_logic;
  signal r_col0     : std_logic; -- rcol = 0
  signal r_col1     : std_logic; -- rcol = 1
  signal r_col2     : std_logic; -- rcol = 2

  -- Row parity of the current row and of the reader's row (a bank of the
  -- head table each): counted over all rows of all frames, so the row being
  -- read and the row being written are never in the same bank.
  signal cur_bank : std_logic;
  signal r_bank   : std_logic;
  -- The stack's RAMs, below its registers: flags (the control's) and
  -- slots and keys (the data path's, written and read a clock later).
  signal flags_we : std_logic;
  signal flags_wa : unsigned(clog2(STACK_WORDS) - 1 downto 0);
  signal flags_wd : std_logic_vector(FLAG_BITS - 1 downto 0);
  signal flags_re : std_logic;
  signal flags_ra : unsigned(clog2(STACK_WORDS) - 1 downto 0);
  signal flags_rd : std_logic_vector(FLAG_BITS - 1 downto 0);
  signal stack_we : std_logic;
  signal stack_wa : unsigned(clog2(STACK_WORDS) - 1 downto 0);
  signal stack_wd : std_logic_vector(ENTRY_BITS - 1 downto 0);
  signal stack_re : std_logic;
  signal stack_ra : unsigned(clog2(STACK_WORDS) - 1 downto 0);
  signal stack_rd : std_logic_vector(ENTRY_BITS - 1 downto 0);

  -- Records.
  signal rec_valid   : std_logic;
  signal rec_eof     : std_logic;
  signal rec_x       : unsigned(XB - 1 downto 0);
  signal rec_y       : unsigned(YB - 1 downto 0);
  signal rec_score   : unsigned(SCORE_BITS - 1 downto 0);
  signal rec_room    : std_logic;
  signal eof_pending : std_logic;
  signal q_data      : std_logic_vector(OUT_BITS - 1 downto 0);

  -- This clock's steps: the flush, the current row, both in lock-step (a row
  -- >= 1), the reader (lock-step or flush), a first row's last two columns
  -- priming the reader.
  signal flush_go  : std_logic;
  signal cur_go    : std_logic;
  signal cstep     : std_logic;
  signal lock      : std_logic;
  signal rstep     : std_logic;
  signal r_last    : std_logic; -- r_ahead = 1, predicted
  signal checks_on : boolean;   -- false until the first reset: the invariants hold from then on
  -- The row memory's last column written (simulation only: the order is asserted).
  signal row_last_wa : integer range -1 to MAX_WIDTH := -1;
  signal r_next      : unsigned(XB - 1 downto 0);
  signal f_prime     : std_logic;
  signal row_next0   : std_logic; -- this clock reads the next row's column 0
  signal holds0      : std_logic; -- the row memory's output is that bit

begin

  assert CONNECTIVITY = 4 or CONNECTIVITY = 8
    report "fastnms_nms_region: CONNECTIVITY must be 4 or 8"
    severity failure;
  assert MAX_WIDTH >= 3
    report "fastnms_nms_region: MAX_WIDTH must be at least 3"
    severity failure;

  pixel_input : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => WB + SCORE_BITS + 4
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => in_valid,
      in_ready  => in_ready,
      in_data   => std_logic_vector(cfg_width) & in_corner & in_sof & in_eol & in_eof &
                   std_logic_vector(in_score),
      out_valid => px_valid,
      out_ready => px_ready,
      out_data  => px_data
    );

  -- cfg_width travels with each pixel: it must hold when a frame's first
  -- pixel is accepted, which is before that pixel steps.
  px_width  <= unsigned(px_data(WB + SCORE_BITS + 3 downto SCORE_BITS + 4));
  px_corner <= px_data(SCORE_BITS + 3);
  px_sof    <= px_data(SCORE_BITS + 2);
  px_eol    <= px_data(SCORE_BITS + 1);
  px_eof    <= px_data(SCORE_BITS);
  px_score  <= unsigned(px_data(SCORE_BITS - 1 downto 0));

  -- The flush steps whenever the record FIFO has room. The current row steps
  -- with room too; rows >= 1 need the reader free and primed; a first row
  -- steps with the flush, so it never overtakes it, and its last column
  -- waits for the flush's last (it writes the slot of the next column, which
  -- a wider flush still reads).
  flush_go <= flushing and rec_room;

  current_row_may_step : process (all) is
  begin

    if first_row = '1' then
      if flush_pending = '1' then
        cur_go <= '0';
      elsif flushing = '0' then
        cur_go <= rec_room;
      elsif px_eol = '0' or r_last = '1' then
        -- In step with the flush, which started first and steps whenever
        -- the row can: the row stays at or behind it (asserted below).
        cur_go <= rec_room;
      else
        cur_go <= '0';
      end if;
    else
      cur_go <= rec_room and primed and not flushing and not flush_pending;
    end if;

  end process current_row_may_step;

  px_ready <= cur_go;
  -- The current pixel goes into the row memory in its own clock, so a read
  -- two columns later (the next row's first columns) finds it there.
  row_we <= cstep;
  row_wa <= cx;
  row_wd <= px_corner;
  cstep  <= cur_go and px_valid;
  -- Written out from registers (the same as cstep and not first_row, and
  -- lock or flush_go), one LUT each: every reader register and operation
  -- bit depends on them.
  lock   <= rec_room and px_valid and primed and not flushing and not flush_pending and
            not first_row;
  rstep  <= rec_room and (flushing or
                          (px_valid and primed and not flush_pending and not first_row));
  r_next <= (others => '0') when r_last = '1' else
            rcol + 1;
  -- A first row reads the next row's first two columns in its last two (the
  -- row memory then holds them); PRIME does the same when a flush held the
  -- port then.
  f_prime <= cstep and first_row and (c_at_penult or px_eol) and not flushing;
  -- The tables are read at the row memory's column, two ahead of the reader;
  -- in its row's last two columns that is slot 0 of the next row (whose head
  -- bit is never read: r_slot0).
  ahead_slot <= slot_of(r_ahead);

  reads : process (all) is
  begin

    -- The address is from registers only (the enable says whether a read
    -- happens): the reader's read two columns ahead (a lock-step row, or a
    -- flush still inside its row), or a read of the next row's column 0
    -- (a first row's penultimate column, PRIME's first clock) or 1.
    row_next0 <= '0';
    row_ra    <= resize(r_ahead, row_ra'length);

    if prime_st = 1 then
      row_ra    <= (others => '0');
      row_next0 <= '1';
    elsif prime_st = 2 then
      row_ra <= to_unsigned(1, row_ra'length);
    elsif first_row = '1' and (flushing = '0' or r_reads = '0') then
      if c_at_penult = '1' then
        row_ra    <= (others => '0');
        row_next0 <= '1';
      else
        row_ra <= to_unsigned(1, row_ra'length);
      end if;
    end if;

    row_re <= '0';

    if rstep = '1' then
      -- A flush does not read past its row.
      row_re <= lock or r_reads;
    elsif f_prime = '1' or prime_st /= 0 then
      row_re <= '1';
    end if;

    -- The same clock's first row step, when the flush's own read is over.
    if rstep = '1' and lock = '0' and r_reads = '0' and cstep = '1' and
       first_row = '1' and (c_at_penult = '1' or px_eol = '1') then
      row_re <= '1';
    end if;

  end process reads;

  -- The control: one column of the step's decisions per clock, on flags
  -- only (the stack entries', attached and active), from registers; the
  -- column's operation goes to the data path (op), which carries it out on
  -- the next clock. The reader and the clock schedule are here too.
  control : process (clk) is

    variable v_top     : flags_t;
    variable v_second  : flags_t;
    variable v_third   : flags_t;
    variable pre_top   : flags_t;
    variable pre_third : flags_t;
    variable v_depth   : unsigned(DB - 1 downto 0);
    variable below     : signed(DB downto 0);
    variable v_att     : std_logic;
    variable v_act     : std_logic;
    variable popped    : flags_t;
    variable pushed    : boolean;
    variable c0        : std_logic;
    variable r_eol     : boolean;
    variable c_eol     : boolean;
    variable touch     : boolean;
    variable o         : op_t;

    variable run_starts : boolean;
    variable flush_ends : boolean;
    variable eof_step   : boolean;
    variable v_primed   : std_logic;
    variable p_start    : boolean;
    variable p_end      : boolean;
    variable run_head   : std_logic;
    variable run_last   : std_logic;
    variable last_now   : std_logic;
    variable fwd_last0  : boolean;
    variable fwd_last1  : boolean;
    variable fwd_head1  : boolean;
    variable next_head  : ahead_t;
    variable next_slot0 : std_logic;
    variable next_col2  : std_logic;

  begin

    if rising_edge(clk) then
      -- The stack's flags before this clock's step: the flag RAM's word
      -- below the second entry (two clocks after a pop), and a last bit
      -- taken at column 0 on the clock before, which the previous row's
      -- last column may rewrite then (the data path writes a clock after the
      -- control decides): that write is in last_w now.
      pre_third := third;
      if third_rd2 = '1' then
        pre_third := unpack(flags_rd);
      end if;
      pre_top := top;
      if fix_last = '1' and last_w.en = '1' and last_w_s0 = '1' then
        pre_top.last := last_w.data;
      end if;
      v_third  := pre_third;
      v_top    := pre_top;
      v_second := second;
      v_depth  := depth;
      v_att    := attached;
      v_act    := active;
      pushed   := false;
      touch    := false;
      below    := below3;

      c0    := px_corner;
      r_eol := r_last = '1';
      c_eol := px_eol = '1';

      o             := op;
      o.push        := '0';
      o.push_ram    := '0';
      o.start       := '0';
      o.attach      := '0';
      o.attach_runs := '0';
      o.takeover    := '0';
      o.pix_top     := '0';
      o.pix_cur     := '0';
      o.cur_final   := '0';
      o.pop         := '0';
      o.pop_ram     := '0';
      o.pop_merged  := '0';
      o.pop_detach  := '0';
      o.pop_final   := '0';
      o.pop_emit    := '0';
      o.flush_ends  := '0';
      o.rv          := rstep;
      o.cv          := cstep;
      o.bank        := cur_bank;
      o.r_col0      := r_col0;
      o.ahead_slot  := ahead_slot;
      o.score       := px_score;
      o.cx          := cx;
      o.cy          := cy;

      -- synthesis translate_off
      if rst = '1' then
        checks_on <= true;
      end if;
      assert not checks_on or rst = '1' or
             (r_last = to_sl(r_ahead = 1) and r_col0 = to_sl(rcol = 0) and
              r_slot0 = to_sl(rcol < 2) and r_col1 = to_sl(rcol = 1) and r_col2 = to_sl(rcol = 2))
        report "fastnms_nms_region: r_last, r_col0, r_col1, r_col2 or r_slot0 out of step"
        severity failure;
      assert not checks_on or rst = '1' or
             (r_reads = to_sl(r_ahead >= 2) and (frame_start = '1' or c_at_penult = to_sl(cx = c_prepen + 1)))
        report "fastnms_nms_region: r_reads or c_at_penult out of step"
        severity failure;
      assert not (cstep = '1' and first_row = '1' and flushing = '1' and cx > rcol)
        report "fastnms_nms_region: a first row overtaking the flush"
        severity failure;
      assert not (lock = '1' and rcol /= cx)
        report "fastnms_nms_region: reader and current row out of step"
        severity failure;
      assert not (lock = '1' and rstep /= cstep)
        report "fastnms_nms_region: a lock-step row with one side stepping"
        severity failure;
      assert lock = (cstep and not first_row) and rstep = (lock or flush_go)
        report "fastnms_nms_region: lock or rstep out of step"
        severity failure;
      -- synthesis translate_on

      -- The step's decisions are made as if both sides stepped, from
      -- registers only: the reader's state (the stack) takes them when the
      -- reader steps (rstep), the current row's (attached, active) when the
      -- current row steps (cstep), and the data path gets both enables with
      -- the operation. Rows >= 1 step both sides together; a first row has
      -- no reader events, a flush no current row (first_row, a register,
      -- says which).

      -- The bits of the previous-row run at rcol. The table writes land a
      -- clock after the step that decides them, so the previous row's last
      -- writes can land as the next row takes their words: at columns 0
      -- and 1 (slot 0; its head bit is known, the run is the row's first)
      -- and at column 2 (slot 1, the last column's second write). Flags
      -- registered with each write say so; the assertions below check that
      -- no other write lands on a word taken.
      p_start   := p0 = '1' and pm = '0';
      p_end     := (pm = '1' and p0 = '0') or (p0 = '1' and r_eol);
      fwd_last0 := last_w.en = '1' and last_w_s0 = '1' and r_slot0 = '1';
      fwd_last1 := last_w.en = '1' and last_w_s1 = '1' and r_col2 = '1';
      run_head  := run_head_r;
      last_now  := last_ahead.word2(0);
      if fwd_last0 or fwd_last1 then
        last_now := last_w.data;
      end if;

      -- synthesis translate_off
      -- The write a registered head bit (run_head_r) took a clock ahead.
      fwd_head1 := head_w.en = '1' and head_w_s1 = '1' and r_col2 = '1' and
                   head_w.addr(0) = r_bank;
      assert not (rstep = '1' and p_start and r_slot0 = '0' and head_w.en = '1' and
                  head_w.addr = head_ahead.addr2 and not fwd_head1)
        report "fastnms_nms_region: a head bit written as the reader takes it"
        severity failure;
      assert not (rstep = '1' and p_start and last_w.en = '1' and
                  last_w.addr = last_ahead.addr2 and not (fwd_last0 or fwd_last1))
        report "fastnms_nms_region: a last bit written as the reader takes it"
        severity failure;
      assert not ((fwd_last0 or fwd_last1) and last_w.addr /= last_ahead.addr2)
        report "fastnms_nms_region: last_w_s0 or last_w_s1 out of step"
        severity failure;
      assert not (fwd_head1 and head_w.addr /= head_ahead.addr2)
        report "fastnms_nms_region: head_w_s1 out of step"
        severity failure;
      assert not checks_on or rst = '1' or
             (fwd_head1 and run_head_r = head_w.data) or
             (not fwd_head1 and run_head_r = (head_ahead.word2(0) or r_slot0))
        report "fastnms_nms_region: run_head_r out of step"
        severity failure;
      assert not (rstep = '1' and p_start and run_head = '0' and v_depth = 0)
        report "fastnms_nms_region: a continuing run without an open class"
        severity failure;
      -- synthesis translate_on

      -- 1. A previous-row run starts at rcol: a run that is not its class's
      -- first continues the top's class (classes nest), a first run pushes.
      if p_start then
        if run_head = '0' then
          v_top.last := last_now;
        else
          o.push     := '1';
          o.push_ram := not below2(DB);
          o.ram_wa   := resize(unsigned(below2(DB - 1 downto 0)), o.ram_wa'length);
          if below2 >= 0 then
            v_third := v_second;
          end if;
          v_second := v_top;
          v_top    := (last => last_now, runs => '0', merged => '0');
          v_depth  := v_depth + 1;
          pushed   := true;
        end if;
      end if;

      -- 2. A current-row run starts: a class of its own for now.
      run_starts := c0 = '1' and cm = '0';
      if run_starts then
        o.start := '1';
        v_att   := '0';
        v_act   := '1';
      end if;

      -- 3. Contact between the current run and the top's run (rows >= 1).
      if first_row = '0' then
        touch := (c0 = '1' and p0 = '1') or
                 (CONNECTIVITY = 8 and ((c0 = '1' and pm = '1') or (cm = '1' and p0 = '1')));
      end if;
      if touch then
        if v_att = '0' then
          o.attach      := '1';
          o.attach_runs := v_top.runs;
          v_top.runs    := '1';
          v_att         := '1';
        elsif pushed then
          -- The current run's class is the entry below: the new entry takes it over.
          o.takeover   := '1';
          v_top.runs   := v_second.runs;
          v_top.merged := '1';
        end if;
      end if;

      -- 4. The pixel joins its run's class.
      if c0 = '1' and cm = '1' then
        o.pix_top := v_att;
        o.pix_cur := not v_att;
      end if;

      -- 5. The current run ends (at cx - 1, or at cx at the end of the row).
      if (cm = '1' and c0 = '0') or (c0 = '1' and c_eol) then
        o.cur_final := not v_att;
        v_act       := '0';
        v_att       := '0';
      end if;

      -- 6. A previous-row run ends: the last run of its class pops it. (In
      -- a flush, the current row's attached is '0': a first row has no
      -- contact.)
      run_last := v_top.last;
      if p_end and run_last = '1' then
        o.pop    := '1';
        popped   := v_top;
        v_top    := v_second;
        v_second := v_third;
        v_depth  := v_depth - 1;
        -- The word below the new second entry: at depth - 3 after a push in
        -- the same column (a one-pixel run at the row's end), else depth - 4.
        if not pushed then
          below := below4;
        end if;
        o.pop_ram := not below(DB);
        o.ram_ra  := resize(unsigned(below(DB - 1 downto 0)), o.ram_ra'length);
        if popped.merged = '1' then
          o.pop_merged := '1';
          v_top.runs   := popped.runs;
        elsif v_act = '1' and v_att = '1' and first_row = '0' then
          o.pop_detach := '1';
          v_att        := '0';
        elsif popped.runs = '1' then
          o.pop_final := '1';
        else
          o.pop_emit := '1';
        end if;
      end if;

      if c_eol then
        v_act := '0';
        v_att := '0';
      end if;

      o.k_base_pushed := o.push and rstep;
      o.k_merge_cur   := o.attach and not o.start and rstep;
      o.k_merge_pix   := o.attach and o.start and rstep;
      o.k_merge_top   := o.takeover and rstep;
      o.k_pix         := o.pix_top and cstep;
      o.k_keep_top    := o.pop and not o.pop_merged and o.push and rstep;
      o.k_take_second := o.pop and not o.pop_merged and not o.push and rstep;
      o.k_cur_start   := o.start and cstep;
      o.k_cur_pix     := o.pix_cur and cstep;
      o.k_detach      := o.pop_detach and rstep;
      o.k_final       := o.pop_final and rstep;

      -- The reader's side.
      flags_we  <= rstep and o.push_ram;
      flags_wa  <= o.ram_wa;
      flags_wd  <= pack(second);
      flags_re  <= rstep and o.pop and o.pop_ram;
      flags_ra  <= o.ram_ra;
      fix_last  <= rstep and to_sl(p_start) and r_col0;
      third_rd2 <= third_rd1 and not (rstep and o.push_ram);
      third_rd1 <= rstep and o.pop and o.pop_ram;
      if rstep = '1' then
        top    <= v_top;
        second <= v_second;
        third  <= v_third;
        depth  <= v_depth;
        if o.push = '1' and o.pop = '0' then
          below2 <= below2 + 1;
          below3 <= below2;
          below4 <= below3;
        elsif o.pop = '1' and o.push = '0' then
          below2 <= below3;
          below3 <= below4;
          below4 <= below4 - 1;
        end if;
      else
        top   <= pre_top;
        third <= pre_third;
      end if;

      -- synthesis translate_off
      assert not (rstep = '1' and v_depth > STACK_DEPTH)
        report "fastnms_nms_region: stack overflow"
        severity failure;
      assert not checks_on or rst = '1' or
             (below2 = signed('0' & depth) - 2 and below3 = signed('0' & depth) - 3 and
              below4 = signed('0' & depth) - 4)
        report "fastnms_nms_region: below2, below3 or below4 out of step with the depth"
        severity failure;
      assert not (lock = '1' and c_eol and v_depth /= 0)
        report "fastnms_nms_region: classes left open at the end of a row"
        severity failure;
      -- synthesis translate_on

      -- The current row's side.
      if cstep = '1' then
        attached <= v_att;
        active   <= v_act;
      end if;

      -- Current row position.
      if cstep = '1' then
        if frame_start = '1' then
          cw       <= px_width;
          c_prepen <= resize(px_width - 3, XB);
        end if;
        -- Widths are at least 3: column 0 is never the penultimate.
        if c_eol then
          c_at_penult <= '0';
        elsif frame_start = '1' then
          c_at_penult <= to_sl(px_width = 3);
        else
          c_at_penult <= to_sl(cx = c_prepen);
        end if;
        frame_start <= px_eof;
        if c_eol then
          cm <= '0';
          cx <= (others => '0');
          if px_eof = '1' then
            cy        <= (others => '0');
            first_row <= '1';
          else
            cy        <= cy + 1;
            first_row <= '0';
          end if;
        else
          cm <= c0;
          cx <= cx + 1;
        end if;
      end if;

      if cstep = '1' and c_eol then
        cur_bank <= not cur_bank;
      end if;
      next_head  := ahead_next(head_ahead, head_w.en, head_w.addr, word(head_w.data),
                               rstep, ahead_slot & r_bank, word(head_rd(0)));
      head_ahead <= next_head;
      -- The head bit of the run the reader takes next, a register: the word
      -- it reads ahead, or the row's first run, or the previous row's last
      -- column's second write (from the spare register: slot 1, taken at
      -- column 2) when it lands as the reader takes that word.
      next_slot0 := r_slot0;
      next_col2  := r_col2;
      if rstep = '1' then
        next_slot0 := r_last or r_col0;
        next_col2  := r_col1;
      end if;
      -- The RAM's output is the last input of the choice (one LUT after the
      -- block RAM, whose clock-to-output is long on ECP5).
      if head_spare.en = '1' and head_spare_s1 = '1' and next_col2 = '1' and
         head_spare.addr(0) = (r_bank xor (rstep and r_last)) then
        run_head_r <= head_spare.data;
      elsif next_slot0 = '1' then
        run_head_r <= '1';
      elsif rstep = '1' and not (head_w.en = '1' and head_w.addr = head_ahead.addr1) and
            head_ahead.fwd_v = '0' then
        run_head_r <= head_rd(0);
      else
        run_head_r <= next_head.word2(0);
      end if;
      last_ahead <= ahead_next(last_ahead, last_w.en, last_w.addr, word(last_w.data),
                               rstep, ahead_slot & '0', word(last_rd(0)));
      if rstep = '1' and r_last = '1' then
        r_bank <= not r_bank;
      end if;

      -- The reader's next column, and its prefetched bits.
      if rstep = '1' then
        rcol    <= r_next;
        r_slot0 <= r_last or r_col0;
        r_col0  <= r_last;
        r_col1  <= r_col0;
        r_col2  <= r_col1;
        if r_ahead = r_lastcol then
          r_ahead <= (others => '0');
        else
          r_ahead <= r_ahead + 1;
        end if;
        r_reads <= to_sl(r_ahead /= r_lastcol and r_ahead /= 0);
        -- Rows are at least 3 wide: after r_ahead = 0 comes 1.
        r_last <= to_sl(r_ahead = 0);
        p0     <= row_rd;
        if r_last = '1' then
          pm <= '0';
        else
          pm <= p0;
        end if;
      elsif (f_prime = '1' and px_eol = '1') or prime_st = 2 then
        -- The next reader row (lock-step or flush) starts at column 0,
        -- where the reader already is (asserted below): a reader row ends
        -- at its last column, and its step there moves it to column 0 two
        -- ahead; only the bits are loaded.
        p0        <= row_rd;
        pm        <= '0';
        r_lastcol <= resize(cw - 1, XB);
      end if;

      -- synthesis translate_off
      assert not (rstep = '0' and ((f_prime = '1' and px_eol = '1') or prime_st = 2) and
                  (rcol /= 0 or r_ahead /= 2))
        report "fastnms_nms_region: the reader primed away from column 0"
        severity failure;
      assert not (checks_on and rst = '0' and flushing = '0' and first_row = '1' and
                  (rcol /= 0 or r_ahead /= 2))
        report "fastnms_nms_region: the reader idle away from column 0"
        severity failure;
      -- The row memory's two columns per word rely on this order.
      if row_we = '1' then
        assert not checks_on or rst = '1' or row_wa = 0 or to_integer(row_wa) = row_last_wa + 1
          report "fastnms_nms_region: the row memory written out of column order"
          severity failure;
        row_last_wa <= to_integer(row_wa);
      end if;
      -- synthesis translate_on

      -- Primed: the reader's prefetch is valid for its next row (lock-step
      -- rows keep it so). A flush spends it; a first row's last column sets it
      -- when its read of column 0 was the last read and no flush moves the
      -- prefetch after it; PRIME sets it.
      flush_ends := flush_go = '1' and r_last = '1';
      if row_re = '1' then
        holds0 <= row_next0;
      end if;
      v_primed := primed;
      if flush_go = '1' then
        v_primed := '0';
      end if;
      if prime_st = 2 then
        v_primed := '1';
      end if;
      if cstep = '1' and c_eol and first_row = '1' and (flushing = '0' or flush_ends) then
        v_primed := holds0;
      end if;
      primed <= v_primed;
      if flush_ends then
        -- The next reader row is a lock-step row of the current frame.
        r_lastcol <= resize(cw - 1, XB);
      end if;
      if lock = '1' and c_eol then
        r_lastcol <= resize(cw - 1, XB);
      end if;
      prime_st <= (others => '0');
      if prime_st = 1 then
        prime_st <= to_unsigned(2, 2);
      end if;

      -- Flush: after a frame's last row, once the reader is free and primed;
      -- on the next clock when frames come back to back.
      eof_step := cstep = '1' and px_eof = '1';
      if flush_ends then
        flushing     <= '0';
        o.flush_ends := '1';
      end if;

      -- synthesis translate_off
      assert not (eof_step and (flushing = '0' or flush_ends) and
                  v_primed /= (not first_row or holds0))
        report "fastnms_nms_region: the flush's start out of step with primed"
        severity failure;
      -- synthesis translate_on

      if eof_step then
        -- The reader is primed after a lock-step row (it steps only
        -- primed), and after a first row if its read of column 0 was the
        -- last (v_primed, written out).
        if (flushing = '0' or flush_ends) and (first_row = '0' or holds0 = '1') then
          flushing  <= '1';
          r_lastcol <= resize(cw - 1, XB);
        else
          flush_pending <= '1';
          flush_w       <= cw;
        end if;
      elsif flush_pending = '1' and (flushing = '0' or flush_ends) and primed = '1' then
        flushing      <= '1';
        flush_pending <= '0';
        r_lastcol     <= resize(flush_w - 1, XB);
      end if;
      if flushing = '0' and primed = '0' and prime_st = 0 and cstep = '0' and
         ((px_valid = '1' and first_row = '0') or flush_pending = '1') then
        prime_st <= to_unsigned(1, 2);
      end if;

      -- synthesis translate_off
      assert not (cstep = '1' and frame_start = '1' and px_sof = '0')
        report "fastnms_nms_region: a frame's first pixel without in_sof"
        severity error;
      -- synthesis translate_on

      op <= o;

      if rst = '1' then
        depth            <= (others => '0');
        below2           <= to_signed(-2, DB + 1);
        below3           <= to_signed(-3, DB + 1);
        below4           <= to_signed(-4, DB + 1);
        attached         <= '0';
        active           <= '0';
        cm               <= '0';
        cx               <= (others => '0');
        cy               <= (others => '0');
        first_row        <= '1';
        frame_start      <= '1';
        rcol             <= (others => '0');
        r_ahead          <= to_unsigned(2, XB);
        r_reads          <= '1';
        run_head_r       <= '1';
        c_at_penult      <= '0';
        r_last           <= '0';
        r_lastcol        <= (others => '0');
        p0               <= '0';
        pm               <= '0';
        flushing         <= '0';
        flush_pending    <= '0';
        primed           <= '0';
        holds0           <= '0';
        prime_st         <= (others => '0');
        flags_we         <= '0';
        flags_re         <= '0';
        third_rd1        <= '0';
        third_rd2        <= '0';
        fix_last         <= '0';
        head_ahead       <= AHEAD_RESET;
        last_ahead       <= AHEAD_RESET;
        r_slot0          <= '1';
        r_col0           <= '1';
        r_col1           <= '0';
        r_col2           <= '0';
        cur_bank         <= '0';
        r_bank           <= '0';
        op.push          <= '0';
        op.push_ram      <= '0';
        op.start         <= '0';
        op.attach        <= '0';
        op.takeover      <= '0';
        op.pix_top       <= '0';
        op.pix_cur       <= '0';
        op.cur_final     <= '0';
        op.pop           <= '0';
        op.pop_ram       <= '0';
        op.rv            <= '0';
        op.cv            <= '0';
        op.flush_ends    <= '0';
        op.k_base_pushed <= '0';
        op.k_merge_cur   <= '0';
        op.k_merge_pix   <= '0';
        op.k_merge_top   <= '0';
        op.k_pix         <= '0';
        op.k_keep_top    <= '0';
        op.k_take_second <= '0';
        op.k_cur_start   <= '0';
        op.k_cur_pix     <= '0';
        op.k_detach      <= '0';
        op.k_final       <= '0';
      end if;
    end if;

  end process control;

  -- The data path: the slots and keys of the column the control stepped on
  -- the clock before (op), with the same operations in the same order; the
  -- table writes, the stack's slots and keys, the records. Slots move by the
  -- operation's bits alone. The keys (Keys, below) and the table writes'
  -- slots (Table writes) are chosen at once, by the operation's bits and
  -- the comparisons, not through the step's sequence of operations.
  apply : process (clk) is

    variable v_top    : entry_t;
    variable v_second : entry_t;
    variable v_third  : entry_t;
    variable v_head   : slot_t;
    variable v_tail   : slot_t;
    variable popped   : entry_t; -- its key is best
    variable dw1      : data_write_t;
    variable dw2      : data_write_t;
    variable hw1      : bit_write_t;
    variable hw2      : bit_write_t;
    variable lw1      : bit_write_t;
    variable lw2      : bit_write_t;
    variable pix      : key_t;
    -- The operations that count (the side that makes them stepped).
    variable pushed    : boolean;
    variable attach    : boolean;
    variable takeover  : boolean;
    variable start     : boolean;
    variable popping   : boolean;
    variable detach    : boolean;
    variable final     : boolean;
    variable cur_final : boolean;
    -- The merge into the top's class (Keys, below): its operands, their
    -- comparisons, the merged key; the current class's key.
    variable base          : key_t;
    variable merge         : key_t;
    variable pix_in        : unsigned(SCORE_BITS - 1 downto 0);
    variable base_ge_merge : boolean;
    variable base_ge_pix   : boolean;
    variable merge_ge_pix  : boolean;
    variable best          : key_t;
    variable cur_ge_pix    : boolean;
    variable cur           : key_t;
    -- The table writes' candidate slots and their flags (Table writes, below).
    variable cands      : slot_array;
    variable slot0      : slot_sel_t;
    variable slot1      : slot_sel_t;
    variable v_head_sel : slot_sel_t;
    variable v_tail_sel : slot_sel_t;
    variable p_head_sel : slot_sel_t;
    variable p_tail_sel : slot_sel_t;
    variable lw1_sel    : slot_sel_t;
    variable lw2_sel    : slot_sel_t;
    variable hw1_sel    : slot_sel_t;
    variable hw2_sel    : slot_sel_t;
    variable dw1_sel    : slot_sel_t;
    variable contact_w  : boolean;
    variable w1_en      : boolean;
    variable w2_en      : boolean;

  begin

    if rising_edge(clk) then
      v_top    := d_top;
      v_second := d_second;
      v_third  := d_third;
      v_head   := c_head;
      v_tail   := c_tail;
      dw1      := (en => '0', addr => c_head, data => c_key);
      dw2      := dw1;
      hw1      := NO_BIT_WRITE;
      hw2      := NO_BIT_WRITE;
      lw1      := NO_BIT_WRITE;
      lw2      := NO_BIT_WRITE;

      -- (The control's k_* bits are these operations, already gated.)
      pushed    := op.k_base_pushed = '1';
      attach    := op.k_merge_cur = '1' or op.k_merge_pix = '1';
      takeover  := op.k_merge_top = '1';
      start     := op.k_cur_start = '1';
      popping   := op.pop = '1' and op.rv = '1';
      detach    := op.k_detach = '1';
      final     := op.k_final = '1';
      cur_final := op.cur_final = '1' and op.cv = '1';
      pix       := op.score & not op.cy & not op.cx;

      -- The stack RAM's word below the second entry, read by the pop on
      -- the clock before (stack_re), straight into its register.
      if d_third_rd = '1' then
        v_third := unpack(stack_rd);
      end if;
      d_third_rd <= stack_re;
      stack_we   <= '0';

      -- Keys. The merge into the top's class (steps 1, 3 and 4 below) has
      -- three operands, each one LUT from registers: its base (the top's
      -- key, or a pushed class's from the data table, or the write landing
      -- there now: the previous row's last, to slot 0, for column 0), the
      -- class merging in (the current class, the pixel starting a run, or
      -- the top taken over; else zero, which no key is: a key's inverted
      -- row is never zero) and the pixel joining it. The pixel comes after
      -- every pixel of a class in raster order, so it wins only with a
      -- higher score.
      if op.k_base_pushed = '0' then
        base := d_top.key;
      elsif data_landing = '1' then
        base := data_w.data;
      else
        base := unsigned(data_ahead.word2);
      end if;
      -- (At most one of them; an AND-OR, one LUT per bit.)
      merge  := (c_key and (c_key'range => op.k_merge_cur)) or
                (pix and (pix'range => op.k_merge_pix)) or
                (d_top.key and (d_top.key'range => op.k_merge_top));
      pix_in := (others => '0');
      if op.k_pix = '1' then
        pix_in := op.score;
      end if;
      -- A tie goes to the first operand: the base, the class merging in,
      -- the pixel. The class merging in, when none does, is zero and
      -- loses to the base; the pixel out of play has score zero. The
      -- pixel is compared on scores (every class's best pixel is before
      -- it), the base and the class merging in on keys.
      base_ge_merge := base >= merge;
      base_ge_pix   := score_of(base) >= pix_in;
      merge_ge_pix  := (op.k_merge_cur = '1' or op.k_merge_pix = '1' or op.k_merge_top = '1') and
                       score_of(merge) >= pix_in;
      if base_ge_merge and base_ge_pix then
        best := base;
      elsif merge_ge_pix then
        best := merge;
      else
        best := pix;
      end if;
      -- The current class's key after steps 2 and 4: the pixel starting it,
      -- or a pixel with a higher score.
      cur_ge_pix := score_of(c_key) >= op.score;
      if op.k_cur_start = '1' or (op.k_cur_pix = '1' and not cur_ge_pix) then
        cur := pix;
      else
        cur := c_key;
      end if;

      -- synthesis translate_off
      assert not (d_third_rd = '1' and popping and not pushed)
        report "fastnms_nms_region: a pop uncovering the stack RAM's word before it is read"
        severity failure;
      assert not (popping and op.pop_emit = '1' and best /= base)
        report "fastnms_nms_region: a closing class merged in its last column"
        severity failure;
      assert data_landing = (data_w0 and op.r_col0)
        report "fastnms_nms_region: data_landing out of step"
        severity failure;
      assert not checks_on or
             ((op.k_merge_cur and op.k_merge_pix) or (op.k_merge_cur and op.k_merge_top) or
              (op.k_merge_pix and op.k_merge_top)) = '0'
        report "fastnms_nms_region: two classes merging in at once"
        severity failure;
      assert not (op.push = '1' and op.rv = '1' and data_w.en = '1' and
                  (data_w.addr & '0') = data_ahead.addr2 and (op.r_col0 = '0' or data_w0 = '0'))
        report "fastnms_nms_region: a key written as the reader takes it"
        severity failure;
      -- synthesis translate_on

      -- Slots and stack moves, step by step.
      -- 1. A pushed class: its key from the data table.
      if pushed then
        if op.push_ram = '1' then
          stack_we <= '1';
          stack_wa <= op.ram_wa;
          stack_wd <= pack(v_second);
          v_third  := v_second;
        end if;
        v_second := v_top;
        v_top    := (head => (others => '0'), tail => (others => '0'), key => base);
      end if;

      -- 2. A current-row run starts: a class of its own for now.
      if start then
        v_head := slot_of(op.cx);
        v_tail := slot_of(op.cx);
      end if;

      -- 3. The current run's class joins the top's, or the pushed class
      -- takes over the one below.
      if attach then
        if op.attach_runs = '0' then
          v_top.head := v_head;
        end if;
        v_top.tail := v_tail;
      elsif takeover then
        v_top.head := v_second.head;
        v_top.tail := v_second.tail;
      end if;

      -- 6. The top pops.
      if popping then
        popped   := v_top;
        v_top    := v_second;
        v_second := v_third;
        if op.pop_merged = '1' then
          v_top := popped;
        elsif detach then
          v_head := popped.head;
          v_tail := popped.tail;
        end if;
      end if;

      -- Table writes (steps 3, 5 and 6), in this order: a contact with a
      -- class that already has current-row runs (its latest run is no
      -- longer its last, this run's class no longer starts at its own first
      -- run); the popped class finalized; the current run's class, if it
      -- ends alone, finalized. A finalized class's key waits at its first
      -- run's slot, which is marked first, and its latest run is marked
      -- last. A port's first write goes out now, its second (only at a
      -- row's last column) from the spare register on the next clock; the
      -- pop's finalize comes first because it can be to slot 0, which the
      -- next row's column 1 reads then. Each write's slot is one of the
      -- column's slot candidates, chosen at once by a one-hot selection;
      -- its slot-0 and slot-1 flags are the candidate's, compared on
      -- registers.
      cands             := (others => (others => '0'));
      cands(S_TOP_HEAD) := d_top.head;
      cands(S_TOP_TAIL) := d_top.tail;
      cands(S_CUR_HEAD) := c_head;
      cands(S_CUR_TAIL) := c_tail;
      cands(S_PIX)      := slot_of(op.cx);
      for i in cands'range loop
        slot0(i) := to_sl(cands(i) = 0);
        slot1(i) := to_sl(cands(i) = 1);
      end loop;
      -- The current class's cands after step 2, and the popped class's
      -- after step 3.
      v_head_sel := one_hot(S_CUR_HEAD);
      v_tail_sel := one_hot(S_CUR_TAIL);
      if start then
        v_head_sel := one_hot(S_PIX);
        v_tail_sel := one_hot(S_PIX);
      end if;
      p_head_sel := one_hot(S_TOP_HEAD);
      p_tail_sel := one_hot(S_TOP_TAIL);
      if pushed and not takeover then
        p_head_sel := one_hot(S_ZERO);
        p_tail_sel := one_hot(S_ZERO);
      end if;
      if attach then
        p_tail_sel := v_tail_sel;
        if op.attach_runs = '0' then
          p_head_sel := v_head_sel;
        end if;
      end if;
      contact_w := attach and op.attach_runs = '1';
      -- First writes.
      w1_en := contact_w or final or cur_final;
      if contact_w then
        lw1_sel := one_hot(S_TOP_TAIL);
        hw1_sel := v_head_sel;
      elsif final then
        lw1_sel := p_tail_sel;
        hw1_sel := p_head_sel;
      else
        lw1_sel := v_tail_sel;
        hw1_sel := v_head_sel;
      end if;
      -- Second writes.
      w2_en := (contact_w and (final or cur_final)) or (final and cur_final);
      if contact_w and final then
        lw2_sel := p_tail_sel;
        hw2_sel := p_head_sel;
      else
        lw2_sel := v_tail_sel;
        hw2_sel := v_head_sel;
      end if;
      if final then
        dw1_sel := p_head_sel;
      else
        dw1_sel := v_head_sel;
      end if;
      dw1 := (en => to_sl(final or cur_final), addr => pick(dw1_sel, cands), data => c_key);
      dw2 := (en => to_sl(final and cur_final), addr => pick(v_head_sel, cands), data => c_key);
      hw1 := (en => to_sl(w1_en), addr => pick(hw1_sel, cands) & op.bank, data => to_sl(not contact_w));
      hw2 := (en => to_sl(w2_en), addr => pick(hw2_sel, cands) & op.bank, data => '1');
      lw1 := (en => to_sl(w1_en), addr => pick(lw1_sel, cands) & '0', data => to_sl(not contact_w));
      lw2 := (en => to_sl(w2_en), addr => pick(lw2_sel, cands) & '0', data => '1');
      -- The keys after step 6: the pop uncovers the entry below (the
      -- second, or the top itself after a push), or leaves the merged
      -- class on top; the popped class (the merged one) goes on as the
      -- current class, is finalized or closes.
      if op.k_keep_top = '1' then
        v_top.key := d_top.key;
      elsif op.k_take_second = '1' then
        v_top.key := d_second.key;
      else
        v_top.key := best;
      end if;
      if op.k_final = '1' then
        dw1.data := best;
      else
        dw1.data := cur;
      end if;
      dw2.data := cur;

      d_top    <= v_top;
      d_second <= v_second;
      d_third  <= v_third;
      if op.k_detach = '1' then
        c_key <= best;
      else
        c_key <= cur;
      end if;
      c_head <= v_head;
      c_tail <= v_tail;

      data_ahead <= ahead_next(data_ahead, data_w.en, data_w.addr & '0', word_t(data_w.data),
                               op.rv, op.ahead_slot & '0', data_rd);

      -- Table writes: the step's first now, a second one on the next clock
      -- (only the last column of a row makes two; the next clock's step
      -- writes nothing). The second data write is the current class's key,
      -- which c_key holds on that clock (the spare register keeps only its
      -- slot; asserted).
      if data_spare.en = '1' then
        data_w        <= (en => '1', addr => data_spare.addr, data => c_key);
        data_w0       <= spare_w0;
        data_landing  <= spare_w0 and r_col0;
        data_spare.en <= '0';
      else
        data_w       <= dw1;
        data_w0      <= dw1.en and pick(dw1_sel, slot0);
        data_landing <= dw1.en and pick(dw1_sel, slot0) and r_col0;
        data_spare   <= dw2;
        spare_w0     <= dw2.en and pick(v_head_sel, slot0);
      end if;
      if head_spare.en = '1' then
        head_w     <= head_spare;
        head_w_s1  <= head_spare_s1;
        head_spare <= NO_BIT_WRITE;
      else
        head_w        <= hw1;
        head_w_s1     <= pick(hw1_sel, slot1);
        head_spare    <= hw2;
        head_spare_s1 <= pick(hw2_sel, slot1);
      end if;
      if last_spare.en = '1' then
        last_w     <= last_spare;
        last_w_s0  <= last_spare_s0;
        last_w_s1  <= last_spare_s1;
        last_spare <= NO_BIT_WRITE;
      else
        last_w        <= lw1;
        last_w_s0     <= pick(lw1_sel, slot0);
        last_w_s1     <= pick(lw1_sel, slot1);
        last_spare    <= lw2;
        last_spare_s0 <= pick(lw2_sel, slot0);
        last_spare_s1 <= pick(lw2_sel, slot1);
      end if;

      -- synthesis translate_off
      assert not (data_spare.en = '1' and c_key /= data_spare.data)
        report "fastnms_nms_region: the second data write's key out of step"
        severity failure;
      assert not ((data_spare.en = '1' and dw1.en = '1') or (head_spare.en = '1' and hw1.en = '1') or
                  (last_spare.en = '1' and lw1.en = '1'))
        report "fastnms_nms_region: table writes on consecutive clocks"
        severity failure;
      assert not (last_spare.en = '0' and lw2.en = '1' and lw2.addr(SB downto 1) = 0)
        report "fastnms_nms_region: a second last-bit write to slot 0"
        severity failure;
      -- synthesis translate_on

      -- Records: a closed region, or the end-of-frame beat in a clock
      -- without one (after the flush's last column's record, if any).
      rec_valid <= '0';
      if op.flush_ends = '1' then
        eof_pending <= '1';
      end if;
      -- A class that closes had no merge and no pixel in its last column
      -- (it has no current-row runs): its key is the base (asserted).
      if popping and op.pop_emit = '1' then
        rec_valid <= '1';
        rec_eof   <= '0';
        rec_x     <= not base(XB - 1 downto 0);
        rec_y     <= not base(XB + YB - 1 downto XB);
        rec_score <= base(KB - 1 downto XB + YB);
      elsif eof_pending = '1' and rec_room = '1' then
        -- Separate narrow registers: GHDL's Verilog output writes a constant
        -- vector of more than 32 bits as a string (ASCII digits).
        rec_valid   <= '1';
        rec_eof     <= '1';
        rec_x       <= (others => '1');
        rec_y       <= (others => '1');
        rec_score   <= (others => '0');
        eof_pending <= op.flush_ends;
      end if;

      if rst = '1' then
        eof_pending   <= '0';
        rec_valid     <= '0';
        stack_we      <= '0';
        d_third_rd    <= '0';
        data_w.en     <= '0';
        data_w0       <= '0';
        data_landing  <= '0';
        data_spare.en <= '0';
        head_w        <= NO_BIT_WRITE;
        head_spare    <= NO_BIT_WRITE;
        last_w        <= NO_BIT_WRITE;
        last_spare    <= NO_BIT_WRITE;
        data_ahead    <= AHEAD_RESET;
      end if;
    end if;

  end process apply;

  -- The stack RAM is read in the pop's own clock, from the operation's
  -- registers: its word is the third entry on the next clock (pops without
  -- a push between them are at least two columns apart, asserted).
  stack_re <= op.pop and op.pop_ram and op.rv;
  stack_ra <= op.ram_ra;

  -- Two columns per word. A row is written in column order, so a word is
  -- written at its even column (both bits that column's: the odd one is
  -- written next) and again at its odd column, with the even column's bit
  -- kept from then. Every bit is read after the clock that writes it, and
  -- the previous row's bits of a word are all read before the current row
  -- writes it (the reader is two columns ahead of the writer, or further
  -- during a flush); a read in the clock of a write to its word gets the
  -- word before it.
  row_pairs : process (clk) is
  begin

    if rising_edge(clk) then
      if row_we = '1' and row_wa(0) = '0' then
        row_even <= row_wd;
      end if;
      if row_re = '1' then
        row_lane <= row_ra(0);
      end if;
    end if;

  end process row_pairs;

  row_memory : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => (MAX_WIDTH + 1) / 2,
      WIDTH => 2
    )
    port map (
      clk     => clk,
      wr_en   => row_we,
      wr_addr => resize(shift_right(row_wa, 1), clog2((MAX_WIDTH + 1) / 2)),
      wr_data => row_wdata,
      rd_en   => row_re,
      rd_addr => resize(shift_right(row_ra, 1), clog2((MAX_WIDTH + 1) / 2)),
      rd_data => row_word
    );

  row_wdata <= row_wd & row_even when row_wa(0) = '1' else
               row_wd & row_wd;
  row_rd    <= row_word(1) when row_lane = '1' else
               row_word(0);

  data_table : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => SLOTS,
      WIDTH => KB
    )
    port map (
      clk     => clk,
      wr_en   => data_w.en,
      wr_addr => resize(data_w.addr, clog2(SLOTS)),
      wr_data => std_logic_vector(data_w.data),
      rd_en   => op.rv,
      rd_addr => resize(op.ahead_slot, clog2(SLOTS)),
      rd_data => data_rd
    );

  -- One bit per word: LUT RAM.
  head_table : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => 2 * SLOTS,
      WIDTH => 1,
      STYLE => "distributed"
    )
    port map (
      clk     => clk,
      wr_en   => head_w.en,
      wr_addr => resize(head_w.addr, clog2(2 * SLOTS)),
      wr_data => (0 => head_w.data),
      rd_en   => rstep,
      rd_addr => resize(ahead_slot & r_bank, clog2(2 * SLOTS)),
      rd_data => head_rd
    );

  last_table : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => SLOTS,
      WIDTH => 1,
      STYLE => "distributed"
    )
    port map (
      clk     => clk,
      wr_en   => last_w.en,
      wr_addr => resize(last_w.addr(SB downto 1), clog2(SLOTS)),
      wr_data => (0 => last_w.data),
      rd_en   => rstep,
      rd_addr => resize(ahead_slot, clog2(SLOTS)),
      rd_data => last_rd
    );

  -- Three bits per word: LUT RAM.
  stack_flags : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => STACK_WORDS,
      WIDTH => FLAG_BITS,
      STYLE => "distributed"
    )
    port map (
      clk     => clk,
      wr_en   => flags_we,
      wr_addr => flags_wa,
      wr_data => flags_wd,
      rd_en   => flags_re,
      rd_addr => flags_ra,
      rd_data => flags_rd
    );

  stack_memory : entity work.fastnms_ram_sdp
    generic map (
      DEPTH => STACK_WORDS,
      WIDTH => ENTRY_BITS
    )
    port map (
      clk     => clk,
      wr_en   => stack_we,
      wr_addr => stack_wa,
      wr_data => stack_wd,
      rd_en   => stack_re,
      rd_addr => stack_ra,
      rd_data => stack_rd
    );

  records : entity work.fastnms_fifo
    generic map (
      DEPTH => 8,
      WIDTH => OUT_BITS,
      STYLE => "distributed"
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => rec_valid,
      in_ready  => open,
      in_room2  => open,
      in_room3  => rec_room,
      in_spare  => open,
      in_data   => rec_eof & std_logic_vector(rec_x) & std_logic_vector(rec_y) &
                   std_logic_vector(rec_score),
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => q_data,
      busy      => open
    );

  out_eof   <= q_data(OUT_BITS - 1);
  out_x     <= unsigned(q_data(OUT_BITS - 2 downto YB + SCORE_BITS));
  out_y     <= unsigned(q_data(YB + SCORE_BITS - 1 downto SCORE_BITS));
  out_score <= unsigned(q_data(SCORE_BITS - 1 downto 0));

end architecture rtl;
