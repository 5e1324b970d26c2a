#include "sweep/size.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "sweep/size_explain.h"
#include "units/catalogue.h"

namespace glint {

SizeObjective parse_size_objective(const std::string& text) {
  if (text == "area") return SizeObjective::kArea;
  if (text == "throughput") return SizeObjective::kThroughput;
  if (text == "area*latency" || text == "area_latency") return SizeObjective::kAreaLatency;
  throw std::invalid_argument(
      fmt::format("--objective '{}': expected area, throughput or area*latency", text));
}

const char* to_string(SizeObjective o) {
  switch (o) {
    case SizeObjective::kArea:
      return "area";
    case SizeObjective::kThroughput:
      return "throughput";
    case SizeObjective::kAreaLatency:
      return "area*latency";
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

double objective_of(const nlohmann::json& row, SizeObjective o) {
  const char* key = o == SizeObjective::kArea         ? "area_ge"
                    : o == SizeObjective::kThroughput ? "throughput"
                                                      : "area_latency";
  const auto v = row.find(key);  // a refused configuration has none
  return v != row.end() && v->is_number() ? v->get<double>() : NAN;
}

// Smaller is cheaper: throughput is negated.
double cost_of(double value, SizeObjective o) {
  return o == SizeObjective::kThroughput ? -value : value;
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
  return {{"index", i},
          {"unit", row.at("unit")},
          {"spec", row.at("spec")},
          {"canonical_spec", row.at("canonical_spec")},
          {"value", run.pick.value[i]},
          {"measures", measures}};
}

}  // namespace

SizePick pick_cheapest(const std::vector<nlohmann::json>& reports,
                       const std::vector<Budget>& budgets, SizeObjective objective) {
  SizePick pick;
  if (reports.empty()) return pick;
  const std::size_t n = reports.front().at("results").size();
  pick.value.assign(n, NAN);
  pick.meets.assign(n, true);
  for (const nlohmann::json& r : reports) {
    const nlohmann::json& rows = r.at("results");
    if (rows.size() != n) throw std::invalid_argument("size: the inputs' sweeps differ in size");
    for (std::size_t i = 0; i < n; ++i) {
      for (const Budget& b : budgets) pick.meets[i] = pick.meets[i] && meets(rows[i], b);
      // The worst over the inputs.
      const double v = objective_of(rows[i], objective);
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
                 const SweepSettings& settings, bool image, std::size_t top,
                 const std::function<void(const std::string&)>& progress) {
  if (inputs.empty()) throw std::invalid_argument("size: give VECTORS files or --scene SCENE");
  SizeRun run;
  for (const SweepInput& in : inputs) {
    SweepJob job;
    job.input = in;
    job.grids = grids;
    job.settings = settings;
    job.image = image;
    job.progress = progress;
    run.reports.push_back(run_sweep(job));
  }
  run.pick = pick_cheapest(run.reports, budgets, objective);

  nlohmann::json conditions = nlohmann::json::array(), in = nlohmann::json::array(),
                 families = nlohmann::json::array(), grid_texts = nlohmann::json::array();
  for (const Budget& b : budgets) conditions.push_back(b.text);
  for (std::size_t k = 0; k < inputs.size(); ++k)
    in.push_back({{"path", inputs[k].path},
                  {"kind", inputs[k].scene ? "scene" : "vectors"},
                  {"pixel_measure", run.reports[k].at("input").at("pixel_measure")}});
  for (const Grid& g : grids) grid_texts.push_back(g.text);
  // Families in catalogue order, each with how close it came (size_explain.h).
  const std::vector<SweepConfig> configs = expand_grids(grids);
  std::vector<double> cost(run.pick.value.size());
  for (std::size_t i = 0; i < cost.size(); ++i) cost[i] = cost_of(run.pick.value[i], objective);
  for (const std::string& name : unit_names()) {
    const auto it = run.pick.by_family.find(name);
    if (it == run.pick.by_family.end()) continue;
    nlohmann::json family = it->second ? choice_json(run, *it->second, budgets)
                                       : nlohmann::json{{"unit", name}, {"spec", nullptr}};
    family.update(
        explain_family(name, run.reports, budgets, grids, configs, cost, it->second.has_value()));
    families.push_back(std::move(family));
  }
  nlohmann::json cheapest = nlohmann::json::array();
  for (std::size_t i : cheapest_meeting(run.pick, objective, top))
    cheapest.push_back(choice_json(run, i, budgets));
  run.document = {{"glint_size_report", 1},
                  {"budget", conditions},
                  {"objective", to_string(objective)},
                  {"inputs", in},
                  {"grids", grid_texts},
                  {"display_bits", settings.display_bits},
                  {"configurations", run.pick.value.size()},
                  {"meeting", run.pick.meeting},
                  {"families", families},
                  {"top", cheapest},
                  {"best", run.pick.best ? choice_json(run, *run.pick.best, budgets)
                                         : nlohmann::json(nullptr)}};
  return run;
}

std::string format_size(const SizeRun& run) {
  const nlohmann::json& d = run.document;
  std::vector<std::string> conditions, paths;
  for (const auto& c : d.at("budget")) conditions.push_back(c.get<std::string>());
  for (const auto& i : d.at("inputs")) paths.push_back(i.at("path").get<std::string>());
  const std::string objective = d.at("objective").get<std::string>();
  std::string out = fmt::format(
      "budget {} on every input ({}); objective: {}{}\n"
      "{} configurations, {} meet the budget on every input\n",
      fmt::join(conditions, ","), fmt::join(paths, ", "), objective,
      paths.size() > 1 ? " (worst over the inputs)" : "", d.at("configurations").get<std::size_t>(),
      d.at("meeting").get<std::size_t>());
  out += fmt::format("{:<8} {:>14}  {}\n", "family", objective, "cheapest spec meeting the budget");
  std::string why;
  for (const nlohmann::json& f : d.at("families")) {
    const std::string unit = f.at("unit").get<std::string>();
    if (f.at("spec").is_null()) {
      out += fmt::format("{:<8} {:>14}  (none meets the budget)\n", unit, "-");
      why +=
          fmt::format("why no {} configuration meets the budget:\n", unit) + format_explanation(f);
    } else {
      out += fmt::format("{:<8} {:>14.6g}  {}\n", unit, f.at("value").get<double>(),
                         f.at("spec").get<std::string>());
    }
  }
  out += why;
  const nlohmann::json& top = d.at("top");
  if (top.size() > 1) {
    out += fmt::format("the {} cheapest meeting the budget:\n", top.size());
    for (const nlohmann::json& c : top)
      out += fmt::format("  {:>14.6g}  {}\n", c.at("value").get<double>(),
                         c.at("spec").get<std::string>());
  }
  if (d.at("best").is_null()) return out + "no configuration meets the budget\n";
  const nlohmann::json& b = d.at("best");
  return out + fmt::format("cheapest overall ({} {:.6g}; canonical {}):\n{}\n", objective,
                           b.at("value").get<double>(), b.at("canonical_spec").get<std::string>(),
                           b.at("spec").get<std::string>());
}

}  // namespace glint
