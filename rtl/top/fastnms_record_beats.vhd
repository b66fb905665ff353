-- A corner record as BEATS 64-bit beats of m_axis_corners (its beat 0 alone
-- for the EMPTY record), tlast on a frame's last beat.
-- Datasheet: docs/fastnms_axi.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

entity fastnms_record_beats is
  generic (
    BEATS : positive := 6
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_data   : in    std_logic_vector(BEATS * 64 - 1 downto 0);
    in_single : in    std_logic;
    in_last   : in    std_logic;
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(63 downto 0);
    out_last  : out   std_logic
  );
end entity fastnms_record_beats;

architecture rtl of fastnms_record_beats is

  signal beat       : unsigned(3 downto 0);
  signal at_final   : std_logic; -- beat is BEATS - 1 (a register)
  signal final_beat : std_logic; -- the beat shown is its record's last

begin

  assert BEATS <= 16
    report "fastnms_record_beats: BEATS must be 1 .. 16"
    severity failure;

  final_beat <= at_final or in_single;
  in_ready   <= out_ready and final_beat;
  out_valid  <= in_valid;
  out_last   <= in_last and final_beat;

  count : process (clk) is
  begin

    if rising_edge(clk) then
      if in_valid = '1' and out_ready = '1' then
        if final_beat = '1' then
          beat     <= (others => '0');
          at_final <= '1' when BEATS = 1 else '0';
        else
          beat     <= beat + 1;
          at_final <= '1' when to_integer(beat) + 2 = BEATS else '0';
        end if;
      end if;

      if rst = '1' then
        beat     <= (others => '0');
        at_final <= '1' when BEATS = 1 else '0';
      end if;
    end if;

  end process count;

  select_beat : process (all) is
  begin

    out_data <= in_data(63 downto 0);

    for i in 1 to BEATS - 1 loop

      if to_integer(beat) = i then
        out_data <= in_data(64 * i + 63 downto 64 * i);
      end if;

    end loop;

  end process select_beat;

end architecture rtl;
