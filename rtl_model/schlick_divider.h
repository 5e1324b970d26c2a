// SchlickDivider: Schlick's t / (n - n t + t) with its exact, correctly rounded divider.
//
// Stages (L = q + 2, q = out.frac_bits + 2 quotient bits, from SpecularUnit::timing()):
//   in     comparator register of the compute path
//   mac    denominator multiply-add n - n t + t
//   divider, one quotient bit per cycle, MSB first:
//     pipelined  q stages q0 .. q{q-1}, one bit each: II = 1
//     iterative  one radix-2 stage `div` that keeps the request for q cycles (`bit` counts them):
//                II = q
//   round  rounding to the output format; drives `result` (SpecularUnit::eval)
// The divider kind is a parameter; it must agree with the unit's timing (II), which the factory
// (compute_units.h) guarantees by reading the unit's `divider` key.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "rtl_model/compute_pipeline.h"

namespace glint::rtl {

enum class DividerKind { kPipelined, kIterative };

class SchlickDivider : public ComputePipeline {
 public:
  SchlickDivider(sc_core::sc_module_name name, const SpecularUnit& unit, DividerKind kind,
                 bool tracing)
      : ComputePipeline(name, unit, layout(unit, kind), tracing), kind_(kind) {}

  DividerKind divider_kind() const { return kind_; }

  static std::vector<StageSpec> layout(const SpecularUnit& unit, DividerKind kind) {
    const UnitTiming t = unit.timing();
    const int q = t.latency - 2;
    if (q < 1) return ComputePipeline::generic_stages(t.latency);
    const int expected_ii = kind == DividerKind::kIterative ? q : 1;
    if (t.ii != expected_ii)
      throw std::invalid_argument("SchlickDivider: divider kind does not match the unit's II (" +
                                  std::to_string(t.ii) + ")");
    std::vector<StageSpec> s{{"in", 0, 0}, {"mac", 1, 1}};
    if (kind == DividerKind::kIterative) {
      s.push_back({"div", 2, q + 1});
    } else {
      for (int k = 0; k < q; ++k) s.push_back({"q" + std::to_string(k), 2 + k, 2 + k});
    }
    s.push_back({"round", q + 2, q + 2});
    return s;
  }

 private:
  DividerKind kind_;
};

}  // namespace glint::rtl
