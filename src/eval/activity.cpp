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

std::uint64_t popcount(std::uint64_t x) {
  return std::bitset<64>(x).count();
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
  entry_skipped_.assign(entries_.size(), false);
  const auto b = static_cast<std::uint64_t>(entries_.size());
  for (std::uint64_t k = 0; k < b; ++k) tag_step_toggles_ += popcount(k ^ ((k + 1) % b));
}

void ActivityCounter::add(std::size_t slot, std::int64_t t_raw) {
  LaneActivity& a = activity_;
  ++a.requests;
  const bool skipped = unit_.skip(slot, t_raw);
  if (!skipped) ++a.computed;
  const bool enters = !skipped || a.gating == Gating::kNone;
  const ResultTiming r = schedule_.next(!enters);
  count_control(r, skipped, enters);
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

void ActivityCounter::count_control(const ResultTiming& r, bool skipped, bool enters) {
  const UnitTiming t = unit_.timing();
  const auto b = static_cast<std::uint64_t>(entries_.size());
  const std::uint64_t i = activity_.requests - 1;  // this request's tag is i mod B
  std::uint64_t n = 0;
  // issue_tag and head each step once a request (every B requests, tag_step_toggles_ in all);
  // cmp_tag0..L copy issue_tag every cycle, byp_tag on every issue.
  const std::uint64_t step = popcount((i % b) ^ ((i + 1) % b));
  const std::uint64_t copies =
      static_cast<std::uint64_t>(t.latency + 1) + (unit_.comparator_enabled() ? 1 : 0);
  n += step * (2 + copies);
  // in_flight: +1 at the issue's edge, -1 at each retire's, no change where both fall on one.
  while (!retires_.empty() && retires_.front() < r.issue) {
    n += popcount(in_flight_ ^ (in_flight_ - 1));
    --in_flight_;
    retires_.pop_front();
  }
  if (!retires_.empty() && retires_.front() == r.issue) {
    retires_.pop_front();
  } else {
    n += popcount(in_flight_ ^ (in_flight_ + 1));
    ++in_flight_;
  }
  retires_.push_back(r.retire);
  // A valid bit rises with the first of a run of issues on consecutive cycles and falls after the
  // last: byp_valid for the skipped ones, each of the L + 1 cmp_valid bits for the started ones.
  if (skipped && !enters) {
    if (last_bypass_ != r.issue) n += 2;
    last_bypass_ = r.issue + 1;
  } else {
    if (last_start_ != r.issue) n += 2 * static_cast<std::uint64_t>(t.latency + 1);
    last_start_ = r.issue + 1;
    // The II counter loads II - 1 and counts down to 0.
    for (auto k = static_cast<std::uint64_t>(t.ii - 1); k > 0; --k) n += popcount(k ^ (k - 1));
    n += popcount(static_cast<std::uint64_t>(t.ii - 1));
  }
  // A result that cannot leave as it arrives waits in its entry: valid set, then cleared as it
  // leaves; the skipped bit written.
  if (r.retire > r.done) {
    n += 2;
    const std::size_t e = i % b;
    const bool skip_bit = skipped && !enters;
    if (unit_.comparator_enabled() && entry_skipped_[e] != skip_bit) ++n;
    entry_skipped_[e] = skip_bit;
  }
  activity_.control_toggles += n;
}

LaneActivity ActivityCounter::activity() const {
  LaneActivity a = activity_;
  // The credits of the results still in flight, one retire an edge.
  for (std::uint64_t v = in_flight_; v > 0; --v) a.control_toggles += popcount(v ^ (v - 1));
  return a;
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
