// The cost proxy at a real node (cost/node.h): every part priced in um2, the stages and the
// lane's own paths in ns, the critical path the slowest of them all, and the node's fanout
// effects where the hardware has them.
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

// The head register drives every entry's read mux unbuffered: a deeper buffer of wider words
// reads slower, faster than linearly (schlick's pipelined divider: a buffer of 20-odd entries).
TEST(NodeCost, MergeBufferReadSlowsWithItsLoads) {
  const UnitCost shallow = lane("schlick:in=uq1.10,out=uq1.10");
  const UnitCost deep = lane("schlick:in=uq1.23,out=uq1.19");
  const StageDelay* a = path(shallow, "merge buffer read");
  const StageDelay* b = path(deep, "merge buffer read");
  ASSERT_TRUE(a && b);
  EXPECT_GT(b->ns, 1.5 * a->ns);
  EXPECT_EQ(deep.critical_path_node, "merge buffer read");
}

// The generic gate-level figures are untouched by the node: the lane paths are not stages.
TEST(NodeCost, GateLevelsKeepTheirStages) {
  const UnitCost c = lane("schlick:in=uq1.23,out=uq1.19");
  for (const StageDelay& s : c.stages) EXPECT_EQ(s.stage.find("merge buffer"), std::string::npos);
  EXPECT_EQ(c.critical_stage.find("merge buffer"), std::string::npos);
  EXPECT_EQ(c.critical_path_node, "merge buffer read");
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

}  // namespace
}  // namespace glint
