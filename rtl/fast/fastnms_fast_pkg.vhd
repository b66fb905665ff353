-- FAST-9/16: the circle, the arcs and the types shared by the detector blocks.
-- Datasheet: docs/README.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

package fastnms_fast_pkg is

  constant CIRCLE_SIZE : positive := 16;
  constant ARC_LENGTH  : positive := 9;
  constant RADIUS      : positive := 3;
  constant WINDOW_SIZE : positive := 2 * RADIUS + 1;

  type offset_t is record
    dx : integer;
    dy : integer;
  end record offset_t;

  type circle_offsets_t is array (0 to CIRCLE_SIZE - 1) of offset_t;

  -- OpenCV's offsets16 (fast_score.cpp), in its cyclic order: arcs are runs
  -- of consecutive entries, wrapping from 15 to 0.
  constant CIRCLE : circle_offsets_t :=
  (
    (0, 3), (1, 3), (2, 2), (3, 1), (3, 0), (3, -1), (2, -2), (1, -3),
    (0, -3), (-1, -3), (-2, -2), (-3, -1), (-3, 0), (-3, 1), (-2, 2), (-1, 3)
  );

  subtype byte_t is unsigned(7 downto 0);

  -- One 8-bit value per circle pixel.
  type circle_bytes_t is array (0 to CIRCLE_SIZE - 1) of byte_t;

  -- One flag per circle pixel.
  subtype circle_flags_t is std_logic_vector(0 to CIRCLE_SIZE - 1);

  -- Circle index k + n, wrapped.
  function wrap (k : natural; n : natural) return natural;

  -- Entry k: the AND of flags k, k + step and k + 2 * step (cyclic). Applied
  -- with step 1 and then 3 it gives, for each arc start k, the AND of the 9
  -- flags of arc k, as two levels of 3-input ANDs.
  function triple_and (x : circle_flags_t; step : positive) return circle_flags_t;

  -- Bit slice of a circle pixel in a flat WINDOW_SIZE x WINDOW_SIZE window of
  -- bytes (row r, column c at slice r * WINDOW_SIZE + c).
  function circle_slice (k : natural) return natural;

  -- The score generic's values.
  constant OPENCV_SCORE : string := "opencv";
  constant SAD_SCORE    : string := "sad";

  function score_width (score : string) return positive;

  -- Register stages of the score blocks.
  function score_latency (score : string) return positive;

end package fastnms_fast_pkg;

package body fastnms_fast_pkg is

  function wrap (k : natural; n : natural) return natural is
  begin
    return (k + n) mod CIRCLE_SIZE;
  end function wrap;

  function triple_and (x : circle_flags_t; step : positive) return circle_flags_t is
    variable all_set : circle_flags_t;
  begin
    for k in 0 to CIRCLE_SIZE - 1 loop
      all_set(k) := x(k) and x(wrap(k, step)) and x(wrap(k, 2 * step));
    end loop;
    return all_set;
  end function triple_and;

  function circle_slice (k : natural) return natural is
  begin
    return (RADIUS + CIRCLE(k).dy) * WINDOW_SIZE + RADIUS + CIRCLE(k).dx;
  end function circle_slice;

  function score_latency (score : string) return positive is
  begin

    if score = SAD_SCORE then
      return 8;
    end if;

    return 7;
  end function score_latency;

  function score_width (score : string) return positive is
  begin

    if score = SAD_SCORE then
      return 12;
    end if;

    return 8;
  end function score_width;

end package body fastnms_fast_pkg;
