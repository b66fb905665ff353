-- The last HEIGHT * SLOTS image rows, written one pixel per clock and read
-- as columns of HEIGHT rows at any x, one column per clock. Rows are
-- numbered on across frames (a ring): the first row after reset is row 0.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_orb_rows is
  generic (
    MAX_WIDTH : positive := 1920;
    HEIGHT    : positive := 37;
    SLOTS     : positive := 2
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- The image: one pixel per wr_valid, in raster order; wr_x = 0 starts
    -- the next row (row_index), a frame's first row too.
    wr_valid  : in    std_logic;
    wr_x      : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    wr_pixel  : in    std_logic_vector(7 downto 0);
    row_index : out   unsigned(clog2(HEIGHT * SLOTS) - 1 downto 0);
    -- Column requests and the columns, row top + j in bits 8 j + 7 .. 8 j.
    rd_valid   : in    std_logic;
    rd_ready   : out   std_logic;
    rd_x       : in    unsigned(clog2(MAX_WIDTH) - 1 downto 0);
    rd_top     : in    unsigned(clog2(HEIGHT * SLOTS) - 1 downto 0);
    out_valid  : out   std_logic;
    out_ready  : in    std_logic;
    out_column : out   std_logic_vector(8 * HEIGHT - 1 downto 0)
  );
end entity fastnms_orb_rows;

architecture rtl of fastnms_orb_rows is

  constant ROWS       : positive := HEIGHT * SLOTS;
  constant X_BITS     : positive := clog2(MAX_WIDTH);
  constant SLOT_BITS  : positive := clog2(maximum(SLOTS, 2));
  constant SHIFT_BITS : positive := clog2(HEIGHT);
  -- Stages of the rotation, two per register.
  constant PAIRS      : positive := (SHIFT_BITS + 1) / 2;
  constant FIFO_DEPTH : positive := 16;
  -- fastnms_fifo takes words without looking at in_ready up to DEPTH - 3.
  constant CREDITS : positive := FIFO_DEPTH - 3;
  -- From the memories' addresses (stage 2) to the rotated column.
  constant LATENCY : positive := 2 + PAIRS;

  type bytes_t is array (0 to HEIGHT - 1) of std_logic_vector(7 downto 0);

  type rotations_t is array (1 to PAIRS) of bytes_t;

  type before_rom_t is array (0 to ROWS - 1) of std_logic_vector(0 to HEIGHT - 1);

  type slot_rom_t is array (0 to ROWS - 1) of natural range 0 to SLOTS - 1;

  -- For each top row t: the memories before its memory (t mod HEIGHT), which
  -- hold the column's later rows in the next slot.
  function before_rom return before_rom_t is
    variable r : before_rom_t;
  begin

    for t in r'range loop

      for m in 0 to HEIGHT - 1 loop

        r(t)(m) := to_sl(m < t mod HEIGHT);

      end loop;

    end loop;

    return r;

  end function before_rom;

  -- Physical row t's slot (t / HEIGHT) and the next (plus one, mod SLOTS).
  function slot_rom (next_slot : boolean) return slot_rom_t is
    variable r : slot_rom_t;
  begin

    for t in r'range loop

      r(t) := t / HEIGHT;

      if next_slot then
        r(t) := (t / HEIGHT + 1) mod SLOTS;
      end if;

    end loop;

    return r;

  end function slot_rom;

  type memory_rom_t is array (0 to ROWS - 1) of natural range 0 to HEIGHT - 1;

  -- For memory m, the slot it reads for each top row t: physical row t lives
  -- in memory t mod HEIGHT at slot t / HEIGHT; the memories before it hold the
  -- column's later rows, in the next slot.
  function slot_rom (m : natural) return slot_rom_t is
    variable r : slot_rom_t;
  begin

    for t in r'range loop

      r(t) := t / HEIGHT;

      if m < t mod HEIGHT then
        r(t) := (t / HEIGHT + 1) mod SLOTS;
      end if;

    end loop;

    return r;

  end function slot_rom;

  -- The top row's memory: the rotation of the column.
  function memory_rom return memory_rom_t is
    variable r : memory_rom_t;
  begin

    for t in r'range loop

      r(t) := t mod HEIGHT;

    end loop;

    return r;

  end function memory_rom;

  constant MEMORY_OF : memory_rom_t := memory_rom;
  constant BEFORE    : before_rom_t := before_rom;
  constant SLOT_OF   : slot_rom_t   := slot_rom(false);
  constant NEXT_SLOT : slot_rom_t   := slot_rom(true);

  -- Rotate left by `by` places (mod HEIGHT): element j takes element j + by.
  function rotate (b : bytes_t; by : natural) return bytes_t is
    variable r : bytes_t;
  begin

    for j in b'range loop

      r(j) := b((j + by) mod HEIGHT);

    end loop;

    return r;

  end function rotate;

  -- The pixel registered (A), then written (B) with its memory (one-hot) and
  -- address; the row being written: its memory (one-hot), slot and number.
  signal a_valid   : std_logic;
  signal a_new_row : std_logic;
  signal a_x       : unsigned(X_BITS - 1 downto 0);
  signal a_pixel   : std_logic_vector(7 downto 0);
  signal wr_memory : std_logic_vector(0 to HEIGHT - 1);
  signal wr_slot   : natural range 0 to SLOTS - 1;
  signal row_count : natural range 0 to ROWS - 1;
  signal row_last  : std_logic; -- row_count = ROWS - 1
  signal wr1_en    : std_logic_vector(0 to HEIGHT - 1);
  signal wr1_addr  : unsigned(SLOT_BITS + X_BITS - 1 downto 0);
  signal wr1_pixel : std_logic_vector(7 downto 0);

  signal take       : std_logic;
  signal req_valid  : std_logic;
  signal req_x      : unsigned(X_BITS - 1 downto 0);
  signal req_memory : natural range 0 to HEIGHT - 1;
  signal req_before : std_logic_vector(0 to HEIGHT - 1);
  signal req_slot   : unsigned(SLOT_BITS - 1 downto 0);
  signal req_next   : unsigned(SLOT_BITS - 1 downto 0);
  signal addr_valid : std_logic;
  signal rd_addr_x  : unsigned(X_BITS - 1 downto 0);
  signal shift      : unsigned(SHIFT_BITS - 1 downto 0);
  signal valid      : std_logic_vector(1 to LATENCY);
  signal shifts     : unsigned(SHIFT_BITS * (LATENCY + 1) - 1 downto 0);
  signal read_bytes : bytes_t;
  signal rotated    : rotations_t;
  -- Columns a request may still claim (taken requests leave when their
  -- column is popped), and whether one is left.
  signal free        : natural range 0 to CREDITS;
  signal room        : std_logic;
  signal fifo_ready  : std_logic;
  signal popped      : std_logic;
  signal column      : std_logic_vector(8 * HEIGHT - 1 downto 0);
  signal out_valid_i : std_logic;

begin

  assert SLOTS >= 1 and HEIGHT >= 2
    report "fastnms_orb_rows: HEIGHT must be at least 2"
    severity failure;

  row_index <= to_unsigned(row_count, row_index'length);

  -- A request is taken while its column has room in the FIFO.
  rd_ready <= room;
  take     <= rd_valid and room;

  write_side : process (clk) is

    variable memory : std_logic_vector(0 to HEIGHT - 1);
    variable slot   : natural range 0 to SLOTS - 1;
    variable row    : natural range 0 to ROWS;

  begin

    if rising_edge(clk) then
      a_valid   <= wr_valid;
      a_new_row <= to_sl(wr_x = 0);
      a_x       <= wr_x;
      a_pixel   <= wr_pixel;

      -- A row's first pixel starts the next row.
      memory := wr_memory;
      slot   := wr_slot;
      row    := row_count;
      if a_valid = '1' and a_new_row = '1' then
        row_last <= to_sl(row_count = ROWS - 2);
      end if;

      if a_new_row = '1' then
        memory := wr_memory(HEIGHT - 1) & wr_memory(0 to HEIGHT - 2);
        if wr_memory(HEIGHT - 1) = '1' then
          slot := (wr_slot + 1) mod SLOTS;
        end if;
        row := row_count + 1;
        if row_last = '1' then
          row := 0;
        end if;
      end if;

      wr1_en <= (others => '0');
      if a_valid = '1' then
        wr_memory <= memory;
        wr_slot   <= slot;
        row_count <= row;
        wr1_en    <= memory;
      end if;
      wr1_addr  <= to_unsigned(slot, SLOT_BITS) & a_x;
      wr1_pixel <= a_pixel;

      -- (Reset: the row before row 0, the last of the ring.)
      if rst = '1' then
        a_valid               <= '0';
        wr_memory             <= (others => '0');
        wr_memory(HEIGHT - 1) <= '1';
        wr_slot               <= SLOTS - 1;
        row_count             <= ROWS - 1;
        row_last              <= '1';
        wr1_en                <= (others => '0');
      end if;
    end if;

  end process write_side;

  control : process (clk) is

    variable more : natural range 0 to CREDITS + 1;

  begin

    if rising_edge(clk) then
      -- 1: the request registered, its top row split into its memory, its
      -- slot, the next slot and the memories before it (ROMs); 2: each
      -- memory's slot (the next one for the memories before the top row's)
      -- and the rotation.
      req_valid  <= take;
      req_x      <= rd_x;
      req_memory <= MEMORY_OF(to_integer(rd_top));
      req_before <= BEFORE(to_integer(rd_top));
      req_slot   <= to_unsigned(SLOT_OF(to_integer(rd_top)), SLOT_BITS);
      req_next   <= to_unsigned(NEXT_SLOT(to_integer(rd_top)), SLOT_BITS);
      addr_valid <= req_valid;
      rd_addr_x  <= req_x;
      shift      <= to_unsigned(req_memory, SHIFT_BITS);
      valid      <= addr_valid & valid(1 to LATENCY - 1);

      more := free;
      if take = '1' and popped = '0' then
        more := free - 1;
      elsif take = '0' and popped = '1' then
        more := free + 1;
      end if;
      free <= more;
      room <= to_sl(more /= 0);

      if rst = '1' then
        req_valid  <= '0';
        addr_valid <= '0';
        valid      <= (others => '0');
        free       <= CREDITS;
        room       <= '1';
      end if;
    end if;

  end process control;

  memories : for m in 0 to HEIGHT - 1 generate
    signal rd_slot : unsigned(SLOT_BITS - 1 downto 0);
    signal rd_addr : unsigned(SLOT_BITS + X_BITS - 1 downto 0);
  begin

    -- 2: the slot this memory reads.
    slot : process (clk) is
    begin

      if rising_edge(clk) then
        rd_slot <= req_slot;
        if req_before(m) = '1' then
          rd_slot <= req_next;
        end if;
      end if;

    end process slot;

    rd_addr <= rd_slot & rd_addr_x;

    row_memory : entity work.fastnms_ram_sdp
      generic map (
        DEPTH        => SLOTS * 2 ** X_BITS,
        WIDTH        => 8,
        READ_LATENCY => 2,
        STYLE        => "block"
      )
      port map (
        clk     => clk,
        wr_en   => wr1_en(m),
        wr_addr => wr1_addr,
        wr_data => wr1_pixel,
        rd_en   => '1',
        rd_addr => rd_addr,
        rd_data => read_bytes(m)
      );

  end generate memories;

  -- 3, 4: the memories' read; then the rotation, two stages a clock.
  rotation : process (clk) is

    variable r  : bytes_t;
    variable by : unsigned(SHIFT_BITS - 1 downto 0);

  begin

    if rising_edge(clk) then
      shifts <= shifts(shifts'high - SHIFT_BITS downto 0) & shift;

      for p in 0 to PAIRS - 1 loop

        if p = 0 then
          r := read_bytes;
        else
          r := rotated(p);
        end if;
        by := shifts(SHIFT_BITS * (1 + p) + SHIFT_BITS - 1 downto SHIFT_BITS * (1 + p));

        for k in 2 * p to minimum(2 * p + 1, SHIFT_BITS - 1) loop

          if by(k) = '1' then
            r := rotate(r, 2 ** k);
          end if;

        end loop;

        rotated(p + 1) <= r;

      end loop;

    end if;

  end process rotation;

  pack : for j in 0 to HEIGHT - 1 generate
    column(8 * j + 7 downto 8 * j) <= rotated(PAIRS)(j);
  end generate pack;

  columns : entity work.fastnms_fifo
    generic map (
      DEPTH => FIFO_DEPTH,
      WIDTH => 8 * HEIGHT,
      STYLE => "distributed"
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => valid(LATENCY),
      in_ready  => fifo_ready,
      in_data   => column,
      out_valid => out_valid_i,
      out_ready => out_ready,
      out_data  => out_column,
      busy      => open
    );

  out_valid <= out_valid_i;
  popped    <= out_valid_i and out_ready;

  -- pragma translate_off
  no_overflow : process (clk) is
  begin

    if rising_edge(clk) then
      if rst = '0' and valid(LATENCY) = '1' then
        assert fifo_ready = '1'
          report "fastnms_orb_rows: a column arrived at a full FIFO"
          severity error;
      end if;
    end if;

  end process no_overflow;

-- pragma translate_on

end architecture rtl;
