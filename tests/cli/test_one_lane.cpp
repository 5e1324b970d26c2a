// One lane, one price: for the same unit spec, requests and chip, every command that prices a lane
// (render, sim, sweep) reports the same area, critical path and operations and states the same
// chip, and `glint synth` of what `glint rtl` writes for it is within the proxy's stated
// tolerance (src/cost/README.md: +-10 %), coloured lights and a chip of given capacity included.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>

#include "test_support.h"

namespace glint {
namespace {

using nlohmann::json;
using test::CliRun;
using test::shell_quote;

const std::string kSrc = GLINT_SOURCE_DIR;

json run_json(const test::TempDir& dir, const std::string& args) {
  const CliRun r = test::run_glint(dir.path(), args);
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  return r.status == 0 ? json::parse(r.out) : json::object();
}

// Operations per kind (sim and render list the kinds a lane executes, the sweep every kind with
// its 0s).
void expect_same_operations(const json& a, const json& b, const std::string& what) {
  for (const auto& [kind, n] : a.items())
    EXPECT_EQ(n.get<double>(), b.value(kind, 0.0)) << what << " " << kind;
  for (const auto& [kind, n] : b.items())
    EXPECT_EQ(n.get<double>(), a.value(kind, 0.0)) << what << " " << kind;
}

// The small scene has a coloured light: before, sim priced a colour stage that render lacked.
TEST(OneLane, RenderSimAndSweepPriceTheSameLaneOnEveryChip) {
  test::TempDir dir;
  const std::string scene = shell_quote(kSrc + "/traces/scenes/small.json");
  for (const std::string chip : {"", "--chip ram", "--chip ram:materials=6,slots=16"}) {
    for (const std::string spec :
         {"lut:in=uq1.16,out=uq1.9,bits=6", "hast", "schlick", "pow", "horner:degree=3"}) {
      SCOPED_TRACE(spec + " " + chip);
      const json render = run_json(dir, "render " + scene + " -o out --write-vectors req.vec " +
                                            "--json --unit " + spec + " " + chip);
      const json sim = run_json(dir, "sim req.vec --json --unit " + spec + " " + chip);
      const json sweep = run_json(dir, "sweep req.vec --json --grid " + spec + " " + chip);
      ASSERT_EQ(render.at("units").size(), 1u);
      const json &r = render.at("units")[0], &s = sim.at("units")[0], &w = sweep.at("results")[0];
      EXPECT_EQ(r.at("area_ge"), s.at("area").at("ge"));
      EXPECT_EQ(w.at("area_ge"), s.at("area").at("ge"));
      EXPECT_EQ(r.at("critical_path"), s.at("critical_path").at("delay"));
      EXPECT_EQ(w.at("critical_path"), s.at("critical_path").at("delay"));
      expect_same_operations(r.at("operations"), s.at("operations"), "render vs sim");
      expect_same_operations(w.at("operations").at("total"), s.at("operations"), "sweep vs sim");
      EXPECT_EQ(render.at("chip"), sim.at("chip"));
      EXPECT_EQ(sweep.at("chip"), sim.at("chip"));
      EXPECT_EQ(sim.at("chip").at("colour_stage"), false);
      EXPECT_EQ(sim.at("chip").at("spec"), chip.empty() ? "rom" : chip.substr(7));
      EXPECT_EQ(s.at("elaboration").at("storage"), chip.empty() ? "rom" : "ram");
    }
  }
}

// The chip is printed in every text report, default or given.
TEST(OneLane, EveryTableHeaderStatesTheChip) {
  test::TempDir dir;
  const std::string vec = shell_quote(kSrc + "/traces/blinn_colored.vec");
  for (const std::string& cmd :
       {"eval " + vec, "sim " + vec,
        "render " + shell_quote(kSrc + "/traces/scenes/small.json") + " -o out"}) {
    SCOPED_TRACE(cmd);
    const CliRun rom = test::run_glint(dir.path(), cmd + " --unit lut");
    EXPECT_EQ(rom.status, 0) << rom.err;
    EXPECT_NE(rom.out.find("chip: rom (default): ROMs of this input's"), std::string::npos)
        << rom.out;
    const CliRun ram = test::run_glint(dir.path(), cmd + " --unit lut --chip ram:materials=8");
    EXPECT_EQ(ram.status, 0) << ram.err;
    EXPECT_NE(ram.out.find("chip: ram:materials=8: loadable tables of 8 materials"),
              std::string::npos)
        << ram.out;
  }
}

// What `glint rtl` writes for a coloured input on a chip of given capacity, synthesized, is what
// sim prices (within the calibration's tolerance), and its co-simulation is a ctest of its own
// (rtl.lut.chip_capacity, rtl.pow.chip_capacity).
TEST(OneLane, SynthesisOfTheRtlIsWithinTheProxyTolerance) {
  if (std::system("command -v yosys > /dev/null 2>&1") != 0) GTEST_SKIP() << "yosys not on PATH";
  test::TempDir dir;
  const std::string vec = shell_quote(kSrc + "/traces/blinn_colored.vec");
  for (const std::string spec : {"lut:bits=4,in=uq1.12", "pow:in=uq1.12,out=uq1.10"}) {
    SCOPED_TRACE(spec);
    const std::string args = spec + " --vectors " + vec + " --chip ram:materials=8,slots=8";
    const json synth = run_json(dir, "synth " + args + " --json");
    const json sim =
        run_json(dir, "sim " + vec + " --json --chip ram:materials=8,slots=8 --unit " + spec);
    const double proxy = sim.at("units")[0].at("area").at("ge").get<double>();
    const double yosys = synth.at("ge").get<double>();
    EXPECT_NEAR(proxy / yosys, 1.0, 0.10) << "proxy " << proxy << " GE, synthesis " << yosys;
  }
}

}  // namespace
}  // namespace glint
