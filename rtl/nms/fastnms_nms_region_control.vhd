-- The region NMS's control: a column's decisions on flags only, registered
-- as the column's operation (op), which fastnms_nms_region_keys carries out
-- on the next clock; the stack entries' flags.
-- Datasheet: docs/fastnms_nms_region.md
-- Contract: docs/design/region_nms_pipeline.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;
  use work.fastnms_nms_region_pkg.all;

entity fastnms_nms_region_control is
  generic (
    MAX_WIDTH    : positive := 1920;
    MAX_HEIGHT   : positive := 4095;
    SCORE_BITS   : positive := 8;
    CONNECTIVITY : positive := 8
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- The schedule's step (fastnms_nms_region_schedule): this clock's steps,
    -- the current row, the reader's bits and position.
    step : in    step_t(cx(clog2(MAX_WIDTH) - 1 downto 0), cy(bits_for(MAX_HEIGHT) - 1 downto 0),
                        ahead_slot(slot_bits(MAX_WIDTH) - 1 downto 0));
    -- The current pixel: its corner bit, the end of its line, its score.
    c0    : in    std_logic;
    c_eol : in    std_logic;
    score : in    unsigned(SCORE_BITS - 1 downto 0);
    -- The previous-row run's head and last bits (fastnms_nms_region_tables).
    run : in    run_t(data(data_bits(MAX_WIDTH, MAX_HEIGHT, SCORE_BITS) - 1 downto 0));
    -- The last table's write landing now, and whether it is to slot 0 (a
    -- last bit taken at column 0 on the clock before may change then).
    last_w : in    bit_table_write_t(addr(slot_bits(MAX_WIDTH) downto 0));
    -- The column's operation, registered.
    cmd : out   command_t(slot(slot_bits(MAX_WIDTH) - 1 downto 0), score(SCORE_BITS - 1 downto 0),
                          cx(clog2(MAX_WIDTH) - 1 downto 0), cy(bits_for(MAX_HEIGHT) - 1 downto 0),
                          ram_wa(clog2(stack_ram_words(MAX_WIDTH)) - 1 downto 0),
                          ram_ra(clog2(stack_ram_words(MAX_WIDTH)) - 1 downto 0))
  );
end entity fastnms_nms_region_control;

architecture rtl of fastnms_nms_region_control is

  constant SB          : positive := slot_bits(MAX_WIDTH);
  constant STACK_DEPTH : positive := stack_entries(MAX_WIDTH);
  constant STACK_WORDS : positive := stack_ram_words(MAX_WIDTH);
  constant DB          : positive := bits_for(STACK_DEPTH);
  constant RB          : positive := clog2(STACK_WORDS);

  -- Current run.
  signal attached : std_logic;
  signal active   : std_logic;

  -- Stack flags: top, second, and a copy of the flag RAM's word below them
  -- (refreshed two clocks after a pop: third_rd1, third_rd2).
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

  -- The stack's flag RAM, below its registers.
  signal flags_we : std_logic;
  signal flags_wa : unsigned(RB - 1 downto 0);
  signal flags_wd : std_logic_vector(FLAG_BITS - 1 downto 0);
  signal flags_re : std_logic;
  signal flags_ra : unsigned(RB - 1 downto 0);
  signal flags_rd : std_logic_vector(FLAG_BITS - 1 downto 0);

  -- The operation.
  signal op_r      : op_t;
  signal ram_wa    : unsigned(RB - 1 downto 0);
  signal op_slot   : unsigned(SB - 1 downto 0);
  signal op_score  : unsigned(SCORE_BITS - 1 downto 0);
  signal op_cx     : unsigned(clog2(MAX_WIDTH) - 1 downto 0);
  signal op_cy     : unsigned(bits_for(MAX_HEIGHT) - 1 downto 0);
  signal ram_ra    : unsigned(RB - 1 downto 0);
  signal checks_on : boolean; -- false until the first reset: the invariants hold from then on

begin

  assert CONNECTIVITY = 4 or CONNECTIVITY = 8
    report "fastnms_nms_region_control: CONNECTIVITY must be 4 or 8"
    severity failure;
  assert MAX_WIDTH >= 3
    report "fastnms_nms_region_control: MAX_WIDTH must be at least 3"
    severity failure;

  cmd <=
  (
    op     => op_r,
    slot   => op_slot,
    score  => op_score,
    cx     => op_cx,
    cy     => op_cy,
    ram_wa => ram_wa,
    ram_ra => ram_ra
  );

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
    variable r_eol     : boolean;
    variable row_ends  : boolean;
    variable touch     : boolean;
    variable o         : op_t;
    variable o_ram_wa  : unsigned(RB - 1 downto 0);
    variable o_ram_ra  : unsigned(RB - 1 downto 0);

    variable run_starts : boolean;
    variable p_start    : boolean;
    variable p_end      : boolean;

  begin

    if rising_edge(clk) then
      -- The stack's flags before this clock's step: the flag RAM's word
      -- below the second entry (two clocks after a pop), and a last bit
      -- taken at column 0 on the clock before, which the previous row's
      -- last column may rewrite then (the data path writes a clock after the
      -- control decides): that write is landing now.
      pre_third := third;
      if third_rd2 = '1' then
        pre_third := unpack(flags_rd);
      end if;
      pre_top := top;
      if fix_last = '1' and last_w.en = '1' and last_w.s0 = '1' then
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

      r_eol    := step.r_last = '1';
      row_ends := c_eol = '1';

      o             := op_r;
      o_ram_wa      := ram_wa;
      o_ram_ra      := ram_ra;
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
      o.rv          := step.rstep;
      o.cv          := step.cstep;
      o.bank        := step.cur_bank;
      o.r_col0      := step.r_col0;

      -- synthesis translate_off
      if rst = '1' then
        checks_on <= true;
      end if;
      -- synthesis translate_on

      -- The step's decisions are made as if both sides stepped, from
      -- registers only: the reader's state (the stack) takes them when the
      -- reader steps (rstep), the current row's (attached, active) when the
      -- current row steps (cstep), and the data path gets both enables with
      -- the operation. Rows >= 1 step both sides together; a first row has
      -- no reader events, a flush no current row (first_row, a register,
      -- says which).

      -- The previous-row run at the reader's column: its bits are the
      -- tables' (run.head, run.last), with the previous row's last writes
      -- taken as they land.
      p_start := step.p0 = '1' and step.pm = '0';
      p_end   := (step.pm = '1' and step.p0 = '0') or (step.p0 = '1' and r_eol);

      -- synthesis translate_off
      assert not (step.rstep = '1' and p_start and run.head = '0' and v_depth = 0)
        report "fastnms_nms_region: a continuing run without an open class"
        severity failure;
      -- synthesis translate_on

      -- 1. A previous-row run starts at rcol: a run that is not its class's
      -- first continues the top's class (classes nest), a first run pushes.
      if p_start then
        if run.head = '0' then
          v_top.last := run.last;
        else
          o.push     := '1';
          o.push_ram := not below2(DB);
          o_ram_wa   := resize(unsigned(below2(DB - 1 downto 0)), RB);
          if below2 >= 0 then
            v_third := v_second;
          end if;
          v_second := v_top;
          v_top    := (last => run.last, runs => '0', merged => '0');
          v_depth  := v_depth + 1;
          pushed   := true;
        end if;
      end if;

      -- 2. A current-row run starts: a class of its own for now.
      run_starts := c0 = '1' and step.cm = '0';
      if run_starts then
        o.start := '1';
        v_att   := '0';
        v_act   := '1';
      end if;

      -- 3. Contact between the current run and the top's run (rows >= 1).
      if step.first_row = '0' then
        touch := (c0 = '1' and step.p0 = '1') or
                 (CONNECTIVITY = 8 and ((c0 = '1' and step.pm = '1') or (step.cm = '1' and step.p0 = '1')));
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
      if c0 = '1' and step.cm = '1' then
        o.pix_top := v_att;
        o.pix_cur := not v_att;
      end if;

      -- 5. The current run ends (at cx - 1, or at cx at the end of the row).
      if (step.cm = '1' and c0 = '0') or (c0 = '1' and row_ends) then
        o.cur_final := not v_att;
        v_act       := '0';
        v_att       := '0';
      end if;

      -- 6. A previous-row run ends: the last run of its class pops it. (In
      -- a flush, the current row's attached is '0': a first row has no
      -- contact.)
      if p_end and v_top.last = '1' then
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
        o_ram_ra  := resize(unsigned(below(DB - 1 downto 0)), RB);
        if popped.merged = '1' then
          o.pop_merged := '1';
          v_top.runs   := popped.runs;
        elsif v_act = '1' and v_att = '1' and step.first_row = '0' then
          o.pop_detach := '1';
          v_att        := '0';
        elsif popped.runs = '1' then
          o.pop_final := '1';
        else
          o.pop_emit := '1';
        end if;
      end if;

      if row_ends then
        v_act := '0';
        v_att := '0';
      end if;

      o.k_base_pushed := o.push and step.rstep;
      o.k_merge_cur   := o.attach and not o.start and step.rstep;
      o.k_merge_pix   := o.attach and o.start and step.rstep;
      o.k_merge_top   := o.takeover and step.rstep;
      o.k_pix         := o.pix_top and step.cstep;
      o.k_keep_top    := o.pop and not o.pop_merged and o.push and step.rstep;
      o.k_take_second := o.pop and not o.pop_merged and not o.push and step.rstep;
      o.k_cur_start   := o.start and step.cstep;
      o.k_cur_pix     := o.pix_cur and step.cstep;
      o.k_detach      := o.pop_detach and step.rstep;
      o.k_final       := o.pop_final and step.rstep;

      -- The reader's side.
      flags_we  <= step.rstep and o.push_ram;
      flags_wa  <= o_ram_wa;
      flags_wd  <= pack(second);
      flags_re  <= step.rstep and o.pop and o.pop_ram;
      flags_ra  <= o_ram_ra;
      fix_last  <= step.rstep and to_sl(p_start) and step.r_col0;
      third_rd2 <= third_rd1 and not (step.rstep and o.push_ram);
      third_rd1 <= step.rstep and o.pop and o.pop_ram;
      if step.rstep = '1' then
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
      assert not (step.rstep = '1' and v_depth > STACK_DEPTH)
        report "fastnms_nms_region: stack overflow"
        severity failure;
      assert not checks_on or rst = '1' or
             (below2 = signed('0' & depth) - 2 and below3 = signed('0' & depth) - 3 and
              below4 = signed('0' & depth) - 4)
        report "fastnms_nms_region: below2, below3 or below4 out of step with the depth"
        severity failure;
      assert not (step.lock = '1' and row_ends and v_depth /= 0)
        report "fastnms_nms_region: classes left open at the end of a row"
        severity failure;
      -- synthesis translate_on

      -- The current row's side.
      if step.cstep = '1' then
        attached <= v_att;
        active   <= v_act;
      end if;

      if step.flush_ends = '1' then
        o.flush_ends := '1';
      end if;

      op_r     <= o;
      ram_wa   <= o_ram_wa;
      ram_ra   <= o_ram_ra;
      op_slot  <= step.ahead_slot;
      op_score <= score;
      op_cx    <= step.cx;
      op_cy    <= step.cy;

      if rst = '1' then
        depth              <= (others => '0');
        below2             <= to_signed(-2, DB + 1);
        below3             <= to_signed(-3, DB + 1);
        below4             <= to_signed(-4, DB + 1);
        attached           <= '0';
        active             <= '0';
        flags_we           <= '0';
        flags_re           <= '0';
        third_rd1          <= '0';
        third_rd2          <= '0';
        fix_last           <= '0';
        op_r.push          <= '0';
        op_r.push_ram      <= '0';
        op_r.start         <= '0';
        op_r.attach        <= '0';
        op_r.takeover      <= '0';
        op_r.pix_top       <= '0';
        op_r.pix_cur       <= '0';
        op_r.cur_final     <= '0';
        op_r.pop           <= '0';
        op_r.pop_ram       <= '0';
        op_r.rv            <= '0';
        op_r.cv            <= '0';
        op_r.flush_ends    <= '0';
        op_r.k_base_pushed <= '0';
        op_r.k_merge_cur   <= '0';
        op_r.k_merge_pix   <= '0';
        op_r.k_merge_top   <= '0';
        op_r.k_pix         <= '0';
        op_r.k_keep_top    <= '0';
        op_r.k_take_second <= '0';
        op_r.k_cur_start   <= '0';
        op_r.k_cur_pix     <= '0';
        op_r.k_detach      <= '0';
        op_r.k_final       <= '0';
      end if;
    end if;

  end process control;

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

end architecture rtl;
