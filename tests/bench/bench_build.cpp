// Unit build speed: each unit at its defaults built for 65536 distinct materials (n log-uniform in
// [1, 1e4], c_y uniform in [0.01, 1], eps 1e-3, fixed seed), and lut:bits=16 for 4096 materials.
// Besides the time, a counting operator new reports each build's peak heap (`peak_MB`: the most
// bytes live at once during the build, above what was live before it) and what the built unit
// keeps (`kept_MB`); VmHWM is the process's peak RSS so far (monotone over the run, so it only
// says something about the first, or the largest, case).
// Run: ./build/tests/bench_build            (one iteration each: a build takes seconds)
//      ./build/tests/bench_build --benchmark_filter=pow
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <new>
#include <random>
#include <vector>

#include "reference/reference.h"
#include "units/catalogue.h"

// ---- Counting allocator: live and peak bytes of every operator new in the process. ----------
namespace {
std::atomic<std::size_t> g_live{0}, g_peak{0};

void* counted_alloc(std::size_t size) {
  // The size is kept in a header in front of the block so delete can subtract it.
  constexpr std::size_t kHeader = alignof(std::max_align_t);
  void* p = std::malloc(size + kHeader);
  if (p == nullptr) throw std::bad_alloc();
  std::memcpy(p, &size, sizeof size);
  const std::size_t live = g_live.fetch_add(size) + size;
  std::size_t peak = g_peak.load();
  while (live > peak && !g_peak.compare_exchange_weak(peak, live)) {
  }
  return static_cast<char*>(p) + kHeader;
}
void counted_free(void* q) {
  if (q == nullptr) return;
  constexpr std::size_t kHeader = alignof(std::max_align_t);
  void* p = static_cast<char*>(q) - kHeader;
  std::size_t size;
  std::memcpy(&size, p, sizeof size);
  g_live.fetch_sub(size);
  std::free(p);
}
}  // namespace

void* operator new(std::size_t size) {
  return counted_alloc(size);
}
void* operator new[](std::size_t size) {
  return counted_alloc(size);
}
void operator delete(void* p) noexcept {
  counted_free(p);
}
void operator delete[](void* p) noexcept {
  counted_free(p);
}
void operator delete(void* p, std::size_t) noexcept {
  counted_free(p);
}
void operator delete[](void* p, std::size_t) noexcept {
  counted_free(p);
}

namespace glint {
namespace {

// The process's peak resident set (VmHWM) in MB, or -1 where /proc is not there.
double vm_hwm_mb() {
  std::FILE* f = std::fopen("/proc/self/status", "r");
  if (f == nullptr) return -1;
  char line[256];
  double kb = -1;
  while (std::fgets(line, sizeof line, f) != nullptr) {
    if (std::strncmp(line, "VmHWM:", 6) == 0) kb = std::atof(line + 6);
  }
  std::fclose(f);
  return kb / 1024.0;
}

// Distinct materials as the brief fixes them; the same seed every run, so every build sees the
// same set.
std::vector<MaterialParams> materials(std::size_t count) {
  std::mt19937_64 rng(20240607);
  std::uniform_real_distribution<double> log_n(0.0, 4.0), cy(0.01, 1.0);
  constexpr double kEps = 1e-3;
  std::vector<MaterialParams> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    const double n = std::pow(10.0, log_n(rng)), c = cy(rng);
    const TauResult t = tau_power(n, kEps, c);
    MaterialParams m(n, t.tau, t.always_skip);
    m.level = kEps / c;
    out.push_back(m);
  }
  return out;
}

void build(benchmark::State& state, const char* spec, std::size_t count) {
  const std::vector<MaterialParams> slots = materials(count);
  const UnitSpec parsed = parse_unit_spec(spec);
  double peak_mb = 0, kept_mb = 0;
  for (auto _ : state) {
    const std::size_t before = g_live.load();
    g_peak.store(before);
    auto unit = make_unit(parsed, slots);
    benchmark::DoNotOptimize(unit.get());
    peak_mb = static_cast<double>(g_peak.load() - before) / (1 << 20);
    kept_mb = static_cast<double>(g_live.load() - before) / (1 << 20);
  }
  state.counters["materials"] = static_cast<double>(count);
  state.counters["peak_MB"] = peak_mb;
  state.counters["kept_MB"] = kept_mb;
  state.counters["VmHWM_MB"] = vm_hwm_mb();
}

constexpr std::size_t kMaterials = 65536;

BENCHMARK_CAPTURE(build, pow, "pow", kMaterials)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(build, schlick, "schlick", kMaterials)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(build, hast, "hast", kMaterials)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(build, horner, "horner", kMaterials)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(build, lut, "lut", kMaterials)->Unit(benchmark::kSecond)->Iterations(1);
BENCHMARK_CAPTURE(build, lut_bits16, "lut:bits=16", 4096)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
}  // namespace glint
