-- Corner records with the end of frame folded in: each record held until
-- the next beat says whether it is its frame's last (record, last, empty,
-- aborted).
-- Datasheet: docs/fastnms_axi.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_corner_pack is
  generic (
    X_BITS     : positive := 11;
    Y_BITS     : positive := 11;
    SCORE_BITS : positive := 8;
    EXTRA_BITS : positive := 1
  );
  port (
    clk        : in    std_logic;
    rst        : in    std_logic;
    abort      : in    std_logic;
    in_valid   : in    std_logic;
    in_ready   : out   std_logic;
    in_x       : in    unsigned(X_BITS - 1 downto 0);
    in_y       : in    unsigned(Y_BITS - 1 downto 0);
    in_score   : in    unsigned(SCORE_BITS - 1 downto 0);
    in_extra   : in    std_logic_vector(EXTRA_BITS - 1 downto 0);
    in_eof     : in    std_logic;
    in_lost    : in    std_logic;
    out_valid  : out   std_logic;
    out_ready  : in    std_logic;
    out_data   : out   std_logic_vector(X_BITS + Y_BITS + SCORE_BITS + EXTRA_BITS + 2 downto 0);
    open_frame : out   std_logic
  );
end entity fastnms_corner_pack;

architecture rtl of fastnms_corner_pack is

  constant KIND_RECORD  : std_logic_vector(1 downto 0) := "00";
  constant KIND_LAST    : std_logic_vector(1 downto 0) := "01";
  constant KIND_ABORTED : std_logic_vector(1 downto 0) := "10";
  constant KIND_EMPTY   : std_logic_vector(1 downto 0) := "11";

  subtype record_t is std_logic_vector(X_BITS + Y_BITS + SCORE_BITS + EXTRA_BITS - 1 downto 0);

  signal held_valid : std_logic;
  signal held       : record_t;
  signal take       : std_logic; -- a beat of the core is taken
  signal emit_valid : std_logic;
  signal emit_kind  : std_logic_vector(1 downto 0);
  signal emit_lost  : std_logic;
  signal emit_data  : record_t;
  signal skid_ready : std_logic;

begin

  assert X_BITS + Y_BITS + SCORE_BITS + 2 <= 64
    report "fastnms_corner_pack: X_BITS + Y_BITS + SCORE_BITS + 2 must be at most 64 (the corner word)"
    severity failure;

  take     <= in_valid and skid_ready and not abort;
  in_ready <= skid_ready and not abort;

  emit_valid <= (abort and held_valid) or (in_valid and not abort and (in_eof or held_valid));
  emit_kind  <= KIND_ABORTED when abort = '1' else
                KIND_RECORD when in_eof = '0' else
                KIND_LAST when held_valid = '1' else
                KIND_EMPTY;
  emit_lost  <= in_eof and in_lost and not abort;
  emit_data  <= held when held_valid = '1' else
                (others => '0');

  hold : process (clk) is
  begin

    if rising_edge(clk) then
      if abort = '1' then
        if skid_ready = '1' then
          held_valid <= '0';
        end if;
      elsif take = '1' then
        held_valid <= not in_eof;
        held       <= std_logic_vector(in_x) & std_logic_vector(in_y) & std_logic_vector(in_score) & in_extra;
      end if;

      if rst = '1' then
        held_valid <= '0';
      end if;
    end if;

  end process hold;

  open_frame <= held_valid;

  output_buffer : entity work.fastnms_skid_buffer
    generic map (
      WIDTH => out_data'length
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => emit_valid,
      in_ready  => skid_ready,
      in_data   => emit_kind & emit_lost & emit_data,
      out_valid => out_valid,
      out_ready => out_ready,
      out_data  => out_data
    );

end architecture rtl;
