#include "cost/liberty.h"

#include <cctype>
#include <cstddef>
#include <cstdlib>
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

namespace {

// Every `keyword ( NAME )` group of `text` (`keyword` as a whole word): where the keyword
// starts, NAME, and the index after ')'.
struct NamedGroup {
  std::size_t at;
  std::string_view name;
  std::size_t end;
};
std::vector<NamedGroup> named_groups(std::string_view text, std::string_view keyword) {
  std::vector<NamedGroup> out;
  for (std::size_t at = text.find(keyword); at != std::string_view::npos;
       at = text.find(keyword, at + 1)) {
    if (at > 0 && is_word(text[at - 1])) continue;
    const std::size_t after = at + keyword.size();
    if (after < text.size() && is_word(text[after])) continue;
    const auto [name, end] = group_name(text, after);
    if (!name.empty()) out.push_back({at, name, end});
  }
  return out;
}

// Every `cell ( NAME )` group of `text`: its name and its text up to the next cell.
std::vector<std::pair<std::string_view, std::string_view>> cells_of(std::string_view text) {
  const std::vector<NamedGroup> starts = named_groups(text, "cell");
  std::vector<std::pair<std::string_view, std::string_view>> out;
  for (std::size_t i = 0; i < starts.size(); ++i) {
    const std::size_t end = i + 1 < starts.size() ? starts[i + 1].at : text.size();
    out.emplace_back(starts[i].name, text.substr(starts[i].at, end - starts[i].at));
  }
  return out;
}

// The value of the first `key : VALUE ;` in `body` (`key` a whole word), quotes removed, or "".
std::string attribute(std::string_view body, std::string_view key) {
  for (std::size_t at = body.find(key); at != std::string_view::npos; at = body.find(key, at + 1)) {
    if (at > 0 && is_word(body[at - 1])) continue;
    std::size_t i = at + key.size();
    if (i < body.size() && is_word(body[i])) continue;
    i = skip_spaces(body, i);
    if (i >= body.size() || body[i] != ':') continue;
    const std::size_t end = body.find(';', i);
    if (end == std::string_view::npos) return "";
    std::string v(body.substr(i + 1, end - i - 1));
    std::string out;
    for (char c : v)
      if (c != '"') out += c;
    const std::size_t b = out.find_first_not_of(" \t\r\n");
    const std::size_t e = out.find_last_not_of(" \t\r\n");
    return b == std::string::npos ? "" : out.substr(b, e - b + 1);
  }
  return "";
}

// Whether a Liberty function is a 2-input NAND of two different pins: !(A B), !(A&B), !(A*B)
// or (A B)', with any pin names and spacing.
bool is_nand2(const std::string& f) {
  std::string t;
  for (char c : f)
    if (!is_space(c) || (!t.empty() && is_word(t.back()))) t += is_space(c) ? ' ' : c;
  std::string core;
  if (t.size() > 3 && t.compare(0, 2, "!(") == 0 && t.back() == ')') {
    core = t.substr(2, t.size() - 3);
  } else if (t.size() > 4 && t.compare(0, 3, "(!(") == 0 && t.compare(t.size() - 2, 2, "))") == 0) {
    core = t.substr(3, t.size() - 5);
  } else if (t.size() > 3 && t.front() == '(' && t.compare(t.size() - 2, 2, ")'") == 0) {
    core = t.substr(1, t.size() - 3);
  } else {
    return false;
  }
  std::size_t i = 0;
  const auto pin = [&] {
    std::size_t b = i;
    while (i < core.size() && is_word(core[i])) ++i;
    return core.substr(b, i - b);
  };
  const std::string a = pin();
  while (i < core.size() && (core[i] == ' ' || core[i] == '&' || core[i] == '*')) ++i;
  const std::string b = pin();
  while (i < core.size() && core[i] == ' ') ++i;
  return !a.empty() && !b.empty() && a != b && i == core.size() &&
         core.find_first_of("&* ") != std::string::npos;
}

// A cell's `area`, or 0 when it has none or not a positive number.
double cell_area(std::string_view body) {
  const std::string area = attribute(body, "area");
  char* end = nullptr;
  const double a = std::strtod(area.c_str(), &end);
  return area.empty() || *end != '\0' || !(a > 0) ? 0 : a;
}

// The names of the cell's pins whose direction is input.
std::vector<std::string> input_pins(std::string_view body) {
  std::vector<std::string> out;
  for (const NamedGroup& pin : named_groups(body, "pin"))
    if (attribute(body.substr(pin.end), "direction") == "input") out.emplace_back(pin.name);
  return out;
}

}  // namespace

std::set<std::string> liberty_registers(std::string_view text) {
  std::set<std::string> out;
  for (const auto& [name, body] : cells_of(text))
    if (holds_register_group(body)) out.emplace(name);
  return out;
}

Nand2 liberty_nand2(std::string_view text) {
  Nand2 best;
  for (const auto& [name, body] : cells_of(text)) {
    if (holds_register_group(body) || !is_nand2(attribute(body, "function"))) continue;
    const double a = cell_area(body);
    if (a > 0 && (best.cell.empty() || a < best.area)) best = {std::string(name), a};
  }
  return best;
}

std::string liberty_buffer(std::string_view text) {
  std::string best;
  double best_area = 0;
  for (const auto& [name, body] : cells_of(text)) {
    if (holds_register_group(body)) continue;
    const std::vector<std::string> ins = input_pins(body);
    std::string f;
    for (char c : attribute(body, "function"))
      if (!is_space(c) && c != '(' && c != ')') f += c;
    const double a = cell_area(body);
    // abc buffers by the cell's delay tables: an area-only library (tests/rtl/tiny.lib) has none.
    const bool timed = body.find("cell_rise") != std::string_view::npos ||
                       body.find("intrinsic_rise") != std::string_view::npos;
    if (ins.size() != 1 || f != ins.front() || !(a > 0) || !timed) continue;
    if (best.empty() || a < best_area) best = std::string(name), best_area = a;
  }
  return best;
}

}  // namespace glint
