#include "eval/evaluate.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>

#include "eval/chip_report.h"
#include "eval/engine.h"

namespace glint {
namespace {

Rgb rgb(const std::array<double, 3>& a) {
  return Rgb{a[0], a[1], a[2]};
}

// "light 2", "lights 0-3, 7", or for scattered sets "lights 0, 2, 4, 6, 8, 10, ... (512 lights)".
std::string light_list(const std::vector<int>& lights) {
  constexpr int kMaxRuns = 6;  // names stay readable with 1024 lights
  std::string out;
  int runs = 0;
  for (std::size_t i = 0; i < lights.size();) {
    std::size_t j = i;
    while (j + 1 < lights.size() && lights[j + 1] == lights[j] + 1) ++j;
    if (runs == kMaxRuns) {
      out += fmt::format(", ... ({} lights)", lights.size());
      break;
    }
    if (!out.empty()) out += ", ";
    out += j == i ? std::to_string(lights[i])
                  : fmt::format("{}{}{}", lights[i], j == i + 1 ? ", " : "-", lights[j]);
    ++runs;
    i = j + 1;
  }
  return (lights.size() > 1 ? "lights " : "light ") + out;
}

// Källberg's threshold for one material at one c_y (eq.5 for power lobes, eq.9 for Gaussian ones),
// with eps_K = eps / K over the K lights (§2).
MaterialParams slot_params(const VectorHeader& header, const VectorMaterial& m, double cy) {
  MaterialParams p;
  TauResult tau;
  if (m.lobe == Lobe::kGaussian) {
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
  return p;
}

}  // namespace

SlotMap make_slots(const VectorHeader& header, const Chip& chip) {
  SlotMap map;
  const std::size_t materials = header.materials.size();
  const auto lights = static_cast<std::size_t>(header.lights);
  map.materials = materials;
  map.slot_capacity = chip.slots;
  map.group_capacity = chip.materials;
  if (lights * materials > kMaxLightMaterialPairs)
    throw ResourceLimitError(fmt::format(
        "{} lights x {} materials are {} light x material pairs, more than the limit of {} per "
        "stream (each slot's report lists its lights: ~70 bytes per pair and unit)",
        lights, materials, lights * materials, kMaxLightMaterialPairs));

  // Slots in order of first use, light by light (light 0's materials first): with every light
  // white this is one slot per material in material order, and with every light changing every
  // material's c_y it is light x material, as before slots were shared.
  struct MaterialSlots {
    std::vector<double> c_y;          // distinct c_y, one per slot of the material
    std::vector<std::uint32_t> slot;  // their slots
  };
  std::vector<MaterialSlots> per_material(materials);
  std::vector<std::uint32_t> slot_of(lights * materials);
  for (std::size_t l = 0; l < lights; ++l) {
    const auto i = header.intensity(static_cast<int>(l));
    for (std::size_t mi = 0; mi < materials; ++mi) {
      const VectorMaterial& m = header.materials[mi];
      MaterialSlots& ms = per_material[mi];
      // A white light's product is the specular colour itself: its c_y is eq.6's exactly.
      const double cy = threshold_weight(header.eps_measure, rgb(i), rgb(m.specular));
      const Rgb w = channel_weights(rgb(i), rgb(m.specular));
      const auto it = std::find(ms.c_y.begin(), ms.c_y.end(), cy);
      std::uint32_t slot;
      if (it != ms.c_y.end()) {
        slot = ms.slot[static_cast<std::size_t>(it - ms.c_y.begin())];
        map.origin[slot].lights.push_back(static_cast<int>(l));
        Rgb& pw = map.pixel_weight[slot];
        pw = Rgb{std::max(pw.r, w.r), std::max(pw.g, w.g), std::max(pw.b, w.b)};
      } else {
        slot = static_cast<std::uint32_t>(map.params.size());
        if (map.params.size() == kMaxStreamSlots)
          throw ResourceLimitError(fmt::format(
              "the stream needs more than {} slots (one per material and c_y; {} materials under "
              "{} lights), the limit per stream (about 15 KB per slot and unit)",
              kMaxStreamSlots, materials, lights));
        ms.c_y.push_back(cy);
        ms.slot.push_back(slot);
        map.params.push_back(slot_params(header, m, cy));
        map.lobe.push_back(m.lobe);
        map.roughness.push_back(m.roughness);
        map.c_y.push_back(cy);
        map.pixel_weight.push_back(w);
        map.origin.push_back(SlotOrigin{mi, {static_cast<int>(l)}, cy, false});
      }
      slot_of[l * materials + mi] = slot;
    }
  }
  map.display = header.display;
  map.eps_measure = header.eps_measure;
  map.skip_ratio = header.eps_measure == EpsMeasure::kChannel ? 1.0 : 0.0;
  for (std::size_t s = 0; s < map.pixel_weight.size(); ++s) {
    map.pixel_weight_max.push_back(largest_channel(map.pixel_weight[s]));
    // The largest channel weight over c_y: at most 1 / 0.0722 (pure blue); 0 / 0 is a black slot.
    if (map.c_y[s] > 0)
      map.skip_ratio = std::max(map.skip_ratio, map.pixel_weight_max[s] / map.c_y[s]);
  }

  // Names: a material's only slot is the material; several slots say which lights give each.
  for (std::size_t s = 0; s < map.params.size(); ++s) {
    SlotOrigin& o = map.origin[s];
    const std::string& name = header.materials[o.material].name;
    o.own_tau = per_material[o.material].slot.size() > 1;
    map.per_light = map.per_light || o.own_tau;
    map.params[s].name =
        o.own_tau ? fmt::format("material '{}' under {} ({} {:.3g}: its own tau)", name,
                                light_list(o.lights),
                                header.eps_measure == EpsMeasure::kChannel ? "w_max" : "c_y", o.c_y)
                  : fmt::format("material '{}'", name);
  }
  if (map.per_light) {
    map.slot_of = std::move(slot_of);
    map.light_stride = materials;
  } else {
    map.slot_of.assign(slot_of.begin(), slot_of.begin() + static_cast<long>(materials));
  }

  // Datapath groups: a material's slots share one datapath, built from the params of its slot of
  // the largest c_y. tau (eq.5, eq.9) and the level eps_K / c_y fall as c_y grows, so that slot
  // has the smallest of both: its datapath covers every input any of the material's comparators
  // lets through (lut's table span, hast's root, horner's fit domain all start at it). Materials
  // whose datapaths would be identical (the same n and threshold) share one too.
  std::map<std::tuple<double, double, double, bool>, std::uint32_t> by_params;
  std::vector<std::uint32_t> group_of_material(materials);
  std::vector<std::vector<std::size_t>> group_materials;
  for (std::size_t mi = 0; mi < materials; ++mi) {
    const MaterialSlots& ms = per_material[mi];
    std::size_t best = 0;
    for (std::size_t k = 1; k < ms.c_y.size(); ++k)
      if (ms.c_y[k] > ms.c_y[best]) best = k;
    const MaterialParams& p = map.params[ms.slot[best]];
    const auto key = std::make_tuple(p.shininess, p.tau, p.level, p.always_skip);
    const auto [it, fresh] = by_params.emplace(key, static_cast<std::uint32_t>(map.groups.size()));
    if (fresh) {
      map.groups.push_back(p);
      group_materials.emplace_back();
    }
    group_of_material[mi] = it->second;
    group_materials[it->second].push_back(mi);
  }
  for (std::size_t g = 0; g < map.groups.size(); ++g) {
    const auto& ms = group_materials[g];
    map.groups[g].name = ms.size() == 1
                             ? fmt::format("material '{}'", header.materials[ms[0]].name)
                             : fmt::format("material '{}' (and {} more with the same datapath)",
                                           header.materials[ms[0]].name, ms.size() - 1);
  }
  map.group.resize(map.params.size());
  for (std::size_t s = 0; s < map.params.size(); ++s)
    map.group[s] = group_of_material[map.origin[s].material];

  if (chip.slots > kMaxSlotCapacity || chip.materials > kMaxSlotCapacity)
    throw SlotCapacityError(fmt::format("a chip holds at most {} slots and {} materials",
                                        kMaxSlotCapacity, kMaxSlotCapacity));
  if (chip.slots > 0 && map.params.size() > chip.slots)
    throw SlotCapacityError(fmt::format(
        "a chip of {} slots cannot hold this stream: it needs {} (one per material and c_y: {} "
        "materials under {} lights)",
        chip.slots, map.params.size(), materials, lights));
  if (chip.materials > 0 && map.groups.size() > chip.materials)
    throw SlotCapacityError(fmt::format(
        "a chip of {} materials cannot hold this stream: it needs {} (one per material with its "
        "own datapath)",
        chip.materials, map.groups.size()));
  return map;
}

std::string pixel_measure_line(const SlotMap& slots) {
  return fmt::format("pixel error: largest channel of light x specular, {} display; eps on {}",
                     to_string(slots.display),
                     slots.eps_measure == EpsMeasure::kChannel ? "the largest channel"
                                                               : "luminance c_y (Källberg eq.3)");
}

nlohmann::json pixel_measure_json(const SlotMap& slots) {
  return {{"display", to_string(slots.display)}, {"eps_measure", to_string(slots.eps_measure)}};
}

void check_lane_slots(std::size_t units, const SlotMap& slots) {
  if (units * slots.params.size() > kMaxLaneSlots)
    throw ResourceLimitError(fmt::format(
        "{} units x {} slots exceed the limit of {} unit slots per run (the default five units on "
        "{} slots, ~5 GB): run fewer units at a time",
        units, slots.params.size(), kMaxLaneSlots, kMaxStreamSlots));
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

bool UnitStats::bound_exact() const {
  for (const SlotContract& c : slots)
    if (!c.always_skipped && !c.exact) return false;
  return true;
}

double UnitStats::weighted_bound() const {
  double w = 0;
  for (const SlotContract& c : slots) w = std::max(w, c.weighted_bound());
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
  // `skipped_fraction` and `description` are eval's own (src/eval/eval_report.md).
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

LaneAccumulator::ContractKey key_of(const SpecularUnit& unit, const SlotMap& slots,
                                    std::size_t slot) {
  return {unit.datapath_of(slot),       unit.tau_raw(slot),    static_cast<int>(slots.lobe[slot]),
          slots.params[slot].shininess, slots.roughness[slot], slots.params[slot].always_skip};
}

}  // namespace

LaneAccumulator::ContractKey LaneAccumulator::contract_key(std::size_t slot) const {
  return key_of(unit_, slots_, slot);
}

std::uint64_t contract_codes(const SpecularUnit& unit, const SlotMap& slots) {
  const std::int64_t one = unit.in_format().raw_one();
  const std::uint64_t per_slot_max = (std::uint64_t{1} << kExactInputBits) + 1;
  std::uint64_t codes = 0;
  std::set<LaneAccumulator::ContractKey> sweeps;
  for (std::size_t s = 0; s < unit.slots(); ++s) {
    if (!sweeps.insert(key_of(unit, slots, s)).second) continue;
    if (slots.params[s].always_skip && unit.comparator_enabled()) continue;
    // The codes slot_contract visits: those above the threshold, up to 1.0.
    const std::int64_t first = std::max<std::int64_t>(std::min(unit.tau_raw(s), one) + 1, 0);
    codes += std::min(per_slot_max, static_cast<std::uint64_t>(one - first + 1));
  }
  return codes;
}

void check_contract_codes(const std::vector<const SpecularUnit*>& units, const SlotMap& slots) {
  std::uint64_t total = 0;
  std::string shares;
  for (const SpecularUnit* u : units) {
    const std::uint64_t codes = contract_codes(*u, slots);
    total += codes;
    shares += fmt::format("{}{} {}", shares.empty() ? "" : ", ", u->name(), codes);
  }
  if (total > kMaxContractCodes)
    throw ResourceLimitError(fmt::format(
        "the accuracy contracts of this run would sweep {} input codes over the stream's {} slots "
        "({}), more than the limit of {} (2^30, a few minutes) per run: use fewer materials or "
        "lights, fewer units at a time, fewer input fraction bits (in=) or the comparator "
        "(skip=on)",
        total, slots.params.size(), shares, kMaxContractCodes));
}

std::uint64_t memo_bytes(const QFormat& in, std::size_t slots) {
  // LaneAccumulator's condition for a memo.
  const int width = in.width();
  if (width > kMemoMaxWidth || (slots << width) > kMemoMaxCodes) return 0;
  // A slot's table holds the codes from above its threshold (at least 0) up to 1.0's.
  return kMemoBytesPerCode * (static_cast<std::uint64_t>(in.raw_one()) + 1) * slots;
}

void check_memo_bytes(const std::vector<const SpecularUnit*>& units) {
  std::uint64_t total = 0;
  for (const SpecularUnit* u : units) total += memo_bytes(u->in_format(), u->slots());
  if (total > kMaxMemoBytes)
    throw ResourceLimitError(fmt::format(
        "the memos of input codes of this run's {} units may take {} MiB, more than the limit of "
        "{} MiB per run ({} bytes per code above each slot's threshold, up to 2^F + 1 codes per "
        "slot for F fraction bits: about 1.3 MB per slot at in=uq1.15): run fewer units at a "
        "time (--unit) or narrower inputs (in=)",
        units.size(), total >> 20, kMaxMemoBytes >> 20, kMemoBytesPerCode));
}

Evaluator::Evaluator(const VectorHeader& header, const std::vector<UnitSpec>& specs,
                     int display_bits, const Chip& chip)
    : slots_(make_slots(header, chip)), chip_(chip), display_bits_(display_bits) {
  check_lane_slots(specs.size(), slots_);
  for (const UnitSpec& spec : specs_on_chip(specs, chip)) units_.push_back(make_unit(spec, slots_));
  std::vector<const SpecularUnit*> built;
  for (const auto& u : units_) built.push_back(u.get());
  check_contract_codes(built, slots_);
  check_memo_bytes(built);
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

Evaluator::~Evaluator() = default;

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
          {"pixel_measure", pixel_measure_json(slots_)},
          {"slots", slots_.params.size()},
          {"per_light_slots", slots_.per_light},
          {"datapath_groups", slots_.groups.size()},
          {"chip", chip_json(chip_, slots_)},
          {"units", units}};
}

namespace {

std::string lsb_cell(double v) {
  return v >= 9999.5 ? fmt::format("{:.2e}", v) : fmt::format("{:.2f}", v);
}

// A stated bound, marked "~" where it is an estimate (UnitStats::bound_exact).
std::string bound_cell(double v, bool exact) {
  return (exact ? "" : "~") + lsb_cell(v);
}

bool any_estimate(const std::vector<UnitStats>& stats) {
  for (const auto& s : stats)
    if (!s.bound_exact()) return true;
  return false;
}

}  // namespace

std::string format_eval_table(const std::vector<UnitStats>& stats) {
  // Every column but unit, skip% and contract is named as the measure it prints is named in the
  // JSON report, the sweep's CSV and a size budget (src/sweep/measures.h), LSB measures with their
  // depth (max_lsb8: max_abs in LSBs of an 8-bit display). Columns `glint sim`'s table has too
  // carry the same headings and unit-column width.
  const int bits = stats.empty() ? 8 : stats.front().display_bits;
  std::string out = fmt::format(
      "{:<9} {:>9} {:>7} {:>10} {:>8} {:>10} {:>9} {:>11} {:>18} {:>17} {:>17} {:<17}\n", "unit",
      "vectors", "skip%", "max_abs", "t_at_max", "rms", fmt::format("max_lsb{}", bits),
      fmt::format("bound_lsb{}", bits), fmt::format("weighted.max_lsb{}", bits),
      "max_datapath_ulps", "mismatch_fraction", "contract");
  for (const auto& s : stats) {
    const double lsb = display_scale(s.display_bits);
    out += fmt::format(
        "{:<9} {:>9} {:>6.1f}% {:>10.3e} {:>8.5f} {:>10.3e} {:>9} {:>11} {:>18} {:>17.3f} "
        "{:>17.4f} {:<17}\n",
        s.name, s.vectors, s.vectors ? 100.0 * s.skipped / s.vectors : 0.0, s.total.max_abs,
        s.total.t_at_max, s.total.rms(), lsb_cell(s.total.max_abs * lsb),
        bound_cell(s.bound().total() * lsb, s.bound_exact()), lsb_cell(s.weighted.max_abs * lsb),
        s.max_ulps(), s.vectors ? static_cast<double>(s.mismatch) / s.vectors : 0.0,
        to_string(s.contract()));
  }
  if (any_estimate(stats)) out += kEstimateNote;
  return out;
}

namespace {

// Which engine fitted the slots' coefficients and Sollya's certified sup norm of their error, for
// units whose slots say (horner: fit_engine, sup_norm; pwp per segment: sollya_segments,
// fitted_segments); nothing for the others.
std::string format_fit_engines(const nlohmann::json& description) {
  const auto slots = description.find("slots");
  if (slots == description.end()) return {};
  std::size_t fitted = 0, sollya = 0, certified = 0, segments = 0, sollya_segments = 0;
  bool per_segment = false;
  double sup = 0;
  for (const nlohmann::json& slot : *slots) {
    if (const auto e = slot.find("fit_engine"); e != slot.end()) {
      ++fitted;
      if (*e == "sollya") ++sollya;
    }
    if (const auto s = slot.find("sollya_segments"); s != slot.end()) {
      per_segment = true;
      sollya_segments += s->get<std::size_t>();
      segments += slot.value("fitted_segments", std::size_t{0});
    }
    if (const auto n = slot.find("sup_norm"); n != slot.end()) {
      ++certified;
      sup = std::max(sup, (*n)["hi"].get<double>());
    }
  }
  if (fitted == 0) return {};
  if (per_segment) {
    std::string out = fmt::format(
        "    fits: Sollya's fpminimax on {} of {} fitted segments ({} slot(s)), glint's on the "
        "rest",
        sollya_segments, segments, fitted);
    if (certified > 0)
      out +=
          fmt::format("; |P_k - t^n| <= {:.4g} on those segments, certified (Sollya supnorm)", sup);
    return out + "\n";
  }
  std::string out = fmt::format(
      "    fits: Sollya's fpminimax on {} of {} slots, glint's on the rest", sollya, fitted);
  if (certified > 0)
    out += fmt::format("; |P_q - t^n| <= {:.4g} certified (Sollya supnorm) on {} of them", sup,
                       certified);
  return out + "\n";
}

}  // namespace

std::string format_elaboration(const std::vector<UnitStats>& stats) {
  std::string out;
  for (const auto& s : stats) {
    const auto it = s.description.find("elaboration");
    if (it == s.description.end()) continue;
    const nlohmann::json& e = *it;
    std::string n;
    if (const auto nr = e.find("n_register"); nr != e.end()) {
      n = fmt::format(
          ", n register {} ({})", (*nr)["built"].get<std::string>(),
          (*nr)["exact"].get<bool>()
              ? "exact"
              : fmt::format("quantized: |n_q - n| up to {:.3g} at {}",
                            (*nr)["max_abs_error"].get<double>(), (*nr)["at"].get<std::string>()));
    }
    const bool sized = e["sized_to"] == "stream";
    out += fmt::format(
        "  {}: {} tables, {} slots ({}), {} datapath groups ({}), {} table entries{}\n", s.name,
        e["storage"].get<std::string>(), e["slots"].get<std::size_t>(),
        sized ? std::string("sized to the stream")
              : fmt::format("a chip of {}", e["capacity"].get<std::size_t>()),
        e["datapath_groups"].get<std::size_t>(),
        sized ? std::string("sized to the stream")
              : fmt::format("a chip of {} materials", e["group_capacity"].get<std::size_t>()),
        e["table_entries"].get<long long>(), n);
    if (const auto share = e.find("hardware_share"); share != e.end())
      out += fmt::format("    {}\n", (*share)["statement"].get<std::string>());
    out += format_fit_engines(s.description);
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
      return lsb_cell(p.max_abs * lsb) + " / " + bound_cell(bound * lsb, s.bound_exact());
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
  if (any_estimate(stats)) out += kEstimateNote;
  return out;
}

}  // namespace glint
