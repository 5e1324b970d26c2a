// The energy at a node through the glint binary: sim's report equals an in-process count over the
// same stream (eval/energy.h), render and sweep count as sim does (the same requests give the
// same figure), and the options that need --node are refused without it, naming both.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cost/energy.h"
#include "eval/activity.h"
#include "eval/energy.h"
#include "eval/evaluate.h"
#include "io/vectors.h"
#include "test_support.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"
#include "vector_rows.h"

namespace glint {
namespace {

const std::string kTrace = std::string(GLINT_SOURCE_DIR) + "/traces/multi_light.vec";
const std::string kScene = std::string(GLINT_SOURCE_DIR) + "/traces/scenes/small.json";

// unit spec -> its lane's energy object, from a sim report run in `dir`.
std::map<std::string, nlohmann::json> sim_energy(const std::filesystem::path& dir,
                                                 const std::string& vectors,
                                                 const std::string& units,
                                                 const std::string& gating) {
  const test::CliRun run =
      test::run_glint(dir, "sim " + test::shell_quote(vectors) + " " + units +
                               " --node osu018 --activity " + gating + " --json");
  EXPECT_EQ(run.status, 0) << run.err;
  std::map<std::string, nlohmann::json> out;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  for (const nlohmann::json& lane : report.at("units"))
    out[lane.at("spec").get<std::string>()] = lane.at("energy");
  return out;
}

TEST(SimEnergy, ReportEqualsACountOverTheSameStream) {
  VectorHeader header;
  const std::vector<VectorRow> rows = test::read_rows(kTrace, header);
  const SlotMap slots = make_slots(header);
  test::TempDir tmp;
  for (const char* gating : {"none", "operand", "clock"}) {
    const auto lanes = sim_energy(tmp.path(), kTrace,
                                  "--unit pow --unit schlick:divider=iterative --unit lut", gating);
    ASSERT_EQ(lanes.size(), 3u);
    for (const auto& [spec, energy] : lanes) {
      const auto unit = make_unit(parse_unit_spec(spec), slots);
      ActivityCounter counter(*unit, parse_gating(gating));
      for (const VectorRow& row : rows)
        counter.add(slots.slot(row), quantize_input(row.t, unit->in_format()));
      const LaneEnergy want =
          lane_energy(unit_cost(*unit), counter.activity(), *find_energy("osu018"));
      EXPECT_EQ(energy, energy_json(want)) << gating << " " << spec;
      EXPECT_GT(energy.at("pj_per_request").get<double>(), 0) << spec;
    }
  }
}

// Without --node, sim reports the activity and no energy (its outputs as before).
TEST(SimEnergy, NeedsTheNode) {
  test::TempDir tmp;
  const test::CliRun run = test::run_glint(
      tmp.path(), "sim " + test::shell_quote(kTrace) + " --unit lut --activity operand --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json lane = nlohmann::json::parse(run.out).at("units").at(0);
  EXPECT_TRUE(lane.contains("activity"));
  EXPECT_FALSE(lane.contains("energy"));
}

// render --node on a scene and sim on the vector file of its requests count the same energy, with
// the skip and without it (the lane's spec with skip=off).
TEST(RenderEnergy, EqualsSimOnTheSameRequests) {
  test::TempDir tmp;
  const std::string vec = (std::filesystem::path(tmp.path()) / "small.vec").string();
  for (const char* gating : {"operand", "clock"}) {
    const test::CliRun run =
        test::run_glint(tmp.path(), "render " + test::shell_quote(kScene) +
                                        " --unit hast --unit pow -o out --node osu018 --activity " +
                                        gating + " --write-vectors " + test::shell_quote(vec));
    ASSERT_EQ(run.status, 0) << run.err;
    EXPECT_NE(run.out.find("per shaded pixel"), std::string::npos) << run.out;
    std::ifstream in(std::filesystem::path(tmp.path()) / "out" / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    const auto sim = sim_energy(tmp.path(), vec, "--unit hast --unit pow", gating);
    for (const nlohmann::json& u : report.at("units")) {
      const nlohmann::json& e = u.at("energy");
      const nlohmann::json& s = sim.at(u.at("spec").get<std::string>());
      EXPECT_EQ(e.at("requests"), s.at("requests"));
      EXPECT_EQ(e.at("computed"), s.at("computed"));
      EXPECT_DOUBLE_EQ(e.at("total_pj").get<double>(), s.at("total_pj").get<double>());
      EXPECT_EQ(e.at("per_request"), s.at("per_request"));
      const auto pixels = e.at("shaded_pixels").get<std::uint64_t>();
      ASSERT_GT(pixels, 0u);
      EXPECT_DOUBLE_EQ(e.at("pj_per_shaded_pixel").get<double>(),
                       e.at("total_pj").get<double>() / static_cast<double>(pixels));
      // What the skip buys: the lane without it, as sim counts that spec on the same requests.
      const nlohmann::json& off = u.at("energy_without_skip");
      const std::string off_spec = off.at("spec").get<std::string>();
      EXPECT_NE(off_spec.find("skip=off"), std::string::npos) << off_spec;
      const auto sim_off =
          sim_energy(tmp.path(), vec, "--unit " + test::shell_quote(off_spec), "none");
      EXPECT_DOUBLE_EQ(off.at("total_pj").get<double>(),
                       sim_off.at(off_spec).at("total_pj").get<double>());
      EXPECT_EQ(off.at("requests"), e.at("requests"));
      EXPECT_GT(off.at("computed").get<std::size_t>(), e.at("computed").get<std::size_t>());
    }
  }
}

// sweep --node: each row's energy per request is sim's for that spec, and it has an energy front.
TEST(SweepEnergy, RowsStateSimsEnergyAndAFront) {
  test::TempDir tmp;
  const test::CliRun run =
      test::run_glint(tmp.path(), "sweep " + test::shell_quote(kTrace) +
                                      " --grid lut:bits=4..6 --grid hast --node osu018 --json");
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json report = nlohmann::json::parse(run.out);
  EXPECT_EQ(report.at("objectives").back().at("name"), "energy");
  std::string units;
  for (const nlohmann::json& r : report.at("results"))
    units += " --unit " + test::shell_quote(r.at("spec").get<std::string>());
  const auto sim = sim_energy(tmp.path(), kTrace, units, "operand");
  bool on_front = false;
  for (const nlohmann::json& r : report.at("results")) {
    const nlohmann::json& s = sim.at(r.at("canonical_spec").get<std::string>());
    EXPECT_DOUBLE_EQ(r.at("energy_pj_per_request").get<double>(),
                     s.at("pj_per_request").get<double>());
    on_front = on_front || r.at("pareto").at("energy").get<bool>();
  }
  EXPECT_TRUE(on_front);
  EXPECT_NE(run.out.find("energy_pj_per_request"), std::string::npos);
  // Without --node: no energy anywhere (the report as before).
  const test::CliRun plain = test::run_glint(
      tmp.path(), "sweep " + test::shell_quote(kTrace) + " --grid lut:bits=4..5 --json");
  ASSERT_EQ(plain.status, 0) << plain.err;
  const nlohmann::json without = nlohmann::json::parse(plain.out);
  EXPECT_EQ(without.at("objectives").size(), 3u);
  for (const nlohmann::json& r : without.at("results")) {
    EXPECT_FALSE(r.contains("energy_pj_per_request"));
    EXPECT_FALSE(r.at("pareto").contains("energy"));
  }
}

TEST(EnergyOptions, NeedTheNodeAndSayWhich) {
  test::TempDir tmp;
  const test::CliRun size =
      test::run_glint(tmp.path(), "size --budget 'lsb8<=1' --grid lut:bits=6 --objective energy " +
                                      test::shell_quote(kTrace));
  EXPECT_EQ(size.status, 2) << size.err;
  EXPECT_NE(size.err.find("--objective energy"), std::string::npos) << size.err;
  EXPECT_NE(size.err.find("--node"), std::string::npos) << size.err;
  const test::CliRun render = test::run_glint(
      tmp.path(), "render " + test::shell_quote(kScene) + " -o out --activity clock");
  EXPECT_EQ(render.status, 2) << render.err;
  EXPECT_NE(render.err.find("--activity"), std::string::npos) << render.err;
  EXPECT_NE(render.err.find("--node"), std::string::npos) << render.err;
  EXPECT_FALSE(std::filesystem::exists(std::filesystem::path(tmp.path()) / "out"));
}

// size --objective energy --node picks, per family, the configuration of least energy per request
// among those meeting the budget.
TEST(EnergyOptions, SizePicksTheLeastEnergy) {
  test::TempDir tmp;
  const test::CliRun run = test::run_glint(
      tmp.path(),
      "size --budget 'lsb8<=2' --grid lut:bits=5..7 --objective energy --node osu018 "
      "--no-widen --json " +
          test::shell_quote(kTrace));
  ASSERT_EQ(run.status, 0) << run.err;
  const nlohmann::json doc = nlohmann::json::parse(run.out);
  EXPECT_EQ(doc.at("objective"), "energy");
  const nlohmann::json& best = doc.at("best");
  ASSERT_TRUE(best.is_object()) << run.out;
  EXPECT_DOUBLE_EQ(best.at("value").get<double>(),
                   best.at("node").at("energy").at("pj_per_request").get<double>());
  // The least of every configuration meeting the budget (all of them, on one input).
  for (const nlohmann::json& c : doc.at("top"))
    EXPECT_GE(c.at("value").get<double>(), best.at("value").get<double>());
}

}  // namespace
}  // namespace glint
