-- What the region NMS's parts share: widths from the generics, the stack
-- entries' flags, the column's operation (op), and the records their ports
-- carry (step_t, run_t, command_t, writes_t).
-- Datasheet: docs/fastnms_nms_region.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

package fastnms_nms_region_pkg is

  -- Key: score, then the inverted row and column, so that the larger key is
  -- the better pixel (higher score, then earlier in raster order).
  function key_bits (max_width : positive; max_height : positive; score_bits : positive)
    return positive;

  -- A class's area: its corner pixels, saturating (the record's AREA field).
  constant AREA_BITS : positive := 11;

  -- A data word (the data table's): the key, then the area as the key data
  -- path keeps it (fastnms_nms_region_keys: the count modulo 2 ** AREA_BITS
  -- and a flag) in the low AREA_BITS + 1 bits.
  function data_bits (max_width : positive; max_height : positive; score_bits : positive)
    return positive;

  -- Slots: one per two columns (two runs of a row start at least two apart).
  function slot_count (max_width : positive) return positive;

  -- Bits of a slot: every slot fits.
  function slot_bits (max_width : positive) return positive;

  -- Open classes of the previous row at once (golden/region_stream.py,
  -- stack_entries): the top three are registers, the others in the stack RAMs.
  function stack_entries (max_width : positive) return positive;

  function stack_ram_words (max_width : positive) return positive;

  -- A column's slot: its column / 2, `bits` wide.
  function slot_of (x : unsigned; bits : positive) return unsigned;

  -- A previous-row class on the stack, in two parts: its flags, which the
  -- control (the step's decisions) keeps, and its slots and key, which the
  -- key data path keeps one clock later (fastnms_nms_region_keys).
  type flags_t is record
    last   : std_logic; -- its run under the reader is its last in the previous row
    runs   : std_logic; -- it has runs in the current row (head and tail are valid)
    merged : std_logic; -- also holds the class of the entry below
  end record flags_t;

  constant FLAG_BITS : positive := 3;

  function pack (f : flags_t) return std_logic_vector;

  function unpack (v : std_logic_vector(FLAG_BITS - 1 downto 0)) return flags_t;

  -- The operation of one column, decided by the control and carried out by
  -- the key data path on the next clock: every selection the data path
  -- makes is on these registered bits (and on the operation's slot, score,
  -- position and stack RAM addresses, which travel beside them).
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
    -- registers (fastnms_nms_region_keys, Keys).
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
    flush_ends    : std_logic; -- a flush's last column: the end-of-frame beat is due
  end record op_t;

  -- op_t as a vector (bit 30: push .. bit 0: flush_ends), for a flat port
  -- (tb/nms/vhdl/fastnms_nms_region_tables_flat.vhd).
  constant OP_BITS : positive := 31;

  function to_slv (o : op_t) return std_logic_vector;

  function to_op (v : std_logic_vector(OP_BITS - 1 downto 0)) return op_t;

  -- The records between the parts. Their fields with widths are unconstrained
  -- here and take their widths where a port or signal is declared:
  -- x, cx: clog2(MAX_WIDTH); y, cy: bits_for(MAX_HEIGHT); slots: slot_bits;
  -- bit table addresses: slot_bits + 1; data words: data_bits; stack RAM
  -- addresses: clog2(stack_ram_words).

  -- This clock's steps and where both sides are (fastnms_nms_region_schedule,
  -- to the tables, the control and the key data path).
  type step_t is record
    -- The steps: the current row (cstep), the reader (rstep), both in
    -- lock-step (lock, a row >= 1); a flush's last column (flush_ends).
    cstep      : std_logic;
    rstep      : std_logic;
    lock       : std_logic;
    flush_ends : std_logic;
    -- The current row: a frame's first row, the previous pixel's corner
    -- bit, its column and row, its head table bank (the row's parity).
    first_row : std_logic;
    cm        : std_logic;
    cx        : unsigned;
    cy        : unsigned;
    cur_bank  : std_logic;
    -- The reader: its bits at rcol - 1 and rcol, its row's last column
    -- (r_last), rcol = 0, 1, 2 or < 2 (r_col0, r_col1, r_col2, r_slot0), its
    -- row's head table bank, and the slot the tables are read at, two
    -- columns ahead of it.
    pm         : std_logic;
    p0         : std_logic;
    r_last     : std_logic;
    r_col0     : std_logic;
    r_col1     : std_logic;
    r_col2     : std_logic;
    r_slot0    : std_logic;
    r_bank     : std_logic;
    ahead_slot : unsigned;
  end record step_t;

  -- The tables' words at the reader's column (fastnms_nms_region_tables, to
  -- the control and the key data path): the previous-row run's head bit (a
  -- register) and last bit (the register, or the write landing now); the
  -- data word (key & area), for the operation's clock.
  type run_t is record
    head : std_logic;
    last : std_logic;
    data : unsigned;
  end record run_t;

  -- The column's operation, registered (fastnms_nms_region_control, to the
  -- tables and the key data path): its decisions, the slot the data table is
  -- read at, the pixel's score and position, the stack RAM's write (push)
  -- and read (pop) addresses.
  type command_t is record
    op     : op_t;
    slot   : unsigned;
    score  : unsigned;
    cx     : unsigned;
    cy     : unsigned;
    ram_wa : unsigned;
    ram_ra : unsigned;
  end record command_t;

  -- A table write, registered (fastnms_nms_region_keys, to the tables; the
  -- last table's also to the control), with whether it is to slot 0 or 1:
  -- the previous row's last writes land as the next row's first columns
  -- take those words.
  type data_table_write_t is record
    en   : std_logic;
    slot : unsigned;
    word : unsigned; -- key & area (a data word)
    s0   : std_logic;
  end record data_table_write_t;

  type bit_table_write_t is record
    en   : std_logic;
    addr : unsigned; -- slot & bank (the head table's), slot & '0' (the last table's)
    data : std_logic;
    s0   : std_logic;
    s1   : std_logic;
  end record bit_table_write_t;

  -- The data table's write, the head table's (and the one waiting in its
  -- spare register for the next clock), the last table's.
  type writes_t is record
    data       : data_table_write_t;
    head       : bit_table_write_t;
    head_spare : bit_table_write_t;
    last       : bit_table_write_t;
  end record writes_t;

end package fastnms_nms_region_pkg;

package body fastnms_nms_region_pkg is

  function key_bits (max_width : positive; max_height : positive; score_bits : positive)
    return positive is
  begin

    return score_bits + bits_for(max_height) + clog2(max_width);

  end function key_bits;

  function data_bits (max_width : positive; max_height : positive; score_bits : positive)
    return positive is
  begin

    return key_bits(max_width, max_height, score_bits) + AREA_BITS + 1;

  end function data_bits;

  function slot_count (max_width : positive) return positive is
  begin

    return (max_width + 1) / 2;

  end function slot_count;

  function slot_bits (max_width : positive) return positive is
  begin

    return bits_for(slot_count(max_width));

  end function slot_bits;

  function stack_entries (max_width : positive) return positive is
  begin

    return (max_width + 1) / 4 + 1;

  end function stack_entries;

  function stack_ram_words (max_width : positive) return positive is
  begin

    return maximum(stack_entries(max_width) - 2, 1);

  end function stack_ram_words;

  function slot_of (x : unsigned; bits : positive) return unsigned is
  begin

    return resize(x(x'high downto 1), bits);

  end function slot_of;

  function pack (f : flags_t) return std_logic_vector is
  begin

    return f.last & f.runs & f.merged;

  end function pack;

  function unpack (v : std_logic_vector(FLAG_BITS - 1 downto 0)) return flags_t is
  begin

    return (last => v(2), runs => v(1), merged => v(0));

  end function unpack;

  function to_slv (o : op_t) return std_logic_vector is
  begin

    return o.push & o.push_ram & o.start & o.attach & o.attach_runs & o.takeover &
           o.pix_top & o.pix_cur & o.cur_final & o.pop & o.pop_ram & o.pop_merged &
           o.pop_detach & o.pop_final & o.pop_emit & o.k_base_pushed & o.k_merge_cur &
           o.k_merge_pix & o.k_merge_top & o.k_pix & o.k_keep_top & o.k_take_second &
           o.k_cur_start & o.k_cur_pix & o.k_detach & o.k_final & o.rv & o.cv & o.bank &
           o.r_col0 & o.flush_ends;

  end function to_slv;

  function to_op (v : std_logic_vector(OP_BITS - 1 downto 0)) return op_t is
    variable o : op_t;
  begin

    o.push          := v(30);
    o.push_ram      := v(29);
    o.start         := v(28);
    o.attach        := v(27);
    o.attach_runs   := v(26);
    o.takeover      := v(25);
    o.pix_top       := v(24);
    o.pix_cur       := v(23);
    o.cur_final     := v(22);
    o.pop           := v(21);
    o.pop_ram       := v(20);
    o.pop_merged    := v(19);
    o.pop_detach    := v(18);
    o.pop_final     := v(17);
    o.pop_emit      := v(16);
    o.k_base_pushed := v(15);
    o.k_merge_cur   := v(14);
    o.k_merge_pix   := v(13);
    o.k_merge_top   := v(12);
    o.k_pix         := v(11);
    o.k_keep_top    := v(10);
    o.k_take_second := v(9);
    o.k_cur_start   := v(8);
    o.k_cur_pix     := v(7);
    o.k_detach      := v(6);
    o.k_final       := v(5);
    o.rv            := v(4);
    o.cv            := v(3);
    o.bank          := v(2);
    o.r_col0        := v(1);
    o.flush_ends    := v(0);
    return o;

  end function to_op;

end package body fastnms_nms_region_pkg;
