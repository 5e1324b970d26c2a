// glint size: the cheapest configuration per unit family and overall that meets an error budget on
// every given input (src/sweep/size.h), printed as a SPEC ready to paste. Exit 1 when none does.
#include <fmt/format.h>
#include <unistd.h>

#include <cstdio>
#include <iostream>
#include <memory>
#include <optional>

#include "cli/cli.h"
#include "eval/parallel.h"
#include "image/image.h"
#include "io/output_set.h"
#include "sweep/size.h"
#include "sweep/sweep_html.h"

namespace glint::cli {
namespace {

// No configuration meets the budget: a check that failed, as regress's exit 1.
constexpr int kExitNoneMeets = 1;

struct SizeOptions {
  std::vector<std::string> vectors, scenes, grids;
  std::string budget, objective = "area";
  std::string html;
  int display_bits = 8;
  Chip chip;
  EpsMeasure eps_measure = EpsMeasure::kLuminance;
  int jobs = 0;
  std::size_t top = 1;
  bool no_image = false;
  std::string node;  // --node
  bool json = false;
  WidenLimits widen;
  bool no_widen = false;
  bool widen_limit_given = false;  // --widen-rounds or --widen-configurations
};

// The overall choice's spec, or "" when nothing meets the budget.
std::string best_spec(const SizeRun& run) {
  const nlohmann::json& b = run.document.at("best");
  return b.is_null() ? std::string() : b.at("spec").get<std::string>();
}

// Without --chip, the answer on both chips (units/chip.h): the default's, ROMs of the inputs'
// materials fixed at synthesis, and a GPU's, tables loaded at run time. The cheapest unit can flip
// between them (a loadable table costs a register per bit): say whether it does.
std::string chips_line(const SizeRun& rom, const SizeRun& ram) {
  const std::string a = best_spec(rom), b = best_spec(ram);
  const auto name = [](const std::string& s) { return s.empty() ? std::string("none") : s; };
  if (a == b) return fmt::format("chips: the same answer on rom and ram: {}\n", name(a));
  return fmt::format("chips: the winner differs: rom {}, ram {} (--chip chooses one)\n", name(a),
                     name(b));
}

int run_size_command(const SizeOptions& o) {
  std::vector<SweepInput> inputs;
  for (const std::string& v : o.vectors) inputs.push_back({v, false});
  for (const std::string& s : o.scenes) inputs.push_back({s, true});
  if (inputs.empty()) throw std::invalid_argument("size: give VECTORS files or --scene SCENE");
  if (o.no_image && o.scenes.empty())
    throw std::invalid_argument(
        "--no-image leaves out the image-level error of --scene: it needs --scene");
  // The caps bound the widening: with --no-widen they would be ignored in silence.
  if (o.no_widen && o.widen_limit_given)
    throw std::invalid_argument(
        "--widen-rounds and --widen-configurations bound the widening: --no-widen has none");
  const SizeObjective objective = parse_size_objective(o.objective);
  // The energy and the area in um2 are priced at a node: without one there is nothing to minimise.
  if (objective == SizeObjective::kEnergy && o.node.empty())
    throw std::invalid_argument(
        "--objective energy minimises the energy per request at a node: it needs --node (e.g. "
        "--node osu018)");
  if (objective == SizeObjective::kAreaUm2 && o.node.empty())
    throw std::invalid_argument(
        "--objective area_um2 minimises the lane's area at a node: it needs --node (e.g. --node "
        "osu018)");
  // Image-level measures only when every input is a scene rendered with them.
  const bool image = !o.no_image && o.vectors.empty();
  const std::vector<Budget> budgets = parse_budgets(o.budget, image);
  std::vector<Grid> grids;
  for (const std::string& g : o.grids.empty() ? default_size_grids() : o.grids)
    grids.push_back(parse_grid(g));
  expand_grids(grids);  // the cap, before any input is read
  if (options_only()) return kExitOk;
  // --html's plots draw text: a bad font is refused before any work. A scene's renders make no
  // images here (RenderImages::kNone), so they need no font.
  if (!o.html.empty()) load_text_font();
  // The page, declared before any work as every output is (io/output_set.h).
  OutputSet set;
  for (const SweepInput& in : inputs) set.add_input(in.scene ? "--scene" : "VECTORS", in.path);
  OutputFile* page = o.html.empty() ? nullptr : &set.add("--html", o.html);
  SweepSettings settings;
  settings.display_bits = o.display_bits;
  settings.chip = o.chip;
  settings.node = !o.node.empty();
  settings.eps_measure = o.eps_measure;
  settings.jobs = o.jobs > 0 ? o.jobs : default_threads();
  std::function<void(const std::string&)> progress;
  if (isatty(STDERR_FILENO))
    progress = [](const std::string& line) { std::fprintf(stderr, "\r%s", line.c_str()); };
  WidenLimits widen = o.widen;
  widen.widen = !o.no_widen;
  const auto size_on = [&](const Chip& chip) {
    SweepSettings on = settings;
    on.chip = chip;
    try {
      SizeRun run =
          run_size(inputs, grids, budgets, objective, on, !o.no_image, widen, o.top, progress);
      run.document["chip"] = chip.spec();
      return run;
    } catch (const SlotCapacityError& e) {
      refuse_chip(chip, e);
    }
  };
  SizeRun run = size_on(o.chip);
  std::optional<SizeRun> loadable;
  if (!o.chip.given) {
    Chip ram;
    ram.ram = ram.given = true;
    loadable = size_on(ram);
    run.document["loadable"] = loadable->document;
    run.document["winner_differs"] = best_spec(run) != best_spec(*loadable);
  }
  if (progress) std::fprintf(stderr, "\n");
  if (page) page->stream() << size_html(run.document, run.reports, html_run_info());
  set.commit();
  if (o.json) {
    print_json(run.document);
  } else {
    // The pixel measure the budgets are judged in (reference/pixel_error.h), per input.
    std::string displays;
    for (const auto& in : run.document.at("inputs"))
      displays += fmt::format("{}{} {}", displays.empty() ? "" : ", ",
                              in.at("pixel_measure").at("display").get<std::string>(),
                              in.at("path").get<std::string>());
    std::cout << fmt::format(
        "pixel error: largest channel of light x specular, display {}; eps on {}\n", displays,
        to_string(o.eps_measure));
    if (loadable) {
      // The default chip's answer last: its spec is the last line, ready to paste.
      std::cout << chips_line(run, *loadable) << "== chip ram: tables loaded at run time\n"
                << format_size(*loadable)
                << "== chip rom (default): ROMs of the inputs' materials\n"
                << format_size(run);
    } else {
      std::cout << "chip: " << o.chip.spec() << "\n" << format_size(run);
    }
  }
  // The answer is the chip's that --chip gives, or the default's.
  return run.pick.best ? kExitOk : kExitNoneMeets;
}

}  // namespace

void add_size_command(CLI::App& app, int& status) {
  auto o = std::make_shared<SizeOptions>();
  CLI::App* sub = app.add_subcommand(
      "size",
      "The cheapest configuration per unit family and overall that meets an error "
      "budget on every input");
  sub->add_option("VECTORS", o->vectors, "Vector files (every one must meet the budget)");
  sub->add_option("--scene", o->scenes, "Scene files (repeatable; every one must meet the budget)")
      ->allow_extra_args(false);
  sub->add_option("--budget", o->budget,
                  "MEASURE OP VALUE[,...], all must hold, e.g. 'max_lsb8<=1', "
                  "'bound_lsb<=0.5,mismatch_fraction<0.01', 'image.max_lsb<=1'; a MEASURE is "
                  "named as in the tables, the CSV and the JSON (aliases: src/cli/guide/size.md)")
      ->required();
  sub->add_option("--objective", o->objective,
                  "area | throughput | area*latency | energy (pJ per request at --node, gating "
                  "operand; or the measure: area_ge, area_latency, energy_pj_per_request) | "
                  "area_um2 (the lane's area at --node)")
      ->capture_default_str();
  sub->add_option("--grid", o->grids,
                  "Grids to choose from (as glint sweep; repeatable); default: a grid per unit "
                  "family (src/cli/guide/size.md)")
      ->allow_extra_args(false);
  add_display_bits_option(sub, o->display_bits);
  add_chip_option(sub, o->chip);
  add_node_option(sub, o->node);
  add_eps_measure_option(sub, o->eps_measure);
  sub->add_option("--jobs", o->jobs, "Threads (default: every core); results do not depend on it")
      ->check(CLI::Range(1, 256));
  sub->add_option("--top", o->top,
                  "List the K cheapest configurations meeting the budget (over every family)")
      ->check(CLI::Range(std::size_t{1}, kMaxSweepConfigurations))
      ->capture_default_str();
  sub->add_flag("--no-widen", o->no_widen,
                "Keep the grids as given: by default a grid whose answer sits at an end of an "
                "ordered key (in, out, bits, d, degree, ...) where it improves outward takes one "
                "more value beyond that end, round by round, within the key's range "
                "(src/cli/guide/size.md)");
  sub->add_option("--widen-rounds", o->widen.rounds, "Widening rounds per grid, at most")
      ->check(CLI::Range(std::size_t{0}, std::size_t{64}))
      ->capture_default_str();
  sub->add_option("--widen-configurations", o->widen.configurations,
                  "Configurations over all grids, at most, when widening (the grids as given "
                  "are swept whatever their size)")
      ->check(CLI::Range(std::size_t{1}, kMaxSweepConfigurations))
      ->capture_default_str();
  sub->add_flag("--no-image", o->no_image,
                "With --scene: leave out the image-level error (request-level errors only)");
  sub->add_flag("--json", o->json, "Print the choice as one JSON document on stdout");
  sub->add_option("--html", o->html,
                  "Also write one HTML page here: the choice per family and overall, the Pareto "
                  "plots per input, the command to reproduce; opens offline");
  sub->callback([o, sub, &status] {
    o->widen_limit_given =
        sub->count("--widen-rounds") > 0 || sub->count("--widen-configurations") > 0;
    status = guarded([&] { return run_size_command(*o); });
  });
}

}  // namespace glint::cli
