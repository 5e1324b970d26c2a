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
      p.level = cy > 0 ? tau.eps / cy : 1.0;
      p.name = map.per_light ? fmt::format("light {} x material '{}'", l, m.name)
                             : fmt::format("material '{}'", m.name);
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

ErrorParts UnitStats::bound() const {
  ErrorParts b;
  for (const SlotContract& c : slots)
    if (!c.always_skipped) b.max_with(c.bound);
  return b;
}

double UnitStats::weighted_bound() const {
  double w = 0;
  for (const SlotContract& c : slots)
    w = std::max(w, c.weight * (c.always_skipped ? 1.0 : c.bound.total()));
  return w;
}

ContractKind UnitStats::contract() const {
  ContractKind k = ContractKind::kCorrectlyRounded;
  for (const SlotContract& c : slots)
    if (!c.always_skipped) k = std::max(k, c.kind);
  return k;
}

nlohmann::json UnitStats::errors_json() const {
  const double lsb = display_scale(display_bits);
  const ErrorParts b = bound();
  const auto part = [](const PartStats& p, double bound) {
    return nlohmann::json{{"max_abs", p.max_abs}, {"t_at_max", p.t_at_max}, {"bound", bound}};
  };
  nlohmann::json parts{{"input", part(input, b.input)},
                       {"parameter", part(parameter, b.parameter)},
                       {"approximation", part(approximation, b.approximation)},
                       {"datapath", part(datapath, b.datapath)},
                       {"skip", part(skip, b.skip)}};
  double dp_ulps = 0;
  std::string reason;
  const ContractKind kind = contract();
  nlohmann::json slot_list = nlohmann::json::array(), always = nlohmann::json::array();
  for (const SlotContract& c : slots) {
    slot_list.push_back(c.to_json(display_bits));
    if (c.always_skipped) {
      always.push_back(c.name);
      continue;
    }
    dp_ulps = std::max(dp_ulps, c.datapath_ulps);
    if (c.kind == kind && reason.empty()) reason = c.reason;
  }
  parts["datapath"]["max_ulps"] = max_ulps();
  parts["datapath"]["bound_ulps"] = dp_ulps;
  nlohmann::json errors = total.to_json();
  errors["max_datapath_ulps"] = max_ulps();
  errors["t_at_max_datapath_ulps"] = datapath.t_at_max;
  errors["display_bits"] = display_bits;
  errors["max_lsb"] = total.max_abs * lsb;
  errors["mismatch_fraction"] = vectors ? static_cast<double>(mismatch) / vectors : 0.0;
  errors["always_skipped_vectors"] = always_skipped_vectors;
  errors["bound"] = b.total();
  errors["bound_lsb"] = b.total() * lsb;
  errors["weighted"] = {{"max_abs", weighted.max_abs},
                        {"t_at_max", weighted.t_at_max},
                        {"max_lsb", weighted.max_abs * lsb},
                        {"bound", weighted_bound()},
                        {"bound_lsb", weighted_bound() * lsb}};
  errors["parts"] = std::move(parts);
  errors["contract"] = to_string(kind);
  errors["contract_reason"] = reason;
  errors["always_skipped_slots"] = std::move(always);
  errors["slots"] = std::move(slot_list);
  return errors;
}

nlohmann::json UnitStats::to_json() const {
  // `glint sim` reports the same "errors" object, so one script reads both reports. `count`,
  // `skipped_fraction` and `description` are eval's own (README, eval report schema).
  return {{"unit", name},
          {"spec", spec},
          {"vectors", vectors},
          {"skipped", skipped},
          {"skipped_fraction", vectors ? static_cast<double>(skipped) / vectors : 0.0},
          {"errors", errors_json()},
          {"description", description}};
}

RowReference make_reference(const SlotMap& slots, std::size_t slot, double t, int display_bits) {
  RowReference r{t, reference_value(slots, slot, t), 0, display_bits};
  r.display = std::lround(std::clamp(r.value, 0.0, 1.0) * display_scale(display_bits));
  return r;
}

namespace {
// The memo holds r per (slot, code) for inputs up to 16 bits, up to this many codes over all slots
// (32 MiB): beyond it every request computes its parts (a file with thousands of materials must
// not allocate per slot what a short stream never revisits).
constexpr std::size_t kMemoCodes = std::size_t{1} << 22;
}  // namespace

LaneAccumulator::LaneAccumulator(const SpecularUnit& unit, const SlotMap& slots, int display_bits)
    : unit_(unit), slots_(slots) {
  stats_.name = unit.name();
  stats_.spec = unit.canonical_spec();
  stats_.display_bits = display_bits;
  ulp_ = unit.out_format().ulp();
  stats_.out_ulp = ulp_;
  in_ulp_ = unit.in_format().ulp();
  display_ = display_scale(display_bits);
  slot_state_.assign(unit.slots(), -1);
  const int width = unit.in_format().width();
  if (width <= 16 && unit.slots() << width <= kMemoCodes) memo_.resize(unit.slots());
}

void LaneAccumulator::fold_code(std::size_t slot, std::int64_t t_raw, double fixed, double t,
                                double r_code) {
  const double model = unit_.model(slot, t_raw);
  const double ideal = unit_.float_model(slot, static_cast<double>(t_raw) * in_ulp_);
  stats_.approximation.add(ideal - r_code, t);
  stats_.parameter.add(model - ideal, t);
  stats_.datapath.add(fixed - model, t);
}

double LaneAccumulator::code_reference(std::size_t slot, std::int64_t t_raw, double fixed,
                                       double t) {
  if (memo_.empty()) {
    const double r = reference_value(slots_, slot, static_cast<double>(t_raw) * in_ulp_);
    fold_code(slot, t_raw, fixed, t, r);
    return r;
  }
  std::vector<double>& m = memo_[slot];
  if (m.empty())
    m.assign(std::size_t{1} << unit_.in_format().width(), std::numeric_limits<double>::quiet_NaN());
  double& r = m[static_cast<std::size_t>(t_raw - unit_.in_format().raw_min())];
  if (std::isnan(r)) {
    r = reference_value(slots_, slot, static_cast<double>(t_raw) * in_ulp_);
    fold_code(slot, t_raw, fixed, t, r);
  }
  return r;
}

void LaneAccumulator::add(std::size_t slot, const RowReference& ref, std::int64_t t_raw,
                          bool skipped, std::int64_t out_raw) {
  if (slot_state_[slot] < 0) {
    stats_.slots.push_back(slot_contract(unit_, slot, slots_));
    slot_state_[slot] = stats_.slots.back().always_skipped ? 1 : 0;
  }
  const double fixed = static_cast<double>(out_raw) * ulp_;
  const double err = fixed - ref.value;
  ++stats_.vectors;
  stats_.skipped += skipped;
  stats_.weighted.add(err * slots_.c_y[slot], ref.t);
  // A lobe that never reaches eps on the pixel is counted apart: its scalar error is the whole
  // lobe and would hide every other slot's (it stays in the weighted error and the digest).
  if (slot_state_[slot] == 1) {
    ++stats_.always_skipped_vectors;
  } else {
    add_scalar(slot, ref, t_raw, skipped, fixed);
  }
  // FNV-1a style over the whole result word (skip flag in bit 63), with a shift-xor so every bit
  // of the word reaches every bit of the digest.
  const std::uint64_t word = static_cast<std::uint64_t>(out_raw) ^ (std::uint64_t{skipped} << 63);
  digest_ = (digest_ ^ word) * 0x100000001b3ULL;
  digest_ ^= digest_ >> 29;
}

void LaneAccumulator::add_scalar(std::size_t slot, const RowReference& ref, std::int64_t t_raw,
                                 bool skipped, double fixed) {
  stats_.total.add(fixed - ref.value, ref.t);
  if (skipped) {
    stats_.skip.add(ref.value, ref.t);
  } else {
    stats_.input.add(code_reference(slot, t_raw, fixed, ref.t) - ref.value, ref.t);
  }
  const long ref_code = ref.display_bits == stats_.display_bits
                            ? ref.display
                            : std::lround(std::clamp(ref.value, 0.0, 1.0) * display_);
  if (std::lround(std::clamp(fixed, 0.0, 1.0) * display_) != ref_code) ++stats_.mismatch;
}

Evaluator::Evaluator(const VectorHeader& header, const std::vector<UnitSpec>& specs,
                     int display_bits)
    : slots_(make_slots(header)), display_bits_(display_bits) {
  for (const UnitSpec& spec : specs) units_.push_back(make_unit(spec, slots_.params));
  std::vector<std::string> names;
  for (const auto& u : units_) names.push_back(u->name());
  const auto labels = unit_labels(names);
  lanes_.reserve(units_.size());
  for (std::size_t i = 0; i < units_.size(); ++i) {
    lanes_.emplace_back(*units_[i], slots_, display_bits);
    lanes_.back().stats().name = labels[i];
    lanes_.back().stats().description = units_[i]->describe();
  }
}

void Evaluator::add(const VectorRow& row, const std::function<void(const EvalRecord&)>& dump) {
  const std::size_t slot = slots_.slot(row);
  const RowReference ref = make_reference(slots_, slot, row.t, display_bits_);
  for (std::size_t u = 0; u < units_.size(); ++u) {
    const SpecularUnit& unit = *units_[u];
    const std::int64_t t_raw = quantize_input(row.t, unit.in_format());
    const bool skipped = unit.skip(slot, t_raw);
    const std::int64_t raw = skipped ? 0 : unit.eval(slot, t_raw);
    lanes_[u].add(slot, ref, t_raw, skipped, raw);
    if (dump) {
      // The float model includes the skip decision: a skipped request is 0 in every view.
      const double model = skipped ? 0.0 : unit.float_model(slot, row.t);
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

namespace {

std::string lsb_cell(double v) {
  return v >= 9999.5 ? fmt::format("{:.2e}", v) : fmt::format("{:.2f}", v);
}

}  // namespace

std::string format_eval_table(const std::vector<UnitStats>& stats) {
  // Columns `glint sim`'s table has too (unit, vectors, skip%, max_err, dp_ulps) carry its headings
  // and unit-column width. Errors in LSBs of the display depth: lsb = observed, bound_lsb = the
  // contract's bound, wlsb = weighted by the slot's c_y (what reaches the pixel).
  const int bits = stats.empty() ? 8 : stats.front().display_bits;
  std::string out = fmt::format(
      "{:<9} {:>9} {:>7} {:>10} {:>8} {:>10} {:>9} {:>9} {:>9} {:>8} {:>7} {:<17}\n", "unit",
      "vectors", "skip%", "max_err", "t@max", "rms_err", fmt::format("lsb{}", bits), "bound_lsb",
      fmt::format("wlsb{}", bits), "dp_ulps", "disp%", "contract");
  for (const auto& s : stats) {
    const double lsb = display_scale(s.display_bits);
    out += fmt::format(
        "{:<9} {:>9} {:>6.1f}% {:>10.3e} {:>8.5f} {:>10.3e} {:>9} {:>9} {:>9} {:>8.3f} {:>6.2f}% "
        "{:<17}\n",
        s.name, s.vectors, s.vectors ? 100.0 * s.skipped / s.vectors : 0.0, s.total.max_abs,
        s.total.t_at_max, s.total.rms(), lsb_cell(s.total.max_abs * lsb),
        lsb_cell(s.bound().total() * lsb), lsb_cell(s.weighted.max_abs * lsb), s.max_ulps(),
        s.vectors ? 100.0 * s.mismatch / s.vectors : 0.0, to_string(s.contract()));
  }
  return out;
}

std::string format_parts_table(const std::vector<UnitStats>& stats) {
  const int bits = stats.empty() ? 8 : stats.front().display_bits;
  std::string out = fmt::format(
      "error parts, LSB of {}-bit output, observed / bound (contract.h):\n{:<9} {:>17} {:>17} "
      "{:>17} {:>17} {:>17}\n",
      bits, "unit", "input", "parameter", "approximation", "datapath", "skip");
  for (const auto& s : stats) {
    const double lsb = display_scale(s.display_bits);
    const ErrorParts b = s.bound();
    const auto cell = [&](const PartStats& p, double bound) {
      return lsb_cell(p.max_abs * lsb) + " / " + lsb_cell(bound * lsb);
    };
    out += fmt::format("{:<9} {:>17} {:>17} {:>17} {:>17} {:>17}\n", s.name, cell(s.input, b.input),
                       cell(s.parameter, b.parameter), cell(s.approximation, b.approximation),
                       cell(s.datapath, b.datapath), cell(s.skip, b.skip));
    for (const SlotContract& c : s.slots) {
      if (c.always_skipped) {
        out += fmt::format("{:<9} {} is always skipped (c_y <= eps): in no bound\n", "", c.name);
      } else if (c.kind == ContractKind::kBound || c.kind == ContractKind::kNone) {
        out += fmt::format("{:<9} {}: contract {}: {}\n", "", c.name, to_string(c.kind), c.reason);
      }
    }
  }
  return out;
}

}  // namespace glint
