#include "io/vector_header.h"

#include <array>
#include <iterator>
#include <optional>
#include <string>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "io/input_error.h"
#include "io/vector_rules.h"
#include "io/vector_syntax.h"
#include "reference/reference.h"

namespace glint {

namespace {

using Tokens = std::vector<std::string_view>;

// Indexed by VectorColumn.
constexpr const char* kColumnNames[] = {"t", "material", "light", "x", "y"};

// Material attributes; their names are also the error fields of their values.
enum class Attribute : std::uint8_t { kSpecular, kShininess, kLobe, kRoughness };
constexpr const char* kAttributeNames[] = {"specular", "shininess", "lobe", "roughness"};
using AttributesGiven = std::array<bool, std::size(kAttributeNames)>;  // indexed by Attribute

template <class Names>
std::string join(const Names& names, const char* separator) {
  std::string out;
  for (const char* name : names) {
    if (!out.empty()) out += separator;
    out += name;
  }
  return out;
}

// Index of `word` in `names`, or nullopt.
template <class Names>
std::optional<std::size_t> find_name(const Names& names, std::string_view word) {
  for (std::size_t i = 0; i < std::size(names); ++i) {
    if (word == names[i]) return i;
  }
  return std::nullopt;
}

// The header's lines come in any order, so what one line needs from another (a light's index
// against `lights`, "given twice") is remembered until `data`.
class HeaderParser {
 public:
  explicit HeaderParser(LineReader& lines) : lines_(lines) {}
  VectorFileHeader read();

 private:
  void parse_magic(const Tokens& tok);
  void parse_keyword(const Tokens& tok);
  void parse_eps(const Tokens& tok);
  void parse_display(const Tokens& tok);
  void parse_lights(const Tokens& tok);
  void parse_light(const Tokens& tok);
  void parse_material(const Tokens& tok);
  void parse_material_attribute(std::string_view token, AttributesGiven& given, VectorMaterial& m);
  void parse_columns(const Tokens& tok);
  void parse_data(const Tokens& tok);
  // The header is complete: every required line was there and the `light` lines fit `lights`.
  void check_complete(std::uint64_t at) const;

  double number(std::string_view text, const char* field) const;
  std::int32_t integer(std::string_view text, const char* field) const;
  std::array<double, 3> rgb(std::string_view text, const char* field) const;
  void expect_tokens(const Tokens& tok, std::size_t n, const char* field, const char* usage) const;
  // Refuses a second line of a keyword that first appeared on `first_line` (0: not yet).
  void once(std::uint64_t first_line, const char* field) const;
  [[noreturn]] void fail(const char* field, const std::string& message) const {
    lines_.fail(field, message);
  }
  std::uint64_t line() const { return lines_.line_number(); }

  struct PendingLight {
    std::int32_t index;
    std::array<double, 3> rgb;
    std::uint64_t line;
  };

  LineReader& lines_;
  VectorFileHeader result_;
  bool magic_seen_ = false;
  bool done_ = false;  // `data` read
  std::uint64_t eps_line_ = 0, lights_line_ = 0, columns_line_ = 0, display_line_ = 0;
  std::vector<PendingLight> pending_lights_;
  // Where each material was defined, by name: also the duplicate check, in constant time since
  // a file may hold kVectorMaxMaterials of them.
  std::unordered_map<std::string, std::uint64_t> material_lines_;
};

VectorFileHeader HeaderParser::read() {
  Tokens tok;
  std::string_view text;
  while (!done_ && lines_.next(text)) {
    if (line() == 1 && text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);  // UTF-8 BOM
    split_header_tokens(text, tok);
    if (tok.empty()) continue;
    if (magic_seen_) {
      parse_keyword(tok);
    } else {
      parse_magic(tok);
    }
  }
  if (done_) return std::move(result_);
  const std::uint64_t at = lines_.end_line();
  if (!magic_seen_) {
    lines_.fail_at(at, "magic",
                   line() == 0 ? "empty file: expected '" + magic_line() + "'"
                               : "no '" + magic_line() + "' line (only comments and blank lines)");
  }
  check_complete(at);
  lines_.fail_at(at, "data", "end of file before the 'data' line");
}

void HeaderParser::parse_magic(const Tokens& tok) {
  if (tok[0] != kVectorMagic) {
    fail("magic", "not a glint vector file: expected '" + magic_line() +
                      "' as the first line, got " + quote_input(tok[0]));
  }
  if (tok.size() < 2) {
    fail("version", "missing format version after '" + std::string(kVectorMagic) + "'");
  }
  const std::int32_t version = integer(tok[1], "version");
  if (version != kVectorFormatVersion) {
    fail("version", "unsupported format version " + std::to_string(version) +
                        " (this reader supports version " + std::to_string(kVectorFormatVersion) +
                        ")");
  }
  if (tok.size() > 2) fail("version", "unexpected " + quote_input(tok[2]) + " after the version");
  result_.header.version = version;
  magic_seen_ = true;
}

void HeaderParser::parse_keyword(const Tokens& tok) {
  struct Keyword {
    const char* name;
    void (HeaderParser::*parse)(const Tokens&);
  };
  static constexpr Keyword kKeywords[] = {
      {"eps", &HeaderParser::parse_eps},         {"lights", &HeaderParser::parse_lights},
      {"light", &HeaderParser::parse_light},     {"material", &HeaderParser::parse_material},
      {"columns", &HeaderParser::parse_columns}, {"data", &HeaderParser::parse_data},
      {"display", &HeaderParser::parse_display},
  };
  const std::string_view key = tok[0];
  for (const Keyword& k : kKeywords) {
    if (key == k.name) return (this->*k.parse)(tok);
  }
  if (key == kVectorMagic) fail("header", "'" + std::string(kVectorMagic) + "' given twice");
  std::string known;
  for (const Keyword& k : kKeywords) known += (known.empty() ? "" : ", ") + std::string(k.name);
  fail("header", "unknown header key " + quote_input(key) + " (known: " + known + ")");
}

void HeaderParser::parse_eps(const Tokens& tok) {
  once(eps_line_, "eps");
  expect_tokens(tok, 2, "eps", "eps VALUE");
  const double eps = number(tok[1], "eps");
  if (!valid_eps(eps)) fail("eps", "eps must be > 0, got " + quote_input(tok[1]));
  result_.header.eps = eps;
  eps_line_ = line();
}

void HeaderParser::parse_display(const Tokens& tok) {
  once(display_line_, "display");
  expect_tokens(tok, 2, "display", "display linear8|srgb8");
  const auto display = try_parse_display(tok[1]);
  if (!display) fail("display", "expected linear8 or srgb8, got " + quote_input(tok[1]));
  result_.header.display = *display;
  display_line_ = line();
}

void HeaderParser::parse_lights(const Tokens& tok) {
  once(lights_line_, "lights");
  expect_tokens(tok, 2, "lights", "lights N");
  const std::int32_t lights = integer(tok[1], "lights");
  if (!valid_light_count(lights)) {
    fail("lights", "must be in " + light_count_range_text() + ", got " + quote_input(tok[1]));
  }
  result_.header.lights = lights;
  lights_line_ = line();
}

void HeaderParser::parse_light(const Tokens& tok) {
  expect_tokens(tok, 3, "light", "light INDEX r,g,b");
  const std::int32_t index = integer(tok[1], "light");
  if (!valid_light_index(index, kVectorMaxLights)) {
    fail("light", "light index out of range: " + quote_input(tok[1]));
  }
  for (const auto& p : pending_lights_) {
    if (p.index == index) {
      fail("light", "light " + std::to_string(index) + " given twice (first on line " +
                        std::to_string(p.line) + ")");
    }
  }
  pending_lights_.push_back({index, rgb(tok[2], "light"), line()});
}

void HeaderParser::parse_material(const Tokens& tok) {
  if (tok.size() < 2) fail("material", "missing material name");
  if (!valid_name(tok[1])) {
    fail("material", "invalid material name " + quote_input(tok[1]) + ": " + name_rule());
  }
  VectorMaterial m;
  m.name = std::string(tok[1]);
  auto& materials = result_.header.materials;
  const auto first = material_lines_.find(m.name);
  if (first != material_lines_.end()) {
    fail("material", "duplicate material " + quote_input(m.name) + " (first defined on line " +
                         std::to_string(first->second) + ")");
  }
  if (!valid_material_count(materials.size() + 1)) {
    fail("material", "too many materials (limit " + std::to_string(kVectorMaxMaterials) + ")");
  }
  AttributesGiven given{};
  for (std::size_t i = 2; i < tok.size(); ++i) parse_material_attribute(tok[i], given, m);
  const auto has = [&](Attribute a) { return given[static_cast<std::size_t>(a)]; };
  if (!has(Attribute::kSpecular)) fail("specular", "missing specular=r,g,b");
  if (!has(Attribute::kLobe)) fail("lobe", "missing lobe=phong|blinn|gaussian");
  if (takes_roughness(m.lobe)) {
    if (!has(Attribute::kRoughness)) {
      fail("roughness", std::string("lobe=") + to_string(m.lobe) + " requires roughness=W");
    }
  } else {
    if (!has(Attribute::kShininess)) {
      fail("shininess", std::string("lobe=") + to_string(m.lobe) + " requires shininess=N (> 0)");
    }
    if (has(Attribute::kRoughness)) fail("roughness", "roughness only applies to lobe=gaussian");
  }
  material_lines_.emplace(m.name, line());
  materials.push_back(std::move(m));
}

void HeaderParser::parse_material_attribute(std::string_view token, AttributesGiven& given,
                                            VectorMaterial& m) {
  const auto eq = token.find('=');
  if (eq == std::string_view::npos) {
    fail("material",
         "expected key=value (" + join(kAttributeNames, "=, ") + "=), got " + quote_input(token));
  }
  const std::string_view key = token.substr(0, eq);
  const std::string_view value = token.substr(eq + 1);
  const auto index = find_name(kAttributeNames, key);
  if (!index) {
    fail("material", "unknown material attribute " + quote_input(key) +
                         " (known: " + join(kAttributeNames, ", ") + ")");
  }
  const char* field = kAttributeNames[*index];
  if (given[*index]) fail(field, "given twice");
  given[*index] = true;
  if (value.empty()) fail(field, "missing value after '='");
  switch (static_cast<Attribute>(*index)) {
    case Attribute::kSpecular:
      m.specular = rgb(value, field);
      break;
    case Attribute::kShininess:
      m.shininess = number(value, field);
      if (!valid_shininess(m.shininess)) {
        fail(field, "shininess must be > 0, got " + quote_input(value));
      }
      break;
    case Attribute::kLobe: {
      const auto lobe = try_parse_lobe(value);
      if (!lobe) {
        fail(field, "unknown lobe " + quote_input(value) + " (expected phong, blinn or gaussian)");
      }
      m.lobe = *lobe;
      break;
    }
    case Attribute::kRoughness:
      m.roughness = number(value, field);
      if (!valid_roughness(m.roughness)) {
        fail(field,
             "roughness must be in " + roughness_range_text() + ", got " + quote_input(value));
      }
      break;
  }
}

void HeaderParser::parse_columns(const Tokens& tok) {
  once(columns_line_, "columns");
  std::array<bool, std::size(kColumnNames)> listed{};
  for (std::size_t i = 1; i < tok.size(); ++i) {
    const auto index = find_name(kColumnNames, tok[i]);
    if (!index) {
      fail("columns",
           "unknown column " + quote_input(tok[i]) + " (known: " + join(kColumnNames, ", ") + ")");
    }
    if (listed[*index]) fail("columns", "column " + quote_input(tok[i]) + " listed twice");
    listed[*index] = true;
    result_.columns.push_back(static_cast<VectorColumn>(*index));
  }
  const auto has = [&](VectorColumn c) { return listed[static_cast<std::size_t>(c)]; };
  for (const VectorColumn required : {VectorColumn::kT, VectorColumn::kMaterial}) {
    if (!has(required)) {
      fail("columns", std::string("the column '") + column_name(required) + "' is required");
    }
  }
  if (has(VectorColumn::kX) != has(VectorColumn::kY)) {
    fail("columns", "pixel columns 'x' and 'y' must be given together");
  }
  result_.header.has_light = has(VectorColumn::kLight);
  result_.header.has_xy = has(VectorColumn::kX);
  columns_line_ = line();
}

void HeaderParser::parse_data(const Tokens& tok) {
  expect_tokens(tok, 1, "data", "data (alone on its line)");
  check_complete(line());
  VectorHeader& h = result_.header;
  h.light_intensity.assign(static_cast<std::size_t>(h.lights), {1, 1, 1});
  for (const auto& p : pending_lights_) {
    h.light_intensity[static_cast<std::size_t>(p.index)] = p.rgb;
  }
  done_ = true;
}

void HeaderParser::check_complete(std::uint64_t at) const {
  const VectorHeader& h = result_.header;
  if (eps_line_ == 0) lines_.fail_at(at, "eps", "missing 'eps VALUE' header line");
  if (lights_line_ == 0) lines_.fail_at(at, "lights", "missing 'lights N' header line");
  if (h.materials.empty()) lines_.fail_at(at, "material", "no 'material' header line");
  if (columns_line_ == 0) lines_.fail_at(at, "columns", "missing 'columns ...' header line");
  for (const auto& p : pending_lights_) {
    if (!valid_light_index(p.index, h.lights)) {
      lines_.fail_at(p.line, "light",
                     "light index " + std::to_string(p.index) + " out of range (lights " +
                         std::to_string(h.lights) + ")");
    }
  }
}

double HeaderParser::number(std::string_view text, const char* field) const {
  double v = 0;
  const NumberStatus status = parse_number(text, v);
  if (status != NumberStatus::kOk) fail(field, number_problem(status, text, false));
  return v;
}

std::int32_t HeaderParser::integer(std::string_view text, const char* field) const {
  std::int32_t v = 0;
  const NumberStatus status = parse_number(text, v);
  if (status != NumberStatus::kOk) fail(field, number_problem(status, text, true));
  return v;
}

std::array<double, 3> HeaderParser::rgb(std::string_view text, const char* field) const {
  std::array<double, 3> components{};
  std::size_t start = 0;
  for (std::size_t k = 0; k < 3; ++k) {
    const std::size_t comma = text.find(',', start);
    const bool last = k == 2;
    if (last != (comma == std::string_view::npos)) {
      fail(field, "expected three comma-separated components r,g,b, got " + quote_input(text));
    }
    const std::string_view part = text.substr(start, last ? std::string_view::npos : comma - start);
    components[k] = number(part, field);
    if (!valid_colour_component(components[k])) {
      fail(field, "components must be >= 0, got " + quote_input(part));
    }
    start = comma + 1;
  }
  return components;
}

void HeaderParser::expect_tokens(const Tokens& tok, std::size_t n, const char* field,
                                 const char* usage) const {
  if (tok.size() < n) fail(field, std::string("missing value; usage: ") + usage);
  if (tok.size() > n) {
    fail(field, "unexpected " + quote_input(tok[n]) + " at the end; usage: " + usage);
  }
}

void HeaderParser::once(std::uint64_t first_line, const char* field) const {
  if (first_line != 0) {
    fail(field, "given twice (first on line " + std::to_string(first_line) + ")");
  }
}

}  // namespace

const char* column_name(VectorColumn column) {
  return kColumnNames[static_cast<std::size_t>(column)];
}

VectorFileHeader read_vector_header(LineReader& lines) {
  return HeaderParser(lines).read();
}

}  // namespace glint
