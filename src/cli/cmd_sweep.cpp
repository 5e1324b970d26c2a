// glint sweep: a grid of unit specs over a vector file or a scene, one row per configuration
// (src/sweep/: the engine, the report and its CSV, Pareto flags, plots).
#include <fmt/format.h>
#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <iostream>
#include <memory>

#include "cli/cli.h"
#include "eval/parallel.h"
#include "image/image.h"
#include "sweep/outputs.h"
#include "sweep/sweep.h"
#include "sweep/sweep_html.h"

namespace glint::cli {
namespace {

struct SweepCommandOptions {
  std::string vectors, scene;
  std::vector<std::string> grids;
  std::string out, csv, plot, shard, html;
  std::string error_measure = "max_lsb";
  int display_bits = 8;
  Chip chip;
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  int jobs = 0;
  bool no_image = false;
  double sink_ready = 1.0;
  std::uint64_t seed = 1;
  bool seed_given = false;
  std::string node;  // --node
  bool json = false;
};

int run_sweep_command(const SweepCommandOptions& o) {
  if (o.vectors.empty() == o.scene.empty())
    throw std::invalid_argument("sweep: give either a VECTORS file or --scene SCENE (one input)");
  if (o.grids.empty())
    throw std::invalid_argument("--grid: at least one grid is needed, e.g. --grid 'lut:bits=4..8'");
  if (!(o.sink_ready >= kMinSinkReady && o.sink_ready <= 1))
    throw std::invalid_argument(fmt::format(
        "--sink-ready must be in [{}, 1] (a run takes ~rows / p cycles)", kMinSinkReady));
  require_backpressure_for_seed(o.seed_given, o.sink_ready);
  if (o.no_image && o.scene.empty())
    throw std::invalid_argument(
        "--no-image leaves out the image-level error of --scene: it needs --scene");
  SweepJob job;
  job.input = {o.vectors.empty() ? o.scene : o.vectors, !o.scene.empty()};
  for (const std::string& g : o.grids) job.grids.push_back(parse_grid(g));
  if (!o.shard.empty()) std::tie(job.shard, job.shards) = parse_shard(o.shard);
  job.settings.display_bits = o.display_bits;
  job.settings.chip = o.chip;
  job.settings.node = !o.node.empty();
  job.settings.eps_measure = o.eps_measure;
  job.settings.jobs = o.jobs > 0 ? o.jobs : default_threads();
  job.settings.sink = SinkReady{o.sink_ready, o.seed};
  job.error_measure = o.error_measure;
  job.image = !o.no_image;
  const SweepOutputs outputs = sweep_outputs(o.out, o.csv, o.plot);
  if (options_only()) return kExitOk;
  // The plots (--plot, and --html's) draw text: a bad font is refused before any work. A scene's
  // renders make no images here (RenderImages::kNone), so they need no font.
  if (!o.plot.empty() || !o.html.empty()) load_text_font();
  OutputSet set;
  set.add_input(o.vectors.empty() ? "--scene" : "VECTORS", job.input.path);
  if (o.json) set.claim_stdout("--json");
  const SweepOutputFiles files = declare_sweep_outputs(set, outputs);
  OutputFile* page = o.html.empty() ? nullptr : &set.add("--html", o.html);
  if (isatty(STDERR_FILENO))
    job.progress = [](const std::string& line) { std::fprintf(stderr, "\r%s", line.c_str()); };

  nlohmann::json report;
  try {
    report = run_sweep(job);
  } catch (const SlotCapacityError& e) {
    refuse_chip(o.chip, e);  // the input needs more slots than the chip holds
  }
  if (job.progress) std::fprintf(stderr, "\n");
  if (page) page->stream() << sweep_html(report, html_run_info());
  return emit_sweep_report(report, files, set, o.json);
}

}  // namespace

int emit_sweep_report(const nlohmann::json& report, const SweepOutputFiles& files, OutputSet& set,
                      bool json) {
  write_sweep_outputs(report, files);
  set.commit();
  if (json) {
    print_json(report);
  } else {
    std::cout << format_sweep_summary(report);
  }
  return kExitOk;
}

void add_sweep_command(CLI::App& app, int& status) {
  auto o = std::make_shared<SweepCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "sweep",
      "Run a grid of unit specs over a vector file or a scene: cost, timing, errors, "
      "Pareto fronts");
  sub->add_option("VECTORS", o->vectors, "Vector file (see traces/README.md)");
  sub->add_option("--scene", o->scene,
                  "Scene file instead of VECTORS: its shading requests, made in memory, and the "
                  "image-level error of each configuration");
  sub->add_option("--grid", o->grids,
                  "UNIT:key=a|b|c,key=lo..hi[/step],... : the cross product of each key's values "
                  "(repeatable)")
      ->required()
      ->allow_extra_args(false);  // one grid per --grid: a word after it is VECTORS
  sub->add_option("-o,--out", o->out,
                  "Write the report: FILE.json (schema glint_sweep_report 2) or FILE.csv");
  sub->add_option("--csv", o->csv, "Also write the CSV table here");
  sub->add_option("--plot", o->plot,
                  "Write error_vs_area and error_vs_throughput as .svg and .png into this folder");
  sub->add_option("--html", o->html,
                  "Also write one HTML page here: plots, fronts and every configuration as "
                  "sortable tables, the command to reproduce; opens offline");
  sub->add_option("--error-measure", o->error_measure,
                  "The error of the Pareto fronts and plots: max_lsb (default), bound_lsb, "
                  "mismatch_fraction, max_abs, weighted.max_lsb, image.max_lsb, ...")
      ->capture_default_str();
  add_display_bits_option(sub, o->display_bits);
  add_chip_option(sub, o->chip);
  add_node_option(sub, o->node);
  add_eps_measure_option(sub, o->eps_measure);
  sub->add_option("--jobs", o->jobs,
                  "Threads over configurations (default: every core); results do not depend on "
                  "it")
      ->check(CLI::Range(1, 256));
  sub->add_option("--shard", o->shard,
                  "K/N: run only configurations i with i mod N == K (join with glint merge)");
  sub->add_flag("--no-image", o->no_image,
                "With --scene: leave out the image-level error (request-level errors only)");
  sub->add_option("--sink-ready", o->sink_ready,
                  "Probability the sink is ready in a cycle (0.01..1), as in glint sim")
      ->capture_default_str();
  add_seed_option(sub, o->seed, o->seed_given);
  sub->add_flag("--json", o->json, "Print the report as one JSON document on stdout");
  sub->callback([o, &status] { status = guarded([&] { return run_sweep_command(*o); }); });
}

}  // namespace glint::cli
