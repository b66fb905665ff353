-- Probe, not part of the core: the region NMS's key data path as modelled
-- by key_flags.vhd (the same seven key registers, operation bits, pixel and
-- memory words), made with a deferred select (issue 37), to measure its
-- depth in this flow (flows/synth/test_probes_deferred.py).
--
-- Every operation of a column makes a register's next key a copy of one
-- source (a move), or the best of some (a merge: the base, the class merging
-- in, the pixel; the current class and the pixel), never anything else, so
-- the keys after column e are each the best of a set of keys that the
-- operation bits alone decide. The probe keeps the resolved keys two columns
-- behind (kr: the keys after column e - 2, as key_deferred_chain's LAG 2)
-- and, for each register, its pending choice: the set, a mask over the
-- window's atoms (the seven resolved keys, the pixels of columns e - 1 and
-- e, the memory words of both columns). The masks come from the operation
-- bits of the two columns (a control pipeline, no key read); the atoms'
-- comparisons are made register to register in one clock, and the keys
-- after column e are resolved a clock later from the atoms, the masks and
-- the comparisons: the best atom of each mask (ties to the lower atom).
--
-- Only eight atoms can meet in a mask: within two columns the register R
-- and the memory words are only moved (R into S, a word into R or N, N into
-- W: a merge reads T, L, W, C and the pixel), so they are alone in their
-- masks and never compared: each register's lone atom (if any) is chosen a
-- clock ahead, by its mask. The others are compared pairwise: 15 full-key
-- comparators between the resolved keys T, S, C, W, L, N, and 13 score
-- comparators between them and the two pixels and between the pixels (as in
-- key_flags, a pixel comes after every key in raster order). The memory
-- words need no flags as inputs: the probe is exact, no lower bound.
--   GATED_FLAGS false: the resolution reads the masks and the 28 shared
--     flags: an atom wins if it is in the mask and no other of the mask
--     beats it.
--   true: the masks are known a clock before the comparisons are, so every
--     register keeps its own copy of each flag with the atoms outside its
--     mask already left out (the flag flip-flops' synchronous set or reset:
--     no level), and an atom wins on its mask bit and 7 flags.
--
-- Timing: column e's operation (in_op, as key_flags' operation bits) is in
-- its input register after edge e - 1 (the control runs a column ahead of
-- the data); its data (in_next_pixel, in_stack_word, in_table_word, as
-- key_flags' next pixel, stack and table words) after edge e, the pixel
-- after it in px after edge e + 1, the keys after column e in kr
-- (out_keys) after edge e + 3.
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity key_deferred is
  generic (
    SCORE_BITS  : positive := 12;
    POS_BITS    : positive := 22;
    GATED_FLAGS : boolean  := true
  );
  port (
    clk : in    std_logic;
    -- The operation's bits, as key_flags' (OP_* below).
    in_op : in    std_logic_vector(22 downto 0);
    -- Keys: score, then the inverted row and column (larger is better). The
    -- next pixel (the pixel after the column if it steps), the stack RAM's
    -- word (into R) and the data table's word (into N).
    in_next_pixel : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_stack_word : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    in_table_word : in    unsigned(SCORE_BITS + POS_BITS - 1 downto 0);
    -- The resolved key registers T .. N, T in the low bits.
    out_keys : out   unsigned(7 * (SCORE_BITS + POS_BITS) - 1 downto 0)
  );
end entity key_deferred;

architecture rtl of key_deferred is

  constant KB : positive := SCORE_BITS + POS_BITS;

  subtype key_t is unsigned(KB - 1 downto 0);

  -- The earliest pixel with score 0: the registers' value before any key.
  constant INIT_KEY : key_t := (KB - 1 downto POS_BITS => '0') & (POS_BITS - 1 downto 0 => '1');

  -- A column's sources, as in key_flags: the key registers, the pixel, the
  -- stack RAM's word (into R) and the data table's word (into N).
  constant T  : natural := 0;
  constant S  : natural := 1;
  constant R  : natural := 2;
  constant C  : natural := 3;
  constant W  : natural := 4;
  constant L  : natural := 5;
  constant N  : natural := 6;
  constant X  : natural := 7;
  constant FR : natural := 8;
  constant FN : natural := 9;

  -- The operation's bits, as key_flags'.
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

  constant OP_IDLE : std_logic_vector(22 downto 0) :=
  (OP_BASE_TOP => '1', OP_KEEP_TOP => '1', others => '0');

  subtype member_t is natural range T to N;

  subtype source_t is natural range T to FN;

  -- The window's atoms for the keys after column e: the resolved keys after
  -- column e - 2 (T .. N), the pixel of column e - 1 and of column e (P1,
  -- P2), the memory words of both columns (FR1, FN1, FR2, FN2).
  constant P1  : natural := 7;
  constant P2  : natural := 8;
  constant FR1 : natural := 9;
  constant FN1 : natural := 10;
  constant FR2 : natural := 11;
  constant FN2 : natural := 12;

  subtype atom_t is natural range T to FN2;

  -- The atoms that can meet another in a mask, and so are compared.
  constant MEETS : std_logic_vector(atom_t) :=
  (T | S | C | W | L | N | P1 | P2 => '1', others => '0');

  type keys_t is array (member_t) of key_t;

  type atom_keys_t is array (atom_t) of key_t;

  -- A column's step: for each register, the sources whose best is its next
  -- key.
  type steps_t is array (member_t) of std_logic_vector(source_t);

  -- A register's pending choice: the atoms whose best is its key.
  type masks_t is array (member_t) of std_logic_vector(atom_t);

  -- ge(a)(b), a < b, both MEETS: atom a >= atom b.
  type flags_t is array (atom_t) of std_logic_vector(atom_t);

  type gated_t is array (member_t) of flags_t;

  function score_of (k : key_t) return unsigned is
  begin

    return k(KB - 1 downto POS_BITS);

  end function score_of;

  function one (i : source_t) return std_logic_vector is
    variable v : std_logic_vector(source_t);
  begin

    v    := (others => '0');
    v(i) := '1';
    return v;

  end function one;

  -- A 2-bit move code: 01 and 10 choose a and b, else the register stays.
  function move (code : std_logic_vector(1 downto 0); stay, a, b : source_t) return std_logic_vector is
  begin

    if code = "01" then
      return one(a);
    elsif code = "10" then
      return one(b);
    end if;

    return one(stay);

  end function move;

  -- A column's step, from its operation bits: key_flags' choices, with the
  -- best of the base, the class merging in and the pixel (when it joins) as
  -- the union of their sources, and the current class as the pixel (a
  -- start), the best of itself and the pixel (cur_pix), or itself.
  function column (o : std_logic_vector(22 downto 0)) return steps_t is
    variable best : std_logic_vector(source_t);
    variable cur  : std_logic_vector(source_t);
    variable st   : steps_t;
  begin

    best    := (others => '0');
    best(T) := o(OP_BASE_TOP) or o(OP_MERGE_TOP);
    best(L) := o(OP_BASE_LAND);
    best(W) := o(OP_BASE_WORD);
    best(C) := o(OP_MERGE_CUR);
    best(X) := o(OP_MERGE_PIX) or o(OP_PIX_JOINS);
    cur     := one(C);

    if o(OP_CUR_START) = '1' then
      cur := one(X);
    elsif o(OP_CUR_PIX) = '1' then
      cur(X) := '1';
    end if;

    if o(OP_KEEP_TOP) = '1' then
      st(T) := one(T);
    elsif o(OP_TAKE_SECOND) = '1' then
      st(T) := one(S);
    else
      st(T) := best;
    end if;

    st(S) := move(o(OP_SECOND + 1 downto OP_SECOND), S, T, R);
    st(R) := move(o(OP_THIRD + 1 downto OP_THIRD), R, S, FR);

    if o(OP_DETACH) = '1' then
      st(C) := best;
    else
      st(C) := cur;
    end if;

    st(W) := move(o(OP_WORD + 1 downto OP_WORD), W, N, L);

    if o(OP_SPARE) = '1' then
      st(L) := one(C);
    elsif o(OP_FINAL) = '1' then
      st(L) := best;
    else
      st(L) := cur;
    end if;

    st(N) := move(o(OP_NEXT + 1 downto OP_NEXT), N, FN, L);
    return st;

  end function column;

  -- The masks of the keys after column e, from the steps of columns e - 1
  -- (before) and e (now): a register's atoms are those of the registers it
  -- takes from, and the pixel and words of column e.
  function compose (now, before : steps_t) return masks_t is
    variable m : masks_t;
  begin

    for i in member_t loop
      m(i) := (others => '0');
      for j in member_t loop

        if now(i)(j) = '1' then
          m(i)(T to N) := m(i)(T to N) or before(j)(T to N);
          m(i)(P1)     := m(i)(P1) or before(j)(X);
          m(i)(FR1)    := m(i)(FR1) or before(j)(FR);
          m(i)(FN1)    := m(i)(FN1) or before(j)(FN);
        end if;

      end loop;
      m(i)(P2)  := now(i)(X);
      m(i)(FR2) := now(i)(FR);
      m(i)(FN2) := now(i)(FN);
    end loop;

    return m;

  end function compose;

  -- Column e's operation (after edge e - 1: the control runs a column
  -- ahead), then its data (after edge e): the pixel after it if it steps,
  -- its words; after edge e + 1, stack_w(1) and table_w(1) are column e's
  -- words, stack_w(2) and table_w(2) column e - 1's.
  type words_t is array (0 to 2) of key_t;

  signal op_ahead : std_logic_vector(22 downto 0) := OP_IDLE;
  signal op       : std_logic_vector(22 downto 0) := OP_IDLE;
  signal next_px  : key_t                         := INIT_KEY;
  signal stack_w  : words_t                       := (others => INIT_KEY);
  signal table_w  : words_t                       := (others => INIT_KEY);
  -- The pixel after column e (after edge e + 1), and after columns e - 1,
  -- e - 2, e - 3.
  signal px     : key_t := INIT_KEY;
  signal px_d   : key_t := INIT_KEY;
  signal px_dd  : key_t := INIT_KEY;
  signal px_ddd : key_t := INIT_KEY;
  -- The steps of columns e and e - 1 (after edge e), the masks of the keys
  -- after column e (after edge e + 1, and a clock later).
  signal step_now    : steps_t := column(OP_IDLE);
  signal step_before : steps_t := column(OP_IDLE);
  signal masks       : masks_t := compose(column(OP_IDLE), column(OP_IDLE));
  signal masks_d     : masks_t := compose(column(OP_IDLE), column(OP_IDLE));
  -- The resolved keys after column e - 2 (after edge e + 1), and a clock
  -- later (kr_d). After edge e + 2: each register's atom if its mask holds
  -- one that meets no other (alone, else zero), and the comparisons of the
  -- atoms that meet: ge(a)(b), a < b: atom a >= atom b; with GATED_FLAGS,
  -- for each register i, keeps(i)(a)(b): a >= b or b is not in i's mask,
  -- loses(i)(a)(b): a >= b and a is in i's mask (b beats a when it is
  -- '0'). All atoms start equal to INIT_KEY: whichever wins, the key is the
  -- same.
  signal kr    : keys_t  := (others => INIT_KEY);
  signal kr_d  : keys_t  := (others => INIT_KEY);
  signal alone : keys_t  := (others => INIT_KEY);
  signal ge    : flags_t := (others => (others => '1'));
  signal keeps : gated_t := (others => (others => (others => '1')));
  signal loses : gated_t := (others => (others => (others => '0')));

begin

  control : process (clk) is
  begin

    if rising_edge(clk) then
      op_ahead    <= in_op;
      op          <= op_ahead;
      step_now    <= column(op_ahead);
      step_before <= step_now;
      masks       <= compose(step_now, step_before);
      masks_d     <= masks;
    end if;

  end process control;

  inputs : process (clk) is
  begin

    if rising_edge(clk) then
      next_px <= in_next_pixel;
      if op(OP_PIX_STEP) = '1' then
        px <= next_px;
      end if;
      px_d    <= px;
      px_dd   <= px_d;
      px_ddd  <= px_dd;
      stack_w <= in_stack_word & stack_w(0 to 1);
      table_w <= in_table_word & table_w(0 to 1);
    end if;

  end process inputs;

  -- Register to register, after edge e + 1: the resolved keys after column
  -- e - 2 (kr), the pixels of columns e - 1 (px_dd) and e (px_d), the words,
  -- and the masks of the keys after column e. With GATED_FLAGS, the masks
  -- reach the flags through their flip-flops' synchronous set and reset.
  compare : process (clk) is

    variable atoms : atom_keys_t;
    variable a_ge  : std_logic;
    variable key   : key_t;

  begin

    if rising_edge(clk) then
      for a in member_t loop
        atoms(a) := kr(a);
      end loop;
      atoms(P1)  := px_dd;
      atoms(P2)  := px_d;
      atoms(FR1) := stack_w(2);
      atoms(FN1) := table_w(2);
      atoms(FR2) := stack_w(1);
      atoms(FN2) := table_w(1);
      for i in member_t loop
        key := (others => '0');
        for a in atom_t loop
          if MEETS(a) = '0' and masks(i)(a) = '1' then
            key := key or atoms(a);
          end if;
        end loop;
        alone(i) <= key;
      end loop;
      for a in atom_t loop
        for b in atom_t loop
          if a < b and MEETS(a) = '1' and MEETS(b) = '1' then
            a_ge := '0';
            if b >= P1 then
              -- On scores: a pixel comes after every key in play, and the
              -- pixel of column e - 1 before that of column e.
              if score_of(atoms(a)) >= score_of(atoms(b)) then
                a_ge := '1';
              end if;
            elsif atoms(a) >= atoms(b) then
              a_ge := '1';
            end if;
            if not GATED_FLAGS then
              ge(a)(b) <= a_ge;
            else
              for i in member_t loop
                if masks(i)(b) = '0' then
                  keeps(i)(a)(b) <= '1';
                else
                  keeps(i)(a)(b) <= a_ge;
                end if;
                if masks(i)(a) = '0' then
                  loses(i)(a)(b) <= '0';
                else
                  loses(i)(a)(b) <= a_ge;
                end if;
              end loop;
            end if;
          end if;
        end loop;
      end loop;
    end if;

  end process compare;

  -- After edge e + 2: the keys after column e, each its mask's best atom:
  -- the one alone, or the one that meets and is >= every other of the mask
  -- (ties to the lower atom).
  resolve : process (clk) is

    variable atoms : atom_keys_t;
    variable wins  : std_logic;
    variable key   : key_t;

  begin

    if rising_edge(clk) then
      atoms := (others => (others => '0'));
      for a in member_t loop
        atoms(a) := kr_d(a);
      end loop;
      atoms(P1) := px_ddd;
      atoms(P2) := px_dd;
      for i in member_t loop
        key := alone(i);
        for a in atom_t loop
          if MEETS(a) = '1' then
            wins := masks_d(i)(a);
            for b in atom_t loop
              if b /= a and MEETS(b) = '1' then
                if GATED_FLAGS and b > a then
                  wins := wins and keeps(i)(a)(b);
                elsif GATED_FLAGS then
                  wins := wins and not loses(i)(b)(a);
                elsif b > a then
                  wins := wins and (not masks_d(i)(b) or ge(a)(b));
                else
                  wins := wins and (not masks_d(i)(b) or not ge(b)(a));
                end if;
              end if;
            end loop;
            if wins = '1' then
              key := key or atoms(a);
            end if;
          end if;
        end loop;
        kr(i) <= key;
      end loop;
      kr_d <= kr;
    end if;

  end process resolve;

  outputs : for i in T to N generate
    out_keys((i + 1) * KB - 1 downto i * KB) <= kr(i);
  end generate outputs;

end architecture rtl;
