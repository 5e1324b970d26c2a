// The rows of a vector file (traces/README.md, "Rows"): one shading request per non-blank,
// non-comment line after `data`, its fields in the order of the `columns` line. Parsing them is
// the hot loop of reading (the header is parsed once before it).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "io/line_reader.h"
#include "io/vector_header.h"
#include "io/vector_syntax.h"
#include "io/vectors.h"

namespace glint {

// Material name -> index, for a row's material field. Rows tend to repeat a material, so the
// last hit is tried first; a handful of names is searched in order, more through a hash map.
class MaterialLookup {
 public:
  // Keeps views of the names: `materials` must outlive the lookup and not change.
  explicit MaterialLookup(const std::vector<VectorMaterial>& materials);

  // Inline, all of it: rows call it per row, and most rows of a mixed file miss the last hit.
  // `last` is the caller's last hit (each thread that parses rows keeps its own).
  bool find(std::string_view name, std::uint32_t& index, std::uint32_t& last) const {
    const std::string_view hit = names_[last];
    if (name.size() == hit.size() && same_bytes(name.data(), hit.data(), name.size())) {
      index = last;
      return true;
    }
    if (names_.size() <= kLinearNames) {
      for (std::uint32_t i = 0; i < names_.size(); ++i) {
        if (names_[i] == name) {
          index = last = i;
          return true;
        }
      }
      return false;
    }
    const auto it = by_name_.find(name);
    if (it == by_name_.end()) return false;
    index = last = it->second;
    return true;
  }

 private:
  // memcmp(a, b, n) == 0 inline, eight bytes at a time: a call to memcmp for each row's name (a
  // few bytes) took 3 % of `glint eval`'s time.
  static bool same_bytes(const char* a, const char* b, std::size_t n) {
    for (; n >= 8; a += 8, b += 8, n -= 8) {
      std::uint64_t x = 0, y = 0;
      std::memcpy(&x, a, 8);
      std::memcpy(&y, b, 8);
      if (x != y) return false;
    }
    for (; n > 0; ++a, ++b, --n)
      if (*a != *b) return false;
    return true;
  }

  // Up to this many names a linear scan beats hashing the name.
  static constexpr std::size_t kLinearNames = 8;

  std::vector<std::string_view> names_;
  std::unordered_map<std::string_view, std::uint32_t> by_name_;
};

// Parses row lines into VectorRows, each field by the rule of its column.
class RowParser {
 public:
  // Rows laid out as `file` declares, from the file called `name`. The parser keeps references to
  // `name` and to `materials` (the names of `file`'s materials), which must outlive it. Copies
  // parse on their own threads.
  RowParser(const std::string& name, const VectorFileHeader& file, const MaterialLookup& materials);

  // Parses `line`, the file's line `line_no`, into `row` (all but row.line). False for a blank or
  // comment-only line, which holds no row. Throws InputError naming line_no for a malformed row.
  bool parse(std::string_view line, std::uint64_t line_no, VectorRow& row);
  const std::string& file() const { return *name_; }

 private:
  [[noreturn]] __attribute__((cold)) void fail_missing(std::size_t column, bool after_comma) const;
  [[noreturn]] __attribute__((cold)) void fail_extra(std::string_view rest) const;
  [[noreturn]] __attribute__((cold)) void fail_number(VectorColumn column, NumberStatus status,
                                                      std::string_view text) const;
  std::string column_list() const;  // "t material light x y"

  [[noreturn]] __attribute__((cold)) void fail(const char* field, const std::string& message) const;

  const std::string* name_;
  std::int32_t lights_;
  std::vector<VectorColumn> columns_;
  const MaterialLookup* materials_;
  std::uint32_t last_material_ = 0;
  std::uint64_t line_ = 0;
};

}  // namespace glint
