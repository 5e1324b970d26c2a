#include "eval/energy.h"

#include <fmt/format.h>

#include <algorithm>

namespace glint {

EnergyParts& EnergyParts::operator+=(const EnergyParts& o) {
  register_pj += o.register_pj;
  clock_pj += o.clock_pj;
  datapath_pj += o.datapath_pj;
  leakage_pj += o.leakage_pj;
  for (std::size_t k = 0; k < kSwitchKinds; ++k) {
    datapath_kinds[k] += o.datapath_kinds[k];
    switching_bits[k] += o.switching_bits[k];
  }
  return *this;
}

double LaneEnergy::per_request() const {
  return requests ? total.total() / static_cast<double>(requests) : 0.0;
}

double LaneEnergy::per_computed() const {
  return computed ? total.total() / static_cast<double>(computed) : 0.0;
}

namespace {

double ratio(std::uint64_t toggles, int bits) {
  return bits > 0 ? static_cast<double>(toggles) / bits : 0.0;
}

}  // namespace

LaneEnergy lane_energy(const UnitCost& cost, const LaneActivity& a, const EnergyWeights& w) {
  LaneEnergy e;
  e.node = w.node;
  e.gating = a.gating;
  e.requests = a.requests;
  e.computed = a.computed;
  e.cycles = a.cycles;
  e.clock_ns = cost.critical_path_ns;
  // Stages of the energy: 0 the comparator, 1..m the unit's layout stages, m + 1 the merge
  // buffer. The inventory's stage index counts the cost's closed stages, which follow the layout
  // one for one (tests/eval/test_energy.cpp holds every unit to it); the lane's parts come after
  // the last.
  const std::size_t m = a.stages.empty() ? 0 : a.stages.size() - 1;
  const auto lane = static_cast<int>(cost.stages.size());
  e.stages.resize(m + 2);
  e.stages.front().stage = "comparator";
  for (std::size_t s = 1; s <= m; ++s) e.stages[s].stage = a.stages[s].name;
  e.stages.back().stage = "merge buffer";
  // What feeds each stage, as a toggle fraction summed over the stream, and its register toggles.
  std::vector<double> input(m + 2);
  std::vector<std::uint64_t> toggles(m + 2);
  input[0] = ratio(a.port_toggles, a.in_bits);
  toggles[0] = a.entry_toggles;
  for (std::size_t s = 1; s <= m; ++s) {
    input[s] = s == 1 ? ratio(a.entry_toggles, a.in_bits)
                      : ratio(a.stages[s - 1].toggles, a.stages[s - 1].bits);
    toggles[s] = a.stages[s].toggles;
  }
  input[m + 1] = ratio(a.output_toggles, a.out_bits);
  toggles[m + 1] = a.output_toggles + a.control_toggles;
  for (std::size_t s = 0; s < e.stages.size(); ++s)
    e.stages[s].pj.register_pj = static_cast<double>(toggles[s]) * w.register_bit;

  // nW x ns = 1e-18 J = 1e-6 pJ.
  const double leak_pj_per_um2 =
      w.leakage_nw_per_um2 * static_cast<double>(a.cycles) * e.clock_ns * 1e-6;
  const KindArray weight = kind_weights(w);
  for (const Primitive& p : cost.inventory) {
    const std::size_t s = p.stage >= lane ? m + 1 : std::min<std::size_t>(p.stage, m);
    EnergyParts& pj = e.stages[s].pj;
    // Pipeline registers stop with clock gating; tables and the lane's own registers do not.
    const bool gated = p.kind == "register" && p.stage < lane;
    pj.clock_pj += static_cast<double>(p.held_bits) *
                   static_cast<double>(gated ? a.clocked_cycles : a.cycles) * w.clock_bit;
    const KindArray bits = part_switching_bits(p);
    for (std::size_t k = 0; k < kSwitchKinds; ++k) {
      pj.switching_bits[k] += bits[k] * input[s];
      pj.datapath_kinds[k] += bits[k] * input[s] * weight[k];
      pj.datapath_pj += bits[k] * input[s] * weight[k];
    }
    pj.leakage_pj += p.um2 * leak_pj_per_um2;
  }
  for (const StageEnergy& s : e.stages) e.total += s.pj;
  return e;
}

namespace {

nlohmann::json parts_json(const EnergyParts& p, double n) {
  const auto per = [&](double x) { return n > 0 ? x / n : 0.0; };
  return {{"register", per(p.register_pj)},
          {"clock", per(p.clock_pj)},
          {"datapath", per(p.datapath_pj)},
          {"leakage", per(p.leakage_pj)},
          {"total", per(p.total())}};
}

}  // namespace

nlohmann::json energy_json(const LaneEnergy& e, std::optional<std::uint64_t> shaded_pixels) {
  const auto n = static_cast<double>(e.requests);
  nlohmann::json stages = nlohmann::json::array();
  for (const StageEnergy& s : e.stages) {
    nlohmann::json j = parts_json(s.pj, n);
    j["stage"] = s.stage;
    stages.push_back(std::move(j));
  }
  nlohmann::json by_kind = nlohmann::json::object(), bits = nlohmann::json::object();
  for (std::size_t k = 0; k < kSwitchKinds; ++k) {
    const char* name = to_string(static_cast<SwitchKind>(k));
    by_kind[name] = n > 0 ? e.total.datapath_kinds[k] / n : 0.0;
    bits[name] = n > 0 ? e.total.switching_bits[k] / n : 0.0;
  }
  const EnergyScale& f = energy_scale();
  nlohmann::json j = {{"node", e.node},
                      {"gating", to_string(e.gating)},
                      {"calibrated", true},
                      {"scale",
                       {{"register_bit", f.register_bit},
                        {"clock_bit", f.clock_bit},
                        {"adder_bit", f.adder_bit},
                        {"multiplier_bit", f.multiplier_bit},
                        {"comparator_bit", f.comparator_bit},
                        {"mux_bit", f.mux_bit},
                        {"table_bit", f.table_bit},
                        {"gate", f.gate},
                        {"leakage", f.leakage}}},
                      {"clock_ns", e.clock_ns},
                      {"requests", e.requests},
                      {"computed", e.computed},
                      {"cycles", e.cycles},
                      {"total_pj", e.total.total()},
                      {"pj_per_request", e.per_request()},
                      {"pj_per_computed", e.per_computed()},
                      {"per_request", parts_json(e.total, n)},
                      {"datapath_by_kind", by_kind},
                      {"switching_bits_by_kind", bits},
                      {"stages", stages}};
  if (shaded_pixels) {
    j["shaded_pixels"] = *shaded_pixels;
    j["pj_per_shaded_pixel"] =
        *shaded_pixels ? e.total.total() / static_cast<double>(*shaded_pixels) : 0.0;
  }
  return j;
}

std::string format_energy(const nlohmann::json& e) {
  const nlohmann::json& p = e.at("per_request");
  std::string line = fmt::format(
      "energy at {} (gating {}, {:.2f} ns clock): {:.2f} pJ per request, {:.2f} per computed one",
      e.at("node").get<std::string>(), e.at("gating").get<std::string>(),
      e.at("clock_ns").get<double>(), e.at("pj_per_request").get<double>(),
      e.at("pj_per_computed").get<double>());
  if (const auto px = e.find("pj_per_shaded_pixel"); px != e.end())
    line += fmt::format(", {:.2f} per shaded pixel", px->get<double>());
  line += fmt::format(
      " (register {:.2f}, clock {:.2f}, datapath {:.2f}, leakage {:.3f} a request; fitted "
      "to gate level)",
      p.at("register").get<double>(), p.at("clock").get<double>(), p.at("datapath").get<double>(),
      p.at("leakage").get<double>());
  return line;
}

}  // namespace glint
