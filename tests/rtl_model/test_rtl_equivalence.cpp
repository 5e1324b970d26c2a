// The clocked SystemC lane against the datapath and TimingEngine: for every shipped trace, random
// in-memory streams and random sink backpressure, every result's value and skip flag equal
// SpecularUnit::eval_with_skip / skip, every ResultTiming equals TimingEngine's for the same skip
// sequence, and the per-lane TimingStats are identical. Each TEST elaborates SystemC once (ctest
// runs every test case in its own process).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "io/vectors.h"
#include "rtl_model/clocked_sim.h"
#include "timing/timing.h"
#include "timing_support.h"
#include "units/catalogue.h"
#include "units/common.h"

namespace glint {
namespace {

const std::string kTraces = std::string(GLINT_SOURCE_DIR) + "/traces/";

// Every unit kind, both dividers, and small merge buffers (credit stalls).
const std::vector<std::string> kSpecs = {
    "pow",
    "schlick:divider=pipelined",
    "schlick:divider=iterative",
    "hast",
    "horner",
    "lut",
    "hast:d=3,buffer=2",
    "schlick:divider=iterative,buffer=2",
    "lut:buffer=1",
    "horner:degree=2,buffer=3",
};

struct Observed {
  std::uint64_t line;
  std::int64_t t_raw;
  bool skipped;
  std::int64_t out_raw;
  ResultTiming timing;
};

// Runs the clocked model over `rows` (streamed by `open`) and checks it row by row against the
// datapath and a TimingEngine fed the same skip sequence.
void check_equivalence(const SlotMap& slots, const std::vector<VectorRow>& rows,
                       const std::function<std::unique_ptr<RowStream>()>& open,
                       const std::vector<std::string>& specs, const ClockedOptions& options) {
  std::vector<std::unique_ptr<SpecularUnit>> owned;
  std::vector<const SpecularUnit*> units;
  for (const std::string& s : specs) {
    owned.push_back(make_unit(parse_unit_spec(s), slots));
    units.push_back(owned.back().get());
  }
  std::vector<std::vector<Observed>> seen(units.size());
  ClockedRunInfo info;
  const std::vector<TimingStats> stats = run_clocked(
      units, slots, open, options,
      [&](const LaneOutput& o) {
        seen[o.lane].push_back({o.row.line, o.t_raw, o.skipped, o.out_raw, o.timing});
      },
      &info);
  ASSERT_EQ(stats.size(), units.size());
  for (std::size_t u = 0; u < units.size(); ++u) {
    SCOPED_TRACE("unit " + specs[u]);
    const SpecularUnit& unit = *units[u];
    EXPECT_EQ(info.mismatches[u], 0u);
    EXPECT_LE(info.max_occupancy[u], static_cast<std::size_t>(unit.timing().buffer_depth));
    ASSERT_EQ(seen[u].size(), rows.size());
    TimingEngine engine(unit.timing(), options.sink);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < rows.size() && bad < 5; ++i) {
      const std::size_t slot = slots.slot(rows[i]);
      const std::int64_t t_raw = quantize_input(rows[i].t, unit.in_format());
      const bool skipped = unit.skip(slot, t_raw);
      const ResultTiming want = engine.next(skipped);
      const Observed& got = seen[u][i];
      const bool ok = got.line == rows[i].line && got.t_raw == t_raw && got.skipped == skipped &&
                      got.out_raw == unit.eval_with_skip(slot, t_raw) &&
                      got.timing.issue == want.issue && got.timing.done == want.done &&
                      got.timing.retire == want.retire;
      if (!ok) {
        ++bad;
        ADD_FAILURE() << "row " << i << ": clocked (t " << got.t_raw << ", skipped " << got.skipped
                      << ", out " << got.out_raw << ", a/d/r " << got.timing.issue << "/"
                      << got.timing.done << "/" << got.timing.retire << ") vs expected (t " << t_raw
                      << ", skipped " << skipped << ", out " << unit.eval_with_skip(slot, t_raw)
                      << ", a/d/r " << want.issue << "/" << want.done << "/" << want.retire << ")";
      }
    }
    EXPECT_EQ(stats[u], engine.stats()) << "clocked, then the engine";
  }
}

struct Trace {
  VectorHeader header;
  std::vector<VectorRow> rows;
};

Trace read_trace(const std::string& path) {
  VectorReader reader(path);
  Trace t{reader.header(), {}};
  VectorRow row;
  while (reader.next(row)) t.rows.push_back(row);
  return t;
}

// Shipped traces, streamed from the file by every lane (VectorReaderStream), with a free-running
// sink and with backpressure.
struct TraceCase {
  const char* file;
  double ready;
};

void PrintTo(const TraceCase& c, std::ostream* os) {
  *os << c.file << " ready " << c.ready;
}

class RtlEquivalenceTrace : public ::testing::TestWithParam<TraceCase> {};

TEST_P(RtlEquivalenceTrace, MatchesDatapathAndTimingEngine) {
  const std::string path = kTraces + GetParam().file;
  const Trace trace = read_trace(path);
  ASSERT_FALSE(trace.rows.empty());
  const SlotMap slots = make_slots(trace.header);
  ClockedOptions options;
  options.sink = SinkReady{GetParam().ready, 0x5eed};
  check_equivalence(
      slots, trace.rows, [&] { return std::make_unique<VectorReaderStream>(path); }, kSpecs,
      options);
}

INSTANTIATE_TEST_SUITE_P(
    Traces, RtlEquivalenceTrace,
    ::testing::Values(TraceCase{"phong_basic.vec", 1.0}, TraceCase{"phong_basic.vec", 0.6},
                      TraceCase{"blinn_colored.vec", 1.0}, TraceCase{"blinn_colored.vec", 0.45},
                      TraceCase{"gaussian.vec", 1.0}, TraceCase{"gaussian.vec", 0.8},
                      TraceCase{"hard_cases.vec", 1.0}, TraceCase{"hard_cases.vec", 0.3},
                      TraceCase{"multi_light.vec", 1.0}, TraceCase{"multi_light.vec", 0.7},
                      TraceCase{"pixels.vec", 1.0}, TraceCase{"pixels.vec", 0.9}),
    [](const ::testing::TestParamInfo<TraceCase>& info) {
      std::string name = info.param.file;
      name = name.substr(0, name.find('.'));
      return name + "_ready" + std::to_string(static_cast<int>(info.param.ready * 100));
    });

// Random in-memory streams: materials of every lobe, several (coloured) lights, t over the whole
// input range with clusters near tau and 1, random sink backpressure in [0.3, 0.9].
struct RandomStream {
  VectorHeader header;
  std::vector<VectorRow> rows;
};

RandomStream random_stream(std::uint64_t seed, std::size_t n, bool coloured_lights) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> uni(0.0, 1.0);
  RandomStream s;
  s.header.eps = 1e-3;
  s.header.lights = coloured_lights ? 3 : 1;
  s.header.has_light = coloured_lights;
  for (int l = 0; l < s.header.lights; ++l)
    s.header.light_intensity.push_back(
        coloured_lights ? std::array<double, 3>{1.0, 0.5 + 0.5 * uni(rng), 0.25 + uni(rng)}
                        : std::array<double, 3>{1, 1, 1});
  const double shininess[] = {2, 8, 40, 128, 700};
  for (int m = 0; m < 5; ++m) {
    VectorMaterial mat;
    mat.name = "m" + std::to_string(m);
    mat.specular = {0.2 + 0.8 * uni(rng), 0.2 + 0.8 * uni(rng), 0.2 + 0.8 * uni(rng)};
    mat.lobe = m == 4 ? Lobe::kGaussian : (m % 2 ? Lobe::kBlinn : Lobe::kPhong);
    if (mat.lobe == Lobe::kGaussian) {
      mat.roughness = 0.3;
    } else {
      mat.shininess = shininess[m];
    }
    s.header.materials.push_back(mat);
  }
  validate(s.header);
  for (std::size_t i = 0; i < n; ++i) {
    VectorRow row;
    const double r = uni(rng);
    row.t = r < 0.2 ? -uni(rng) : (r < 0.6 ? 0.8 + 0.2 * uni(rng) : (r < 0.95 ? uni(rng) : 1.0));
    row.material = static_cast<std::uint32_t>(rng() % s.header.materials.size());
    row.light = static_cast<std::int32_t>(rng() % static_cast<std::uint64_t>(s.header.lights));
    row.line = i + 1;
    s.rows.push_back(row);
  }
  return s;
}

class RtlEquivalenceRandom : public ::testing::TestWithParam<std::uint64_t> {};

TEST_P(RtlEquivalenceRandom, MatchesDatapathAndTimingEngine) {
  const std::uint64_t seed = GetParam();
  const bool coloured = seed % 2 == 1;
  const RandomStream s = random_stream(seed, 2000, coloured);
  const SlotMap slots = make_slots(s.header);
  std::mt19937_64 rng(seed * 7919);
  ClockedOptions options;
  options.sink = SinkReady{0.3 + 0.6 * std::uniform_real_distribution<double>(0, 1)(rng), seed};
  SCOPED_TRACE("sink ready probability " + std::to_string(options.sink.probability));
  check_equivalence(
      slots, s.rows, [&] { return std::make_unique<MemoryRowStream>(s.rows); }, kSpecs, options);
}

INSTANTIATE_TEST_SUITE_P(Seeds, RtlEquivalenceRandom, ::testing::Values(1, 2, 3, 4, 5, 6));

// Every unit's own latency; the datapath's formats and spec keys other than timing.
TEST(RtlEquivalenceEdge, OddFormatsDeepPipelinesAndTinyBuffers) {
  const RandomStream s = random_stream(99, 1200, false);
  const SlotMap slots = make_slots(s.header);
  ClockedOptions options;
  options.sink = SinkReady{0.5, 3};
  check_equivalence(
      slots, s.rows, [&] { return std::make_unique<MemoryRowStream>(s.rows); },
      {"schlick:in=uq1.11,out=uq1.9,divider=iterative,buffer=1",
       "schlick:out=uq1.20,divider=pipelined,buffer=4", "hast:d=1,buffer=1", "hast:d=8",
       "horner:degree=6,buffer=2", "pow:buffer=1", "lut:skip=off", "hast:skip=off,buffer=2"},
      options);
}

TEST(RtlEquivalenceEdge, EmptyAndSingleRowStreams) {
  const RandomStream s = random_stream(5, 1, false);
  const SlotMap slots = make_slots(s.header);
  const std::vector<VectorRow> none;
  std::vector<std::unique_ptr<SpecularUnit>> owned;
  owned.push_back(make_unit(parse_unit_spec("hast"), slots));
  owned.push_back(make_unit(parse_unit_spec("lut"), slots));
  // Lane 0 gets no rows, lane 1 the single row.
  int opened = 0;
  std::vector<LaneOutput> out;
  std::vector<std::uint64_t> lanes;
  const auto stats = run_clocked(
      {owned[0].get(), owned[1].get()}, slots,
      [&]() -> std::unique_ptr<RowStream> {
        return std::make_unique<MemoryRowStream>(opened++ == 0 ? none : s.rows);
      },
      ClockedOptions{}, [&](const LaneOutput& o) { lanes.push_back(o.lane); });
  ASSERT_EQ(stats.size(), 2u);
  EXPECT_EQ(stats[0].results, 0u);
  EXPECT_EQ(stats[0].cycles, 0u);
  EXPECT_EQ(stats[1].results, 1u);
  ASSERT_EQ(lanes.size(), 1u);
  EXPECT_EQ(lanes[0], 1u);
  TimingEngine engine(owned[1]->timing(), SinkReady{});
  const std::size_t slot = slots.slot(s.rows[0]);
  engine.next(owned[1]->skip(slot, quantize_input(s.rows[0].t, owned[1]->in_format())));
  EXPECT_EQ(stats[1], engine.stats());
}

}  // namespace
}  // namespace glint
