#include "eval/activity.h"

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

LaneActivity measure_activity(const SpecularUnit& unit, const std::vector<ActivityRequest>& stream,
                              Gating gating) {
  const StageLayout& layout = unit.stages();
  const int ii = unit.timing().ii;
  LaneActivity a;
  a.gating = gating;
  a.requests = stream.size();
  a.cycles = static_cast<std::uint64_t>(stream.size()) * static_cast<std::uint64_t>(ii);

  // Flat register index -> (stage, width): positions 1..L, each position's registers in order.
  std::vector<std::size_t> stage_of(layout.size());
  std::vector<int> width_of(layout.size());
  for (const Stage& s : layout.stages()) {
    StageActivity sa;
    sa.name = s.name;
    a.stages.push_back(sa);
  }
  for (int p = 1; p <= layout.latency(); ++p) {
    const std::size_t si = layout.stage_index_at(p);
    const Stage& s = layout.stages()[si];
    for (std::size_t r = 0; r < s.registers.size(); ++r) {
      const std::size_t i = layout.offset(p) + r;
      stage_of[i] = si;
      width_of[i] = s.registers[r].format.width();
      a.stages[si].bits += width_of[i];
    }
  }

  std::vector<std::int64_t> values(layout.size()), held(layout.size(), 0);
  for (const ActivityRequest& q : stream) {
    const bool skipped = unit.skip(q.slot, q.t_raw);
    if (!skipped) ++a.computed;
    const bool enters = !skipped || gating == Gating::kNone;
    if (enters) {
      unit.eval_staged(q.slot, q.t_raw, values.data());
      for (std::size_t i = 0; i < values.size(); ++i) {
        const std::uint64_t changed =
            register_bits(values[i], width_of[i]) ^ register_bits(held[i], width_of[i]);
        a.stages[stage_of[i]].toggles += std::bitset<64>(changed).count();
        held[i] = values[i];
      }
    }
    const bool clocked = enters || gating != Gating::kClock;
    if (clocked) {
      for (StageActivity& s : a.stages)
        s.clocked_bits += static_cast<std::uint64_t>(s.bits) * static_cast<std::uint64_t>(ii);
    }
  }
  return a;
}

}  // namespace glint
