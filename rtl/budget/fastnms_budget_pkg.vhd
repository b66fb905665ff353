-- The keypoint budget's memory word (K entries best first, an entry a valid
-- bit, the score, y and x in the cell) and the decoded beat's flags F_*.
-- Datasheet: docs/fastnms_cell_budget.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

package fastnms_budget_pkg is

  -- A decoded beat's flags: bit F_* set when the beat is so. Each beat has one of
  -- F_OUT, F_FREE, F_ENDS, F_FILL and F_OTHER: what it waits for.
  constant F_OUT    : natural  := 0; -- K = 0 and not a row-end beat: the beat leaves
  constant F_FREE   : natural  := 1; -- a row-end beat that queues no job: it waits for nothing
  constant F_ENDS   : natural  := 2; -- an end of frame or a row-end beat that closes the row (K > 0)
  constant F_FILL   : natural  := 3; -- a record into the bank being filled (K > 0)
  constant F_OTHER  : natural  := 4; -- a record into the other bank: F_FILL's, F_SWITCH (K > 0)
  constant F_INSERT : natural  := 5; -- F_FILL or F_OTHER: a record to insert
  constant F_SWITCH : natural  := 6; -- a record of a later cell row than the last record
  constant F_FIRST  : natural  := 7; -- a record that opens a cell row (no row open, or F_SWITCH)
  constant F_BITS   : positive := 8;

  -- E, the bits of an entry.
  function entry_width (score_bits : positive) return positive;

  -- Entry j of word w.
  function entry (w : std_logic_vector; j : natural; e_bits : positive) return std_logic_vector;

  function valid_of (e : std_logic_vector) return std_logic;

  function score_of (e : std_logic_vector) return unsigned;

  -- y (15 .. 8) and x (7 .. 0) inside the cell.
  function offset_of (e : std_logic_vector) return std_logic_vector;

  -- Does entry e rank before a later record of score s (a tie keeps the earlier)?
  function beats (e : std_logic_vector; s : unsigned) return std_logic;

  -- The word with its first entry gone (the drain's next record comes first).
  function drop_first (w : std_logic_vector; e_bits : positive) return std_logic_vector;

  -- The word with every entry invalid (an empty cell): the other bits do not matter.
  function emptied (w : std_logic_vector; e_bits : positive) return std_logic_vector;

end package fastnms_budget_pkg;

package body fastnms_budget_pkg is

  function entry_width (score_bits : positive) return positive is
  begin

    return 1 + score_bits + 16;

  end function entry_width;

  function entry (w : std_logic_vector; j : natural; e_bits : positive) return std_logic_vector is
    alias wv : std_logic_vector(w'length - 1 downto 0) is w;
  begin

    return wv((j + 1) * e_bits - 1 downto j * e_bits);

  end function entry;

  function valid_of (e : std_logic_vector) return std_logic is
    alias ev : std_logic_vector(e'length - 1 downto 0) is e;
  begin

    return ev(e'length - 1);

  end function valid_of;

  function score_of (e : std_logic_vector) return unsigned is
    alias ev : std_logic_vector(e'length - 1 downto 0) is e;
  begin

    return unsigned(ev(e'length - 2 downto 16));

  end function score_of;

  function offset_of (e : std_logic_vector) return std_logic_vector is
    alias ev : std_logic_vector(e'length - 1 downto 0) is e;
  begin

    return ev(15 downto 0);

  end function offset_of;

  function beats (e : std_logic_vector; s : unsigned) return std_logic is
  begin

    return valid_of(e) and (score_of(e) ?>= s);

  end function beats;

  function drop_first (w : std_logic_vector; e_bits : positive) return std_logic_vector is
  begin

    return std_logic_vector(shift_right(unsigned(w), e_bits));

  end function drop_first;

  function emptied (w : std_logic_vector; e_bits : positive) return std_logic_vector is
    variable result : std_logic_vector(w'length - 1 downto 0);
  begin

    result := w;

    for j in 0 to w'length / e_bits - 1 loop

      result((j + 1) * e_bits - 1) := '0';

    end loop;

    return result;

  end function emptied;

end package body fastnms_budget_pkg;
