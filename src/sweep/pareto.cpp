#include "sweep/pareto.h"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace glint {

std::vector<bool> pareto_front(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size()) throw std::invalid_argument("pareto_front: sizes differ");
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::isfinite(a[i]) && std::isfinite(b[i])) order.push_back(i);
  // By a, then b: a point is dominated by an earlier point with a smaller a and a b no larger,
  // or by one with the same a and a smaller b. O(n log n).
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return a[i] != a[j] ? a[i] < a[j] : b[i] != b[j] ? b[i] < b[j] : i < j;
  });
  std::vector<bool> on(a.size(), false);
  double best_b = INFINITY;  // least b over the points of strictly smaller a
  for (std::size_t g = 0; g < order.size();) {
    std::size_t end = g;
    while (end < order.size() && a[order[end]] == a[order[g]]) ++end;
    const double group_b = b[order[g]];  // the least b of this a (sorted)
    if (group_b < best_b)
      for (std::size_t k = g; k < end && b[order[k]] == group_b; ++k) on[order[k]] = true;
    best_b = std::min(best_b, group_b);
    g = end;
  }
  return on;
}

}  // namespace glint
