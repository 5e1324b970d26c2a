#include "scene/tracer.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "scene/bvh.h"

namespace glint {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A triangle ready for Moller-Trumbore: a corner and the two edges from it.
struct Triangle {
  Vec3 p0, e1, e2;
  std::uint32_t mesh, face;
};

struct Hit {
  double t = Aabb::kInf;
  std::uint32_t primitive = 0;  // triangles first, then spheres
  double u = 0, v = 0;          // barycentrics of the triangle's second and third corner
};

// Moller & Trumbore 1997, "Fast, Minimum Storage Ray/Triangle Intersection".
bool hit_triangle(const Triangle& tri, Vec3 o, Vec3 d, double t_max, Hit& hit) {
  const Vec3 p = cross(d, tri.e2);
  const double det = dot(tri.e1, p);
  if (det == 0) return false;  // parallel, or a zero-area triangle (a pole of a Bezier patch)
  const double inv = 1 / det;
  const Vec3 s = o - tri.p0;
  const double u = dot(s, p) * inv;
  if (!(u >= 0 && u <= 1)) return false;  // also rejects NaN from a near-zero det
  const Vec3 q = cross(s, tri.e1);
  const double v = dot(d, q) * inv;
  if (!(v >= 0 && u + v <= 1)) return false;
  const double t = dot(tri.e2, q) * inv;
  if (!(t > 0 && t < t_max)) return false;
  hit.t = t;
  hit.u = u;
  hit.v = v;
  return true;
}

// The nearest t > 0 on the sphere (the far side when the ray starts inside), or +inf.
double hit_sphere(const Sphere& s, Vec3 o, Vec3 d) {
  const Vec3 oc = o - s.center;
  const double b = dot(oc, d);
  const double c = dot(oc, oc) - s.radius * s.radius;
  const double disc = b * b - c;
  if (!(disc >= 0)) return Aabb::kInf;
  // The root of larger magnitude first (no cancellation), the other from the product c.
  const double q = b > 0 ? -b - std::sqrt(disc) : -b + std::sqrt(disc);
  if (q == 0) return Aabb::kInf;  // tangent at the origin: t = 0 is not in front
  const double near = std::min(q, c / q), far = std::max(q, c / q);
  if (near > 0) return near;
  return far > 0 ? far : Aabb::kInf;
}

}  // namespace

struct SceneTracer::Impl {
  const Scene& scene;
  std::vector<Triangle> triangles;
  std::unique_ptr<Bvh> bvh;
  Vec3 eye, forward, right, up;
  double tan_half = 0, aspect = 1;

  explicit Impl(const Scene& s) : scene(s) {
    std::vector<Aabb> boxes;
    for (std::uint32_t m = 0; m < scene.meshes.size(); ++m) {
      const Mesh& mesh = scene.meshes[m];
      for (std::uint32_t f = 0; f < mesh.faces.size(); ++f) {
        const auto& face = mesh.faces[f];
        const Vec3 a = mesh.positions[face[0]], b = mesh.positions[face[1]],
                   c = mesh.positions[face[2]];
        triangles.push_back({a, b - a, c - a, m, f});
        Aabb box;
        box.grow(a);
        box.grow(b);
        box.grow(c);
        boxes.push_back(box);
      }
    }
    for (const Sphere& sp : scene.spheres) {
      const Vec3 r{sp.radius, sp.radius, sp.radius};
      Aabb box;
      box.grow(sp.center - r);
      box.grow(sp.center + r);
      boxes.push_back(box);
    }
    bvh = std::make_unique<Bvh>(boxes);

    const SceneCamera& cam = scene.camera;
    eye = cam.position;
    forward = normalize(cam.look_at - cam.position);
    right = normalize(cross(forward, cam.up));
    up = cross(right, forward);
    tan_half = std::tan(cam.fov_y_degrees * kPi / 360);
    aspect = static_cast<double>(cam.width) / cam.height;
  }

  SurfaceSample trace(int x, int y) const {
    const SceneCamera& cam = scene.camera;
    const double sx = (2 * (x + 0.5) / cam.width - 1) * tan_half * aspect;
    const double sy = (1 - 2 * (y + 0.5) / cam.height) * tan_half;
    const Vec3 d = normalize(forward + right * sx + up * sy);

    Hit best;
    double nearest = Aabb::kInf;  // best.t once something is hit: the traversal prunes with it
    const auto n_tri = static_cast<std::uint32_t>(triangles.size());
    bvh->traverse(eye, safe_inverse(d), nearest, [&](std::uint32_t prim, double& t_max) {
      if (prim < n_tri) {
        Hit h;
        if (hit_triangle(triangles[prim], eye, d, t_max, h)) {
          best = h;
          best.primitive = prim;
          t_max = h.t;
        }
      } else {
        const double t = hit_sphere(scene.spheres[prim - n_tri], eye, d);
        if (t < t_max) {
          best = Hit{t, prim, 0, 0};
          t_max = t;
        }
      }
    });
    std::size_t plane_hit = scene.planes.size();
    for (std::size_t i = 0; i < scene.planes.size(); ++i) {
      const Plane& pl = scene.planes[i];
      const double den = dot(pl.normal, d);
      if (den == 0) continue;
      const double t = dot(pl.point - eye, pl.normal) / den;
      if (t > 0 && t < best.t) {
        best.t = t;
        plane_hit = i;
      }
    }

    SurfaceSample s;
    if (best.t == Aabb::kInf) return s;
    s.hit = true;
    s.position = eye + d * best.t;
    s.view = -d;
    if (plane_hit < scene.planes.size()) {
      s.normal = scene.planes[plane_hit].normal;
      s.material = scene.planes[plane_hit].material;
    } else if (best.primitive < n_tri) {
      const Triangle& tri = triangles[best.primitive];
      const Mesh& mesh = scene.meshes[tri.mesh];
      const auto& f = mesh.faces[tri.face];
      const Vec3 n = mesh.normals[f[0]] * (1 - best.u - best.v) + mesh.normals[f[1]] * best.u +
                     mesh.normals[f[2]] * best.v;
      // Opposite vertex normals can cancel: fall back to the face's own normal.
      s.normal = length(n) > 0 ? normalize(n) : normalize(cross(tri.e1, tri.e2));
      s.material = mesh.material;
    } else {
      const Sphere& sp = scene.spheres[best.primitive - n_tri];
      s.normal = normalize(s.position - sp.center);
      s.material = sp.material;
    }
    if (dot(s.normal, s.view) < 0) s.normal = -s.normal;
    return s;
  }
};

SceneTracer::SceneTracer(const Scene& scene) : impl_(std::make_unique<Impl>(scene)) {}

SceneTracer::~SceneTracer() = default;

SurfaceSample SceneTracer::trace(int x, int y) const {
  const SceneCamera& cam = impl_->scene.camera;
  if (x < 0 || y < 0 || x >= cam.width || y >= cam.height) {
    throw std::invalid_argument("SceneTracer::trace: pixel (" + std::to_string(x) + ", " +
                                std::to_string(y) + ") outside the image");
  }
  return impl_->trace(x, y);
}

void SceneTracer::trace_rows(int y0, int y1, SurfaceSample* out) const {
  const SceneCamera& cam = impl_->scene.camera;
  if (y0 < 0 || y1 > cam.height || y0 > y1) {
    throw std::invalid_argument("SceneTracer::trace_rows: rows [" + std::to_string(y0) + ", " +
                                std::to_string(y1) + ") outside the image");
  }
  for (int y = y0; y < y1; ++y) {
    for (int x = 0; x < cam.width; ++x) *out++ = impl_->trace(x, y);
  }
}

std::size_t SceneTracer::triangles() const {
  return impl_->triangles.size();
}

LightSample light_sample(const Scene& scene, const SurfaceSample& sample, std::size_t light) {
  if (!sample.hit) throw std::invalid_argument("light_sample: the sample is not a hit");
  if (light >= scene.lights.size()) throw std::invalid_argument("light_sample: no such light");
  const SceneLight& l = scene.lights[light];
  LightSample out;
  out.to_light =
      l.kind == LightKind::kPoint ? normalize(l.position - sample.position) : -l.direction;
  const Vec3 n = sample.normal, v = sample.view, to = out.to_light;
  out.n_dot_l = dot(n, to);
  out.t_phong = dot(n * (2 * out.n_dot_l) - to, v);
  out.t_blinn = dot(n, normalize(to + v));
  return out;
}

}  // namespace glint
