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
  if (plan.capacity > kMaxSlotCapacity)
    // not from a spec: --slots, range-checked and named by the command line
    throw std::invalid_argument(
        fmt::format("slot capacity {}: at most {}", plan.capacity, kMaxSlotCapacity));
  if (plan.capacity > 0 && plan.capacity < plan.params.size())
    // not from a spec: --slots, whose refusal the command line words (SlotCapacityError)
    throw std::invalid_argument(fmt::format("slot capacity {}: the stream needs {} slots",
                                            plan.capacity, plan.params.size()));
}

}  // namespace glint
