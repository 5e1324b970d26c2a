#include "sweep/size.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>

#include "sweep/report.h"
#include "sweep/size_explain.h"
#include "units/catalogue.h"

namespace glint {

SizeObjective parse_size_objective(const std::string& text) {
  // The objective's words, or the measure each minimises or maximises.
  if (text == "area" || text == "area_ge") return SizeObjective::kArea;
  if (text == "throughput") return SizeObjective::kThroughput;
  if (text == "area*latency" || text == "area_latency") return SizeObjective::kAreaLatency;
  if (text == "energy" || text == "energy_pj_per_request") return SizeObjective::kEnergy;
  if (text == "area_um2") return SizeObjective::kAreaUm2;
  throw std::invalid_argument(fmt::format(
      "--objective '{}': expected area, throughput, area*latency, energy or area_um2 (or the "
      "measure: area_ge, throughput, area_latency, energy_pj_per_request)",
      text));
}

const char* objective_measure(SizeObjective o) {
  switch (o) {
    case SizeObjective::kArea:
      return "area_ge";
    case SizeObjective::kThroughput:
      return "throughput";
    case SizeObjective::kAreaLatency:
      return "area_latency";
    case SizeObjective::kEnergy:
      return "energy_pj_per_request";
    case SizeObjective::kAreaUm2:
      return "area_um2";
  }
  return "?";
}

const char* to_string(SizeObjective o) {
  switch (o) {
    case SizeObjective::kArea:
      return "area";
    case SizeObjective::kThroughput:
      return "throughput";
    case SizeObjective::kAreaLatency:
      return "area*latency";
    case SizeObjective::kEnergy:
      return "energy";
    case SizeObjective::kAreaUm2:
      return "area_um2";
  }
  return "?";
}

const std::vector<std::string>& default_size_grids() {
  // Each family's main accuracy knobs at display-relevant widths: the input format (where t's
  // rounding matters: 10 to 16 fraction bits), the output format (8-bit displays need 10-12) and
  // the unit's own size key. 224 configurations (src/cli/guide/size.md lists them).
  static const std::vector<std::string> grids = {
      "pow:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,log_bits=4..8/2,exp_bits=4|6",
      "schlick:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,match=none|width|minimax",
      "hast:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,d=2..5,match=none|minimax",
      "horner:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,degree=2..6",
      "lut:in=uq1.10|uq1.12|uq1.14|uq1.16,out=uq1.10|uq1.12,bits=4..9",
  };
  return grids;
}

namespace {

// The objective's measure, found as a budget's is: area_um2 sits in the row's "node".
MeasureRef objective_ref(SizeObjective o) {
  return measure_or_throw(objective_measure(o), false, "--objective");
}

double objective_of(const nlohmann::json& row, const MeasureRef& m) {
  const std::optional<double> v = measure_value(row, m);  // a refused configuration has none
  return v ? *v : NAN;
}

// Smaller is cheaper: throughput is negated.
double cost_of(double value, SizeObjective o) {
  return o == SizeObjective::kThroughput ? -value : value;
}

// The report one sweep of `grids` would write, from the rows of several sweeps by spec and the
// first sweep's report without its rows.
nlohmann::json sweep_report_of(const nlohmann::json& shell,
                               const std::map<std::string, nlohmann::json>& rows,
                               const std::vector<Grid>& grids,
                               const std::vector<SweepConfig>& configs) {
  nlohmann::json report = shell, texts = nlohmann::json::array(), results = nlohmann::json::array();
  for (const Grid& g : grids) texts.push_back(g.text);
  for (const SweepConfig& c : configs) {
    nlohmann::json row = rows.at(c.spec);
    row["index"] = c.index;
    results.push_back(std::move(row));
  }
  report["grids"] = std::move(texts);
  report["configurations"] = configs.size();
  report["results"] = std::move(results);
  mark_pareto(report);
  return report;
}

nlohmann::json choice_json(const SizeRun& run, std::size_t i, const std::vector<Budget>& budgets) {
  const nlohmann::json& row = run.reports.front().at("results").at(i);
  nlohmann::json measures = nlohmann::json::object();
  for (const Budget& b : budgets) {
    nlohmann::json per_input = nlohmann::json::array();
    for (const nlohmann::json& r : run.reports) {
      const std::optional<double> v = measure_value(r.at("results").at(i), b.measure);
      per_input.push_back(v ? nlohmann::json(*v) : nlohmann::json(nullptr));
    }
    measures[b.measure.name] = per_input;
  }
  nlohmann::json choice = {{"index", i},
                           {"unit", row.at("unit")},
                           {"spec", row.at("spec")},
                           {"canonical_spec", row.at("canonical_spec")},
                           {"value", run.pick.value[i]},
                           {"measures", measures}};
  if (row.contains("node")) choice["node"] = row.at("node");  // --node, on the first input
  return choice;
}

}  // namespace

SizePick pick_cheapest(const std::vector<nlohmann::json>& reports,
                       const std::vector<Budget>& budgets, SizeObjective objective) {
  SizePick pick;
  if (reports.empty()) return pick;
  const std::size_t n = reports.front().at("results").size();
  pick.value.assign(n, NAN);
  pick.meets.assign(n, true);
  const MeasureRef measure = objective_ref(objective);
  for (const nlohmann::json& r : reports) {
    const nlohmann::json& rows = r.at("results");
    if (rows.size() != n) throw std::invalid_argument("size: the inputs' sweeps differ in size");
    for (std::size_t i = 0; i < n; ++i) {
      for (const Budget& b : budgets) pick.meets[i] = pick.meets[i] && meets(rows[i], b);
      // The worst over the inputs.
      const double v = objective_of(rows[i], measure);
      if (std::isnan(pick.value[i]) || cost_of(v, objective) > cost_of(pick.value[i], objective))
        pick.value[i] = v;
    }
  }
  const nlohmann::json& rows = reports.front().at("results");
  for (std::size_t i = 0; i < n; ++i)
    pick.by_family.emplace(rows[i].at("unit").get<std::string>(), std::nullopt);
  const auto better = [&](std::size_t i, const std::optional<std::size_t>& than) {
    return !than || cost_of(pick.value[i], objective) < cost_of(pick.value[*than], objective);
  };
  for (std::size_t i = 0; i < n; ++i) {
    if (!pick.meets[i] || std::isnan(pick.value[i])) continue;
    ++pick.meeting;
    if (better(i, pick.best)) pick.best = i;
    auto& fam = pick.by_family[rows[i].at("unit").get<std::string>()];
    if (better(i, fam)) fam = i;
  }
  return pick;
}

std::vector<std::size_t> cheapest_meeting(const SizePick& pick, SizeObjective objective,
                                          std::size_t k) {
  std::vector<std::size_t> out;
  for (std::size_t i = 0; i < pick.value.size(); ++i)
    if (pick.meets[i] && !std::isnan(pick.value[i])) out.push_back(i);
  std::stable_sort(out.begin(), out.end(), [&](std::size_t a, std::size_t b) {
    return cost_of(pick.value[a], objective) < cost_of(pick.value[b], objective);
  });
  if (out.size() > k) out.resize(k);
  return out;
}

SizeRun run_size(const std::vector<SweepInput>& inputs, const std::vector<Grid>& grids,
                 const std::vector<Budget>& budgets, SizeObjective objective,
                 const SweepSettings& settings, bool image, const WidenLimits& widen,
                 std::size_t top, const std::function<void(const std::string&)>& progress) {
  if (inputs.empty()) throw std::invalid_argument("size: give VECTORS files or --scene SCENE");
  SizeRun run;
  // Per input: every row swept so far by spec (each configuration is swept once, whatever round
  // added it), and the first sweep's report without its rows (its input and settings).
  std::vector<std::map<std::string, nlohmann::json>> rows(inputs.size());
  std::vector<nlohmann::json> shells(inputs.size());
  const auto sweep = [&](const std::vector<Grid>& more) {
    for (std::size_t k = 0; k < inputs.size(); ++k) {
      SweepJob job;
      job.input = inputs[k];
      job.grids = more;
      job.settings = settings;
      job.image = image;
      job.progress = progress;
      nlohmann::json r = run_sweep(job);
      for (nlohmann::json& row : r.at("results")) {
        const std::string spec = row.at("spec").get<std::string>();
        rows[k][spec] = std::move(row);
      }
      if (shells[k].is_null()) {
        r.erase("results");
        shells[k] = std::move(r);
      }
    }
  };
  std::vector<GridSearch> searches;
  for (const Grid& g : grids) {
    GridSearch& s = searches.emplace_back();
    s.given = s.grid = g;
  }
  std::vector<bool> searching(grids.size(), widen.widen);
  std::vector<SweepConfig> configs;
  std::size_t rounds = 0;
  sweep(grids);
  for (;;) {
    // The reports of the grids as they stand, as one sweep of them would write them.
    std::vector<Grid> now;
    for (const GridSearch& s : searches) now.push_back(s.grid);
    configs = expand_grids(now);
    run.reports.clear();
    for (std::size_t k = 0; k < inputs.size(); ++k)
      run.reports.push_back(sweep_report_of(shells[k], rows[k], now, configs));
    run.pick = pick_cheapest(run.reports, budgets, objective);
    std::vector<double> cost(configs.size()), margin(configs.size());
    for (std::size_t i = 0; i < configs.size(); ++i) {
      cost[i] = cost_of(run.pick.value[i], objective);
      margin[i] = -std::numeric_limits<double>::infinity();
      for (const Budget& b : budgets)
        margin[i] = std::max(margin[i], relative_margin(worst_over_inputs(run.reports, i, b), b));
    }
    std::vector<Grid> more;
    std::size_t total = configs.size();
    for (std::size_t g = 0; g < searches.size(); ++g) {
      GridSearch& s = searches[g];
      if (!searching[g]) continue;
      const WidenDecision d = decide_widening(s.grid, g, configs, cost, run.pick.meets, margin,
                                              widen.rounds - s.rounds);
      if (d.stop) {
        s.stop = *d.stop;
        s.why = d.why;
        searching[g] = false;
        continue;
      }
      Grid wider = widen_grid(s.grid, d.steps);
      const std::size_t added = wider.size() - s.grid.size();
      if (total + added > widen.configurations) {
        s.stop = WidenStop::kConfigurationCap;
        s.why =
            fmt::format("widening to {} would make {} configurations in all, over the cap of {}",
                        wider.text, total + added, widen.configurations);
        searching[g] = false;
        continue;
      }
      total += added;
      ++s.rounds;
      for (const GridStep& step : d.steps)
        s.steps.push_back(
            nlohmann::json{{"round", s.rounds}, {"key", step.key}, {"value", step.value}});
      for (Grid& part : grid_difference(s.grid, wider)) more.push_back(std::move(part));
      s.grid = std::move(wider);
    }
    if (more.empty()) break;
    ++rounds;
    if (progress) progress(fmt::format("size: widening, round {}", rounds));
    sweep(more);
  }
  if (!widen.widen)
    for (GridSearch& s : searches) s.why = "--no-widen: the grid as given";

  nlohmann::json conditions = nlohmann::json::array(), in = nlohmann::json::array(),
                 families = nlohmann::json::array(), grid_texts = nlohmann::json::array(),
                 given_texts = nlohmann::json::array();
  for (const Budget& b : budgets) conditions.push_back(b.text);
  for (std::size_t k = 0; k < inputs.size(); ++k)
    in.push_back({{"path", inputs[k].path},
                  {"kind", inputs[k].scene ? "scene" : "vectors"},
                  {"pixel_measure", run.reports[k].at("input").at("pixel_measure")}});
  std::vector<Grid> final_grids;
  for (const GridSearch& s : searches) {
    grid_texts.push_back(s.grid.text);
    given_texts.push_back(s.given.text);
    final_grids.push_back(s.grid);
  }
  // Families in catalogue order, each with how close it came (size_explain.h) and how its grids
  // widened.
  std::vector<double> cost(run.pick.value.size());
  for (std::size_t i = 0; i < cost.size(); ++i) cost[i] = cost_of(run.pick.value[i], objective);
  for (const std::string& name : unit_names()) {
    const auto it = run.pick.by_family.find(name);
    if (it == run.pick.by_family.end()) continue;
    nlohmann::json family = it->second ? choice_json(run, *it->second, budgets)
                                       : nlohmann::json{{"unit", name}, {"spec", nullptr}};
    family.update(explain_family(name, run.reports, budgets, final_grids, configs, cost,
                                 it->second.has_value()));
    nlohmann::json search = nlohmann::json::array();
    for (const GridSearch& s : searches)
      if (s.grid.unit == name) search.push_back(s.to_json());
    family["search"] = std::move(search);
    families.push_back(std::move(family));
  }
  nlohmann::json cheapest = nlohmann::json::array();
  for (std::size_t i : cheapest_meeting(run.pick, objective, top))
    cheapest.push_back(choice_json(run, i, budgets));
  run.document = {{"glint_size_report", 2},
                  {"budget", conditions},
                  {"objective", to_string(objective)},
                  {"inputs", in},
                  {"grids_given", given_texts},
                  {"grids", grid_texts},
                  {"widen",
                   {{"enabled", widen.widen},
                    {"max_rounds", widen.rounds},
                    {"max_configurations", widen.configurations},
                    {"rounds", rounds}}},
                  {"display_bits", settings.display_bits},
                  {"configurations", run.pick.value.size()},
                  {"meeting", run.pick.meeting},
                  {"families", families},
                  {"top", cheapest},
                  {"best", run.pick.best ? choice_json(run, *run.pick.best, budgets)
                                         : nlohmann::json(nullptr)}};
  return run;
}

namespace {

// How each grid was searched: one line per grid, and the grid it ended with when it widened.
std::string format_search(const nlohmann::json& d) {
  const nlohmann::json& w = d.at("widen");
  std::string out =
      w.at("enabled").get<bool>()
          ? fmt::format(
                "grids widened where the answer improves outward (at most {} rounds per "
                "grid, {} configurations in all):\n",
                w.at("max_rounds").get<std::size_t>(),
                w.at("max_configurations").get<std::size_t>())
          : std::string("grids as given (--no-widen)\n");
  if (!w.at("enabled").get<bool>()) return out;
  for (const nlohmann::json& f : d.at("families")) {
    for (const nlohmann::json& s : f.at("search")) {
      std::vector<std::string> steps;
      for (const nlohmann::json& step : s.at("steps"))
        steps.push_back(fmt::format("{}={}", step.at("key").get<std::string>(),
                                    step.at("value").get<std::string>()));
      const auto rounds = s.at("rounds").get<std::size_t>();
      out += fmt::format("  {}: {} round{}{}; stopped ({}): {}\n", f.at("unit").get<std::string>(),
                         rounds, rounds == 1 ? "" : "s",
                         steps.empty() ? "" : fmt::format(" ({})", fmt::join(steps, ", ")),
                         s.at("stopped").get<std::string>(), s.at("why").get<std::string>());
      if (rounds > 0) out += fmt::format("    searched {}\n", s.at("grid").get<std::string>());
    }
  }
  return out;
}

// With --node (the choices state the lane at it): the lane's area in GE and um2 and its clock
// beside the objective's value, each the worst over the inputs as the value is, headed by its
// measure's name; the objective's own measure is not repeated.
struct NodeColumn {
  const char* measure;
  bool larger_worse;  // an area; else a clock (printed to 0.1 MHz)
};
constexpr NodeColumn kNodeColumns[] = {
    {"area_ge", true}, {"area_um2", true}, {"max_clock_mhz", false}};

std::vector<const NodeColumn*> node_columns(const nlohmann::json& d, const std::string& measure) {
  std::vector<const NodeColumn*> out;
  const nlohmann::json& best = d.at("best");
  const nlohmann::json& top = d.at("top");
  const bool node = (!best.is_null() && best.contains("node")) ||
                    (!top.empty() && top[0].contains("node")) ||
                    std::any_of(d.at("families").begin(), d.at("families").end(),
                                [](const nlohmann::json& f) { return f.contains("node"); });
  if (!node) return out;
  for (const NodeColumn& c : kNodeColumns)
    if (measure != c.measure) out.push_back(&c);
  return out;
}

std::string node_headings(const std::vector<const NodeColumn*>& cols) {
  std::string out;
  for (const NodeColumn* c : cols) out += fmt::format(" {:>14}", c->measure);
  return out;
}

// The worst value over the inputs of each column for a choice ("-" for none).
std::vector<std::string> node_values(const SizeRun& run, const std::vector<const NodeColumn*>& cols,
                                     const nlohmann::json& choice) {
  std::vector<std::string> out;
  for (const NodeColumn* c : cols) {
    const MeasureRef m = measure_or_throw(c->measure, false, "size");
    std::optional<double> worst;
    if (choice.contains("index"))
      for (const nlohmann::json& r : run.reports) {
        const std::optional<double> v =
            measure_value(r.at("results").at(choice.at("index").get<std::size_t>()), m);
        if (v && (!worst || (c->larger_worse ? *v > *worst : *v < *worst))) worst = v;
      }
    out.push_back(!worst            ? std::string("-")
                  : c->larger_worse ? fmt::format("{:.6g}", *worst)
                                    : fmt::format("{:.1f}", *worst));
  }
  return out;
}

std::string node_cells(const SizeRun& run, const std::vector<const NodeColumn*>& cols,
                       const nlohmann::json& choice) {
  std::string out;
  for (const std::string& v : node_values(run, cols, choice)) out += fmt::format(" {:>14}", v);
  return out;
}

}  // namespace

std::string format_size(const SizeRun& run) {
  const nlohmann::json& d = run.document;
  std::vector<std::string> conditions, paths;
  for (const auto& c : d.at("budget")) conditions.push_back(c.get<std::string>());
  for (const auto& i : d.at("inputs")) paths.push_back(i.at("path").get<std::string>());
  const std::string objective = d.at("objective").get<std::string>();
  // Values are headed by the measure's name (area_ge, ...), as in every table and budget.
  const std::string measure = objective_measure(parse_size_objective(objective));
  std::string out = fmt::format(
      "budget {} on every input ({}); objective: {}{}\n"
      "{} configurations, {} meet the budget on every input\n",
      fmt::join(conditions, ","), fmt::join(paths, ", "), objective,
      paths.size() > 1 ? " (worst over the inputs)" : "", d.at("configurations").get<std::size_t>(),
      d.at("meeting").get<std::size_t>());
  const std::vector<const NodeColumn*> cols = node_columns(d, measure);
  out += fmt::format("{:<8} {:>14}{}  {}\n", "family", measure, node_headings(cols),
                     "cheapest spec meeting the budget");
  std::string why;
  for (const nlohmann::json& f : d.at("families")) {
    const std::string unit = f.at("unit").get<std::string>();
    if (f.at("spec").is_null()) {
      out += fmt::format("{:<8} {:>14}{}  (none meets the budget)\n", unit, "-",
                         node_cells(run, cols, f));
      why +=
          fmt::format("why no {} configuration meets the budget:\n", unit) + format_explanation(f);
    } else {
      out += fmt::format("{:<8} {:>14.6g}{}  {}\n", unit, f.at("value").get<double>(),
                         node_cells(run, cols, f), f.at("spec").get<std::string>());
    }
  }
  out += why;
  out += format_search(d);
  const nlohmann::json& top = d.at("top");
  if (top.size() > 1) {
    std::string heading = measure;
    for (const NodeColumn* c : cols) heading += fmt::format(", {}", c->measure);
    out += fmt::format("the {} cheapest meeting the budget ({}):\n", top.size(), heading);
    for (const nlohmann::json& c : top)
      out += fmt::format("  {:>14.6g}{}  {}\n", c.at("value").get<double>(),
                         node_cells(run, cols, c), c.at("spec").get<std::string>());
  }
  if (d.at("best").is_null()) return out + "no configuration meets the budget\n";
  const nlohmann::json& b = d.at("best");
  std::string figures;
  const std::vector<std::string> values = node_values(run, cols, b);
  for (std::size_t k = 0; k < cols.size(); ++k)
    figures += fmt::format("{} {} {}", k ? "," : ";", cols[k]->measure, values[k]);
  return out + fmt::format("cheapest overall ({} {:.6g}{}; canonical {}):\n{}\n", measure,
                           b.at("value").get<double>(), figures,
                           b.at("canonical_spec").get<std::string>(),
                           b.at("spec").get<std::string>());
}

}  // namespace glint
