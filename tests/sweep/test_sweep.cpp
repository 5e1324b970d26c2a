// The sweep layer as a library: grid syntax and validation, cross products and shards, Pareto
// fronts on hand-made sets, measures and budgets, the pick of `glint size` against a brute force,
// the engine against eval's Evaluator and `glint sim`'s timing recurrences, thread counts, and
// the report's CSV. Expected values come from the definitions (counts of a cross product, the
// dominance relation, the timing recurrence run directly), never from a copied run.
#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "io/vectors.h"
#include "sweep/engine.h"
#include "sweep/grid.h"
#include "sweep/measures.h"
#include "sweep/outputs.h"
#include "sweep/pareto.h"
#include "sweep/report.h"
#include "sweep/size.h"
#include "sweep/size_explain.h"
#include "sweep/sweep.h"
#include "test_support.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"

namespace {

using glint::Grid;
using glint::parse_grid;
using nlohmann::json;

const std::string kTraces = GLINT_SOURCE_DIR "/traces";

// The message of the std::invalid_argument `f` throws ("" if it throws nothing).
template <class F>
std::string error_of(F f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}

TEST(SweepGrid, RangesAndAlternatives) {
  const Grid g = parse_grid("horner:degree=2..8,in=uq1.11|uq1.15");
  EXPECT_EQ(g.unit, "horner");
  ASSERT_EQ(g.axes.size(), 2u);
  EXPECT_EQ(g.axes[0].key, "degree");
  EXPECT_EQ(g.axes[0].values, (std::vector<std::string>{"2", "3", "4", "5", "6", "7", "8"}));
  EXPECT_EQ(g.axes[1].values, (std::vector<std::string>{"uq1.11", "uq1.15"}));
  EXPECT_EQ(g.size(), 14u);
  EXPECT_EQ(parse_grid("lut:bits=4..9/2").axes[0].values,
            (std::vector<std::string>{"4", "6", "8"}));
  EXPECT_EQ(parse_grid("lut:bits=4..8/2").axes[0].values,
            (std::vector<std::string>{"4", "6", "8"}));
  EXPECT_EQ(parse_grid("horner:degree=2..4|8").axes[0].values,
            (std::vector<std::string>{"2", "3", "4", "8"}));
  // A key with one value passes through; a grid without keys is the unit's defaults.
  EXPECT_EQ(parse_grid("hast:d=3").size(), 1u);
  EXPECT_EQ(parse_grid("pow").size(), 1u);
  EXPECT_TRUE(parse_grid("pow").axes.empty());
}

TEST(SweepGrid, KeysThatNeedOthersAreAcceptedWithThem) {
  // hast's d=auto goes only with match=minimax: checked with the grid's other values.
  EXPECT_EQ(parse_grid("hast:match=minimax,d=auto|3").size(), 2u);
  const std::string e = error_of([] { parse_grid("hast:d=auto"); });
  EXPECT_NE(e.find("--grid 'hast:d=auto'"), std::string::npos) << e;
}

TEST(SweepGrid, BadGridsNameTheGridAndTheKey) {
  struct Case {
    const char* grid;
    std::vector<const char*> mentions;
  };
  const Case cases[] = {
      {"horner:degre=2", {"--grid 'horner:degre=2'", "no key 'degre'", "degree"}},
      {"horner:degree=0..3", {"--grid 'horner:degree=0..3'", "key 'degree'", "'0'"}},
      {"horner:degree=2,method=fast", {"key 'method'", "'fast'"}},
      {"lut:in=uq1.x", {"key 'in'", "uq1.x"}},
      {"frob:x=1", {"--grid 'frob:x=1'", "unknown unit 'frob'"}},
      {"horner:degree=4..2", {"key 'degree'", "empty range"}},
      {"horner:degree=2..4/0", {"key 'degree'", "step"}},
      {"horner:degree=2..x", {"key 'degree'", "lo..hi"}},
      {"horner:degree=2|2", {"key 'degree'", "listed twice"}},
      {"hast:buffer=1..65536|7", {"key 'buffer'", "'7' listed twice"}},
      {"horner:degree=2..82222", {"key 'degree'", "'82222'", "1..10"}},
      // Ranges whose hi - lo overflows a long long (found reading the code, UB before).
      {"horner:degree=-9223372036854775808..9223372036854775807", {"more than 100000 values"}},
      {"horner:degree=-9223372036854775808..9223372036854775807/9223372036854775807",
       {"key 'degree'", "'-9223372036854775808'"}},
      {"horner:degree=-5000000000000000000..5000000000000000000/4000000000000000000",
       {"key 'degree'", "'-5000000000000000000'"}},
      {"hast:d=auto,match=none|width",
       {"key 'd' = 'auto' is refused alone and with the grid's other values (2 combinations "
        "tried)",
        "needs match=minimax"}},
      {"hast:buffer=1..1000,d=1..16,guard=0..7",
       {"128000 configurations exceed the limit of 100000"}},
      {"horner:degree=", {"key 'degree'", "empty value"}},
      {"horner:degree=2||3", {"key 'degree'", "empty value"}},
      {"horner:degree=2,degree=3", {"key 'degree' given twice"}},
      {"horner:", {"no keys"}},
      {"horner:degree=2,", {"trailing ','"}},
      {"horner:degree", {"'degree' is not key=values"}},
      {":degree=2", {"no unit name"}},
  };
  for (const Case& c : cases) {
    const std::string e = error_of([&] { parse_grid(c.grid); });
    ASSERT_FALSE(e.empty()) << c.grid << " was accepted";
    for (const char* m : c.mentions) EXPECT_NE(e.find(m), std::string::npos) << c.grid << ": " << e;
  }
}

// parse_grid checks a range at its two ends only, which holds because every key's accepted
// integers form an interval: checked here for every key of every unit over -2..70.
TEST(SweepGrid, EveryKeyAcceptsAnIntervalOfIntegers) {
  for (const glint::UnitInfo& unit : glint::unit_catalog())
    for (const glint::UnitKey& key : unit.keys) {
      std::vector<int> accepted;
      for (int v = -2; v <= 70; ++v)
        if (error_of([&] { parse_grid(fmt::format("{}:{}={}", unit.name, key.key, v)); }).empty())
          accepted.push_back(v);
      if (accepted.empty()) continue;
      EXPECT_EQ(accepted.back() - accepted.front() + 1, static_cast<int>(accepted.size()))
          << unit.name << ":" << key.key << " accepts "
          << fmt::format("{}", fmt::join(accepted, ","));
    }
}

TEST(SweepGrid, CrossProductOrderAndCount) {
  const std::vector<Grid> grids = {parse_grid("horner:degree=2..4,in=uq1.11|uq1.15"),
                                   parse_grid("lut:bits=4..6"), parse_grid("pow")};
  const auto configs = glint::expand_grids(grids);
  ASSERT_EQ(configs.size(), 3u * 2u + 3u + 1u);
  // The first key varies slowest.
  EXPECT_EQ(configs[0].spec, "horner:degree=2,in=uq1.11");
  EXPECT_EQ(configs[1].spec, "horner:degree=2,in=uq1.15");
  EXPECT_EQ(configs[2].spec, "horner:degree=3,in=uq1.11");
  EXPECT_EQ(configs[5].spec, "horner:degree=4,in=uq1.15");
  EXPECT_EQ(configs[6].spec, "lut:bits=4");
  EXPECT_EQ(configs[9].spec, "pow");
  std::set<std::string> specs;
  for (std::size_t i = 0; i < configs.size(); ++i) {
    EXPECT_EQ(configs[i].index, i);
    specs.insert(configs[i].spec);
    // The spec is what --unit would parse.
    const glint::UnitSpec parsed = glint::parse_unit_spec(configs[i].spec);
    EXPECT_EQ(parsed.name, configs[i].unit_spec.name);
    EXPECT_EQ(parsed.keys, configs[i].unit_spec.keys);
  }
  EXPECT_EQ(specs.size(), configs.size());
  EXPECT_EQ(configs[6].grid, 1u);
}

TEST(SweepGrid, CapOnConfigurations) {
  const std::vector<Grid> grids = {parse_grid("lut:bits=4..9"), parse_grid("hast:d=1..5")};
  EXPECT_EQ(glint::expand_grids(grids, 11).size(), 11u);
  const std::string e = error_of([&] { glint::expand_grids(grids, 10); });
  EXPECT_NE(e.find("11 configurations"), std::string::npos) << e;
  EXPECT_NE(e.find("limit of 10"), std::string::npos) << e;
  EXPECT_EQ(glint::kMaxSweepConfigurations, 100000u);
}

TEST(SweepGrid, ShardsPartitionRoundRobin) {
  const auto all = glint::expand_grids({parse_grid("lut:bits=4..9,in=uq1.11|uq1.15")});
  for (std::size_t n : {1u, 2u, 3u, 5u, 13u}) {
    std::vector<int> seen(all.size(), 0);
    for (std::size_t k = 0; k < n; ++k)
      for (const auto& c : glint::shard_configs(all, k, n)) {
        EXPECT_EQ(c.index % n, k);
        ++seen[c.index];
      }
    for (int s : seen) EXPECT_EQ(s, 1);
  }
  EXPECT_EQ(glint::parse_shard("2/4"), (std::pair<std::size_t, std::size_t>{2, 4}));
  for (const char* bad : {"4/4", "-1/4", "1/0", "1", "a/b", "1/2/3", ""})
    EXPECT_NE(error_of([&] { glint::parse_shard(bad); }).find("--shard"), std::string::npos) << bad;
}

TEST(SweepPareto, HandMadeSet) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  //                            0  1  2  3  4  5    6
  const std::vector<double> a = {1, 2, 3, 2, 4, nan, 5};
  const std::vector<double> b = {5, 3, 4, 3, 1, 0, 1};
  // 0: least a. 1 and 3: equal, both on. 2: dominated by 1. 4: least b among finite. 5: NaN.
  // 6: dominated by 4 (same b, larger a).
  EXPECT_EQ(glint::pareto_front(a, b),
            (std::vector<bool>{true, true, false, true, true, false, false}));
  EXPECT_TRUE(glint::pareto_front({}, {}).empty());
}

TEST(SweepPareto, AgreesWithTheDefinitionOnRandomSets) {
  std::uint64_t s = 12345;
  const auto next = [&] {
    s = s * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>((s >> 33) % 20);  // many ties
  };
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<double> a(30), b(30);
    for (std::size_t i = 0; i < a.size(); ++i) {
      a[i] = next();
      b[i] = next();
    }
    const std::vector<bool> on = glint::pareto_front(a, b);
    for (std::size_t i = 0; i < a.size(); ++i) {
      bool dominated = false;
      for (std::size_t j = 0; j < a.size(); ++j)
        dominated = dominated || (a[j] <= a[i] && b[j] <= b[i] && (a[j] < a[i] || b[j] < b[i]));
      EXPECT_EQ(on[i], !dominated) << "trial " << trial << " point " << i;
    }
  }
}

TEST(SweepMeasures, NamesSuffixesAndBudgets) {
  json row = {{"area_ge", 100.0},
              {"errors", {{"max_abs", 2.0 / 255}, {"max_lsb", 2.0}, {"mismatch_fraction", 0.5}}}};
  const auto lsb8 = glint::find_measure("lsb8", false);
  ASSERT_TRUE(lsb8);
  EXPECT_NEAR(*glint::measure_value(row, *lsb8), 2.0, 1e-12);
  const auto lsb10 = glint::find_measure("max_lsb10", false);
  ASSERT_TRUE(lsb10);
  EXPECT_NEAR(*glint::measure_value(row, *lsb10), 2.0 / 255 * 1023, 1e-12);
  EXPECT_FALSE(glint::find_measure("max_lsb17", false));
  EXPECT_FALSE(glint::find_measure("frobs", false));
  EXPECT_FALSE(glint::find_measure("image.max_lsb", false));
  EXPECT_TRUE(glint::find_measure("image.max_lsb", true));

  const auto budgets = glint::parse_budgets("lsb8<=2,mismatch_fraction<0.5,area_ge>=100", false);
  ASSERT_EQ(budgets.size(), 3u);
  EXPECT_TRUE(glint::meets(row, budgets[0]));
  EXPECT_FALSE(glint::meets(row, budgets[1]));  // strict
  EXPECT_TRUE(glint::meets(row, budgets[2]));
  EXPECT_FALSE(glint::meets(json::object(), budgets[0]));  // a refused configuration
  for (const char* bad : {"frobs<=1", "lsb8", "lsb8<=x", "<=1", "lsb8<=1,", "image.max_lsb<=1"}) {
    const std::string e = error_of([&] { glint::parse_budgets(bad, false); });
    EXPECT_NE(e.find("--budget"), std::string::npos) << bad << ": " << e;
  }
  EXPECT_NE(
      error_of([] { glint::parse_budgets("frobs<=1", false); }).find("unknown measure 'frobs'"),
      std::string::npos);
  EXPECT_NE(error_of([] { glint::parse_budgets("image.max_lsb<=1", false); }).find("--scene"),
            std::string::npos);
}

// Every alias names the measure it stands for, with a depth suffix where the measure is in LSBs,
// and the size guide's table lists exactly the aliases there are.
TEST(SweepMeasures, AliasesNameTheirMeasures) {
  std::set<std::string> listed;
  {
    std::ifstream guide(GLINT_SOURCE_DIR "/src/cli/guide/size.md");
    ASSERT_TRUE(guide) << "src/cli/guide/size.md";
    bool in_table = false;
    for (std::string line; std::getline(guide, line);) {
      if (line == "| alias | measure | from |") in_table = true;
      if (!in_table) continue;
      if (line.empty()) break;
      const auto a = line.find("| `"), b = line.find("` |");
      if (a == 0 && b != std::string::npos) listed.insert(line.substr(3, b - 3));
    }
  }
  std::set<std::string> aliases;
  for (const glint::MeasureAlias& a : glint::measure_aliases()) {
    aliases.insert(a.alias);
    const auto alias = glint::find_measure(a.alias, true);
    const auto measure = glint::find_measure(a.measure, true);
    ASSERT_TRUE(alias) << a.alias;
    ASSERT_TRUE(measure) << a.measure;
    EXPECT_EQ(alias->pointer, measure->pointer) << a.alias;
    EXPECT_EQ(alias->bits, measure->bits) << a.alias;
    EXPECT_EQ(alias->name, a.alias);  // reports name it as written
    EXPECT_FALSE(glint::find_measure(std::string(a.alias) + "x", true)) << a.alias << "x";
    if (std::string(a.measure).find("lsb") != std::string::npos) {
      const auto deep = glint::find_measure(std::string(a.alias) + "10", false);
      ASSERT_TRUE(deep) << a.alias << "10";
      EXPECT_EQ(deep->bits, 10);
      EXPECT_EQ(deep->pointer, glint::find_measure(std::string(a.measure) + "10", false)->pointer);
    }
  }
  EXPECT_EQ(listed, aliases);
  // The headings eval's table used to print parse as the measures they headed.
  const json row = {{"errors", {{"max_abs", 2.0 / 255}, {"weighted", {{"max_abs", 1.0 / 255}}}}}};
  EXPECT_NEAR(*glint::measure_value(row, *glint::find_measure("wlsb8", false)), 1.0, 1e-12);
  EXPECT_NEAR(*glint::measure_value(row, *glint::find_measure("lsb8", false)), 2.0, 1e-12);
  EXPECT_FALSE(glint::find_measure("wlsb17", false));
}

// The engine on one file: each configuration's errors equal a plain Evaluator's over the same
// rows, and its cycles equal a TimingEngine fed the same unit's skip decisions one by one.
TEST(SweepEngine, EqualsEvaluatorAndTimingRecurrences) {
  const std::string file = kTraces + "/multi_light.vec";
  const auto configs = glint::expand_grids({parse_grid("hast:d=2..4"),
                                            parse_grid("schlick:divider=pipelined|iterative"),
                                            parse_grid("lut:bits=5,buffer=2")});
  glint::SweepSettings settings;
  settings.block = 2;         // several blocks
  settings.chunk_rows = 100;  // several chunks
  glint::VectorReader reader(file);
  glint::SweepEngine engine(reader.header(), configs, settings);
  std::vector<glint::VectorRow> rows;
  glint::VectorRow row;
  while (reader.next(row)) rows.push_back(row);
  engine.add(rows.data(), rows.size());
  const std::vector<json> results = engine.results();
  ASSERT_EQ(results.size(), configs.size());
  for (std::size_t k = 0; k < configs.size(); ++k) {
    glint::Evaluator ev(reader.header(), {configs[k].unit_spec});
    const glint::SpecularUnit& unit = *ev.units()[0];
    glint::TimingEngine timing(unit.timing(), glint::SinkReady{});
    const glint::SlotMap& slots = ev.slots();
    for (const auto& r : rows) {
      ev.add(r);
      timing.next(unit.skip(slots.slot(r), glint::quantize_input(r.t, unit.in_format())));
    }
    const json& got = results[k];
    EXPECT_EQ(got.at("spec"), configs[k].spec);
    EXPECT_EQ(got.at("canonical_spec"), unit.canonical_spec());
    EXPECT_EQ(got.at("errors"), ev.stats()[0].errors_json()) << configs[k].spec;
    EXPECT_EQ(got.at("cycles"), timing.stats().cycles) << configs[k].spec;
    EXPECT_EQ(got.at("computed"), timing.stats().computed);
    EXPECT_EQ(got.at("stall_cycles"), timing.stats().stall_cycles());
    EXPECT_EQ(got.at("digest"), fmt::format("{:016x}", ev.digest(0)));
  }
}

// A configuration the stream cannot build is refused, the others run.
TEST(SweepEngine, RefusedConfigurationKeepsTheRest) {
  glint::SweepJob job;
  job.input = {kTraces + "/contract_cases.vec", false};
  // contract_cases.vec has a material of n ~ 13889: schlick's width match needs an n' beyond
  // uq14.4.
  job.grids = {parse_grid("schlick:match=none|width"), parse_grid("lut:bits=5")};
  const json report = glint::run_sweep(job);
  const json& rows = report.at("results");
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_TRUE(rows[0].at("refused").is_null());
  ASSERT_TRUE(rows[1].at("refused").is_string());
  EXPECT_NE(rows[1].at("refused").get<std::string>().find("n register"), std::string::npos);
  EXPECT_TRUE(rows[1].at("error").is_null());
  EXPECT_FALSE(rows[1].at("pareto").at("area").get<bool>());
  EXPECT_TRUE(rows[2].at("refused").is_null());
  EXPECT_GT(rows[2].at("vectors").get<std::uint64_t>(), 0u);
}

// --jobs: the same bytes for any thread count, whatever the block and chunk sizes.
TEST(SweepEngine, SameReportForAnyThreadCount) {
  glint::SweepJob job;
  job.input = {kTraces + "/blinn_colored.vec", false};
  job.grids = {parse_grid("horner:degree=2..5,in=uq1.11|uq1.15"), parse_grid("lut:bits=4..7"),
               parse_grid("pow:log_bits=4|6")};
  job.settings.block = 3;
  job.settings.chunk_rows = 333;
  job.settings.jobs = 1;
  const std::string one = glint::report_json_text(glint::run_sweep(job));
  for (int jobs : {2, 3, 5}) {
    job.settings.jobs = jobs;
    EXPECT_EQ(glint::report_json_text(glint::run_sweep(job)), one) << jobs << " threads";
  }
  job.settings.block = 64;
  job.settings.chunk_rows = 16384;
  EXPECT_EQ(glint::report_json_text(glint::run_sweep(job)), one) << "other block sizes";
}

// size's pick against a brute force over the sweep's rows.
TEST(SweepSize, PicksTheCheapestMeetingTheBudgetOnEveryInput) {
  const std::vector<Grid> grids = {parse_grid("lut:bits=4..8,in=uq1.11|uq1.15"),
                                   parse_grid("horner:degree=2..5"), parse_grid("hast:d=2..4")};
  std::vector<json> reports;
  for (const char* f : {"/phong_basic.vec", "/multi_light.vec"}) {
    glint::SweepJob job;
    job.input = {kTraces + f, false};
    job.grids = grids;
    reports.push_back(glint::run_sweep(job));
  }
  for (const char* budget : {"max_lsb8<=2", "lsb8<=1.5,mismatch_fraction<0.05", "bound_lsb<=4"}) {
    for (auto objective : {glint::SizeObjective::kArea, glint::SizeObjective::kThroughput,
                           glint::SizeObjective::kAreaLatency}) {
      const auto budgets = glint::parse_budgets(budget, false);
      const glint::SizePick pick = glint::pick_cheapest(reports, budgets, objective);
      // Brute force: the objective's worst over the inputs, over every configuration meeting
      // every condition on both inputs; ties to the lower index.
      const char* key = objective == glint::SizeObjective::kArea         ? "area_ge"
                        : objective == glint::SizeObjective::kThroughput ? "throughput"
                                                                         : "area_latency";
      const bool maximise = objective == glint::SizeObjective::kThroughput;
      std::optional<std::size_t> best;
      double best_v = 0;
      std::size_t meeting = 0;
      const std::size_t n = reports[0].at("results").size();
      for (std::size_t i = 0; i < n; ++i) {
        bool ok = true;
        double v = maximise ? INFINITY : -INFINITY;
        for (const json& r : reports) {
          const json& row = r.at("results")[i];
          const double abs = row.at("errors").at("max_abs").get<double>();
          const std::string b = budget;
          if (b == "max_lsb8<=2") ok = ok && abs * 255 <= 2;
          if (b.rfind("lsb8<=1.5", 0) == 0)
            ok = ok && abs * 255 <= 1.5 &&
                 row.at("errors").at("mismatch_fraction").get<double>() < 0.05;
          if (b == "bound_lsb<=4") ok = ok && row.at("errors").at("bound").get<double>() * 255 <= 4;
          const double x = row.at(key).get<double>();
          v = maximise ? std::min(v, x) : std::max(v, x);
        }
        if (!ok) continue;
        ++meeting;
        if (!best || (maximise ? v > best_v : v < best_v)) {
          best = i;
          best_v = v;
        }
      }
      EXPECT_EQ(pick.meeting, meeting) << budget;
      EXPECT_EQ(pick.best, best) << budget << " " << glint::to_string(objective);
      EXPECT_GT(meeting, 0u) << budget << ": the test wants a budget some configuration meets";
    }
  }
  // Nothing meets an impossible budget.
  const glint::SizePick none = glint::pick_cheapest(
      reports, glint::parse_budgets("max_abs<0", false), glint::SizeObjective::kArea);
  EXPECT_FALSE(none.best);
  EXPECT_EQ(none.meeting, 0u);
}

// A row of a hand-made sweep report: the measures explain_family reads.
json hand_row(std::size_t index, double area, double max_abs, double approx, double input_part) {
  return {{"index", index},
          {"unit", "lut"},
          {"spec", fmt::format("lut:bits={}", 4 + index)},
          {"area_ge", area},
          {"errors",
           {{"max_abs", max_abs},
            {"bound_lsb", 2 * max_abs * 255},
            {"parts",
             {{"approximation", {{"max_abs", approx}, {"bound", approx * 2}}},
              {"input", {{"max_abs", input_part}, {"bound", input_part * 2}}}}},
            {"slots",
             {{{"slot", 0},
               {"name", "material 'a'"},
               {"bound_lsb", 1.0},
               {"bound", {{"approximation", 0.001}, {"input", 0.003}, {"total", 0.004}}}},
              {{"slot", 1},
               {"name", "material 'b'"},
               {"bound_lsb", 3.0},
               {"bound", {{"approximation", 0.009}, {"input", 0.002}, {"total", 0.011}}}}}}}}};
}

json hand_report(std::vector<json> rows) {
  return {{"display_bits", 8}, {"input", {{"path", "hand.vec"}}}, {"results", std::move(rows)}};
}

// What glint size says of a family none of whose configurations meets the budget: the best value
// per condition, the closest configuration, its largest part and weakest slot, its grid's edges.
TEST(SweepSize, ExplainsWhatBlocksAFamily) {
  const std::vector<Grid> grids = {parse_grid("lut:bits=4..6")};
  const auto configs = glint::expand_grids(grids);
  // bits=4: refused (no errors), bits=5: 3.8 LSB, bits=6: 2.04 LSB, mostly approximation.
  json refused = {{"index", 0}, {"unit", "lut"}, {"spec", "lut:bits=4"}, {"refused", "too wide"}};
  const std::vector<json> reports = {hand_report(
      {refused, hand_row(1, 200, 0.015, 0.014, 0.001), hand_row(2, 300, 0.008, 0.007, 0.001)})};
  const auto budgets = glint::parse_budgets("lsb8<=1", false);
  const std::vector<double> cost = {NAN, 200, 300};
  const json e = glint::explain_family("lut", reports, budgets, grids, configs, cost, false);
  ASSERT_EQ(e.at("reached").size(), 1u);
  EXPECT_EQ(e.at("reached")[0].at("index"), 2);
  EXPECT_DOUBLE_EQ(e.at("reached")[0].at("best").get<double>(), 0.008 * 255);
  const json& c = e.at("closest");
  EXPECT_EQ(c.at("index"), 2);
  EXPECT_EQ(c.at("missed"), "lsb8<=1");
  EXPECT_DOUBLE_EQ(c.at("miss").get<double>(), 0.008 * 255 - 1);
  EXPECT_EQ(c.at("part").at("name"), "approximation");
  EXPECT_DOUBLE_EQ(c.at("part").at("max_lsb").get<double>(), 0.007 * 255);
  EXPECT_EQ(c.at("slot").at("slot"), 1);
  EXPECT_EQ(c.at("slot").at("part"), "approximation");
  ASSERT_EQ(c.at("grid_edges").size(), 1u);
  EXPECT_EQ(c.at("grid_edges")[0].at("key"), "bits");
  EXPECT_EQ(c.at("grid_edges")[0].at("end"), "largest");
  const std::string text = glint::format_explanation(e);
  EXPECT_NE(text.find("closest: lut:bits=6 misses lsb8<=1 by a factor 2.04"), std::string::npos)
      << text;
  EXPECT_NE(text.find("bits=6 (largest in the grid): a wider --grid may help"), std::string::npos)
      << text;
  // After a search that stopped, the edges are where it stopped, and why is said below.
  json searched = e;
  searched["search"] = json::array({{{"stopped", "too_slow"}}});
  const std::string after = glint::format_explanation(searched);
  EXPECT_NE(after.find("bits=6 (largest in the grid): the search stopped there (too_slow, below)"),
            std::string::npos)
      << after;

  // An end the error does not improve towards is no hint: bits=5 as good as bits=6.
  const std::vector<json> flat = {hand_report(
      {refused, hand_row(1, 200, 0.008, 0.007, 0.001), hand_row(2, 300, 0.008, 0.007, 0.001)})};
  const json f = glint::explain_family("lut", flat, budgets, grids, configs, cost, false);
  EXPECT_EQ(f.at("closest").at("index"), 1);  // the cheaper of two equally close
  EXPECT_TRUE(f.at("closest").at("grid_edges").empty());

  // A bound measure names the part with the largest bound; a family that meets says only how close
  // it came.
  const json b = glint::explain_family("lut", reports, glint::parse_budgets("bound_lsb<=1", false),
                                       grids, configs, cost, false);
  EXPECT_TRUE(b.at("closest").at("part").contains("bound_lsb"));
  const json met = glint::explain_family("lut", reports, glint::parse_budgets("lsb8<=6", false),
                                         grids, configs, cost, true);
  EXPECT_FALSE(met.contains("closest"));
  EXPECT_EQ(glint::format_explanation(met), "");
}

// A bound measured at sampled codes (a slot's "exact": false) is marked "~" wherever the
// explanation shows it: the best value, the closest's value, its part and its slot.
TEST(SweepSize, ExplanationMarksEstimatedBounds) {
  const std::vector<Grid> grids = {parse_grid("lut:bits=5..6")};
  const auto configs = glint::expand_grids(grids);
  json r5 = hand_row(0, 200, 0.015, 0.014, 0.001), r6 = hand_row(1, 300, 0.008, 0.007, 0.001);
  r6["errors"]["slots"][1]["exact"] = false;
  r5["errors"]["slots"][1]["exact"] = true;
  const std::vector<json> reports = {hand_report({r5, r6})};
  const std::vector<double> cost = {200, 300};
  const json e = glint::explain_family("lut", reports, glint::parse_budgets("bound_lsb<=1", false),
                                       grids, configs, cost, false);
  EXPECT_FALSE(e.at("reached")[0].at("exact").get<bool>());
  EXPECT_FALSE(e.at("closest").at("exact").get<bool>());
  EXPECT_FALSE(e.at("closest").at("part").at("exact").get<bool>());
  EXPECT_FALSE(e.at("closest").at("slot").at("exact").get<bool>());
  const std::string text = glint::format_explanation(e);
  EXPECT_NE(text.find("best ~"), std::string::npos) << text;
  EXPECT_NE(text.find("(~"), std::string::npos) << text;
  EXPECT_NE(text.find("(bound ~"), std::string::npos) << text;
  EXPECT_NE(text.find("an estimate: inputs sampled"), std::string::npos) << text;
  // Exact bounds carry no mark; a measured error never does.
  r6["errors"]["slots"][1]["exact"] = true;
  const json x = glint::explain_family("lut", {hand_report({r5, r6})},
                                       glint::parse_budgets("bound_lsb<=1", false), grids, configs,
                                       cost, false);
  EXPECT_EQ(glint::format_explanation(x).find('~'), std::string::npos);
  const json m = glint::explain_family("lut", reports, glint::parse_budgets("lsb8<=1", false),
                                       grids, configs, cost, false);
  EXPECT_FALSE(m.at("reached")[0].contains("exact"));
  EXPECT_EQ(glint::format_explanation(m).find("best ~"), std::string::npos);
}

// glint sweep's fronts mark a bound measure's value "~" in a row whose bounds are estimates, as
// eval's and size's text do; a certified bound, or a measured error, carries no mark.
TEST(SweepSummary, MarksEstimatedBounds) {
  json r5 = hand_row(0, 200, 0.015, 0.014, 0.001), r6 = hand_row(1, 300, 0.008, 0.007, 0.001);
  for (json* r : {&r5, &r6}) {
    (*r)["refused"] = nullptr;
    (*r)["throughput"] = 1.0;
    (*r)["area_latency"] = (*r)["area_ge"];
    (*r)["latency"] = 1;
  }
  const auto summary = [](const json& a, const json& b, const char* measure) {
    json report = hand_report({a, b});
    report["input"]["rows"] = 10;
    report["input"]["kind"] = "vectors";
    report["shard"] = nullptr;
    report["configurations"] = 2;
    report["error_measure"] = measure;
    glint::mark_pareto(report);
    return glint::format_sweep_summary(report);
  };
  r6["errors"]["slots"][1]["exact"] = false;
  const std::string marked = summary(r5, r6, "bound_lsb");
  EXPECT_NE(marked.find(" ~4.08 "), std::string::npos) << marked;
  EXPECT_EQ(marked.find("~7.65"), std::string::npos) << marked;
  EXPECT_NE(marked.find(glint::kEstimateNote), std::string::npos) << marked;
  EXPECT_EQ(summary(r5, r6, "max_lsb").find('~'), std::string::npos);
  r6["errors"]["slots"][1]["exact"] = true;
  EXPECT_EQ(summary(r5, r6, "bound_lsb").find('~'), std::string::npos);
}

TEST(SweepSize, RelativeMissAndTheCheapestK) {
  const auto le = glint::parse_budgets("lsb8<=2", false)[0];
  const auto lt = glint::parse_budgets("lsb8<2", false)[0];
  const auto ge = glint::parse_budgets("throughput>=0.5", false)[0];
  EXPECT_EQ(glint::relative_miss(2.0, le), 0);
  EXPECT_DOUBLE_EQ(glint::relative_miss(3.0, le), 0.5);
  EXPECT_GT(glint::relative_miss(2.0, lt), 0);  // a strict limit reached is missed
  EXPECT_DOUBLE_EQ(glint::relative_miss(0.25, ge), 0.5);
  EXPECT_EQ(glint::relative_miss(std::nullopt, le), std::numeric_limits<double>::infinity());

  glint::SizePick pick;
  pick.value = {5, 3, 3, NAN, 1, 9};
  pick.meets = {true, true, true, true, false, true};
  using V = std::vector<std::size_t>;
  EXPECT_EQ(glint::cheapest_meeting(pick, glint::SizeObjective::kArea, 3), (V{1, 2, 0}));
  EXPECT_EQ(glint::cheapest_meeting(pick, glint::SizeObjective::kArea, 10), (V{1, 2, 0, 5}));
  EXPECT_EQ(glint::cheapest_meeting(pick, glint::SizeObjective::kThroughput, 2), (V{5, 0}));
}

TEST(SweepReport, CsvHasAHeaderAndARowPerConfiguration) {
  glint::SweepJob job;
  job.input = {kTraces + "/phong_basic.vec", false};
  job.grids = {parse_grid("horner:degree=2..4,in=uq1.11|uq1.15")};
  const json report = glint::run_sweep(job);
  const std::string csv = glint::report_csv_text(report);
  std::vector<std::string> lines;
  std::size_t at = 0;
  while (at < csv.size()) {
    const std::size_t nl = csv.find('\n', at);
    lines.push_back(csv.substr(at, nl - at));
    at = nl + 1;
  }
  ASSERT_EQ(lines.size(), 7u);
  EXPECT_EQ(lines[0].rfind("index,unit,spec,canonical_spec,area_ge,", 0), 0u) << lines[0];
  EXPECT_EQ(lines[0].find("image."), std::string::npos);  // vectors: no image columns
  // Specs hold commas: quoted.
  EXPECT_NE(lines[1].find("\"horner:degree=2,in=uq1.11\""), std::string::npos) << lines[1];
  EXPECT_EQ(report.at("glint_sweep_report"), glint::kSweepReportVersion);
  EXPECT_TRUE(report.at("shard").is_null());
  EXPECT_EQ(report.at("configurations"), 6u);
}

}  // namespace
