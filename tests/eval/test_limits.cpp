// Resources proportional to the input, with stated limits (issue 11, item 5; src/cli/README.md
// "Limits and guarantees"): slots and light x material pairs per stream, units x slots per run, the
// accuracy contracts' sweep per run and lut's tables per unit are refused beyond their limits with
// a message naming the limit, before the memory or time is spent; slots that share a datapath,
// threshold and lobe share one contract sweep (a file of many identical materials costs what one
// material does).
#include <gtest/gtest.h>

#include <string>

#include "eval/evaluate.h"
#include "io/vectors.h"
#include "units/catalogue.h"
#include "units/unit_set.h"

namespace {

using glint::ResourceLimitError;
using glint::VectorHeader;
using glint::VectorMaterial;

// `materials` Phong materials, shininess 2, 3, ... (distinct) or all 50; `lights` lights, each of
// a colour of its own when `coloured` (so every light changes every material's c_y).
VectorHeader header(std::size_t materials, int lights, bool distinct, bool coloured = false) {
  VectorHeader h;
  h.eps = 1e-3;
  h.lights = lights;
  for (int l = 0; l < lights; ++l)
    h.light_intensity.push_back({1, coloured ? 0.5 + 0.4 * l / lights : 1, 1});
  for (std::size_t m = 0; m < materials; ++m) {
    VectorMaterial vm;
    vm.name = "m" + std::to_string(m);
    vm.shininess = distinct ? 2.0 + static_cast<double>(m) : 50.0;
    h.materials.push_back(vm);
  }
  h.has_light = lights > 1;
  return h;
}

template <class F>
std::string refusal(F&& f) {
  try {
    f();
  } catch (const ResourceLimitError& e) {
    return e.what();
  } catch (const std::invalid_argument& e) {
    return std::string("invalid_argument: ") + e.what();
  }
  return "";
}

TEST(Limits, SlotsPerStream) {
  // 32768 materials under two lights of different colours: 65536 slots, the limit; one more
  // material crosses it.
  EXPECT_EQ(glint::make_slots(header(32768, 2, false, true)).params.size(), 65536u);
  const std::string why = refusal([] { glint::make_slots(header(32769, 2, false, true)); });
  EXPECT_NE(why.find("more than 65536 slots"), std::string::npos) << why;
  // Lights that leave c_y unchanged add no slot: 65536 materials under 16 white lights.
  EXPECT_EQ(glint::make_slots(header(65536, 16, false)).params.size(), 65536u);
}

TEST(Limits, LightMaterialPairsPerStream) {
  // 1024 lights x 4096 materials: 2^22 pairs, the limit; one more material crosses it, and so
  // does the largest header the vector format allows (1024 x 65536), refused before any slot.
  EXPECT_EQ(glint::make_slots(header(4096, 1024, false)).params.size(), 4096u);
  for (const std::size_t materials : {4097, 65536}) {
    const std::string why = refusal([&] { glint::make_slots(header(materials, 1024, false)); });
    EXPECT_NE(why.find("more than the limit of 4194304"), std::string::npos) << why;
    EXPECT_NE(why.find("1024 lights x " + std::to_string(materials) + " materials"),
              std::string::npos)
        << why;
  }
}

TEST(Limits, UnitSlotsPerRun) {
  const glint::SlotMap slots = glint::make_slots(header(65536, 1, true));
  EXPECT_EQ(refusal([&] { glint::check_lane_slots(5, slots); }), "");
  const std::string why = refusal([&] { glint::check_lane_slots(6, slots); });
  EXPECT_NE(why.find("327680"), std::string::npos) << why;
  // The Evaluator checks before it builds any unit.
  EXPECT_NE(refusal([] {
              glint::Evaluator(header(65536, 1, true),
                               std::vector<glint::UnitSpec>(6, glint::parse_unit_spec("lut")));
            }).find("327680"),
            std::string::npos);
}

TEST(Limits, ContractSweepPerRun) {
  const auto spec = glint::parse_unit_spec("lut:skip=off,in=uq1.20");
  // Without the comparator every slot sweeps all 2^20 + 1 codes of uq1.20: 1023 slots fit in
  // 2^30, 1024 do not; nor do two units of 512 slots.
  const auto check = [&](std::size_t materials, std::size_t units) {
    const glint::SlotMap slots = glint::make_slots(header(materials, 1, true));
    std::vector<std::unique_ptr<glint::SpecularUnit>> owned;
    std::vector<const glint::SpecularUnit*> built;
    for (std::size_t u = 0; u < units; ++u) {
      owned.push_back(glint::make_unit(spec, slots));
      built.push_back(owned.back().get());
    }
    return refusal([&] { glint::check_contract_codes(built, slots); });
  };
  EXPECT_EQ(check(1023, 1), "");
  std::string why = check(1024, 1);
  EXPECT_NE(why.find("1073741824"), std::string::npos) << why;
  EXPECT_NE(why.find("lut 1073742848"), std::string::npos) << why;
  why = check(512, 2);
  EXPECT_NE(why.find("1073741824"), std::string::npos) << why;
  // The Evaluator checks before it reads a row.
  EXPECT_NE(refusal([&] {
              glint::Evaluator(header(1024, 1, true), std::vector<glint::UnitSpec>{spec});
            }).find("1073741824"),
            std::string::npos);
}

TEST(Limits, IdenticalSlotsShareOneSweep) {
  // 20000 identical materials: one sweep, within the limit however many slots.
  const glint::SlotMap slots = glint::make_slots(header(20000, 1, false));
  const auto unit = glint::make_unit(glint::parse_unit_spec("lut:skip=off"), slots);
  glint::LaneAccumulator acc(*unit, slots);
  for (std::size_t s = 0; s < 3; ++s) {
    const std::int64_t t = glint::quantize_input(0.9, unit->in_format());
    acc.add(s, glint::make_reference(slots, s, 0.9), t, false, unit->eval(s, t));
  }
  const auto& c = acc.stats().slots;
  ASSERT_EQ(c.size(), 3u);
  for (std::size_t s = 0; s < 3; ++s) {
    const glint::SlotContract fresh = glint::slot_contract(*unit, s, slots);
    EXPECT_EQ(c[s].slot, s);
    EXPECT_EQ(c[s].name, fresh.name);
    EXPECT_EQ(c[s].to_json(8), fresh.to_json(8));
  }
}

TEST(Limits, LutTablesPerUnit) {
  // bits=16 keeps 2^16 + 1 entries of 4 bytes per group when the input has 16 fraction bits and
  // the table spans [0, 1]: 1024 groups of such tables exceed 256 MiB. The refusal comes as soon as
  // the limit is crossed, naming it.
  const glint::SlotMap slots = glint::make_slots(header(1100, 1, true));
  const std::string why = refusal(
      [&] { glint::make_unit(glint::parse_unit_spec("lut:bits=16,skip=off,in=uq1.16"), slots); });
  EXPECT_NE(why.find("256 MiB of tables per unit"), std::string::npos) << why;
  EXPECT_NE(why.find("of 1100 datapath groups"), std::string::npos) << why;
  // Smaller tables for the same materials are built.
  EXPECT_EQ(refusal([&] { glint::make_unit(glint::parse_unit_spec("lut:bits=12"), slots); }), "");
}

}  // namespace
