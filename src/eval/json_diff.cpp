#include "eval/json_diff.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace glint {

bool moved_beyond(double a, double b, double rel_tol) {
  return std::fabs(a - b) > 1e-12 + rel_tol * std::max(std::fabs(a), std::fabs(b));
}

void diff_json(const std::string& path, const nlohmann::json& g, const nlohmann::json& f,
               const Tolerant& tolerant, double rel_tol, std::vector<std::string>& out) {
  const auto at = [&path](const std::string& key) { return path.empty() ? key : path + "." + key; };
  if (g.is_object() && f.is_object()) {
    for (auto it = g.begin(); it != g.end(); ++it) {
      if (!f.contains(it.key())) {
        out.push_back(at(it.key()) + ": missing in the new report");
      } else {
        diff_json(at(it.key()), *it, f.at(it.key()), tolerant, rel_tol, out);
      }
    }
    for (auto it = f.begin(); it != f.end(); ++it)
      if (!g.contains(it.key())) out.push_back(at(it.key()) + ": new field (not in the golden)");
    return;
  }
  if (g.is_array() && f.is_array()) {
    if (g.size() != f.size()) {
      out.push_back(fmt::format("{}: {} entries, golden {}", path, f.size(), g.size()));
      return;
    }
    for (std::size_t i = 0; i < g.size(); ++i)
      diff_json(fmt::format("{}[{}]", path, i), g[i], f[i], tolerant, rel_tol, out);
    return;
  }
  if (tolerant(g, f)) {
    const double a = g.get<double>(), b = f.get<double>();
    if (moved_beyond(a, b, rel_tol))
      out.push_back(
          fmt::format("{}: {:.17g}, golden {:.17g} (beyond tolerance {:g})", path, b, a, rel_tol));
    return;
  }
  if (g != f) out.push_back(fmt::format("{}: {}, golden {}", path, f.dump(), g.dump()));
}

}  // namespace glint
