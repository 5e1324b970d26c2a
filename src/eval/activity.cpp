#include "eval/activity.h"

#include <fmt/format.h>

#include <algorithm>
#include <bitset>
#include <stdexcept>

#include "units/stages.h"
#include "units/unit.h"

namespace glint {

const char* to_string(Gating g) {
  switch (g) {
    case Gating::kNone:
      return "none";
    case Gating::kOperand:
      return "operand";
    case Gating::kClock:
      return "clock";
  }
  return "none";
}

Gating parse_gating(const std::string& text) {
  if (text == "none") return Gating::kNone;
  if (text == "operand") return Gating::kOperand;
  if (text == "clock") return Gating::kClock;
  throw std::invalid_argument("gating '" + text + "': expected none, operand or clock");
}

std::uint64_t LaneActivity::toggles() const {
  std::uint64_t sum = 0;
  for (const StageActivity& s : stages) sum += s.toggles;
  return sum;
}

std::uint64_t LaneActivity::clocked_bits() const {
  std::uint64_t sum = 0;
  for (const StageActivity& s : stages) sum += s.clocked_bits;
  return sum;
}

namespace {

// The bits of a raw value a register of `width` bits holds (signed values in two's complement).
std::uint64_t register_bits(std::int64_t value, int width) {
  const auto v = static_cast<std::uint64_t>(value);
  return width >= 64 ? v : v & ((std::uint64_t{1} << width) - 1);
}

}  // namespace

ActivityCounter::ActivityCounter(const SpecularUnit& unit, Gating gating)
    : unit_(unit), ii_(static_cast<std::uint64_t>(unit.timing().ii)), schedule_(unit.timing(), {}) {
  const StageLayout& layout = unit.stages();
  activity_.gating = gating;
  for (const Stage& s : layout.stages()) activity_.stages.push_back(StageActivity{s.name});
  stage_of_.resize(layout.size());
  width_of_.resize(layout.size());
  for (int p = 1; p <= layout.latency(); ++p) {
    const std::size_t si = layout.stage_index_at(p);
    const Stage& s = layout.stages()[si];
    for (std::size_t r = 0; r < s.registers.size(); ++r) {
      const std::size_t i = layout.offset(p) + r;
      stage_of_[i] = si;
      width_of_[i] = s.registers[r].format.width();
      activity_.stages[si].bits += width_of_[i];
    }
  }
  values_.resize(layout.size());
  held_.assign(layout.size(), 0);
  activity_.in_bits = unit.in_format().width();
  activity_.out_bits = unit.out_format().width();
  entries_.assign(static_cast<std::size_t>(std::max(unit.timing().buffer_depth, 1)), 0);
}

void ActivityCounter::add(std::size_t slot, std::int64_t t_raw) {
  LaneActivity& a = activity_;
  ++a.requests;
  const bool skipped = unit_.skip(slot, t_raw);
  if (!skipped) ++a.computed;
  const bool enters = !skipped || a.gating == Gating::kNone;
  schedule_.next(!enters);
  const std::uint64_t cycles = schedule_.stats().cycles, added = cycles - a.cycles;
  a.cycles = cycles;
  const auto toggles = [](std::int64_t x, std::int64_t y, int width) {
    return std::bitset<64>(register_bits(x, width) ^ register_bits(y, width)).count();
  };
  a.port_toggles += toggles(t_raw, port_t_, a.in_bits);
  port_t_ = t_raw;
  std::int64_t result = 0;
  if (enters) {
    a.entry_toggles += toggles(t_raw, entry_t_, a.in_bits);
    entry_t_ = t_raw;
    unit_.eval_staged(slot, t_raw, values_.data());
    if (!skipped) result = values_[unit_.stages().result_index()];
    for (std::size_t i = 0; i < values_.size(); ++i) {
      const std::uint64_t changed =
          register_bits(values_[i], width_of_[i]) ^ register_bits(held_[i], width_of_[i]);
      a.stages[stage_of_[i]].toggles += std::bitset<64>(changed).count();
      held_[i] = values_[i];
    }
  }
  std::int64_t& entry = entries_[next_entry_];
  a.output_toggles += toggles(result, entry, a.out_bits);
  entry = result;
  next_entry_ = (next_entry_ + 1) % entries_.size();
  // Clock gating runs the stage registers II cycles per request they take; otherwise they are
  // clocked every cycle of the lane's.
  const std::uint64_t clocked = a.gating == Gating::kClock ? (enters ? ii_ : 0) : added;
  a.clocked_cycles += clocked;
  for (StageActivity& s : a.stages) s.clocked_bits += static_cast<std::uint64_t>(s.bits) * clocked;
}

nlohmann::json activity_json(const LaneActivity& a) {
  nlohmann::json stages = nlohmann::json::array();
  int bits = 0;
  for (const StageActivity& s : a.stages) {
    stages.push_back({{"stage", s.name},
                      {"bits", s.bits},
                      {"toggles", s.toggles},
                      {"clocked_bits", s.clocked_bits}});
    bits += s.bits;
  }
  const auto per = [](std::uint64_t x, std::uint64_t n) {
    return n ? static_cast<double>(x) / static_cast<double>(n) : 0.0;
  };
  return {{"gating", to_string(a.gating)},
          {"requests", a.requests},
          {"computed", a.computed},
          {"cycles", a.cycles},
          {"register_bits", bits},
          {"toggles", a.toggles()},
          {"clocked_bits", a.clocked_bits()},
          {"toggles_per_request", per(a.toggles(), a.requests)},
          {"toggles_per_computed", per(a.toggles(), a.computed)},
          {"clocked_fraction", per(a.clocked_bits(), static_cast<std::uint64_t>(bits) * a.cycles)},
          {"stages", stages}};
}

std::string format_activity(const nlohmann::json& a) {
  return fmt::format(
      "activity (gating {}): {:.1f} register bit toggles per request, {:.1f} per computed one; "
      "{} register bits, clocked on {:.1f} % of their cycles",
      a.at("gating").get<std::string>(), a.at("toggles_per_request").get<double>(),
      a.at("toggles_per_computed").get<double>(), a.at("register_bits").get<int>(),
      100.0 * a.at("clocked_fraction").get<double>());
}

LaneActivity measure_activity(const SpecularUnit& unit, const std::vector<ActivityRequest>& stream,
                              Gating gating) {
  ActivityCounter counter(unit, gating);
  for (const ActivityRequest& q : stream) counter.add(q.slot, q.t_raw);
  return counter.activity();
}

}  // namespace glint
