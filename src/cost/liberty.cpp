#include "cost/liberty.h"

#include <cctype>
#include <cstddef>
#include <utility>
#include <vector>

namespace glint {

namespace {

bool is_space(char c) {
  return std::isspace(static_cast<unsigned char>(c)) != 0;
}
bool is_word(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_';
}
// The characters of a cell name (as the register count reads them from the netlist).
bool is_name(char c) {
  return is_word(c) || c == '$' || c == '.' || c == '[' || c == ']';
}
std::size_t skip_spaces(std::string_view s, std::size_t i) {
  while (i < s.size() && is_space(s[i])) ++i;
  return i;
}

// At `i`, `( NAME )` with NAME optionally quoted: NAME and the index after ')', or "" if not.
std::pair<std::string_view, std::size_t> group_name(std::string_view s, std::size_t i) {
  i = skip_spaces(s, i);
  if (i >= s.size() || s[i] != '(') return {{}, i};
  i = skip_spaces(s, i + 1);
  if (i < s.size() && s[i] == '"') ++i;
  const std::size_t begin = i;
  while (i < s.size() && is_name(s[i])) ++i;
  const std::size_t end = i;
  if (i < s.size() && s[i] == '"') ++i;
  i = skip_spaces(s, i);
  if (end == begin || i >= s.size() || s[i] != ')') return {{}, i};
  return {s.substr(begin, end - begin), i + 1};
}

// Whether `body` holds one of the sequential groups: the keyword as a whole word, then '('.
bool holds_register_group(std::string_view body) {
  for (const std::string_view key : {"ff_bank", "latch_bank", "ff", "latch"}) {
    for (std::size_t at = body.find(key); at != std::string_view::npos;
         at = body.find(key, at + 1)) {
      const std::size_t after = at + key.size();
      if (at > 0 && is_word(body[at - 1])) continue;
      if (after < body.size() && is_word(body[after])) continue;
      const std::size_t open = skip_spaces(body, after);
      if (open < body.size() && body[open] == '(') return true;
    }
  }
  return false;
}

}  // namespace

std::set<std::string> liberty_registers(std::string_view text) {
  // Each `cell` as a whole word followed by a name group, where it starts and its name.
  std::vector<std::pair<std::size_t, std::string_view>> cells;
  constexpr std::string_view kCell = "cell";
  for (std::size_t at = text.find(kCell); at != std::string_view::npos;
       at = text.find(kCell, at + 1)) {
    if (at > 0 && is_word(text[at - 1])) continue;
    const std::size_t after = at + kCell.size();
    if (after < text.size() && is_word(text[after])) continue;
    const auto [name, end] = group_name(text, after);
    if (!name.empty()) cells.emplace_back(at, name);
  }
  std::set<std::string> out;
  for (std::size_t i = 0; i < cells.size(); ++i) {
    const std::size_t end = i + 1 < cells.size() ? cells[i + 1].first : text.size();
    if (holds_register_group(text.substr(cells[i].first, end - cells[i].first)))
      out.emplace(cells[i].second);
  }
  return out;
}

}  // namespace glint
