// The accuracy contract of one slot of a unit: every error source bounded on its own, on every
// input code the datapath can see, so that the total against the reference lobe is bounded on any
// real t, on the input grid or off it.
//
// For a real t (the front end clamps it to [0, 1]) whose code c = quantize_input(t) (value t_c)
// the comparator keeps:
//   y(c) - r(t) = [y(c) - M(c)]     datapath rounding: the unit's budget, datapath_bound_ulps
//               + [M(c) - F(t_c)]   parameter quantization: n, tau, k, coefficients, tables
//               + [F(t_c) - r(t_c)] approximation: the unit's real-valued function vs the lobe
//               + [r(t_c) - r(t)]   input quantization: t rounded to the input format
// with M = SpecularUnit::model (real arithmetic at the quantized parameters), F = float_model
// (exact parameters) and r the reference lobe (t^n, or Källberg eq.7 for Gaussian materials). The
// parameter and approximation parts are bounded over every code the comparator keeps (measured at
// each, or certified from sampled ones: contract_sweep.h), the input part over each code's whole
// rounding cell (r is monotone, so the cell's ends bound it), so by the triangle inequality
// |y - r(t)| never exceeds their sum plus the datapath budget.
// A skipped t gives 0 where r(t) <= r at the top of the threshold code's cell, which the unit's
// threshold keeps at or below tau (unit_threshold_raw), i.e. <= eps_K / c_y: the skip part. The
// total bound is the larger of the skip part and the sum of the other four.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>

#include "reference/pixel_error.h"
#include "units/unit.h"

namespace glint {

struct SlotMap;

// Absolute errors in units of the scalar lobe (1.0 = the lobe's peak).
struct ErrorParts {
  double input = 0, parameter = 0, approximation = 0, datapath = 0, skip = 0;

  double computed_sum() const { return input + parameter + approximation + datapath; }
  double total() const { return std::max(skip, computed_sum()); }
  void max_with(const ErrorParts& o);
};

// What the datapath promises against its own model: correctly rounded (<= ½ ulp), faithful
// (< 1 ulp), a stated bound in ulps (a user-forced weak configuration, e.g. guard=0), or none
// (the stated error is kNoContractFraction of the output range or more).
enum class ContractKind : std::uint8_t { kCorrectlyRounded, kFaithful, kBound, kNone };

// A slot whose stated error (the sum of the computed parts) reaches this fraction of the output
// range promises nothing: results within B of the truth tell a lobe at 1/4 of its peak from one at
// 3/4 only while B < 1/4, so from there on not even one bit of the output is guaranteed
// (contract.md, "The datapath contract per unit").
inline constexpr double kNoContractFraction = 0.25;
const char* to_string(ContractKind kind);  // "correctly_rounded", "faithful", "bound", "none"

// Inputs with up to this many fraction bits (2^20 + 1 codes in [0, 1]) are measured at every code;
// finer ones at ~2^20 evenly spaced codes, which the enclosure of contract_sweep.h certifies where
// the unit's models are monotone (SlotContract::exact = false elsewhere: the parts are then
// estimates, not bounds).
inline constexpr int kExactInputBits = 20;

struct SlotContract {
  std::size_t slot = 0;
  std::string name;             // "material 'm'" or "light 2 x material 'm'"
  bool always_skipped = false;  // c_y <= eps: never computed, reported apart from the bounds
  // The slot's largest channel weight (SlotMap::pixel_weight_max): what the scalar lobe is
  // multiplied by on the pixel's largest channel, in the display's encoding.
  double weight = 1.0;
  DisplayEncoding display = DisplayEncoding::kLinear8;
  std::int64_t threshold_raw = -1;
  ErrorParts bound;
  double datapath_ulps = 0.0;
  ContractKind kind = ContractKind::kFaithful;
  std::string reason;
  // The parts are bounds: every code swept, or the sampled codes certified (contract_sweep.h).
  bool exact = true;

  // The bound on the slot's pixel error (reference/pixel_error.h): the whole lobe when always
  // skipped, else the bound's total, through the weight and the encoding's slope.
  double weighted_bound() const;
  nlohmann::json to_json(int display_bits) const;
};

// Sets c.kind and c.reason from c.datapath_ulps and c.bound: the datapath's budget names the kind,
// unless the stated error reaches kNoContractFraction of the range (or is not finite): kNone.
void classify_contract(SlotContract& c);

// Measures and bounds every part for one slot (cost: a few evaluations per code above the
// threshold, ~1-10 ms for a 16-bit input; at most ~2^21 codes' worth for a wider one).
SlotContract slot_contract(const SpecularUnit& unit, std::size_t slot, const SlotMap& slots);

// A display depth's LSB: errors in LSBs of a `bits`-bit output are err * (2^bits - 1).
inline double display_scale(int bits) {
  return static_cast<double>((std::int64_t{1} << bits) - 1);
}

}  // namespace glint
