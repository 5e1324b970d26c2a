// Pareto fronts of two objectives, both minimised (negate one to maximise it).
#pragma once

#include <vector>

namespace glint {

// on_front[i]: no other point is at least as good in both objectives and better in one. Points
// with the same pair of values are all on the front or all off it; a point with a non-finite
// objective (NaN, a missing value) is never on it and dominates nothing.
std::vector<bool> pareto_front(const std::vector<double>& a, const std::vector<double>& b);

}  // namespace glint
