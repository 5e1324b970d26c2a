#include "scene/transform.h"

#include <cmath>

namespace glint {

namespace {

constexpr double kPi = 3.14159265358979323846;

Vec3 rotate(Vec3 v, Vec3 degrees) {
  const auto turn = [](double& a, double& b, double deg) {
    // Exact quarter turns (the teapot's -90) keep exact coordinates: cos(pi/2) is not 0 in double.
    double c = std::cos(deg * kPi / 180), s = std::sin(deg * kPi / 180);
    if (std::fmod(deg, 90.0) == 0) {
      c = std::round(c);
      s = std::round(s);
    }
    const double a2 = c * a - s * b, b2 = s * a + c * b;
    a = a2;
    b = b2;
  };
  turn(v.y, v.z, degrees.x);  // about X: y towards z
  turn(v.z, v.x, degrees.y);  // about Y: z towards x
  turn(v.x, v.y, degrees.z);  // about Z: x towards y
  return v;
}

}  // namespace

Vec3 Transform::point(Vec3 p) const {
  return rotate({p.x * scale.x, p.y * scale.y, p.z * scale.z}, rotate_degrees) + translate;
}

Vec3 Transform::normal(Vec3 n) const {
  return normalize(rotate({n.x / scale.x, n.y / scale.y, n.z / scale.z}, rotate_degrees));
}

bool Transform::identity() const {
  return scale.x == 1 && scale.y == 1 && scale.z == 1 && rotate_degrees.x == 0 &&
         rotate_degrees.y == 0 && rotate_degrees.z == 0 && translate.x == 0 && translate.y == 0 &&
         translate.z == 0;
}

void apply(const Transform& t, Mesh& mesh) {
  if (t.identity()) return;
  for (Vec3& p : mesh.positions) p = t.point(p);
  for (Vec3& n : mesh.normals) n = t.normal(n);
}

}  // namespace glint
