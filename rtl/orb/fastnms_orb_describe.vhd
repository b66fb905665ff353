-- The ORB engine: a keypoint's unblurred and blurred columns in, its angle
-- and descriptor out (golden/orb.py's ic_angle and descriptors), a keypoint
-- every 512 / LANES clocks.
-- Datasheet: docs/orb_rtl.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_orb_describe is
  generic (
    LANES       : positive := 8;
    RECORD_BITS : positive := 40
  );
  port (
    clk            : in    std_logic;
    rst            : in    std_logic;
    plain_valid    : in    std_logic;
    plain_ready    : out   std_logic;
    plain_column   : in    std_logic_vector(31 * 8 - 1 downto 0);
    plain_record   : in    std_logic_vector(RECORD_BITS - 1 downto 0);
    blurred_valid  : in    std_logic;
    blurred_ready  : out   std_logic;
    blurred_column : in    std_logic_vector(37 * 8 - 1 downto 0);
    out_valid      : out   std_logic;
    out_ready      : in    std_logic;
    out_record     : out   std_logic_vector(RECORD_BITS - 1 downto 0);
    out_angle      : out   std_logic_vector(31 downto 0);
    out_descriptor : out   std_logic_vector(255 downto 0)
  );
end entity fastnms_orb_describe;

architecture rtl of fastnms_orb_describe is

  constant COLUMNS : positive := 31;
  -- (float)(CV_PI/180) (golden/float32.py, DEG_TO_RAD).
  constant DEG_TO_RAD : std_logic_vector(31 downto 0) := x"3C8EFA35";
  -- Keypoints between their last plain column and their output: one in the
  -- moments unit and one waiting there, two in the angle units, one in the
  -- radians, one in the cos/sin unit, two in the rotation, two in the sampler
  -- and one waiting (the FIFOs hold 16 + 3).
  constant QUEUE_DEPTH : positive := 16;

  type angles_t is array (0 to 1) of std_logic_vector(31 downto 0);

  -- The plain column count.
  signal column      : natural range 0 to COLUMNS - 1;
  signal last        : std_logic;
  signal take        : std_logic;
  signal moments_rdy : std_logic;
  signal record_rdy  : std_logic;

  -- Moments to the angle units, in turn.
  signal m_valid        : std_logic;
  signal m_ready        : std_logic;
  signal m01,       m10 : signed(20 downto 0);
  signal to_unit        : std_logic;
  signal from_unit      : std_logic;
  signal a_in_valid     : std_logic_vector(0 to 1);
  signal a_in_ready     : std_logic_vector(0 to 1);
  signal a_valid        : std_logic_vector(0 to 1);
  signal a_ready        : std_logic_vector(0 to 1);
  signal a_angle        : angles_t;
  signal angle          : std_logic_vector(31 downto 0);
  signal a_offered      : std_logic;
  signal angle_take     : std_logic;
  signal angle_rdy      : std_logic;

  -- The radians: the product in flight or waiting for the cos/sin unit.
  signal pending    : std_logic;
  signal rad_valid  : std_logic;
  signal product    : std_logic_vector(31 downto 0);
  signal prod_valid : std_logic;
  signal radians    : std_logic_vector(31 downto 0);
  signal cs_ready   : std_logic;

  signal cs_valid,  cs_take : std_logic;
  signal cos,       sin     : std_logic_vector(31 downto 0);
  signal rot_ready          : std_logic;

  signal pt_valid         : std_logic;
  signal pt_ready         : std_logic;
  signal pt_first         : std_logic;
  signal pt_last          : std_logic;
  signal pt_dx,     pt_dy : std_logic_vector(6 * LANES - 1 downto 0);

  signal d_valid,   d_ready   : std_logic;
  signal descriptor           : std_logic_vector(255 downto 0);
  signal rec_valid, ang_valid : std_logic;
  signal done                 : std_logic;

begin

  assert LANES = 2 or LANES = 4 or LANES = 8 or LANES = 16
    report "fastnms_orb_describe: LANES must be 2, 4, 8 or 16"
    severity failure;

  -- A plain column goes to the moments unit, the last one's record to the record
  -- FIFO: taken when both have room.
  plain_ready <= moments_rdy and (record_rdy or not last);
  take        <= plain_valid and moments_rdy and (record_rdy or not last);

  count : process (clk) is
  begin

    if rising_edge(clk) then
      if take = '1' then
        if last = '1' then
          column <= 0;
        else
          column <= column + 1;
        end if;
        last <= to_sl(column + 1 = COLUMNS - 1);
      end if;

      if rst = '1' then
        column <= 0;
        last   <= '0';
      end if;
    end if;

  end process count;

  moments : entity work.fastnms_orb_moments
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => take,
      in_ready  => moments_rdy,
      in_column => plain_column,
      out_valid => m_valid,
      out_ready => m_ready,
      out_m01   => m01,
      out_m10   => m10
    );

  -- Two angle units in turn: keypoint k to unit k mod 2, and back in that order.
  m_ready       <= a_in_ready(0) when to_unit = '0' else
                   a_in_ready(1);
  a_in_valid(0) <= m_valid and not to_unit;
  a_in_valid(1) <= m_valid and to_unit;

  angle_units : for u in 0 to 1 generate

    unit : entity work.fastnms_orb_angle
      port map (
        clk       => clk,
        rst       => rst,
        in_valid  => a_in_valid(u),
        in_ready  => a_in_ready(u),
        in_m01    => m01,
        in_m10    => m10,
        out_valid => a_valid(u),
        out_ready => a_ready(u),
        out_angle => a_angle(u)
      );

  end generate angle_units;

  -- An angle leaves its unit when the radians stage is free and the angle FIFO
  -- has room.
  a_offered  <= a_valid(0) when from_unit = '0' else
                a_valid(1);
  angle_take <= a_offered and not pending and angle_rdy;
  angle      <= a_angle(0) when from_unit = '0' else
                a_angle(1);
  a_ready(0) <= not pending and angle_rdy and not from_unit;
  a_ready(1) <= not pending and angle_rdy and from_unit;

  turns : process (clk) is
  begin

    if rising_edge(clk) then
      if m_valid = '1' and m_ready = '1' then
        to_unit <= not to_unit;
      end if;
      if angle_take = '1' then
        from_unit <= not from_unit;
      end if;

      -- The radians: pending from the angle's hand-over until the cos/sin unit
      -- takes them.
      if angle_take = '1' then
        pending <= '1';
      elsif rad_valid = '1' and cs_ready = '1' then
        pending <= '0';
      end if;
      if prod_valid = '1' then
        radians   <= product;
        rad_valid <= '1';
      elsif cs_ready = '1' then
        rad_valid <= '0';
      end if;

      if rst = '1' then
        to_unit   <= '0';
        from_unit <= '0';
        pending   <= '0';
        rad_valid <= '0';
      end if;
    end if;

  end process turns;

  to_radians : entity work.fastnms_f32_mul
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => angle_take,
      in_a      => angle,
      in_b      => DEG_TO_RAD,
      out_valid => prod_valid,
      out_p     => product
    );

  cos_sin : entity work.fastnms_orb_cos_sin
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => rad_valid,
      in_ready  => cs_ready,
      in_x      => radians,
      out_valid => cs_valid,
      out_ready => rot_ready,
      out_cos   => cos,
      out_sin   => sin
    );

  rotate : entity work.fastnms_orb_rotate
    generic map (
      LANES => LANES
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => cs_valid,
      in_ready  => rot_ready,
      in_cos    => cos,
      in_sin    => sin,
      out_valid => pt_valid,
      out_ready => pt_ready,
      out_first => pt_first,
      out_last  => pt_last,
      out_dx    => pt_dx,
      out_dy    => pt_dy
    );

  sample : entity work.fastnms_orb_sample
    generic map (
      LANES => LANES
    )
    port map (
      clk            => clk,
      rst            => rst,
      patch_valid    => blurred_valid,
      patch_ready    => blurred_ready,
      patch_column   => blurred_column,
      point_valid    => pt_valid,
      point_ready    => pt_ready,
      point_first    => pt_first,
      point_last     => pt_last,
      point_dx       => pt_dx,
      point_dy       => pt_dy,
      out_valid      => d_valid,
      out_ready      => d_ready,
      out_descriptor => descriptor
    );

  records : entity work.fastnms_fifo
    generic map (
      DEPTH => QUEUE_DEPTH,
      WIDTH => RECORD_BITS,
      STYLE => "distributed"
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => take and last,
      in_ready  => record_rdy,
      in_data   => plain_record,
      out_valid => rec_valid,
      out_ready => done,
      out_data  => out_record,
      busy      => open
    );

  angles : entity work.fastnms_fifo
    generic map (
      DEPTH => QUEUE_DEPTH,
      WIDTH => 32,
      STYLE => "distributed"
    )
    port map (
      clk       => clk,
      rst       => rst,
      in_valid  => angle_take,
      in_ready  => angle_rdy,
      in_data   => angle,
      out_valid => ang_valid,
      out_ready => done,
      out_data  => out_angle,
      busy      => open
    );

  -- The record and the angle entered their FIFOs long before the descriptor
  -- (the angle comes first, and the record with the columns before it): the
  -- join only waits in theory.
  out_valid      <= d_valid and rec_valid and ang_valid;
  d_ready        <= out_ready and rec_valid and ang_valid;
  done           <= out_ready and d_valid and rec_valid and ang_valid;
  out_descriptor <= descriptor;

end architecture rtl;
