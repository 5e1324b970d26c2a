// glint render: a scene through the reference and the units, as images and a report.
#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <memory>

#include "cli/cli.h"
#include "eval/chip_report.h"
#include "eval/energy.h"
#include "eval/parallel.h"
#include "eval/sim_report.h"
#include "image/image.h"
#include "io/output_set.h"
#include "io/vectors.h"
#include "render/render.h"
#include "render/render_html.h"
#include "scene/mesh_summary.h"
#include "scene/scene.h"
#include "units/catalogue.h"

namespace glint::cli {
namespace {

struct RenderCommandOptions {
  std::string scene;
  std::vector<std::string> units;
  std::string out_dir;
  std::string vectors;
  std::string float_format;  // --float: empty for none
  int threads = 0;
  Chip chip;
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  HeatScale heat_scale = HeatScale::kShared;
  std::string node;      // --node
  std::string activity;  // --activity GATING (needs --node)
  bool json = false;
  bool html = false;
};

std::string lsb_text(double v) {
  return fmt::format("{:.0f}", v);
}

// The lane's error beside its without-skip lane's (a saving is fair only at equal error): the
// frame's worst and mean pixel error, the request-level pixel error and the datapath's ulps, and
// how the two frames differ.
std::string without_skip_error_line(const UnitRender& u, std::size_t label_width) {
  const UnitRender::WithoutSkip& w = *u.without_skip;
  const std::string differ =
      w.pixels_differing == 0
          ? "the frames are identical"
          : fmt::format("the frames differ in {} pixel{} (by at most {} LSB)", w.pixels_differing,
                        w.pixels_differing == 1 ? "" : "s", w.max_lsb_between);
  const std::string verdict = w.error.max_lsb == u.error.max_lsb
                                  ? "equal error (the same max_lsb)"
                                  : "the skip changes the error: compare at equal error with "
                                    "glint size (src/cli/guide/render.md)";
  return fmt::format(
      "{:<{}} error with / without the skip: max_lsb {} / {}, mean_lsb {:.4f} / {:.4f}, "
      "weighted.max_lsb8 {:.3f} / {:.3f}, max_datapath_ulps {:.3f} / {:.3f}; {}: {}\n",
      u.label, label_width, lsb_text(u.error.max_lsb), lsb_text(w.error.max_lsb), u.error.mean_lsb,
      w.error.mean_lsb, u.stats.weighted.max_abs * display_scale(u.stats.display_bits),
      w.stats.weighted.max_abs * display_scale(w.stats.display_bits), u.stats.max_ulps(),
      w.stats.max_ulps(), differ, verdict);
}

int run_render(const RenderCommandOptions& o) {
  RenderOptions options;
  if (!o.units.empty()) options.units = parse_unit_options(o.units);  // empty: the default set
  options.units = specs_for_chip(options.units, o.chip);
  options.threads = o.threads > 0 ? o.threads : default_threads();
  options.chip = o.chip;
  options.node = !o.node.empty();
  if (!o.activity.empty() && o.node.empty())
    throw std::invalid_argument(
        "--activity sets the gating of the energy at a node: it needs --node (e.g. --node osu018)");
  if (options.node) {
    try {
      options.gating = parse_gating(o.activity.empty() ? "operand" : o.activity);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--activity: ") + e.what());
    }
  }
  options.eps_measure = o.eps_measure;
  options.heat_scale = o.heat_scale;
  options.progress = isatty(STDERR_FILENO);
  if (!o.float_format.empty()) {
    try {
      options.float_format = parse_float_format(o.float_format);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(std::string("--float: ") + e.what());
    }
  }
  if (options_only()) return kExitOk;
  load_text_font();  // a bad GLINT_FONT is refused before any work (the sheet has labels)
  // Outputs first, before any work: the folder made if missing, every file checked and its
  // temporary created; all committed together at the end, or none (output_set.h).
  OutputSet outputs;
  outputs.add_input("SCENE", o.scene);
  if (o.json) outputs.claim_stdout("--json");
  // The scene before the outputs: the per-light skip masks are named after its lights. Loading
  // writes nothing, so a bad scene still leaves no output.
  const Scene scene = load_scene(o.scene);
  const std::vector<std::string> labels = render_unit_labels(options.units);
  const RenderOutputs files =
      declare_render_outputs(outputs, o.out_dir, labels, render_light_names(scene), "-o");
  std::vector<std::pair<std::string, OutputFile*>> float_files;
  if (options.float_format)
    for (const std::string& name : render_float_file_names(labels, *options.float_format))
      float_files.emplace_back(name,
                               &outputs.add("--float (" + name + ")",
                                            (std::filesystem::path(o.out_dir) / name).string()));
  OutputFile* page =
      o.html ? &outputs.add("--html", (std::filesystem::path(o.out_dir) / "report.html").string())
             : nullptr;
  OutputFile* vectors_file =
      o.vectors.empty() ? nullptr : &outputs.add("--write-vectors", o.vectors, true);
  std::unique_ptr<VectorWriter> vectors;
  if (vectors_file) {
    vectors = std::make_unique<VectorWriter>(vectors_file->stream(), scene_request_header(scene),
                                             o.vectors);
    options.on_requests = [&](const VectorRow* rows, std::size_t n) {
      for (std::size_t i = 0; i < n; ++i) vectors->write(rows[i]);
    };
  }
  // Every PNG is encoded as its rows are made, straight into its output (memory: the error maps,
  // not the images).
  options.images = RenderImages::kStream;
  options.png_sinks = render_png_sinks(files);
  // Float images likewise, row by row through a descriptor of their own (EXR seeks back).
  std::vector<std::unique_ptr<FloatRowWriter>> float_writers;
  for (const auto& [name, file] : float_files) {
    float_writers.push_back(std::make_unique<FloatRowWriter>(*options.float_format, file->dup_fd(),
                                                             scene.camera.width,
                                                             scene.camera.height, file->path()));
    options.float_sinks.emplace_back(
        [w = float_writers.back().get()](const float* rgb, int rows) { w->add_rows(rgb, rows); });
  }
  RenderResult r;
  try {
    r = render_scene(scene, options);
  } catch (const SlotCapacityError& e) {
    refuse_chip(o.chip, e);  // the scene needs more than the chip holds
  } catch (const ResourceLimitError& e) {
    refuse_size(o.scene, e);  // more slots or contract work than a run may take
  }
  for (const auto& w : float_writers) w->finish();
  write_render(r, files);
  if (page) {
    HtmlRunInfo run = html_run_info();
    run.figures.emplace_back("eps", fmt::format("{}", scene.eps));
    write_render_html(r.to_json(), files, *page, run);
  }
  if (vectors) vectors->commit();  // flushes into its output
  outputs.commit();
  if (o.json) {
    print_json(r.to_json());
    return kExitOk;
  }
  // With --write-vectors - (standard output), the summary goes to stderr.
  std::ostream& out = outputs.writes_stdout() ? std::cerr : std::cout;
  const SkipCounts total = r.skip_total();
  const auto pct = [](std::uint64_t part, std::uint64_t whole) {
    return whole ? 100.0 * static_cast<double>(part) / static_cast<double>(whole) : 0.0;
  };
  // The skip's statement is in the pixel measure of the table below; its bound is stated only
  // where the image holds it (it must: skip_guarantee_lsb is a proof, the image a check of it).
  out << fmt::format(
      "{}: {}x{}, {} light{}, {} requests; of {} light x pixel pairs skipped: {:.1f}% with tau, "
      "{:.1f}% with t <= 0; skip alone: max {} LSB{}\n",
      r.scene_name, r.width, r.height, r.lights.size(), r.lights.size() == 1 ? "" : "s", r.requests,
      total.total(), pct(total.facing_away + total.zero + total.tau, total.total()),
      pct(total.facing_away + total.zero, total.total()), lsb_text(r.skip_only_error.max_lsb),
      r.skip_within_guarantee ? fmt::format(", within {} LSB by eps", r.skip_guarantee_lsb)
                              : fmt::format(" (beyond the {} LSB bound from eps: a bug in glint)",
                                            r.skip_guarantee_lsb));
  out << chip_line(r.chip);
  if (const std::string line = reproduces_line(r); !line.empty()) out << line << '\n';
  out << meshes_text(r.meshes);
  out << fmt::format(
      "pixel error: largest channel's 8-bit code difference, {} display; eps on {}\n",
      to_string(r.display),
      r.eps_measure == EpsMeasure::kChannel ? "the largest channel (--eps-measure channel)"
                                            : "luminance c_y (Källberg eq.3)");
  out << "skip fractions: of light x pixel pairs (visible pixels x lights; a light behind the "
         "surface counts as skipped)\n";
  // highlight / core: the extent at 10 % and 50 % of the material's peak, against the reference.
  // The unit column as wide as its longest label ("lut in=uq1.16 out=uq1.9"), at least 9.
  std::size_t label_width = 9;
  for (const UnitRender& u : r.units) label_width = std::max(label_width, u.label.size());
  out << fmt::format("{:<{}} {:>8} {:>9} {:>8} {:>7} {:>10} {:>7} {:>8} {:>9} {:<}\n", "unit",
                     label_width, "max_lsb", "mean_lsb", "psnr_dB", "diff%", "highlight", "core",
                     "skip%LxP", "area_ge", "spec");
  for (const UnitRender& u : r.units) {
    out << fmt::format(
        "{:<{}} {:>8} {:>9.4f} {:>8} {:>6.2f}% {:>9.3f}x {:>6.3f}x {:>7.1f}% {:>9.0f} {}\n",
        u.label, label_width, lsb_text(u.error.max_lsb), u.error.mean_lsb,
        std::isfinite(u.error.psnr_db) ? fmt::format("{:.2f}", u.error.psnr_db) : "inf",
        100.0 * u.error.differing_fraction, u.error.highlight_ratio, u.error.core_ratio,
        100.0 * r.unit_skipped_fraction(u), u.cost.area_ge, u.spec);
  }
  if (!o.node.empty())
    for (const UnitRender& u : r.units)
      out << fmt::format("{:<{}} {}\n", u.label, label_width, node_line(u.cost.node_json()));
  for (const UnitRender& u : r.units)
    if (!u.energy.is_null())
      out << fmt::format("{:<{}} {:.1f} nJ per frame; {}\n", u.label, label_width,
                         u.energy.at("total_pj").get<double>() / 1000, format_energy(u.energy));
  // What the skip buys: the same lane with skip=off on the same requests.
  for (const UnitRender& u : r.units)
    if (!u.energy_without_skip.is_null()) {
      const double with = u.energy.at("total_pj").get<double>();
      const double without = u.energy_without_skip.at("total_pj").get<double>();
      out << fmt::format(
          "{:<{}} without the skip (skip=off): {:.1f} nJ per frame, {:.2f} pJ per shaded pixel; "
          "the skip saves {:.1f} nJ ({:.1f} %)\n",
          u.label, label_width, without / 1000,
          u.energy_without_skip.at("pj_per_shaded_pixel").get<double>(), (without - with) / 1000,
          without > 0 ? 100 * (without - with) / without : 0.0);
      if (u.without_skip) out << without_skip_error_line(u, label_width);
    }
  out << fmt::format("images and report.json{} in {}\n", o.html ? " (and report.html)" : "",
                     o.out_dir);
  return kExitOk;
}

}  // namespace

void add_render_command(CLI::App& app, int& status) {
  auto o = std::make_shared<RenderCommandOptions>();
  CLI::App* sub = app.add_subcommand(
      "render", "Ray-cast a scene, run its shading requests through the units, write images");
  sub->add_option("SCENE", o->scene, "Scene file (JSON, see traces/scenes/README.md)")->required();
  sub->add_option(
      "--unit", o->units,
      fmt::format("Unit SPEC NAME[:key=value,...] (repeatable, at most {}; default: the "
                  "default set, which glint units marks)",
                  kMaxUnitOptions));
  sub->add_option("-o,--out", o->out_dir, "Folder for the PNG images and report.json")->required();
  sub->add_option("--write-vectors", o->vectors,
                  "Also write the scene's shading requests as a vector file (for eval, sim, "
                  "regress; - for stdout, then the summary goes to stderr)");
  sub->add_option("--float", o->float_format,
                  "Also write linear float images of the reference and of each unit's specular "
                  "term: exr (OpenEXR, 32-bit float RGB) or pfm (Portable Float Map)")
      ->type_name("FORMAT");
  add_threads_option(sub, o->threads);
  add_chip_option(sub, o->chip);
  add_node_option(sub, o->node);
  sub->add_option("--activity", o->activity,
                  "GATING of the energy --node states (per frame, per request and per shaded "
                  "pixel, from each lane's switching on the frame's requests): none, operand "
                  "(default) or clock, as glint sim --activity")
      ->type_name("GATING");
  add_eps_measure_option(sub, o->eps_measure);
  sub->add_option_function<std::string>(
         "--heat-scale",
         [o](const std::string& text) {
           if (text != "shared" && text != "own")
             throw CLI::ValidationError("--heat-scale", "'" + text + "' is not one of shared, own");
           o->heat_scale = text == "shared" ? HeatScale::kShared : HeatScale::kOwn;
         },
         "Error maps' full scale: shared = the largest error of any unit, the same colours on "
         "every map (the default); own = each unit's largest error")
      ->type_name("shared|own");
  sub->add_flag("--json", o->json, "Print the report on stdout instead of the summary");
  sub->add_flag("--html", o->html,
                "Also write report.html into the folder: one page, offline, with the images, "
                "sortable tables and the command to reproduce");
  sub->callback([o, &status] { status = guarded([&] { return run_render(*o); }); });
}

}  // namespace glint::cli
