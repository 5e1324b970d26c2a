// Energy of a request stream (eval/energy.h, cost/energy.h): the sum of its parts, what each
// gating mode saves, and per-request figures that do not depend on the stream's length.
#include <gtest/gtest.h>

#include <cctype>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "cost/energy.h"
#include "eval/activity.h"
#include "eval/energy.h"
#include "eval/evaluate.h"
#include "test_support.h"
#include "trace_unit.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"
#include "units/stages.h"
#include "vector_rows.h"

namespace glint {
namespace {

const EnergyWeights& osu018() {
  const EnergyWeights* w = find_energy("osu018");
  EXPECT_NE(w, nullptr);
  return *w;
}

LaneEnergy energy_of(const SpecularUnit& u, const std::vector<ActivityRequest>& stream, Gating g) {
  return lane_energy(unit_cost(u), measure_activity(u, stream, g), osu018());
}

// t codes spread over [0, 1]: a third of them at or below the threshold (skipped), the rest
// computed, in a scrambled order so that consecutive requests differ.
std::vector<ActivityRequest> mixed_stream(const SpecularUnit& u, std::size_t n) {
  const std::int64_t one = u.in_format().raw_one();
  std::vector<ActivityRequest> s;
  std::uint64_t x = 12345;
  for (std::size_t i = 0; i < n; ++i) {
    x = x * 6364136223846793005ull + 1442695040888963407ull;
    s.push_back({0, static_cast<std::int64_t>((x >> 11) % static_cast<std::uint64_t>(one + 1))});
  }
  return s;
}

class Energy : public ::testing::TestWithParam<std::string> {};

// The cost's stages follow the unit's layout one for one (lane_energy places each part in the
// layout's stage of the same index).
TEST_P(Energy, CostStagesFollowTheLayout) {
  const test::TraceUnit b = test::trace_unit(GetParam());
  EXPECT_EQ(unit_cost(*b.unit).stages.size(), b.unit->stages().stages().size());
}

TEST_P(Energy, IsTheSumOfItsParts) {
  const test::TraceUnit b = test::trace_unit(GetParam());
  const LaneEnergy e = energy_of(*b.unit, mixed_stream(*b.unit, 300), Gating::kOperand);
  EnergyParts sum;
  for (const StageEnergy& s : e.stages) {
    EXPECT_GE(s.pj.register_pj, 0) << s.stage;
    EXPECT_GE(s.pj.datapath_pj, 0) << s.stage;
    sum += s.pj;
  }
  EXPECT_DOUBLE_EQ(sum.total(), e.total.total());
  EXPECT_DOUBLE_EQ(e.total.total(), e.total.register_pj + e.total.clock_pj + e.total.datapath_pj +
                                        e.total.leakage_pj);
  for (double part :
       {e.total.register_pj, e.total.clock_pj, e.total.datapath_pj, e.total.leakage_pj})
    EXPECT_GT(part, 0);
  EXPECT_EQ(e.stages.front().stage, "comparator");
  EXPECT_EQ(e.stages.back().stage, "merge buffer");
  EXPECT_DOUBLE_EQ(e.per_request() * 300, e.total.total());
  const nlohmann::json j = energy_json(e);
  EXPECT_DOUBLE_EQ(j.at("pj_per_request").get<double>(), e.per_request());
  double stages = 0;
  for (const auto& s : j.at("stages")) stages += s.at("total").get<double>();
  EXPECT_NEAR(stages, j.at("per_request").at("total").get<double>(), 1e-9 * stages);
}

// Operand isolation saves the skipped requests' datapath and register toggles: less than none
// on a stream with skipped requests, the same on one without.
TEST_P(Energy, OperandGatingSavesOnlyWhatIsSkipped) {
  const test::TraceUnit b = test::trace_unit(GetParam());
  const SpecularUnit& u = *b.unit;
  const std::vector<ActivityRequest> mixed = mixed_stream(u, 300);
  const LaneEnergy none = energy_of(u, mixed, Gating::kNone);
  const LaneEnergy operand = energy_of(u, mixed, Gating::kOperand);
  ASSERT_LT(operand.computed, operand.requests) << "the stream should skip some requests";
  EXPECT_LT(operand.total.total(), none.total.total());
  EXPECT_LT(operand.total.datapath_pj, none.total.datapath_pj);
  // Held out of the datapath, a skipped request does not wait for its initiation interval: the
  // lane spends fewer cycles where II > 1, as many where II = 1.
  if (u.timing().ii > 1) {
    EXPECT_LT(operand.cycles, none.cycles);
    EXPECT_LT(operand.total.clock_pj, none.total.clock_pj);
  } else {
    EXPECT_EQ(operand.cycles, none.cycles);
    EXPECT_DOUBLE_EQ(operand.total.clock_pj, none.total.clock_pj);
  }
  std::vector<ActivityRequest> computed;
  for (const ActivityRequest& q : mixed)
    if (!u.skip(q.slot, q.t_raw)) computed.push_back(q);
  EXPECT_DOUBLE_EQ(energy_of(u, computed, Gating::kOperand).total.total(),
                   energy_of(u, computed, Gating::kNone).total.total());
}

// Clock gating stops the stage registers' clock on the skipped requests' cycles: it saves clock
// energy and nothing else.
TEST_P(Energy, ClockGatingSavesClockEnergyOnly) {
  const test::TraceUnit b = test::trace_unit(GetParam());
  const std::vector<ActivityRequest> mixed = mixed_stream(*b.unit, 300);
  const LaneEnergy operand = energy_of(*b.unit, mixed, Gating::kOperand);
  const LaneEnergy clock = energy_of(*b.unit, mixed, Gating::kClock);
  EXPECT_LT(clock.total.clock_pj, operand.total.clock_pj);
  EXPECT_DOUBLE_EQ(clock.total.register_pj, operand.total.register_pj);
  EXPECT_DOUBLE_EQ(clock.total.datapath_pj, operand.total.datapath_pj);
  EXPECT_DOUBLE_EQ(clock.total.leakage_pj, operand.total.leakage_pj);
}

// The same requests twice over: the lane's cycles per request are the same but for the
// pipeline's fill and drain (a few cycles), the clock and leakage energy per cycle are the same
// (every flip-flop clocked every cycle but with clock gating), and the toggles' energy per
// request is within a few per cent (only the reset state's first toggles differ).
TEST_P(Energy, PerRequestEnergyDoesNotDependOnTheStreamLength) {
  const test::TraceUnit b = test::trace_unit(GetParam());
  std::vector<ActivityRequest> once = mixed_stream(*b.unit, 400);
  std::vector<ActivityRequest> twice = once;
  twice.insert(twice.end(), once.begin(), once.end());
  for (Gating g : {Gating::kNone, Gating::kOperand, Gating::kClock}) {
    const LaneEnergy a = energy_of(*b.unit, once, g), c = energy_of(*b.unit, twice, g);
    const auto per = [](double pj, std::uint64_t n) { return pj / static_cast<double>(n); };
    const auto fill = static_cast<double>(b.unit->timing().latency + 2);
    EXPECT_NEAR(static_cast<double>(c.cycles), 2.0 * static_cast<double>(a.cycles), fill);
    if (g != Gating::kClock) {
      EXPECT_NEAR(per(c.total.clock_pj, c.cycles), per(a.total.clock_pj, a.cycles),
                  1e-9 * per(a.total.clock_pj, a.cycles));
    }
    EXPECT_NEAR(per(c.total.leakage_pj, c.cycles), per(a.total.leakage_pj, a.cycles),
                1e-9 * per(a.total.leakage_pj, a.cycles));
    const double dyn_a = per(a.total.register_pj + a.total.datapath_pj, a.requests);
    const double dyn_c = per(c.total.register_pj + c.total.datapath_pj, c.requests);
    EXPECT_NEAR(dyn_c, dyn_a, 0.03 * dyn_a) << to_string(g);
  }
}

INSTANTIATE_TEST_SUITE_P(Units, Energy,
                         ::testing::Values("pow", "schlick", "hast", "horner", "lut", "sfu", "pwp",
                                           "schlick:divider=iterative", "lut:tables=ram"),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

// A part's switching bits follow its widths: a multiplier's grow with the product of its
// operands' widths, an adder's with its width.
TEST(PartSwitching, ScalesWithThePartsSize) {
  const EnergyWeights& w = osu018();
  Primitive mul{"multiplier", 12, 10, 1, 0, ""}, add{"adder", 16, 0, 1, 0, ""};
  EXPECT_DOUBLE_EQ(part_switching(mul, w).bits, 120);
  EXPECT_DOUBLE_EQ(part_switching(add, w).bits, 16);
  mul.width_a = 24;
  EXPECT_DOUBLE_EQ(part_switching(mul, w).pj(), 2 * 120 * w.multiplier_bit);
  EXPECT_DOUBLE_EQ(part_switching(Primitive{"register", 16, 0, 1, 0, ""}, w).pj(), 0);
  EXPECT_EQ(find_energy("no-such-node"), nullptr);
}

}  // namespace
}  // namespace glint
