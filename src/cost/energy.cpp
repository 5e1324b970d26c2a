#include "cost/energy.h"

#include "cost/energy_fit_osu018.h"
#include "cost/energy_osu018.h"

namespace glint {

const EnergyScale& energy_scale() {
  static const EnergyScale s = make_energy_scale_osu018();
  return s;
}

namespace {

EnergyWeights scaled(EnergyWeights w, const EnergyScale& s) {
  w.register_bit *= s.register_bit;
  w.clock_bit *= s.clock_bit;
  w.adder_bit *= s.adder_bit;
  w.multiplier_bit *= s.multiplier_bit;
  w.comparator_bit *= s.comparator_bit;
  w.mux_bit *= s.mux_bit;
  w.table_bit *= s.table_bit;
  w.gate *= s.gate;
  w.leakage_nw_per_um2 *= s.leakage;
  return w;
}

}  // namespace

const EnergyWeights* find_energy(const std::string& node) {
  static const EnergyWeights osu018 = scaled(make_energy_osu018(), energy_scale());
  return node == osu018.node ? &osu018 : nullptr;
}

PartSwitching part_switching(const Primitive& p, const EnergyWeights& w) {
  const double a = p.width_a, b = p.width_b, n = p.count;
  const std::string& k = p.kind;
  if (k == "adder") return {n * a, w.adder_bit};
  if (k == "comparator") return {n * a, w.comparator_bit};
  if (k == "multiplier") return {n * a * b, w.multiplier_bit};
  if (k == "divider") return {n * a * (b + 1), w.adder_bit + w.mux_bit};
  if (k == "mux") return {n * a * (b - 1), w.mux_bit};
  if (k == "shifter") return {n * a * b, w.mux_bit};
  if (k == "lzd" || k == "gates") return {n * a, w.gate};
  if (k == "table") return {n * b * clog2(p.width_a), w.table_bit};
  return {};  // registers: counted toggles
}

const char* to_string(SwitchKind k) {
  switch (k) {
    case SwitchKind::kAdder:
      return "adder";
    case SwitchKind::kMultiplier:
      return "multiplier";
    case SwitchKind::kComparator:
      return "comparator";
    case SwitchKind::kMux:
      return "mux";
    case SwitchKind::kTable:
      return "table";
    case SwitchKind::kGate:
      return "gate";
  }
  return "adder";
}

KindArray part_switching_bits(const Primitive& p) {
  KindArray bits{};
  const auto at = [&bits](SwitchKind k) -> double& { return bits[static_cast<std::size_t>(k)]; };
  // part_switching's bits do not depend on the weights.
  const double n = part_switching(p, EnergyWeights{}).bits;
  const std::string& k = p.kind;
  if (k == "divider") {
    at(SwitchKind::kAdder) = n;
    at(SwitchKind::kMux) = n;
  } else if (k == "adder") {
    at(SwitchKind::kAdder) = n;
  } else if (k == "comparator") {
    at(SwitchKind::kComparator) = n;
  } else if (k == "multiplier") {
    at(SwitchKind::kMultiplier) = n;
  } else if (k == "mux" || k == "shifter") {
    at(SwitchKind::kMux) = n;
  } else if (k == "lzd" || k == "gates") {
    at(SwitchKind::kGate) = n;
  } else if (k == "table") {
    at(SwitchKind::kTable) = n;
  }
  return bits;
}

KindArray kind_weights(const EnergyWeights& w) {
  return {w.adder_bit, w.multiplier_bit, w.comparator_bit, w.mux_bit, w.table_bit, w.gate};
}

}  // namespace glint
