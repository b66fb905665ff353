-- The keypoint budget's input decode: each beat with its frame's CELL and K,
-- its cell and its kind as flags, two clocks later, so that the parent's
-- decision reads registers only.
-- Datasheet: docs/fastnms_cell_budget.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_budget_pkg.all;

entity fastnms_budget_decode is
  generic (
    X_BITS     : positive := 11;
    Y_BITS     : positive := 12;
    SCORE_BITS : positive := 8;
    K_MAX      : positive := 15
  );
  port (
    clk         : in    std_logic;
    rst         : in    std_logic;
    in_valid    : in    std_logic;
    in_ready    : out   std_logic;
    in_x        : in    unsigned(X_BITS - 1 downto 0);
    in_y        : in    unsigned(Y_BITS - 1 downto 0);
    in_score    : in    unsigned(SCORE_BITS - 1 downto 0);
    in_eof      : in    std_logic;
    in_row_end  : in    std_logic;
    in_cell_log : in    unsigned(2 downto 0);
    in_per_cell : in    unsigned(3 downto 0);
    out_valid   : out   std_logic;
    out_ready   : in    std_logic;
    out_x       : out   unsigned(X_BITS - 1 downto 0);
    out_y       : out   unsigned(Y_BITS - 1 downto 0);
    out_score   : out   unsigned(SCORE_BITS - 1 downto 0);
    out_eof     : out   std_logic;
    out_log     : out   natural range 0 to 4;
    out_k       : out   natural range 0 to K_MAX;
    out_flags   : out   std_logic_vector(F_BITS - 1 downto 0);
    out_cell    : out   unsigned(X_BITS - 1 downto 0)
  );
end entity fastnms_budget_decode;

architecture rtl of fastnms_budget_decode is

  constant BEAT_BITS : positive := 1 + X_BITS + Y_BITS + SCORE_BITS;
  -- The first buffer: the beat, in_row_end, log, K, K = 0, differs, at_last.
  constant P_BITS : positive := BEAT_BITS + 1 + 3 + 4 + 3;
  -- The second: the record's cell, the beat, log, K, the flags.
  constant D_BITS : positive := X_BITS + BEAT_BITS + 3 + 4 + F_BITS;

  subtype log_t is natural range 0 to 4;

  -- The bits of a coordinate inside a cell of 16 << log pixels.
  function cell_mask (log : log_t) return unsigned is
  begin

    return shift_right(to_unsigned(255, 16), 4 - log);

  end function cell_mask;

  -- First clock: the frame's configuration (its first beat's) and the last record's line.
  signal p_take    : std_logic;
  signal p_ready   : std_logic;
  signal p_started : std_logic;
  signal p_log     : log_t;
  signal p_k       : natural range 0 to K_MAX;
  signal p_pass    : std_logic;             -- p_k = 0
  signal p_in_cell : unsigned(15 downto 0); -- cell_mask(p_log), registered with it
  signal p_last_y  : unsigned(Y_BITS - 1 downto 0);
  signal p_data    : std_logic_vector(P_BITS - 1 downto 0);

  -- Second clock: the first buffer's beat, whether a cell row is open.
  signal q_valid : std_logic;
  signal q_data  : std_logic_vector(P_BITS - 1 downto 0);
  signal i_take  : std_logic;
  signal i_ready : std_logic;
  signal i_open  : std_logic; -- a record went in since the frame's start or the last close
  signal i_close : std_logic; -- the beat is a row-end beat that closes the open cell row
  signal i_data  : std_logic_vector(D_BITS - 1 downto 0);

  signal s_data : std_logic_vector(D_BITS - 1 downto 0);

begin

  assert K_MAX <= 15
    report "fastnms_budget_decode: K_MAX must be 1 .. 15"
    severity failure;
  assert X_BITS <= 16 and Y_BITS <= 16
    report "fastnms_budget_decode: X_BITS and Y_BITS must be at most 16"
    severity failure;

  -- ---- first clock: the configuration and the comparisons with the last record ----------

  p_take <= in_valid and p_ready;

  compare : process (all) is

    variable log     : log_t;
    variable k       : natural range 0 to K_MAX;
    variable k_zero  : std_logic;
    variable y_wide  : unsigned(15 downto 0);
    variable differs : std_logic; -- y is in another cell row than the last record
    variable at_last : std_logic; -- y is the last line of its cell row

  begin

    if p_started = '1' then
      log    := p_log;
      k      := p_k;
      k_zero := p_pass;
    else
      log    := minimum(4, to_integer(in_cell_log));
      k      := minimum(K_MAX, to_integer(in_per_cell));
      k_zero := to_sl(in_per_cell = 0);
    end if;

    -- A differing bit of y above the cell's (raster order: never before). Only read
    -- with a cell row open, so after the frame's first beat: the registered mask holds.
    y_wide  := resize(in_y, 16);
    differs := to_sl(((y_wide xor resize(p_last_y, 16)) and not p_in_cell) /= 0);
    at_last := to_sl((y_wide(7 downto 0) or not p_in_cell(7 downto 0)) = x"FF");

    p_data <= in_eof & std_logic_vector(in_x) & std_logic_vector(in_y) & std_logic_vector(in_score)
              & in_row_end & std_logic_vector(to_unsigned(log, 3)) & std_logic_vector(to_unsigned(k, 4))
              & k_zero & differs & at_last;

  end process compare;

  first_side : process (clk) is
  begin

    if rising_edge(clk) then
      if p_take = '1' then
        p_started <= not in_eof;
        if in_eof = '0' and in_row_end = '0' then
          p_last_y <= in_y;
        end if;
        if p_started = '0' then
          p_log     <= minimum(4, to_integer(in_cell_log));
          p_in_cell <= cell_mask(minimum(4, to_integer(in_cell_log)));
          p_k       <= minimum(K_MAX, to_integer(in_per_cell));
          p_pass    <= to_sl(in_per_cell = 0);
        end if;
      end if;
      if rst = '1' then
        p_started <= '0';
      end if;
    end if;

  end process first_side;

  first_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => P_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => in_valid,
      in_ready  => p_ready,
      in_data   => p_data,
      out_valid => q_valid,
      out_ready => i_ready,
      out_data  => q_data
    );

  in_ready <= p_ready;

  -- ---- second clock: the flags -----------------------------------------------------------

  i_take <= q_valid and i_ready;

  flag : process (all) is

    variable eof      : std_logic;
    variable row_end  : std_logic;
    variable k_zero   : std_logic;
    variable differs  : std_logic;
    variable at_last  : std_logic;
    variable a_record : std_logic;
    variable closed   : std_logic;
    variable flags    : std_logic_vector(F_BITS - 1 downto 0);
    variable log      : log_t;
    variable cell     : unsigned(X_BITS - 1 downto 0);

  begin

    eof      := q_data(P_BITS - 1);
    row_end  := q_data(10);
    k_zero   := q_data(2);
    differs  := q_data(1);
    at_last  := q_data(0);
    a_record := not eof and not row_end;
    -- A row-end beat closes the open cell row at its last line (or past it).
    closed  := i_open and row_end and (differs or at_last);
    i_close <= closed;

    -- Each flag a function of few registers (a beat is a record, a row-end beat or an
    -- end of frame); F_ENDS and F_OTHER queue a job.
    flags(F_OUT)    := k_zero and not row_end;
    flags(F_FREE)   := row_end and (k_zero or not closed);
    flags(F_ENDS)   := not k_zero and (eof or closed);
    flags(F_FILL)   := a_record and not k_zero and not (i_open and differs);
    flags(F_OTHER)  := a_record and not k_zero and i_open and differs;
    flags(F_INSERT) := a_record and not k_zero;
    flags(F_SWITCH) := a_record and i_open and differs;
    flags(F_FIRST)  := a_record and (differs or not i_open);

    -- The record's cell (a register for the parent's read address and same-cell compares).
    log  := to_integer(unsigned(q_data(9 downto 7)));
    cell := shift_right(unsigned(q_data(P_BITS - 2 downto P_BITS - 1 - X_BITS)), log + 4);

    -- The cell, the beat, log and K as they are, then the flags.
    i_data <= std_logic_vector(cell) & q_data(P_BITS - 1 downto 11) & q_data(9 downto 3) & flags;

  end process flag;

  second_side : process (clk) is
  begin

    if rising_edge(clk) then
      if i_take = '1' then
        if q_data(P_BITS - 1) = '0' and q_data(10) = '0' then
          i_open <= '1';
        end if;
        if q_data(P_BITS - 1) = '1' or i_close = '1' then
          i_open <= '0';
        end if;
      end if;
      if rst = '1' then
        i_open <= '0';
      end if;
    end if;

  end process second_side;

  second_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => D_BITS
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => q_valid,
      in_ready  => i_ready,
      in_data   => i_data,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => s_data
    );

  out_cell  <= unsigned(s_data(D_BITS - 1 downto D_BITS - X_BITS));
  out_eof   <= s_data(BEAT_BITS + 6 + F_BITS);
  out_x     <= unsigned(s_data(BEAT_BITS + 5 + F_BITS downto BEAT_BITS + 6 + F_BITS - X_BITS));
  out_y     <= unsigned(s_data(BEAT_BITS + 5 + F_BITS - X_BITS downto SCORE_BITS + 7 + F_BITS));
  out_score <= unsigned(s_data(SCORE_BITS + 6 + F_BITS downto 7 + F_BITS));
  out_log   <= to_integer(unsigned(s_data(F_BITS + 6 downto F_BITS + 4)));
  out_k     <= to_integer(unsigned(s_data(F_BITS + 3 downto F_BITS)));
  out_flags <= s_data(F_BITS - 1 downto 0);

end architecture rtl;
