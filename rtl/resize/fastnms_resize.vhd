-- One step of cv2.ORB's image pyramid: a stream of 8-bit pixels shrunk to
-- the destination size exactly as cv2.resize(..., INTER_LINEAR_EXACT), at
-- one source pixel per clock. The scale of each axis is computed from the
-- sizes (fastnms_resize_scale), the taps from the scale
-- (fastnms_resize_taps); one line buffer keeps the row above.
-- Datasheet: docs/fastnms_resize.md
library ieee;
  use ieee.std_logic_1164.all;
  use ieee.numeric_std.all;

library work;
  use work.fastnms_pkg.all;

entity fastnms_resize is
  generic (
    MAX_WIDTH  : positive := 1920;
    MAX_HEIGHT : positive := 1080
  );
  port (
    clk : in    std_logic;
    rst : in    std_logic;
    -- Sizes, taken at each start of frame once their scales are computed
    -- (1 <= dst <= src, src up to MAX_WIDTH x MAX_HEIGHT).
    cfg_src_width  : in    unsigned(11 downto 0);
    cfg_src_height : in    unsigned(11 downto 0);
    cfg_dst_width  : in    unsigned(11 downto 0);
    cfg_dst_height : in    unsigned(11 downto 0);
    -- Source pixels, row after row; in_sof on the first of a frame, in_eol
    -- on the last of each row.
    in_valid : in    std_logic;
    in_ready : out   std_logic;
    in_data  : in    std_logic_vector(7 downto 0);
    in_sof   : in    std_logic;
    in_eol   : in    std_logic;
    -- Destination pixels.
    out_valid : out   std_logic;
    out_ready : in    std_logic;
    out_data  : out   std_logic_vector(7 downto 0);
    out_sof   : out   std_logic;
    out_eol   : out   std_logic;
    -- One-clock pulses: a frame whose sizes are not 1 <= dst <= src <= MAX
    -- (dropped); a frame cut short by a start of frame, or a pixel outside a
    -- frame (dropped); an in_eol not on a row's last pixel.
    err_size  : out   std_logic;
    err_frame : out   std_logic;
    err_line  : out   std_logic
  );
end entity fastnms_resize;

architecture rtl of fastnms_resize is

  constant SB : positive := 12;
  -- Output FIFO: room promised for 14 clocks (the pixel pipeline's depth).
  constant OUT_DEPTH : positive := 32;
  constant OUT_ROOM  : positive := 14;

  subtype size_t is unsigned(SB - 1 downto 0);

  -- ---- sizes and scales ----
  signal cfg_seen    : std_logic;
  signal cfg_changed : std_logic;

  type sizes_state_t is (wait_change, check, start, compute);

  signal sizes_state  : sizes_state_t;
  signal checks       : std_logic_vector(5 downto 0);
  signal scale_start  : std_logic;
  signal x_busy       : std_logic;
  signal y_busy       : std_logic;
  signal x_done       : std_logic;
  signal y_done       : std_logic;
  signal x_done_seen  : std_logic;
  signal y_done_seen  : std_logic;
  signal m_x          : unsigned(52 + SB - 1 downto 0);
  signal m_y          : unsigned(52 + SB - 1 downto 0);
  signal new_sw       : size_t;
  signal new_sh       : size_t;
  signal new_dw       : size_t;
  signal new_dh       : size_t;
  signal new_ok       : std_logic;
  signal params_ready : std_logic;
  signal params_gen   : std_logic;
  -- The sizes of the frames the taps are primed for.
  signal sw         : size_t;
  signal sh         : size_t;
  signal dw         : size_t;
  signal dh         : size_t;
  signal cfg_same   : std_logic;
  signal sizes_ok   : std_logic;
  signal primed     : std_logic;
  signal primed_gen : std_logic;
  signal priming    : std_logic;
  signal restart    : std_logic;

  -- ---- taps ----
  signal tx_valid   : std_logic;
  signal tx_ready   : std_logic;
  signal tx_delta   : unsigned(SB - 1 downto 0);
  signal tx_c0      : unsigned(7 downto 0);
  signal tx_last    : std_logic;
  signal ty_valid   : std_logic;
  signal ty_ready   : std_logic;
  signal ty_delta   : unsigned(SB - 1 downto 0);
  signal ty_c0      : unsigned(7 downto 0);
  signal ty_last    : std_logic;
  signal x_ready    : std_logic;
  signal y_ready    : std_logic;
  signal step_x     : std_logic;
  signal step_y     : std_logic;
  signal x_hit      : std_logic;
  signal y_hit      : std_logic;
  signal x_c0       : unsigned(7 downto 0);
  signal y_c0       : unsigned(7 downto 0);
  signal x_tap_last : std_logic;
  signal y_tap_last : std_logic;
  signal x_starved  : std_logic;
  signal y_starved  : std_logic;
  signal cols_done  : std_logic;
  signal rows_done  : std_logic;
  signal row_out    : std_logic;
  signal xl0        : std_logic;

  -- ---- frame and position ----
  signal accept_ok : std_logic;
  signal take      : std_logic;

  type frame_state_t is (idle, frame, drop);

  signal frame_state : frame_state_t;
  signal x           : size_t;
  signal y           : size_t;
  signal x_last      : std_logic;
  signal y_last      : std_logic;
  signal sw_m2       : size_t;
  signal sh_m2       : size_t;
  signal first_out   : std_logic;
  -- The pixel taken next is the frame's last.
  signal ending  : std_logic;
  signal sof_ok  : std_logic;
  signal sof_bad : std_logic;
  signal sw_two  : std_logic;
  signal sh_one  : std_logic;
  signal read_at : unsigned(clog2(MAX_WIDTH) - 1 downto 0);

  -- ---- pixel pipeline ----
  signal v0              : std_logic;
  signal sof0            : std_logic;
  signal px0             : std_logic_vector(7 downto 0);
  signal x0              : size_t;
  signal y0              : size_t;
  signal above           : std_logic_vector(7 downto 0);
  signal up_left         : unsigned(7 downto 0);
  signal up_right        : unsigned(7 downto 0);
  signal cur_left        : unsigned(7 downto 0);
  signal cur_right       : unsigned(7 downto 0);
  signal hit             : std_logic;
  signal v2              : std_logic;
  signal cx2             : unsigned(7 downto 0);
  signal cy2             : unsigned(7 downto 0);
  signal sof2            : std_logic;
  signal eol2            : std_logic;
  signal d_ab3           : signed(8 downto 0);
  signal d_cd3           : signed(8 downto 0);
  signal b3              : unsigned(7 downto 0);
  signal d3              : unsigned(7 downto 0);
  signal cx3             : unsigned(7 downto 0);
  signal cy3             : unsigned(7 downto 0);
  signal m_ab4           : signed(17 downto 0);
  signal m_cd4           : signed(17 downto 0);
  signal b4              : unsigned(7 downto 0);
  signal d4              : unsigned(7 downto 0);
  signal cy4             : unsigned(7 downto 0);
  signal h_up5           : unsigned(16 downto 0);
  signal h_cur5          : unsigned(16 downto 0);
  signal cy5             : unsigned(7 downto 0);
  signal lo6             : unsigned(9 downto 0);
  signal h_up6           : unsigned(16 downto 0);
  signal h_cur6          : unsigned(16 downto 0);
  signal cy6             : unsigned(7 downto 0);
  signal d_h7            : signed(17 downto 0);
  signal h_cur7          : unsigned(16 downto 0);
  signal cy7             : unsigned(7 downto 0);
  signal m_h8            : signed(26 downto 0);
  signal h_cur8          : unsigned(16 downto 0);
  signal mid9            : unsigned(8 downto 0);
  signal hi9             : signed(10 downto 0);
  signal h_hi9           : unsigned(8 downto 0);
  signal pix10           : unsigned(7 downto 0);
  signal v_pipe          : std_logic_vector(10 downto 3);
  signal sof_pipe        : std_logic_vector(10 downto 3);
  signal eol_pipe        : std_logic_vector(10 downto 3);
  signal wr_valid        : std_logic;
  signal wr_data         : std_logic_vector(9 downto 0);
  signal out_word        : std_logic_vector(9 downto 0);
  signal out_almost_full : std_logic;
  signal out_in_ready    : std_logic;

begin

  assert MAX_WIDTH <= 4095 and MAX_HEIGHT <= 4095
    report "fastnms_resize: MAX_WIDTH and MAX_HEIGHT must be at most 4095"
    severity failure;

  -- ---- the scales: computed again whenever the sizes change ------------------

  sizes : process (clk) is
  begin

    if rising_edge(clk) then
      scale_start <= '0';
      cfg_changed <= to_sl(cfg_src_width /= new_sw or cfg_src_height /= new_sh or
                           cfg_dst_width /= new_dw or cfg_dst_height /= new_dh);

      if sizes_state = wait_change then
        -- cfg_changed is a clock old: a change seen now was compared with
        -- the sizes of the clock before; the sizes taken are today's.
        if cfg_changed = '1' or cfg_seen = '0' then
          new_sw       <= cfg_src_width;
          new_sh       <= cfg_src_height;
          new_dw       <= cfg_dst_width;
          new_dh       <= cfg_dst_height;
          cfg_seen     <= '1';
          params_ready <= '0';
          sizes_state  <= check;
        end if;
      elsif sizes_state = check then
        checks(0)   <= to_sl(new_dw >= 1);
        checks(1)   <= to_sl(new_dh >= 1);
        checks(2)   <= to_sl(new_dw <= new_sw);
        checks(3)   <= to_sl(new_dh <= new_sh);
        checks(4)   <= to_sl(new_sw >= 2 and new_sw <= MAX_WIDTH);
        checks(5)   <= to_sl(new_sh >= 2 and new_sh <= MAX_HEIGHT);
        sizes_state <= start;
      elsif sizes_state = start then
        new_ok <= and checks;
        if (and checks) = '1' then
          scale_start <= '1';
          x_done_seen <= '0';
          y_done_seen <= '0';
          sizes_state <= compute;
        else
          -- Nothing to compute: frames with these sizes are dropped.
          params_ready <= '1';
          params_gen   <= not params_gen;
          sizes_state  <= wait_change;
        end if;
      elsif sizes_state = compute then
        if x_done = '1' then
          x_done_seen <= '1';
        end if;
        if y_done = '1' then
          y_done_seen <= '1';
        end if;
        if (x_done_seen = '1' or x_done = '1') and (y_done_seen = '1' or y_done = '1') then
          params_ready <= '1';
          params_gen   <= not params_gen;
          sizes_state  <= wait_change;
        end if;
      end if;

      if rst = '1' then
        cfg_seen     <= '0';
        params_ready <= '0';
        params_gen   <= '0';
        scale_start  <= '0';
        sizes_state  <= wait_change;
      end if;
    end if;

  end process sizes;

  x_scale : entity work.fastnms_resize_scale
    generic map (
      SIZE_BITS => SB
    )
    port map (
      clk   => clk,
      rst   => rst,
      start => scale_start,
      src   => new_sw,
      dst   => new_dw,
      busy  => x_busy,
      done  => x_done,
      m     => m_x
    );

  y_scale : entity work.fastnms_resize_scale
    generic map (
      SIZE_BITS => SB
    )
    port map (
      clk   => clk,
      rst   => rst,
      start => scale_start,
      src   => new_sh,
      dst   => new_dh,
      busy  => y_busy,
      done  => y_done,
      m     => m_y
    );

  -- ---- priming: the taps restart from index 0 between frames -----------------

  prime : process (clk) is
  begin

    if rising_edge(clk) then
      restart <= '0';
      if frame_state = idle and take = '0' and params_ready = '1' and
         (primed = '0' or primed_gen /= params_gen) and priming = '0' and restart = '0' then
        primed     <= '0';
        primed_gen <= params_gen;
        sw         <= new_sw;
        sh         <= new_sh;
        dw         <= new_dw;
        dh         <= new_dh;
        sizes_ok   <= new_ok;
        sw_m2      <= new_sw - 2;
        sh_m2      <= new_sh - 2;
        sw_two     <= to_sl(new_sw = 2);
        sh_one     <= to_sl(new_sh = 1);
        if new_ok = '1' then
          restart <= '1';
          priming <= '1';
        else
          primed <= '1';
        end if;
      elsif priming = '1' and restart = '0' and x_ready = '1' and y_ready = '1' then
        priming <= '0';
        primed  <= '1';
      end if;
      if take = '1' and frame_state = frame and in_sof = '1' then
        -- A frame cut short: the taps are mid-frame, prime them again.
        primed <= '0';
      end if;
      if rst = '1' then
        primed  <= '0';
        priming <= '0';
        restart <= '0';
      end if;
    end if;

  end process prime;

  x_taps : entity work.fastnms_resize_taps
    generic map (
      SIZE_BITS => SB
    )
    port map (
      clk       => clk,
      rst       => rst,
      restart   => restart,
      m         => m_x,
      src       => sw,
      dst       => dw,
      out_valid => tx_valid,
      out_ready => tx_ready,
      out_delta => tx_delta,
      out_c0    => tx_c0,
      out_last  => tx_last
    );

  y_taps : entity work.fastnms_resize_taps
    generic map (
      SIZE_BITS => SB
    )
    port map (
      clk       => clk,
      rst       => rst,
      restart   => restart,
      m         => m_y,
      src       => sh,
      dst       => dh,
      out_valid => ty_valid,
      out_ready => ty_ready,
      out_delta => ty_delta,
      out_c0    => ty_c0,
      out_last  => ty_last
    );

  -- The taps as a flag per column and per row, on registers.
  x_walk : entity work.fastnms_resize_walk
    generic map (
      SIZE_BITS => SB
    )
    port map (
      clk      => clk,
      rst      => rst,
      start    => restart,
      ready    => x_ready,
      step     => step_x,
      hit      => x_hit,
      c0       => x_c0,
      last     => x_tap_last,
      in_valid => tx_valid,
      in_ready => tx_ready,
      in_delta => tx_delta,
      in_c0    => tx_c0,
      in_last  => tx_last,
      starved  => x_starved
    );

  y_walk : entity work.fastnms_resize_walk
    generic map (
      SIZE_BITS => SB
    )
    port map (
      clk      => clk,
      rst      => rst,
      start    => restart,
      ready    => y_ready,
      step     => step_y,
      hit      => y_hit,
      c0       => y_c0,
      last     => y_tap_last,
      in_valid => ty_valid,
      in_ready => ty_ready,
      in_delta => ty_delta,
      in_c0    => ty_c0,
      in_last  => ty_last,
      starved  => y_starved
    );

  -- pragma translate_off
  fed : process (clk) is
  begin

    if rising_edge(clk) then
      assert not (x_starved = '1' or y_starved = '1')
        report "fastnms_resize: the taps came too late"
        severity failure;
    end if;

  end process fed;

  -- pragma translate_on

  -- ---- input: frames and positions -------------------------------------------

  in_ready <= accept_ok and not out_almost_full;
  take     <= in_valid and accept_ok and not out_almost_full;
  -- The column read from the row above: 0 at a start of frame.
  read_at <= (others => '0') when in_sof = '1' else
             resize(x, clog2(MAX_WIDTH));

  frames : process (clk) is

    variable base   : size_t;
    variable inc    : std_logic;
    variable base_y : size_t;

  begin

    if rising_edge(clk) then
      err_size  <= '0';
      err_frame <= '0';
      err_line  <= '0';
      v0        <= '0';
      sof0      <= '0';
      sof_ok    <= primed and sizes_ok;
      sof_bad   <= primed and not sizes_ok;
      if take = '1' then
        px0 <= in_data;
        -- Positions: the operands chosen before the add (no mux after it).
        if in_sof = '1' or x_last = '1' then
          base := (others => '0');
        else
          base := x;
        end if;
        inc := in_sof or not x_last;
        if in_sof = '1' or frame_state /= idle then
          x <= base + unsigned'(0 => inc);
        end if;
        -- The row: 0 at a start of frame, one more after a row's last pixel.
        if in_sof = '1' or (frame_state /= idle and x_last = '1') then
          if in_sof = '1' then
            base_y := (others => '0');
          else
            base_y := y;
          end if;
          y <= base_y + unsigned'(0 => not in_sof);
        end if;
        xl0 <= x_last and not in_sof;
        if in_sof = '1' then
          x0     <= (others => '0');
          y0     <= (others => '0');
          x_last <= sw_two;
          y_last <= sh_one;
          ending <= '0';
          -- sw >= 2: the first pixel never ends its row.
          err_line  <= in_eol;
          err_frame <= to_sl(frame_state /= idle);
          if frame_state = frame then
            -- Cut short: the taps are mid-frame; this frame is dropped and
            -- they prime again once it is over.
            frame_state <= drop;
          elsif sof_ok = '1' then
            frame_state <= frame;
            v0          <= '1';
            sof0        <= '1';
          else
            frame_state <= drop;
            err_size    <= sof_bad;
          end if;
        elsif frame_state = idle then
          -- A pixel between frames.
          err_frame <= '1';
        else
          v0 <= to_sl(frame_state = frame);
          x0 <= x;
          y0 <= y;
          if x_last = '1' then
            x_last <= '0';
            y_last <= to_sl(y = sh_m2);
            ending <= '0';
          else
            x_last <= to_sl(x = sw_m2);
            ending <= y_last and to_sl(x = sw_m2);
          end if;
          if ending = '1' then
            frame_state <= idle;
          end if;
          err_line <= in_eol xor x_last;
        end if;
      end if;
      if rst = '1' then
        frame_state <= idle;
        v0          <= '0';
      end if;
    end if;

  end process frames;

  accepting : process (clk) is
  begin

    if rising_edge(clk) then
      -- Between frames only once the taps are primed for the sizes in use.
      -- The sizes in use are the ones on the cfg ports a clock before.
      cfg_same <= to_sl(cfg_src_width = sw and cfg_src_height = sh and
                        cfg_dst_width = dw and cfg_dst_height = dh);
      -- Within a frame, up to its last pixel (taken now, or not yet).
      accept_ok <= (to_sl(frame_state /= idle) and not (take and ending and not in_sof)) or
                   (primed and cfg_same and to_sl(primed_gen = params_gen) and not restart);
      if rst = '1' then
        accept_ok <= '0';
      end if;
    end if;

  end process accepting;

  -- ---- the row above ------------------------------------------------------

  row_above : entity work.fastnms_ram_sdp
    generic map (
      DEPTH        => MAX_WIDTH,
      WIDTH        => 8,
      READ_LATENCY => 1,
      STYLE        => "block"
    )
    port map (
      clk     => clk,
      wr_en   => v0,
      wr_addr => resize(x0, clog2(MAX_WIDTH)),
      wr_data => px0,
      rd_en   => take,
      rd_addr => read_at,
      rd_data => above
    );

  -- ---- S1: the 2 x 2 window and the taps -----------------------------------

  -- The row is a destination row (a frame's first pixel opens its rows).
  row_out <= y_hit and not (rows_done and not sof0);
  step_x  <= v0 and row_out and not cols_done;
  step_y  <= v0 and xl0 and not (rows_done and not sof0);
  hit     <= step_x and x_hit;

  window : process (clk) is
  begin

    if rising_edge(clk) then
      if v0 = '1' then
        up_left   <= up_right;
        up_right  <= unsigned(above);
        cur_left  <= cur_right;
        cur_right <= unsigned(px0);
      end if;
      v2   <= hit;
      cx2  <= x_c0;
      cy2  <= y_c0;
      eol2 <= x_tap_last;
      -- The frame's first destination pixel: at the first hit from its first
      -- source pixel on.
      sof2 <= sof0 or first_out;
      if v0 = '1' then
        first_out <= (sof0 or first_out) and not hit;
      end if;
      -- After a row's last tap the columns wait for the next row; after the
      -- last destination row the rows wait for the next frame.
      if v0 = '1' and xl0 = '1' then
        cols_done <= '0';
      elsif hit = '1' and x_tap_last = '1' then
        cols_done <= '1';
      end if;
      if v0 = '1' and sof0 = '1' then
        rows_done <= '0';
      end if;
      if step_y = '1' and y_hit = '1' and y_tap_last = '1' then
        rows_done <= '1';
      end if;
      if rst = '1' or restart = '1' then
        v2        <= '0';
        cols_done <= '0';
        rows_done <= '0';
      end if;
    end if;

  end process window;

  -- ---- S3 .. S10: (cy (cx A + (256 - cx) B) + (256 - cy) (cx C + (256 - cx) D)
  -- + 2**15) >> 16, as 256 H + c (H' - H) steps ------------------------------

  interpolate : process (clk) is

    variable s   : unsigned(8 downto 0);
    variable row : signed(9 downto 0);

  begin

    if rising_edge(clk) then
      -- S3: A - B, C - D.
      d_ab3 <= signed('0' & up_left) - signed('0' & up_right);
      d_cd3 <= signed('0' & cur_left) - signed('0' & cur_right);
      b3    <= up_right;
      d3    <= cur_right;
      cx3   <= cx2;
      cy3   <= cy2;

      -- S4: cx (A - B), cx (C - D).
      m_ab4 <= signed('0' & cx3) * d_ab3;
      m_cd4 <= signed('0' & cx3) * d_cd3;
      b4    <= b3;
      d4    <= d3;
      cy4   <= cy3;

      -- S5: the row sums, 256 B + cx (A - B): the add is on bits 16..8.
      row    := resize(signed('0' & b4), 10) + m_ab4(17 downto 8);
      h_up5  <= unsigned(row(8 downto 0)) & unsigned(m_ab4(7 downto 0));
      row    := resize(signed('0' & d4), 10) + m_cd4(17 downto 8);
      h_cur5 <= unsigned(row(8 downto 0)) & unsigned(m_cd4(7 downto 0));
      cy5    <= cy4;

      -- S6, S7: H_up - H_cur in two halves.
      lo6    <= ('0' & h_up5(8 downto 0)) - ('0' & h_cur5(8 downto 0));
      h_up6  <= h_up5;
      h_cur6 <= h_cur5;
      cy6    <= cy5;

      d_h7   <=
      (
        resize(signed('0' & h_up6(16 downto 9)),
                9) -
        signed('0' & h_cur6(16 downto 9)) -
        signed(resize(unsigned'(
                                 0 => lo6(9)
                               ),
                       9))
      ) & signed(lo6(8 downto 0)
                );
      h_cur7 <= h_cur6;
      cy7    <= cy6;

      -- S8: cy (H_up - H_cur).
      m_h8   <= resize(signed('0' & cy7) * d_h7, 27);
      h_cur8 <= h_cur7;

      -- S9: the carry of bits 15..8 with the rounding 2**15, and the high
      -- parts (mh(15) stands for the 128 added to its byte).
      s     := ('0' & h_cur8(7 downto 0)) + ('0' & (unsigned(m_h8(15 downto 8)) xor x"80"));
      mid9  <= s;
      hi9   <= m_h8(26 downto 16) + signed(resize(unsigned'(0 => m_h8(15)), 11));
      h_hi9 <= h_cur8(16 downto 8);

      -- S10: the pixel.
      pix10 <= resize(unsigned(hi9 + signed(resize(h_hi9, 11)) +
                               signed(resize(unsigned'(0 => mid9(8)), 11))), 8);

      v_pipe   <= v_pipe(9 downto 3) & v2;
      sof_pipe <= sof_pipe(9 downto 3) & sof2;
      eol_pipe <= eol_pipe(9 downto 3) & eol2;
      if rst = '1' then
        v_pipe <= (others => '0');
      end if;
    end if;

  end process interpolate;

  wr_valid <= v_pipe(10);
  wr_data  <= sof_pipe(10) & eol_pipe(10) & std_logic_vector(pix10);

  out_fifo : entity work.fastnms_fifo
    generic map (
      DEPTH             => OUT_DEPTH,
      WIDTH             => 10,
      STYLE             => "distributed",
      ALMOST_FULL_LEVEL => OUT_DEPTH - 2 - OUT_ROOM
    )
    port map (
      clk         => clk,
      rst         => rst,
      in_valid    => wr_valid,
      in_ready    => out_in_ready,
      almost_full => out_almost_full,
      in_data     => wr_data,
      out_valid   => out_valid,
      out_ready   => out_ready,
      out_data    => out_word,
      busy        => open
    );

  out_data <= out_word(7 downto 0);
  out_eol  <= out_word(8);
  out_sof  <= out_word(9);

end architecture rtl;
