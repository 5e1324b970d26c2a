#include "sweep/sweep.h"

#include <fmt/format.h>

#include <algorithm>
#include <iterator>
#include <memory>
#include <optional>
#include <stdexcept>

#include "eval/chip_report.h"
#include "eval/evaluate.h"
#include "io/input_error.h"
#include "io/vectors.h"
#include "render/render.h"
#include "scene/scene.h"
#include "sweep/measures.h"
#include "sweep/report.h"

namespace glint {
namespace {

// Renders per group of configurations, without images (RenderImages::kNone): a configuration
// keeps only its image-error sums and, for the tile of rows in flight, its specular light per
// pixel (24 bytes) and its result per request (8 bytes per light), so a group is as large as
// ~256 MB of tiles allows, whatever the resolution. Usually one render makes every figure.
std::size_t render_group_size(const Scene& scene, std::size_t configs) {
  const double per_config = RenderOptions{}.tile_rows * static_cast<double>(scene.camera.width) *
                            (24.0 + 8.0 * static_cast<double>(scene.lights.size()));
  const double fits = 256.0 * 1024 * 1024 / std::max(per_config, 1.0);
  return static_cast<std::size_t>(
      std::clamp(fits, 1.0, std::max(1.0, static_cast<double>(configs))));
}

struct SceneRun {
  nlohmann::json input;
  nlohmann::json chip;  // eval/chip_report.h
  std::vector<nlohmann::json> rows;
};

// The report's "input" object as every input kind has it (a scene adds its name and size).
nlohmann::json input_json(const char* kind, const std::string& path, const SweepEngine& engine) {
  return {{"kind", kind},
          {"path", path},
          {"rows", engine.rows()},
          {"pixel_measure", pixel_measure_json(engine.slots())},
          {"slots", engine.slots().params.size()},
          {"datapath_groups", engine.slots().groups.size()},
          {"per_light_slots", engine.slots().per_light}};
}

// A scene: the render layer ray-casts it and hands every tile's requests to the engine (the first
// render only); the image-level error of each configuration is the render's own, from the final
// 8-bit pixels, a group of configurations per render.
// The engine for the input's slots; a stream beyond the limits of src/eval/evaluate.h is refused
// against the input file, as eval and sim refuse it.
SweepEngine make_engine(const SweepJob& job, const VectorHeader& header,
                        const std::vector<SweepConfig>& mine) {
  try {
    return SweepEngine(with_eps_measure(header, job.settings.eps_measure), mine, job.settings);
  } catch (const ResourceLimitError& e) {
    throw InputError(job.input.path, 0, "slots", e.what());
  }
}

SceneRun sweep_scene(const SweepJob& job, const std::vector<SweepConfig>& all,
                     const std::vector<SweepConfig>& mine) {
  const Scene scene = load_scene(job.input.path);
  SweepEngine engine = make_engine(job, scene_request_header(scene), mine);
  const std::size_t group = render_group_size(scene, mine.size());
  // Without image errors (or with no configuration in this shard) one render of one unit still
  // makes the requests.
  const std::size_t renders = job.image && !mine.empty() ? (mine.size() + group - 1) / group : 1;
  std::vector<std::optional<ImageError>> images(mine.size());
  for (std::size_t r = 0; r < renders; ++r) {
    RenderOptions options;
    options.threads = job.settings.jobs;
    options.chip = job.settings.chip;
    options.eps_measure = job.settings.eps_measure;
    options.images = RenderImages::kNone;
    const std::size_t first = r * group;
    const std::size_t last = job.image ? std::min(mine.size(), first + group) : first;
    for (std::size_t k = first; k < last; ++k) options.units.push_back(mine[k].unit_spec);
    if (options.units.empty()) options.units.push_back(all.front().unit_spec);
    if (r == 0)
      options.on_requests = [&](const VectorRow* rows, std::size_t n) { engine.add(rows, n); };
    if (job.progress)
      job.progress(fmt::format("sweep: {} render {}/{}", job.input.path, r + 1, renders));
    const RenderResult result = render_scene(scene, options);
    for (std::size_t k = first; k < last; ++k) images[k] = result.units[k - first].error;
  }
  SceneRun run;
  run.rows = engine.results();
  for (std::size_t k = 0; k < mine.size(); ++k)
    if (images[k]) run.rows[k]["image"] = images[k]->to_json();
  run.input = input_json("scene", job.input.path, engine);
  run.chip = chip_json(job.settings.chip, engine.slots());
  run.input["scene"] = scene.name;
  run.input["width"] = scene.camera.width;
  run.input["height"] = scene.camera.height;
  return run;
}

SceneRun sweep_vectors(const SweepJob& job, const std::vector<SweepConfig>& mine) {
  VectorReader reader(job.input.path);
  SweepEngine engine = make_engine(job, reader.header(), mine);
  std::vector<VectorRow> chunk(std::max<std::size_t>(1, job.settings.chunk_rows));
  for (;;) {
    std::size_t n = 0;
    while (n < chunk.size() && reader.next(chunk[n])) ++n;
    if (n == 0) break;
    engine.add(chunk.data(), n);
    if (job.progress && (engine.rows() / chunk.size()) % 16 == 0)
      job.progress(fmt::format("sweep: {} rows", engine.rows()));
  }
  SceneRun run;
  run.rows = engine.results();
  run.input = input_json("vectors", job.input.path, engine);
  run.chip = chip_json(job.settings.chip, engine.slots());
  return run;
}

}  // namespace

nlohmann::json run_sweep(const SweepJob& job) {
  const bool image = job.input.scene && job.image;
  const MeasureRef measure = measure_or_throw(job.error_measure, image, "--error-measure");
  if (!is_error_measure(measure))
    throw std::invalid_argument(fmt::format(
        "--error-measure '{}': not an error measure (a lower-is-better error: max_lsb, "
        "bound_lsb, mismatch_fraction, max_abs, rms, weighted.max_lsb, parts.*.max_abs, "
        "image.max_lsb, ...)",
        job.error_measure));
  if (job.grids.empty()) throw std::invalid_argument("--grid: at least one grid is needed");
  const std::vector<SweepConfig> all = expand_grids(job.grids);
  const std::vector<SweepConfig> mine =
      job.shards > 0 ? shard_configs(all, job.shard, job.shards) : all;
  SceneRun run = job.input.scene ? sweep_scene(job, all, mine) : sweep_vectors(job, mine);

  nlohmann::json grids = nlohmann::json::array();
  for (const Grid& g : job.grids) grids.push_back(g.text);
  nlohmann::json objectives = nlohmann::json::array();
  std::vector<Objective> all_objectives(std::begin(kObjectives), std::end(kObjectives));
  if (job.settings.node) all_objectives.push_back(kEnergyObjective);
  for (const Objective& o : all_objectives)
    objectives.push_back({{"name", o.name}, {"key", o.key}, {"minimise", o.minimise}});
  nlohmann::json report = {
      {"glint_sweep_report", kSweepReportVersion},
      {"input", run.input},
      {"grids", grids},
      {"configurations", all.size()},
      {"shard", job.shards > 0 ? nlohmann::json{{"index", job.shard}, {"count", job.shards}}
                               : nlohmann::json(nullptr)},
      {"display_bits", job.settings.display_bits},
      {"chip", run.chip},
      {"sink", {{"ready", job.settings.sink.probability}, {"seed", job.settings.sink.seed}}},
      {"image_error", image},
      {"error_measure", job.error_measure},
      {"objectives", objectives},
      {"results", std::move(run.rows)},
  };
  mark_pareto(report);
  return report;
}

}  // namespace glint
