// Switching activity (eval/activity.h): register toggles counted from the staged evaluation, and
// what each gating mode does with the requests the comparator skips.
#include <gtest/gtest.h>

#include <algorithm>
#include <bitset>
#include <cctype>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "eval/activity.h"
#include "eval/evaluate.h"
#include "io/vectors.h"
#include "test_support.h"
#include "trace_unit.h"
#include "units/catalogue.h"
#include "units/stages.h"
#include "vector_rows.h"

namespace glint {
namespace {

// The toggles between two staged evaluations, register by register at its width: what the
// pipeline's registers change when request b follows request a.
std::uint64_t toggles_between(const SpecularUnit& u, std::int64_t a, std::int64_t b) {
  std::vector<std::int64_t> va(u.stages().size()), vb(u.stages().size());
  u.eval_staged(0, a, va.data());
  u.eval_staged(0, b, vb.data());
  std::uint64_t sum = 0;
  const StageLayout& layout = u.stages();
  for (int p = 1; p <= layout.latency(); ++p) {
    const Stage& s = layout.stage_at(p);
    for (std::size_t r = 0; r < s.registers.size(); ++r) {
      const std::size_t i = layout.offset(p) + r;
      const int w = s.registers[r].format.width();
      const std::uint64_t mask = (std::uint64_t{1} << w) - 1;
      sum += std::bitset<64>(
                 (static_cast<std::uint64_t>(va[i]) ^ static_cast<std::uint64_t>(vb[i])) & mask)
                 .count();
    }
  }
  return sum;
}

class Activity : public ::testing::TestWithParam<std::string> {};

// Alternating two computed requests toggles, each time, exactly the bits their registers differ
// in; repeating one request toggles nothing after the first.
TEST_P(Activity, CountsTheBitsThatDifferBetweenConsecutiveRequests) {
  const test::TraceUnit b = test::trace_unit(GetParam());
  const SpecularUnit& u = *b.unit;
  const std::int64_t one = u.in_format().raw_one();
  const std::int64_t a = one, c = one - one / 16;  // both far above the threshold
  ASSERT_FALSE(u.skip(0, a));
  ASSERT_FALSE(u.skip(0, c));
  const std::uint64_t ac = toggles_between(u, a, c);
  ASSERT_GT(ac, 0u) << "two different inputs should differ in some register";
  std::vector<ActivityRequest> alternating;
  for (int i = 0; i < 10; ++i) alternating.push_back({0, i % 2 ? c : a});
  for (Gating g : {Gating::kNone, Gating::kOperand, Gating::kClock}) {
    const LaneActivity act = measure_activity(u, alternating, g);
    EXPECT_EQ(act.requests, 10u);
    EXPECT_EQ(act.computed, 10u);
    // From reset (every register 0) to a: the bits a's registers hold.
    std::vector<std::int64_t> va(u.stages().size());
    u.eval_staged(0, a, va.data());
    std::uint64_t from_reset = 0;
    for (int p = 1; p <= u.stages().latency(); ++p) {
      const Stage& s = u.stages().stage_at(p);
      for (std::size_t r = 0; r < s.registers.size(); ++r) {
        const int w = s.registers[r].format.width();
        from_reset += std::bitset<64>(static_cast<std::uint64_t>(va[u.stages().offset(p) + r]) &
                                      ((std::uint64_t{1} << w) - 1))
                          .count();
      }
    }
    EXPECT_EQ(act.toggles(), from_reset + 9 * ac) << to_string(g);
  }
  std::vector<ActivityRequest> same(10, ActivityRequest{0, a});
  const LaneActivity once = measure_activity(u, {ActivityRequest{0, a}}, Gating::kNone);
  EXPECT_EQ(measure_activity(u, same, Gating::kNone).toggles(), once.toggles());
}

// A skipped request: fed to the datapath with gating none (it toggles as a computed one would),
// held out of it with operand and clock gating (no toggle), and unclocked with clock gating.
TEST_P(Activity, GatingDecidesWhatASkippedRequestCosts) {
  const test::TraceUnit b = test::trace_unit(GetParam());
  const SpecularUnit& u = *b.unit;
  ASSERT_TRUE(u.comparator_enabled());
  const std::int64_t one = u.in_format().raw_one();
  const std::int64_t skipped = 1;  // t just above 0: far below any threshold
  ASSERT_TRUE(u.skip(0, skipped));
  const std::vector<ActivityRequest> stream = {{0, one}, {0, skipped}, {0, one}, {0, skipped}};
  const LaneActivity none = measure_activity(u, stream, Gating::kNone);
  const LaneActivity operand = measure_activity(u, stream, Gating::kOperand);
  const LaneActivity clock = measure_activity(u, stream, Gating::kClock);
  for (const LaneActivity* a : {&none, &operand, &clock}) EXPECT_EQ(a->computed, 2u);
  const LaneActivity first = measure_activity(u, {ActivityRequest{0, one}}, Gating::kNone);
  // Operand isolation: the registers hold `one`'s values through the skipped requests.
  EXPECT_EQ(operand.toggles(), first.toggles());
  EXPECT_EQ(clock.toggles(), first.toggles());
  EXPECT_EQ(none.toggles(), first.toggles() + 3 * toggles_between(u, one, skipped));
  EXPECT_GT(none.toggles(), operand.toggles());
  // The lane's schedule, from reset to the last retire (timing/timing.h; the merge buffer has a
  // credit for each of the four): with gating none every request enters the datapath and waits
  // for its initiation interval, the fourth issuing at 3 II and leaving L + 1 edges later. Held
  // out, a skipped request issues the cycle after the previous one and waits in the merge buffer
  // for the computed one ahead of it, so the second computed request issues at max(2, II).
  const UnitTiming t = u.timing();
  ASSERT_GE(t.buffer_depth, 4);
  const auto ii = static_cast<std::uint64_t>(t.ii), lat = static_cast<std::uint64_t>(t.latency);
  EXPECT_EQ(none.cycles, 3 * ii + lat + 2);
  EXPECT_EQ(operand.cycles, std::max<std::uint64_t>(2, ii) + lat + 3);
  EXPECT_EQ(clock.cycles, operand.cycles);
  // Every bit clocked on every cycle of the lane's but where clock gating stops it: then the
  // stage registers run II cycles for each of the two computed requests.
  std::uint64_t bits = 0;
  for (const StageActivity& s : none.stages) bits += static_cast<std::uint64_t>(s.bits);
  EXPECT_GT(bits, 0u);
  EXPECT_EQ(none.clocked_bits(), bits * none.cycles);
  EXPECT_EQ(operand.clocked_bits(), bits * operand.cycles);
  EXPECT_EQ(clock.clocked_bits(), bits * 2 * ii);
}

// The lane's control flip-flops (hdl/lane.cpp) on a stream the comparator skips whole: each
// request bypasses the cycle after the previous one and leaves as it arrives, so no merge-buffer
// entry is written, no position's valid bit nor the II counter moves, the bypass valid bit rises
// once and falls once, in_flight goes 0 -> 1 at the first issue and back after the last retire,
// and the issue tag, the head, the bypass tag and the L + 1 position tags each step through
// 0, 1, .., B - 1, 0, .. once a request.
TEST_P(Activity, ControlTogglesFollowTheLanesSchedule) {
  const test::TraceUnit b = test::trace_unit(GetParam());
  const SpecularUnit& u = *b.unit;
  ASSERT_TRUE(u.comparator_enabled());
  ASSERT_TRUE(u.skip(0, 1));
  const std::size_t n = 23;
  const LaneActivity a =
      measure_activity(u, std::vector<ActivityRequest>(n, {0, 1}), Gating::kOperand);
  const UnitTiming t = u.timing();
  const auto depth = static_cast<std::uint64_t>(t.buffer_depth);
  std::uint64_t steps = 0;
  for (std::uint64_t i = 0; i < n; ++i)
    steps += std::bitset<64>((i % depth) ^ ((i + 1) % depth)).count();
  const auto tags = static_cast<std::uint64_t>(3 + t.latency + 1);
  EXPECT_EQ(a.control_toggles, 2 + 2 + tags * steps);
  EXPECT_EQ(a.cycles, n + 1);  // the last bypasses at n - 1 and leaves at n
}

INSTANTIATE_TEST_SUITE_P(Units, Activity,
                         ::testing::Values("pow", "schlick", "hast", "horner", "lut", "sfu",
                                           "schlick:divider=iterative"),
                         [](const ::testing::TestParamInfo<std::string>& i) {
                           std::string n = i.param;
                           for (char& ch : n)
                             if (!std::isalnum(static_cast<unsigned char>(ch))) ch = '_';
                           return n;
                         });

TEST(Gating, ParsesItsThreeModesAndNamesAnythingElse) {
  EXPECT_EQ(parse_gating("none"), Gating::kNone);
  EXPECT_EQ(parse_gating("operand"), Gating::kOperand);
  EXPECT_EQ(parse_gating("clock"), Gating::kClock);
  for (Gating g : {Gating::kNone, Gating::kOperand, Gating::kClock})
    EXPECT_EQ(parse_gating(to_string(g)), g);
  try {
    parse_gating("always");
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'always'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace glint
