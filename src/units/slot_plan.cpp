#include "units/slot_plan.h"

#include <fmt/format.h>

#include <stdexcept>

namespace glint {

void check_slot_plan(const SlotPlan& plan) {
  if (plan.group.size() != plan.params.size())
    // not from a spec: the evaluation layer builds the plan
    throw std::invalid_argument(fmt::format("slot plan: {} slots but {} group indices",
                                            plan.params.size(), plan.group.size()));
  std::vector<bool> used(plan.groups.size(), false);
  for (std::size_t s = 0; s < plan.group.size(); ++s) {
    if (plan.group[s] >= plan.groups.size())
      // not from a spec: the evaluation layer builds the plan
      throw std::invalid_argument(fmt::format("slot plan: slot {} names group {} of {}", s,
                                              plan.group[s], plan.groups.size()));
    used[plan.group[s]] = true;
  }
  for (std::size_t g = 0; g < used.size(); ++g)
    // not from a spec: the evaluation layer builds the plan
    if (!used[g]) throw std::invalid_argument(fmt::format("slot plan: group {} serves no slot", g));
  if (!plan.origin.empty() && plan.origin.size() != plan.params.size())
    // not from a spec: the evaluation layer builds the plan
    throw std::invalid_argument(
        fmt::format("slot plan: {} slots but {} origins", plan.params.size(), plan.origin.size()));
  // --chip's capacities: range-checked and named by the command line, which words the refusal of
  // a stream beyond the chip (SlotCapacityError) too.
  const auto check = [](std::size_t capacity, std::size_t used, const char* what) {
    if (capacity > kMaxSlotCapacity)
      // not from a spec: --chip
      throw std::invalid_argument(
          fmt::format("{} capacity {}: at most {}", what, capacity, kMaxSlotCapacity));
    if (capacity > 0 && capacity < used)
      // not from a spec: --chip
      throw std::invalid_argument(
          fmt::format("{} capacity {}: the stream needs {}", what, capacity, used));
  };
  check(plan.slot_capacity, plan.params.size(), "slot");
  check(plan.group_capacity, plan.groups.size(), "material");
}

}  // namespace glint
