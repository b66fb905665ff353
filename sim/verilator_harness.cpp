// The fast simulation engine's driver: fastnms_axi as the netlist GHDL
// synthesizes from rtl/, compiled by Verilator, driven clock by clock from C++
// the way the cocotb bench drives it (sim/driver.py): reset, AXI4-Lite writes of
// WIDTH, HEIGHT, THRESHOLD (and BUDGET, MIN_AREA), AXI4-Stream video in, corner
// records out. sim/verilator.py builds it and reads what it writes.
//
//   fastnms_vsim JOB PIXELS RECORDS [+verilator+... options]
//
// JOB (text, one setting per line):
//   seed N | idle rate P | idle bits 0110.. | stall rate P | stall bits ..
//   hblank N | vblank N | ppc N | budget CELL K | min_area N | frame WIDTH HEIGHT THRESHOLD
// (budget, min_area: BUDGET, MIN_AREA written with each frame's registers; none: not
// written)
// PIXELS: the frames' pixels, raster order, one byte each, frame after frame;
// they go in as beats of PPC pixels (the build's generic, `ppc` in the job;
// default 1), pixel 0 of a beat in the low byte, as UG934 packs video.
// RECORDS: written with every beat of the corner records: tdata, then the clock
// of its handshake (two 64-bit little-endian words).
// stdout: one "frame" line per frame and one "done" line (see sim/verilator.py);
// stderr: "progress PIXELS_IN PIXELS" about once a second, and errors.
//
// Clocks are counted at rising edges from the first one after aresetn rises,
// as AxiTop does in sim/driver.py; a handshake is seen at the edge that takes it.
#include <cinttypes>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <deque>
#include <memory>
#include <string>
#include <vector>

#include "Vfastnms_axi.h"
#include "fastnms_regs.h"
#include "verilated.h"

namespace {

// The seeded pause patterns; sim/timing.py computes the same values.
uint64_t splitmix64(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

struct Pattern {
  double rate = 0.0;
  std::string bits;  // '1' = pause, repeated
  uint64_t key = 0;
  // Whether the driver pauses at clock k of its pattern.
  bool at(uint64_t k) const {
    if (!bits.empty()) return bits[k % bits.size()] == '1';
    if (rate <= 0.0) return false;
    return static_cast<double>(splitmix64(key ^ splitmix64(k)) >> 11) * 0x1.0p-53 < rate;
  }
};

struct FrameSpec {
  unsigned width, height, threshold;
};

struct FrameResult {
  uint64_t first_pixel = 0, last_pixel = 0, last_record = 0, records = 0, input_stalls = 0;
};

[[noreturn]] void fail(const char* what) {
  std::fprintf(stderr, "fastnms_vsim: %s\n", what);
  std::exit(1);
}

struct AxiLiteWrite {
  uint32_t addr, data;
  size_t configures;  // frames configured once this write is answered
};

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) fail("usage: fastnms_vsim JOB PIXELS RECORDS [+verilator+...]");
  auto context = std::make_unique<VerilatedContext>();
  context->commandArgs(argc, argv);

  uint64_t seed = 1, hblank = 0, vblank = 0, ppc = 1;
  bool budget = false, min_area = false;
  unsigned budget_cell = 16, budget_k = 0;
  uint32_t min_area_value = 0;
  Pattern idle, stall;
  std::vector<FrameSpec> frames;
  {
    FILE* job = std::fopen(argv[1], "r");
    if (!job) fail("cannot read the job file");
    char line[512];
    while (std::fgets(line, sizeof line, job)) {
      char word[32], kind[32], value[400];
      unsigned w, h, t;
      unsigned long long n;
      if (std::sscanf(line, "frame %u %u %u", &w, &h, &t) == 3) {
        frames.push_back({w, h, t});
      } else if (std::sscanf(line, "budget %u %u", &budget_cell, &budget_k) == 2) {
        budget = true;
      } else if (std::sscanf(line, "%31s %31s %399s", word, kind, value) == 3) {
        Pattern& p = std::strcmp(word, "idle") == 0 ? idle : stall;
        if (std::strcmp(kind, "rate") == 0) p.rate = std::atof(value);
        else p.bits = value;
      } else if (std::sscanf(line, "%31s %llu", word, &n) == 2) {
        if (std::strcmp(word, "seed") == 0) seed = n;
        else if (std::strcmp(word, "hblank") == 0) hblank = n;
        else if (std::strcmp(word, "vblank") == 0) vblank = n;
        else if (std::strcmp(word, "ppc") == 0) ppc = n;
        else if (std::strcmp(word, "min_area") == 0) {
          if (n > FASTNMS_MIN_AREA_VALUE_MASK >> FASTNMS_MIN_AREA_VALUE_SHIFT)
            fail("min_area out of range");
          min_area = true;
          min_area_value = static_cast<uint32_t>(n);
        } else fail("unknown job setting");
      }
    }
    std::fclose(job);
  }
  if (frames.empty()) fail("no frame in the job");
  if (ppc != 1 && ppc != 2 && ppc != 4) fail("ppc must be 1, 2 or 4");
  for (const auto& f : frames)
    if (f.width % ppc != 0) fail("a frame width is not a multiple of ppc");
  idle.key = splitmix64(seed * 2);
  stall.key = splitmix64(seed * 2 + 1);

  std::vector<uint8_t> pixels;
  {
    FILE* f = std::fopen(argv[2], "rb");
    if (!f) fail("cannot read the pixel file");
    uint8_t buf[1 << 16];
    size_t n;
    while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) pixels.insert(pixels.end(), buf, buf + n);
    std::fclose(f);
  }
  uint64_t total_pixels = 0;
  for (const auto& f : frames) total_pixels += uint64_t(f.width) * f.height;
  if (pixels.size() != total_pixels) fail("the pixel file does not match the frames");
  FILE* records_out = std::fopen(argv[3], "wb");
  if (!records_out) fail("cannot write the record file");

  auto top = std::make_unique<Vfastnms_axi>(context.get());
  // Every input explicitly: +verilator+rand+reset+2 randomises inputs too.
  top->aclk = 0;
  top->aresetn = 0;
  top->s_axis_video_tdata = 0;
  top->s_axis_video_tuser = 0;
  top->s_axis_video_tlast = 0;
  top->s_axis_video_tvalid = 0;
  top->m_axis_corners_tready = 0;
  top->m_axis_score_tready = 0;
  top->s_axi_ctrl_awaddr = 0;
  top->s_axi_ctrl_awprot = 0;
  top->s_axi_ctrl_awvalid = 0;
  top->s_axi_ctrl_wdata = 0;
  top->s_axi_ctrl_wstrb = 0xF;
  top->s_axi_ctrl_wvalid = 0;
  top->s_axi_ctrl_bready = 1;
  top->s_axi_ctrl_araddr = 0;
  top->s_axi_ctrl_arprot = 0;
  top->s_axi_ctrl_arvalid = 0;
  top->s_axi_ctrl_rready = 1;

  // One clock: settle the inputs set since the last edge, sample the handshakes
  // (the values the rising edge takes), then the edge.
  struct Seen {
    bool video, video_stall, record, record_last, aw, w, b, ar, r;
    uint64_t record_word;
    uint32_t rdata;
    bool record_valid;
    uint32_t record_keep;
    bool score_valid;
  };
  auto clock = [&]() {
    top->aclk = 0;
    top->eval();
    Seen s{top->s_axis_video_tvalid && top->s_axis_video_tready,
           top->s_axis_video_tvalid && !top->s_axis_video_tready,
           top->m_axis_corners_tvalid && top->m_axis_corners_tready,
           top->m_axis_corners_tlast != 0,
           top->s_axi_ctrl_awvalid && top->s_axi_ctrl_awready,
           top->s_axi_ctrl_wvalid && top->s_axi_ctrl_wready,
           top->s_axi_ctrl_bvalid && top->s_axi_ctrl_bready,
           top->s_axi_ctrl_arvalid && top->s_axi_ctrl_arready,
           top->s_axi_ctrl_rvalid && top->s_axi_ctrl_rready,
           top->m_axis_corners_tdata,
           top->s_axi_ctrl_rdata,
           top->m_axis_corners_tvalid != 0,
           top->m_axis_corners_tkeep,
           top->m_axis_score_tvalid != 0};
    top->aclk = 1;
    top->eval();
    context->timeInc(1);
    return s;
  };

  // Reset as AxiTop.reset: aresetn low, then a few clocks of rest. Outputs are
  // not looked at while aresetn is low (the netlist's power-up values are
  // arbitrary under --x-initial unique).
  for (int i = 0; i < 8; ++i) clock();
  top->aresetn = 1;
  uint64_t cycle = 0;
  for (int i = 0; i < 4; ++i) {
    clock();
    ++cycle;
  }

  std::deque<AxiLiteWrite> writes;
  bool aw_done = false, w_done = false, ar_done = false, write_active = false, read_active = false;
  size_t configured = 0;  // frames whose registers have been written
  auto queue_config = [&](size_t i) {
    writes.push_back({FASTNMS_WIDTH_OFFSET, frames[i].width, configured});
    writes.push_back({FASTNMS_HEIGHT_OFFSET, frames[i].height, configured});
    if (budget)
      writes.push_back({FASTNMS_BUDGET_OFFSET,
                        budget_cell << FASTNMS_BUDGET_CELL_SHIFT | budget_k << FASTNMS_BUDGET_PER_CELL_SHIFT,
                        configured});
    if (min_area)
      writes.push_back(
          {FASTNMS_MIN_AREA_OFFSET, min_area_value << FASTNMS_MIN_AREA_VALUE_SHIFT, configured});
    writes.push_back({FASTNMS_THRESHOLD_OFFSET, frames[i].threshold, i + 1});
  };
  queue_config(0);

  std::vector<FrameResult> results(frames.size());
  size_t in_frame = 0, out_frame = 0;  // frame of the next pixel in / record out
  uint64_t in_pos = 0, in_line_pos = 0, in_line = 0, pixel_base = 0, pixels_in = 0;
  uint64_t blank = 0, pattern_clock = 0, input_stalls = 0;
  bool streaming = false, video_valid = false;
  uint32_t status = 0, frame_count = 0;
  int reads_left = -1;  // -1: the frames are still running
  uint64_t idle_since = 0;
  std::time_t last_report = std::time(nullptr);
  const uint64_t stuck_limit = 1000000;  // clocks without any handshake: the IP is stuck

  // The output rules of sim/axi_protocol.py that apply here (its other checks run
  // under the cocotb engine): a record offered stays offered, unchanged, until
  // taken; TKEEP all ones; TLAST equal to the record's LAST bit on its final beat
  // (an ORB record is FASTNMS_REC_ORB_BEATS beats) and 0 on the others; no score video.
  Seen before{};
  unsigned payload_left = 0;  // beats of the ORB record in progress still to come
  bool payload_last = false;  // that record is its frame's last
  auto check_outputs = [&](const Seen& s) {
    if (before.record_valid && !before.record) {
      if (!s.record_valid) fail("AXI protocol: m_axis_corners_tvalid fell before tready");
      if (s.record_word != before.record_word || s.record_last != before.record_last)
        fail("AXI protocol: a corner record changed before tready");
    }
    if (s.record_valid) {
      if (s.record_keep != 0xFF) fail("AXI protocol: m_axis_corners_tkeep not all ones");
      const bool orb = ((s.record_word >> FASTNMS_REC_ORB_SHIFT) & 1) != 0;
      const bool last = ((s.record_word >> FASTNMS_REC_LAST_SHIFT) & 1) != 0;
      const bool want = payload_left ? payload_left == 1 && payload_last : last && !orb;
      if (s.record_last != want)
        fail("AXI protocol: m_axis_corners_tlast not on the frame's last beat");
      if (s.record && payload_left) {
        --payload_left;
      } else if (s.record && orb) {
        payload_left = FASTNMS_REC_ORB_BEATS - 1;
        payload_last = last;
      }
    }
    if (s.score_valid) fail("AXI protocol: m_axis_score_tvalid without SCORE_VIDEO");
    before = s;
  };

  while (true) {
    Seen s = clock();
    ++cycle;
    check_outputs(s);
    bool progress = false;
    // ---- AXI4-Lite: one write at a time, address and data together -----------
    if (s.aw) aw_done = true;
    if (s.w) w_done = true;
    if (s.ar) ar_done = true;
    if (s.b) {
      if (writes.empty()) fail("an AXI4-Lite write response nobody asked for");
      configured = writes.front().configures;
      writes.pop_front();
      write_active = aw_done = w_done = false;
      progress = true;
    }
    if (s.r) {
      (reads_left == 2 ? status : frame_count) = s.rdata;
      --reads_left;
      read_active = ar_done = false;
      progress = true;
    }
    if (!write_active && !read_active && !writes.empty()) {
      write_active = true;
      top->s_axi_ctrl_awaddr = writes.front().addr;
      top->s_axi_ctrl_wdata = writes.front().data;
    }
    if (reads_left > 0 && !read_active && !write_active && writes.empty()) {
      read_active = true;
      top->s_axi_ctrl_araddr = reads_left == 2 ? FASTNMS_STATUS_OFFSET : FASTNMS_FRAME_COUNT_OFFSET;
    }
    top->s_axi_ctrl_awvalid = write_active && !aw_done;
    top->s_axi_ctrl_wvalid = write_active && !w_done;
    top->s_axi_ctrl_arvalid = read_active && !ar_done;
    if (reads_left == 0) break;

    // ---- video in, as cocotbext-axi's AxiStreamSource ------------------------
    if (s.video_stall) {
      ++input_stalls;
      ++results[in_frame].input_stalls;
    }
    if (s.video) {
      if (in_frame == frames.size()) fail("a pixel taken after the last frame");
      FrameResult& r = results[in_frame];
      if (in_pos == 0) r.first_pixel = cycle;
      in_pos += ppc;
      pixels_in += ppc;
      video_valid = false;
      progress = true;
      const FrameSpec& f = frames[in_frame];
      in_line_pos += ppc;
      if (in_line_pos == f.width) {
        in_line_pos = 0;
        blank = hblank;
        // The next frame's size and threshold, written once this frame's first
        // line is in: by then its start of frame has left the input buffer and
        // taken the values it waited for (docs/fastnms_axi.md).
        if (in_line == 0 && in_frame + 1 < frames.size()) queue_config(in_frame + 1);
        if (++in_line == f.height) {
          r.last_pixel = cycle;
          blank = vblank;
          pixel_base += in_pos;
          in_pos = in_line = 0;
          ++in_frame;
        }
      }
    }
    if (!streaming && configured >= 1) streaming = true;
    if (streaming && !video_valid && in_frame < frames.size() && configured > in_frame) {
      if (blank > 0) {
        --blank;
      } else if (!idle.at(pattern_clock)) {
        const FrameSpec& f = frames[in_frame];
        uint32_t beat = 0;
        for (uint64_t i = 0; i < ppc; ++i) beat |= uint32_t(pixels[pixel_base + in_pos + i]) << (8 * i);
        top->s_axis_video_tdata = beat;
        top->s_axis_video_tuser = in_pos == 0;
        top->s_axis_video_tlast = in_line_pos + ppc == f.width;
        video_valid = true;
      }
    }
    top->s_axis_video_tvalid = video_valid;

    // ---- corner records out ---------------------------------------------------
    if (s.record) {
      if (out_frame == frames.size()) fail("a corner record after the last frame's");
      const uint64_t beat[2] = {s.record_word, cycle};
      std::fwrite(beat, sizeof beat[0], 2, records_out);
      FrameResult& r = results[out_frame];
      ++r.records;
      progress = true;
      if (s.record_last) {
        r.last_record = cycle;
        if (++out_frame == frames.size()) reads_left = 2;
      }
    }
    top->m_axis_corners_tready = streaming && !stall.at(pattern_clock);
    if (streaming) ++pattern_clock;

    // ---- guard and progress ---------------------------------------------------
    idle_since = progress ? 0 : idle_since + 1;
    if (idle_since > stuck_limit) {
      std::fprintf(stderr,
                   "fastnms_vsim: no handshake for %" PRIu64 " clocks (frame %zu: %" PRIu64
                   " pixels in; %zu frames out)\n",
                   idle_since, in_frame, in_pos, out_frame);
      return 3;
    }
    if (((cycle & 0xFFFF) == 0) && std::time(nullptr) != last_report) {
      last_report = std::time(nullptr);
      std::fprintf(stderr, "progress %" PRIu64 " %" PRIu64 "\n", pixels_in, total_pixels);
    }
  }
  std::fclose(records_out);
  for (size_t i = 0; i < frames.size(); ++i) {
    const FrameResult& r = results[i];
    std::printf("frame %zu %" PRIu64 " %" PRIu64 " %" PRIu64 " %" PRIu64 " %" PRIu64 "\n", i,
                r.first_pixel, r.last_pixel, r.last_record, r.records, r.input_stalls);
  }
  std::printf("done %" PRIu64 " %" PRIu64 " %" PRIu32 " %" PRIu32 "\n", cycle, input_stalls, status,
              frame_count);
  top->final();
  return 0;
}
