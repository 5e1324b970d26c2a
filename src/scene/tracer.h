// The ray caster: one primary ray through each pixel's centre, nearest hit over a BVH of the
// scene's triangles, spheres and planes. No shadows, no secondary rays (the papers' local Phong
// model). Build is O(T log T); tracing is const and thread-safe, so callers trace rows in
// parallel. Results are deterministic: they do not depend on threads or on the order of calls.
#pragma once

#include <cstdint>
#include <memory>

#include "scene/scene.h"

namespace glint {

// What the camera sees at one pixel.
struct SurfaceSample {
  bool hit = false;
  std::uint32_t material = 0;
  Vec3 position;
  Vec3 normal;  // unit shading normal, turned towards the viewer (two-sided surfaces)
  Vec3 view;    // unit vector from the surface to the eye
};

// One light at one surface sample: the cosines a specular unit is fed.
struct LightSample {
  Vec3 to_light;       // unit vector from the surface to the light
  double n_dot_l = 0;  // <= 0: the surface faces away from the light (no request is made)
  double t_phong = 0;  // r . v, r the mirror direction of to_light about the normal
  double t_blinn = 0;  // n . h, h = normalize(to_light + view)
};

class SceneTracer {
 public:
  explicit SceneTracer(const Scene& scene);  // builds the BVH; the scene must outlive the tracer
  ~SceneTracer();
  SceneTracer(const SceneTracer&) = delete;
  SceneTracer& operator=(const SceneTracer&) = delete;

  // The sample at pixel (x, y), y = 0 the top row.
  SurfaceSample trace(int x, int y) const;
  // Rows [y0, y1) into out[(y - y0) * width + x].
  void trace_rows(int y0, int y1, SurfaceSample* out) const;

  std::size_t triangles() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The cosines of light `light` at a sample (sample.hit must be true).
LightSample light_sample(const Scene& scene, const SurfaceSample& sample, std::size_t light);

}  // namespace glint
