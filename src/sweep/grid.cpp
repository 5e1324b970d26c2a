#include "sweep/grid.h"

#include <fmt/format.h>

#include <algorithm>
#include <charconv>
#include <limits>
#include <stdexcept>
#include <string_view>
#include <unordered_set>

#include "reference/reference.h"
#include "units/catalogue.h"

namespace glint {
namespace {

// A range bound: a decimal integer, optionally negative.
bool parse_int(std::string_view s, long long& out) {
  if (s.empty()) return false;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), out);
  return ec == std::errc() && end == s.data() + s.size();
}

// No grid may name more values for one key than the whole sweep may run.
constexpr long long kMaxAxisValues = static_cast<long long>(kMaxSweepConfigurations);

// One alternative: a literal value, or lo..hi[/step] expanded. `probes` gets the values that
// stand for it in parse_grid's check: the literal, or a range's first and last value.
void expand_alternative(const std::string& grid, const std::string& key, std::string_view alt,
                        std::vector<std::string>& out, std::vector<std::string>& probes) {
  const auto bad = [&](const std::string& why) {
    return std::invalid_argument(
        fmt::format("--grid '{}': key '{}' value '{}': {}", grid, key, alt, why));
  };
  if (alt.empty()) throw bad("empty value (between '|' or after '=')");
  const auto dots = alt.find("..");
  if (dots == std::string_view::npos) {
    out.emplace_back(alt);
    probes.emplace_back(alt);
    return;
  }
  std::string_view hi_text = alt.substr(dots + 2);
  std::string_view step_text = "1";
  if (const auto slash = hi_text.find('/'); slash != std::string_view::npos) {
    step_text = hi_text.substr(slash + 1);
    hi_text = hi_text.substr(0, slash);
  }
  long long lo = 0, hi = 0, step = 0;
  if (!parse_int(alt.substr(0, dots), lo) || !parse_int(hi_text, hi) || !parse_int(step_text, step))
    throw bad("a range is lo..hi or lo..hi/step with integers lo, hi and step");
  if (lo > hi) throw bad(fmt::format("empty range: {} > {}", lo, hi));
  if (step < 1) throw bad("the step must be at least 1");
  // Distances in unsigned: hi - lo of two long longs overflows (UB) for e.g. -2^63..2^63-1, but
  // with lo <= hi the true distance fits in 64 unsigned bits.
  const auto distance = [](long long from, long long to) {
    return static_cast<unsigned long long>(to) - static_cast<unsigned long long>(from);
  };
  const auto ustep = static_cast<unsigned long long>(step);
  if (distance(lo, hi) / ustep >= static_cast<unsigned long long>(kMaxAxisValues))  // count - 1
    throw bad(fmt::format("more than {} values", kMaxAxisValues));
  for (long long v = lo;; v += step) {
    out.push_back(std::to_string(v));
    if (distance(v, hi) < ustep) break;
  }
  probes.push_back(std::to_string(lo));
  if (out.back() != probes.back()) probes.push_back(out.back());
}

// A unit built for one material (n = 50, Källberg's tau at eps = 1e-3) checks each value on its
// own through the unit's own key reader, the one place that knows what a key accepts.
const SlotPlan& probe_plan() {
  static const SlotPlan plan = [] {
    const TauResult tau = tau_power(50, 1e-3, 1.0);
    MaterialParams p(50, tau.tau);
    p.level = tau.eps;
    p.name = "material 'probe'";
    return SlotPlan::per_slot({p});
  }();
  return plan;
}

bool builds(const UnitSpec& spec, std::string* why = nullptr) {
  try {
    make_unit(spec, probe_plan());
    return true;
  } catch (const std::invalid_argument& e) {
    if (why) *why = e.what();
    return false;
  }
}

// A value is accepted if the unit builds with it alone, or, for keys that only go with others
// (hast's d=auto needs match=minimax), with some choice of the grid's other keys (at most
// kMaxCombinations tried). A combination the unit refuses is reported when the sweep builds it.
void check_value(const Grid& g, std::size_t axis, const std::string& value) {
  constexpr std::size_t kMaxCombinations = 256;
  std::string why;
  if (builds(UnitSpec{g.unit, {{g.axes[axis].key, value}}}, &why)) return;
  if (g.axes.size() == 1) throw std::invalid_argument(fmt::format("--grid '{}': {}", g.text, why));
  std::vector<std::size_t> at(g.axes.size(), 0);
  std::size_t tried = 0;
  while (tried < kMaxCombinations) {
    UnitSpec spec{g.unit, {}};
    for (std::size_t a = 0; a < g.axes.size(); ++a)
      spec.keys.emplace_back(g.axes[a].key, a == axis ? value : g.axes[a].values[at[a]]);
    ++tried;
    if (builds(spec)) return;
    std::size_t a = g.axes.size();
    while (a-- > 0) {
      if (a == axis) continue;
      if (++at[a] < g.axes[a].values.size()) break;
      at[a] = 0;
    }
    if (a == static_cast<std::size_t>(-1)) break;  // every combination tried
  }
  // The reason alone may name another key's default or auto value: say which of the grid's
  // values it is, and that the grid's other values did not help.
  throw std::invalid_argument(
      fmt::format("--grid '{}': key '{}' = '{}' is refused alone and with the grid's other "
                  "values ({} combination{} tried); alone: {}",
                  g.text, g.axes[axis].key, value, tried, tried == 1 ? "" : "s", why));
}

}  // namespace

std::size_t Grid::size() const {
  std::size_t n = 1;
  for (const GridAxis& a : axes) {
    if (a.values.empty()) return 0;
    if (n > std::numeric_limits<std::size_t>::max() / a.values.size())
      return std::numeric_limits<std::size_t>::max();
    n *= a.values.size();
  }
  return n;
}

Grid parse_grid(std::string_view text) {
  Grid g;
  g.text = std::string(text);
  const auto fail = [&](const std::string& why) {
    return std::invalid_argument(fmt::format("--grid '{}': {}", g.text, why));
  };
  const auto colon = text.find(':');
  g.unit = std::string(text.substr(0, colon));
  if (g.unit.empty()) throw fail("no unit name (expected UNIT[:key=values,...])");
  const UnitInfo* info = nullptr;
  try {
    info = &unit_info(g.unit);
  } catch (const std::invalid_argument& e) {
    throw fail(e.what());
  }
  std::vector<std::vector<std::string>> probes;  // per axis: the values checked below
  if (colon != std::string_view::npos) {
    std::string_view rest = text.substr(colon + 1);
    if (rest.empty()) throw fail("no keys after ':'");
    for (;;) {
      const auto comma = rest.find(',');
      const std::string_view item = rest.substr(0, comma);
      const auto eq = item.find('=');
      if (eq == std::string_view::npos || eq == 0)
        throw fail(fmt::format("'{}' is not key=values", item));
      GridAxis axis;
      axis.key = std::string(item.substr(0, eq));
      if (std::none_of(info->keys.begin(), info->keys.end(),
                       [&](const UnitKey& k) { return k.key == axis.key; })) {
        std::vector<std::string> known;
        for (const UnitKey& k : info->keys) known.push_back(k.key);
        throw fail(fmt::format("unit '{}' has no key '{}' (its keys: {}; see `glint units`)",
                               g.unit, axis.key, fmt::join(known, ", ")));
      }
      for (const GridAxis& a : g.axes)
        if (a.key == axis.key) throw fail(fmt::format("key '{}' given twice", axis.key));
      std::string_view values = item.substr(eq + 1);
      std::vector<std::string>& axis_probes = probes.emplace_back();
      for (;;) {
        const auto bar = values.find('|');
        expand_alternative(g.text, axis.key, values.substr(0, bar), axis.values, axis_probes);
        if (bar == std::string_view::npos) break;
        values.remove_prefix(bar + 1);
      }
      // A set, not a pairwise scan: a range may list up to kMaxAxisValues values.
      std::unordered_set<std::string_view> seen;
      for (const std::string& v : axis.values)
        if (!seen.insert(v).second)
          throw fail(fmt::format("key '{}': value '{}' listed twice", axis.key, v));
      g.axes.push_back(std::move(axis));
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
      if (rest.empty()) throw fail("trailing ','");
    }
  }
  // Too many configurations is refused before any value is checked by building a unit.
  if (const std::size_t n = g.size(); n > kMaxSweepConfigurations)
    throw fail(fmt::format(
        "{} configurations exceed the limit of {} per run (narrow the grid, or run parts of it "
        "separately)",
        n == std::numeric_limits<std::size_t>::max() ? std::string("too many") : std::to_string(n),
        kMaxSweepConfigurations));
  // Every value the unit's own key reader accepts, each on its own (combinations are checked when
  // the sweep builds its configurations, before any input row is read). A range is checked at its
  // ends: every integer key accepts an interval (`glint units`), and a check builds a unit (a
  // horner build proves monotonicity on every input code), so checking all of 1..65536 took
  // minutes under sanitizers. A value inside a range that a unit did refuse would still show, as
  // that configuration's `refused` reason in the results, as a refused combination does.
  for (std::size_t a = 0; a < g.axes.size(); ++a)
    for (const std::string& v : probes[a]) check_value(g, a, v);
  return g;
}

std::vector<SweepConfig> expand_grids(const std::vector<Grid>& grids, std::size_t cap) {
  constexpr std::size_t kMax = std::numeric_limits<std::size_t>::max();
  std::size_t total = 0;
  for (const Grid& g : grids) total = g.size() > kMax - total ? kMax : total + g.size();
  if (total > cap)
    throw std::invalid_argument(fmt::format(
        "--grid: {} configurations{} exceed the limit of {} per run (narrow the grids, or run "
        "parts of them separately)",
        total == kMax ? std::string("too many") : std::to_string(total),
        grids.size() > 1 ? " over all grids" : "", cap));
  std::vector<SweepConfig> out;
  out.reserve(total);
  for (std::size_t gi = 0; gi < grids.size(); ++gi) {
    const Grid& g = grids[gi];
    std::vector<std::size_t> at(g.axes.size(), 0);
    for (std::size_t k = 0; k < g.size(); ++k) {
      SweepConfig c;
      c.index = out.size();
      c.grid = gi;
      c.unit_spec.name = g.unit;
      c.spec = g.unit;
      for (std::size_t a = 0; a < g.axes.size(); ++a) {
        const std::string& v = g.axes[a].values[at[a]];
        c.unit_spec.keys.emplace_back(g.axes[a].key, v);
        c.spec += fmt::format("{}{}={}", a == 0 ? ":" : ",", g.axes[a].key, v);
      }
      out.push_back(std::move(c));
      // The last key varies fastest.
      for (std::size_t a = g.axes.size(); a-- > 0;) {
        if (++at[a] < g.axes[a].values.size()) break;
        at[a] = 0;
      }
    }
  }
  return out;
}

std::vector<SweepConfig> shard_configs(const std::vector<SweepConfig>& all, std::size_t k,
                                       std::size_t n) {
  std::vector<SweepConfig> out;
  for (const SweepConfig& c : all)
    if (c.index % n == k) out.push_back(c);
  return out;
}

std::pair<std::size_t, std::size_t> parse_shard(std::string_view text) {
  const auto slash = text.find('/');
  long long k = -1, n = 0;
  if (slash == std::string_view::npos || !parse_int(text.substr(0, slash), k) ||
      !parse_int(text.substr(slash + 1), n) || n < 1 || k < 0 || k >= n ||
      n > static_cast<long long>(kMaxSweepConfigurations))
    throw std::invalid_argument(
        fmt::format("--shard '{}': expected K/N with 0 <= K < N, N in 1..{} (shard K of N)", text,
                    kMaxSweepConfigurations));
  return {static_cast<std::size_t>(k), static_cast<std::size_t>(n)};
}

}  // namespace glint
