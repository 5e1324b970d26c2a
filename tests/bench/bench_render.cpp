// Render speed: the shipped multi-material scene at 1920x1080 with 8 lights, through the float
// reference and all five units at their defaults (issue 8: at most 5 s on the 2-core machine), on
// 1 thread and on every core side by side. It times the whole of `glint render`: ray casting, the
// units, the images and their PNGs written into a folder and committed, as the command does
// (src/cli/cmd_render.cpp). Its CPU column is the process's (every thread).
// Run: build/tests/bench_render
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "eval/parallel.h"
#include "io/output_set.h"
#include "render/render.h"
#include "scene/scene.h"
#include "units/catalogue.h"

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
  o.images = RenderImages::kStream;
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() / ("glint_bench_render_" + std::to_string(::getpid()));
  const std::vector<std::string> lights = render_light_names(scene);
  std::uint64_t requests = 0;
  for (auto _ : state) {
    OutputSet outputs;
    const RenderOutputs files =
        declare_render_outputs(outputs, dir.string(), render_unit_labels(o.units), lights);
    o.png_sinks = render_png_sinks(files);
    const RenderResult r = render_scene(scene, o);
    write_render(r, files, o.threads);
    outputs.commit(false);  // not durable: no fsync in the figure
    requests = r.requests;
  }
  std::filesystem::remove_all(dir);
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
    ->MeasureProcessCPUTime()
    ->UseRealTime();

}  // namespace
}  // namespace glint
