// Simulation speed: one run per process (SystemC elaborates once), printing figures.
//   sim_speed [--vectors N] [--units all|SPEC[;SPEC...]] [--mode fast|clocked]
//             [--vcd FILE] [--vcd-window FIRST:LAST] [--threads N] [--t-min T]
// The stream is generated on the fly (no storage, so memory stays flat in N): t uniform over
// [T, 1] (--t-min, default -1) from a fixed-seed generator, one white Blinn material n = 50, eps =
// 1e-3. Clocked mode gives every lane its own generator (same seed, same rows); the sink is always
// ready. --vcd (and --vcd-window) trace the clocked run as `glint sim --vcd` does.
#include <fmt/format.h>
#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "generated_stream.h"
#include "io/thread_pool.h"
#include "rtl_model/clocked_sim.h"
#include "rtl_model/fast_sim.h"
#include "rtl_model/row_stream.h"

namespace {

// The benchmark stream (generated_stream.h): `count` rows. Besides a row at a time (clocked mode),
// a block at a time on several threads, as `glint sim` parses a block of a file on its threads
// (VectorReader::next_block): each part of the block starts from its own state (jump-ahead, the
// same rows), and four rows a step break the LCG's chain of dependent multiplies.
class GeneratedRows {
 public:
  GeneratedRows(std::uint64_t count, double t_min) : count_(count), t_min_(t_min) {}

  bool next(glint::VectorRow& row) {
    if (produced_ == count_) return false;
    state_ = glint::bench::lcg_step(state_);
    row = make_row(state_, ++produced_, t_min_);
    return true;
  }

  // The next rows (at most block.size()) into `block`, on `pool`'s threads; false at the end.
  bool next_block(std::vector<glint::VectorRow>& block, glint::ThreadPool& pool) {
    const std::uint64_t n = std::min<std::uint64_t>(block.size(), count_ - produced_);
    block.resize(n);
    if (n == 0) return false;
    const std::uint64_t parts = static_cast<std::uint64_t>(pool.threads());
    const std::uint64_t per_part = (n + parts - 1) / parts;
    pool.run(parts, [&](std::size_t p) {
      const std::uint64_t a = std::min(n, p * per_part), b = std::min(n, a + per_part);
      fill(block.data(), a, b, jump(state_, a));
    });
    state_ = jump(state_, n);
    produced_ += n;
    return true;
  }

 private:
  static glint::VectorRow make_row(std::uint64_t state, std::uint64_t line, double t_min) {
    glint::VectorRow row;
    row.t = glint::bench::stream_t(state, t_min);
    row.line = line;
    return row;
  }

  // The state `steps` steps after `state`: lcg_step applied by squaring.
  static std::uint64_t jump(std::uint64_t state, std::uint64_t steps) {
    std::uint64_t mul = 1, add = 0, step_mul = glint::bench::kLcgMul,
                  step_add = glint::bench::kLcgAdd;
    for (; steps > 0; steps >>= 1) {
      if (steps & 1) {
        mul *= step_mul;
        add = add * step_mul + step_add;
      }
      step_add = step_add * (step_mul + 1);
      step_mul *= step_mul;
    }
    return state * mul + add;
  }

  // Rows [a, b) of a block whose row 0 follows `state` (the state before row a).
  // The members in locals: the rows' stores could otherwise change them, as far as the compiler
  // knows, and each row would load them again. Only t and line are written: every other field is
  // the same in every row (one material, one light, no pixel), and the block's rows keep it from
  // when the vector made them (next_block resizes, which leaves existing rows as they are). Two
  // stores a row instead of six: the loop waits on stores to lines beyond the cache (x0.97).
  void fill(glint::VectorRow* rows, std::uint64_t a, std::uint64_t b, std::uint64_t state) const {
    const std::uint64_t mul4 = jump(1, 4) - jump(0, 4), add4 = jump(0, 4);
    const std::uint64_t line = produced_ + 1;
    const double t_min = t_min_;
    std::uint64_t s[4];
    for (int j = 0; j < 4; ++j) s[j] = jump(state, static_cast<std::uint64_t>(j) + 1);
    std::uint64_t k = a;
    for (; k + 4 <= b; k += 4)
      for (int j = 0; j < 4; ++j) {
        rows[k + j].t = glint::bench::stream_t(s[j], t_min);
        rows[k + j].line = line + k + j;
        s[j] = s[j] * mul4 + add4;
      }
    for (int j = 0; k < b; ++k, ++j) {
      rows[k].t = glint::bench::stream_t(s[j], t_min);
      rows[k].line = line + k;
    }
  }

  std::uint64_t count_, produced_ = 0, state_ = glint::bench::kStreamSeed;
  double t_min_;
};

class GeneratedStream final : public glint::RowStream {
 public:
  GeneratedStream(std::uint64_t count, double t_min) : rows_(count, t_min) {}
  bool next(glint::VectorRow& row) override { return rows_.next(row); }

 private:
  GeneratedRows rows_;
};

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::size_t pos = 0;
  while (pos <= s.size()) {
    std::size_t end = s.find(';', pos);
    if (end == std::string::npos) end = s.size();
    out.push_back(s.substr(pos, end - pos));
    pos = end + 1;
  }
  return out;
}

}  // namespace

int sc_main(int argc, char* argv[]) {
  std::uint64_t vectors = 10'000'000;
  std::string units_arg = "schlick", mode = "fast", vcd, window;
  int threads = 1;
  double t_min = -1.0;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--vectors")) vectors = std::stoull(argv[i + 1]);
    if (!std::strcmp(argv[i], "--units")) units_arg = argv[i + 1];
    if (!std::strcmp(argv[i], "--mode")) mode = argv[i + 1];
    if (!std::strcmp(argv[i], "--vcd")) vcd = argv[i + 1];
    if (!std::strcmp(argv[i], "--vcd-window")) window = argv[i + 1];
    if (!std::strcmp(argv[i], "--threads")) threads = std::stoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--t-min")) t_min = std::stod(argv[i + 1]);
  }
  if (!vcd.empty() && mode != "clocked") {
    std::fprintf(stderr, "--vcd needs --mode clocked\n");
    return 2;
  }
  if (units_arg == "all") {
    units_arg.clear();
    for (const auto& n : glint::default_unit_names())
      units_arg += (units_arg.empty() ? "" : ";") + n;
  }
  glint::VectorHeader header;
  header.eps = 1e-3;
  header.lights = 1;
  header.materials.push_back({"white", {1, 1, 1}, 50, glint::Lobe::kBlinn, 0});
  const glint::SlotMap slots = glint::make_slots(header);
  std::vector<std::unique_ptr<glint::SpecularUnit>> owned;
  std::vector<const glint::SpecularUnit*> units;
  for (const auto& s : split(units_arg)) {
    owned.push_back(glint::make_unit(glint::parse_unit_spec(s), slots));
    units.push_back(owned.back().get());
  }
  std::vector<glint::LaneAccumulator> acc;
  acc.reserve(units.size());
  for (const auto* u : units) acc.emplace_back(*u, slots);
  std::vector<std::uint64_t> skipped(units.size(), 0);
  const auto start = std::chrono::steady_clock::now();
  std::vector<glint::TimingStats> stats;
  if (mode == "fast") {
    GeneratedRows rows(vectors, t_min);
    glint::ThreadPool generator_pool(threads);
    glint::FastOptions options;
    options.threads = threads;
    // A block at a time, as `glint sim` reads a file (VectorReader::next_block).
    stats = glint::run_fast_blocks(
        units, slots,
        [&](std::vector<glint::VectorRow>& block) {
          block.resize(glint::kEngineBatch);
          return rows.next_block(block, generator_pool);
        },
        options, &acc);
    for (std::size_t i = 0; i < units.size(); ++i) skipped[i] = acc[i].stats().skipped;
  } else if (mode == "clocked") {
    glint::ClockedOptions options;
    options.vcd_path = vcd;
    if (!window.empty()) {
      const auto colon = window.find(':');
      options.vcd_first = std::stoull(window.substr(0, colon));
      options.vcd_last = std::stoull(window.substr(colon + 1));
    }
    stats = glint::run_clocked(units, slots,
                               [&] { return std::make_unique<GeneratedStream>(vectors, t_min); },
                               options, {});
    for (std::size_t i = 0; i < units.size(); ++i)
      skipped[i] = stats[i].results - stats[i].computed;
  } else {
    std::fprintf(stderr, "mode %s not available\n", mode.c_str());
    return 2;
  }
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  // CPU seconds (user + system, the whole process) besides the wall clock: on a machine shared with
  // other work they are the figure that compares.
  const auto seconds = [](const timeval& tv) {
    return static_cast<double>(tv.tv_sec) + static_cast<double>(tv.tv_usec) * 1e-6;
  };
  const double cpu = seconds(ru.ru_utime) + seconds(ru.ru_stime);
  fmt::print(
      "mode {}{} units {} vectors {} threads {}: {:.3f} s, {:.2f} M vectors/s, CPU {:.3f} s "
      "({:.2f} M vectors per CPU second), max RSS {:.1f} MB\n",
      mode, vcd.empty() ? "" : " (VCD)", units.size(), vectors, threads, secs,
      static_cast<double>(vectors) / secs / 1e6, cpu, static_cast<double>(vectors) / cpu / 1e6,
      static_cast<double>(ru.ru_maxrss) / 1024.0);
  for (std::size_t i = 0; i < units.size(); ++i)
    fmt::print("  {:<8} cycles {} skipped {}\n", units[i]->name(), stats[i].cycles, skipped[i]);
  return 0;
}
