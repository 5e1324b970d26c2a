#include "io/vector_rows.h"

#include <array>

#include "io/input_error.h"
#include "io/vector_rules.h"

namespace glint {

namespace {

// Bytes that end a row field: blanks, the comma separator and the comment mark. A table, since
// it is asked once per byte; internal, so that position-independent code reads it directly
// rather than through the GOT.
constexpr std::array<bool, 256> kRowFieldEnd = [] {
  std::array<bool, 256> end{};
  for (const char c : {' ', '\t', ',', '#'}) end[static_cast<unsigned char>(c)] = true;
  return end;
}();

inline bool ends_row_field(char c) {
  return kRowFieldEnd[static_cast<unsigned char>(c)];
}

}  // namespace

MaterialLookup::MaterialLookup(const std::vector<VectorMaterial>& materials) {
  names_.reserve(materials.size());
  for (std::size_t i = 0; i < materials.size(); ++i) {
    names_.emplace_back(materials[i].name);
    by_name_.emplace(names_.back(), static_cast<std::uint32_t>(i));
  }
}

RowParser::RowParser(const std::string& name, const VectorFileHeader& file,
                     const MaterialLookup& materials)
    : name_(&name), lights_(file.header.lights), columns_(file.columns), materials_(&materials) {}

void RowParser::fail(const char* field, const std::string& message) const {
  throw InputError(*name_, line_, field, message);
}

bool RowParser::parse(std::string_view line, std::uint64_t line_no, VectorRow& row) {
  line_ = line_no;
  const char* p = line.data();
  const char* const e = p + line.size();
  while (p < e && is_blank(*p)) ++p;
  if (p == e || *p == '#') return false;
  row.light = 0;
  row.x = -1;
  row.y = -1;
  const std::size_t n = columns_.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (i > 0) {
      // Fields are separated by blanks, or by one comma with optional blanks around it.
      bool comma = false;
      while (p < e && is_blank(*p)) ++p;
      if (p < e && *p == ',') {
        comma = true;
        ++p;
        while (p < e && is_blank(*p)) ++p;
      }
      if (p == e || *p == '#') fail_missing(i, comma);
    }
    const char* const f = p;
    const VectorColumn c = columns_[i];
    if (c == VectorColumn::kT) {
      // The common form at once, without scanning the field twice (parse_plain_decimal).
      double v = 0;
      const char* const q = parse_plain_decimal(p, e, v);
      if (q && (q == e || ends_row_field(*q)) && valid_t(v)) {
        row.t = v;
        p = q;
        continue;
      }
    }
    while (p < e && !ends_row_field(*p)) ++p;
    const std::string_view tok(f, static_cast<std::size_t>(p - f));
    if (tok.empty()) fail(column_name(c), "empty field");
    switch (c) {
      case VectorColumn::kT: {
        double v = 0;
        const NumberStatus st = parse_number(tok, v);
        if (st != NumberStatus::kOk) fail_number(c, st, tok);
        if (!valid_t(v)) fail("t", "t = " + std::string(tok) + " outside " + t_range_text());
        row.t = v;
        break;
      }
      case VectorColumn::kMaterial: {
        std::uint32_t index = 0;
        if (!materials_->find(tok, index, last_material_)) {
          fail("material", "unknown material " + quote_input(tok));
        }
        row.material = index;
        break;
      }
      case VectorColumn::kLight: {
        std::int32_t v = 0;
        const NumberStatus st = parse_number(tok, v);
        if (st != NumberStatus::kOk) fail_number(c, st, tok);
        if (!valid_light_index(v, lights_)) {
          fail("light", "light index " + std::string(tok) + " out of range 0.." +
                            std::to_string(lights_ - 1));
        }
        row.light = v;
        break;
      }
      case VectorColumn::kX:
      case VectorColumn::kY: {
        std::int32_t v = 0;
        const NumberStatus st = parse_number(tok, v);
        if (st != NumberStatus::kOk) fail_number(c, st, tok);
        if (!valid_pixel(v)) {
          fail(column_name(c), "pixel coordinate must be >= 0, got " + std::string(tok));
        }
        (c == VectorColumn::kX ? row.x : row.y) = v;
        break;
      }
    }
  }
  while (p < e && is_blank(*p)) ++p;
  if (p < e && *p == ',') {
    ++p;
    while (p < e && is_blank(*p)) ++p;
    if (p == e || *p == '#') fail("columns", "trailing ',' after the last column");
  }
  if (p < e && *p != '#') fail_extra(std::string_view(p, static_cast<std::size_t>(e - p)));
  return true;
}

std::string RowParser::column_list() const {
  std::string list;
  for (const VectorColumn c : columns_) {
    if (!list.empty()) list += ' ';
    list += column_name(c);
  }
  return list;
}

void RowParser::fail_missing(std::size_t column, bool after_comma) const {
  fail(column_name(columns_[column]),
       after_comma ? std::string("empty field after ','")
                   : "missing field: the row has " + std::to_string(column) + " of " +
                         std::to_string(columns_.size()) + " columns (" + column_list() + ")");
}

void RowParser::fail_extra(std::string_view rest) const {
  std::size_t n = 0;
  while (n < rest.size() && !ends_row_field(rest[n])) ++n;
  fail("columns", "extra field " + quote_input(rest.substr(0, n)) + ": rows have " +
                      std::to_string(columns_.size()) + " columns (" + column_list() + ")");
}

void RowParser::fail_number(VectorColumn column, NumberStatus status, std::string_view text) const {
  fail(column_name(column), number_problem(status, text, column != VectorColumn::kT));
}

}  // namespace glint
