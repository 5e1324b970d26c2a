#include "eval/evaluate.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace glint {
namespace {

Rgb rgb(const std::array<double, 3>& a) {
  return Rgb{a[0], a[1], a[2]};
}

}  // namespace

SlotMap make_slots(const VectorHeader& header) {
  SlotMap map;
  map.materials = header.materials.size();
  for (int l = 0; l < header.lights; ++l) {
    const auto i = header.intensity(l);
    if (i[0] != 1.0 || i[1] != 1.0 || i[2] != 1.0) map.per_light = true;
  }
  const int light_slots = map.per_light ? header.lights : 1;
  for (int l = 0; l < light_slots; ++l) {
    for (const VectorMaterial& m : header.materials) {
      const double cy =
          map.per_light ? c_y(rgb(header.intensity(l)), rgb(m.specular)) : c_y(rgb(m.specular));
      const Lobe lobe = m.lobe;
      MaterialParams p;
      TauResult tau;
      if (lobe == Lobe::kGaussian) {
        // The t^n units approximate the Gaussian lobe through its equivalent exponent 2/omega^2
        // unless the file gives a shininess of its own.
        p.shininess = m.shininess > 0 ? m.shininess : gaussian_equivalent_shininess(m.roughness);
        tau = tau_gaussian(m.roughness, header.eps, cy, header.lights);
      } else {
        p.shininess = m.shininess;
        tau = tau_power(m.shininess, header.eps, cy, header.lights);
      }
      p.always_skip = tau.always_skip;
      p.tau = tau.never_skip ? -1.0 : tau.tau;
      map.params.push_back(p);
      map.lobe.push_back(lobe);
      map.roughness.push_back(m.roughness);
      map.c_y.push_back(cy);
    }
  }
  return map;
}

double reference_value(const SlotMap& slots, std::size_t slot, double t) {
  // t = cos(phi) <= 1: the slack up to 1 + 1e-3 that vector files allow is float noise of unit
  // vectors, not a brighter highlight (1.001^5000 would be 147).
  t = std::min(t, 1.0);
  if (slots.lobe[slot] == Lobe::kGaussian) return gaussian_lobe(t, slots.roughness[slot]);
  return glossy_scalar(t, slots.params[slot].shininess);
}

double ErrorStats::rms() const {
  return count ? std::sqrt(sum_sq / count) : 0.0;
}

nlohmann::json ErrorStats::to_json() const {
  return {{"max_abs", max_abs}, {"rms", rms()}, {"t_at_max", t_at_max}, {"count", count}};
}

nlohmann::json UnitStats::to_json() const {
  // The statistics `glint sim` reports too carry its key names and nesting (`errors.max_abs`,
  // `errors.max_datapath_ulps`, ...), so one script reads both reports. `count`, `model`,
  // `skipped_fraction` and `description` are eval's own (README, eval report schema).
  nlohmann::json errors = total.to_json();
  errors["max_datapath_ulps"] = max_ulps;
  errors["t_at_max_datapath_ulps"] = t_at_max_ulps;
  errors["mismatch_8bit_fraction"] = vectors ? static_cast<double>(mismatch8) / vectors : 0.0;
  errors["error_bound"] = std::isfinite(error_bound) ? nlohmann::json(error_bound) : nullptr;
  errors["model"] = model.to_json();
  return {{"unit", name},
          {"spec", spec},
          {"vectors", vectors},
          {"skipped", skipped},
          {"skipped_fraction", vectors ? static_cast<double>(skipped) / vectors : 0.0},
          {"errors", errors},
          {"description", description}};
}

RowReference make_reference(const SlotMap& slots, std::size_t slot, double t) {
  RowReference r;
  r.t = t;
  r.value = reference_value(slots, slot, t);
  r.value8 = std::lround(std::clamp(r.value, 0.0, 1.0) * 255.0);
  return r;
}

LaneAccumulator::LaneAccumulator(const SpecularUnit& unit) : unit_(unit) {
  stats_.name = unit.name();
  stats_.spec = unit.canonical_spec();
  stats_.error_bound = std::numeric_limits<double>::quiet_NaN();
  for (std::size_t k = 0; k < unit.slots(); ++k) {
    const double b = unit.error_bound(k);
    if (std::isfinite(b))
      stats_.error_bound = std::isfinite(stats_.error_bound) ? std::max(stats_.error_bound, b) : b;
  }
  ulp_ = unit.out_format().ulp();
  out_scale_ = ulp_;  // raw -> value: exact power-of-two scale
  if (unit.in_format().width() <= 20) memo_.resize(unit.slots());
}

double LaneAccumulator::model(std::size_t slot, std::int64_t t_raw) {
  if (memo_.empty()) return unit_.model(slot, t_raw);
  std::vector<double>& m = memo_[slot];
  if (m.empty()) m.assign(std::size_t{1} << unit_.in_format().width(), -1.0);
  double& v = m[static_cast<std::size_t>(t_raw - unit_.in_format().raw_min())];
  if (v < 0) v = unit_.model(slot, t_raw);
  return v;
}

void LaneAccumulator::add(std::size_t slot, const RowReference& ref, std::int64_t t_raw,
                          bool skipped, std::int64_t out_raw) {
  const double fixed = static_cast<double>(out_raw) * out_scale_;
  ++stats_.vectors;
  stats_.skipped += skipped;
  stats_.total.add(fixed - ref.value, ref.t);
  if (!skipped) {
    const double ulps = std::fabs(fixed - model(slot, t_raw)) / ulp_;
    if (ulps > stats_.max_ulps) {
      stats_.max_ulps = ulps;
      stats_.t_at_max_ulps = ref.t;
    }
  }
  if (std::lround(std::clamp(fixed, 0.0, 1.0) * 255.0) != ref.value8) ++stats_.mismatch8;
  // FNV-1a style over the whole result word (skip flag in bit 63), with a shift-xor so every bit
  // of the word reaches every bit of the digest.
  const std::uint64_t word = static_cast<std::uint64_t>(out_raw) ^ (std::uint64_t{skipped} << 63);
  digest_ = (digest_ ^ word) * 0x100000001b3ULL;
  digest_ ^= digest_ >> 29;
}

Evaluator::Evaluator(const VectorHeader& header, const std::vector<UnitSpec>& specs)
    : slots_(make_slots(header)) {
  for (const UnitSpec& spec : specs) units_.push_back(make_unit(spec, slots_.params));
  std::vector<std::string> names;
  for (const auto& u : units_) names.push_back(u->name());
  const auto labels = unit_labels(names);
  for (std::size_t i = 0; i < units_.size(); ++i) {
    lanes_.emplace_back(*units_[i]);
    lanes_.back().stats().name = labels[i];
    lanes_.back().stats().description = units_[i]->describe();
  }
}

void Evaluator::add(const VectorRow& row, const std::function<void(const EvalRecord&)>& dump) {
  const std::size_t slot = slots_.slot(row);
  const RowReference ref = make_reference(slots_, slot, row.t);
  for (std::size_t u = 0; u < units_.size(); ++u) {
    const SpecularUnit& unit = *units_[u];
    const std::int64_t t_raw = quantize_input(row.t, unit.in_format());
    const bool skipped = unit.skip(slot, t_raw);
    const std::int64_t raw = skipped ? 0 : unit.eval(slot, t_raw);
    lanes_[u].add(slot, ref, t_raw, skipped, raw);
    // The float model includes the skip decision: a skipped request is 0 in every view.
    const double model = skipped ? 0.0 : unit.float_model(slot, row.t);
    lanes_[u].stats().model.add(model - ref.value, row.t);
    if (dump) {
      const double fixed = std::ldexp(static_cast<double>(raw), -unit.out_format().frac_bits);
      dump(EvalRecord{&row, u, t_raw, ref.value, model, fixed, raw, skipped});
    }
  }
}

std::vector<UnitStats> Evaluator::stats() const {
  std::vector<UnitStats> out;
  for (const auto& lane : lanes_) out.push_back(lane.stats());
  return out;
}

nlohmann::json Evaluator::to_json() const {
  nlohmann::json units = nlohmann::json::array();
  for (const auto& lane : lanes_) units.push_back(lane.stats().to_json());
  return {{"glint_eval_report", kEvalReportVersion},
          {"slots", slots_.params.size()},
          {"per_light_slots", slots_.per_light},
          {"units", units}};
}

std::string format_eval_table(const std::vector<UnitStats>& stats) {
  // Columns `glint sim`'s table has too (unit, vectors, skip%, max_err, dp_ulps, 8bit%) carry its
  // headings and unit-column width.
  std::string out = fmt::format("{:<9} {:>9} {:>7} {:>10} {:>8} {:>10} {:>10} {:>9} {:>7} {:>10}\n",
                                "unit", "vectors", "skip%", "max_err", "t@max", "rms_err",
                                "model_max", "dp_ulps", "8bit%", "bound");
  for (const auto& s : stats) {
    out += fmt::format(
        "{:<9} {:>9} {:>6.1f}% {:>10.3e} {:>8.5f} {:>10.3e} {:>10.3e} {:>9.3f} {:>6.2f}% {:>10}\n",
        s.name, s.vectors, s.vectors ? 100.0 * s.skipped / s.vectors : 0.0, s.total.max_abs,
        s.total.t_at_max, s.total.rms(), s.model.max_abs, s.max_ulps,
        s.vectors ? 100.0 * s.mismatch8 / s.vectors : 0.0,
        std::isfinite(s.error_bound) ? fmt::format("{:.3e}", s.error_bound) : "-");
  }
  return out;
}

}  // namespace glint
