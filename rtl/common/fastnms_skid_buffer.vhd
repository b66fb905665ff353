-- Skid buffer: a two-entry pipeline register whose in_ready is a flip-flop,
-- the one way the core cuts a ready path (PING_PONG: the main/skid or the
-- ping-pong style).
-- Datasheet: docs/fastnms_skid_buffer.md
library ieee;
  use ieee.std_logic_1164.all;

entity fastnms_skid_buffer is
  generic (
    WIDTH     : positive := 8;
    PING_PONG : boolean  := false
  );
  port (
    clk       : in    std_logic;
    rst       : in    std_logic;
    in_valid  : in    std_logic;
    in_ready  : out   std_logic;
    in_data   : in    std_logic_vector(WIDTH - 1 downto 0);
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(WIDTH - 1 downto 0)
  );
end entity fastnms_skid_buffer;

architecture rtl of fastnms_skid_buffer is

  subtype word_t is std_logic_vector(WIDTH - 1 downto 0);

  type entries_t is array (0 to 1) of word_t;

begin

  main_and_skid : if not PING_PONG generate
    signal main_valid : std_logic;
    signal main_data  : word_t;
    signal skid_valid : std_logic;
    signal skid_data  : word_t;
  begin

    registers : process (clk) is
    begin

      if rising_edge(clk) then
        if skid_valid = '0' then
          if main_valid = '0' or out_ready = '1' then
            main_valid <= in_valid;
            main_data  <= in_data;
          else
            skid_valid <= in_valid;
            skid_data  <= in_data;
          end if;
        elsif out_ready = '1' then
          main_data  <= skid_data;
          skid_valid <= '0';
        end if;

        if rst = '1' then
          main_valid <= '0';
          skid_valid <= '0';
        end if;
      end if;

    end process registers;

    in_ready  <= not skid_valid;
    out_valid <= main_valid;
    out_data  <= main_data;

  end generate main_and_skid;

  ping_pong_entries : if PING_PONG generate
    signal entries   : entries_t;
    signal write_sel : std_logic; -- the entry the next input beat goes to
    signal read_sel  : std_logic; -- the entry out_data shows
    signal empty     : std_logic;
    signal full      : std_logic;
    signal push      : std_logic;
    signal pop       : std_logic;
  begin

    push <= in_valid and not full;
    pop  <= out_ready and not empty;

    registers : process (clk) is
    begin

      if rising_edge(clk) then
        -- The free entry takes in_data on every clock, valid or not (it holds
        -- no beat), so no handshake signal enables the data registers.
        if full = '0' then
          if write_sel = '0' then
            entries(0) <= in_data;
          else
            entries(1) <= in_data;
          end if;
        end if;
        if push = '1' then
          write_sel <= not write_sel;
        end if;
        if pop = '1' then
          read_sel <= not read_sel;
        end if;
        -- Two beats held: full; none: empty (a push and a pop together keep
        -- the count).
        if push = '1' and pop = '0' then
          empty <= '0';
          full  <= not empty;
        elsif pop = '1' and push = '0' then
          full  <= '0';
          empty <= not full;
        end if;

        if rst = '1' then
          write_sel <= '0';
          read_sel  <= '0';
          empty     <= '1';
          full      <= '0';
        end if;
      end if;

    end process registers;

    in_ready  <= not full;
    out_valid <= not empty;
    out_data  <= entries(0) when read_sel = '0' else
                 entries(1);

  end generate ping_pong_entries;

end architecture rtl;
