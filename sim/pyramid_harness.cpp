// The pyramid engine's driver: sim/fastnms_resize_chain.vhd (LEVELS - 1
// fastnms_resize in a chain) as GHDL synthesizes it, compiled by Verilator.
// sim/pyramid.py builds it and reads what it writes.
//
//   fastnms_pyramid_vsim PIXELS OUT_PREFIX W0 H0 W1 H1 ... (LEVELS sizes)
//
// PIXELS: level 0's pixels, raster order, one byte each (one frame). The chain
// is reset, the scales are left 1 300 clocks, then the pixels go in one per
// clock (held only while in_ready is low). Each level k >= 1's pixels are
// written to OUT_PREFIX<k>.raw as they are taken. stdout: one line
// "done CLOCKS HELD STALLS ERRORS": the clocks from the first pixel offered to
// the last pixel out, the clocks the input was held, the clocks a link waited
// and the error pulses of all steps.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <vector>

#include "Vfastnms_resize_chain.h"
#include "verilated.h"

namespace {

void put_field(VlWide<3>& word, int k, uint32_t v) {
  for (int b = 0; b < 12; b++) {
    int bit = 12 * k + b;
    uint32_t mask = 1u << (bit % 32);
    if ((v >> b) & 1) {
      word[bit / 32] |= mask;
    } else {
      word[bit / 32] &= ~mask;
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5 || (argc - 3) % 2 != 0) {
    std::fprintf(stderr, "usage: %s PIXELS OUT_PREFIX W0 H0 W1 H1 ...\n", argv[0]);
    return 2;
  }
  const int levels = (argc - 3) / 2;
  std::vector<uint32_t> w(levels), h(levels);
  for (int k = 0; k < levels; k++) {
    w[k] = std::strtoul(argv[3 + 2 * k], nullptr, 10);
    h[k] = std::strtoul(argv[4 + 2 * k], nullptr, 10);
  }
  FILE* in = std::fopen(argv[1], "rb");
  if (!in) {
    std::perror(argv[1]);
    return 2;
  }
  std::vector<uint8_t> pixels(static_cast<size_t>(w[0]) * h[0]);
  if (std::fread(pixels.data(), 1, pixels.size(), in) != pixels.size()) {
    std::fprintf(stderr, "%s: fewer than %zu pixels\n", argv[1], pixels.size());
    return 2;
  }
  std::fclose(in);

  auto context = std::make_unique<VerilatedContext>();
  auto top = std::make_unique<Vfastnms_resize_chain>(context.get());
  std::vector<FILE*> out(levels, nullptr);
  std::vector<size_t> expect(levels), got(levels, 0);
  for (int k = 1; k < levels; k++) {
    std::string name = std::string(argv[2]) + std::to_string(k) + ".raw";
    out[k] = std::fopen(name.c_str(), "wb");
    if (!out[k]) {
      std::perror(name.c_str());
      return 2;
    }
    expect[k] = static_cast<size_t>(w[k]) * h[k];
  }
  for (int k = 0; k < levels; k++) {
    put_field(top->cfg_widths, k, w[k]);
    put_field(top->cfg_heights, k, h[k]);
  }
  uint64_t held = 0, stalls = 0, errors = 0, clocks = 0;
  auto clock = [&]() {
    top->clk = 0;
    top->eval();
    const uint64_t valid = top->link_valid, ready = top->link_ready, data = top->link_data;
    for (int k = 1; k < levels; k++) {
      if (!((valid >> k) & 1)) continue;
      if (!((ready >> k) & 1)) {
        stalls++;
        continue;
      }
      std::fputc(static_cast<int>((data >> (8 * k)) & 0xff), out[k]);
      got[k]++;
    }
    if (top->in_valid && !top->in_ready) held++;
    errors += __builtin_popcountll(top->errors);
    top->clk = 1;
    top->eval();
    context->timeInc(1);
  };
  top->rst = 1;
  top->in_valid = 0;
  for (int i = 0; i < 3; i++) clock();
  top->rst = 0;
  for (int i = 0; i < 1300; i++) clock();
  const size_t n = pixels.size();
  size_t i = 0;
  while (i < n) {
    top->in_valid = 1;
    top->in_data = pixels[i];
    top->in_sof = i == 0;
    top->in_eol = i % w[0] == w[0] - 1;
    top->eval();
    const bool taken = top->in_ready;
    clock();
    clocks++;
    if (taken) i++;
  }
  top->in_valid = 0;
  auto done = [&]() {
    for (int k = 1; k < levels; k++) {
      if (got[k] < expect[k]) return false;
    }
    return true;
  };
  for (int spare = 0; !done() && spare < 100000; spare++) {
    clock();
    clocks++;
  }
  for (int k = 1; k < levels; k++) std::fclose(out[k]);
  top->final();
  std::printf("done %llu %llu %llu %llu\n", static_cast<unsigned long long>(clocks),
              static_cast<unsigned long long>(held), static_cast<unsigned long long>(stalls),
              static_cast<unsigned long long>(errors));
  return 0;
}
