#include "evaluate.h"

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
  return {{"unit", name},
          {"spec", spec},
          {"vectors", vectors},
          {"skipped", skipped},
          {"skipped_fraction", vectors ? static_cast<double>(skipped) / vectors : 0.0},
          {"error_vs_reference", total.to_json()},
          {"model_error", model.to_json()},
          {"datapath_error_ulps", {{"max", max_ulps}, {"t_at_max", t_at_max_ulps}}},
          {"mismatch_8bit_fraction", vectors ? static_cast<double>(mismatch8) / vectors : 0.0},
          {"error_bound", std::isfinite(error_bound) ? nlohmann::json(error_bound) : nullptr},
          {"description", description}};
}

Evaluator::Evaluator(const VectorHeader& header, const std::vector<UnitSpec>& specs)
    : slots_(make_slots(header)) {
  for (const UnitSpec& spec : specs) {
    units_.push_back(make_unit(spec, slots_.params));
    UnitStats s;
    s.name = units_.back()->name();
    s.spec = units_.back()->canonical_spec();
    s.description = units_.back()->describe();
    s.error_bound = std::numeric_limits<double>::quiet_NaN();
    for (std::size_t k = 0; k < slots_.params.size(); ++k) {
      const double b = units_.back()->error_bound(k);
      if (std::isfinite(b))
        s.error_bound = std::isfinite(s.error_bound) ? std::max(s.error_bound, b) : b;
    }
    stats_.push_back(std::move(s));
  }
  std::vector<std::string> names;
  for (const auto& u : units_) names.push_back(u->name());
  const auto labels = unit_labels(names);
  for (std::size_t i = 0; i < stats_.size(); ++i) stats_[i].name = labels[i];
}

void Evaluator::add(const VectorRow& row, const std::function<void(const EvalRecord&)>& dump) {
  const std::size_t slot = slots_.slot(row);
  const double ref = reference_value(slots_, slot, row.t);
  const long ref8 = std::lround(std::clamp(ref, 0.0, 1.0) * 255.0);
  for (std::size_t u = 0; u < units_.size(); ++u) {
    const SpecularUnit& unit = *units_[u];
    UnitStats& st = stats_[u];
    const QFormat in = unit.in_format(), out = unit.out_format();
    const std::int64_t t_raw = quantize_input(row.t, in);
    const bool skipped = unit.skip(slot, t_raw);
    const std::int64_t raw = skipped ? 0 : unit.eval(slot, t_raw);
    const double fixed = std::ldexp(static_cast<double>(raw), -out.frac_bits);
    // The float model includes the skip decision: a skipped request is 0 in every view.
    const double model = skipped ? 0.0 : unit.float_model(slot, row.t);
    ++st.vectors;
    st.skipped += skipped;
    st.total.add(fixed - ref, row.t);
    st.model.add(model - ref, row.t);
    if (!skipped) {
      const double ulps = std::fabs(fixed - unit.model(slot, t_raw)) / out.ulp();
      if (ulps > st.max_ulps) {
        st.max_ulps = ulps;
        st.t_at_max_ulps = row.t;
      }
    }
    if (std::lround(std::clamp(fixed, 0.0, 1.0) * 255.0) != ref8) ++st.mismatch8;
    if (dump) dump(EvalRecord{&row, u, t_raw, ref, model, fixed, raw, skipped});
  }
}

nlohmann::json Evaluator::to_json() const {
  nlohmann::json units = nlohmann::json::array();
  for (const auto& s : stats_) units.push_back(s.to_json());
  return {{"slots", slots_.params.size()}, {"per_light_slots", slots_.per_light}, {"units", units}};
}

std::string format_eval_table(const std::vector<UnitStats>& stats) {
  std::string out = fmt::format("{:<8} {:>9} {:>8} {:>10} {:>8} {:>10} {:>10} {:>9} {:>7} {:>10}\n",
                                "unit", "vectors", "skipped", "max_err", "t@max", "rms_err",
                                "model_max", "dp_ulps", "8bit%", "bound");
  for (const auto& s : stats) {
    out += fmt::format(
        "{:<8} {:>9} {:>7.1f}% {:>10.3e} {:>8.5f} {:>10.3e} {:>10.3e} {:>9.3f} {:>6.2f}% {:>10}\n",
        s.name, s.vectors, s.vectors ? 100.0 * s.skipped / s.vectors : 0.0, s.total.max_abs,
        s.total.t_at_max, s.total.rms(), s.model.max_abs, s.max_ulps,
        s.vectors ? 100.0 * s.mismatch8 / s.vectors : 0.0,
        std::isfinite(s.error_bound) ? fmt::format("{:.3e}", s.error_bound) : "-");
  }
  return out;
}

}  // namespace glint
