// Verilator's cycle rate on the lane `glint rtl` writes: the hardware simulator that issue 9 sets
// glint's fast mode against ("at the speed of the hardware simulators"). Not built by CMake: it
// drives the C++ model Verilator makes of the generated Verilog, and tests/bench/verilator_speed.sh
// builds the two together (Verilator's `--prefix Vlane`, so this file names no unit).
//   verilator_speed CYCLES [T_MIN]
// One request offered every cycle, the sink always ready, no trace: what a Verilator testbench of
// this lane does at its fastest. Built with GLINT_DATAPATH_LATENCY=L it drives the datapath module
// alone instead (no comparator, no merge buffer: a request started every cycle, II = 1, its result
// read L cycles later), the least RTL that computes the lobe: Verilator's rate at its highest. t is
// sim_speed's stream (generated_stream.h, t uniform over [T_MIN, 1], default -1), quantized to the
// lane's input code as glint's front end does (clamped to [0, 1], rounded to nearest, ties to
// even), one row a cycle, inline.
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "Vlane.h"
#include "generated_stream.h"
#include "verilated.h"

namespace {

// The input code of t for a uq1.F port of `bits` bits (F = bits - 1).
std::uint32_t input_code(double t, int bits) {
  const double scale = std::ldexp(1.0, bits - 1);
  const double clamped = std::fmin(std::fmax(t, 0.0), 1.0);
  return static_cast<std::uint32_t>(std::nearbyint(clamped * scale));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: verilator_speed CYCLES [T_MIN]\n");
    return 2;
  }
  const std::uint64_t cycles = std::strtoull(argv[1], nullptr, 10);
  const double t_min = argc > 2 ? std::strtod(argv[2], nullptr) : -1.0;
  const int in_bits = GLINT_IN_BITS;

  auto context = std::make_unique<VerilatedContext>();
  auto top = std::make_unique<Vlane>(context.get());
  const auto edge = [&] {
    top->clk = 1;
    top->eval();
    top->clk = 0;
    top->eval();
  };
  std::uint64_t state = glint::bench::kStreamSeed, retired = 0, skipped = 0, sum = 0;
  const auto next_code = [&] {
    state = glint::bench::lcg_step(state);
    return input_code(glint::bench::stream_t(state, t_min), in_bits);
  };
#if defined(GLINT_DATAPATH_LATENCY)
  // The result of the request started at edge c is read before edge c + L.
  constexpr std::uint64_t kLatency = GLINT_DATAPATH_LATENCY;
  top->clk = 0;
  top->start = 1;
  top->start_group = 0;
  const auto retire = [&](std::uint64_t c) {
    if (c >= kLatency) {
      ++retired;
      sum += top->result;
    }
  };
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t c = 0; c < cycles; ++c) {
    top->start_t = next_code();
    retire(c);
    edge();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  top->start = 0;
  for (std::uint64_t c = cycles; c < cycles + kLatency; ++c) {
    retire(c);
    edge();
  }
#else
  top->clk = 0;
  top->rst = 1;
  top->in_valid = 0;
  top->in_slot = 0;
  top->out_ready = 1;
  top->eval();
  for (int i = 0; i < 4; ++i) edge();
  top->rst = 0;
  top->in_valid = 1;
  const auto retire = [&] {
    if (top->out_valid) {
      ++retired;
      skipped += top->out_skipped;
      sum += top->out_result;
    }
  };
  const auto start = std::chrono::steady_clock::now();
  for (std::uint64_t c = 0; c < cycles; ++c) {
    top->in_t = next_code();
    retire();
    edge();
  }
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  // Drain (not timed): every request offered must leave, one result each. A lane that stalled would
  // have dropped requests (the loop offers the next one whatever in_ready said; reading in_ready
  // would need a second eval a cycle) and retired fewer.
  top->in_valid = 0;
  for (int i = 0; i < 256 && retired < cycles; ++i) {
    retire();
    edge();
  }
#endif
  top->final();
  if (retired != cycles) {
    std::fprintf(stderr, "verilator_speed: %" PRIu64 " requests offered, %" PRIu64 " results\n",
                 cycles, retired);
    return 1;
  }
  std::printf("verilator cycles %" PRIu64 ": %.3f s, %.2f M cycles/s (results %" PRIu64
              ", skipped %" PRIu64 ", result sum %" PRIu64 ")\n",
              cycles, seconds, static_cast<double>(cycles) / seconds * 1e-6, retired, skipped, sum);
  return 0;
}
