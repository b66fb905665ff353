-- Probe, not part of the core: the region NMS's key data path
-- (rtl/nms/fastnms_nms_region.vhd, process apply) with its comparisons made
-- ahead and kept up to date as order flags, to measure the depth of such a
-- data path in this flow (docs/fastnms_nms_region.md, Depth and clock).
--
-- Seven key registers: the stack's top, second and third (T, S, R), the
-- current class (C), the pushed word of this column and of the next (W, N),
-- the data table write landing now (L); and the pixel (X). Beside them, one
-- order flag per pair of key registers (K_i >= K_j) and one per key register
-- against the pixel (on scores: every class's best pixel comes before the
-- pixel in raster order). A column chooses its merged key and every
-- register's next key as apply does, from the operation's bits and the
-- decision (the best of the base, the class merging in and the pixel; the
-- current class or the pixel), and every next flag from the flags of the
-- two sources of its keys. No slot, table write, stack address or control
-- is modelled, and keys entering from a memory (the stack RAM into R, the
-- data table into N) come with their flags against the registers as inputs
-- (comparing them ahead is left out): the probe gives a lower bound on such
-- a data path's depth.
--   DECIDED_AHEAD false: the decision is made from the flags in the clock.
--     true: it is a register, made a clock ahead from the next flags, with
--     the next column's operand sources chosen two clocks ahead (the
--     control would then run three clocks ahead of the data path; the probe
--     takes each operation two clocks before it is carried out, in both
--     modes).
--   PIXEL_AHEAD false: the next pixel's score is compared with every
--     source's key in the clock. true: those comparisons come in as
--     registers.
-- flows/synth/test_synth.py maps it with the core's flow; tb/probes/
-- simulates it against a model that compares the keys themselves.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity key_flags is
  generic (
    SCORE_BITS    : positive := 12;
    POS_BITS      : positive := 22;
    DECIDED_AHEAD : boolean  := false;
    PIXEL_AHEAD   : boolean  := false
  );
  port (
    clk : in    std_logic;
    -- The operation's bits (OP_*, below), as the block's control registers
    -- them.
    in_op : in    std_logic_vector(22 downto 0);
    -- Keys: score, then the inverted row and column (larger is better). The
    -- next pixel, with PIXEL_AHEAD its comparisons (the key from each source
    -- below >= the next pixel); the words entering R and N, with their flags
    -- (>=) against the key registers T .. N, the pixel (7) and each other (8).
    in_next_pixel : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_next_ge    : in    std_logic_vector(9 downto 0);
    in_stack_word : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_stack_ge   : in    std_logic_vector(8 downto 0);
    in_table_word : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_table_ge   : in    std_logic_vector(8 downto 0);
    -- The key registers T .. N, T in the low bits.
    out_keys : out   unsigned(7 * (SCORE_BITS + POS_BITS) - 1 downto 0)
  );
end entity key_flags;

architecture rtl of key_flags is

  constant KB : positive := SCORE_BITS + POS_BITS;

  subtype key_t is unsigned(KB - 1 downto 0);

  -- The earliest pixel with score 0: the registers' value before any key,
  -- before every pixel in raster order.
  constant INIT_KEY : key_t := (KB - 1 downto POS_BITS => '0') & (POS_BITS - 1 downto 0 => '1');

  -- Where a key comes from: a register, the pixel, or a memory's word.
  constant T  : natural := 0;
  constant S  : natural := 1;
  constant R  : natural := 2;
  constant C  : natural := 3;
  constant W  : natural := 4;
  constant L  : natural := 5;
  constant N  : natural := 6;
  constant X  : natural := 7;
  constant FR : natural := 8;  -- the stack RAM's word, into R
  constant FN : natural := 9;  -- the data table's word, into N
  constant XN : natural := 10; -- the next pixel

  -- The operation's bits: the base and the class merging in (one-hot; no
  -- merge bit: none merges), the pixel joining, the top's, the current
  -- class's and the table write's choices as in apply, the moves of the
  -- second, third, word and next word (2-bit codes), a new pixel.
  constant OP_BASE_TOP    : natural := 0;
  constant OP_BASE_LAND   : natural := 1;
  constant OP_BASE_WORD   : natural := 2;
  constant OP_MERGE_CUR   : natural := 3;
  constant OP_MERGE_PIX   : natural := 4;
  constant OP_MERGE_TOP   : natural := 5;
  constant OP_PIX_JOINS   : natural := 6;
  constant OP_KEEP_TOP    : natural := 7;
  constant OP_TAKE_SECOND : natural := 8;
  constant OP_CUR_START   : natural := 9;
  constant OP_CUR_PIX     : natural := 10;
  constant OP_DETACH      : natural := 11;
  constant OP_FINAL       : natural := 12;
  constant OP_SPARE       : natural := 13;
  constant OP_SECOND      : natural := 14; -- 01: T (push), 10: R (pop)
  constant OP_THIRD       : natural := 16; -- 01: S (push), 10: the stack word
  constant OP_WORD        : natural := 18; -- 01: N (step), 10: L (forward)
  constant OP_NEXT        : natural := 20; -- 01: the table word, 10: L
  constant OP_PIX_STEP    : natural := 22;

  subtype member_t is natural range T to N;

  subtype source_t is natural range T to XN;

  -- The decision's outcomes: the best is the base, the class merging in or
  -- the pixel.
  subtype outcome_t is natural range 0 to 2;

  type keys_t is array (member_t) of key_t;

  type source_keys_t is array (source_t) of key_t;

  subtype onehot_t is std_logic_vector(source_t);

  type onehots_t is array (member_t) of onehot_t;

  type outcome_srcs_t is array (outcome_t) of onehots_t;

  type outcome_keys_t is array (outcome_t) of key_t;

  type by_cur_t is array (0 to 1) of std_logic_vector(2 downto 0);

  type decisions_t is array (outcome_t) of by_cur_t;

  type onehot_by_cur_t is array (0 to 1) of onehot_t;

  type onehot_by_outcome_t is array (outcome_t) of onehot_by_cur_t;

  -- ge(a)(b): the key from a >= the key from b.
  type ge_t is array (source_t) of std_logic_vector(source_t);

  type pair_flags_t is array (member_t) of std_logic_vector(member_t);

  function score_of (k : key_t) return unsigned is
  begin

    return k(KB - 1 downto POS_BITS);

  end function score_of;

  function one (i : source_t) return onehot_t is
    variable v : onehot_t;
  begin

    v    := (others => '0');
    v(i) := '1';
    return v;

  end function one;

  function choose (sel : boolean; a, b : onehot_t) return onehot_t is
  begin

    if sel then
      return a;
    end if;

    return b;

  end function choose;

  -- A 2-bit move code: 01 and 10 choose a and b, else the register stays.
  function move (code : std_logic_vector(1 downto 0); stay, a, b : source_t) return onehot_t is
  begin

    if code = "01" then
      return one(a);
    elsif code = "10" then
      return one(b);
    end if;

    return one(stay);

  end function move;

  -- An operation's base (is_base) or class merging in, one-hot over the
  -- registers (the pixel merging in is pix).
  function operands (o : std_logic_vector(22 downto 0); is_base : boolean; pix : onehot_t) return onehot_t is
    variable v : onehot_t;
  begin

    v := (others => '0');

    if is_base then
      v(T) := o(OP_BASE_TOP);
      v(L) := o(OP_BASE_LAND);
      v(W) := o(OP_BASE_WORD);
    else
      v(C) := o(OP_MERGE_CUR);
      v(T) := o(OP_MERGE_TOP);
      if o(OP_MERGE_PIX) = '1' then
        v := v or pix;
      end if;
    end if;

    return v;

  end function operands;

  -- Every register's next source for an operation, with the best operand
  -- (0: the base, 1: the class merging in, 2: the pixel) and the current
  -- class (the pixel, or itself).
  function sources (o : std_logic_vector(22 downto 0); outcome : outcome_t; cur_is_pix : boolean)
    return onehots_t is
    variable best : onehot_t;
    variable cur  : onehot_t;
    variable src  : onehots_t;
  begin

    if outcome = 0 then
      best := operands(o, true, one(X));
    elsif outcome = 1 then
      best := operands(o, false, one(X));
    else
      best := one(X);
    end if;

    cur    := choose(cur_is_pix, one(X), one(C));
    src(T) := choose(o(OP_KEEP_TOP) = '1', one(T), choose(o(OP_TAKE_SECOND) = '1', one(S), best));
    src(S) := move(o(OP_SECOND + 1 downto OP_SECOND), S, T, R);
    src(R) := move(o(OP_THIRD + 1 downto OP_THIRD), R, S, FR);
    src(C) := choose(o(OP_DETACH) = '1', best, cur);
    src(W) := move(o(OP_WORD + 1 downto OP_WORD), W, N, L);
    src(L) := choose(o(OP_SPARE) = '1', one(C), choose(o(OP_FINAL) = '1', best, cur));
    src(N) := move(o(OP_NEXT + 1 downto OP_NEXT), N, FN, L);
    return src;

  end function sources;

  -- The flag between the keys from two one-hot sources.
  function flag_of (ge : ge_t; a, b : onehot_t) return std_logic is
    variable f : std_logic;
  begin

    f := '0';
    for i in source_t loop
      for j in source_t loop
        f := f or (a(i) and b(j) and ge(i)(j));
      end loop;
    end loop;
    return f;

  end function flag_of;

  function key_of (vals : source_keys_t; src : onehot_t) return key_t is
    variable k : key_t;
  begin

    k := (others => '0');
    for a in source_t loop

      if src(a) = '1' then
        k := k or vals(a);
      end if;

    end loop;
    return k;

  end function key_of;

  -- Registers: keys and flags start equal (INIT_KEY), so every flag is '1'.
  signal keys     : keys_t                     := (others => INIT_KEY);
  signal pixel    : key_t                      := INIT_KEY;
  signal pair_ge  : pair_flags_t               := (others => (others => '1'));
  signal pixel_ge : std_logic_vector(member_t) := (others => '1');
  -- The operation a clock before it is carried out (op_ahead), then carried
  -- out (op); at first the top's key stays and the current class goes on.
  -- The decision: the best is the base (0), the class merging in (1), else
  -- the pixel; the current class is the pixel (2).
  constant OP_IDLE : std_logic_vector(22 downto 0) :=
  (OP_BASE_TOP => '1', OP_KEEP_TOP => '1', others => '0');

  signal op_ahead : std_logic_vector(22 downto 0) := OP_IDLE;
  signal op       : std_logic_vector(22 downto 0) := OP_IDLE;
  signal decision : std_logic_vector(2 downto 0)  := "001";
  -- With DECIDED_AHEAD: the next decision's operands (the next base and
  -- class merging in, the next current class), by this column's outcome and
  -- current class.
  signal n_base_r  : onehot_by_outcome_t := (others => (others => (T => '1', others => '0')));
  signal n_merge_r : onehot_by_outcome_t := (others => (others => (others => '0')));
  signal n_cur_r   : onehot_by_outcome_t := (others => (others => (C => '1', others => '0')));
  signal next_pix  : key_t;
  signal next_in   : std_logic_vector(9 downto 0);
  signal stack_wd  : key_t;
  signal stack_ge  : std_logic_vector(8 downto 0);
  signal table_wd  : key_t;
  signal table_ge  : std_logic_vector(8 downto 0);

begin

  step : process (clk) is

    variable ge        : ge_t;
    variable vals      : source_keys_t;
    variable base      : onehot_t;
    variable merge     : onehot_t;
    variable any_merge : boolean;
    variable pix_joins : boolean;
    variable b_ge_m    : boolean;
    variable b_ge_p    : boolean;
    variable m_ge_p    : boolean;
    variable cur_pix   : boolean;
    variable outcome   : outcome_t;
    variable src       : outcome_srcs_t;
    variable cand_key  : outcome_keys_t;
    variable cand_flag : std_logic_vector(outcome_t);
    variable next_px   : onehot_t;
    variable n_base    : onehot_t;
    variable n_merge   : onehot_t;
    variable n_any     : boolean;
    variable n_joins   : boolean;
    variable cand_dec  : decisions_t;
    variable ahead     : onehots_t;

  begin

    if rising_edge(clk) then
      -- Every flag between two sources, from registers (the opposite
      -- order's is the complement: equal keys are the same key, and either
      -- choice between them is right).
      ge := (others => (others => '1'));
      for i in member_t loop
        for j in member_t loop
          if i < j then
            ge(i)(j) := pair_ge(i)(j);
            ge(j)(i) := not pair_ge(i)(j);
          end if;
        end loop;
        ge(i)(X)  := pixel_ge(i);
        ge(X)(i)  := not pixel_ge(i);
        ge(FR)(i) := stack_ge(i);
        ge(i)(FR) := not stack_ge(i);
        ge(FN)(i) := table_ge(i);
        ge(i)(FN) := not table_ge(i);
      end loop;
      ge(FR)(X)  := stack_ge(7);
      ge(X)(FR)  := not stack_ge(7);
      ge(FN)(X)  := table_ge(7);
      ge(X)(FN)  := not table_ge(7);
      ge(FR)(FN) := stack_ge(8);
      ge(FN)(FR) := not stack_ge(8);
      for i in member_t loop
        vals(i) := keys(i);
      end loop;
      vals(X)  := pixel;
      vals(FR) := stack_wd;
      vals(FN) := table_wd;
      vals(XN) := next_pix;
      -- The next pixel against every source, on scores.
      for a in T to FN loop
        if PIXEL_AHEAD then
          ge(a)(XN) := next_in(a);
        else
          ge(a)(XN) := '0';
          if score_of(vals(a)) >= score_of(next_pix) then
            ge(a)(XN) := '1';
          end if;
        end if;
        ge(XN)(a) := not ge(a)(XN);
      end loop;

      -- The decision, as apply makes it.
      base      := operands(op, true, one(X));
      merge     := operands(op, false, one(X));
      any_merge := (op(OP_MERGE_CUR) or op(OP_MERGE_PIX) or op(OP_MERGE_TOP)) = '1';
      pix_joins := op(OP_PIX_JOINS) = '1';
      if DECIDED_AHEAD then
        b_ge_m  := decision(0) = '1';
        b_ge_p  := true;
        m_ge_p  := decision(1) = '1';
        cur_pix := decision(2) = '1';
      else
        b_ge_m  := not any_merge or flag_of(ge, base, merge) = '1';
        b_ge_p  := not pix_joins or flag_of(ge, base, one(X)) = '1';
        m_ge_p  := any_merge and (not pix_joins or flag_of(ge, merge, one(X)) = '1');
        cur_pix := op(OP_CUR_START) = '1' or (op(OP_CUR_PIX) = '1' and ge(C)(X) = '0');
      end if;
      if b_ge_m and b_ge_p then
        outcome := 0;
      elsif m_ge_p then
        outcome := 1;
      else
        outcome := 2;
      end if;

      -- Every register's next source, for each outcome, from the
      -- operation's bits; the outcome chooses last.
      for o in outcome_t loop
        src(o) := sources(op, o, cur_pix);
      end loop;

      -- The next pixel register's source.
      next_px := one(X);
      if op(OP_PIX_STEP) = '1' then
        next_px := one(XN);
        pixel   <= next_pix;
      end if;

      for i in member_t loop
        for o in outcome_t loop
          cand_key(o) := key_of(vals, src(o)(i));
        end loop;
        keys(i) <= cand_key(outcome);
        for j in member_t loop
          if i < j then
            for o in outcome_t loop
              cand_flag(o) := flag_of(ge, src(o)(i), src(o)(j));
            end loop;
            pair_ge(i)(j) <= cand_flag(outcome);
          end if;
        end loop;
        for o in outcome_t loop
          cand_flag(o) := flag_of(ge, src(o)(i), next_px);
        end loop;
        pixel_ge(i) <= cand_flag(outcome);
      end loop;

      -- The next column's decision, from the next flags, for each outcome
      -- of this one: its operands' sources were chosen a clock ahead, from
      -- this operation and the next.
      if DECIDED_AHEAD then
        n_any   := (op_ahead(OP_MERGE_CUR) or op_ahead(OP_MERGE_PIX) or op_ahead(OP_MERGE_TOP)) = '1';
        n_joins := op_ahead(OP_PIX_JOINS) = '1';
        for o in outcome_t loop
          for pc in 0 to 1 loop
            b_ge_m          := not n_any or flag_of(ge, n_base_r(o)(pc), n_merge_r(o)(pc)) = '1';
            b_ge_p          := not n_joins or flag_of(ge, n_base_r(o)(pc), next_px) = '1';
            m_ge_p          := n_any and (not n_joins or flag_of(ge, n_merge_r(o)(pc), next_px) = '1');
            cur_pix         := op_ahead(OP_CUR_START) = '1' or
                       (op_ahead(OP_CUR_PIX) = '1' and flag_of(ge, n_cur_r(o)(pc), next_px) = '0');
            cand_dec(o)(pc) := to_sl(cur_pix) & to_sl(m_ge_p) & to_sl(b_ge_m and b_ge_p);
          end loop;
        end loop;
        decision <= cand_dec(outcome)(to_integer(unsigned'('0' & decision(2))));
        -- A clock ahead: the sources of the operands after the next column,
        -- from the next operation (op_ahead) and the one after (in_op).
        for o in outcome_t loop
          for pc in 0 to 1 loop
            ahead   := sources(op_ahead, o, pc = 1);
            n_base  := (others => '0');
            n_merge := (others => '0');
            for m in member_t loop
              n_base  := n_base or (ahead(m) and operands(in_op, true, one(X))(m));
              n_merge := n_merge or (ahead(m) and operands(in_op, false, one(X))(m));
            end loop;
            if in_op(OP_MERGE_PIX) = '1' then
              n_merge := one(X);
              if op_ahead(OP_PIX_STEP) = '1' then
                n_merge := one(XN);
              end if;
            end if;
            n_base_r(o)(pc)  <= n_base;
            n_merge_r(o)(pc) <= n_merge;
            n_cur_r(o)(pc)   <= ahead(C);
          end loop;
        end loop;
      end if;

      op_ahead <= in_op;
      op       <= op_ahead;
      next_pix <= in_next_pixel;
      next_in  <= in_next_ge;
      stack_wd <= in_stack_word;
      stack_ge <= in_stack_ge;
      table_wd <= in_table_word;
      table_ge <= in_table_ge;
    end if;

  end process step;

  outputs : for i in T to N generate
    out_keys((i + 1) * KB - 1 downto i * KB) <= keys(i);
  end generate outputs;

end architecture rtl;
