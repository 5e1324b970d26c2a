// The goldens of `glint regress` checked against their schema (eval/golden.h): every shipped golden
// passes; a missing or extra field, a value of the wrong type, a report of another schema version
// or of other settings, a nesting or duplicate key is an InputError naming the file and the field;
// and the comparison covers the whole report, not only what the golden holds.
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "eval/golden.h"
#include "eval/golden_diff.h"
#include "eval/sim_report.h"
#include "io/input_error.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using glint::GoldenUse;
using glint::InputError;
using nlohmann::json;

const std::string kGoldenDir = GLINT_SOURCE_DIR "/traces/golden";

json shipped(const std::string& name) {
  return json::parse(glint::test::read_file(kGoldenDir + "/" + name + ".json"));
}

// The field an InputError names when `text` is parsed as a golden ("" when it parses).
std::string refused_field(const std::string& text, GoldenUse use = GoldenUse::kCompare,
                          std::string* message = nullptr) {
  try {
    glint::parse_golden(text, "g.json", use);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "g.json");
    if (message) *message = e.message();
    return e.field();
  }
  return "";
}

std::string refused_json(const json& golden, GoldenUse use = GoldenUse::kCompare) {
  return refused_field(golden.dump(), use);
}

TEST(Golden, EveryShippedGoldenPasses) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(kGoldenDir)) {
    if (e.path().extension() != ".json") continue;
    SCOPED_TRACE(e.path().string());
    const glint::Golden g = glint::read_golden(e.path().string());
    EXPECT_EQ(g.trace, e.path().stem().string() + ".vec");
    EXPECT_FALSE(g.units.empty());
    EXPECT_EQ(g.report.at("units").size(), g.units.size());
    // Written back, it reads the same.
    EXPECT_EQ(glint::parse_golden(g.to_json().dump(), "again.json").to_json(), g.to_json());
    ++n;
  }
  EXPECT_GE(n, 8);
}

// The scene goldens: a report, and budgets alone on a chip of 8 slots.
TEST(Golden, EveryShippedSceneGoldenPasses) {
  int reports = 0, budgets_only = 0;
  for (const auto& e : fs::directory_iterator(kGoldenDir + "/scenes")) {
    if (e.path().extension() != ".json") continue;
    SCOPED_TRACE(e.path().string());
    const glint::Golden g = glint::read_golden(e.path().string());
    EXPECT_EQ(g.kind, glint::GoldenKind::kScene);
    EXPECT_TRUE(fs::exists(GLINT_SOURCE_DIR "/traces/scenes/" + g.scene)) << g.scene;
    if (g.budgets_only) {
      ++budgets_only;
      EXPECT_FALSE(g.budgets.empty());
    } else {
      ++reports;
      EXPECT_EQ(g.report.at("units").size(), g.units.size());
    }
    EXPECT_EQ(glint::parse_golden(g.to_json().dump(), "again.json").to_json(), g.to_json());
  }
  EXPECT_GE(reports, 1);
  EXPECT_GE(budgets_only, 1);
}

TEST(Golden, BudgetsAndChipAreChecked) {
  json g = shipped("phong_basic");
  g["budgets"] = {{"lut", "lsb8<=1"}};
  g["chip"] = "ram:materials=4,slots=4";
  EXPECT_EQ(refused_json(g), "");
  const glint::Golden parsed = glint::parse_golden(g.dump(), "g.json");
  EXPECT_EQ(parsed.chip, "ram:materials=4,slots=4");
  ASSERT_EQ(parsed.budgets.size(), 1u);
  EXPECT_EQ(parsed.budgets[0].second, "lsb8<=1");
  g["chip"] = "ram:slots=0";
  EXPECT_EQ(refused_json(g), "chip");
  g["chip"] = 4;
  EXPECT_EQ(refused_json(g), "chip");
  g["chip"] = "ram:materials=4,slots=4";
  g["budgets"] = {{"lut:bits=9", "lsb8<=1"}};
  EXPECT_EQ(refused_json(g), "budgets.lut:bits=9");
  g["budgets"] = {{"lut", json::array({"lsb8<=1"})}};
  EXPECT_EQ(refused_json(g), "budgets.lut");
  // Budgets only: the report null, which needs budgets.
  g["budgets"] = {{"lut", "lsb8<=1"}};
  g["report"] = nullptr;
  EXPECT_EQ(refused_json(g), "");
  EXPECT_TRUE(glint::parse_golden(g.dump(), "g.json").budgets_only);
  g.erase("budgets");
  EXPECT_EQ(refused_json(g), "report");
  // A scene's golden has no sink; a trace's key in it is unknown.
  json s = {{"scene", "small.json"},
            {"units", {"lut"}},
            {"budgets", {{"lut", "area_ge<=1"}}},
            {"report", nullptr}};
  EXPECT_EQ(refused_json(s), "");
  s["seed"] = 1;
  EXPECT_EQ(refused_json(s), "seed");
  s.erase("seed");
  s["scene"] = "scenes/small.json";
  EXPECT_EQ(refused_json(s), "scene");
}

// What changed in the hardware, run first (the chip), then lane by lane.
TEST(Golden, HardwareChangesNameTheChipAndTheLanes) {
  const json report = shipped("eight_lights").at("report");
  EXPECT_TRUE(glint::hardware_changes(glint::GoldenKind::kTrace, report, report).empty());
  json golden = report, fresh = report;
  fresh["chip"]["spec"] = "ram:materials=16";
  const std::string spec = report["units"][6]["spec"];
  ASSERT_NE(spec.find("bits=6"), std::string::npos) << spec;
  fresh["units"][6]["spec"] =
      spec.substr(0, spec.find("bits=6")) + "bits=7" + spec.substr(spec.find("bits=6") + 6);
  fresh["units"][6]["timing"]["latency"] = 3;
  const auto lines = glint::hardware_changes(glint::GoldenKind::kTrace, golden, fresh);
  const std::vector<std::string> want = {"chip rom -> ram:materials=16",
                                         "lut.1: spec bits=6 -> bits=7", "lut.1: latency 2 -> 3"};
  EXPECT_EQ(lines, want);
}

// The issue's example: the lane that moved most first, errors in LSB, area in grouped GE.
TEST(Golden, LargestChangesInWords) {
  const json report = shipped("phong_basic").at("report");
  EXPECT_TRUE(glint::largest_changes(glint::GoldenKind::kTrace, report, report, 1e-9).empty());
  json golden = report, fresh = report;
  // Lane 3 is hast, lane 0 pow (default_specs in cmd_regress.cpp).
  ASSERT_EQ(report["units"][3]["unit"], "hast");
  golden["units"][3]["errors"]["max_lsb"] = 0.31;
  fresh["units"][3]["errors"]["max_lsb"] = 0.52;
  golden["units"][3]["area"]["ge"] = 6301.0;
  fresh["units"][3]["area"]["ge"] = 6762.0;
  golden["units"][0]["area"]["ge"] = 1000.0;
  fresh["units"][0]["area"]["ge"] = 990.0;
  fresh["units"][0]["digest"] = "0000000000000000";
  const auto lines = glint::largest_changes(glint::GoldenKind::kTrace, golden, fresh, 1e-9);
  const std::vector<std::string> want = {
      "hast: max error rose 0.31 LSB -> 0.52 LSB (+68 %); area 6 301 -> 6 762 GE (+7.3 %)",
      "pow: area 1 000 -> 990 GE (-1.0 %); results differ bit for bit (digest)"};
  EXPECT_EQ(lines, want);
  // Within a tolerance of 10 %, only the error moved; the digest is exact whatever it is.
  const auto loose = glint::largest_changes(glint::GoldenKind::kTrace, golden, fresh, 0.1);
  ASSERT_EQ(loose.size(), 2u);
  EXPECT_EQ(loose[0], "hast: max error rose 0.31 LSB -> 0.52 LSB (+68 %)");
  EXPECT_EQ(loose[1], "pow: results differ bit for bit (digest)");
}

TEST(Golden, MissingOrExtraTopLevelFieldsAreNamed) {
  const json g = shipped("phong_basic");
  for (const char* key : {"trace", "units", "sink_ready", "seed", "report"}) {
    json h = g;
    h.erase(key);
    EXPECT_EQ(refused_json(h), key);
  }
  json extra = g;
  extra["comment"] = "hi";
  EXPECT_EQ(refused_json(extra), "comment");
  EXPECT_EQ(refused_json(json::array()), "json");
}

TEST(Golden, WrongTypesAndValuesAreNamed) {
  const json g = shipped("phong_basic");
  struct Case {
    std::function<void(json&)> edit;
    std::string field;
  };
  const Case cases[] = {
      {[](json& h) { h["seed"] = "7"; }, "seed"},
      {[](json& h) { h["seed"] = -7; }, "seed"},
      {[](json& h) { h["seed"] = 7.5; }, "seed"},
      // An always-ready sink has no pattern: sim refuses --seed, so only the default is a setting.
      {[](json& h) { h["seed"] = h["report"]["seed"] = 7; }, "seed"},
      {[](json& h) { h["sink_ready"] = "1"; }, "sink_ready"},
      {[](json& h) { h["sink_ready"] = 0.001; }, "sink_ready"},
      {[](json& h) { h["sink_ready"] = 2; }, "sink_ready"},
      {[](json& h) { h["units"] = "pow"; }, "units"},
      {[](json& h) { h["units"] = json::array(); }, "units"},
      {[](json& h) { h["units"][0] = 3; }, "units[0]"},
      {[](json& h) { h["units"][0] = "pow:"; }, "units[0]"},
      {[](json& h) { h["trace"] = "../x.vec"; }, "trace"},
      {[](json& h) { h["trace"] = "phong_basic"; }, "trace"},
      {[](json& h) { h["report"] = json::array(); }, "report"},
      {[](json& h) { h["report"]["glint_sim_report"] = 2; }, "report.glint_sim_report"},
      {[](json& h) { h["report"]["vectors_file"] = "other.vec"; }, "report.vectors_file"},
      {[](json& h) { h["report"]["seed"] = 8; }, "report.seed"},
      {[](json& h) { h["report"]["sink_ready"] = 0.5; }, "report.sink_ready"},
      {[](json& h) { h["report"]["mode"] = "slow"; }, "report.mode"},
      {[](json& h) { h["report"]["rows"] = "1001"; }, "report.rows"},
      {[](json& h) { h["report"].erase("rows"); }, "report.rows"},
      {[](json& h) { h["report"]["extra"] = 1; }, "report.extra"},
      {[](json& h) { h["report"]["units"].erase(0); }, "report.units"},
      {[](json& h) { h["report"]["units"][0].erase("digest"); }, "report.units[0].digest"},
      {[](json& h) { h["report"]["units"][0]["digest"] = "xyz"; }, "report.units[0].digest"},
      {[](json& h) { h["report"]["units"][0]["digest"] = 5; }, "report.units[0].digest"},
      {[](json& h) { h["report"]["units"][0]["note"] = 1; }, "report.units[0].note"},
      {[](json& h) { h["report"]["units"][0]["vectors"] = -1; }, "report.units[0].vectors"},
      {[](json& h) { h["report"]["units"][0]["latency"].erase("mean"); },
       "report.units[0].latency.mean"},
      {[](json& h) { h["report"]["units"][0]["stalls"]["x"] = 0; }, "report.units[0].stalls.x"},
      {[](json& h) { h["report"]["units"][0]["operations"]["add"] = "3"; },
       "report.units[0].operations.add"},
      {[](json& h) { h["report"]["units"][0]["errors"] = 0; }, "report.units[0].errors"},
  };
  for (const Case& c : cases) {
    json h = g;
    c.edit(h);
    EXPECT_EQ(refused_json(h), c.field) << h.dump().substr(0, 200);
  }
}

TEST(Golden, NestingDuplicatesAndSyntaxAreRefused) {
  std::string message;
  const std::string deep = std::string(100000, '[') + std::string(100000, ']');
  EXPECT_EQ(refused_field(deep, GoldenUse::kCompare, &message), "json");
  EXPECT_NE(message.find("nested deeper than 32"), std::string::npos) << message;
  EXPECT_EQ(refused_field(R"({"seed": 1, "seed": 2})"), "seed");
  EXPECT_EQ(refused_field("{\"trace\": "), "json");
  EXPECT_EQ(refused_field(""), "json");
  EXPECT_EQ(refused_field(R"({"seed": 1e999})"), "json");
}

// --update replaces the report: an old schema, or none, is accepted; the settings still checked.
TEST(Golden, UpdateNeedsOnlyTheSettings) {
  json g = shipped("phong_basic");
  g["report"]["glint_sim_report"] = 2;
  EXPECT_EQ(refused_json(g, GoldenUse::kUpdate), "");
  g.erase("report");
  EXPECT_EQ(refused_json(g, GoldenUse::kUpdate), "");
  EXPECT_EQ(refused_json(g, GoldenUse::kCompare), "report");
  g["seed"] = "x";
  EXPECT_EQ(refused_json(g, GoldenUse::kUpdate), "seed");
}

std::string shape_field(const json& golden_report, const json& fresh) {
  try {
    glint::check_report_shape(golden_report, fresh, "g.json");
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "g.json");
    return e.field();
  }
  return "";
}

// The nested parts (errors, elaboration, config, inventory) against this build's report.
TEST(Golden, NestedShapeIsCheckedAgainstTheFreshReport) {
  const json fresh = shipped("eight_lights").at("report");
  EXPECT_EQ(shape_field(fresh, fresh), "");
  json g = fresh;
  g["units"][1]["errors"]["slots"][3]["bound"].erase("input");
  EXPECT_EQ(shape_field(g, fresh), "report.units[1].errors.slots[3].bound.input");
  g = fresh;
  g["units"][0]["elaboration"]["groups"][0]["extra"] = 1;
  EXPECT_EQ(shape_field(g, fresh), "report.units[0].elaboration.groups[0].extra");
  g = fresh;
  g["units"][2]["config"]["d"] = "4";
  EXPECT_EQ(shape_field(g, fresh), "report.units[2].config.d");
  // A number written as 1.0 or 1 is one type; a null stands for a NaN number.
  g = fresh;
  g["units"][0]["errors"]["max_abs"] = json(nullptr);
  g["units"][0]["vectors"] = static_cast<double>(fresh["units"][0]["vectors"].get<std::uint64_t>());
  EXPECT_EQ(shape_field(g, fresh), "");
  // Arrays of another length are compared as values, not refused as a schema.
  g = fresh;
  g["units"][0]["errors"]["slots"].erase(0);
  EXPECT_EQ(shape_field(g, fresh), "");
  EXPECT_FALSE(glint::diff_sim_reports(g, fresh).empty());
}

TEST(Golden, DiffCoversTheWholeReport) {
  const json fresh = shipped("phong_basic").at("report");
  EXPECT_TRUE(glint::diff_sim_reports(fresh, fresh).empty());
  json g = fresh;
  g["rows"] = 1000;
  EXPECT_FALSE(glint::diff_sim_reports(g, fresh).empty());
  g = fresh;
  g["units"][0].erase("digest");
  const auto diffs = glint::diff_sim_reports(g, fresh);
  ASSERT_EQ(diffs.size(), 1u);
  EXPECT_NE(diffs[0].find("digest"), std::string::npos) << diffs[0];
}

}  // namespace
