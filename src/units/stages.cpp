#include "units/stages.h"

#include <fmt/format.h>

#include <set>
#include <stdexcept>

namespace glint {

Stage input_stage() {
  return {"in", 0, 0, {}};
}

StageLayout::StageLayout(std::vector<Stage> stages, int ii, const QFormat& out)
    : stages_(std::move(stages)) {
  int next = 0;
  std::set<std::string> names;
  for (std::size_t k = 0; k < stages_.size(); ++k) {
    const Stage& s = stages_[k];
    if (s.first != next || s.last < s.first)
      // not from a spec: a unit's stage layout, fixed by its code
      throw std::invalid_argument(
          fmt::format("stage layout: '{}' covers {}..{}, expected to start at {}", s.name, s.first,
                      s.last, next));
    if (s.name.empty() || s.name.find_first_of(". []") != std::string::npos ||
        !names.insert(s.name).second)
      // not from a spec: a unit's stage layout, fixed by its code
      throw std::invalid_argument(fmt::format("stage layout: bad or repeated name '{}'", s.name));
    if (s.last - s.first + 1 > ii)
      // not from a spec: a unit's stage layout, fixed by its code
      throw std::invalid_argument(
          fmt::format("stage layout: '{}' holds a request for {} cycles but the unit's II is {}",
                      s.name, s.last - s.first + 1, ii));
    for (const StageRegister& r : s.registers)
      if (r.format.width() < 1 || r.format.width() > 64)
        // not from a spec: a unit's stage layout, fixed by its code
        throw std::invalid_argument(
            fmt::format("stage layout: {}.{} has width {}", s.name, r.name, r.format.width()));
    for (int p = s.first; p <= s.last; ++p) stage_of_.push_back(k);
    next = s.last + 1;
  }
  if (stages_.empty() || stages_.front().name != "in")
    // not from a spec: a unit's stage layout, fixed by its code
    throw std::invalid_argument("stage layout: the first stage must be the input register 'in'");
  const Stage& last = stages_.back();
  if (last.last == 0 || last.registers.empty() || last.registers.back().name != "result" ||
      !(last.registers.back().format == out))
    // not from a spec: a unit's stage layout, fixed by its code
    throw std::invalid_argument(
        "stage layout: the last stage must end with the result register in the output format");
  offset_.assign(stage_of_.size() + 1, 0);
  for (std::size_t p = 1; p < stage_of_.size(); ++p)
    offset_[p + 1] = offset_[p] + stages_[stage_of_[p]].registers.size();
}

}  // namespace glint
