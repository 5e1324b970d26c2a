// A small VCD reader for the tests: variables by full dotted name (scopes joined with '.'), their
// widths, and every value change, so a test can ask for any signal's value at any time.
#pragma once

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace glint::test {

class VcdReader {
 public:
  explicit VcdReader(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::string line;
    std::vector<std::string> scope;
    bool header = true;
    std::uint64_t time = 0;
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string tok;
      ls >> tok;
      if (tok.empty()) continue;
      if (header) {
        if (tok == "$scope") {
          std::string kind, name;
          ls >> kind >> name;
          scope.push_back(name);
        } else if (tok == "$upscope") {
          scope.pop_back();
        } else if (tok == "$var") {
          std::string type, id, name;
          int width = 0;
          ls >> type >> width >> id >> name;
          std::string full;
          for (const std::string& s : scope) full += s + ".";
          widths_[full + name] = width;
          ids_[full + name] = id;
        } else if (tok == "$enddefinitions") {
          header = false;
        }
      } else if (tok[0] == '#') {
        time = std::stoull(tok.substr(1));
      } else if (tok[0] == 'b') {
        std::string id;
        ls >> id;
        changes_[id].push_back({time, std::stoull(tok.substr(1), nullptr, 2)});
      } else if (tok[0] == '0' || tok[0] == '1') {
        changes_[tok.substr(1)].push_back({time, tok[0] == '1' ? 1u : 0u});
      }
    }
  }

  bool has(const std::string& name) const { return ids_.count(name) != 0; }
  int width(const std::string& name) const { return widths_.at(name); }

  // The value of `name` after every change at time t (throws if it has none yet).
  std::uint64_t value_at(const std::string& name, std::uint64_t t) const {
    const auto id = ids_.find(name);
    if (id == ids_.end()) throw std::out_of_range("no VCD variable " + name);
    const auto c = changes_.find(id->second);
    if (c == changes_.end()) throw std::out_of_range("no value for " + name);
    const auto& v = c->second;
    auto it = std::upper_bound(v.begin(), v.end(), std::make_pair(t, ~std::uint64_t{0}));
    if (it == v.begin())
      throw std::out_of_range("no value of " + name + " at " + std::to_string(t));
    return std::prev(it)->second;
  }

 private:
  std::map<std::string, int> widths_;
  std::map<std::string, std::string> ids_;
  std::map<std::string, std::vector<std::pair<std::uint64_t, std::uint64_t>>> changes_;
};

}  // namespace glint::test
