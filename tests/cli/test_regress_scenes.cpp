// glint regress on scenes and budgets (issue 25, item 6), through the real binary: a scene's
// golden passes and, edited, fails saying first what changed in the hardware, then the figures
// that moved, then every difference; budgets hold or fail, alone or beside a report; a malformed
// budget exits 2 naming the golden and the field before anything runs; --update records no
// figures that break a budget.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using glint::test::CliRun;
using nlohmann::json;

const std::string kTraces = GLINT_SOURCE_DIR "/traces";

class RegressScenes : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_.path() / "t" / "scenes");
    fs::create_directories(dir_.path() / "t" / "golden" / "scenes");
    fs::copy_file(kTraces + "/scenes/small.json", dir_.path() / "t" / "scenes" / "small.json");
  }
  fs::path scene_golden() const { return dir_.path() / "t" / "golden" / "scenes" / "small.json"; }
  void write(const fs::path& path, const json& j) { std::ofstream(path) << j.dump(2); }
  json read(const fs::path& path) { return json::parse(glint::test::read_file(path)); }
  CliRun glint(const std::string& args) { return glint::test::run_glint(dir_.path(), args); }
  CliRun regress() { return glint("regress --traces t"); }
  // A golden of the small scene through these lanes, recorded by --update.
  void record(const std::vector<std::string>& units) {
    write(scene_golden(), {{"scene", "small.json"}, {"units", units}});
    const CliRun r = glint("regress --traces t --update");
    ASSERT_EQ(r.status, 0) << r.out << r.err;
  }
  // The phong trace and its shipped golden beside the scene.
  void add_phong(const std::function<void(json&)>& edit) {
    fs::copy_file(kTraces + "/phong_basic.vec", dir_.path() / "t" / "phong_basic.vec",
                  fs::copy_options::overwrite_existing);
    json g = read(kTraces + "/golden/phong_basic.json");
    edit(g);
    write(dir_.path() / "t" / "golden" / "phong_basic.json", g);
  }
  glint::test::TempDir dir_;
};

// `needles` appear in `text` in this order; returns false (and says which) otherwise.
::testing::AssertionResult in_order(const std::string& text,
                                    const std::vector<std::string>& needles) {
  std::size_t at = 0;
  for (const auto& n : needles) {
    const auto found = text.find(n, at);
    if (found == std::string::npos)
      return ::testing::AssertionFailure() << "'" << n << "' not found after offset " << at;
    at = found + n.size();
  }
  return ::testing::AssertionSuccess();
}

TEST_F(RegressScenes, RecordedSceneGoldenPasses) {
  record({"hast", "lut"});
  const json g = read(scene_golden());
  EXPECT_EQ(g.at("report").at("glint_render_report"), 4);
  EXPECT_EQ(g.at("report").at("units").size(), 2u);
  const CliRun r = regress();
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("ok    scenes/small.json\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0 traces and 1 scene checked, 0 failed"), std::string::npos) << r.out;
}

// The golden's lane is edited (hast's degree 3 -> 4, its report left as recorded): the spec that
// changed comes first, then the figures in words, then the full list; the untouched lane is in
// none of them.
TEST_F(RegressScenes, EditedGoldenSaysWhatChangedInTheHardwareFirst) {
  record({"hast:d=3", "lut"});
  json g = read(scene_golden());
  g["units"][0] = "hast";
  write(scene_golden(), g);
  const CliRun r = regress();
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_TRUE(in_order(
      r.out,
      {"FAIL  scenes/small.json (", "what changed in the hardware:", "hast: spec ", "d=3 -> d=4",
       "largest differences:", "hast: image max error fell ", "LSB (-", "every difference:",
       "hast.image_error.max_lsb: ", "0 traces and 1 scene checked, 1 failed"}))
      << r.out;
  const std::string head = r.out.substr(0, r.out.find("every difference:"));
  EXPECT_EQ(head.find("lut"), std::string::npos) << head;
}

TEST_F(RegressScenes, BudgetOnlyGoldenChecksOnlyItsBudgets) {
  const json holds = {
      {"scene", "small.json"},
      {"units", {"hast", "lut"}},
      {"chip", "ram:materials=8,slots=8"},
      {"budgets", {{"lut", "image.max_lsb<=1,area_ge<=1e6"}, {"hast", "image.max_lsb<=255"}}},
      {"report", nullptr}};
  write(scene_golden(), holds);
  const std::string before = glint::test::read_file(scene_golden());
  CliRun r = regress();
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("ok    scenes/small.json"), std::string::npos) << r.out;
  // --update keeps it a contract: no figures recorded.
  r = glint("regress --traces t --update");
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_EQ(glint::test::read_file(scene_golden()), before);

  json fails = holds;
  fails["budgets"] = {{"lut", "area_ge<=10"}, {"hast", "image.max_lsb<=1"}};
  write(scene_golden(), fails);
  r = regress();
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_TRUE(in_order(
      r.out, {"FAIL  scenes/small.json (2 budget conditions not met)", "budgets not met:",
              "hast: image.max_lsb<=1 does not hold: ", "lut: area_ge<=10 does not hold: "}))
      << r.out;
  EXPECT_EQ(r.out.find("differences"), std::string::npos) << r.out;
}

// Beside a report, the budgets not met come after the hardware and before the figures.
TEST_F(RegressScenes, TraceBudgetsBesideTheReport) {
  add_phong([](json& g) { g["budgets"] = {{"lut", "lsb8<=1"}}; });
  CliRun r = regress();
  EXPECT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("1 traces checked, 0 failed"), std::string::npos) << r.out;
  add_phong([](json& g) {
    g["budgets"] = {{"lut", "lsb8<=1,area_ge<=10"}};
    // The lut lane's recorded area, as if the cost model had moved since.
    auto& area = g["report"]["units"][6]["area"]["ge"];
    area = area.get<double>() * 0.9;
    // And a chip of fixed capacity, recorded but never re-run.
    g["chip"] = "ram:materials=4,slots=4";
  });
  r = regress();
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_TRUE(
      in_order(r.out, {"FAIL  phong_basic.vec (", "differences, 1 budget condition not met)",
                       "what changed in the hardware:", "every lane: slot capacity 1 -> 4",
                       "budgets not met:", "lut.1: area_ge<=10 does not hold: ",
                       "largest differences:", "every difference:", "chip.slots: 4, golden 1"}))
      << r.out;
}

TEST_F(RegressScenes, MalformedBudgetNamesTheGoldenAndTheField) {
  struct Case {
    json budgets;
    const char* field;
    const char* says;
  };
  const json base = {{"scene", "small.json"}, {"units", {"hast", "lut"}}, {"report", nullptr}};
  for (const Case& c : std::vector<Case>{
           {{{"hast", "frobs<=1"}}, "budgets.hast", "unknown measure 'frobs'"},
           {{{"hast", "image.max_lsb<=x"}}, "budgets.hast", "not a finite number"},
           {{{"hast", "image.max_lsb=1"}}, "budgets.hast", "expected MEASURE OP VALUE"},
           {{{"hast", "cycles<=5"}}, "budgets.hast", "a render report has no figure for 'cycles'"},
           {{{"hast:d=9", "area_ge<=1"}}, "budgets.hast:d=9", "no lane has this spec"},
           {{{"hast", 5}}, "budgets.hast", "must be a string"},
           {json::object(), "budgets", "empty"},
       }) {
    json g = base;
    g["budgets"] = c.budgets;
    write(scene_golden(), g);
    const CliRun r = regress();
    SCOPED_TRACE(c.field);
    EXPECT_EQ(r.status, 2) << r.out << r.err;
    EXPECT_NE(r.err.find("small.json: field '" + std::string(c.field) + "': "), std::string::npos)
        << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
  }
  // Neither report nor budgets: nothing would be checked.
  json g = base;
  write(scene_golden(), g);
  CliRun r = regress();
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("field 'report'"), std::string::npos) << r.err;
  // A trace's golden has no image to hold to a budget.
  fs::remove(scene_golden());
  add_phong([](json& t) { t["budgets"] = {{"lut", "image.max_lsb<=1"}}; });
  r = regress();
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("phong_basic.json: field 'budgets.lut': "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("image-level"), std::string::npos) << r.err;
  EXPECT_EQ(r.out, "");
}

TEST_F(RegressScenes, UpdateRecordsNoFiguresThatBreakABudget) {
  record({"hast", "lut"});
  json g = read(scene_golden());
  g["budgets"] = {{"hast", "image.max_lsb<=1"}};
  write(scene_golden(), g);
  const std::string before = glint::test::read_file(scene_golden());
  const CliRun r = glint("regress --traces t --update");
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("hast: image.max_lsb<=1 does not hold"), std::string::npos) << r.out;
  EXPECT_NE(r.err.find("no golden updated"), std::string::npos) << r.err;
  EXPECT_EQ(glint::test::read_file(scene_golden()), before);
}

TEST_F(RegressScenes, GoldenOfAMissingSceneIsRefused) {
  write(scene_golden(), {{"scene", "gone.json"},
                         {"units", {"lut"}},
                         {"budgets", {{"lut", "area_ge<=1e6"}}},
                         {"report", nullptr}});
  const CliRun r = regress();
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("small.json: field 'scene': no scene 'gone.json'"), std::string::npos)
      << r.err;
}

}  // namespace
