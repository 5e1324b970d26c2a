// The ray caster: hits on spheres, planes and triangles at known depths and normals, the camera's
// orientation, light_sample on hand-computed configurations, the BVH against brute force, and
// determinism over row ranges and threads.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "scene/scene.h"
#include "scene/tracer.h"

namespace glint {
namespace {

const std::string kScenes = std::string(GLINT_SOURCE_DIR) + "/traces/scenes";
constexpr double kPi = 3.14159265358979323846;

Scene camera_scene(Vec3 eye, Vec3 at, Vec3 up, int width, int height, double fov = 30) {
  Scene s;
  s.file = "memory";
  s.camera = SceneCamera{eye, at, up, fov, width, height};
  s.lights.push_back({"l", LightKind::kPoint, {0, 10, 0}, {}, {1, 1, 1}});
  s.materials.push_back({"m0", {0.5, 0.5, 0.5}, {1, 1, 1}, Lobe::kPhong, 10, 0});
  s.materials.push_back({"m1", {0.5, 0.5, 0.5}, {1, 1, 1}, Lobe::kBlinn, 10, 0});
  return s;
}

void expect_vec(Vec3 got, Vec3 want, double tol = 0) {
  EXPECT_NEAR(got.x, want.x, tol);
  EXPECT_NEAR(got.y, want.y, tol);
  EXPECT_NEAR(got.z, want.z, tol);
}

TEST(Tracer, SphereAtTheCentrePixel) {
  // 101 x 101: the centre pixel's ray is exactly the view direction.
  Scene s = camera_scene({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 101, 101);
  s.spheres.push_back({{0, 0, 0}, 1, 1});
  const SceneTracer tracer(s);
  EXPECT_EQ(tracer.triangles(), 0u);
  const SurfaceSample c = tracer.trace(50, 50);
  ASSERT_TRUE(c.hit);
  EXPECT_EQ(c.material, 1u);
  expect_vec(c.position, {0, 0, 1});  // depth 4 from the eye
  expect_vec(c.normal, {0, 0, 1});
  expect_vec(c.view, {0, 0, 1});
  EXPECT_FALSE(tracer.trace(0, 0).hit);  // the corner ray passes 1.9 units off the centre
}

TEST(Tracer, NearestOfTwoAndInside) {
  Scene s = camera_scene({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 101, 101);
  s.spheres.push_back({{0, 0, -3}, 1, 0});
  s.spheres.push_back({{0, 0, 0}, 1, 1});
  SurfaceSample c = SceneTracer(s).trace(50, 50);
  EXPECT_EQ(c.material, 1u);
  expect_vec(c.position, {0, 0, 1});
  // From inside a sphere the far side is hit, its normal turned towards the eye.
  s.camera.position = {0, 0, 0.5};
  c = SceneTracer(s).trace(50, 50);
  EXPECT_EQ(c.material, 1u);
  expect_vec(c.position, {0, 0, -1});
  expect_vec(c.normal, {0, 0, 1});
}

TEST(Tracer, RowZeroIsTheTop) {
  Scene s = camera_scene({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 40, 30, 60);
  s.spheres.push_back({{0, 1.5, 0}, 0.5, 0});  // above the view axis
  const SceneTracer tracer(s);
  int top = 0, bottom = 0;
  for (int y = 0; y < 30; ++y) {
    for (int x = 0; x < 40; ++x) (y < 15 ? top : bottom) += tracer.trace(x, y).hit;
  }
  EXPECT_GT(top, 0);
  EXPECT_EQ(bottom, 0);
  // And x = 0 is the left: a sphere at -x shows in the left half.
  s.spheres[0].center = {-1.5, 0, 0};
  const SceneTracer left(s);
  EXPECT_TRUE(left.trace(10, 15).hit);
  EXPECT_FALSE(left.trace(30, 15).hit);
}

TEST(Tracer, PlaneIsTwoSided) {
  // Looking straight down at a plane whose normal points away: the normal is turned up.
  Scene s = camera_scene({0, 2, 0}, {0, 0, 0}, {0, 0, -1}, 11, 11);
  s.planes.push_back({{0, 0, 0}, {0, -1, 0}, 1});
  SurfaceSample c = SceneTracer(s).trace(5, 5);
  ASSERT_TRUE(c.hit);
  EXPECT_EQ(c.material, 1u);
  expect_vec(c.position, {0, 0, 0});
  expect_vec(c.normal, {0, 1, 0});
  // A ray parallel to the plane misses it.
  s.camera = SceneCamera{{0, 1, 0}, {0, 1, -1}, {0, 1, 0}, 30, 11, 11};
  EXPECT_FALSE(SceneTracer(s).trace(5, 5).hit);
}

TEST(Tracer, TriangleNormalIsInterpolated) {
  Scene s = camera_scene({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 101, 101);
  Mesh m;
  m.positions = {{-1, -1, 0}, {3, -1, 0}, {-1, 3, 0}};
  const Vec3 n0{0, 0, 1}, n1 = normalize({1, 0, 1}), n2 = normalize({0, 1, 1});
  m.normals = {n0, n1, n2};
  m.faces = {{0, 1, 2}};
  m.material = 1;
  s.meshes.push_back(m);
  // The centre ray hits (0, 0, 0): barycentrics 1/2, 1/4, 1/4.
  const Vec3 want = normalize(n0 * 0.5 + n1 * 0.25 + n2 * 0.25);
  SurfaceSample c = SceneTracer(s).trace(50, 50);
  ASSERT_TRUE(c.hit);
  EXPECT_EQ(c.material, 1u);
  expect_vec(c.position, {0, 0, 0}, 1e-15);
  expect_vec(c.normal, want, 1e-15);
  // From behind, the same normal turned towards the eye.
  s.camera.position = {0, 0, -5};
  c = SceneTracer(s).trace(50, 50);
  ASSERT_TRUE(c.hit);
  expect_vec(c.normal, -want, 1e-15);
  expect_vec(c.view, {0, 0, -1});
}

TEST(Tracer, BadArguments) {
  Scene s = camera_scene({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 8, 6);
  const SceneTracer tracer(s);
  EXPECT_THROW(tracer.trace(-1, 0), std::invalid_argument);
  EXPECT_THROW(tracer.trace(8, 0), std::invalid_argument);
  EXPECT_THROW(tracer.trace(0, 6), std::invalid_argument);
  std::vector<SurfaceSample> out(8 * 7);
  EXPECT_THROW(tracer.trace_rows(0, 7, out.data()), std::invalid_argument);
  EXPECT_THROW(tracer.trace_rows(3, 2, out.data()), std::invalid_argument);
  EXPECT_NO_THROW(tracer.trace_rows(2, 2, out.data()));
  const SurfaceSample miss;
  EXPECT_THROW(light_sample(s, miss, 0), std::invalid_argument);
  SurfaceSample hit;
  hit.hit = true;
  EXPECT_THROW(light_sample(s, hit, 1), std::invalid_argument);
}

// ---- light_sample ----------------------------------------------------------------------------

TEST(LightSample, LightAt45Degrees) {
  // Normal and view along +z, the light 45 degrees off towards +x: n.l = cos 45, the mirror
  // direction is 45 degrees the other way, so r.v = cos 45, and h is 22.5 degrees off the normal.
  Scene s = camera_scene({0, 0, 5}, {0, 0, 0}, {0, 1, 0}, 8, 6);
  const double c45 = std::sqrt(0.5);
  s.lights = {{"dir", LightKind::kDirectional, {}, {-c45, 0, -c45}, {1, 1, 1}},
              {"point", LightKind::kPoint, {3, 0, 3}, {}, {1, 1, 1}},
              {"behind", LightKind::kDirectional, {}, {0, 0, 1}, {1, 1, 1}}};
  SurfaceSample p;
  p.hit = true;
  p.normal = {0, 0, 1};
  p.view = {0, 0, 1};
  for (std::size_t l = 0; l < 2; ++l) {
    SCOPED_TRACE(l);
    const LightSample ls = light_sample(s, p, l);
    expect_vec(ls.to_light, {c45, 0, c45}, 1e-16);
    EXPECT_NEAR(ls.n_dot_l, c45, 1e-16);
    EXPECT_NEAR(ls.t_phong, c45, 1e-15);
    EXPECT_NEAR(ls.t_blinn, std::cos(kPi / 8), 1e-15);  // 0.92387953...
  }
  const LightSample back = light_sample(s, p, 2);
  EXPECT_EQ(back.n_dot_l, -1);
  EXPECT_EQ(back.t_phong, -1);  // r = 2 (n.l) n - l = (0, 0, -1)
  // Light straight along the normal: r = v and h = n.
  s.lights[0].direction = {0, 0, -1};
  const LightSample head_on = light_sample(s, p, 0);
  EXPECT_EQ(head_on.t_phong, 1);
  EXPECT_EQ(head_on.t_blinn, 1);
}

// ---- The BVH against brute force, determinism ------------------------------------------------

// Moller-Trumbore, written out again: the nearest t over every triangle of the scene.
double brute_force_t(const Scene& s, Vec3 o, Vec3 d) {
  double best = INFINITY;
  for (const Mesh& m : s.meshes) {
    for (const auto& f : m.faces) {
      const Vec3 p0 = m.positions[f[0]], e1 = m.positions[f[1]] - p0, e2 = m.positions[f[2]] - p0;
      const Vec3 p = cross(d, e2);
      const double det = dot(e1, p);
      if (det == 0) continue;
      const Vec3 t0 = o - p0, q = cross(t0, e1);
      const double u = dot(t0, p) / det, v = dot(d, q) / det, t = dot(e2, q) / det;
      if (u >= 0 && u <= 1 && v >= 0 && u + v <= 1 && t > 0 && t < best) best = t;
    }
  }
  return best;
}

TEST(Tracer, BvhFindsTheNearestTriangle) {
  Scene s = load_scene(kScenes + "/teapot.json");
  s.camera.width = 64;
  s.camera.height = 48;
  const SceneTracer tracer(s);
  EXPECT_EQ(tracer.triangles(), 32u * 16 * 16 * 2);
  // The camera as documented: a pinhole, rays through the pixel centres.
  const SceneCamera& c = s.camera;
  const Vec3 f = normalize(c.look_at - c.position), r = normalize(cross(f, c.up)), u = cross(r, f);
  const double th = std::tan(c.fov_y_degrees * kPi / 360), aspect = 64.0 / 48;
  int hits = 0;
  for (int y = 0; y < 48; ++y) {
    for (int x = 0; x < 64; ++x) {
      const Vec3 d = normalize(f + r * ((2 * (x + 0.5) / 64 - 1) * th * aspect) +
                               u * ((1 - 2 * (y + 0.5) / 48) * th));
      const double want = brute_force_t(s, c.position, d);
      const SurfaceSample got = tracer.trace(x, y);
      ASSERT_EQ(got.hit, std::isfinite(want)) << x << "," << y;
      if (!got.hit) continue;
      ++hits;
      EXPECT_NEAR(length(got.position - c.position), want, 1e-9 * want) << x << "," << y;
      expect_vec(got.view, -d, 1e-15);
    }
  }
  EXPECT_GT(hits, 64 * 48 / 5);
}

bool same(const SurfaceSample& a, const SurfaceSample& b) {
  const auto bits = [](Vec3 v, Vec3 w) { return std::memcmp(&v, &w, sizeof v) == 0; };
  return a.hit == b.hit && a.material == b.material && bits(a.position, b.position) &&
         bits(a.normal, b.normal) && bits(a.view, b.view);
}

TEST(Tracer, DeterministicOverRowRangesAndThreads) {
  Scene s = load_scene(kScenes + "/multi.json");
  s.camera.width = 96;
  s.camera.height = 72;
  const SceneTracer tracer(s);
  const std::size_t w = 96, n = w * 72;
  std::vector<SurfaceSample> whole(n), split(n), threaded(n);
  tracer.trace_rows(0, 72, whole.data());
  tracer.trace_rows(0, 13, split.data());
  tracer.trace_rows(13, 50, split.data() + 13 * w);
  tracer.trace_rows(50, 72, split.data() + 50 * w);
  std::thread a([&] { tracer.trace_rows(0, 31, threaded.data()); });
  std::thread b([&] { tracer.trace_rows(31, 72, threaded.data() + 31 * w); });
  a.join();
  b.join();
  const SceneTracer rebuilt(s);  // a second build gives the same tree, hence the same hits
  for (std::size_t i = 0; i < n; ++i) {
    ASSERT_TRUE(same(whole[i], split[i])) << i;
    ASSERT_TRUE(same(whole[i], threaded[i])) << i;
    const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    ASSERT_TRUE(same(whole[i], tracer.trace(x, y))) << i;
    ASSERT_TRUE(same(whole[i], rebuilt.trace(x, y))) << i;
  }
}

}  // namespace
}  // namespace glint
