#include "scene/bvh.h"

#include <array>
#include <cmath>
#include <stdexcept>

namespace glint {

void Aabb::grow(Vec3 p) {
  lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
  hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
}

void Aabb::grow(const Aabb& b) {
  // Component-wise, so that growing by an empty box (lo = +inf, hi = -inf) changes nothing.
  lo = {std::min(lo.x, b.lo.x), std::min(lo.y, b.lo.y), std::min(lo.z, b.lo.z)};
  hi = {std::max(hi.x, b.hi.x), std::max(hi.y, b.hi.y), std::max(hi.z, b.hi.z)};
}

double Aabb::half_area() const {
  if (!(lo.x <= hi.x)) return 0;
  const Vec3 d = hi - lo;
  return d.x * d.y + d.y * d.z + d.z * d.x;
}

namespace {

constexpr int kBins = 12;
constexpr std::uint32_t kMaxLeaf = 4;

double axis(Vec3 v, int a) {
  return a == 0 ? v.x : a == 1 ? v.y : v.z;
}

struct Split {
  int axis = -1;
  double cost = Aabb::kInf;
  double at = 0;  // centroids below `at` go left
};

// The cheapest binned split of order[begin, end) by the surface area heuristic.
Split best_split(const std::vector<Aabb>& boxes, const std::vector<Vec3>& centres,
                 const std::uint32_t* first, std::uint32_t count, const Aabb& centre_box) {
  Split best;
  for (int a = 0; a < 3; ++a) {
    const double lo = axis(centre_box.lo, a), extent = axis(centre_box.hi, a) - lo;
    // Finite scenes (kSceneMaxCoordinate) have finite extents; an infinite one would bin NaNs.
    if (!(extent > 0) || !std::isfinite(extent)) continue;
    std::array<Aabb, kBins> bin_box;
    std::array<std::uint32_t, kBins> bin_count{};
    const auto bin_of = [&](std::uint32_t prim) {
      const int b = static_cast<int>((axis(centres[prim], a) - lo) / extent * kBins);
      return std::min(b, kBins - 1);
    };
    for (std::uint32_t i = 0; i < count; ++i) {
      const int b = bin_of(first[i]);
      bin_box[b].grow(boxes[first[i]]);
      ++bin_count[b];
    }
    // Sweep from the right to get each suffix's area, then from the left for the costs.
    std::array<double, kBins> right_area{};
    std::array<std::uint32_t, kBins> right_count{};
    Aabb acc;
    std::uint32_t n = 0;
    for (int b = kBins - 1; b > 0; --b) {
      acc.grow(bin_box[b]);
      n += bin_count[b];
      right_area[b] = acc.half_area();
      right_count[b] = n;
    }
    acc = Aabb();
    n = 0;
    for (int b = 0; b < kBins - 1; ++b) {
      acc.grow(bin_box[b]);
      n += bin_count[b];
      if (n == 0 || right_count[b + 1] == 0) continue;
      const double cost = acc.half_area() * n + right_area[b + 1] * right_count[b + 1];
      if (cost < best.cost) best = {a, cost, lo + extent * (b + 1) / kBins};
    }
  }
  return best;
}

}  // namespace

Bvh::Bvh(const std::vector<Aabb>& boxes) {
  if (boxes.size() >= std::numeric_limits<std::uint32_t>::max() / 2) {
    throw std::invalid_argument("Bvh: too many primitives");
  }
  if (boxes.empty()) return;
  std::vector<Vec3> centres;
  centres.reserve(boxes.size());
  for (const Aabb& b : boxes) centres.push_back(b.centre());
  order_.resize(boxes.size());
  for (std::uint32_t i = 0; i < order_.size(); ++i) order_[i] = i;

  struct Task {
    std::uint32_t node, begin, end;
    int depth;
  };
  std::vector<Task> tasks{{0, 0, static_cast<std::uint32_t>(boxes.size()), 0}};
  nodes_.emplace_back();
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    Aabb box, centre_box;
    for (std::uint32_t i = t.begin; i < t.end; ++i) {
      box.grow(boxes[order_[i]]);
      centre_box.grow(centres[order_[i]]);
    }
    nodes_[t.node].box = box;
    const std::uint32_t count = t.end - t.begin;
    std::uint32_t mid = t.begin + count / 2;
    bool leaf = count <= kMaxLeaf;
    if (!leaf && t.depth < kSahDepth) {
      const Split s = best_split(boxes, centres, order_.data() + t.begin, count, centre_box);
      if (s.axis < 0) {
        leaf = count <= 4 * kMaxLeaf;  // every centre in one point: split by position in order_
      } else if (s.cost >= box.half_area() * count && count <= 4 * kMaxLeaf) {
        leaf = true;  // splitting would not pay for the extra box tests
      } else {
        mid = static_cast<std::uint32_t>(
            std::partition(order_.begin() + t.begin, order_.begin() + t.end,
                           [&](std::uint32_t p) { return axis(centres[p], s.axis) < s.at; }) -
            order_.begin());
      }
    } else if (!leaf) {
      // Deep enough: object median on the widest axis, so the depth stays bounded.
      const Vec3 e = centre_box.hi - centre_box.lo;
      const int a = e.x >= e.y && e.x >= e.z ? 0 : e.y >= e.z ? 1 : 2;
      std::nth_element(order_.begin() + t.begin, order_.begin() + mid, order_.begin() + t.end,
                       [&](std::uint32_t p, std::uint32_t q) {
                         return axis(centres[p], a) < axis(centres[q], a) ||
                                (axis(centres[p], a) == axis(centres[q], a) && p < q);
                       });
    }
    if (leaf) {
      nodes_[t.node].first = t.begin;
      nodes_[t.node].count = count;
      continue;
    }
    if (mid == t.begin || mid == t.end) mid = t.begin + count / 2;  // binning vs. "< at" rounding
    const auto left = static_cast<std::uint32_t>(nodes_.size());
    nodes_[t.node].first = left;
    nodes_[t.node].count = 0;
    nodes_.emplace_back();
    nodes_.emplace_back();
    tasks.push_back({left + 1, mid, t.end, t.depth + 1});
    tasks.push_back({left, t.begin, mid, t.depth + 1});
  }
}

}  // namespace glint
