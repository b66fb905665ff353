-- Probe, not part of the core: the control of one column of the region NMS's
-- step (golden/region_stream.py, RegionStream.step) on its own: the stack
-- entries' flags, the current run's two flags and the decisions, from
-- registered inputs to a registered operation code, with no slot, key or
-- table address. It measures how deep the step's decisions are when slots
-- and keys follow them a clock later. The stack's depth is left out (kept as
-- registers beside it, it is not on these paths). flows/synth/test_synth.py
-- maps it with the same flow as the core and records its logic levels
-- (docs/fastnms_nms_region.md, Depth and clock).
library ieee;
  use ieee.std_logic_1164.all;

entity step_control is
  generic (
    CONNECTIVITY : positive := 4
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- This column's steps: the reader, the current row, both in lock-step.
    in_rstep : in    std_logic;
    in_cstep : in    std_logic;
    in_lock  : in    std_logic;
    -- The previous row's bits at the reader (pm at x - 1, p0 at x), its run's
    -- head and last bits, the reader's last column; the current row's bits.
    in_p0    : in    std_logic;
    in_pm    : in    std_logic;
    in_head  : in    std_logic;
    in_last  : in    std_logic;
    in_r_eol : in    std_logic;
    in_c0    : in    std_logic;
    in_cm    : in    std_logic;
    in_c_eol : in    std_logic;
    -- The third entry's flags, from the stack's RAM.
    in_third_v : in    std_logic;
    in_third   : in    std_logic_vector(2 downto 0);
    -- Operations for the slots and keys: continue, push, run start, attach,
    -- attach to a class with runs (two bit writes), take over the class
    -- below, pixel to the top or to the current class, finalize the current
    -- class, pop, and the pop's kind (merged, detach, finalize, emit).
    out_op : out   std_logic_vector(13 downto 0)
  );
end entity step_control;

architecture rtl of step_control is

  type flags_t is record
    last   : std_logic;
    runs   : std_logic;
    merged : std_logic;
  end record flags_t;

  constant NO_FLAGS : flags_t := (last => '0', runs => '0', merged => '0');

  signal rstep   : std_logic;
  signal cstep   : std_logic;
  signal lock    : std_logic;
  signal p0      : std_logic;
  signal pm      : std_logic;
  signal head    : std_logic;
  signal last    : std_logic;
  signal r_eol   : std_logic;
  signal c0      : std_logic;
  signal cm      : std_logic;
  signal c_eol   : std_logic;
  signal third_v : std_logic;
  signal third_r : flags_t;

  signal attached : std_logic;
  signal active   : std_logic;
  signal top      : flags_t;
  signal second   : flags_t;
  signal third    : flags_t;

begin

  step : process (clk) is

    variable v_top    : flags_t;
    variable v_second : flags_t;
    variable v_third  : flags_t;
    variable popped   : flags_t;
    variable v_att    : std_logic;
    variable v_act    : std_logic;
    variable p_start  : boolean;
    variable p_end    : boolean;
    variable pushed   : boolean;
    variable touch    : boolean;
    variable op       : std_logic_vector(13 downto 0);

  begin

    if rising_edge(clk) then
      rstep   <= in_rstep;
      cstep   <= in_cstep;
      lock    <= in_lock;
      p0      <= in_p0;
      pm      <= in_pm;
      head    <= in_head;
      last    <= in_last;
      r_eol   <= in_r_eol;
      c0      <= in_c0;
      cm      <= in_cm;
      c_eol   <= in_c_eol;
      third_v <= in_third_v;
      third_r <= (last => in_third(2), runs => in_third(1), merged => in_third(0));

      op       := (others => '0');
      v_top    := top;
      v_second := second;
      v_third  := third;
      v_att    := attached;
      v_act    := active;
      if third_v = '1' then
        v_third := third_r;
      end if;

      -- 1. A previous-row run starts: it continues the top or pushes.
      p_start := rstep = '1' and p0 = '1' and pm = '0';
      pushed  := p_start and head = '1';
      if p_start and head = '0' then
        v_top.last := last;
        op(0)      := '1';
      end if;
      if pushed then
        v_third  := v_second;
        v_second := v_top;
        v_top    := (last => last, runs => '0', merged => '0');
        op(1)    := '1';
      end if;

      -- 2. A current-row run starts.
      if cstep = '1' and c0 = '1' and cm = '0' then
        v_att := '0';
        v_act := '1';
        op(2) := '1';
      end if;

      -- 3. Contact with the top's run.
      touch := lock = '1' and
               ((c0 = '1' and p0 = '1') or
                (CONNECTIVITY = 8 and ((c0 = '1' and pm = '1') or (cm = '1' and p0 = '1'))));
      if touch then
        if v_att = '0' then
          op(3)      := '1';
          op(4)      := v_top.runs;
          v_top.runs := '1';
          v_att      := '1';
        elsif pushed then
          op(5)        := '1';
          v_top.runs   := v_second.runs;
          v_top.merged := '1';
        end if;
      end if;

      -- 4. The pixel joins its run's class.
      if cstep = '1' and c0 = '1' and cm = '1' then
        op(6) := v_att;
        op(7) := not v_att;
      end if;

      -- 5. The current run ends.
      if cstep = '1' and ((cm = '1' and c0 = '0') or (c0 = '1' and c_eol = '1')) then
        op(8) := not v_att;
        v_act := '0';
        v_att := '0';
      end if;

      -- 6. A previous-row run ends: the last run of its class pops it.
      p_end := rstep = '1' and ((pm = '1' and p0 = '0') or (p0 = '1' and r_eol = '1'));
      if p_end and v_top.last = '1' then
        popped   := v_top;
        v_top    := v_second;
        v_second := v_third;
        v_third  := NO_FLAGS;
        op(9)    := '1';
        if popped.merged = '1' then
          v_top.runs := popped.runs;
          op(10)     := '1';
        elsif v_act = '1' and v_att = '1' then
          v_att  := '0';
          op(11) := '1';
        elsif popped.runs = '1' then
          op(12) := '1';
        else
          op(13) := '1';
        end if;
      end if;

      if cstep = '1' and c_eol = '1' then
        v_act := '0';
        v_att := '0';
      end if;

      top      <= v_top;
      second   <= v_second;
      third    <= v_third;
      attached <= v_att;
      active   <= v_act;
      out_op   <= op;

      if rst = '1' then
        attached <= '0';
        active   <= '0';
      end if;
    end if;

  end process step;

end architecture rtl;
