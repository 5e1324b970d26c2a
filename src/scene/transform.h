// An object's placement: scale, then rotations about X, Y and Z (degrees, in that order), then a
// translation. Normals go through the inverse transpose of the linear part, which for a rotation
// R and a positive scale S is R S^-1: no general matrix inverse is needed.
#pragma once

#include "scene/scene.h"
#include "scene/vec3.h"

namespace glint {

struct Transform {
  Vec3 scale{1, 1, 1};  // every component > 0
  Vec3 rotate_degrees;  // about X, then Y, then Z
  Vec3 translate;

  Vec3 point(Vec3 p) const;
  Vec3 normal(Vec3 n) const;  // unit length (n must be non-zero)
  bool identity() const;
};

// Transforms a mesh's positions and normals in place.
void apply(const Transform& t, Mesh& mesh);

}  // namespace glint
