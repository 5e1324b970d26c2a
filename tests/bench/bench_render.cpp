// Render speed: the shipped multi-material scene at 1920x1080 with 8 lights, through the float
// reference and all five units at their defaults (issue 8: at most 5 s on the 2-core machine), on
// 1 thread and on every core side by side. Run: build/tests/bench_render
#include <benchmark/benchmark.h>

#include <string>

#include "eval/parallel.h"
#include "render/render.h"
#include "scene/scene.h"

namespace glint {
namespace {

Scene full_hd_eight_lights() {
  Scene s = load_scene(std::string(GLINT_SOURCE_DIR) + "/traces/scenes/multi.json");
  s.camera.width = 1920;
  s.camera.height = 1080;
  // Eight lights: the scene's own, then copies moved around the scene, dimmed so the sum of the
  // highlights stays in range.
  const std::size_t own = s.lights.size();
  for (std::size_t i = own; i < 8; ++i) {
    SceneLight l = s.lights[i % own];
    l.name = "extra" + std::to_string(i);
    l.position = l.position + Vec3{static_cast<double>(i) - 4.0, 0.5 * static_cast<double>(i), 0};
    s.lights.push_back(l);
  }
  return s;
}

void BM_RenderFullHd8Lights(benchmark::State& state) {
  const Scene scene = full_hd_eight_lights();
  RenderOptions o;
  o.threads = state.range(0) == 0 ? default_threads() : static_cast<int>(state.range(0));
  std::uint64_t requests = 0;
  for (auto _ : state) {
    const RenderResult r = render_scene(scene, o);
    requests = r.requests;
    benchmark::DoNotOptimize(r.reference.pixels.data());
  }
  state.counters["requests"] = static_cast<double>(requests);
  state.counters["threads"] = o.threads;
  state.counters["requests/s"] = benchmark::Counter(static_cast<double>(requests),
                                                    benchmark::Counter::kIsIterationInvariantRate);
}
BENCHMARK(BM_RenderFullHd8Lights)
    ->Arg(1)
    ->Arg(0)
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace glint
