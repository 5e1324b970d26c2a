#include "sweep/size_explain.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "fixed/fixed_point.h"

namespace glint {

namespace {

bool upper_limit(const Budget& b) {
  return b.op == "<=" || b.op == "<";
}

// The depth a measure's LSBs are counted at: its own suffix, else the sweep's --display-bits.
int lsb_bits(const Budget& b, const nlohmann::json& report) {
  return b.measure.bits > 0 ? b.measure.bits : report.at("display_bits").get<int>();
}

double lsb_scale(int bits) {
  return std::ldexp(1.0, bits) - 1.0;
}

// Whether configuration i's stated bounds are bounds on every input (row_bounds_exact).
bool bounds_exact(const std::vector<nlohmann::json>& reports, std::size_t i) {
  for (const nlohmann::json& report : reports)
    if (!row_bounds_exact(report.at("results").at(i))) return false;
  return true;
}

// Where the measured error of a row comes from: the part of the contract's decomposition with the
// largest error (measured, or its bound for a bound measure).
nlohmann::json blocking_part(const nlohmann::json& row, bool bound, double scale) {
  const auto parts = row.find("errors");
  if (parts == row.end() || !parts->contains("parts")) return nullptr;
  std::string name;
  double largest = -1;
  for (const auto& [part, v] : parts->at("parts").items()) {
    const auto x = v.find(bound ? "bound" : "max_abs");
    if (x == v.end() || !x->is_number()) continue;
    if (x->get<double>() > largest) {
      largest = x->get<double>();
      name = part;
    }
  }
  if (largest < 0) return nullptr;
  if (!bound) return {{"name", name}, {"max_lsb", largest * scale}};
  return {{"name", name}, {"bound_lsb", largest * scale}, {"exact", row_bounds_exact(row)}};
}

bool bound_measure(const Budget& b) {
  return is_bound_measure(b.measure);
}

// The slot with the weakest guarantee (the largest stated bound, weighted by what reaches the pixel
// for a weighted measure) and the part that dominates its bound.
nlohmann::json blocking_slot(const nlohmann::json& row, bool weighted, double scale) {
  const auto errors = row.find("errors");
  if (errors == row.end() || !errors->contains("slots")) return nullptr;
  const char* key = weighted ? "weighted_bound_lsb" : "bound_lsb";
  const nlohmann::json* worst = nullptr;
  for (const nlohmann::json& s : errors->at("slots")) {
    const auto v = s.find(key);
    if (v == s.end() || !v->is_number()) continue;  // an always-skipped slot states none
    if (!worst || v->get<double>() > worst->at(key).get<double>()) worst = &s;
  }
  if (!worst) return nullptr;
  std::string part;
  double largest = -1;
  for (const auto& [name, v] : worst->at("bound").items()) {
    if (name == "total" || !v.is_number()) continue;
    if (v.get<double>() > largest) {
      largest = v.get<double>();
      part = name;
    }
  }
  nlohmann::json out = {
      {"slot", worst->at("slot")},         {"name", worst->at("name")},
      {"bound_lsb", worst->at(key)},       {"part", part},
      {"part_bound_lsb", largest * scale}, {"exact", worst->value("exact", true)}};
  return out;
}

// The keys of the closest configuration that sit at an end of their grid's ordered axis while the
// budget gets nearer towards that end: its neighbour one value inwards misses by more. (An end the
// error does not improve towards, e.g. a narrower output that the error ignores, is no hint.)
nlohmann::json grid_edges(const Grid& grid, const std::vector<SweepConfig>& configs,
                          std::size_t index, const std::vector<double>& miss) {
  nlohmann::json out = nlohmann::json::array();
  const SweepConfig& config = configs.at(index);
  for (const GridAxis& axis : grid.axes) {
    if (axis.values.size() < 2) continue;
    const auto order = axis_order(axis);
    const std::string* given = config_value(config, axis.key);
    if (!order || !given) continue;
    const auto at = std::find(axis.values.begin(), axis.values.end(), *given);
    if (at == axis.values.end()) continue;
    const double mine = (*order)[static_cast<std::size_t>(at - axis.values.begin())];
    // The next value inwards: the nearest in the axis's order.
    const auto [lo, hi] = std::minmax_element(order->begin(), order->end());
    if (mine != *lo && mine != *hi) continue;
    std::optional<std::size_t> inward;
    for (std::size_t k = 0; k < order->size(); ++k) {
      if ((*order)[k] == mine) continue;
      if (!inward || std::abs((*order)[k] - mine) < std::abs((*order)[*inward] - mine)) inward = k;
    }
    const auto next = grid_neighbour(configs, config, axis.key, axis.values[*inward]);
    if (!next || !(miss[*next] > miss[index]) || std::isinf(miss[*next])) continue;
    out.push_back(
        {{"key", axis.key}, {"value", *given}, {"end", mine == *hi ? "largest" : "smallest"}});
  }
  return out;
}

std::string lsb_text(double lsb) {
  return fmt::format("{:.3g} LSB", lsb);
}

}  // namespace

std::optional<std::vector<double>> axis_order(const GridAxis& axis) {
  std::vector<double> keys;
  bool integers = true, formats = true;
  for (const std::string& v : axis.values) {
    long long n = 0;
    const auto r = std::from_chars(v.data(), v.data() + v.size(), n);
    integers = integers && r.ec == std::errc() && r.ptr == v.data() + v.size();
    double fmt_key = 0;
    try {
      const QFormat q = parse_q_format(v);
      fmt_key = q.frac_bits * 1000.0 + q.int_bits;
    } catch (const std::invalid_argument&) {
      formats = false;
    }
    keys.push_back(integers ? static_cast<double>(n) : fmt_key);
  }
  if (!integers && !formats) return std::nullopt;
  return keys;
}

const std::string* config_value(const SweepConfig& c, const std::string& key) {
  for (const auto& [k, v] : c.unit_spec.keys)
    if (k == key) return &v;
  return nullptr;
}

std::optional<std::size_t> grid_neighbour(const std::vector<SweepConfig>& configs,
                                          const SweepConfig& c, const std::string& key,
                                          const std::string& value) {
  for (const SweepConfig& o : configs) {
    if (o.grid != c.grid || o.unit_spec.keys.size() != c.unit_spec.keys.size()) continue;
    bool same = true;
    for (std::size_t k = 0; k < o.unit_spec.keys.size() && same; ++k) {
      const auto& [name, v] = o.unit_spec.keys[k];
      same = name == c.unit_spec.keys[k].first &&
             (name == key ? v == value : v == c.unit_spec.keys[k].second);
    }
    if (same) return o.index;
  }
  return std::nullopt;
}

std::optional<double> worst_over_inputs(const std::vector<nlohmann::json>& reports, std::size_t i,
                                        const Budget& b) {
  std::optional<double> worst;
  for (const nlohmann::json& r : reports) {
    const std::optional<double> v = measure_value(r.at("results").at(i), b.measure);
    if (!v || std::isnan(*v)) return std::nullopt;
    if (!worst || (upper_limit(b) ? *v > *worst : *v < *worst)) worst = v;
  }
  return worst;
}

double relative_margin(const std::optional<double>& value, const Budget& b) {
  if (!value || std::isnan(*value)) return std::numeric_limits<double>::infinity();
  const double over = upper_limit(b) ? *value - b.limit : b.limit - *value;
  return b.limit != 0 ? over / std::abs(b.limit) : over;
}

double relative_miss(const std::optional<double>& value, const Budget& b) {
  if (!value) return std::numeric_limits<double>::infinity();
  const double over = upper_limit(b) ? *value - b.limit : b.limit - *value;
  const bool holds = b.op == "<"    ? *value < b.limit
                     : b.op == "<=" ? *value <= b.limit
                     : b.op == ">"  ? *value > b.limit
                                    : *value >= b.limit;
  if (holds) return 0;
  // A strict limit missed by equality misses by nothing measurable: the smallest positive miss.
  const double miss = b.limit != 0 ? over / std::abs(b.limit) : over;
  return std::max(miss, std::numeric_limits<double>::min());
}

nlohmann::json explain_family(const std::string& unit, const std::vector<nlohmann::json>& reports,
                              const std::vector<Budget>& budgets, const std::vector<Grid>& grids,
                              const std::vector<SweepConfig>& configs,
                              const std::vector<double>& cost, bool meets_budget) {
  const nlohmann::json& rows = reports.front().at("results");
  std::vector<std::size_t> family;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].at("unit") == unit) family.push_back(i);
  // Ties go to the cheaper configuration, then to the lower index.
  const auto cheaper = [&](std::size_t a, std::size_t b) {
    const bool na = std::isnan(cost[a]), nb = std::isnan(cost[b]);
    if (na != nb) return nb;
    return !na && cost[a] != cost[b] ? cost[a] < cost[b] : a < b;
  };

  nlohmann::json reached = nlohmann::json::array();
  for (const Budget& b : budgets) {
    std::optional<std::size_t> best;
    std::optional<double> best_value;
    for (std::size_t i : family) {
      const std::optional<double> v = worst_over_inputs(reports, i, b);
      if (!v) continue;
      const bool better = !best_value || (upper_limit(b) ? *v < *best_value : *v > *best_value) ||
                          (*v == *best_value && cheaper(i, *best));
      if (better) {
        best = i;
        best_value = v;
      }
    }
    nlohmann::json r = best ? nlohmann::json{{"condition", b.text},
                                             {"best", *best_value},
                                             {"index", *best},
                                             {"spec", rows[*best].at("spec")}}
                            : nlohmann::json{{"condition", b.text}, {"best", nullptr}};
    if (best && bound_measure(b)) r["exact"] = bounds_exact(reports, *best);
    reached.push_back(std::move(r));
  }
  nlohmann::json out = {{"reached", reached}};
  if (meets_budget || family.empty()) return out;

  // The configuration whose worst condition misses by the least.
  std::optional<std::size_t> closest;
  double closest_miss = std::numeric_limits<double>::infinity();
  std::size_t missed = 0;
  std::vector<double> miss(rows.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i : family) {
    double worst = 0;
    std::size_t worst_b = 0;
    for (std::size_t k = 0; k < budgets.size(); ++k) {
      const double m = relative_miss(worst_over_inputs(reports, i, budgets[k]), budgets[k]);
      if (m > worst) {
        worst = m;
        worst_b = k;
      }
    }
    miss[i] = worst;
    if (!closest || worst < closest_miss || (worst == closest_miss && cheaper(i, *closest))) {
      closest = i;
      closest_miss = worst;
      missed = worst_b;
    }
  }
  if (!closest || std::isinf(closest_miss)) {
    out["closest"] = nullptr;  // every configuration was refused or lacks a measure
    return out;
  }
  const Budget& b = budgets[missed];
  // The input where the missed condition is worst: the one that decides.
  std::size_t input = 0;
  for (std::size_t k = 1; k < reports.size(); ++k) {
    const auto v = measure_value(reports[k].at("results").at(*closest), b.measure);
    const auto w = measure_value(reports[input].at("results").at(*closest), b.measure);
    if (v && w && (upper_limit(b) ? *v > *w : *v < *w)) input = k;
  }
  const nlohmann::json& report = reports[input];
  const nlohmann::json& row = report.at("results").at(*closest);
  const bool error_measure =
      b.measure.pointer.rfind("/errors/", 0) == 0 || b.measure.pointer.rfind("/image/", 0) == 0;
  const bool bound = bound_measure(b);
  const bool weighted = b.measure.pointer.rfind("/errors/weighted", 0) == 0;
  const double scale = lsb_scale(lsb_bits(b, report));
  const SweepConfig& config = configs.at(*closest);
  out["closest"] = {
      {"index", *closest},
      {"spec", rows[*closest].at("spec")},
      {"missed", b.text},
      {"value", worst_over_inputs(reports, *closest, b).value_or(NAN)},
      {"miss", closest_miss},
      {"input", report.at("input").at("path")},
      {"part", error_measure ? blocking_part(row, bound, scale) : nlohmann::json(nullptr)},
      {"slot", error_measure ? blocking_slot(row, weighted, scale) : nlohmann::json(nullptr)},
      {"grid_edges", grid_edges(grids.at(config.grid), configs, *closest, miss)}};
  if (bound) out["closest"]["exact"] = bounds_exact(reports, *closest);
  return out;
}

std::string format_explanation(const nlohmann::json& e) {
  const auto closest = e.find("closest");
  if (closest == e.end()) return "";
  std::string out;
  for (const nlohmann::json& r : e.at("reached")) {
    if (r.at("best").is_null()) {
      out += fmt::format("  {}: no value in any configuration\n",
                         r.at("condition").get<std::string>());
    } else {
      out += fmt::format("  {}: best {}{:.6g} ({})\n", r.at("condition").get<std::string>(),
                         r.value("exact", true) ? "" : "~", r.at("best").get<double>(),
                         r.at("spec").get<std::string>());
    }
  }
  if (closest->is_null()) return out + "  every configuration was refused or lacks the measures\n";
  const nlohmann::json& c = *closest;
  // A miss under 100 % reads best as a percentage; a larger one as a factor of the limit.
  const double miss = c.at("miss").get<double>();
  const std::string by =
      miss < 1 ? fmt::format("{:.3g} %", 100 * miss) : fmt::format("a factor {:.3g}", 1 + miss);
  out += fmt::format("  closest: {} misses {} by {} ({}{:.6g}, on {})\n",
                     c.at("spec").get<std::string>(), c.at("missed").get<std::string>(), by,
                     c.value("exact", true) ? "" : "~", c.at("value").get<double>(),
                     c.at("input").get<std::string>());
  if (!c.at("part").is_null()) {
    const nlohmann::json& p = c.at("part");
    const bool bound = p.contains("bound_lsb");
    const bool estimate = bound && !p.value("exact", true);
    out += fmt::format("    largest error part: {} ({} {}{}){}\n", p.at("name").get<std::string>(),
                       bound ? "bound" : "measured", estimate ? "~" : "",
                       lsb_text(p.at(bound ? "bound_lsb" : "max_lsb").get<double>()),
                       estimate ? ", an estimate: inputs sampled" : "");
  }
  if (!c.at("slot").is_null()) {
    const nlohmann::json& s = c.at("slot");
    // "~": the slot's bound was measured at sampled codes and could not be certified.
    const std::string estimate = s.value("exact", true) ? "" : "~";
    out += fmt::format("    weakest slot: {}, {} (bound {}{}, {} of it {}{}){}\n",
                       s.at("slot").get<int>(), s.at("name").get<std::string>(), estimate,
                       lsb_text(s.at("bound_lsb").get<double>()), s.at("part").get<std::string>(),
                       estimate, lsb_text(s.at("part_bound_lsb").get<double>()),
                       estimate.empty() ? "" : ", an estimate: inputs sampled");
  }
  std::vector<std::string> edges;
  for (const nlohmann::json& g : c.at("grid_edges"))
    edges.push_back(fmt::format("{}={} ({} in the grid)", g.at("key").get<std::string>(),
                                g.at("value").get<std::string>(), g.at("end").get<std::string>()));
  // After a search (size_widen.h) the edges are the searched grid's, where it stopped.
  std::vector<std::string> stops;
  if (const auto search = e.find("search"); search != e.end())
    for (const nlohmann::json& g : *search)
      if (g.at("stopped") != "fixed") stops.push_back(g.at("stopped").get<std::string>());
  if (!edges.empty())
    out += fmt::format("    at its grid's edge: {}: {}\n", fmt::join(edges, ", "),
                       stops.empty() ? std::string("a wider --grid may help")
                                     : fmt::format("the search stopped there ({}, below)",
                                                   fmt::join(stops, ", ")));
  return out;
}

}  // namespace glint
