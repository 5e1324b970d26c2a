// Untimed datapath throughput: one unit, one material, a batch of 16-bit inputs spread over
// [0, 1], comparator in front (the eval_batch path that `glint eval` and sweeps use), and the
// datapath classes called directly (the inlined path a SystemC fast mode uses).
// Run: ./build/tests/bench_datapath --benchmark_min_time=0.5
#include <benchmark/benchmark.h>

#include <nlohmann/json.hpp>
#include <random>
#include <vector>

#include "reference/reference.h"
#include "units/catalogue.h"
#include "units/hast/datapath.h"
#include "units/horner/datapath.h"
#include "units/lut/datapath.h"
#include "units/pow/datapath.h"
#include "units/schlick/datapath.h"

namespace glint {
namespace {

constexpr std::size_t kBatch = 4096;

MaterialParams material50() {
  const TauResult t = tau_power(50, 1e-3, 1.0);
  return MaterialParams{50, t.tau, t.always_skip};
}

std::vector<std::int64_t> inputs(bool above_tau) {
  // above_tau: every input reaches the datapath (no skipping); otherwise uniform over [0, 1].
  std::mt19937_64 rng(42);
  const std::int64_t lo = above_tau ? 29000 : 0;
  std::uniform_int_distribution<std::int64_t> d(lo, 32768);
  std::vector<std::int64_t> v(kBatch);
  for (auto& x : v) x = d(rng);
  return v;
}

template <class Unit>
void run_direct(benchmark::State& state, const Unit& u) {
  const auto in = inputs(true);
  std::vector<std::int64_t> out(kBatch);
  for (auto _ : state) {
    for (std::size_t i = 0; i < kBatch; ++i) out[i] = u.eval(in[i]);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

void BM_SchlickDirect(benchmark::State& s) {
  run_direct(s, SchlickUnit({}, material50()));
}
void BM_HastDirect(benchmark::State& s) {
  run_direct(s, HastUnit({}, material50()));
}
void BM_PowDirect(benchmark::State& s) {
  run_direct(s, PowUnit({}, material50()));
}
void BM_LutDirect(benchmark::State& s) {
  run_direct(s, LutUnit({}, material50()));
}
void BM_HornerP4Direct(benchmark::State& s) {
  // Degree 4 on [tau, 1], coefficients of a constrained minimax fit (as the horner unit builds).
  const auto unit = make_unit(parse_unit_spec("horner:degree=4"), {material50()});
  const nlohmann::json c = unit->describe()["slots"][0]["coefficients"];
  HornerCoefficients hc{c.get<std::vector<double>>(), true, true, true};
  run_direct(s, HornerUnit({}, material50(), hc));
}

void run_batch(benchmark::State& state, const char* spec, bool above_tau) {
  const auto u = make_unit(parse_unit_spec(spec), {material50()});
  const auto in = inputs(above_tau);
  std::vector<std::int64_t> out(kBatch);
  std::vector<std::uint8_t> skipped(kBatch);
  for (auto _ : state) {
    u->eval_batch(0, in.data(), out.data(), skipped.data(), kBatch);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBatch));
}

BENCHMARK(BM_SchlickDirect);
BENCHMARK(BM_HastDirect);
BENCHMARK(BM_HornerP4Direct);
BENCHMARK(BM_PowDirect);
BENCHMARK(BM_LutDirect);
BENCHMARK_CAPTURE(run_batch, schlick_no_skip, "schlick", true);
BENCHMARK_CAPTURE(run_batch, hast_no_skip, "hast", true);
BENCHMARK_CAPTURE(run_batch, horner_p4_no_skip, "horner:degree=4", true);
BENCHMARK_CAPTURE(run_batch, pow_no_skip, "pow", true);
BENCHMARK_CAPTURE(run_batch, lut_no_skip, "lut", true);
BENCHMARK_CAPTURE(run_batch, schlick_uniform_t, "schlick", false);

}  // namespace
}  // namespace glint
