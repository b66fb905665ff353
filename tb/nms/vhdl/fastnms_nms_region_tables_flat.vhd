-- fastnms_nms_region_tables with flat ports, for its cocotb testbench
-- (tb/nms/region_tables_tb.py): GHDL's VPI does not show record ports. The
-- inputs are the fields the tables read, under the names they had as ports
-- (op as to_slv packs it); the fields they do not read are zero.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_nms_region_pkg.all;

entity fastnms_nms_region_tables_flat is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 4095;
    SCORE_BITS : positive := 8
  );
  port (
    clk             : in    std_logic;
    rst             : in    std_logic;
    rstep           : in    std_logic;
    pm              : in    std_logic;
    p0              : in    std_logic;
    r_last          : in    std_logic;
    r_col0          : in    std_logic;
    r_col1          : in    std_logic;
    r_col2          : in    std_logic;
    r_slot0         : in    std_logic;
    r_bank          : in    std_logic;
    ahead_slot      : in    unsigned(slot_bits(MAX_WIDTH) - 1 downto 0);
    op              : in    std_logic_vector(OP_BITS - 1 downto 0);
    op_slot         : in    unsigned(slot_bits(MAX_WIDTH) - 1 downto 0);
    data_w_en       : in    std_logic;
    data_w_slot     : in    unsigned(slot_bits(MAX_WIDTH) - 1 downto 0);
    data_w_key      : in    unsigned(data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS) - 1 downto 0);
    data_w_s0       : in    std_logic;
    head_w_en       : in    std_logic;
    head_w_addr     : in    unsigned(slot_bits(MAX_WIDTH) downto 0);
    head_w_bit      : in    std_logic;
    head_w_s1       : in    std_logic;
    head_spare_en   : in    std_logic;
    head_spare_addr : in    unsigned(slot_bits(MAX_WIDTH) downto 0);
    head_spare_bit  : in    std_logic;
    head_spare_s1   : in    std_logic;
    last_w_en       : in    std_logic;
    last_w_addr     : in    unsigned(slot_bits(MAX_WIDTH) downto 0);
    last_w_bit      : in    std_logic;
    last_w_s0       : in    std_logic;
    last_w_s1       : in    std_logic;
    run_head        : out   std_logic;
    run_last        : out   std_logic;
    data_word       : out   unsigned(data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS) - 1 downto 0)
  );
end entity fastnms_nms_region_tables_flat;

architecture wrapper of fastnms_nms_region_tables_flat is

  constant XB : positive := clog2(MAX_WIDTH);
  constant YB : positive := bits_for(MAX_HEIGHT);
  constant SB : positive := slot_bits(MAX_WIDTH);
  constant DB : positive := data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS);
  constant RB : positive := clog2(stack_ram_words(MAX_WIDTH));

  signal step   : step_t(cx(XB - 1 downto 0), cy(YB - 1 downto 0), ahead_slot(SB - 1 downto 0));
  signal cmd    : command_t(slot(SB - 1 downto 0), score(SCORE_BITS - 1 downto 0), cx(XB - 1 downto 0),
                            cy(YB - 1 downto 0), ram_wa(RB - 1 downto 0), ram_ra(RB - 1 downto 0));
  signal writes : writes_t(data(slot(SB - 1 downto 0), word(DB - 1 downto 0)), head(addr(SB downto 0)),
                           head_spare(addr(SB downto 0)), last(addr(SB downto 0)));
  signal run    : run_t(data(DB - 1 downto 0));

begin

  step <=
  (
    cstep      => '0',
    rstep      => rstep,
    lock       => '0',
    flush_ends => '0',
    first_row  => '0',
    cm         => '0',
    cx         => (others => '0'),
    cy         => (others => '0'),
    cur_bank   => '0',
    pm         => pm,
    p0         => p0,
    r_last     => r_last,
    r_col0     => r_col0,
    r_col1     => r_col1,
    r_col2     => r_col2,
    r_slot0    => r_slot0,
    r_bank     => r_bank,
    ahead_slot => ahead_slot
  );

  cmd <=
  (
    op     => to_op(op),
    slot   => op_slot,
    score  => (others => '0'),
    cx     => (others => '0'),
    cy     => (others => '0'),
    ram_wa => (others => '0'),
    ram_ra => (others => '0')
  );

  writes.data       <= (en => data_w_en, slot => data_w_slot, word => data_w_key, s0 => data_w_s0);
  writes.head       <= (en => head_w_en, addr => head_w_addr, data => head_w_bit, s0 => '0', s1 => head_w_s1);
  writes.head_spare <=
  (
    en   => head_spare_en,
    addr => head_spare_addr,
    data => head_spare_bit,
    s0   => '0',
    s1   => head_spare_s1
  );
  writes.last       <= (en => last_w_en, addr => last_w_addr, data => last_w_bit, s0 => last_w_s0, s1 => last_w_s1);

  tables : entity work.fastnms_nms_region_tables
    generic map (
      MAX_WIDTH  => MAX_WIDTH,
      MAX_HEIGHT => MAX_HEIGHT,
      SCORE_BITS => SCORE_BITS
    )
    port map (
      clk    => clk,
      rst    => rst,
      step   => step,
      cmd    => cmd,
      writes => writes,
      run    => run
    );

  run_head  <= run.head;
  run_last  <= run.last;
  data_word <= run.data;

end architecture wrapper;
