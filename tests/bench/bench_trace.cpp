// Ray caster speed: primary rays on the default teapot scene (traces/scenes/teapot.json, 16384
// triangles) at 1920x1080 on one thread, and the BVH build.
//
//   build/tests/bench_trace
//
// rays/s is per core (CPU time, so the figure holds on a shared machine). Every ray of the image
// is traced; about 20% of them hit the teapot; the rest leave through the BVH's root box or miss
// inside it.
#include <benchmark/benchmark.h>

#include <string>
#include <vector>

#include "scene/scene.h"
#include "scene/tracer.h"

namespace {

glint::Scene teapot_scene(int width, int height) {
  glint::Scene s = glint::load_scene(std::string(GLINT_SOURCE_DIR) + "/traces/scenes/teapot.json");
  s.camera.width = width;
  s.camera.height = height;
  return s;
}

void BM_TraceTeapot1080p(benchmark::State& state) {
  const glint::Scene scene = teapot_scene(1920, 1080);
  const glint::SceneTracer tracer(scene);
  std::vector<glint::SurfaceSample> image(1920 * 1080);
  std::size_t hits = 0;
  for (auto _ : state) {
    tracer.trace_rows(0, 1080, image.data());
    benchmark::DoNotOptimize(image.data());
  }
  for (const auto& p : image) hits += p.hit;
  state.counters["rays/s"] = benchmark::Counter(static_cast<double>(image.size()),
                                                benchmark::Counter::kIsIterationInvariantRate);
  state.counters["hit_fraction"] = static_cast<double>(hits) / static_cast<double>(image.size());
  state.counters["triangles"] = static_cast<double>(tracer.triangles());
}
BENCHMARK(BM_TraceTeapot1080p)->Unit(benchmark::kMillisecond);

void BM_BuildTeapotBvh(benchmark::State& state) {
  const glint::Scene scene = teapot_scene(1920, 1080);
  for (auto _ : state) {
    glint::SceneTracer tracer(scene);
    benchmark::DoNotOptimize(tracer.triangles());
  }
}
BENCHMARK(BM_BuildTeapotBvh)->Unit(benchmark::kMillisecond);

}  // namespace
