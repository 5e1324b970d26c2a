// Build time of the horner unit at its defaults for many distinct materials (issue 7: building
// units for 65536 materials must take under 5 s). Every slot gets its own fit (Remez, monotone
// check, quantization, the datapath's monotonicity proof), so this measures the fits.
// Run: ./build/tests/bench_horner_build (add --benchmark_filter=/65536 for the figure of the issue)
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "reference/reference.h"
#include "units/catalogue.h"

namespace glint {
namespace {

// n log-uniform in [1, 1e4], c_y uniform in [0.01, 1], eps 1e-3, one light: slots as
// evaluate.cpp's make_slots builds them (level = eps_K / c_y).
std::vector<MaterialParams> materials(std::size_t count) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> log_n(0.0, std::log(1e4));
  std::uniform_real_distribution<double> cy(0.01, 1.0);
  std::vector<MaterialParams> out;
  out.reserve(count);
  for (std::size_t i = 0; i < count; ++i) {
    MaterialParams m;
    m.shininess = std::exp(log_n(rng));
    const double c = cy(rng);
    const TauResult t = tau_power(m.shininess, 1e-3, c);
    m.always_skip = t.always_skip;
    m.tau = t.never_skip ? -1.0 : t.tau;
    m.level = t.eps / c;
    out.push_back(m);
  }
  return out;
}

void BM_HornerBuild(benchmark::State& state, const char* spec) {
  const auto slots = materials(static_cast<std::size_t>(state.range(0)));
  const UnitSpec parsed = parse_unit_spec(spec);
  for (auto _ : state) {
    auto unit = make_unit(parsed, slots);
    benchmark::DoNotOptimize(unit.get());
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * state.range(0)));
}

BENCHMARK_CAPTURE(BM_HornerBuild, defaults, "horner")
    ->Arg(1024)
    ->Arg(65536)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1);

}  // namespace
}  // namespace glint
