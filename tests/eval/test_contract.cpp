// The accuracy contract as the reports state it (src/eval/contract.h): on the shipped traces every
// observed part stays within its bound and the total within the stated total, on the scalar lobe
// and weighted; always-skipped slots are named and kept out of the bounds; weak configurations
// say so (contract bound/none) instead of passing silently; refusals name their reason.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "eval/contract.h"
#include "eval/evaluate.h"
#include "io/vectors.h"
#include "test_support.h"

namespace glint {
namespace {

const std::string kTraces = std::string(GLINT_SOURCE_DIR) + "/traces/";

std::vector<UnitStats> evaluate(const std::string& trace, const std::vector<std::string>& specs,
                                int display_bits = 8) {
  std::vector<UnitSpec> parsed;
  for (const auto& s : specs.empty() ? unit_names() : specs) parsed.push_back(parse_unit_spec(s));
  VectorReader reader(kTraces + trace);
  Evaluator ev(reader.header(), parsed, display_bits);
  VectorRow row;
  while (reader.next(row)) ev.add(row);
  return ev.stats();
}

void expect_within_bounds(const UnitStats& s, const std::string& what) {
  const ErrorParts b = s.bound();
  // Each part's observed maximum is one of the values its bound is the maximum of (1e-12: the
  // stream's t and the contract's code values are the same doubles, summed in another order).
  const double slack = 1 + 1e-12;
  EXPECT_LE(s.input.max_abs, b.input * slack) << what;
  EXPECT_LE(s.parameter.max_abs, b.parameter * slack) << what;
  EXPECT_LE(s.approximation.max_abs, b.approximation * slack) << what;
  EXPECT_LE(s.datapath.max_abs, b.datapath * slack) << what;
  EXPECT_LE(s.skip.max_abs, b.skip * slack) << what;
  EXPECT_LE(s.total.max_abs, b.total()) << what;
  EXPECT_LE(s.weighted.max_abs, s.weighted_bound()) << what;
  double stated_ulps = 0;
  for (const SlotContract& c : s.slots) stated_ulps = std::max(stated_ulps, c.datapath_ulps);
  EXPECT_LE(s.max_ulps(), stated_ulps * slack) << what;
  for (const SlotContract& c : s.slots) {
    if (c.always_skipped) continue;
    EXPECT_LE(c.bound.skip, 1.0) << what << " " << c.name;
    EXPECT_TRUE(c.exact) << what << " " << c.name;
  }
}

TEST(Contract, EveryShippedTraceWithinItsBounds) {
  for (const char* trace : {"phong_basic.vec", "blinn_colored.vec", "multi_light.vec",
                            "gaussian.vec", "hard_cases.vec", "pixels.vec"}) {
    for (const UnitStats& s : evaluate(trace, {}))
      expect_within_bounds(s, std::string(trace) + " " + s.spec);
  }
}

TEST(Contract, NonDefaultSpecsWithinTheirBounds) {
  for (const char* spec :
       {"pow:n=uq13.2", "schlick:in=uq1.11,out=uq1.9", "hast:d=2,in=uq1.12", "hast:d=1",
        "horner:degree=3,method=ls", "horner:domain=full,method=robust", "lut:bits=3",
        "lut:bits=9,table_frac=20", "pow:skip=off", "schlick:skip=off"}) {
    for (const char* trace : {"phong_basic.vec", "hard_cases.vec", "multi_light.vec"})
      for (const UnitStats& s : evaluate(trace, {spec}))
        expect_within_bounds(s, std::string(trace) + " " + s.spec);
  }
}

TEST(Contract, AlwaysSkippedSlotIsNamedAndInNoBound) {
  // hard_cases' 'dim' material has c_y <= eps: every unit skips it everywhere.
  for (const UnitStats& s : evaluate("hard_cases.vec", {})) {
    int always = 0;
    for (const SlotContract& c : s.slots) {
      if (!c.always_skipped) continue;
      ++always;
      EXPECT_EQ(c.name, "material 'dim'") << s.name;
      EXPECT_LE(c.weight, 1e-3) << s.name;
    }
    EXPECT_EQ(always, 1) << s.name;
    EXPECT_GT(s.always_skipped_vectors, 0u) << s.name;
    // Its requests (t up to 1, where the lobe is 1.0) would have made max_abs 1.0.
    EXPECT_LT(s.total.max_abs, 1.0) << s.name;
    EXPECT_LT(s.bound().total(), 1.0) << s.name;
  }
}

TEST(Contract, DisplayBitsScaleTheLsbFigures) {
  const auto s8 = evaluate("phong_basic.vec", {"pow"}, 8).front();
  const auto s10 = evaluate("phong_basic.vec", {"pow"}, 10).front();
  const nlohmann::json e8 = s8.errors_json(), e10 = s10.errors_json();
  EXPECT_DOUBLE_EQ(e8.at("max_lsb").get<double>(), s8.total.max_abs * 255);
  EXPECT_DOUBLE_EQ(e10.at("max_lsb").get<double>(), s10.total.max_abs * 1023);
  EXPECT_DOUBLE_EQ(e10.at("bound_lsb").get<double>(), s10.bound().total() * 1023);
  EXPECT_GE(s10.mismatch, s8.mismatch);  // a finer display shows more differing codes
}

TEST(Contract, WeakConfigurationsSaySo) {
  const auto stats = evaluate(
      "phong_basic.vec", {"hast:guard=0", "pow:log_frac=4,y_frac=4", "hast", "schlick", "lut"});
  EXPECT_EQ(stats[0].contract(), ContractKind::kBound);  // guard=0: not faithful any more
  EXPECT_GT(stats[0].slots[0].datapath_ulps, 1.0);
  EXPECT_LE(stats[0].max_ulps(), stats[0].slots[0].datapath_ulps);
  EXPECT_EQ(stats[1].contract(), ContractKind::kNone);  // coarse tables: the whole range
  EXPECT_NE(stats[1].slots[0].reason.find("whole output range"), std::string::npos);
  EXPECT_EQ(stats[2].contract(), ContractKind::kFaithful);
  EXPECT_EQ(stats[3].contract(), ContractKind::kCorrectlyRounded);
  EXPECT_EQ(stats[4].contract(), ContractKind::kCorrectlyRounded);
}

// The label follows the stated error: a faithful datapath keeps its label while the sum of the
// computed parts stays below kNoContractFraction of the range, and is labelled none from there on,
// whatever its datapath budget; the reason says which.
TEST(Contract, NoneFromAQuarterOfTheRange) {
  ASSERT_EQ(kNoContractFraction, 0.25);
  for (const double ulps : {0.5, 0.75, 3.0}) {
    for (const double scale : {1 - 1e-9, 1.0, 1 + 1e-9, 3.88}) {
      SlotContract c;
      c.datapath_ulps = ulps;
      c.bound.input = 0.05;
      c.bound.parameter = 0.02;
      c.bound.datapath = 0.01;
      c.bound.approximation = kNoContractFraction * scale - 0.08;
      c.bound.skip = 1e-3;
      classify_contract(c);
      const std::string what =
          "ulps " + std::to_string(ulps) + ", sum " + std::to_string(c.bound.computed_sum());
      if (scale < 1) {
        EXPECT_EQ(c.kind, ulps <= 0.5  ? ContractKind::kCorrectlyRounded
                          : ulps < 1.0 ? ContractKind::kFaithful
                                       : ContractKind::kBound)
            << what;
        EXPECT_EQ(c.reason.find("stated error"), std::string::npos) << what << ": " << c.reason;
      } else {
        EXPECT_EQ(c.kind, ContractKind::kNone) << what;
        EXPECT_NE(c.reason.find(scale < 4 ? "1/4 of the output range" : "whole output range"),
                  std::string::npos)
            << what << ": " << c.reason;
      }
    }
  }
}

// On the shipped traces, slots on both sides of the fraction, each labelled by it.
TEST(Contract, ShippedSlotsLabelledByTheFraction) {
  int below = 0, above = 0;
  for (const char* trace : {"contract_cases.vec", "hard_cases.vec"}) {
    for (const UnitStats& s : evaluate(trace, {"schlick", "hast", "lut:bits=4",
                                               "horner:degree=6,method=ls,domain=full,"
                                               "constrain=off"})) {
      for (const SlotContract& c : s.slots) {
        if (c.always_skipped) continue;
        const bool none = c.bound.computed_sum() >= kNoContractFraction;
        (none ? above : below) += 1;
        EXPECT_EQ(c.kind == ContractKind::kNone, none)
            << trace << " " << s.name << " " << c.name << ": " << c.bound.computed_sum();
      }
    }
  }
  EXPECT_GT(below, 0);
  EXPECT_GT(above, 0);
}

TEST(Contract, OffGridInputsWithinTheTotalBound) {
  // Real t between the codes, where only the input part can account for the difference.
  VectorHeader h;
  h.eps = 1e-3;
  h.lights = 1;
  for (double n : {0.3, 1.03, 50.0, 1000.0}) {
    VectorMaterial m;
    m.name = "n" + std::to_string(static_cast<int>(n * 100));
    m.shininess = n;
    h.materials.push_back(m);
  }
  for (const std::string& spec : unit_names()) {
    std::vector<UnitSpec> specs{parse_unit_spec(spec)};
    Evaluator ev(h, specs);
    VectorRow row;
    for (std::uint32_t mat = 0; mat < h.materials.size(); ++mat) {
      row.material = mat;
      for (int k = 0; k <= 32768; k += 7) {
        for (double off : {-0.5, -0.4999, 0.25, 0.4999, 0.5}) {
          row.t = (k + off) / 32768.0;
          ev.add(row);
        }
      }
    }
    expect_within_bounds(ev.stats().front(), spec + " off-grid");
    EXPECT_GT(ev.stats().front().input.max_abs, 0.0) << spec;
  }
}

int run_glint(const std::string& args, const test::TempDir& dir) {
  const std::string cmd = test::shell_quote(std::string(GLINT_BINARY_DIR) + "/glint") + " " + args +
                          " >" + test::shell_quote(dir.file("out")) + " 2>" +
                          test::shell_quote(dir.file("err"));
  const int st = std::system(cmd.c_str());
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

TEST(Contract, RefusalsNameTheirReason) {
  const test::TempDir dir;
  const std::string vec = test::shell_quote(kTraces + "phong_basic.vec");
  EXPECT_EQ(run_glint("eval " + vec + " --unit hast:in=uq1.0", dir), 2);
  const std::string err = test::read_file(dir.path() / "err");
  EXPECT_NE(err.find("'hast'"), std::string::npos) << err;
  EXPECT_NE(err.find("key 'in' = 'uq1.0'"), std::string::npos) << err;
  EXPECT_EQ(run_glint("eval " + vec + " --display-bits 17", dir), 2);
  EXPECT_NE(test::read_file(dir.path() / "err").find("--display-bits"), std::string::npos);
  // A material the n register cannot hold is named.
  const std::string big = dir.file("big.vec");
  std::ofstream(big) << "glint-vectors 1\neps 1e-3\nlights 1\n"
                     << "material ok specular=1,1,1 lobe=phong shininess=50\n"
                     << "material huge specular=1,1,1 lobe=phong shininess=20000\n"
                     << "columns t material\ndata\n0.9 ok\n0.95 huge\n";
  EXPECT_EQ(run_glint("eval " + test::shell_quote(big) + " --unit schlick", dir), 2);
  EXPECT_NE(test::read_file(dir.path() / "err").find("material 'huge'"), std::string::npos)
      << test::read_file(dir.path() / "err");
}

}  // namespace
}  // namespace glint
