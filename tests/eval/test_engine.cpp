// The evaluation engine (eval/engine.h) against the row-at-a-time path (LaneAccumulator::add and
// TimingEngine::next per row, what `glint eval --dump` and the clocked scoreboard run): the same
// statistics, digests and timing, bit for bit, for thread counts 1, 2, 3 and 7, uneven windows and
// runs, on every shipped trace and on a generated stream of several materials and lights.
#include <gtest/gtest.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <filesystem>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "eval/deferral.h"
#include "eval/engine.h"
#include "eval/evaluate.h"
#include "io/thread_pool.h"
#include "io/vectors.h"
#include "test_support.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"
#include "vector_rows.h"

namespace glint {
namespace {

// Units by their specs: one or two lanes let the shared pass defer small references (no lane
// computes them), which the eight of engine_specs() do not.
std::vector<UnitSpec> specs_of(const std::vector<std::string>& texts) {
  std::vector<UnitSpec> specs;
  for (const std::string& t : texts) specs.push_back(parse_unit_spec(t));
  return specs;
}

std::vector<UnitSpec> engine_specs() {
  std::vector<std::string> texts = unit_names();
  // No comparator, a narrow input, and an input too wide for the per-code memo.
  texts.insert(texts.end(),
               {"horner:skip=off", "lut:in=uq1.9,out=uq1.9", "hast:in=uq1.20,out=uq1.18"});
  return specs_of(texts);
}

// The generated streams' numbers: a 64-bit LCG's next state, its top 53 bits as a double in [0,
// 1).
double next_uniform(std::uint64_t& state) {
  state = state * 6364136223846793005ULL + 1442695040888963407ULL;
  return static_cast<double>(state >> 11) * 0x1.0p-53;
}

struct Lanes {
  Lanes(const SlotMap& slots, const std::vector<UnitSpec>& specs) {
    for (const UnitSpec& s : specs) units.push_back(make_unit(s, slots));
    acc.reserve(units.size());
    for (const auto& u : units) {
      acc.emplace_back(*u, slots, 8);
      timing.emplace_back(u->timing(), SinkReady{0.7, 3});
    }
  }
  std::string report() const {
    std::string out;
    for (std::size_t u = 0; u < acc.size(); ++u) {
      const TimingStats& t = timing[u].stats();
      out += acc[u].stats().to_json().dump() + " digest " + std::to_string(acc[u].digest()) +
             " cycles " + std::to_string(t.cycles) + " stalls " + std::to_string(t.stall_credit) +
             "/" + std::to_string(t.stall_unit) + " latency " + std::to_string(t.latency_sum) +
             "/" + std::to_string(t.latency_min) + "/" + std::to_string(t.latency_max) + " sink " +
             std::to_string(t.sink_wait) + "\n";
    }
    return out;
  }
  std::vector<std::unique_ptr<SpecularUnit>> units;
  std::vector<LaneAccumulator> acc;
  std::vector<TimingEngine> timing;
};

std::string row_by_row(const SlotMap& slots, const std::vector<VectorRow>& rows,
                       const std::vector<UnitSpec>& specs) {
  Lanes lanes(slots, specs);
  for (const VectorRow& row : rows) {
    const std::size_t slot = slots.slot(row);
    const RowReference ref = make_reference(slots, slot, row.t, 8);
    for (std::size_t u = 0; u < lanes.units.size(); ++u) {
      const SpecularUnit& unit = *lanes.units[u];
      const std::int64_t t_raw = quantize_input(row.t, unit.in_format());
      const bool skipped = unit.skip(slot, t_raw);
      lanes.acc[u].add(slot, ref, t_raw, skipped, skipped ? 0 : unit.eval(slot, t_raw));
      lanes.timing[u].next(skipped);
    }
  }
  return lanes.report();
}

// The stream through an engine, in calls of uneven sizes.
std::string engine_run(const SlotMap& slots, const std::vector<VectorRow>& rows,
                       const EngineOptions& options, const std::vector<UnitSpec>& specs) {
  Lanes lanes(slots, specs);
  std::vector<LaneAccumulator*> acc;
  std::vector<TimingEngine*> timing;
  for (std::size_t u = 0; u < lanes.acc.size(); ++u) {
    acc.push_back(&lanes.acc[u]);
    timing.push_back(&lanes.timing[u]);
  }
  EvalEngine engine(slots, acc, timing, options);
  std::size_t at = 0, size = 1, call = 0;
  BatchResults out;
  // Side work in every call (0 to 3 steps): each step taken once, on one thread at a time, all of
  // them before add() returns; it changes nothing in the lanes.
  std::atomic<int> inside{0};
  int steps = 0, overlapped = 0;
  while (at < rows.size()) {
    const std::size_t n = std::min(size, rows.size() - at);
    const int wanted = static_cast<int>(call % 4);
    // Calls 4, 8, ...: no results, no side work, the last merges left to the next call.
    const bool open = call++ % 4 == 0 && call > 1;
    int taken = 0;
    const EvalEngine::SideWork side = [&] {
      overlapped += inside.fetch_add(1) != 0;
      ++taken;
      inside.fetch_sub(1);
      return taken < wanted;
    };
    if (open) {
      engine.add_open(rows.data() + at, n);
    } else {
      engine.add(rows.data() + at, n, size % 2 ? &out : nullptr, wanted > 0 ? side : nullptr);
    }
    EXPECT_EQ(taken, wanted) << "call " << call;
    steps += taken;
    at += n;
    size = size * 5 + 3;
  }
  engine.finish();
  EXPECT_EQ(overlapped, 0);
  EXPECT_GT(steps, 0);
  return lanes.report();
}

void expect_engine_equals_rows(const VectorHeader& header, const std::vector<VectorRow>& rows,
                               const std::vector<UnitSpec>& specs = engine_specs()) {
  const SlotMap slots = make_slots(header);
  const std::string expected = row_by_row(slots, rows, specs);
  struct Case {
    int threads;
    std::size_t window, run;  // run 0: the engine's choice
  };
  // 2 and 3 threads with runs the engine's choice: the 8 lanes take whole windows, spans of them
  // in any order that keeps each lane's (EvalEngine::add_span).
  for (const Case& c :
       {Case{1, 65536, 0}, Case{2, 1000, 0}, Case{3, 4097, 333}, Case{7, 777, 1},
        Case{2, 50000, 4099}, Case{7, 65536, 0}, Case{3, 4097, 0}, Case{2, 65536, 0}}) {
    EngineOptions options;
    options.threads = c.threads;
    options.window_rows = c.window;
    options.run_rows = c.run;
    EXPECT_EQ(engine_run(slots, rows, options, specs), expected)
        << specs.size() << " lanes, " << c.threads << " threads, window " << c.window
        << ", runs of " << c.run;
  }
}

std::vector<std::string> shipped_traces() {
  std::vector<std::string> names;
  for (const auto& entry :
       std::filesystem::directory_iterator(std::string(GLINT_SOURCE_DIR) + "/traces"))
    if (entry.path().extension() == ".vec") names.push_back(entry.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

class EngineTrace : public ::testing::TestWithParam<std::string> {};

TEST_P(EngineTrace, EqualsRowByRow) {
  VectorHeader header;
  const std::vector<VectorRow> rows =
      test::read_rows(std::string(GLINT_SOURCE_DIR) + "/traces/" + GetParam() + ".vec", header);
  expect_engine_equals_rows(header, rows);
}

INSTANTIATE_TEST_SUITE_P(Shipped, EngineTrace, ::testing::ValuesIn(shipped_traces()),
                         [](const auto& info) { return info.param; });

TEST(Engine, EqualsRowByRowOnAGeneratedStream) {
  VectorHeader header;
  header.eps = 1e-3;
  header.lights = 3;
  header.light_intensity = {{1, 1, 1}, {1, 0.5, 0.25}, {0.002, 0.002, 0.002}};
  header.has_light = true;
  header.materials.push_back({"shiny", {1, 1, 1}, 50, Lobe::kBlinn, 0});
  header.materials.push_back({"gold", {1, 0.77, 0.34}, 8, Lobe::kPhong, 0});
  header.materials.push_back({"soft", {0.5, 0.5, 0.5}, 0, Lobe::kGaussian, 0.3});
  // First used at row 120001, in the middle of a window: the runs before it go through the lanes
  // at once, those from it on once its slots have begun.
  header.materials.push_back({"late", {0.8, 0.8, 0.8}, 20, Lobe::kBlinn, 0});
  std::vector<VectorRow> rows(150000);
  std::uint64_t state = 0x9E3779B97F4A7C15ULL;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    // t over [-1, 1.001], a few exact 0 and 1.
    const double u = next_uniform(state);
    rows[i].t = i % 97 == 0 ? 0.0 : i % 89 == 0 ? 1.0 : -1.0 + 2.001 * u;
    rows[i].material = static_cast<std::uint32_t>((state >> 7) % (i >= 120000 ? 4 : 3));
    rows[i].light = static_cast<std::int32_t>((state >> 17) % 3);
    rows[i].line = i + 1;
  }
  expect_engine_equals_rows(header, rows);
  expect_engine_equals_rows(header, rows, specs_of({"horner"}));
}

// With few lanes the shared pass leaves references to the lanes up to a bound that grows with
// their sums of squares (LaneAccumulator::deferred_exponent). One material, n = 50, t over [-1,
// 1]: the sum passes 2^-12 within the first few thousand rows, which allows 2^-33, and the
// stream has rows of reference just above each bound it reaches (t in (0.63, 0.67]): a bound
// larger than the sum allows leaves their squares out of it. A second stream has only rows of
// reference 2^-39 and 2^-41.5 in turn: the maxima settle at once, but the sum (of squares near
// 2^-78) does not allow to leave out the squares of the second kind.
TEST(Engine, DefersUpToWhatTheSumOfSquaresAllows) {
  VectorHeader header;
  header.eps = 1e-3;
  header.materials.push_back({"shiny", {1, 1, 1}, 50, Lobe::kBlinn, 0});
  std::vector<VectorRow> rows(150000), small(4000);
  std::uint64_t state = 0x6A09E667F3BCC909ULL;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].t = -1.0 + 2.0 * next_uniform(state);
    rows[i].line = i + 1;
  }
  for (std::size_t i = 0; i < small.size(); ++i) {
    small[i].t = std::exp2((i % 2 ? -41.5 : -39.0) / 50);
    small[i].line = i + 1;
  }
  for (const auto& units : std::vector<std::vector<std::string>>{
           {"horner"}, {"horner", "hast"}, {"lut:bits=4", "horner:degree=3"}}) {
    expect_engine_equals_rows(header, rows, specs_of(units));
    expect_engine_equals_rows(header, small, specs_of(units));
  }
  // The bound did grow: the test above is about it.
  const SlotMap slots = make_slots(header);
  Lanes lanes(slots, specs_of({"horner"}));
  EngineOptions options;
  options.threads = 2;
  EvalEngine engine(slots, {&lanes.acc[0]}, {}, options);
  engine.add(rows.data(), rows.size());
  EXPECT_GE(engine.deferred_exponent(), -33);
}

// A lane leaves out rows it skips with a reference below kDeferredBound only once every slot's
// weighted maximum is above the bound times the slot's weight: here a dim material settles the
// scalar maxima early (t = 0.8355: reference 1.26e-4 >= 2^-13, weighted 2.5e-7), while a material
// under a light of 1e7 has skipped rows of reference up to 4.4e-13 (t < 0.566), weighted up to
// 4.4e-6: leaving them out after the scalars settle would lose the weighted maximum.
TEST(Engine, LeavesRowsOutOnlyWhenEveryWeightIsSettled) {
  VectorHeader header;
  header.eps = 1e-3;
  header.lights = 2;
  header.light_intensity = {{1, 1, 1}, {1e7, 1e7, 1e7}};
  header.has_light = true;
  header.materials.push_back({"dim", {0.002, 0.002, 0.002}, 50, Lobe::kBlinn, 0});
  header.materials.push_back({"bright", {1, 1, 1}, 50, Lobe::kBlinn, 0});
  std::vector<VectorRow> rows(20000);
  std::uint64_t state = 0x2545F4914F6CDD1DULL;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double u = next_uniform(state);
    const bool dim = i % 16 < 4;
    rows[i].material = dim ? 0 : 1;
    rows[i].light = dim ? 0 : 1;
    rows[i].t = dim ? 0.8355 : 0.54 + 0.0259 * u;
    rows[i].line = i + 1;
  }
  expect_engine_equals_rows(header, rows);
}

// The deferral policy's pieces (eval/deferral.h) on values checked by hand.
// A sum S absorbs x^2 when x^2 is below half an ulp of S, 2^(ilogb(S) - 53): for S = 1, x =
// 2^-27 squares to 2^-54 (absorbed) and 2^-26 to 2^-52 (one ulp, not).
TEST(Deferral, ExponentAbsorbedBySumsOfSquares) {
  EXPECT_EQ(exponent_absorbed_by(0.0), std::numeric_limits<int>::min());
  EXPECT_EQ(exponent_absorbed_by(std::numeric_limits<double>::min() / 2),
            std::numeric_limits<int>::min());
  EXPECT_EQ(exponent_absorbed_by(1.0), -27);
  EXPECT_EQ(exponent_absorbed_by(1.999), -27);  // (0 - 54) / 2
  EXPECT_EQ(exponent_absorbed_by(2.0), -27);    // (1 - 54) / 2 = -26.5
  EXPECT_EQ(exponent_absorbed_by(4.0), -26);
  EXPECT_EQ(exponent_absorbed_by(0x1.0p-26), -40);
  // The bound is absorbed by every sum of its binade, and one more is not by the sum 2^E of even
  // E (where 2^(e+1) squares to a whole ulp).
  std::uint64_t state = 0x9E3779B97F4A7C15ULL;
  for (int i = 0; i < 2000; ++i) {
    const double sum = std::ldexp(1.0 + next_uniform(state), static_cast<int>(i % 120) - 80);
    const int e = exponent_absorbed_by(sum);
    const double x = std::ldexp(1.0, e);
    EXPECT_EQ(sum + x * x, sum) << sum;
    EXPECT_EQ(sum + x * x * next_uniform(state), sum) << sum;
  }
  for (int even = -80; even <= 40; even += 2) {
    const double sum = std::ldexp(1.0, even);
    const double x = std::ldexp(1.0, exponent_absorbed_by(sum) + 1);
    EXPECT_NE(sum + x * x, sum) << even;
  }
}

// allowed_deferral_exponent: the sum's exponent, capped below any display code, at least -40.
TEST(Deferral, AllowedExponentIsFlooredAndCapped) {
  const double eight_bits = 255;
  EXPECT_EQ(allowed_deferral_exponent(0.0, eight_bits), kDeferredExponent);
  EXPECT_EQ(allowed_deferral_exponent(0x1.0p-30, eight_bits), kDeferredExponent);  // -42
  EXPECT_EQ(allowed_deferral_exponent(1.0, eight_bits), -27);
  EXPECT_EQ(allowed_deferral_exponent(0x1.0p40, eight_bits), -10);  // -7 capped: ilogb(255) = 7
  EXPECT_EQ(allowed_deferral_exponent(0x1.0p40, 1023), -12);        // 10 bits: ilogb(1023) = 9
  for (int bits = 1; bits <= 16; ++bits) {
    const double display = std::ldexp(1.0, bits) - 1;
    const int cap = allowed_deferral_exponent(1e300, display);
    EXPECT_EQ(std::lround(std::ldexp(1.0, cap) * display), 0) << bits;
    // Not far below: two steps up, the reference's code is 1.
    EXPECT_EQ(std::lround(std::ldexp(1.0, cap + 2) * display), 1) << bits;
  }
}

// deferred_t: a power lobe at or below it is at most 2^e, and the t is within 2e-9 of
// 2^((e-1)/n); a Gaussian lobe has none.
TEST(Deferral, DeferredTBoundsTheLobe) {
  VectorHeader header;
  header.eps = 1e-3;
  for (const double n : {1.0, 2.5, 8.0, 50.0, 1000.0, 10000.0})
    header.materials.push_back(
        {"n" + std::to_string(header.materials.size()), {1, 1, 1}, n, Lobe::kBlinn, 0});
  header.materials.push_back({"gauss", {1, 1, 1}, 0, Lobe::kGaussian, 0.2});
  const SlotMap slots = make_slots(header);
  for (const int e : {kDeferredExponent, -33, -27, -10}) {
    const std::vector<double> cut = deferred_t(slots, e);
    ASSERT_EQ(cut.size(), slots.params.size());
    for (std::size_t s = 0; s < cut.size(); ++s) {
      if (slots.lobe[s] == Lobe::kGaussian) {
        EXPECT_EQ(cut[s], 0.0);
        continue;
      }
      const double n = slots.params[s].shininess;
      EXPECT_LE(reference_value(slots, s, cut[s]), std::ldexp(1.0, e)) << n << " " << e;
      EXPECT_NEAR(cut[s], std::exp2((e - 1.0) / n), 2e-9) << n << " " << e;
    }
  }
}

// SettledRows: at the least bound a run's own error of 2^-13 absorbs the bound's square; above
// it only the lane's sum before the window does.
TEST(Deferral, SettledRowsNeedEveryMaximumAboveTheBound) {
  const SettledRows least(kDeferredExponent, false);
  EXPECT_EQ(least.bound(), kDeferredBound);
  EXPECT_TRUE(least.scalars(0x1.0p-13, 1e-12));
  EXPECT_FALSE(least.scalars(0x1.0p-13 * 0.999, 1.0));  // the sum not yet absorbing
  EXPECT_FALSE(least.scalars(1.0, kDeferredBound));     // skip not above the bound (strict)
  EXPECT_TRUE(least.weighted(1e-12, 0.5));              // bound x c_y = 4.5e-13
  EXPECT_FALSE(least.weighted(4e-13, 0.5));
  const SettledRows higher(-30, false);
  EXPECT_FALSE(higher.scalars(1.0, 1.0));  // a run's error does not absorb 2^-60
  const SettledRows absorbed(-30, true);
  EXPECT_TRUE(absorbed.scalars(0x1.0p-29, 0x1.0p-29));
  EXPECT_FALSE(absorbed.scalars(0x1.0p-30, 1.0));
  EXPECT_FALSE(absorbed.weighted(0x1.0p-31, 0.5));
}

// Deferring never changes a result: the engine (which defers up to the bound its lanes' sums
// allow, here from 2^-40 up past 2^-27) against the row-at-a-time path (which never defers) on
// rows at each bound's deferred_t, one ulp above and below, among rows of large error that let
// the bound grow; with one lane and with two whose thresholds differ.
TEST(Deferral, NeverChangesAResult) {
  VectorHeader header;
  header.eps = 1e-3;
  header.materials.push_back({"shiny", {1, 1, 1}, 50, Lobe::kBlinn, 0});
  const SlotMap slots = make_slots(header);
  std::vector<VectorRow> rows(120000);
  std::uint64_t state = 0x3C6EF372FE94F82BULL;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const int e = kDeferredExponent + static_cast<int>(i / 7 % 31);
    const double cut = deferred_t(slots, e)[0];
    switch (i % 4) {
      case 0:
        rows[i].t = cut;
        break;
      case 1:
        rows[i].t = std::nextafter(cut, 2.0);
        break;
      case 2:
        rows[i].t = std::nextafter(cut, 0.0);
        break;
      default:
        rows[i].t = -1.0 + 2.0 * next_uniform(state);
    }
    rows[i].line = i + 1;
  }
  for (const auto& units :
       std::vector<std::vector<std::string>>{{"horner"}, {"lut:bits=4", "schlick"}})
    expect_engine_equals_rows(header, rows, specs_of(units));
  Lanes lanes(slots, specs_of({"lut:bits=4"}));
  EngineOptions options;
  options.window_rows = 4096;
  EvalEngine engine(slots, {&lanes.acc[0]}, {}, options);
  engine.add(rows.data(), rows.size());
  EXPECT_GE(engine.deferred_exponent(), -30);  // the test is about a bound that grew
}

// The engine's pool: every task once per run, over many short runs, and a task's exception
// rethrown by run() with the pool still usable.
TEST(ThreadPool, RunsEveryTaskOnceAndRethrows) {
  ThreadPool pool(3);
  std::vector<int> hits(257, 0);
  for (int round = 0; round < 200; ++round)
    pool.run(hits.size(), [&](std::size_t i) { hits[i] += 1; });
  for (const int h : hits) EXPECT_EQ(h, 200);
  EXPECT_THROW(pool.run(100,
                        [](std::size_t i) {
                          if (i == 37) throw std::runtime_error("task 37");
                        }),
               std::runtime_error);
  pool.run(hits.size(), [&](std::size_t i) { hits[i] += 1; });
  for (const int h : hits) EXPECT_EQ(h, 201);
}

// Side work that throws: add() rethrows it once the lanes have stopped, with the lanes' windows
// taken by whole windows on two threads.
TEST(Engine, SideWorkErrorReachesTheCaller) {
  VectorHeader header;
  header.eps = 1e-3;
  header.materials.push_back({"m", {1, 1, 1}, 8, Lobe::kPhong, 0});
  const SlotMap slots = make_slots(header);
  Lanes lanes(slots, engine_specs());
  std::vector<LaneAccumulator*> acc;
  for (auto& a : lanes.acc) acc.push_back(&a);
  EngineOptions options;
  options.threads = 2;
  options.window_rows = 1000;
  ASSERT_TRUE(EvalEngine::overlaps_side_work(acc.size(), options.threads));
  EvalEngine engine(slots, acc, {}, options);
  std::vector<VectorRow> rows(20000);
  int steps = 0;
  EXPECT_THROW(engine.add(rows.data(), rows.size(), nullptr,
                          [&]() -> bool {
                            if (++steps == 3) throw std::runtime_error("side step 3");
                            return true;
                          }),
               std::runtime_error);
  EXPECT_EQ(steps, 3);
}

// A sweep's shard may hold no configuration: the rows go through no lane.
TEST(Engine, NoLanes) {
  VectorHeader header;
  header.eps = 1e-3;
  header.materials.push_back({"m", {1, 1, 1}, 8, Lobe::kPhong, 0});
  const SlotMap slots = make_slots(header);
  EngineOptions options;
  options.threads = 2;
  EvalEngine engine(slots, {}, {}, options);
  std::vector<VectorRow> rows(10000);
  int steps = 0;
  engine.add(rows.data(), rows.size(), nullptr, [&] { return ++steps < 2; });
  EXPECT_EQ(steps, 2);  // side work still runs
}

}  // namespace
}  // namespace glint
