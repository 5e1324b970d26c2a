// A bounding volume hierarchy over primitives given by their boxes: binned SAH build (12 bins per
// axis, deterministic: the same boxes give the same tree), iterative front-to-back traversal.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <vector>

#include "scene/vec3.h"

namespace glint {

struct Aabb {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  Vec3 lo{kInf, kInf, kInf}, hi{-kInf, -kInf, -kInf};

  void grow(Vec3 p);
  void grow(const Aabb& b);
  Vec3 centre() const { return (lo + hi) * 0.5; }
  double half_area() const;  // 0 for an empty box
};

struct BvhNode {
  Aabb box;
  std::uint32_t first = 0;  // leaf: first index into order(); inner: the left child (right = +1)
  std::uint32_t count = 0;  // leaf: number of primitives (> 0); inner: 0
};

class Bvh {
 public:
  // The traversal stack's size bounds the depth: the build splits at the object median below
  // kSahDepth, which adds at most log2(primitives) levels.
  static constexpr int kMaxDepth = 128;
  static constexpr int kSahDepth = 64;

  explicit Bvh(const std::vector<Aabb>& boxes);

  const std::vector<BvhNode>& nodes() const { return nodes_; }
  const std::vector<std::uint32_t>& order() const { return order_; }

  // Calls hit(primitive, t_max) for every primitive in a leaf whose box the ray (origin o,
  // component-wise inverse direction inv) enters before t_max; hit may lower t_max (the nearest
  // hit so far), which prunes the rest. Nearer children are visited first.
  template <class Hit>
  void traverse(Vec3 o, Vec3 inv, double& t_max, Hit&& hit) const;

 private:
  std::vector<BvhNode> nodes_;
  std::vector<std::uint32_t> order_;
};

// The distance at which the ray enters `box`, or +inf if it misses it before t_max. inv must be
// finite (safe_inverse): 0 * inf would be NaN for an axis-parallel ray on a box face.
inline double enter(const Aabb& box, Vec3 o, Vec3 inv, double t_max) {
  const double tx0 = (box.lo.x - o.x) * inv.x, tx1 = (box.hi.x - o.x) * inv.x;
  const double ty0 = (box.lo.y - o.y) * inv.y, ty1 = (box.hi.y - o.y) * inv.y;
  const double tz0 = (box.lo.z - o.z) * inv.z, tz1 = (box.hi.z - o.z) * inv.z;
  double t0 = tx0 < tx1 ? tx0 : tx1, t1 = tx0 < tx1 ? tx1 : tx0;
  t0 = std::max(t0, std::min(ty0, ty1));
  t1 = std::min(t1, std::max(ty0, ty1));
  t0 = std::max(t0, std::min(tz0, tz1));
  t1 = std::min(t1, std::max(tz0, tz1));
  t0 = std::max(t0, 0.0);
  return t0 <= t1 && t0 < t_max ? t0 : Aabb::kInf;
}

// 1 / d per component, a zero component replaced by a tiny one so the inverse stays finite.
inline Vec3 safe_inverse(Vec3 d) {
  const auto inv = [](double c) { return 1 / (c != 0 ? c : 1e-300); };
  return {inv(d.x), inv(d.y), inv(d.z)};
}

template <class Hit>
void Bvh::traverse(Vec3 o, Vec3 inv, double& t_max, Hit&& hit) const {
  if (nodes_.empty() || enter(nodes_[0].box, o, inv, t_max) == Aabb::kInf) return;
  std::uint32_t stack[kMaxDepth];
  int top = 0;
  std::uint32_t node = 0;
  for (;;) {
    const BvhNode& n = nodes_[node];
    if (n.count > 0) {
      for (std::uint32_t i = n.first; i < n.first + n.count; ++i) hit(order_[i], t_max);
    } else {
      const double tl = enter(nodes_[n.first].box, o, inv, t_max);
      const double tr = enter(nodes_[n.first + 1].box, o, inv, t_max);
      if (tl != Aabb::kInf || tr != Aabb::kInf) {
        const bool left_first = tl <= tr;
        node = left_first ? n.first : n.first + 1;
        if ((left_first ? tr : tl) != Aabb::kInf) stack[top++] = left_first ? n.first + 1 : n.first;
        continue;
      }
    }
    // Pop the next subtree that may still hold a nearer hit.
    for (;;) {
      if (top == 0) return;
      node = stack[--top];
      if (enter(nodes_[node].box, o, inv, t_max) != Aabb::kInf) break;
    }
  }
}

}  // namespace glint
