// glint::Fixed vs SystemC's sc_fixed (not sc_fixed_fast) on a multiply-add chain:
//   acc = quantize(acc * x[i] + c)   over 4096 inputs, 16-bit formats (sq2.14), SC_RND / SC_SAT
// with one rounding per step (the exact product plus c, then rounded and saturated), as
// sc_fixed<16, 2, SC_RND, SC_SAT> computes `acc = acc * x[i] + c`. Each step depends on the one
// before, so this measures latency. The *Map variants compute the same kind of step on
// independent elements, y[i] = quantize(x[i] * w[i] + c), which measures throughput (e.g. one
// value per pixel). Every variant computes the same bits as sc_fixed; the setup checks that
// before timing. Reported: items/s = steps (elements) per second.
//
// Run: ./build/tests/bench_fixed_point --benchmark_min_time=0.2
#define SC_INCLUDE_FX
#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <systemc>
#include <vector>

#include "fixed/fixed_point.h"

namespace {

using glint::Fixed;
using glint::Overflow;
using glint::QFormat;
using glint::Quant;

constexpr int kN = 4096;
constexpr QFormat kFmt = glint::sq(2, 14);      // acc, x and c
constexpr QFormat kProduct = glint::sq(4, 28);  // exact acc * x
constexpr Quant kQ = Quant::kRnd;
constexpr Overflow kO = Overflow::kSat;
constexpr int kShift = kProduct.frac_bits - kFmt.frac_bits;  // product -> kFmt
using ScAcc = sc_dt::sc_fixed<16, 2, sc_dt::SC_RND, sc_dt::SC_SAT>;

struct Inputs {
  std::vector<std::int64_t> x;  // raws in kFmt, |x| <= 1.75: ~1.3% of the chain steps saturate
  std::vector<std::int64_t> w;  // raws in kFmt, for the map variants
  std::int64_t c = 0;
};

const Inputs& inputs() {
  static const Inputs in = [] {
    Inputs r;
    std::mt19937_64 g(42);
    std::uniform_int_distribution<std::int64_t> d(-28672, 28672);
    for (int i = 0; i < kN; ++i) r.x.push_back(d(g));
    std::uniform_int_distribution<std::int64_t> dw(-32768, 32767);
    for (int i = 0; i < kN; ++i) r.w.push_back(dw(g));
    r.c = 3277;  // ~0.2
    return r;
  }();
  return in;
}

// ---- The chain, four ways ------------------------------------------------------------------

std::int64_t chain_sc_fixed(const std::vector<ScAcc>& x, const ScAcc& c) {
  ScAcc acc = 0;
  for (const ScAcc& xi : x) acc = acc * xi + c;
  return static_cast<std::int64_t>(std::ldexp(acc.to_double(), 14));  // exact: 16 bits
}

// Value API, exact ops then one quantize.
std::int64_t chain_fixed(const std::vector<Fixed>& x, const Fixed& c) {
  Fixed acc = Fixed::from_raw(0, kFmt);
  for (const Fixed& xi : x) acc = glint::quantize(glint::add(glint::mul(acc, xi), c), kFmt, kQ, kO);
  return acc.raw();
}

// Value API with the fused product (exact here: kProduct holds every product).
std::int64_t chain_fixed_mul_quantize(const std::vector<Fixed>& x, const Fixed& c) {
  Fixed acc = Fixed::from_raw(0, kFmt);
  for (const Fixed& xi : x) {
    const Fixed p = glint::mul_quantize(acc, xi, kProduct, Quant::kTrn, Overflow::kWrap);
    acc = glint::quantize(glint::add(p, c), kFmt, kQ, kO);
  }
  return acc.raw();
}

// Raw kernels on int64: round_shift + fit_overflow.
std::int64_t chain_raw(const std::vector<std::int64_t>& x, std::int64_t c) {
  std::int64_t acc = 0;
  const std::int64_t c_aligned = c * (std::int64_t{1} << kShift);
  for (std::int64_t xi : x) {
    acc = glint::fit_overflow(glint::round_shift(acc * xi + c_aligned, kShift, kQ), kFmt, kO);
  }
  return acc;
}

// Raw kernels on int64: quantize_raw.
std::int64_t chain_quantize_raw(const std::vector<std::int64_t>& x, std::int64_t c) {
  std::int64_t acc = 0;
  const std::int64_t c_aligned = c * (std::int64_t{1} << kShift);
  for (std::int64_t xi : x) {
    acc = glint::quantize_raw(acc * xi + c_aligned, kProduct.frac_bits, kFmt, kQ, kO);
  }
  return acc;
}

// ---- The map (independent elements), three ways ----------------------------------------------

void map_sc_fixed(const std::vector<ScAcc>& x, const std::vector<ScAcc>& w, const ScAcc& c,
                  std::vector<ScAcc>& y) {
  for (std::size_t i = 0; i < x.size(); ++i) y[i] = x[i] * w[i] + c;
}

void map_fixed(const std::vector<Fixed>& x, const std::vector<Fixed>& w, const Fixed& c,
               std::vector<Fixed>& y) {
  for (std::size_t i = 0; i < x.size(); ++i) {
    y[i] = glint::quantize(glint::add(glint::mul(x[i], w[i]), c), kFmt, kQ, kO);
  }
}

void map_raw(const std::vector<std::int64_t>& x, const std::vector<std::int64_t>& w, std::int64_t c,
             std::vector<std::int64_t>& y) {
  const std::int64_t c_aligned = c * (std::int64_t{1} << kShift);
  for (std::size_t i = 0; i < x.size(); ++i) {
    y[i] = glint::fit_overflow(glint::round_shift(x[i] * w[i] + c_aligned, kShift, kQ), kFmt, kO);
  }
}

struct Prepared {
  std::vector<ScAcc> sc_x, sc_w;
  ScAcc sc_c;
  std::vector<Fixed> fx_x, fx_w;
  Fixed fx_c;
};

[[noreturn]] void disagree(const char* what, std::int64_t got, std::int64_t want) {
  std::fprintf(stderr, "bench_fixed_point: %s disagrees with sc_fixed (%lld vs %lld)\n", what,
               static_cast<long long>(got), static_cast<long long>(want));
  std::abort();
}

const Prepared& prepared() {
  static const Prepared p = [] {
    const Inputs& in = inputs();
    Prepared r;
    for (std::int64_t v : in.x) {
      r.sc_x.emplace_back(std::ldexp(static_cast<double>(v), -14));
      r.fx_x.push_back(Fixed::from_raw(v, kFmt));
    }
    for (std::int64_t v : in.w) {
      r.sc_w.emplace_back(std::ldexp(static_cast<double>(v), -14));
      r.fx_w.push_back(Fixed::from_raw(v, kFmt));
    }
    r.sc_c = std::ldexp(static_cast<double>(in.c), -14);
    r.fx_c = Fixed::from_raw(in.c, kFmt);
    // All variants must agree bit for bit before anything is timed.
    const std::int64_t want = chain_sc_fixed(r.sc_x, r.sc_c);
    const std::int64_t got[] = {chain_fixed(r.fx_x, r.fx_c),
                                chain_fixed_mul_quantize(r.fx_x, r.fx_c), chain_raw(in.x, in.c),
                                chain_quantize_raw(in.x, in.c)};
    for (std::int64_t g : got) {
      if (g != want) disagree("a chain variant", g, want);
    }
    std::vector<ScAcc> sc_y(kN);
    std::vector<Fixed> fx_y(kN);
    std::vector<std::int64_t> raw_y(kN);
    map_sc_fixed(r.sc_x, r.sc_w, r.sc_c, sc_y);
    map_fixed(r.fx_x, r.fx_w, r.fx_c, fx_y);
    map_raw(in.x, in.w, in.c, raw_y);
    for (int i = 0; i < kN; ++i) {
      const auto want_i = static_cast<std::int64_t>(std::ldexp(sc_y[i].to_double(), 14));
      if (fx_y[i].raw() != want_i) disagree("map_fixed", fx_y[i].raw(), want_i);
      if (raw_y[i] != want_i) disagree("map_raw", raw_y[i], want_i);
    }
    return r;
  }();
  return p;
}

void BM_ScFixed_MulAddChain(benchmark::State& state) {
  const Prepared& p = prepared();
  for (auto _ : state) benchmark::DoNotOptimize(chain_sc_fixed(p.sc_x, p.sc_c));
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_ScFixed_MulAddChain);

void BM_Fixed_MulAddQuantize(benchmark::State& state) {
  const Prepared& p = prepared();
  for (auto _ : state) benchmark::DoNotOptimize(chain_fixed(p.fx_x, p.fx_c));
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_Fixed_MulAddQuantize);

void BM_Fixed_MulQuantizeAddQuantize(benchmark::State& state) {
  const Prepared& p = prepared();
  for (auto _ : state) benchmark::DoNotOptimize(chain_fixed_mul_quantize(p.fx_x, p.fx_c));
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_Fixed_MulQuantizeAddQuantize);

void BM_Raw_RoundShiftFitOverflow(benchmark::State& state) {
  const Inputs& in = inputs();
  prepared();
  for (auto _ : state) benchmark::DoNotOptimize(chain_raw(in.x, in.c));
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_Raw_RoundShiftFitOverflow);

void BM_Raw_QuantizeRaw(benchmark::State& state) {
  const Inputs& in = inputs();
  prepared();
  for (auto _ : state) benchmark::DoNotOptimize(chain_quantize_raw(in.x, in.c));
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_Raw_QuantizeRaw);

void BM_ScFixed_MulAddMap(benchmark::State& state) {
  const Prepared& p = prepared();
  std::vector<ScAcc> y(kN);
  for (auto _ : state) {
    map_sc_fixed(p.sc_x, p.sc_w, p.sc_c, y);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_ScFixed_MulAddMap);

void BM_Fixed_MulAddMap(benchmark::State& state) {
  const Prepared& p = prepared();
  std::vector<Fixed> y(kN);
  for (auto _ : state) {
    map_fixed(p.fx_x, p.fx_w, p.fx_c, y);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_Fixed_MulAddMap);

void BM_Raw_MulAddMap(benchmark::State& state) {
  const Inputs& in = inputs();
  prepared();
  std::vector<std::int64_t> y(kN);
  for (auto _ : state) {
    map_raw(in.x, in.w, in.c, y);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kN);
}
BENCHMARK(BM_Raw_MulAddMap);

}  // namespace
