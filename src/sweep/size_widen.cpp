#include "sweep/size_widen.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "fixed/fixed_point.h"
#include "sweep/size_explain.h"

namespace glint {
namespace {

bool as_integer(const std::string& v, long long& out) {
  const auto r = std::from_chars(v.data(), v.data() + v.size(), out);
  return r.ec == std::errc() && r.ptr == v.data() + v.size();
}

// "a|b|c", or lo..hi[/step] for three or more integers rising by one step.
std::string values_text(const std::vector<std::string>& values) {
  std::vector<long long> n(values.size());
  bool run = values.size() >= 3;
  for (std::size_t i = 0; i < values.size() && run; ++i) run = as_integer(values[i], n[i]);
  const long long step = run ? n[1] - n[0] : 0;
  for (std::size_t i = 1; i < n.size() && run; ++i) run = step >= 1 && n[i] - n[i - 1] == step;
  if (!run) return fmt::format("{}", fmt::join(values, "|"));
  return step == 1 ? fmt::format("{}..{}", n.front(), n.back())
                   : fmt::format("{}..{}/{}", n.front(), n.back(), step);
}

std::string steps_text(const std::vector<GridStep>& steps) {
  std::vector<std::string> out;
  for (const GridStep& s : steps) out.push_back(fmt::format("{}={}", s.key, s.value));
  return fmt::format("{}", fmt::join(out, ", "));
}

}  // namespace

const char* to_string(WidenStop s) {
  switch (s) {
    case WidenStop::kFixed:
      return "fixed";
    case WidenStop::kMet:
      return "met";
    case WidenStop::kNoImprovement:
      return "no_improvement";
    case WidenStop::kTooSlow:
      return "too_slow";
    case WidenStop::kRangeEnd:
      return "range_end";
    case WidenStop::kRoundCap:
      return "round_cap";
    case WidenStop::kConfigurationCap:
      return "configuration_cap";
    case WidenStop::kNoValue:
      return "no_value";
  }
  return "?";
}

std::string grid_text(const Grid& grid) {
  std::string out = grid.unit;
  for (std::size_t a = 0; a < grid.axes.size(); ++a)
    out += fmt::format("{}{}={}", a == 0 ? ":" : ",", grid.axes[a].key,
                       values_text(grid.axes[a].values));
  return out;
}

std::optional<std::string> probe_step(const Grid& grid, std::size_t axis, bool largest,
                                      std::string* why) {
  const GridAxis& a = grid.axes.at(axis);
  const auto order = axis_order(a);
  if (!order || order->empty()) throw std::invalid_argument("probe_step: an unordered axis");
  const auto end = largest ? std::max_element(order->begin(), order->end())
                           : std::min_element(order->begin(), order->end());
  const std::string& at = a.values[static_cast<std::size_t>(end - order->begin())];
  std::string next;
  long long n = 0;
  if (as_integer(at, n)) {
    next = std::to_string(largest ? n + 1 : n - 1);
  } else {
    QFormat q = parse_q_format(at);
    q.frac_bits += largest ? 1 : -1;
    next = q.name();
  }
  // The unit's own key reader decides (the key table's range, a format's width), as for --grid.
  try {
    parse_grid(fmt::format("{}:{}={}", grid.unit, a.key, next));
  } catch (const std::invalid_argument& e) {
    if (why) *why = e.what();
    return std::nullopt;
  }
  return next;
}

WidenDecision decide_widening(const Grid& grid, std::size_t grid_index,
                              const std::vector<SweepConfig>& configs,
                              const std::vector<double>& cost, const std::vector<bool>& meets,
                              const std::vector<double>& margin, std::size_t rounds_left) {
  WidenDecision d;
  const auto cheaper = [&](std::size_t a, std::size_t b) {
    const bool na = std::isnan(cost[a]), nb = std::isnan(cost[b]);
    if (na != nb) return nb;
    return !na && cost[a] != cost[b] ? cost[a] < cost[b] : a < b;
  };
  // The configuration that decides: the cheapest meeting the budget, else the closest to it.
  std::optional<std::size_t> at;
  bool met = false;
  for (const SweepConfig& c : configs) {
    if (c.grid != grid_index || !meets[c.index] || std::isnan(cost[c.index])) continue;
    if (!at || cheaper(c.index, *at)) at = c.index;
  }
  met = at.has_value();
  if (!met) {
    for (const SweepConfig& c : configs) {
      const std::size_t i = c.index;
      if (c.grid != grid_index || !std::isfinite(margin[i])) continue;
      if (!at || margin[i] < margin[*at] || (margin[i] == margin[*at] && cheaper(i, *at))) at = i;
    }
  }
  if (!at) {
    d.stop = WidenStop::kNoValue;
    d.why = "no configuration has a value for every condition";
    return d;
  }
  const SweepConfig& config = configs[*at];
  // Per key at an end of its grid: outward improves when the configuration one value inwards is
  // worse. Its gain: by how much (the margin's difference, or the relative cost).
  std::vector<GridStep> wanted;
  std::vector<double> gain;
  double closing = 0;  // how much of the miss the wanted keys' last values closed, together
  for (std::size_t k = 0; k < grid.axes.size(); ++k) {
    const GridAxis& axis = grid.axes[k];
    const auto order = axis_order(axis);
    const std::string* given = config_value(config, axis.key);
    if (axis.values.size() < 2 || !order || !given) continue;
    const auto pos = std::find(axis.values.begin(), axis.values.end(), *given);
    if (pos == axis.values.end()) continue;
    const double mine = (*order)[static_cast<std::size_t>(pos - axis.values.begin())];
    const auto [lo, hi] = std::minmax_element(order->begin(), order->end());
    if (mine != *lo && mine != *hi) continue;
    std::optional<std::size_t> inward;
    for (std::size_t v = 0; v < order->size(); ++v) {
      if ((*order)[v] == mine) continue;
      if (!inward || std::abs((*order)[v] - mine) < std::abs((*order)[*inward] - mine)) inward = v;
    }
    const auto n = grid_neighbour(configs, config, axis.key, axis.values[*inward]);
    if (!n) continue;
    // Met: the objective improves outward (the answer inwards is dearer). Missed: the margin does
    // (the answer inwards misses by more).
    const bool better = met ? !std::isnan(cost[*n]) && cost[*n] > cost[*at]
                            : std::isfinite(margin[*n]) && margin[*n] > margin[*at];
    if (!better) continue;
    if (!met) closing += margin[*n] - margin[*at];
    wanted.push_back({k, axis.key, *given, mine == *hi});
    gain.push_back(met ? (cost[*n] - cost[*at]) / std::abs(cost[*at]) : margin[*n] - margin[*at]);
  }
  const std::string spec = config.spec;
  if (wanted.empty()) {
    d.stop = met ? WidenStop::kMet : WidenStop::kNoImprovement;
    d.why = met ? fmt::format(
                      "the budget holds; its cheapest, {}, is at no end of the grid that "
                      "improves outward",
                      spec)
                : fmt::format(
                      "the budget is missed; the closest, {}, is at no end of the grid "
                      "towards which the miss shrinks",
                      spec);
    return d;
  }
  if (rounds_left == 0) {
    d.stop = WidenStop::kRoundCap;
    d.why = fmt::format("the round cap is reached; {} sits at the end {} towards which it improves",
                        spec, steps_text(wanted));
    return d;
  }
  // A miss that the last values closed by a small share of would take more rounds than are left,
  // even at that rate (errors shrink ever more slowly towards the approximation's floor).
  if (!met && margin[*at] / closing > static_cast<double>(rounds_left)) {
    d.stop = WidenStop::kTooSlow;
    d.why = fmt::format(
        "the budget is missed by {:.3g} (relative) at {}; its last step to {} closed {:.3g} of "
        "it: at that rate more than the {} round{} left would be needed",
        margin[*at], spec, steps_text(wanted), closing, rounds_left, rounds_left == 1 ? "" : "s");
    return d;
  }
  // One key a round, the one that gained most (keys in the grid's order on a tie): a round's
  // new configurations are that key's new value with every value of the others, so widening
  // every improving key at once would sweep their cross product, mostly far from the answer.
  std::vector<std::size_t> by_gain(wanted.size());
  for (std::size_t k = 0; k < by_gain.size(); ++k) by_gain[k] = k;
  std::stable_sort(by_gain.begin(), by_gain.end(),
                   [&](std::size_t a, std::size_t b) { return gain[a] > gain[b]; });
  std::vector<std::string> refused;
  for (std::size_t k : by_gain) {
    GridStep s = wanted[k];
    std::string why;
    if (const auto next = probe_step(grid, s.axis, s.largest, &why)) {
      s.value = *next;
      d.steps.push_back(s);
      break;
    }
    refused.push_back(fmt::format("{} beyond {} ({})", s.key, s.value, why));
  }
  if (d.steps.empty()) {
    d.stop = WidenStop::kRangeEnd;
    d.why = fmt::format("{} would widen, but the unit takes no further value: {}", spec,
                        fmt::join(refused, "; "));
  }
  return d;
}

Grid widen_grid(const Grid& grid, const std::vector<GridStep>& steps) {
  Grid out = grid;
  for (const GridStep& s : steps) {
    std::vector<std::string>& v = out.axes.at(s.axis).values;
    if (s.largest)
      v.push_back(s.value);
    else
      v.insert(v.begin(), s.value);
  }
  out.text = grid_text(out);
  return out;
}

std::vector<Grid> grid_difference(const Grid& narrower, const Grid& wider) {
  if (narrower.unit != wider.unit || narrower.axes.size() != wider.axes.size())
    throw std::invalid_argument("grid_difference: grids of other keys");
  // A configuration is new when some key takes a new value; the first such key (in the grid's
  // order) names the part it falls in: old values before that key, new at it, any after it.
  std::vector<Grid> out;
  for (std::size_t k = 0; k < wider.axes.size(); ++k) {
    const std::vector<std::string>& old = narrower.axes[k].values;
    Grid part;
    part.unit = wider.unit;
    part.axes = wider.axes;
    for (std::size_t j = 0; j < k; ++j) part.axes[j].values = narrower.axes[j].values;
    std::vector<std::string>& added = part.axes[k].values;
    added.erase(std::remove_if(added.begin(), added.end(),
                               [&](const std::string& v) {
                                 return std::find(old.begin(), old.end(), v) != old.end();
                               }),
                added.end());
    if (added.empty()) continue;
    part.text = grid_text(part);
    out.push_back(std::move(part));
  }
  return out;
}

nlohmann::json GridSearch::to_json() const {
  return {{"given", given.text}, {"grid", grid.text}, {"configurations", grid.size()},
          {"rounds", rounds},    {"steps", steps},    {"stopped", to_string(stop)},
          {"why", why}};
}

}  // namespace glint
