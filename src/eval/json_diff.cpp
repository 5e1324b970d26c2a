#include "eval/json_diff.h"

#include <fmt/format.h>

namespace glint {

void diff_json(const std::string& path, const nlohmann::json& g, const nlohmann::json& f,
               const LeafDiff& leaf, std::vector<std::string>& out) {
  const auto at = [&path](const std::string& key) { return path.empty() ? key : path + "." + key; };
  if (g.is_object() && f.is_object()) {
    for (auto it = g.begin(); it != g.end(); ++it) {
      if (!f.contains(it.key())) {
        out.push_back(at(it.key()) + ": missing in the new report");
      } else {
        diff_json(at(it.key()), *it, f.at(it.key()), leaf, out);
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
      diff_json(fmt::format("{}[{}]", path, i), g[i], f[i], leaf, out);
    return;
  }
  leaf(path, g, f, out);
}

}  // namespace glint
