-- The NMS blocks' output record (a keypoint, a row-end beat or the end-of-frame
-- beat) as a VHDL record with pack/unpack for a skid buffer or a FIFO word.
-- Datasheet: docs/README.md#packages
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

package fastnms_corner_pkg is

  type corner_t is record
    eof     : std_logic; -- the end-of-frame beat (x, y: the frame's last pixel; score 0)
    row_end : std_logic; -- a row-end beat (x, y: the line's last pixel; score 0)
    x       : unsigned;
    y       : unsigned;
    score   : unsigned;
  end record corner_t;

  -- Bits of a packed record.
  function corner_width (x_bits : positive; y_bits : positive; score_bits : positive) return positive;

  function pack (c : corner_t) return std_logic_vector;

  -- A packed record (corner_width(x_bits, y_bits, score_bits) bits).
  function unpack (v : std_logic_vector; x_bits : positive; y_bits : positive; score_bits : positive)
    return corner_t;

end package fastnms_corner_pkg;

package body fastnms_corner_pkg is

  function corner_width (x_bits : positive; y_bits : positive; score_bits : positive) return positive is
  begin

    return 2 + x_bits + y_bits + score_bits;

  end function corner_width;

  function pack (c : corner_t) return std_logic_vector is
  begin

    return c.eof & c.row_end & std_logic_vector(c.x) & std_logic_vector(c.y) & std_logic_vector(c.score);

  end function pack;

  function unpack (v : std_logic_vector; x_bits : positive; y_bits : positive; score_bits : positive)
    return corner_t is
    alias    vv : std_logic_vector(v'length - 1 downto 0) is v;
    variable c  : corner_t(x(x_bits - 1 downto 0), y(y_bits - 1 downto 0), score(score_bits - 1 downto 0));
  begin

    c.eof     := vv(x_bits + y_bits + score_bits + 1);
    c.row_end := vv(x_bits + y_bits + score_bits);
    c.x       := unsigned(vv(x_bits + y_bits + score_bits - 1 downto y_bits + score_bits));
    c.y       := unsigned(vv(y_bits + score_bits - 1 downto score_bits));
    c.score   := unsigned(vv(score_bits - 1 downto 0));
    return c;

  end function unpack;

end package body fastnms_corner_pkg;
