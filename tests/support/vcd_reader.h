// A VCD reader for the tests: variables by full dotted name (scopes joined with '.'), their widths
// and identifier codes, the time stamps, and every value change, so a test can ask for any
// signal's value at any time.
#pragma once

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace glint::test {

struct VcdReader {
  std::map<std::string, int> vars;         // full name -> width
  std::map<std::string, std::string> ids;  // full name -> identifier code
  std::vector<std::uint64_t> times;
  std::uint64_t value_changes = 0;
  bool dumpvars_before_first_time = false;
  // identifier code -> (time, value) in file order (the $dumpvars values at their time stamp).
  std::map<std::string, std::vector<std::pair<std::uint64_t, std::uint64_t>>> changes;

  explicit VcdReader(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot open " + path);
    std::string line;
    std::vector<std::string> scope;
    bool header = true;
    while (std::getline(in, line)) {
      std::istringstream ls(line);
      std::string tok;
      ls >> tok;
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
          vars[full + name] = width;
          ids[full + name] = id;
        } else if (tok == "$enddefinitions") {
          header = false;
        }
      } else if (!tok.empty() && tok[0] == '#') {
        times.push_back(std::stoull(tok.substr(1)));
      } else if (tok == "$dumpvars" && times.empty()) {
        dumpvars_before_first_time = true;
      } else if (!tok.empty() && tok[0] != '$') {
        ++value_changes;
        const std::uint64_t t = times.empty() ? 0 : times.back();
        if (tok[0] == 'b') {
          std::string id;
          ls >> id;
          changes[id].push_back({t, std::stoull(tok.substr(1), nullptr, 2)});
        } else {
          changes[tok.substr(1)].push_back({t, tok[0] == '1' ? 1u : 0u});
        }
      }
    }
  }

  // The value of `name` after every change at time t (throws if it has none yet).
  std::uint64_t value_at(const std::string& name, std::uint64_t t) const {
    const auto id = ids.find(name);
    if (id == ids.end()) throw std::out_of_range("no VCD variable " + name);
    const auto c = changes.find(id->second);
    if (c == changes.end()) throw std::out_of_range("no value for " + name);
    const auto& v = c->second;
    const auto it = std::upper_bound(v.begin(), v.end(), std::make_pair(t, ~std::uint64_t{0}));
    if (it == v.begin())
      throw std::out_of_range("no value of " + name + " at " + std::to_string(t));
    return std::prev(it)->second;
  }
};

}  // namespace glint::test
