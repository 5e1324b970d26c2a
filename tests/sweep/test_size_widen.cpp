// How `glint size` widens a grid (sweep/size_widen.h), on hand-made costs and margins: which key
// takes which value beyond which end, and why a grid stops.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <string>
#include <vector>

#include "sweep/grid.h"
#include "sweep/size_widen.h"

namespace {

using glint::decide_widening;
using glint::GridStep;
using glint::parse_grid;
using glint::WidenStop;

constexpr double kInf = std::numeric_limits<double>::infinity();

// lut:out=uq1.10|uq1.12,bits=4..6: configurations 0-2 are out=uq1.10 with bits 4, 5, 6, and 3-5
// out=uq1.12 with the same bits.
struct Fixture {
  glint::Grid grid = parse_grid("lut:out=uq1.10|uq1.12,bits=4..6");
  std::vector<glint::SweepConfig> configs = glint::expand_grids({grid});
  std::vector<double> cost = {100, 200, 300, 120, 240, 360};
  glint::WidenDecision decide(const std::vector<bool>& meets, const std::vector<double>& margin,
                              std::size_t rounds_left = 8) const {
    return decide_widening(grid, 0, configs, cost, meets, margin, rounds_left);
  }
};

std::vector<std::string> steps(const glint::WidenDecision& d) {
  std::vector<std::string> out;
  for (const GridStep& s : d.steps)
    out.push_back(s.key + "=" + s.value + (s.largest ? " (largest)" : " (smallest)"));
  return out;
}

using V = std::vector<std::string>;

TEST(SizeWiden, MetBudgetWidensTowardsTheCheaperEnd) {
  const Fixture f;
  // The cheapest meeting is out=uq1.10,bits=5 (200): out=uq1.12 inwards costs more, so a narrower
  // output may be cheaper still; bits=5 is inside its grid.
  const auto d = f.decide({false, true, true, false, true, true}, {1, -0.1, -0.5, 1, -0.2, -0.6});
  EXPECT_FALSE(d.stop) << d.why;
  EXPECT_EQ(steps(d), (V{"out=uq1.9 (smallest)"}));

  // The cheapest meeting is out=uq1.12,bits=5 and out=uq1.10 inwards is cheaper (but misses): no
  // end improves outward.
  const auto met = f.decide({false, false, false, false, true, false}, {1, 0.1, 0.1, 1, -0.2, 0.3});
  EXPECT_EQ(met.stop, WidenStop::kMet);
  EXPECT_NE(met.why.find("lut:out=uq1.12,bits=5"), std::string::npos) << met.why;
}

TEST(SizeWiden, MissedBudgetWidensWhereTheMissShrinks) {
  const Fixture f;
  const std::vector<bool> none(6, false);
  // Closest: out=uq1.10,bits=6 (margin 1); bits=5 (by 1) and out=uq1.12 (by 0.5) inwards miss by
  // more: bits, the steeper, widens first.
  const std::vector<double> margin = {3, 2, 1, 3.5, 2.5, 1.5};
  const auto d = f.decide(none, margin);
  EXPECT_FALSE(d.stop) << d.why;
  EXPECT_EQ(steps(d), (V{"bits=7 (largest)"}));
  // out, when it is the steeper.
  EXPECT_EQ(steps(f.decide(none, {3, 2, 1, 3.5, 2.5, 2.5})), (V{"out=uq1.9 (smallest)"}));

  // The same with no round left: the round cap.
  EXPECT_EQ(f.decide(none, margin, 0).stop, WidenStop::kRoundCap);

  // A miss of 20 that the last values closed by 0.15 in all: more than 8 rounds at that rate.
  const auto slow = f.decide(none, {30, 20.1, 20, 31, 21, 20.05});
  EXPECT_EQ(slow.stop, WidenStop::kTooSlow);
  EXPECT_NE(slow.why.find("8 rounds"), std::string::npos) << slow.why;
  // ... but within 200 rounds it would widen.
  EXPECT_FALSE(f.decide(none, {30, 20.1, 20, 31, 21, 20.05}, 200).stop);

  // Closest inside the bits range (bits=5, tied with out=uq1.12,bits=5 and cheaper): no end
  // towards which the miss shrinks.
  const auto flat = f.decide(none, {3, 1, 2, 3, 1, 2});
  EXPECT_EQ(flat.stop, WidenStop::kNoImprovement);
  EXPECT_NE(flat.why.find("lut:out=uq1.10,bits=5"), std::string::npos) << flat.why;

  // No configuration with a value.
  EXPECT_EQ(f.decide(none, std::vector<double>(6, kInf)).stop, WidenStop::kNoValue);
}

TEST(SizeWiden, KeyTableEndsTheRange) {
  const glint::Grid grid = parse_grid("lut:bits=15..16");
  const auto configs = glint::expand_grids({grid});
  const auto d = decide_widening(grid, 0, configs, {100, 200}, {false, false}, {2, 1}, 8);
  EXPECT_EQ(d.stop, WidenStop::kRangeEnd);
  EXPECT_NE(d.why.find("1..16"), std::string::npos) << d.why;  // the key table's range
  // A steeper key at its range's end leaves the step to the next one.
  const glint::Grid two = parse_grid("lut:out=uq1.10|uq1.12,bits=15..16");
  const auto both = decide_widening(two, 0, glint::expand_grids({two}), {100, 200, 120, 240},
                                    {false, false, false, false}, {3, 1, 3.5, 1.5}, 8);
  ASSERT_FALSE(both.stop) << both.why;
  ASSERT_EQ(both.steps.size(), 1u);
  EXPECT_EQ(both.steps[0].key, "out");
  EXPECT_EQ(both.steps[0].value, "uq1.9");
  // Formats step by one fraction bit either way.
  const glint::Grid out = parse_grid("lut:out=uq1.10|uq1.12");
  EXPECT_EQ(glint::probe_step(out, 0, false), "uq1.9");
  EXPECT_EQ(glint::probe_step(out, 0, true), "uq1.13");
  EXPECT_EQ(glint::probe_step(parse_grid("lut:bits=1..3"), 0, false), std::nullopt);
}

std::vector<std::string> specs(const std::vector<glint::Grid>& grids) {
  std::vector<std::string> out;
  for (const auto& c : glint::expand_grids(grids)) out.push_back(c.spec);
  return out;
}

TEST(SizeWiden, WidenedGridIsAGridAndTheDifferenceHoldsTheNewConfigurationsOnce) {
  const glint::Grid g = parse_grid("lut:in=uq1.12|uq1.16,out=uq1.10|uq1.12,bits=5..7");
  const glint::Grid w =
      glint::widen_grid(g, {GridStep{1, "out", "uq1.9", false}, GridStep{2, "bits", "8", true}});
  EXPECT_EQ(w.text, "lut:in=uq1.12|uq1.16,out=uq1.9|uq1.10|uq1.12,bits=5..8");
  // Its text as a --grid sweeps the same configurations in the same order.
  EXPECT_EQ(specs({parse_grid(w.text)}), specs({w}));
  const std::vector<glint::Grid> parts = glint::grid_difference(g, w);
  std::vector<std::string> added = specs(parts);
  const std::vector<std::string> old = specs({g});
  std::multiset<std::string> all(added.begin(), added.end());
  all.insert(old.begin(), old.end());
  const std::vector<std::string> wide = specs({w});
  EXPECT_EQ(all, std::multiset<std::string>(wide.begin(), wide.end()));
  EXPECT_EQ(added.size(), w.size() - g.size());
}

}  // namespace
