// What the tau skip buys, at equal error (issue 26 item 5), through the glint binary: render
// --node states, beside each lane's energy without its skip, that lane's error on the frame,
// measured as a lane of that spec is measured on its own; a render without --node does none of
// it; and bad options are still refused before any output.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "test_support.h"

namespace glint {
namespace {

const std::string kScene = std::string(GLINT_SOURCE_DIR) + "/traces/scenes/small.json";

nlohmann::json render_report(const std::filesystem::path& dir, const std::string& args,
                             std::string* summary = nullptr) {
  const test::CliRun run =
      test::run_glint(dir, "render " + test::shell_quote(kScene) + " -o out " + args);
  EXPECT_EQ(run.status, 0) << run.err;
  if (summary) *summary = run.out;
  std::ifstream in(dir / "out" / "report.json");
  return nlohmann::json::parse(in);
}

// A lane with the skip beside the same spec with skip=off rendered as a unit of its own: the
// without-skip entries are exactly that unit's error and energy, its skip part is zero, and the
// two frames' difference bounds the difference of their worst errors.
TEST(RenderWithoutSkip, IsTheSkipOffLaneOnItsOwn) {
  test::TempDir tmp;
  std::string summary;
  const nlohmann::json report = render_report(
      tmp.path(), "--unit pow --unit pow:skip=off --unit lut --node osu018", &summary);
  const nlohmann::json& units = report.at("units");
  ASSERT_EQ(units.size(), 3u);
  const nlohmann::json& on = units.at(0);
  const nlohmann::json& off = units.at(1);
  ASSERT_TRUE(on.contains("error_without_skip")) << on.dump();
  const nlohmann::json& w = on.at("error_without_skip");
  EXPECT_EQ(w.at("spec"), off.at("spec"));
  EXPECT_EQ(w.at("spec"), on.at("energy_without_skip").at("spec"));
  EXPECT_EQ(w.at("image_error"), off.at("image_error"));
  EXPECT_EQ(w.at("errors"), off.at("errors"));
  EXPECT_DOUBLE_EQ(on.at("energy_without_skip").at("total_pj").get<double>(),
                   off.at("energy").at("total_pj").get<double>());
  // Nothing is skipped without the comparator; the lane with it skips some t > 0 on this scene.
  EXPECT_EQ(w.at("errors").at("parts").at("skip").at("max_abs").get<double>(), 0.0);
  EXPECT_GT(on.at("errors").at("parts").at("skip").at("max_abs").get<double>(), 0.0);
  // A lane without the skip has nothing to compare.
  EXPECT_FALSE(off.contains("error_without_skip"));
  EXPECT_FALSE(off.contains("energy_without_skip"));
  for (const nlohmann::json& u : {units.at(0), units.at(2)}) {
    const nlohmann::json& e = u.at("error_without_skip");
    const double max_on = u.at("image_error").at("max_lsb").get<double>();
    const double max_off = e.at("image_error").at("max_lsb").get<double>();
    EXPECT_EQ(e.at("equal_error").get<bool>(), max_on == max_off) << u.at("unit");
    EXPECT_LE(std::abs(max_on - max_off), e.at("max_lsb_between").get<double>()) << u.at("unit");
    if (e.at("pixels_differing").get<std::uint64_t>() == 0)
      EXPECT_EQ(e.at("image_error"), u.at("image_error")) << u.at("unit");
    else
      EXPECT_GT(e.at("max_lsb_between").get<int>(), 0) << u.at("unit");
  }
  // The summary states both errors on the lane's line (its label padded to the column).
  const std::size_t line =
      summary.find("\npow skip=on  error with / without the skip: max_lsb 1 /");
  EXPECT_NE(line, std::string::npos) << summary;
}

// Without --node the render evaluates no lane without the skip and reports none.
TEST(RenderWithoutSkip, OnlyWithTheNode) {
  test::TempDir tmp;
  const nlohmann::json report = render_report(tmp.path(), "--unit pow");
  const nlohmann::json& u = report.at("units").at(0);
  EXPECT_FALSE(u.contains("error_without_skip"));
  EXPECT_FALSE(u.contains("energy_without_skip"));
  EXPECT_FALSE(u.contains("energy"));
}

// Bad options are refused before any output, naming the option.
TEST(RenderWithoutSkip, BadOptionsAreRefused) {
  test::TempDir tmp;
  for (const std::string& args : {std::string("--node osu018 --activity sometimes"),
                                  std::string("--activity clock"), std::string("--node nowhere")}) {
    const test::CliRun run =
        test::run_glint(tmp.path(), "render " + test::shell_quote(kScene) + " -o out " + args);
    EXPECT_EQ(run.status, 2) << args << ": " << run.err;
    const std::string option =
        args.find("--activity") != std::string::npos ? "--activity" : "--node";
    EXPECT_NE(run.err.find(option), std::string::npos) << args << ": " << run.err;
    EXPECT_FALSE(std::filesystem::exists(tmp.path() / "out")) << args;
  }
}

}  // namespace
}  // namespace glint
