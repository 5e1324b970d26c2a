// Vector file throughput: parsing (from a file and from memory) and writing.
//
//   build/tests/bench_vectors --benchmark_filter=Vector
//
// The input is a ~64 MiB temporary file of realistic rows "t material light x y" with 6
// materials, 4 lights and 1920x1080 pixel coordinates; t is written either in shortest round-trip
// form (up to 17 significant digits, as VectorWriter writes computed values) or with 6 decimals
// (as hand-made traces often are). bytes_per_second is the parsing rate per core (CPU time, so
// the figure holds on a shared machine; the file is in the page cache after generation); rows/s
// is reported too. BM_VectorWrite uses wall time, since it includes the fsync of commit().
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "io/vectors.h"

namespace {

namespace fs = std::filesystem;
constexpr std::uint64_t kTargetBytes = 64ull << 20;

glint::VectorHeader bench_header() {
  glint::VectorHeader h;
  h.eps = 1e-3;
  h.lights = 4;
  h.has_light = true;
  h.has_xy = true;
  const char* names[] = {"gold", "copper", "silver", "red_plastic", "blue_glaze", "jade"};
  double n = 4;
  for (const char* name : names) {
    h.materials.push_back({name, {0.9, 0.7, 0.4}, n, glint::VectorLobe::kBlinn, 0});
    n *= 2.5;
  }
  return h;
}

struct BenchFile {
  std::string path;
  std::uint64_t bytes = 0;
  std::uint64_t rows = 0;
};

// Temporary input files, generated once per process and removed at exit.
class BenchFiles {
 public:
  ~BenchFiles() {
    for (const auto& [digits, f] : files_) std::remove(f.path.c_str());
  }
  const BenchFile& get(int digits) {
    auto it = files_.find(digits);
    if (it != files_.end()) return it->second;
    BenchFile f;
    f.path = (fs::temp_directory_path() / ("glint_bench_vectors_" + std::to_string(::getpid()) +
                                           "_" + std::to_string(digits) + ".vec"))
                 .string();
    const auto h = bench_header();
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> t_dist(-1, 1);
    if (digits == 0) {
      glint::VectorWriter w(f.path, h);
      // ~44 bytes per row in this form.
      const std::uint64_t rows = kTargetBytes / 44;
      for (std::uint64_t i = 0; i < rows; ++i) {
        w.write({t_dist(rng), static_cast<std::uint32_t>(rng() % 6),
                 static_cast<std::int32_t>(rng() % 4), static_cast<std::int32_t>(rng() % 1920),
                 static_cast<std::int32_t>(rng() % 1080), 0});
      }
      w.commit();
      f.rows = rows;
    } else {
      // Fixed decimals: write the header with VectorWriter, rows by hand.
      std::ostringstream head;
      glint::VectorWriter hw(head, h);
      hw.commit();
      std::ofstream out(f.path, std::ios::binary);
      out << head.str();
      std::uint64_t bytes = head.str().size();
      char line[128];
      while (bytes < kTargetBytes) {
        const int len =
            std::snprintf(line, sizeof line, "%.*f %s %d %d %d\n", digits, t_dist(rng),
                          h.materials[rng() % 6].name.c_str(), static_cast<int>(rng() % 4),
                          static_cast<int>(rng() % 1920), static_cast<int>(rng() % 1080));
        out.write(line, len);
        bytes += static_cast<std::uint64_t>(len);
        ++f.rows;
      }
    }
    f.bytes = fs::file_size(f.path);
    return files_.emplace(digits, f).first->second;
  }

 private:
  std::map<int, BenchFile> files_;
};

BenchFiles& files() {
  static BenchFiles instance;
  return instance;
}

// Arg: 0 = shortest round-trip t (VectorWriter output), N = t with N decimals.
void BM_VectorReadFile(benchmark::State& state) {
  const BenchFile& f = files().get(static_cast<int>(state.range(0)));
  double checksum = 0;
  for (auto _ : state) {
    glint::VectorReader reader(f.path);
    glint::VectorRow row;
    std::uint64_t n = 0;
    while (reader.next(row)) {
      checksum += row.t + row.material + row.x;
      ++n;
    }
    if (n != f.rows) state.SkipWithError("row count mismatch");
  }
  benchmark::DoNotOptimize(checksum);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * f.bytes));
  state.counters["rows/s"] = benchmark::Counter(static_cast<double>(state.iterations() * f.rows),
                                                benchmark::Counter::kIsRate);
  state.counters["MiB"] = static_cast<double>(f.bytes) / (1 << 20);
}
BENCHMARK(BM_VectorReadFile)->Arg(0)->Arg(6)->Unit(benchmark::kMillisecond);

// The same parse from an in-memory stream (no file system): the parser's own speed.
void BM_VectorReadMemory(benchmark::State& state) {
  const BenchFile& f = files().get(static_cast<int>(state.range(0)));
  std::string text;
  {
    std::ifstream in(f.path, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    text = ss.str();
  }
  std::istringstream in(std::move(text));
  double checksum = 0;
  for (auto _ : state) {
    in.clear();
    in.seekg(0);
    glint::VectorReader reader(in, "memory");
    glint::VectorRow row;
    while (reader.next(row)) checksum += row.t;
  }
  benchmark::DoNotOptimize(checksum);
  state.SetBytesProcessed(static_cast<std::int64_t>(state.iterations() * f.bytes));
  state.counters["rows/s"] = benchmark::Counter(static_cast<double>(state.iterations() * f.rows),
                                                benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VectorReadMemory)->Arg(0)->Arg(6)->Unit(benchmark::kMillisecond);

// Writing 1M rows through VectorWriter (shortest round-trip doubles) to an atomic file.
void BM_VectorWrite(benchmark::State& state) {
  const auto h = bench_header();
  const std::string path =
      (fs::temp_directory_path() / ("glint_bench_vectors_w_" + std::to_string(::getpid()) + ".vec"))
          .string();
  constexpr std::uint64_t kRows = 1000000;
  std::uint64_t bytes = 0;
  for (auto _ : state) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> t_dist(-1, 1);
    glint::VectorWriter w(path, h);
    for (std::uint64_t i = 0; i < kRows; ++i) {
      w.write({t_dist(rng), static_cast<std::uint32_t>(i % 6), static_cast<std::int32_t>(i % 4),
               static_cast<std::int32_t>(i % 1920), static_cast<std::int32_t>(i % 1080), 0});
    }
    w.commit();
    bytes += fs::file_size(path);
  }
  std::remove(path.c_str());
  state.SetBytesProcessed(static_cast<std::int64_t>(bytes));
  state.counters["rows/s"] = benchmark::Counter(static_cast<double>(state.iterations() * kRows),
                                                benchmark::Counter::kIsRate);
}
BENCHMARK(BM_VectorWrite)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace
