// Sweep speed: one sweep of many configurations over a long stream, printing where the time goes.
//   sweep_speed [--vectors N] [--jobs J] [--t-min T] [--file VECTORS] [--grid G]...
// Without --file the stream is generated in memory (nothing stored, so memory stays flat in N):
// t uniform over [T, 1] (default T = -1) from a fixed-seed generator, one white Blinn material
// n = 50, eps = 1e-3: with T = -1 ~94 % of the requests are skipped by t^n's units, with T = 0.9
// (above tau = 0.871) every unit computes every request. With --file the rows come from
// a vector file (its parsing included). Without --grid, 200 configurations of the five families.
// Prints the phases (building the configurations, the untimed datapaths and statistics, the
// timing recurrences, the report rows), configurations x rows per second and the peak RSS.
#include <fmt/format.h>
#include <sys/resource.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <vector>

#include "generated_stream.h"
#include "io/vectors.h"
#include "sweep/engine.h"
#include "sweep/grid.h"

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

const std::vector<std::string> kDefaultGrids = {
    "horner:degree=2..7,in=uq1.10|uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15",   // 54
    "lut:bits=4..8,in=uq1.10|uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15",        // 45
    "hast:d=2..5,in=uq1.10|uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15",          // 36
    "pow:log_bits=4..8/2,in=uq1.10|uq1.12|uq1.15,out=uq1.10|uq1.12|uq1.15",  // 27
    "schlick:match=none|width,divider=pipelined|iterative,in=uq1.10|uq1.12|uq1.15,"
    "out=uq1.10|uq1.15",                                        // 24
    "lut:bits=9|10,in=uq1.15|uq1.16,out=uq1.12|uq1.15|uq1.16",  // 12
    "pow:in=uq1.16,out=uq1.16",                                 // 1
    "horner:degree=8,in=uq1.16",                                // 1
};

}  // namespace

int main(int argc, char* argv[]) {
  std::uint64_t vectors = 1'000'000;
  int jobs = 2;
  double t_min = -1.0;
  std::string file;
  std::vector<std::string> grid_texts;
  for (int i = 1; i + 1 < argc; i += 2) {
    if (!std::strcmp(argv[i], "--vectors")) vectors = std::stoull(argv[i + 1]);
    if (!std::strcmp(argv[i], "--jobs")) jobs = std::stoi(argv[i + 1]);
    if (!std::strcmp(argv[i], "--file")) file = argv[i + 1];
    if (!std::strcmp(argv[i], "--t-min")) t_min = std::stod(argv[i + 1]);
    if (!std::strcmp(argv[i], "--grid")) grid_texts.push_back(argv[i + 1]);
  }
  if (grid_texts.empty()) grid_texts = kDefaultGrids;
  std::vector<glint::Grid> grids;
  for (const auto& g : grid_texts) grids.push_back(glint::parse_grid(g));
  const auto configs = glint::expand_grids(grids);

  glint::VectorHeader header;
  std::unique_ptr<glint::VectorReader> reader;
  if (file.empty()) {
    header.eps = 1e-3;
    header.lights = 1;
    glint::VectorMaterial m;
    m.name = "bench";
    m.shininess = 50;
    m.lobe = glint::Lobe::kBlinn;
    header.materials.push_back(m);
  } else {
    reader = std::make_unique<glint::VectorReader>(file);
    header = reader->header();
  }
  glint::SweepSettings settings;
  settings.jobs = jobs;
  const auto t_build = Clock::now();
  glint::SweepEngine engine(header, configs, settings);
  const double build_s = since(t_build);

  const auto t_stream = Clock::now();
  std::vector<glint::VectorRow> chunk(settings.chunk_rows);
  std::uint64_t state = glint::bench::kStreamSeed, produced = 0;
  for (;;) {
    std::size_t n = 0;
    if (reader) {
      while (n < chunk.size() && reader->next(chunk[n])) ++n;
    } else {
      for (; n < chunk.size() && produced < vectors; ++n) {
        state = glint::bench::lcg_step(state);
        chunk[n].t = glint::bench::stream_t(state, t_min);
        chunk[n].material = 0;
        chunk[n].line = ++produced;
      }
    }
    if (n == 0) break;
    engine.add(chunk.data(), n);
  }
  const double stream_s = since(t_stream);
  const auto t_rows = Clock::now();
  const auto rows = engine.results();
  const double rows_s = since(t_rows);

  std::uint64_t skipped = 0, vectors_seen = 0;
  for (const auto& r : rows) {
    skipped += r.value("skipped", std::uint64_t{0});
    vectors_seen += r.value("vectors", std::uint64_t{0});
  }
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double total = build_s + stream_s + rows_s;
  const double work = static_cast<double>(configs.size()) * static_cast<double>(engine.rows());
  std::printf("%zu configurations x %llu rows (%s), %d threads: %.2f s\n", configs.size(),
              static_cast<unsigned long long>(engine.rows()),
              file.empty() ? "generated" : file.c_str(), jobs, total);
  std::printf(
      "  build configurations %.2f s, stream %.2f s (engine: datapaths, statistics and timing "
      "%.2f s; reading the rest), report rows %.2f s\n",
      build_s, stream_s, engine.profile().evaluate_s, rows_s);
  std::printf("  %.1f M configuration-rows/s; skipped %.1f %%; peak RSS %.0f MB\n",
              work / total / 1e6, vectors_seen ? 100.0 * skipped / vectors_seen : 0.0,
              usage.ru_maxrss / 1024.0);
  return 0;
}
