// Simulation speed: one run per process (SystemC elaborates once), printing figures.
//   sim_speed [--vectors N] [--units all|SPEC[;SPEC...]] [--mode fast|clocked]
//             [--vcd FILE] [--vcd-window FIRST:LAST] [--threads N] [--t-min T]
// The stream is generated on the fly (no storage, so memory stays flat in N): t uniform over
// [T, 1] (--t-min, default -1) from a fixed-seed generator, one white Blinn material n = 50, eps =
// 1e-3. Clocked mode gives every lane its own generator (same seed, same rows); the sink is always
// ready. --vcd (and
// --vcd-window) trace the clocked run as `glint sim --vcd` does.
#include <fmt/format.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "rtl_model/clocked_sim.h"
#include "rtl_model/fast_sim.h"
#include "rtl_model/row_stream.h"

namespace {

// The benchmark stream: `count` rows from a 64-bit LCG.
class GeneratedRows {
 public:
  GeneratedRows(std::uint64_t count, double t_min) : count_(count), t_min_(t_min) {}
  bool next(glint::VectorRow& row) {
    if (produced_ == count_) return false;
    state_ = state_ * 6364136223846793005ULL + 1442695040888963407ULL;
    row.t = t_min_ + static_cast<double>(state_ >> 11) * 0x1.0p-53 * (1.0 - t_min_);
    row.material = 0;
    row.line = ++produced_;
    return true;
  }

 private:
  std::uint64_t count_, produced_ = 0, state_ = 0x243F6A8885A308D3ULL;
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
    for (const auto& n : glint::unit_names()) units_arg += (units_arg.empty() ? "" : ";") + n;
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
    glint::FastOptions options;
    options.threads = threads;
    // A block at a time, as `glint sim` reads a file (VectorReader::next_block).
    stats = glint::run_fast_blocks(
        units, slots,
        [&](std::vector<glint::VectorRow>& block) {
          block.resize(glint::kEngineBatch);
          std::size_t n = 0;
          while (n < block.size() && rows.next(block[n])) ++n;
          block.resize(n);
          return n > 0;
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
