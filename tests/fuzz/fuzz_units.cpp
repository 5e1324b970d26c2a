// Unit SPECs (units/catalogue.h): parse_unit_spec, then make_unit for a small scene and a short
// stream through the built unit. The input is the SPEC on its first line; what follows, when it is
// a vector-file header with at most kMaxMaterials materials and kMaxLights lights, gives the scene
// (so the fuzzer varies shininess, roughness, colours, lights and eps too); anything else leaves
// the default scene (traces/hard_cases.vec's extremes: n = 0.5 and 5000, a Gaussian lobe, an
// always-skipped faint material, a coloured light).
//
// A bad spec or a scene a unit cannot be built for is refused with std::invalid_argument (exit 2
// in the CLI); anything else thrown is a finding. A built unit's staged evaluation must agree with
// eval(), its batch with eval_with_skip(), and its canonical spec must build the same unit again.
// The work per input is bounded: at most 8 materials x 4 lights, 24 codes per slot, and the
// accuracy contract (a sweep over the kept input codes) of one slot when the input has at most 12
// fraction bits (the contract's cost grows with the codes; tests/eval/test_contract_properties.cpp
// sweeps wide inputs).
#include <algorithm>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "eval/evaluate.h"
#include "fuzz.h"
#include "io/input_error.h"
#include "io/vectors.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"

namespace glint::fuzz {

namespace {

constexpr std::size_t kMaxMaterials = 8;
constexpr int kMaxLights = 4;
constexpr std::size_t kContractSlots = 1;
constexpr int kContractMaxFracBits = 12;

const char* const kDefaultScene =
    "glint-vectors 1\n"
    "eps 1e-3\n"
    "lights 2\n"
    "light 1 1,0.5,0.25\n"
    "material soft specular=1,1,1 shininess=0.5 lobe=phong\n"
    "material sharp specular=0.9,0.8,0.7 shininess=5000 lobe=blinn\n"
    "material lobe specular=1,1,1 roughness=0.2 lobe=gaussian\n"
    "material faint specular=0.0005,0.0005,0.0005 shininess=50 lobe=phong\n"
    "columns t material light\n"
    "data\n";

VectorHeader read_header(const std::string& text) {
  std::istringstream in(text);
  VectorReader reader(in, "scene.vec");
  return reader.header();
}

VectorHeader scene_of(const std::string& rest) {
  if (rest.find("data") != std::string::npos) {
    try {
      VectorHeader h = read_header(rest);
      if (h.materials.size() <= kMaxMaterials && h.lights <= kMaxLights) return h;
    } catch (const InputError&) {
      // not a header: the default scene
    }
  }
  static const VectorHeader fallback = read_header(kDefaultScene);
  return fallback;
}

// Input codes worth visiting in a slot: the ends, around its threshold, and a spread.
std::vector<std::int64_t> codes_of(const SpecularUnit& u, std::size_t slot) {
  const std::int64_t one = u.in_format().raw_one();
  const std::int64_t tau = u.tau_raw(slot);
  std::vector<std::int64_t> codes = {0, 1, one - 1, one, tau, tau + 1};
  for (int i = 1; i < 18; ++i) codes.push_back(one / 18 * i);
  for (auto& c : codes) c = std::clamp<std::int64_t>(c, 0, one);
  return codes;
}

void exercise(const SpecularUnit& u, const SlotMap& slots) {
  std::vector<std::int64_t> staged(u.stages().size());
  LaneAccumulator acc(u, slots);
  std::size_t contracts = 0;
  const bool contract_ok = u.in_format().frac_bits <= kContractMaxFracBits;
  for (std::size_t s = 0; s < u.slots(); ++s) {
    const auto codes = codes_of(u, s);
    std::vector<std::int64_t> out(codes.size());
    std::vector<std::uint8_t> skipped(codes.size());
    u.eval_batch(s, codes.data(), out.data(), skipped.data(), codes.size());
    for (std::size_t i = 0; i < codes.size(); ++i) {
      const std::int64_t c = codes[i];
      const std::int64_t y = u.eval(s, c);
      if (out[i] != u.eval_with_skip(s, c)) fail("eval_batch disagrees with eval_with_skip");
      u.eval_staged(s, c, staged.data());
      if (staged[u.stages().result_index()] != y) fail("eval_staged disagrees with eval");
      (void)u.model(s, c);
      (void)u.float_model(s, static_cast<double>(c) * u.in_format().ulp());
    }
    (void)u.error_bound(s);
    (void)u.datapath_bound_ulps(s);
    if (contract_ok && contracts < kContractSlots && !slots.slot_of.empty()) {
      // A short stream through the accumulator: the slot's contract and every statistic.
      ++contracts;
      for (const double t : {-0.5, 0.0, 0.5, 0.99, 1.0}) {
        const std::int64_t c = quantize_input(t, u.in_format());
        const bool sk = u.skip(s, c);
        acc.add(s, make_reference(slots, s, t), c, sk, sk ? 0 : u.eval(s, c));
      }
    }
  }
  (void)acc.stats().to_json().dump();
  (void)u.describe().dump();
  (void)unit_cost(u);
}

}  // namespace

int units(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  const auto newline = text.find('\n');
  const std::string spec_text = text.substr(0, newline);
  const std::string rest = newline == std::string::npos ? "" : text.substr(newline + 1);
  std::unique_ptr<SpecularUnit> unit;
  SlotMap slots;
  try {
    const UnitSpec spec = parse_unit_spec(spec_text);
    slots = make_slots(scene_of(rest));
    unit = make_unit(spec, slots);
  } catch (const std::invalid_argument&) {
    return 0;  // a bad spec, or a scene this unit cannot be built for: exit 2
  } catch (const std::exception& e) {
    fail(std::string("building the unit threw something other than invalid_argument: ") + e.what());
  }
  exercise(*unit, slots);
  // The canonical spec (every key resolved) builds the same unit.
  std::unique_ptr<SpecularUnit> again;
  try {
    again = make_unit(parse_unit_spec(unit->canonical_spec()), slots);
  } catch (const std::exception& e) {
    fail("the canonical spec " + unit->canonical_spec() + " does not build: " + e.what());
  }
  if (again->canonical_spec() != unit->canonical_spec())
    fail("canonical spec not idempotent: " + unit->canonical_spec() + " -> " +
         again->canonical_spec());
  for (std::size_t s = 0; s < unit->slots(); ++s)
    if (again->tau_raw(s) != unit->tau_raw(s)) fail("the canonical spec's thresholds differ");
  return 0;
}

}  // namespace glint::fuzz

GLINT_FUZZ_TARGET(units)
