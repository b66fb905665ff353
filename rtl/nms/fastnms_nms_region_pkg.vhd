-- What the parts of the region NMS (fastnms_nms_region) share: the widths
-- they compute from the generics, the stack entries' flags and the column's
-- operation (op), which the control decides and the key data path carries
-- out one clock later.
--
-- Ports between the parts are std_logic_vector or unsigned, with widths
-- computed from the generics by the functions below: a record whose element
-- widths follow generics would need VHDL-2008 unconstrained record elements
-- or a generic package, which GHDL 2.0's synthesis is not trusted with. The
-- operation's one-bit decisions travel as a record of std_logic packed into
-- a vector (to_slv, to_op); its fields that have widths (slot, score,
-- position, stack RAM addresses) as ports of their own.
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

  constant OP_BITS : positive := 31;

  function to_slv (o : op_t) return std_logic_vector;

  function to_op (v : std_logic_vector(OP_BITS - 1 downto 0)) return op_t;

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
