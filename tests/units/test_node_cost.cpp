// The cost proxy at a real node (cost/node.h): every part priced in um2, the stages and the
// lane's own paths in ns, the critical path the slowest of them all, and the node's fanout
// effects where the hardware has them (buffered: the log of the loads).
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>
#include <vector>

#include "cost/node.h"
#include "reference/reference.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"
#include "units/slot_plan.h"

namespace glint {
namespace {

UnitCost lane(const std::string& spec, const std::vector<double>& shininess = {50}) {
  std::vector<MaterialParams> slots;
  for (double n : shininess) {
    const TauResult t = tau_power(n, 1e-3, 1.0);
    slots.push_back(MaterialParams{n, t.never_skip ? -1.0 : t.tau, t.always_skip});
  }
  return unit_cost(*make_unit(parse_unit_spec(spec), SlotPlan::per_slot(slots)));
}

const StageDelay* path(const UnitCost& c, const std::string& name) {
  for (const auto* list : {&c.stages, &c.lane_paths})
    for (const StageDelay& s : *list)
      if (s.stage == name) return &s;
  return nullptr;
}

TEST(NodeCost, OnlyTheBuiltInNode) {
  ASSERT_NE(find_node("osu018"), nullptr);
  EXPECT_EQ(find_node("osu018")->name, "osu018");
  EXPECT_EQ(find_node("tsmc7"), nullptr);
  EXPECT_EQ(node_names(), std::vector<std::string>{"osu018"});
}

TEST(NodeCost, AreaIsTheSumOfItsParts) {
  for (const char* spec : {"lut", "hast", "horner", "pow", "schlick", "lut:tables=ram"}) {
    const UnitCost c = lane(spec, {20, 50, 200});
    double sum = 0;
    for (const Primitive& p : c.inventory) {
      EXPECT_GT(p.um2, 0) << spec << ": " << p.where;
      sum += p.um2;
    }
    EXPECT_NEAR(c.area_um2, sum, 1e-6 * sum) << spec;
    // A real library's area per NAND2-sized GE: 0.18 um cells of 16-176 um2.
    EXPECT_GT(c.area_um2, 8 * c.area_ge) << spec;
    EXPECT_LT(c.area_um2, 30 * c.area_ge) << spec;
  }
}

TEST(NodeCost, CriticalPathIsTheSlowestStageOrLanePath) {
  for (const char* spec :
       {"lut", "hast", "horner:degree=5", "pow", "schlick", "schlick:divider=iterative"}) {
    const UnitCost c = lane(spec);
    double slowest = 0;
    std::string which;
    for (const auto* list : {&c.stages, &c.lane_paths})
      for (const StageDelay& s : *list) {
        EXPECT_GE(s.ns, node_osu018().reg_ns) << spec << ": " << s.stage;
        if (s.ns > slowest) {
          slowest = s.ns;
          which = s.stage;
        }
      }
    EXPECT_DOUBLE_EQ(c.critical_path_ns, slowest) << spec;
    EXPECT_EQ(c.critical_path_node, which) << spec;
    ASSERT_NE(path(c, "merge buffer read"), nullptr) << spec;
    ASSERT_NE(path(c, "merge buffer write"), nullptr) << spec;
    const nlohmann::json j = c.node_json();
    EXPECT_DOUBLE_EQ(j.at("max_clock_mhz").get<double>(), 1000.0 / slowest) << spec;
    EXPECT_EQ(j.at("paths").size(), c.stages.size() + c.lane_paths.size()) << spec;
  }
}

// The head register drives every entry's read mux through the buffer tree the flow builds: a
// deeper buffer of wider words reads slower, by the log of its loads, not their square (schlick's
// pipelined divider: a buffer of 20-odd entries), and OpenSTA's worst path of the deep lane is in
// its datapath (set_osu018.json: in -> mac), as the proxy's.
TEST(NodeCost, MergeBufferReadGrowsWithTheLogOfItsLoads) {
  const UnitCost shallow = lane("schlick:in=uq1.10,out=uq1.10");
  const UnitCost deep = lane("schlick:in=uq1.23,out=uq1.19");
  const StageDelay* a = path(shallow, "merge buffer read");
  const StageDelay* b = path(deep, "merge buffer read");
  ASSERT_TRUE(a && b);
  EXPECT_GT(b->ns, a->ns);
  EXPECT_LT(b->ns, 1.5 * a->ns);
  EXPECT_EQ(deep.critical_path_node, "stage 1");
}

// The generic gate-level figures are untouched by the node: the lane paths are not stages.
TEST(NodeCost, GateLevelsKeepTheirStages) {
  const UnitCost c = lane("schlick:in=uq1.23,out=uq1.19");
  for (const StageDelay& s : c.stages) EXPECT_EQ(s.stage.find("merge buffer"), std::string::npos);
  EXPECT_EQ(c.critical_stage.find("merge buffer"), std::string::npos);
  EXPECT_NE(path(c, "merge buffer read"), nullptr);
  const nlohmann::json j = c.to_json();
  EXPECT_FALSE(j.contains("area_um2"));
  EXPECT_FALSE(j.contains("lane_paths"));
}

// A RAM table is loaded through a write port: a lane path of its own; a ROM has none.
TEST(NodeCost, RamTablesHaveWritePorts) {
  const auto write_ports = [](const UnitCost& c) {
    return std::count_if(c.lane_paths.begin(), c.lane_paths.end(), [](const StageDelay& s) {
      return s.stage.find("write port") != std::string::npos;
    });
  };
  EXPECT_EQ(write_ports(lane("lut", {20, 50})), 0);
  EXPECT_GT(write_ports(lane("lut:tables=ram", {20, 50})), 0);
}

// The node's carry chains: a wider adder path is slower by about its width at ~0.1 ns a bit, where
// gate levels grow with log2 of it.
TEST(NodeCost, AdderDelayGrowsWithWidth) {
  const NodePart& a = node_osu018().adder;
  const double d16 = a.delay.at(16, 16, 0), d32 = a.delay.at(32, 32, 0);
  EXPECT_GT(d32 - d16, 16 * 0.05);
  EXPECT_LT(d32 - d16, 16 * 0.3);
}

// Arithmetic parts in a row overlap at the node (CostBuilder::close): each primitive of the chain
// counts its own delay times the factor its place gives it, the adder inside hast's parallel
// group (the slower branch's) included.
TEST(NodeCost, ArithmeticPartsInARowOverlap) {
  const NodeOverlap& o = node_osu018().overlap;
  ASSERT_LT(o.adder_before_multiplier, 1);
  for (const char* spec : {"lut", "hast", "horner", "pow", "schlick"}) {
    const UnitCost c = lane(spec);
    int before = 0;
    for (const StageDelay& s : c.stages) {
      double counted = node_osu018().reg_ns;
      for (std::size_t i = 0; i < s.parts.size(); ++i) {
        const StageDelay::Part& p = s.parts[i];
        counted += p.counted_ns;
        EXPECT_LE(p.counted_ns, p.ns + 1e-12) << spec << ": " << p.label;
        if (p.kind == "adder" && i + 1 < s.parts.size() && s.parts[i + 1].kind == "multiplier") {
          EXPECT_NEAR(p.counted_ns, o.adder_before_multiplier * p.ns, 1e-9) << spec;
          ++before;
        }
        if (p.kind == "multiplier") {
          EXPECT_DOUBLE_EQ(p.counted_ns, p.ns) << spec;
        }
      }
      EXPECT_NEAR(s.ns, counted, 1e-9) << spec << ": " << s.stage;
    }
    if (std::string(spec) != "schlick") {
      EXPECT_GT(before, 0) << spec;
    }
  }
}

// A lane's part keeps lane_area of its primitive's area (abc shares logic across parts);
// registers are as measured.
TEST(NodeCost, LaneAreaScalesTheUnfittedArea) {
  const NodeConstants& k = node_osu018();
  for (const char* spec : {"lut", "hast", "pow", "schlick:divider=iterative", "lut:tables=ram"}) {
    const UnitCost c = lane(spec, {20, 50});
    for (const Primitive& p : c.inventory) {
      EXPECT_GT(p.um2_unfitted, 0) << spec << ": " << p.where;
      if (p.kind == "register") {
        EXPECT_DOUBLE_EQ(p.um2, p.um2_unfitted) << spec;
      }
      if (p.node_part == "multiplier") {
        EXPECT_NEAR(p.um2, k.multiplier.lane_area * p.um2_unfitted, 1e-9) << spec;
      }
      if (p.node_part == "adder") {
        EXPECT_NEAR(p.um2, k.adder.lane_area * p.um2_unfitted, 1e-9) << spec;
      }
      EXPECT_NE(p.node_part, "other") << spec << ": " << p.where;
    }
  }
}

}  // namespace
}  // namespace glint
