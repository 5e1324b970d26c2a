// `glint sim --activity GATING`: each lane's register toggles and clocked bits, as the report
// states them, equal an in-process count over the same stream (eval/activity.h) in both modes,
// and a bad gating is refused naming the option.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/activity.h"
#include "eval/evaluate.h"
#include "io/vectors.h"
#include "test_support.h"
#include "units/catalogue.h"
#include "vector_rows.h"

namespace glint {
namespace {

const std::string kTrace = std::string(GLINT_SOURCE_DIR) + "/traces/multi_light.vec";

class SimActivity : public ::testing::TestWithParam<std::string> {};

TEST_P(SimActivity, ReportEqualsACountOverTheSameStream) {
  const std::string gating = GetParam();
  test::TempDir tmp;
  VectorHeader header;
  const std::vector<VectorRow> rows = test::read_rows(kTrace, header);
  const SlotMap slots = make_slots(header);
  for (const char* mode : {"fast", "clocked"}) {
    const test::CliRun run = test::run_glint(
        tmp.path(), "sim " + test::shell_quote(kTrace) + " --unit pow --unit hast --unit " +
                        "schlick:divider=iterative --mode " + mode + " --activity " + gating +
                        " --json");
    ASSERT_EQ(run.status, 0) << run.err;
    const nlohmann::json report = nlohmann::json::parse(run.out);
    for (const nlohmann::json& lane : report.at("units")) {
      const std::string spec = lane.at("spec").get<std::string>();
      const auto unit = make_unit(parse_unit_spec(spec), slots);
      ActivityCounter counter(*unit, parse_gating(gating));
      for (const VectorRow& row : rows)
        counter.add(slots.slot(row), quantize_input(row.t, unit->in_format()));
      const nlohmann::json want = activity_json(counter.activity());
      EXPECT_EQ(lane.at("activity"), want) << mode << " " << spec;
      EXPECT_EQ(lane.at("activity").at("requests").get<std::size_t>(), rows.size());
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Gatings, SimActivity, ::testing::Values("none", "operand", "clock"));

TEST(SimActivityOption, RefusesAnUnknownGatingNamingTheOption) {
  test::TempDir tmp;
  const test::CliRun run =
      test::run_glint(tmp.path(), "sim " + test::shell_quote(kTrace) + " --activity always");
  EXPECT_EQ(run.status, 2) << run.err;
  EXPECT_NE(run.err.find("--activity"), std::string::npos) << run.err;
  EXPECT_NE(run.err.find("'always'"), std::string::npos) << run.err;
  EXPECT_TRUE(run.out.empty()) << run.out;
}

}  // namespace
}  // namespace glint
