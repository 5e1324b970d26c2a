// What the VCD shows of each compute stage is the hardware's registers: read the trace back and
// check, cycle by cycle, every stage of every lane: `valid` exactly when a request is in the stage,
// its `seq` and `t` (and the sink's seq of each retired result), the iteration `bit` of a
// multi-cycle stage, and every register against the unit's staged evaluation of that request. One
// elaboration per TEST.
#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "rtl_model/clocked_sim.h"
#include "rtl_model/rtl_common.h"
#include "test_support.h"
#include "units/catalogue.h"
#include "vcd_reader.h"

namespace glint {
namespace {

TEST(RtlStageTrace, EveryStageShowsItsRegistersCycleByCycle) {
  test::TempDir dir;
  VectorHeader header;
  header.eps = 1e-3;
  header.lights = 1;
  VectorMaterial m;
  m.name = "sharp";
  m.shininess = 64;
  m.lobe = Lobe::kBlinn;
  header.materials.push_back(m);
  m.name = "broad";
  m.specular = {0.5, 0.5, 0.5};
  m.shininess = 6;
  header.materials.push_back(m);
  std::vector<VectorRow> rows;
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> t(-0.1, 1.0);
  for (std::size_t i = 0; i < 400; ++i) {
    VectorRow r;
    r.t = t(rng);
    r.material = static_cast<std::uint32_t>(rng() % 2);
    r.line = i + 1;
    rows.push_back(r);
  }
  const SlotMap slots = make_slots(header);
  // Every unit kind; skip=off on some so that every request is computed; the iterative divider
  // for a stage that spans several cycles.
  const std::vector<std::string> specs = {
      "hast:d=4,skip=off", "horner:degree=3",   "pow:skip=off",
      "lut:bits=5",        "schlick:out=uq1.9", "schlick:divider=iterative,out=uq1.7,skip=off"};
  std::vector<std::unique_ptr<SpecularUnit>> owned;
  std::vector<const SpecularUnit*> units;
  for (const std::string& sp : specs) {
    owned.push_back(make_unit(parse_unit_spec(sp), slots));
    units.push_back(owned.back().get());
  }
  ClockedOptions options;
  options.vcd_path = dir.file("run.vcd");
  options.sink = SinkReady{0.7, 3};
  struct Issued {
    std::uint64_t seq, issue;
    std::int64_t t_raw;
    std::size_t slot;
  };
  std::vector<std::vector<Issued>> computed(units.size());
  std::vector<std::vector<std::uint64_t>> retire(units.size());  // per request, in stream order
  std::vector<std::uint64_t> seq(units.size(), 0);
  ClockedRunInfo info;
  run_clocked(
      units, slots, [&] { return std::make_unique<MemoryRowStream>(rows); }, options,
      [&](const LaneOutput& o) {
        const std::uint64_t s = seq[o.lane]++;
        retire[o.lane].push_back(o.timing.retire);
        if (!o.skipped) computed[o.lane].push_back({s, o.timing.issue, o.t_raw, slots.slot(o.row)});
      },
      &info);

  const test::VcdReader vcd(dir.file("run.vcd"));
  for (std::size_t u = 0; u < units.size(); ++u) {
    SCOPED_TRACE(specs[u]);
    const SpecularUnit& unit = *units[u];
    const StageLayout& layout = unit.stages();
    ASSERT_GT(computed[u].size(), 50u);
    // Who is in position p at cycle c: the request issued at c - p.
    std::map<std::uint64_t, const Issued*> by_issue;
    std::uint64_t last_cycle = 0;
    for (const Issued& r : computed[u]) {
      by_issue[r.issue] = &r;
      last_cycle = std::max<std::uint64_t>(last_cycle, r.issue + layout.latency());
    }
    std::vector<std::int64_t> staged(layout.size());
    std::uint64_t checked = 0;
    for (const Stage& s : layout.stages()) {
      const std::string p = "SystemC.top." + info.labels[u] + "." + s.name + ".";
      for (const StageRegister& r : s.registers)
        ASSERT_EQ(vcd.vars.at(p + r.name), r.format.width()) << p << r.name;
      for (std::uint64_t c = 0; c <= last_cycle; ++c) {
        const Issued* in = nullptr;
        int position = s.first;
        for (int q = s.first; q <= s.last && !in; ++q) {
          const auto it =
              c >= static_cast<std::uint64_t>(q) ? by_issue.find(c - q) : by_issue.end();
          if (it != by_issue.end()) {
            in = it->second;
            position = q;
          }
        }
        const std::uint64_t time = rtl::cycle_time_ns(c);
        ASSERT_EQ(vcd.value_at(p + "valid", time), in ? 1u : 0u) << p << " cycle " << c;
        if (!in) continue;
        ASSERT_EQ(vcd.value_at(p + "seq", time), in->seq & 0xffffffffu) << p << " cycle " << c;
        ASSERT_EQ(vcd.value_at(p + "t", time), static_cast<std::uint64_t>(in->t_raw));
        if (s.last > s.first) {
          ASSERT_EQ(vcd.value_at(p + "bit", time), static_cast<std::uint64_t>(position - s.first));
        }
        if (position == 0) continue;
        unit.eval_staged(in->slot, in->t_raw, staged.data());
        for (std::size_t k = 0; k < s.registers.size(); ++k) {
          const int w = s.registers[k].format.width();
          const std::uint64_t mask = w >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << w) - 1;
          const std::uint64_t want =
              static_cast<std::uint64_t>(staged[layout.offset(position) + k]) & mask;
          ASSERT_EQ(vcd.value_at(p + s.registers[k].name, time), want)
              << p << s.registers[k].name << " cycle " << c << " seq " << in->seq;
          ++checked;
        }
      }
    }
    EXPECT_GT(checked, computed[u].size());
    // The id goes on with the result: the sink shows each request's seq in its retire cycle.
    for (std::size_t i = 0; i < retire[u].size(); ++i) {
      const std::uint64_t time = rtl::cycle_time_ns(retire[u][i]);
      const std::string sink = "SystemC.top." + info.labels[u] + ".sink.";
      ASSERT_EQ(vcd.value_at(sink + "valid", time), 1u);
      ASSERT_EQ(vcd.value_at(sink + "seq", time), i) << info.labels[u];
    }
  }
}

}  // namespace
}  // namespace glint
