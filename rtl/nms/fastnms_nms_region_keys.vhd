-- The region NMS's key data path: the control's operation (op) carried out
-- on slots, keys and areas a clock later; the stack's slots and keys, the
-- table writes and the records.
-- Datasheet: docs/fastnms_nms_region.md
-- Contract: docs/design/region_nms_pipeline.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_nms_region_pkg.all;

entity fastnms_nms_region_keys is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 4095;
    SCORE_BITS : positive := 8
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- The column's operation (fastnms_nms_region_control), registered.
    cmd : in    command_t(slot(slot_bits(MAX_WIDTH) - 1 downto 0), score(SCORE_BITS - 1 downto 0),
                          cx(clog2(MAX_WIDTH) - 1 downto 0), cy(bits_for(MAX_HEIGHT) - 1 downto 0),
                          ram_wa(clog2(stack_ram_words(MAX_WIDTH)) - 1 downto 0),
                          ram_ra(clog2(stack_ram_words(MAX_WIDTH)) - 1 downto 0));
    -- The reader is at its row's column 0 now (fastnms_nms_region_schedule):
    -- a write to slot 0 landing on the next clock is the key a push there takes.
    r_col0 : in    std_logic;
    -- The data word (key & area) of the reader's column (fastnms_nms_region_tables).
    data_word : in    unsigned(data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS) - 1 downto 0);
    -- The table writes, registered (to fastnms_nms_region_tables; the last
    -- table's also to the control).
    writes : out   writes_t(data(slot(slot_bits(MAX_WIDTH) - 1 downto 0),
                                 word(data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS) - 1 downto 0)),
                            head(addr(slot_bits(MAX_WIDTH) downto 0)),
                            head_spare(addr(slot_bits(MAX_WIDTH) downto 0)),
                            last(addr(slot_bits(MAX_WIDTH) downto 0)));
    -- Records, to the record FIFO, which has room for the records in flight
    -- (rec_room: the end-of-frame beat waits for it).
    rec_room  : in    std_logic;
    rec_valid : out   std_logic;
    rec_eof   : out   std_logic;
    rec_x     : out   unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    rec_y     : out   unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
    rec_score : out   unsigned(SCORE_BITS - 1 downto 0);
    rec_area  : out   unsigned(AREA_BITS - 1 downto 0)
  );
end entity fastnms_nms_region_keys;

architecture rtl of fastnms_nms_region_keys is

  constant XB          : positive := clog2(MAX_WIDTH);
  constant YB          : positive := bits_for(MAX_HEIGHT);
  constant KB          : positive := key_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS);
  constant SB          : positive := slot_bits(MAX_WIDTH);
  constant STACK_WORDS : positive := stack_ram_words(MAX_WIDTH);
  constant AB          : positive := AREA_BITS + 1; -- the count and its flag
  constant ENTRY_BITS  : positive := 2 * SB + KB + AB;

  subtype slot_t is unsigned(SB - 1 downto 0);

  subtype key_t is unsigned(KB - 1 downto 0);

  subtype area_t is unsigned(AB - 1 downto 0);

  constant AREA_ONE : area_t := to_unsigned(1, AB);

  -- a + b + c (c 0 or 1): the counts' sum, c on the carry chain's input
  -- (one chain: a form with c folded in as an extra low bit took one
  -- CARRY4 more), the flag set by the carry out or by either operand's.
  function area_sum (a : area_t; b : area_t; c : std_logic) return area_t is
    variable sum   : unsigned(AB - 1 downto 0);
    variable carry : unsigned(0 downto 0);
  begin

    carry(0) := c;
    sum      := ('0' & a(AB - 2 downto 0)) + ('0' & b(AB - 2 downto 0)) + carry;
    return (sum(AB - 1) or a(AB - 1) or b(AB - 1)) & sum(AB - 2 downto 0);

  end function area_sum;

  -- The record's area: the count, or all ones once the flag is set.
  function saturated (a : area_t) return unsigned is
  begin

    if a(AB - 1) = '1' then
      return (AB - 2 downto 0 => '1');
    end if;

    return a(AB - 2 downto 0);

  end function saturated;

  -- A previous-row class on the stack: the data path's half (the control
  -- keeps its flags).
  type entry_t is record
    head : slot_t; -- slot of its first run in the current row
    tail : slot_t; -- slot of its latest run in the current row
    key  : key_t;  -- best pixel (valid unless merged into the entry above)
    area : area_t; -- corner pixels (valid with the key)
  end record entry_t;

  function pack (e : entry_t) return std_logic_vector is
  begin

    return std_logic_vector(e.head) & std_logic_vector(e.tail) & std_logic_vector(e.key) &
           std_logic_vector(e.area);

  end function pack;

  function unpack (v : std_logic_vector(ENTRY_BITS - 1 downto 0)) return entry_t is
    variable e : entry_t;
  begin

    e.head := unsigned(v(ENTRY_BITS - 1 downto ENTRY_BITS - SB));
    e.tail := unsigned(v(ENTRY_BITS - SB - 1 downto KB + AB));
    e.key  := unsigned(v(KB + AB - 1 downto AB));
    e.area := unsigned(v(AB - 1 downto 0));
    return e;

  end function unpack;

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

  -- Table write requests: the step's first and, at the end of a row, second.
  type data_write_t is record
    en   : std_logic;
    addr : slot_t;
    data : key_t;
    area : area_t;
  end record data_write_t;

  -- A bit table's write: the slot, then the bank (the row's parity; '0' in
  -- the last table, which has one bank).
  subtype bit_addr_t is unsigned(SB downto 0);

  type bit_write_t is record
    en   : std_logic;
    addr : bit_addr_t;
    data : std_logic;
  end record bit_write_t;

  -- A bit write as the tables take it, with whether it is to slot 0 or 1.
  function table_write (w : bit_write_t; s0 : std_logic; s1 : std_logic) return bit_table_write_t is
    variable t : bit_table_write_t(addr(bit_addr_t'range));
  begin

    t := (en => w.en, addr => w.addr, data => w.data, s0 => s0, s1 => s1);
    return t;

  end function table_write;

  -- (No constant wider than 32 bits: GHDL's Verilog output writes those as
  -- strings. The data of a write that is not enabled does not matter.)
  constant NO_BIT_WRITE : bit_write_t := (en => '0', addr => (others => '0'), data => '0');

  -- The operation, the current class's slots and key, the stack's slots and
  -- keys (top, second, third). (sim_zeros: the compares made every clock
  -- read c_key, the stack and the tables before their first write.)
  signal op_r       : op_t;
  signal c_key      : key_t   := unsigned(sim_zeros(KB));
  signal c_area     : area_t  := unsigned(sim_zeros(AB));
  signal c_head     : slot_t  := unsigned(sim_zeros(SB));
  signal c_tail     : slot_t  := unsigned(sim_zeros(SB));
  signal d_top      : entry_t := unpack(sim_zeros(ENTRY_BITS));
  signal d_second   : entry_t := unpack(sim_zeros(ENTRY_BITS));
  signal d_third    : entry_t := unpack(sim_zeros(ENTRY_BITS));
  signal d_third_rd : std_logic;

  -- Table writes, registered: the first of a column now, the second from
  -- the spare register on the next clock.
  signal data_w     : data_write_t;
  signal data_spare : data_write_t;
  signal head_w     : bit_write_t;
  signal head_spare : bit_write_t;
  signal last_w     : bit_write_t;
  signal last_spare : bit_write_t;
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
  signal last_w_s0_r     : std_logic;
  signal last_w_s1_r     : std_logic;
  signal head_w_s1_r     : std_logic;
  signal last_spare_s0   : std_logic;
  signal last_spare_s1   : std_logic;
  signal head_spare_s1_r : std_logic;

  -- The stack's slots and keys below its registers.
  signal stack_we : std_logic;
  signal stack_wa : unsigned(clog2(STACK_WORDS) - 1 downto 0);
  signal stack_wd : std_logic_vector(ENTRY_BITS - 1 downto 0);
  signal stack_re : std_logic;
  signal stack_ra : unsigned(clog2(STACK_WORDS) - 1 downto 0);
  signal stack_rd : std_logic_vector(ENTRY_BITS - 1 downto 0);

  signal eof_pending : std_logic;
  signal checks_on   : boolean; -- false until the first reset: the invariants hold from then on

begin

  assert MAX_WIDTH >= 3
    report "fastnms_nms_region_keys: MAX_WIDTH must be at least 3"
    severity failure;

  op_r <= cmd.op;

  writes <=
  (
    data       => (en => data_w.en, slot => data_w.addr, word => data_w.data & data_w.area, s0 => data_w0),
    head       => table_write(head_w, '0', head_w_s1_r),
    head_spare => table_write(head_spare, '0', head_spare_s1_r),
    last       => table_write(last_w, last_w_s0_r, last_w_s1_r)
  );

  -- The data path: the slots and keys of the column the control stepped on
  -- the clock before (op), with the same operations in the same order; the
  -- table writes, the stack's slots and keys, the records. Slots move by the
  -- operation's bits alone. The keys (Keys, below) and the table writes'
  -- slots (Table writes) are chosen at once, by the operation's bits and
  -- the comparisons, not through the step's sequence of operations.
  keys : process (clk) is

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
    -- The areas beside those keys: the base's, the class merging in's,
    -- their sum with the pixel joining; the current class's.
    variable base_area  : area_t;
    variable merge_area : area_t;
    variable best_area  : area_t;
    variable cur_area   : area_t;
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
      dw1      := (en => '0', addr => c_head, data => c_key, area => c_area);
      dw2      := dw1;
      hw1      := NO_BIT_WRITE;
      hw2      := NO_BIT_WRITE;
      lw1      := NO_BIT_WRITE;
      lw2      := NO_BIT_WRITE;

      -- (The control's k_* bits are these operations, already gated.)
      pushed    := op_r.k_base_pushed = '1';
      attach    := op_r.k_merge_cur = '1' or op_r.k_merge_pix = '1';
      takeover  := op_r.k_merge_top = '1';
      start     := op_r.k_cur_start = '1';
      popping   := op_r.pop = '1' and op_r.rv = '1';
      detach    := op_r.k_detach = '1';
      final     := op_r.k_final = '1';
      cur_final := op_r.cur_final = '1' and op_r.cv = '1';
      pix       := cmd.score & not cmd.cy & not cmd.cx;

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
      if op_r.k_base_pushed = '0' then
        base      := d_top.key;
        base_area := d_top.area;
      elsif data_landing = '1' then
        base      := data_w.data;
        base_area := data_w.area;
      else
        base      := data_word(KB + AB - 1 downto AB);
        base_area := data_word(AB - 1 downto 0);
      end if;
      -- (At most one of them; an AND-OR, one LUT per bit.)
      merge  := (c_key and (c_key'range => op_r.k_merge_cur)) or
                (pix and (pix'range => op_r.k_merge_pix)) or
                (d_top.key and (d_top.key'range => op_r.k_merge_top));
      pix_in := (others => '0');
      if op_r.k_pix = '1' then
        pix_in := cmd.score;
      end if;
      -- A tie goes to the first operand: the base, the class merging in,
      -- the pixel. The class merging in, when none does, is zero and
      -- loses to the base; the pixel out of play has score zero. The
      -- pixel is compared on scores (every class's best pixel is before
      -- it), the base and the class merging in on keys.
      base_ge_merge := base >= merge;
      base_ge_pix   := score_of(base) >= pix_in;
      merge_ge_pix  := (op_r.k_merge_cur = '1' or op_r.k_merge_pix = '1' or op_r.k_merge_top = '1') and
                       score_of(merge) >= pix_in;
      if base_ge_merge and base_ge_pix then
        best := base;
      elsif merge_ge_pix then
        best := merge;
      else
        best := pix;
      end if;
      -- The merged class's area: every pixel of the three operands (the
      -- pixel starting a run is a class of one pixel).
      merge_area := (c_area and (c_area'range => op_r.k_merge_cur)) or
                    (AREA_ONE and (AREA_ONE'range => op_r.k_merge_pix)) or
                    (d_top.area and (d_top.area'range => op_r.k_merge_top));
      best_area  := area_sum(base_area, merge_area, op_r.k_pix);
      -- The current class's key after steps 2 and 4: the pixel starting it,
      -- or a pixel with a higher score.
      cur_ge_pix := score_of(c_key) >= cmd.score;
      if op_r.k_cur_start = '1' or (op_r.k_cur_pix = '1' and not cur_ge_pix) then
        cur := pix;
      else
        cur := c_key;
      end if;
      if op_r.k_cur_start = '1' then
        cur_area := AREA_ONE;
      else
        cur_area := area_sum(c_area, (others => '0'), op_r.k_cur_pix);
      end if;

      -- synthesis translate_off
      if rst = '1' then
        checks_on <= true;
      end if;
      assert not (d_third_rd = '1' and popping and not pushed)
        report "fastnms_nms_region: a pop uncovering the stack RAM's word before it is read"
        severity failure;
      assert not (popping and op_r.pop_emit = '1' and (best /= base or best_area /= base_area))
        report "fastnms_nms_region: a closing class merged in its last column"
        severity failure;
      assert data_landing = (data_w0 and op_r.r_col0)
        report "fastnms_nms_region: data_landing out of step"
        severity failure;
      assert not checks_on or
             ((op_r.k_merge_cur and op_r.k_merge_pix) or (op_r.k_merge_cur and op_r.k_merge_top) or
              (op_r.k_merge_pix and op_r.k_merge_top)) = '0'
        report "fastnms_nms_region: two classes merging in at once"
        severity failure;
      -- synthesis translate_on

      -- Slots and stack moves, step by step.
      -- 1. A pushed class: its key from the data table.
      if pushed then
        if op_r.push_ram = '1' then
          stack_we <= '1';
          stack_wa <= cmd.ram_wa;
          stack_wd <= pack(v_second);
          v_third  := v_second;
        end if;
        v_second := v_top;
        v_top    := (head => (others => '0'), tail => (others => '0'), key => base, area => base_area);
      end if;

      -- 2. A current-row run starts: a class of its own for now.
      if start then
        v_head := slot_of(cmd.cx, SB);
        v_tail := slot_of(cmd.cx, SB);
      end if;

      -- 3. The current run's class joins the top's, or the pushed class
      -- takes over the one below.
      if attach then
        if op_r.attach_runs = '0' then
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
        if op_r.pop_merged = '1' then
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
      cands(S_PIX)      := slot_of(cmd.cx, SB);
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
        if op_r.attach_runs = '0' then
          p_head_sel := v_head_sel;
        end if;
      end if;
      contact_w := attach and op_r.attach_runs = '1';
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
      dw1 := (en => to_sl(final or cur_final), addr => pick(dw1_sel, cands), data => c_key, area => c_area);
      dw2 := (en => to_sl(final and cur_final), addr => pick(v_head_sel, cands), data => c_key, area => c_area);
      hw1 := (en => to_sl(w1_en), addr => pick(hw1_sel, cands) & op_r.bank, data => to_sl(not contact_w));
      hw2 := (en => to_sl(w2_en), addr => pick(hw2_sel, cands) & op_r.bank, data => '1');
      lw1 := (en => to_sl(w1_en), addr => pick(lw1_sel, cands) & '0', data => to_sl(not contact_w));
      lw2 := (en => to_sl(w2_en), addr => pick(lw2_sel, cands) & '0', data => '1');
      -- The keys after step 6: the pop uncovers the entry below (the
      -- second, or the top itself after a push), or leaves the merged
      -- class on top; the popped class (the merged one) goes on as the
      -- current class, is finalized or closes.
      if op_r.k_keep_top = '1' then
        v_top.key  := d_top.key;
        v_top.area := d_top.area;
      elsif op_r.k_take_second = '1' then
        v_top.key  := d_second.key;
        v_top.area := d_second.area;
      else
        v_top.key  := best;
        v_top.area := best_area;
      end if;
      if op_r.k_final = '1' then
        dw1.data := best;
        dw1.area := best_area;
      else
        dw1.data := cur;
        dw1.area := cur_area;
      end if;
      dw2.data := cur;
      dw2.area := cur_area;

      d_top    <= v_top;
      d_second <= v_second;
      d_third  <= v_third;
      if op_r.k_detach = '1' then
        c_key  <= best;
        c_area <= best_area;
      else
        c_key  <= cur;
        c_area <= cur_area;
      end if;
      c_head <= v_head;
      c_tail <= v_tail;

      -- Table writes: the step's first now, a second one on the next clock
      -- (only the last column of a row makes two; the next clock's step
      -- writes nothing). The second data write is the current class's key,
      -- which c_key holds on that clock (the spare register keeps only its
      -- slot; asserted).
      if data_spare.en = '1' then
        data_w        <= (en => '1', addr => data_spare.addr, data => c_key, area => c_area);
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
        head_w      <= head_spare;
        head_w_s1_r <= head_spare_s1_r;
        head_spare  <= NO_BIT_WRITE;
      else
        head_w          <= hw1;
        head_w_s1_r     <= pick(hw1_sel, slot1);
        head_spare      <= hw2;
        head_spare_s1_r <= pick(hw2_sel, slot1);
      end if;
      if last_spare.en = '1' then
        last_w      <= last_spare;
        last_w_s0_r <= last_spare_s0;
        last_w_s1_r <= last_spare_s1;
        last_spare  <= NO_BIT_WRITE;
      else
        last_w        <= lw1;
        last_w_s0_r   <= pick(lw1_sel, slot0);
        last_w_s1_r   <= pick(lw1_sel, slot1);
        last_spare    <= lw2;
        last_spare_s0 <= pick(lw2_sel, slot0);
        last_spare_s1 <= pick(lw2_sel, slot1);
      end if;

      -- synthesis translate_off
      assert not (data_spare.en = '1' and (c_key /= data_spare.data or c_area /= data_spare.area))
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
      if op_r.flush_ends = '1' then
        eof_pending <= '1';
      end if;
      -- A class that closes had no merge and no pixel in its last column
      -- (it has no current-row runs): its key is the base (asserted).
      if popping and op_r.pop_emit = '1' then
        rec_valid <= '1';
        rec_eof   <= '0';
        rec_x     <= not base(XB - 1 downto 0);
        rec_y     <= not base(XB + YB - 1 downto XB);
        rec_score <= base(KB - 1 downto XB + YB);
        rec_area  <= saturated(base_area);
      elsif eof_pending = '1' and rec_room = '1' then
        -- Separate narrow registers: GHDL's Verilog output writes a constant
        -- vector of more than 32 bits as a string (ASCII digits).
        rec_valid   <= '1';
        rec_eof     <= '1';
        rec_x       <= (others => '1');
        rec_y       <= (others => '1');
        rec_score   <= (others => '0');
        rec_area    <= (others => '0');
        eof_pending <= op_r.flush_ends;
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
      end if;
    end if;

  end process keys;

  -- The stack RAM is read in the pop's own clock, from the operation's
  -- registers: its word is the third entry on the next clock (pops without
  -- a push between them are at least two columns apart, asserted).
  stack_re <= op_r.pop and op_r.pop_ram and op_r.rv;
  stack_ra <= cmd.ram_ra;

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

end architecture rtl;
