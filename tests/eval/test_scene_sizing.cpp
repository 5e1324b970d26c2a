// Only the hardware a scene needs (issue 8, item 5): slots per (material, c_y), datapaths shared by
// a material's slots, tables counted once per datapath group, the n register as wide as the
// scene's shininess values need, and chips of fixed capacity (--chip ram:materials=M,slots=S).
// Expected values come from the headers themselves (counts of materials, lights and colours), from
// builds of the same units without sharing (one datapath per slot, as before), and from the cost
// model's own inventory.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "io/vectors.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"

namespace glint {
namespace {

const std::vector<std::string> kUnits = {"pow", "schlick", "hast", "horner", "lut"};
const std::string kTraces = GLINT_SOURCE_DIR "/traces";

VectorMaterial material(const std::string& name, double n, std::array<double, 3> specular,
                        Lobe lobe = Lobe::kBlinn) {
  VectorMaterial m;
  m.name = name;
  m.lobe = lobe;
  m.shininess = n;
  m.specular = specular;
  return m;
}

// Eight materials of different shininess and colour (specular with a zero blue channel for the
// last two: a light that only changes blue leaves their c_y as it is).
std::vector<VectorMaterial> eight_materials() {
  return {
      material("gold", 64, {1, 0.766, 0.336}),       material("copper", 32, {0.955, 0.638, 0.538}),
      material("silver", 500, {0.972, 0.96, 0.915}), material("plastic", 4, {0.5, 0.1, 0.1}),
      material("glaze", 128, {0.2, 0.3, 0.8}),       material("jade", 16, {0.3, 0.6, 0.35}),
      material("brass", 90, {0.9, 0.8, 0}),          material("rust", 20, {0.6, 0.3, 0})};
}

VectorHeader header(std::vector<VectorMaterial> materials,
                    std::vector<std::array<double, 3>> lights = {{1, 1, 1}}) {
  VectorHeader h;
  h.eps = 1e-3;
  h.lights = static_cast<int>(lights.size());
  h.light_intensity = std::move(lights);
  h.materials = std::move(materials);
  h.has_light = true;
  validate(h);
  return h;
}

std::unique_ptr<SpecularUnit> build(const std::string& spec, const SlotPlan& plan) {
  return make_unit(parse_unit_spec(spec), plan);
}

// The tables of a cost inventory by where they sit.
std::map<std::string, Primitive> tables(const UnitCost& c) {
  std::map<std::string, Primitive> out;
  for (const Primitive& p : c.inventory)
    if (p.kind == "table") out[p.where] = p;
  return out;
}

bool is_tau_table(const std::string& where) {
  return where.rfind("tau table", 0) == 0;
}

// ---- slots and groups --------------------------------------------------------------------------

TEST(SceneSlots, WhiteLightsShareTheMaterialsSlots) {
  const VectorHeader one = header(eight_materials());
  const VectorHeader eight =
      header(eight_materials(), std::vector<std::array<double, 3>>(8, {1, 1, 1}));
  const SlotMap a = make_slots(one), b = make_slots(eight);
  ASSERT_EQ(a.params.size(), 8u);
  ASSERT_EQ(b.params.size(), 8u);
  EXPECT_EQ(b.groups.size(), 8u);
  EXPECT_FALSE(b.per_light);
  EXPECT_EQ(b.light_stride, 0u);
  for (std::size_t m = 0; m < 8; ++m) {
    EXPECT_EQ(b.params[m].name, "material '" + eight.materials[m].name + "'");
    EXPECT_EQ(b.origin[m].lights, (std::vector<int>{0, 1, 2, 3, 4, 5, 6, 7}));
    EXPECT_EQ(b.c_y[m], c_y(Rgb{eight.materials[m].specular[0], eight.materials[m].specular[1],
                                eight.materials[m].specular[2]}));  // Källberg eq.6
    for (int l = 0; l < 8; ++l) {
      VectorRow row;
      row.material = static_cast<std::uint32_t>(m);
      row.light = l;
      EXPECT_EQ(b.slot(row), m);
    }
  }
  // eps_K = eps / 8 (Källberg §2): the thresholds move down, the structure does not.
  EXPECT_LT(b.params[0].tau, a.params[0].tau);
}

TEST(SceneSlots, AColouredLightAddsOneSlotPerMaterialItChanges) {
  const std::vector<VectorMaterial> mats = eight_materials();
  // Blue only: materials with a zero blue channel (brass, rust) keep their c_y exactly.
  const VectorHeader h = header(mats, {{1, 1, 1}, {1, 1, 0.5}, {1, 1, 1}});
  const SlotMap s = make_slots(h);
  std::size_t changed = 0;
  for (const VectorMaterial& m : mats) changed += m.specular[2] > 0;
  ASSERT_EQ(changed, 6u);
  EXPECT_EQ(s.params.size(), mats.size() + changed);
  EXPECT_EQ(s.groups.size(), mats.size());  // no datapath for the light
  EXPECT_TRUE(s.per_light);
  for (std::size_t slot = 0; slot < s.params.size(); ++slot) {
    const SlotOrigin& o = s.origin[slot];
    const std::string& name = mats[o.material].name;
    if (mats[o.material].specular[2] > 0) {
      EXPECT_TRUE(o.own_tau) << slot;
      EXPECT_NE(s.params[slot].name.find("under light"), std::string::npos) << s.params[slot].name;
    } else {
      EXPECT_EQ(s.params[slot].name, "material '" + name + "'");
      EXPECT_EQ(o.lights, (std::vector<int>{0, 1, 2}));
    }
    // The group's datapath is built for the smallest tau and level of its slots (largest c_y).
    const MaterialParams& g = s.groups[s.group[slot]];
    EXPECT_LE(g.tau, s.params[slot].tau) << s.params[slot].name;
    EXPECT_LE(g.level, s.params[slot].level) << s.params[slot].name;
    EXPECT_EQ(g.shininess, s.params[slot].shininess);
  }
  // Lights 0 and 2 (white) share every material's first slot; light 1 gives the changed ones
  // their own.
  for (std::uint32_t m = 0; m < mats.size(); ++m) {
    VectorRow r0, r1, r2;
    r0.material = r1.material = r2.material = m;
    r1.light = 1;
    r2.light = 2;
    EXPECT_EQ(s.slot(r0), s.slot(r2));
    EXPECT_EQ(s.slot(r0) != s.slot(r1), mats[m].specular[2] > 0) << mats[m].name;
    EXPECT_EQ(s.group[s.slot(r0)], s.group[s.slot(r1)]);
  }

  // ... and no table: every per-material table is the same as with the white light alone; the tau
  // table has one entry per slot.
  const SlotMap white = make_slots(header(mats));
  for (const std::string& spec : kUnits) {
    SCOPED_TRACE(spec);
    const auto u = build(spec, s);
    const auto w = build(spec, white);
    EXPECT_EQ(u->datapath_groups(), w->datapath_groups());
    const auto tu = tables(unit_cost(*u)), tw = tables(unit_cost(*w));
    for (const auto& [where, p] : tu) {
      if (is_tau_table(where)) {
        EXPECT_EQ(p.width_a, static_cast<int>(s.params.size())) << where;
        continue;
      }
      ASSERT_EQ(tw.count(where), 1u) << where;
      EXPECT_EQ(p.width_a, tw.at(where).width_a) << where;  // entries
      EXPECT_EQ(p.count, tw.at(where).count) << where;      // banks
    }
  }
}

TEST(SceneSlots, MaterialsWithIdenticalDatapathsShareOne) {
  const VectorHeader h = header(
      {material("a", 50, {1, 1, 1}), material("b", 50, {1, 1, 1}), material("c", 20, {1, 1, 1})});
  const SlotMap s = make_slots(h);
  ASSERT_EQ(s.params.size(), 3u);
  ASSERT_EQ(s.groups.size(), 2u);
  EXPECT_EQ(s.group[0], s.group[1]);
  EXPECT_NE(s.group[0], s.group[2]);
  EXPECT_EQ(s.groups[0].name, "material 'a' (and 1 more with the same datapath)");
}

TEST(SceneSlots, ShippedMultiLightTrace) {
  VectorReader r(kTraces + "/multi_light.vec");
  const SlotMap s = make_slots(r.header());
  // Three lights, each changing each material's c_y: 3 x 3 slots, light by light as before, and
  // one datapath group per material.
  EXPECT_EQ(s.params.size(), 9u);
  EXPECT_EQ(s.groups.size(), 3u);
  for (std::size_t slot = 0; slot < 9; ++slot) {
    EXPECT_EQ(s.origin[slot].lights, std::vector<int>{static_cast<int>(slot / 3)});
    EXPECT_EQ(s.origin[slot].material, slot % 3);
    EXPECT_EQ(s.group[slot], slot % 3);
  }
}

// ---- shared datapaths --------------------------------------------------------------------------

// A slot served by a datapath built from its own params computes exactly what a unit built for
// that slot alone computes (bit-exact where the structure is unchanged); pow and schlick, whose
// datapaths do not depend on tau, compute the same for every slot.
TEST(SharedDatapaths, BitExactWhereTheGroupIsTheSlotsOwn) {
  VectorReader r(kTraces + "/eight_lights.vec");
  const SlotMap s = make_slots(r.header());
  ASSERT_LT(s.groups.size(), s.params.size());
  for (const std::string& spec : kUnits) {
    SCOPED_TRACE(spec);
    const auto shared = build(spec, s);
    const auto own = make_unit(parse_unit_spec(spec), s.params);  // one datapath per slot
    ASSERT_EQ(shared->datapath_groups(), s.groups.size());
    ASSERT_EQ(own->datapath_groups(), s.params.size());
    const bool tau_free = spec == "pow" || spec == "schlick";
    const std::int64_t one = shared->in_format().raw_one();
    for (std::size_t slot = 0; slot < s.params.size(); ++slot) {
      const MaterialParams& p = s.params[slot];
      const MaterialParams& g = s.groups[s.group[slot]];
      if (!tau_free && (p.tau != g.tau || p.level != g.level)) continue;
      EXPECT_EQ(shared->tau_raw(slot), own->tau_raw(slot)) << p.name;
      for (std::int64_t t = 0; t <= one; ++t)
        ASSERT_EQ(shared->eval(slot, t), own->eval(slot, t)) << p.name << " t " << t;
    }
  }
}

// Every slot keeps its own threshold through the shared datapath: what it skips is imperceptible
// for its own c_y, and nothing the float test keeps is skipped.
TEST(SharedDatapaths, EachSlotKeepsItsOwnThreshold) {
  VectorReader r(kTraces + "/eight_lights.vec");
  const SlotMap s = make_slots(r.header());
  for (const std::string& spec : kUnits) {
    SCOPED_TRACE(spec);
    const auto u = build(spec, s);
    const QFormat in = u->in_format(), out = u->out_format();
    for (std::size_t slot = 0; slot < s.params.size(); ++slot) {
      const MaterialParams& p = s.params[slot];
      const std::int64_t tau = u->tau_raw(slot);
      EXPECT_LE(tau, tau_threshold_raw(p, in)) << p.name;
      ASSERT_FALSE(p.always_skip) << p.name;
      if (tau >= 0) {
        EXPECT_LE(static_cast<double>(u->eval(slot, tau)) * out.ulp(), p.level) << p.name;
      }
      EXPECT_EQ(u->eval(slot, in.raw_one()), out.raw_one()) << p.name;  // f(1) = 1
    }
  }
}

// ---- area --------------------------------------------------------------------------------------

TEST(SceneArea, OneMaterialIsSmallerThanEight) {
  std::vector<VectorMaterial> mats = eight_materials();
  const SlotMap eight = make_slots(header(mats));
  mats.resize(1);
  const SlotMap one = make_slots(header(mats));
  for (const std::string& spec : kUnits) {
    SCOPED_TRACE(spec);
    const UnitCost a = unit_cost(*build(spec, one)), b = unit_cost(*build(spec, eight));
    EXPECT_LT(a.area_ge, b.area_ge);
    // Every per-material table has one entry (bank) per material.
    // A per-material scalar (one entry a material) is a constant with one material: a ROM of one
    // entry is wiring, not built (cost/cost_model.h).
    const auto tables_a = tables(a);
    for (const auto& [where, p] : tables(b)) {
      if (where.find("per datapath group") == std::string::npos) continue;
      if (tables_a.count(where) == 0) {
        EXPECT_EQ(p.width_a, 8) << where;
        continue;
      }
      const Primitive& q = tables_a.at(where);
      EXPECT_EQ(p.width_a * p.count, 8 * q.width_a * q.count) << where;
    }
  }
}

// 1 -> 8 white lights: the same slots, groups and table entries. What changes is what eps_K = eps
// / 8 changes in the datapaths (Källberg §2): nothing for pow and schlick, whose hardware does not
// depend on tau (identical inventories); for lut, hast and horner only the widths the datapaths
// derive from tau (lut's interpolation bits, hast's and horner's k and coefficient formats), never
// a table's entries or banks.
TEST(SceneArea, WhiteLightsAddNoTable) {
  const SlotMap one = make_slots(header(eight_materials()));
  const SlotMap eight =
      make_slots(header(eight_materials(), std::vector<std::array<double, 3>>(8, {1, 1, 1})));
  for (const std::string& spec : kUnits) {
    SCOPED_TRACE(spec);
    const auto ua = build(spec, one), ub = build(spec, eight);
    EXPECT_EQ(ua->slots(), ub->slots());
    EXPECT_EQ(ua->datapath_groups(), ub->datapath_groups());
    const UnitCost a = unit_cost(*ua), b = unit_cost(*ub);
    const auto ta = tables(a), tb = tables(b);
    ASSERT_EQ(ta.size(), tb.size());
    for (const auto& [where, p] : ta) {
      ASSERT_EQ(tb.count(where), 1u) << where;
      EXPECT_EQ(p.width_a, tb.at(where).width_a) << where;
      EXPECT_EQ(p.count, tb.at(where).count) << where;
    }
    EXPECT_EQ(ua->describe()["elaboration"]["table_entries"],
              ub->describe()["elaboration"]["table_entries"]);
    if (spec == "pow" || spec == "schlick") {
      EXPECT_EQ(a.area_ge, b.area_ge);
      ASSERT_EQ(a.inventory.size(), b.inventory.size());
      for (std::size_t i = 0; i < a.inventory.size(); ++i)
        EXPECT_EQ(a.inventory[i].ge, b.inventory[i].ge) << a.inventory[i].where;
    }
  }
}

// The default pow and lut on the 8-light coloured trace against the same materials under one light
// (blinn_colored.vec): every part is the same except the threshold table (one entry per slot, now
// with its group id). Built as before (a datapath per slot), the per-material
// storage grew with the lights.
TEST(SceneArea, PowAndLutDoNotScaleWithLights) {
  VectorReader r8(kTraces + "/eight_lights.vec");
  VectorReader r1(kTraces + "/blinn_colored.vec");
  const SlotMap s8 = make_slots(r8.header()), s1 = make_slots(r1.header());
  ASSERT_EQ(s1.params.size(), 6u);
  ASSERT_EQ(s8.params.size(), 42u);  // 6 materials x (2 white lights sharing + 6 coloured)
  ASSERT_EQ(s8.groups.size(), 6u);
  for (const std::string spec : {"pow", "lut"}) {
    SCOPED_TRACE(spec);
    const auto u8 = build(spec, s8), u1 = build(spec, s1);
    const UnitCost c8 = unit_cost(*u8);
    const UnitCost c1 = unit_cost(*u1);
    std::map<std::string, double> ge1;
    for (const Primitive& p : c1.inventory) ge1[p.where] += p.ge;
    for (const Primitive& p : c8.inventory) {
      if (is_tau_table(p.where)) continue;
      ASSERT_EQ(ge1.count(p.where), 1u) << p.where;
      // A ROM is priced from its contents (cost_model.h, rom_ge), and lut's t^n entries follow
      // each group's threshold, which the lights' c_y move: the same storage, not the same GE.
      if (p.kind == "table") continue;
      EXPECT_EQ(p.ge, ge1[p.where]) << p.where;
    }
    const auto t1 = tables(c1);
    for (const auto& [where, p] : tables(c8)) {
      if (is_tau_table(where)) continue;
      ASSERT_EQ(t1.count(where), 1u) << where;
      EXPECT_EQ(p.width_a, t1.at(where).width_a) << where;
      EXPECT_EQ(p.width_b, t1.at(where).width_b) << where;
      EXPECT_EQ(p.count, t1.at(where).count) << where;
    }
    EXPECT_EQ(tables(c8).at("tau table (per slot, with its group id)").width_a, 42);
    // Before: one datapath per slot; its per-material storage scaled with the slots.
    const auto before = make_unit(parse_unit_spec(spec), s8.params);
    const UnitCost cb = unit_cost(*before);
    EXPECT_LT(c8.area_ge, cb.area_ge);
    const auto tables_before = tables(cb);
    for (const auto& [where, p] : tables(c8)) {
      if (where.find("per datapath group") == std::string::npos) continue;
      const Primitive& q = tables_before.at(where);
      EXPECT_EQ(q.width_a * q.count, 7 * p.width_a * p.count) << where;  // 42 slots / 6 groups
    }
  }
}

// ---- the n register ----------------------------------------------------------------------------

TEST(NRegister, JustWideEnoughForTheScenesShininess) {
  // n = 64, 32, 500, 4, 128, 16, 90, 20: integers up to 500 (9 bits), uq14.4 holds them exactly.
  const SlotMap s = make_slots(header(eight_materials()));
  for (const std::string spec : {"pow", "schlick"}) {
    SCOPED_TRACE(spec);
    const auto u = build(spec, s);
    const nlohmann::json n = u->describe()["elaboration"]["n_register"];
    EXPECT_EQ(n["format"], "uq14.4");
    EXPECT_EQ(n["built"], "uq9.0");
    EXPECT_EQ(n["exact"], true);
    EXPECT_EQ(tables(unit_cost(*u))
                  .at(spec == "pow" ? "stage 2: n table (per datapath group)"
                                    : "stage 1: n table (per datapath group)")
                  .width_b,
              9);
  }
  // 0.3 is not a multiple of 1/16: the register holds 0.3125 and the report says so and where.
  const SlotMap q =
      make_slots(header({material("a", 0.3, {1, 1, 1}), material("b", 50, {1, 1, 1})}));
  const nlohmann::json n = build("pow", q)->describe()["elaboration"]["n_register"];
  EXPECT_EQ(n["exact"], false);
  EXPECT_DOUBLE_EQ(n["max_abs_error"].get<double>(), std::fabs(5.0 / 16 - 0.3));
  EXPECT_EQ(n["at"], "material 'a'");
  EXPECT_EQ(n["built"], "uq6.4");  // 50 needs 6 integer bits, 5/16 four fraction bits
}

// ---- a chip of fixed capacity ------------------------------------------------------------------

// --chip ram:materials=N,slots=N.
Chip ram_chip(std::size_t n) {
  Chip c;
  c.ram = c.given = true;
  c.materials = c.slots = n;
  return c;
}

TEST(SlotCapacity, TooSmallIsRefusedWithTheCounts) {
  VectorReader r(kTraces + "/multi_light.vec");
  try {
    make_slots(r.header(), ram_chip(8));
    FAIL() << "a chip of 8 slots took a stream of 9";
  } catch (const SlotCapacityError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("8 slots"), std::string::npos) << what;
    EXPECT_NE(what.find("needs 9"), std::string::npos) << what;
  }
  EXPECT_EQ(make_slots(r.header(), ram_chip(9)).slot_capacity, 9u);
  EXPECT_THROW(make_slots(r.header(), ram_chip(kMaxSlotCapacity + 1)), SlotCapacityError);
}

TEST(SlotCapacity, LargerChipsAreLarger) {
  VectorReader r(kTraces + "/multi_light.vec");
  for (const std::string& spec : kUnits) {
    SCOPED_TRACE(spec);
    const auto fitted = build(spec, make_slots(r.header()));
    const auto exact = build(spec, make_slots(r.header(), ram_chip(9)));
    const auto big = build(spec, make_slots(r.header(), ram_chip(64)));
    // The same results whatever the capacity: it only sizes the tables.
    for (std::size_t slot = 0; slot < 9; ++slot) {
      EXPECT_EQ(fitted->tau_raw(slot), big->tau_raw(slot));
      for (std::int64_t t = 0; t <= fitted->in_format().raw_one(); t += 97)
        ASSERT_EQ(fitted->eval(slot, t), big->eval(slot, t));
    }
    const double a = unit_cost(*fitted).area_ge, b = unit_cost(*exact).area_ge,
                 c = unit_cost(*big).area_ge;
    EXPECT_LE(a, b);  // a fixed chip of 9 holds 9 materials, not the stream's 3
    EXPECT_LT(b, c);
    EXPECT_EQ(big->describe()["elaboration"]["capacity"], 64);
    EXPECT_EQ(big->describe()["elaboration"]["sized_to"], "capacity");
    for (const auto& [where, p] : tables(unit_cost(*big)))
      if (where.find("per slot") != std::string::npos ||
          where.find("per datapath group") != std::string::npos) {
        EXPECT_EQ(p.width_a * p.count % 64, 0) << where;
      }
  }
}

// Materials and thresholds are sized apart: multi_light.vec needs 3 datapath groups and 9 slots.
TEST(SlotCapacity, MaterialsAndSlotsAreIndependent) {
  VectorReader r(kTraces + "/multi_light.vec");
  Chip few_materials = ram_chip(64), few_slots = ram_chip(64);
  few_materials.materials = 3;
  few_slots.slots = 9;
  Chip too_few = ram_chip(64);
  too_few.materials = 2;
  try {
    make_slots(r.header(), too_few);
    FAIL() << "a chip of 2 materials took a stream of 3";
  } catch (const SlotCapacityError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("2 materials"), std::string::npos) << what;
    EXPECT_NE(what.find("needs 3"), std::string::npos) << what;
  }
  for (const std::string& spec : kUnits) {
    SCOPED_TRACE(spec);
    const auto m = build(spec, make_slots(r.header(), few_materials));
    const auto s = build(spec, make_slots(r.header(), few_slots));
    EXPECT_EQ(m->describe()["elaboration"]["capacity"], 64);
    EXPECT_EQ(m->describe()["elaboration"]["group_capacity"], 3);
    EXPECT_EQ(s->describe()["elaboration"]["capacity"], 9);
    EXPECT_EQ(s->describe()["elaboration"]["group_capacity"], 64);
    // The threshold table follows slots=, every per-material table materials=.
    for (const auto& [where, p] : tables(unit_cost(*m))) {
      if (where.find("per slot") != std::string::npos) {
        EXPECT_EQ(p.width_a * p.count % 64, 0) << where;
      }
      if (where.find("per datapath group") != std::string::npos) {
        EXPECT_EQ(p.width_a * p.count % 3, 0) << where;
      }
    }
    for (const auto& [where, p] : tables(unit_cost(*s))) {
      if (where.find("per datapath group") != std::string::npos) {
        EXPECT_EQ(p.width_a * p.count % 64, 0) << where;
      }
    }
  }
}

}  // namespace
}  // namespace glint
