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
  bool find(std::string_view name, std::uint32_t& index) {
    const std::string_view last = names_[last_];
    if (name.size() == last.size() && std::memcmp(name.data(), last.data(), name.size()) == 0) {
      index = last_;
      return true;
    }
    if (names_.size() <= kLinearNames) {
      for (std::uint32_t i = 0; i < names_.size(); ++i) {
        if (names_[i] == name) {
          index = last_ = i;
          return true;
        }
      }
      return false;
    }
    const auto it = by_name_.find(name);
    if (it == by_name_.end()) return false;
    index = last_ = it->second;
    return true;
  }

 private:
  // Up to this many names a linear scan beats hashing the name.
  static constexpr std::size_t kLinearNames = 8;

  std::vector<std::string_view> names_;
  std::unordered_map<std::string_view, std::uint32_t> by_name_;
  std::uint32_t last_ = 0;
};

// Parses row lines into VectorRows, each field by the rule of its column.
class RowParser {
 public:
  // Rows laid out as `file` declares. Errors name the current line of `lines`; the parser keeps
  // references to `lines` and to the materials of `file`, which must outlive it.
  RowParser(const LineReader& lines, const VectorFileHeader& file);

  // Parses `line` into `row` (all but row.line). False for a blank or comment-only line, which
  // holds no row. Throws InputError for a malformed row.
  bool parse(std::string_view line, VectorRow& row);

 private:
  [[noreturn]] __attribute__((cold)) void fail_missing(std::size_t column, bool after_comma) const;
  [[noreturn]] __attribute__((cold)) void fail_extra(std::string_view rest) const;
  [[noreturn]] __attribute__((cold)) void fail_number(VectorColumn column, NumberStatus status,
                                                      std::string_view text) const;
  std::string column_list() const;  // "t material light x y"

  const LineReader& lines_;
  std::int32_t lights_;
  std::vector<VectorColumn> columns_;
  MaterialLookup materials_;
};

}  // namespace glint
