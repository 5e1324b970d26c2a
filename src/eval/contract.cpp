#include "eval/contract.h"

#include <fmt/format.h>

#include <cmath>

#include "eval/contract_sweep.h"
#include "eval/evaluate.h"

namespace glint {

void ErrorParts::max_with(const ErrorParts& o) {
  input = std::max(input, o.input);
  parameter = std::max(parameter, o.parameter);
  approximation = std::max(approximation, o.approximation);
  datapath = std::max(datapath, o.datapath);
  skip = std::max(skip, o.skip);
}

const char* to_string(ContractKind kind) {
  switch (kind) {
    case ContractKind::kCorrectlyRounded:
      return "correctly_rounded";
    case ContractKind::kFaithful:
      return "faithful";
    case ContractKind::kBound:
      return "bound";
    case ContractKind::kNone:
      break;
  }
  return "none";
}

namespace {

nlohmann::json parts_json(const ErrorParts& p, double scale) {
  return {{"input", p.input * scale},
          {"parameter", p.parameter * scale},
          {"approximation", p.approximation * scale},
          {"datapath", p.datapath * scale},
          {"skip", p.skip * scale}};
}

}  // namespace

double SlotContract::weighted_bound() const {
  return pixel_error_bound(display, weight, always_skipped ? 1.0 : bound.total());
}

nlohmann::json SlotContract::to_json(int display_bits) const {
  nlohmann::json j{{"slot", slot},
                   {"name", name},
                   {"weight", weight},
                   {"threshold_raw", threshold_raw},
                   {"always_skipped", always_skipped}};
  if (always_skipped) {
    // The lobe never reaches eps on the pixel: not folded into any bound (its scalar error is the
    // whole lobe, its weighted error at most the weight, c_y <= eps under the luminance measure).
    j["weighted_bound"] = weighted_bound();
    return j;
  }
  j["contract"] = to_string(kind);
  j["reason"] = reason;
  j["datapath_bound_ulps"] = datapath_ulps;
  j["bound"] = parts_json(bound, 1.0);
  j["bound"]["total"] = bound.total();
  j["bound_lsb"] = bound.total() * display_scale(display_bits);
  j["weighted_bound_lsb"] = weighted_bound() * display_scale(display_bits);
  j["exact"] = exact;
  return j;
}

void classify_contract(SlotContract& c) {
  c.kind = c.datapath_ulps <= 0.5  ? ContractKind::kCorrectlyRounded
           : c.datapath_ulps < 1.0 ? ContractKind::kFaithful
                                   : ContractKind::kBound;
  switch (c.kind) {
    case ContractKind::kCorrectlyRounded:
      c.reason = "datapath correctly rounded against the unit's model";
      break;
    case ContractKind::kFaithful:
      c.reason =
          fmt::format("datapath faithful: within {:.3g} ulp of the unit's model", c.datapath_ulps);
      break;
    default:
      c.reason = fmt::format("datapath error up to {:.3g} ulp of the unit's model (not faithful)",
                             c.datapath_ulps);
  }
  if (!std::isfinite(c.bound.total()) || c.bound.computed_sum() >= kNoContractFraction) {
    c.kind = ContractKind::kNone;
    const double sum = c.bound.computed_sum();
    c.reason = !(sum < 1.0)
                   ? fmt::format("the stated error ({:.3g}) covers the whole output range", sum)
                   : fmt::format(
                         "the stated error ({:.3g}) is 1/4 of the output range or more: "
                         "a result cannot tell a lobe at 1/4 of its peak from one at 3/4",
                         sum);
  }
}

SlotContract slot_contract(const SpecularUnit& unit, std::size_t slot, const SlotMap& slots) {
  SlotContract c;
  const MaterialParams& m = slots.params[slot];
  c.slot = slot;
  c.name = m.name;
  c.weight = slots.pixel_weight_max[slot];
  c.display = slots.display;
  c.threshold_raw = unit.tau_raw(slot);
  if (m.always_skip && unit.comparator_enabled()) {
    c.always_skipped = true;
    c.bound.skip = 1.0;
    c.kind = ContractKind::kNone;
    c.reason = slots.eps_measure == EpsMeasure::kChannel ? "always skipped: w_max <= eps"
                                                         : "always skipped: c_y <= eps";
    return c;
  }
  const QFormat in = unit.in_format();
  const double h = in.ulp();
  const std::int64_t one = in.raw_one();
  // The lobe over the whole range a code can stand for: t >= -1 (the front end clamps t < 0 to
  // code 0, and a Gaussian lobe is not 0 there) up to 1 (reference_value clamps above).
  const auto ref = [&](double t) { return reference_value(slots, slot, std::max(t, -1.0)); };

  // Skip part: every real t that lands on a code <= T lies below (T + ½) h.
  const std::int64_t top = std::min(c.threshold_raw, one);
  if (top >= 0) c.bound.skip = ref((static_cast<double>(top) + 0.5) * h);

  // The codes the comparator keeps: all of them up to kExactInputBits, else evenly spaced ones,
  // certified where the unit's models are monotone (contract_sweep.h).
  const std::int64_t first = std::max<std::int64_t>(top + 1, 0);
  // A uq1.F input has 2^F + 1 codes in [0, 1] (1.0 included): up to F = kExactInputBits, all.
  const std::int64_t limit = (std::int64_t{1} << kExactInputBits) + 1;
  const bool sampled = one - first + 1 > limit;
  const SlotFunctions fn{[&](std::int64_t code) { return unit.model(slot, code); },
                         [&](double t) { return unit.float_model(slot, t); }, ref};
  const SweptParts parts =
      sweep_parts(fn, first, one, h, sampled && unit.models_monotone(slot), limit);
  c.bound.input = parts.input;
  c.bound.parameter = parts.parameter;
  c.bound.approximation = parts.approximation;
  c.exact = parts.certified;
  c.datapath_ulps = unit.datapath_bound_ulps(slot);
  c.bound.datapath = c.datapath_ulps * unit.out_format().ulp();

  classify_contract(c);
  return c;
}

}  // namespace glint
