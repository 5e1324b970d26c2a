#include "io/vectors.h"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <fstream>
#include <istream>
#include <ostream>
#include <stdexcept>
#include <system_error>
#include <unordered_map>
#include <unordered_set>

#include "io/atomic_file.h"

namespace glint {

namespace {

constexpr std::size_t kBufferBytes = std::size_t{1} << 20;  // reader block size

enum class Column : std::uint8_t { kT, kMaterial, kLight, kX, kY };

const char* column_name(Column c) {
  switch (c) {
    case Column::kT:
      return "t";
    case Column::kMaterial:
      return "material";
    case Column::kLight:
      return "light";
    case Column::kX:
      return "x";
    case Column::kY:
      return "y";
  }
  return "?";
}

// Bytes that end a row field: blanks, the comma separator and the comment mark.
constexpr std::array<bool, 256> make_sep_table() {
  std::array<bool, 256> t{};
  t[static_cast<unsigned char>(' ')] = true;
  t[static_cast<unsigned char>('\t')] = true;
  t[static_cast<unsigned char>(',')] = true;
  t[static_cast<unsigned char>('#')] = true;
  return t;
}
constexpr std::array<bool, 256> kSep = make_sep_table();

inline bool is_blank(char c) {
  return c == ' ' || c == '\t';
}

enum class Num { kOk, kNotNumber, kOutOfRange, kNotFinite };

// Decimal numbers via std::from_chars (locale-independent), for doubles and 32-bit integers. An
// optional leading '+' is accepted. Hex floats are not (from_chars' general format has no "0x").
// nan/inf are parsed but reported as kNotFinite; magnitudes beyond the type's range (1e999,
// 1e-999, 2^31) as kOutOfRange.
template <class T>
Num parse_number(std::string_view s, T& out) {
  const char* b = s.data();
  const char* const e = b + s.size();
  if (b != e && *b == '+') {
    ++b;
    if (b != e && *b == '-') return Num::kNotNumber;
  }
  if (b == e) return Num::kNotNumber;
  T v = 0;
  const auto r = std::from_chars(b, e, v);
  if (r.ptr != e) return Num::kNotNumber;
  if (r.ec == std::errc::result_out_of_range) return Num::kOutOfRange;
  if (r.ec != std::errc()) return Num::kNotNumber;
  if constexpr (std::is_floating_point_v<T>) {
    if (!std::isfinite(v)) return Num::kNotFinite;
  }
  out = v;
  return Num::kOk;
}
inline Num parse_double(std::string_view s, double& out) {
  return parse_number(s, out);
}
inline Num parse_int(std::string_view s, std::int32_t& out) {
  return parse_number(s, out);
}

std::string num_problem(Num status, std::string_view text, bool integer) {
  switch (status) {
    case Num::kOk:
      break;
    case Num::kNotNumber:
      return std::string(integer ? "not an integer: " : "not a number: ") + quote_input(text);
    case Num::kOutOfRange:
      return (integer ? "integer out of range: " : "number out of the range of a double: ") +
             quote_input(text);
    case Num::kNotFinite:
      return "value must be finite, got " + quote_input(text);
  }
  return "invalid value " + quote_input(text);
}

std::string fmt_double(double v) {
  char tmp[32];
  const auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  return std::string(tmp, r.ptr);
}

void append_double(std::string& out, double v) {
  char tmp[32];
  const auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  out.append(tmp, r.ptr);
}

void append_int(std::string& out, std::int64_t v) {
  char tmp[24];
  const auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
  out.append(tmp, r.ptr);
}

bool valid_name(std::string_view name) {
  if (name.empty() || name.size() > kVectorMaxNameLength) return false;
  const auto alpha = [](char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); };
  if (!alpha(name[0]) && name[0] != '_') return false;
  for (char c : name) {
    if (!alpha(c) && !(c >= '0' && c <= '9') && c != '_' && c != '.' && c != '-') return false;
  }
  return true;
}

const char* kNameRule = "names are 1-64 characters [A-Za-z0-9_.-] starting with a letter or '_'";

bool parse_lobe(std::string_view s, VectorLobe& lobe) {
  if (s == "phong") {
    lobe = VectorLobe::kPhong;
  } else if (s == "blinn") {
    lobe = VectorLobe::kBlinn;
  } else if (s == "gaussian") {
    lobe = VectorLobe::kGaussian;
  } else {
    return false;
  }
  return true;
}

bool is_white(const std::array<double, 3>& c) {
  return c[0] == 1 && c[1] == 1 && c[2] == 1;
}

}  // namespace

std::size_t VectorHeader::material_index(std::string_view name) const {
  for (std::size_t i = 0; i < materials.size(); ++i) {
    if (materials[i].name == name) return i;
  }
  return npos;
}

std::array<double, 3> VectorHeader::intensity(int index) const {
  if (index < 0 || index >= lights) {
    throw std::out_of_range("VectorHeader::intensity: light " + std::to_string(index) +
                            " out of range (lights " + std::to_string(lights) + ")");
  }
  if (light_intensity.empty()) return {1, 1, 1};
  return light_intensity.at(static_cast<std::size_t>(index));
}

void validate(const VectorHeader& h) {
  const auto bad = [](const std::string& msg) {
    throw std::invalid_argument("invalid vector header: " + msg);
  };
  const auto finite_nonneg = [](const std::array<double, 3>& c) {
    for (double v : c) {
      if (!std::isfinite(v) || v < 0) return false;
    }
    return true;
  };
  if (h.version != kVectorFormatVersion) bad("version must be 1");
  if (!std::isfinite(h.eps) || !(h.eps > 0)) bad("eps must be finite and > 0");
  if (h.lights < 1 || h.lights > kVectorMaxLights) bad("lights must be in 1..1024");
  if (!h.light_intensity.empty()) {
    if (h.light_intensity.size() != static_cast<std::size_t>(h.lights)) {
      bad("light_intensity must be empty or have one entry per light");
    }
    for (const auto& c : h.light_intensity) {
      if (!finite_nonneg(c)) bad("light intensities must be finite and >= 0");
    }
  }
  if (h.materials.empty()) bad("at least one material is required");
  if (h.materials.size() > kVectorMaxMaterials) bad("too many materials");
  std::unordered_set<std::string_view> names;
  for (const auto& m : h.materials) {
    const std::string who = "material '" + m.name + "': ";
    if (!valid_name(m.name)) bad(who + kNameRule);
    if (!names.insert(m.name).second) bad(who + "duplicate name");
    if (!finite_nonneg(m.specular)) bad(who + "specular must be finite and >= 0");
    if (m.lobe == VectorLobe::kGaussian) {
      if (!std::isfinite(m.roughness) || !(m.roughness > 0) || m.roughness > 1) {
        bad(who + "roughness must be in (0, 1]");
      }
      if (!std::isfinite(m.shininess) || m.shininess < 0) {
        bad(who + "shininess must be > 0 (or 0 = not given) for gaussian");
      }
    } else if (m.lobe == VectorLobe::kPhong || m.lobe == VectorLobe::kBlinn) {
      if (!std::isfinite(m.shininess) || !(m.shininess > 0)) bad(who + "shininess must be > 0");
      if (m.roughness != 0) bad(who + "roughness only applies to lobe=gaussian");
    } else {
      bad(who + "unknown lobe");
    }
  }
}

// ---- Reader ----------------------------------------------------------------------------------

struct VectorReader::Impl {
  std::string name;
  std::unique_ptr<std::ifstream> owned;
  std::istream* in = nullptr;

  std::unique_ptr<char[]> buf;
  char* pos = nullptr;
  char* end = nullptr;
  const char* nul = nullptr;  // first NUL byte in [pos, end), if any
  bool eof = false;
  bool last_unterminated = false;
  std::uint64_t line_no = 0;
  std::uint64_t rows = 0;

  VectorHeader header;
  std::vector<Column> columns;
  std::vector<std::string_view> names;  // views of header.materials[i].name
  std::unordered_map<std::string_view, std::uint32_t> name_map;
  std::uint32_t last_material = 0;
  std::unique_ptr<InputError> error;

  std::ios_base::iostate saved_exceptions = std::ios_base::goodbit;

  Impl(std::istream* stream, std::string display_name) : name(std::move(display_name)) {
    in = stream;
    // Short reads at the end set failbit: keep a caller's exception mask from turning that into
    // std::ios_base::failure while we read (restored in the destructor).
    saved_exceptions = in->exceptions();
    in->exceptions(std::ios_base::goodbit);
    buf.reset(new char[kBufferBytes]);
    pos = end = buf.get();
  }

  ~Impl() {
    try {
      in->exceptions(saved_exceptions);
    } catch (...) {  // the stream is at EOF/failed: restoring the mask may throw; nothing to do
    }
  }

  [[noreturn]] __attribute__((noinline, cold)) void fail(std::uint64_t line, const char* field,
                                                         const std::string& message) {
    error = std::make_unique<InputError>(name, line, field, message);
    throw *error;
  }

  void refill() {
    const std::size_t rem = static_cast<std::size_t>(end - pos);
    if (pos != buf.get()) {
      std::memmove(buf.get(), pos, rem);
      if (nul != nullptr) nul -= pos - buf.get();
      pos = buf.get();
      end = pos + rem;
    }
    const std::size_t room = kBufferBytes - rem;
    errno = 0;
    in->read(end, static_cast<std::streamsize>(room));
    const auto got = static_cast<std::size_t>(in->gcount());
    if (in->bad()) {
      const int err = errno;
      fail(line_no + 1, "file",
           std::string("read error") + (err != 0 ? std::string(": ") + std::strerror(err) : ""));
    }
    if (got < room) eof = true;
    if (nul == nullptr && got > 0) nul = static_cast<const char*>(std::memchr(end, '\0', got));
    end += got;
  }

  // The next physical line without its "\n" or "\r\n"; false at end of input.
  bool next_line(std::string_view& out) {
    for (;;) {
      const std::size_t avail = static_cast<std::size_t>(end - pos);
      char* nl = avail != 0 ? static_cast<char*>(std::memchr(pos, '\n', avail)) : nullptr;
      char* line_end = nl;
      if (nl == nullptr) {
        if (avail > kVectorMaxLineBytes + 1) {
          fail(line_no + 1, "line", "line longer than 4096 bytes");
        }
        if (!eof) {
          refill();
          continue;
        }
        if (avail == 0) return false;
        line_end = end;
        last_unterminated = true;
      }
      ++line_no;
      const char* b = pos;
      pos = nl != nullptr ? nl + 1 : end;
      std::size_t len = static_cast<std::size_t>(line_end - b);
      if (len != 0 && b[len - 1] == '\r') --len;
      if (len > kVectorMaxLineBytes) fail(line_no, "line", "line longer than 4096 bytes");
      if (nul != nullptr && nul < line_end) {
        fail(line_no, "line", "embedded NUL byte (not a text file?)");
      }
      out = std::string_view(b, len);
      return true;
    }
  }

  std::uint64_t eof_line() const { return last_unterminated ? line_no : line_no + 1; }

  static void split_header(std::string_view line, std::vector<std::string_view>& tok) {
    tok.clear();
    const auto hash = line.find('#');
    if (hash != std::string_view::npos) line = line.substr(0, hash);
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && is_blank(line[i])) ++i;
      const std::size_t start = i;
      while (i < line.size() && !is_blank(line[i])) ++i;
      if (i > start) tok.push_back(line.substr(start, i - start));
    }
  }

  double header_number(std::string_view text, const char* field) {
    double v = 0;
    const Num st = parse_double(text, v);
    if (st != Num::kOk) fail(line_no, field, num_problem(st, text, false));
    return v;
  }

  std::int32_t header_int(std::string_view text, const char* field) {
    std::int32_t v = 0;
    const Num st = parse_int(text, v);
    if (st != Num::kOk) fail(line_no, field, num_problem(st, text, true));
    return v;
  }

  std::array<double, 3> header_rgb(std::string_view text, const char* field) {
    std::array<double, 3> rgb{};
    std::size_t start = 0;
    for (int k = 0; k < 3; ++k) {
      const std::size_t comma = text.find(',', start);
      const bool last = k == 2;
      if (last != (comma == std::string_view::npos)) {
        fail(line_no, field,
             "expected three comma-separated components r,g,b, got " + quote_input(text));
      }
      const std::string_view part =
          text.substr(start, last ? std::string_view::npos : comma - start);
      rgb[static_cast<std::size_t>(k)] = header_number(part, field);
      if (rgb[static_cast<std::size_t>(k)] < 0) {
        fail(line_no, field, "components must be >= 0, got " + quote_input(part));
      }
      start = comma + 1;
    }
    return rgb;
  }

  void expect_tokens(const std::vector<std::string_view>& tok, std::size_t n, const char* field,
                     const char* usage) {
    if (tok.size() < n) fail(line_no, field, std::string("missing value; usage: ") + usage);
    if (tok.size() > n) {
      fail(line_no, field,
           "unexpected " + quote_input(tok[n]) + " at the end; usage: " + std::string(usage));
    }
  }

  void parse_material(const std::vector<std::string_view>& tok,
                      std::vector<std::uint64_t>& material_lines) {
    if (tok.size() < 2) fail(line_no, "material", "missing material name");
    VectorMaterial m;
    if (!valid_name(tok[1])) {
      fail(line_no, "material", "invalid material name " + quote_input(tok[1]) + ": " + kNameRule);
    }
    m.name = std::string(tok[1]);
    const std::size_t prev = header.material_index(m.name);
    if (prev != VectorHeader::npos) {
      fail(line_no, "material",
           "duplicate material " + quote_input(m.name) + " (first defined on line " +
               std::to_string(material_lines[prev]) + ")");
    }
    if (header.materials.size() >= kVectorMaxMaterials) {
      fail(line_no, "material", "too many materials (limit 65536)");
    }
    bool has_specular = false, has_shininess = false, has_lobe = false, has_roughness = false;
    for (std::size_t i = 2; i < tok.size(); ++i) {
      const auto eq = tok[i].find('=');
      if (eq == std::string_view::npos) {
        fail(line_no, "material",
             "expected key=value (specular=, shininess=, lobe=, roughness=), got " +
                 quote_input(tok[i]));
      }
      const std::string_view key = tok[i].substr(0, eq);
      const std::string_view value = tok[i].substr(eq + 1);
      bool* seen = nullptr;
      const char* field = nullptr;
      if (key == "specular") {
        seen = &has_specular;
        field = "specular";
      } else if (key == "shininess") {
        seen = &has_shininess;
        field = "shininess";
      } else if (key == "lobe") {
        seen = &has_lobe;
        field = "lobe";
      } else if (key == "roughness") {
        seen = &has_roughness;
        field = "roughness";
      } else {
        fail(line_no, "material",
             "unknown material attribute " + quote_input(key) +
                 " (known: specular, shininess, lobe, roughness)");
      }
      if (*seen) fail(line_no, field, "given twice");
      *seen = true;
      if (value.empty()) fail(line_no, field, "missing value after '='");
      if (key == "specular") {
        m.specular = header_rgb(value, field);
      } else if (key == "shininess") {
        m.shininess = header_number(value, field);
        if (!(m.shininess > 0)) {
          fail(line_no, field, "shininess must be > 0, got " + quote_input(value));
        }
      } else if (key == "lobe") {
        if (!parse_lobe(value, m.lobe)) {
          fail(line_no, field,
               "unknown lobe " + quote_input(value) + " (expected phong, blinn or gaussian)");
        }
      } else {
        m.roughness = header_number(value, field);
        if (!(m.roughness > 0) || m.roughness > 1) {
          fail(line_no, field, "roughness must be in (0, 1], got " + quote_input(value));
        }
      }
    }
    if (!has_specular) fail(line_no, "specular", "missing specular=r,g,b");
    if (!has_lobe) fail(line_no, "lobe", "missing lobe=phong|blinn|gaussian");
    if (m.lobe == VectorLobe::kGaussian) {
      if (!has_roughness) fail(line_no, "roughness", "lobe=gaussian requires roughness=W");
    } else {
      if (!has_shininess) {
        fail(line_no, "shininess",
             std::string("lobe=") + to_string(m.lobe) + " requires shininess=N (> 0)");
      }
      if (has_roughness) fail(line_no, "roughness", "roughness only applies to lobe=gaussian");
    }
    header.materials.push_back(std::move(m));
    material_lines.push_back(line_no);
  }

  void parse_columns(const std::vector<std::string_view>& tok) {
    bool seen[5] = {false, false, false, false, false};
    for (std::size_t i = 1; i < tok.size(); ++i) {
      Column c;
      if (tok[i] == "t") {
        c = Column::kT;
      } else if (tok[i] == "material") {
        c = Column::kMaterial;
      } else if (tok[i] == "light") {
        c = Column::kLight;
      } else if (tok[i] == "x") {
        c = Column::kX;
      } else if (tok[i] == "y") {
        c = Column::kY;
      } else {
        fail(line_no, "columns",
             "unknown column " + quote_input(tok[i]) + " (known: t, material, light, x, y)");
      }
      if (seen[static_cast<int>(c)]) {
        fail(line_no, "columns", "column " + quote_input(tok[i]) + " listed twice");
      }
      seen[static_cast<int>(c)] = true;
      columns.push_back(c);
    }
    if (!seen[static_cast<int>(Column::kT)]) fail(line_no, "columns", "the column 't' is required");
    if (!seen[static_cast<int>(Column::kMaterial)]) {
      fail(line_no, "columns", "the column 'material' is required");
    }
    if (seen[static_cast<int>(Column::kX)] != seen[static_cast<int>(Column::kY)]) {
      fail(line_no, "columns", "pixel columns 'x' and 'y' must be given together");
    }
    header.has_light = seen[static_cast<int>(Column::kLight)];
    header.has_xy = seen[static_cast<int>(Column::kX)];
  }

  void parse_header() {
    struct PendingLight {
      std::int32_t index;
      std::array<double, 3> rgb;
      std::uint64_t line;
    };
    std::vector<PendingLight> pending;
    std::vector<std::uint64_t> material_lines;
    std::uint64_t eps_line = 0, lights_line = 0, columns_line = 0;
    bool magic = false;
    std::vector<std::string_view> tok;
    std::string_view line;

    const auto complete = [&](std::uint64_t at) {
      if (eps_line == 0) fail(at, "eps", "missing 'eps VALUE' header line");
      if (lights_line == 0) fail(at, "lights", "missing 'lights N' header line");
      if (header.materials.empty()) fail(at, "material", "no 'material' header line");
      if (columns_line == 0) fail(at, "columns", "missing 'columns ...' header line");
      for (const auto& p : pending) {
        if (p.index >= header.lights) {
          fail(p.line, "light",
               "light index " + std::to_string(p.index) + " out of range (lights " +
                   std::to_string(header.lights) + ")");
        }
      }
    };

    while (next_line(line)) {
      if (line_no == 1 && line.size() >= 3 && line.substr(0, 3) == "\xEF\xBB\xBF") {
        line.remove_prefix(3);  // UTF-8 byte order mark
      }
      split_header(line, tok);
      if (tok.empty()) continue;
      if (!magic) {
        if (tok[0] != "glint-vectors") {
          fail(line_no, "magic",
               "not a glint vector file: expected 'glint-vectors 1' as the first line, got " +
                   quote_input(tok[0]));
        }
        if (tok.size() < 2)
          fail(line_no, "version", "missing format version after 'glint-vectors'");
        const std::int32_t v = header_int(tok[1], "version");
        if (v != kVectorFormatVersion) {
          fail(line_no, "version",
               "unsupported format version " + std::to_string(v) +
                   " (this reader supports version 1)");
        }
        if (tok.size() > 2) {
          fail(line_no, "version", "unexpected " + quote_input(tok[2]) + " after the version");
        }
        header.version = v;
        magic = true;
        continue;
      }
      const std::string_view key = tok[0];
      if (key == "eps") {
        if (eps_line != 0) {
          fail(line_no, "eps", "given twice (first on line " + std::to_string(eps_line) + ")");
        }
        expect_tokens(tok, 2, "eps", "eps VALUE");
        header.eps = header_number(tok[1], "eps");
        if (!(header.eps > 0)) fail(line_no, "eps", "eps must be > 0, got " + quote_input(tok[1]));
        eps_line = line_no;
      } else if (key == "lights") {
        if (lights_line != 0) {
          fail(line_no, "lights",
               "given twice (first on line " + std::to_string(lights_line) + ")");
        }
        expect_tokens(tok, 2, "lights", "lights N");
        header.lights = header_int(tok[1], "lights");
        if (header.lights < 1 || header.lights > kVectorMaxLights) {
          fail(line_no, "lights", "must be in 1..1024, got " + quote_input(tok[1]));
        }
        lights_line = line_no;
      } else if (key == "light") {
        expect_tokens(tok, 3, "light", "light INDEX r,g,b");
        const std::int32_t index = header_int(tok[1], "light");
        if (index < 0 || index >= kVectorMaxLights) {
          fail(line_no, "light", "light index out of range: " + quote_input(tok[1]));
        }
        for (const auto& p : pending) {
          if (p.index == index) {
            fail(line_no, "light",
                 "light " + std::to_string(index) + " given twice (first on line " +
                     std::to_string(p.line) + ")");
          }
        }
        pending.push_back({index, header_rgb(tok[2], "light"), line_no});
      } else if (key == "material") {
        parse_material(tok, material_lines);
      } else if (key == "columns") {
        if (columns_line != 0) {
          fail(line_no, "columns",
               "given twice (first on line " + std::to_string(columns_line) + ")");
        }
        parse_columns(tok);
        columns_line = line_no;
      } else if (key == "data") {
        expect_tokens(tok, 1, "data", "data (alone on its line)");
        complete(line_no);
        header.light_intensity.assign(static_cast<std::size_t>(header.lights), {1, 1, 1});
        for (const auto& p : pending) {
          header.light_intensity[static_cast<std::size_t>(p.index)] = p.rgb;
        }
        names.reserve(header.materials.size());
        for (std::size_t i = 0; i < header.materials.size(); ++i) {
          names.emplace_back(header.materials[i].name);
          name_map.emplace(names.back(), static_cast<std::uint32_t>(i));
        }
        return;
      } else if (key == "glint-vectors") {
        fail(line_no, "header", "'glint-vectors' given twice");
      } else {
        fail(line_no, "header",
             "unknown header key " + quote_input(key) +
                 " (known: eps, lights, light, material, columns, data)");
      }
    }
    const std::uint64_t at = eof_line();
    if (!magic) {
      fail(at, "magic",
           line_no == 0 ? "empty file: expected 'glint-vectors 1'"
                        : "no 'glint-vectors 1' line (only comments and blank lines)");
    }
    complete(at);
    fail(at, "data", "end of file before the 'data' line");
  }

  bool find_material(std::string_view tok, std::uint32_t& index) {
    const std::string_view last = names[last_material];
    if (tok.size() == last.size() && std::memcmp(tok.data(), last.data(), tok.size()) == 0) {
      index = last_material;
      return true;
    }
    if (names.size() <= 8) {
      for (std::uint32_t i = 0; i < names.size(); ++i) {
        if (names[i] == tok) {
          index = last_material = i;
          return true;
        }
      }
      return false;
    }
    const auto it = name_map.find(tok);
    if (it == name_map.end()) return false;
    index = last_material = it->second;
    return true;
  }

  [[noreturn]] __attribute__((noinline, cold)) void fail_missing(std::size_t i, bool comma) {
    std::string list;
    for (Column c : columns) {
      if (!list.empty()) list += ' ';
      list += column_name(c);
    }
    fail(line_no, column_name(columns[i]),
         comma ? std::string("empty field after ','")
               : "missing field: the row has " + std::to_string(i) + " of " +
                     std::to_string(columns.size()) + " columns (" + list + ")");
  }

  [[noreturn]] __attribute__((noinline, cold)) void fail_extra(std::string_view rest) {
    std::string list;
    for (Column c : columns) {
      if (!list.empty()) list += ' ';
      list += column_name(c);
    }
    std::size_t n = 0;
    while (n < rest.size() && !kSep[static_cast<unsigned char>(rest[n])]) ++n;
    fail(line_no, "columns",
         "extra field " + quote_input(rest.substr(0, n)) + ": rows have " +
             std::to_string(columns.size()) + " columns (" + list + ")");
  }

  [[noreturn]] __attribute__((noinline, cold)) void fail_field(Column c, Num st,
                                                               std::string_view text) {
    fail(line_no, column_name(c), num_problem(st, text, c != Column::kT));
  }

  void parse_row(const char* p, const char* e, VectorRow& row) {
    row.light = 0;
    row.x = -1;
    row.y = -1;
    const std::size_t n = columns.size();
    for (std::size_t i = 0; i < n; ++i) {
      if (i > 0) {
        bool comma = false;
        while (p < e && is_blank(*p)) ++p;
        if (p < e && *p == ',') {
          comma = true;
          ++p;
          while (p < e && is_blank(*p)) ++p;
        }
        if (p == e || *p == '#') fail_missing(i, comma);
      }
      const char* f = p;
      while (p < e && !kSep[static_cast<unsigned char>(*p)]) ++p;
      const std::string_view tok(f, static_cast<std::size_t>(p - f));
      const Column c = columns[i];
      if (tok.empty()) fail(line_no, column_name(c), "empty field");
      switch (c) {
        case Column::kT: {
          double v = 0;
          const Num st = parse_double(tok, v);
          if (st != Num::kOk) fail_field(c, st, tok);
          if (!(v >= kVectorTMin && v <= kVectorTMax)) {
            fail(line_no, "t", "t = " + std::string(tok) + " outside [-1, 1.001]");
          }
          row.t = v;
          break;
        }
        case Column::kMaterial: {
          std::uint32_t index = 0;
          if (!find_material(tok, index)) {
            fail(line_no, "material", "unknown material " + quote_input(tok));
          }
          row.material = index;
          break;
        }
        case Column::kLight: {
          std::int32_t v = 0;
          const Num st = parse_int(tok, v);
          if (st != Num::kOk) fail_field(c, st, tok);
          if (v < 0 || v >= header.lights) {
            fail(line_no, "light",
                 "light index " + std::string(tok) + " out of range 0.." +
                     std::to_string(header.lights - 1));
          }
          row.light = v;
          break;
        }
        case Column::kX:
        case Column::kY: {
          std::int32_t v = 0;
          const Num st = parse_int(tok, v);
          if (st != Num::kOk) fail_field(c, st, tok);
          if (v < 0) {
            fail(line_no, column_name(c), "pixel coordinate must be >= 0, got " + std::string(tok));
          }
          (c == Column::kX ? row.x : row.y) = v;
          break;
        }
      }
    }
    while (p < e && is_blank(*p)) ++p;
    if (p < e && *p == ',') {
      ++p;
      while (p < e && is_blank(*p)) ++p;
      if (p == e || *p == '#') fail(line_no, "columns", "trailing ',' after the last column");
    }
    if (p < e && *p != '#') fail_extra(std::string_view(p, static_cast<std::size_t>(e - p)));
  }

  bool next(VectorRow& row) {
    if (error) throw *error;
    std::string_view line;
    for (;;) {
      if (!next_line(line)) return false;
      const char* p = line.data();
      const char* const e = p + line.size();
      while (p < e && is_blank(*p)) ++p;
      if (p == e || *p == '#') continue;
      parse_row(p, e, row);
      row.line = line_no;
      ++rows;
      return true;
    }
  }
};

VectorReader::VectorReader(const std::string& path) {
  auto file = std::make_unique<std::ifstream>(path, std::ios::in | std::ios::binary);
  if (!file->is_open()) {
    const int err = errno;
    throw InputError(path, 0, "file",
                     std::string("cannot open for reading: ") +
                         (err != 0 ? std::strerror(err) : "unknown error"));
  }
  impl_ = std::make_unique<Impl>(file.get(), path);
  impl_->owned = std::move(file);
  impl_->parse_header();
}

VectorReader::VectorReader(std::istream& in, std::string name)
    : impl_(std::make_unique<Impl>(&in, std::move(name))) {
  impl_->parse_header();
}

VectorReader::~VectorReader() = default;

const VectorHeader& VectorReader::header() const {
  return impl_->header;
}
const std::string& VectorReader::name() const {
  return impl_->name;
}
bool VectorReader::next(VectorRow& row) {
  return impl_->next(row);
}
std::uint64_t VectorReader::rows_read() const {
  return impl_->rows;
}

// ---- Writer ----------------------------------------------------------------------------------

struct VectorWriter::Impl {
  std::string where;  // the path, or "<stream>", for messages
  VectorHeader header;
  std::unique_ptr<AtomicOutputFile> file;
  std::ostream* out = nullptr;
  std::string buf;
  std::uint64_t rows = 0;
  bool committed = false;

  static constexpr std::size_t kFlushBytes = std::size_t{1} << 20;

  Impl(std::string w, const VectorHeader& h) : where(std::move(w)), header(h) {
    validate(header);
    buf.reserve(kFlushBytes + 256);
  }

  void write_header() {
    buf += "glint-vectors 1\neps ";
    append_double(buf, header.eps);
    buf += "\nlights ";
    append_int(buf, header.lights);
    buf += '\n';
    for (std::size_t i = 0; i < header.light_intensity.size(); ++i) {
      const auto& c = header.light_intensity[i];
      if (is_white(c)) continue;
      buf += "light ";
      append_int(buf, static_cast<std::int64_t>(i));
      for (int k = 0; k < 3; ++k) {
        buf += k == 0 ? ' ' : ',';
        append_double(buf, c[static_cast<std::size_t>(k)]);
      }
      buf += '\n';
    }
    for (const auto& m : header.materials) {
      buf += "material ";
      buf += m.name;
      buf += " specular=";
      for (int k = 0; k < 3; ++k) {
        if (k != 0) buf += ',';
        append_double(buf, m.specular[static_cast<std::size_t>(k)]);
      }
      buf += " lobe=";
      buf += to_string(m.lobe);
      if (m.shininess > 0) {
        buf += " shininess=";
        append_double(buf, m.shininess);
      }
      if (m.lobe == VectorLobe::kGaussian) {
        buf += " roughness=";
        append_double(buf, m.roughness);
      }
      buf += '\n';
    }
    buf += "columns t material";
    if (header.has_light) buf += " light";
    if (header.has_xy) buf += " x y";
    buf += "\ndata\n";
  }

  void flush() {
    out->write(buf.data(), static_cast<std::streamsize>(buf.size()));
    buf.clear();
    if (!*out) throw std::runtime_error("VectorWriter: cannot write '" + where + "'");
  }

  void write(const VectorRow& r) {
    if (committed) throw std::logic_error("VectorWriter::write after commit()");
    const auto bad = [&](const std::string& msg) {
      throw std::invalid_argument("VectorWriter: row " + std::to_string(rows + 1) + ": " + msg);
    };
    if (!std::isfinite(r.t) || !(r.t >= kVectorTMin && r.t <= kVectorTMax)) {
      bad("t = " + fmt_double(r.t) + " is not finite or outside [-1, 1.001]");
    }
    if (r.material >= header.materials.size()) {
      bad("material index " + std::to_string(r.material) + " out of range");
    }
    if (header.has_light) {
      if (r.light < 0 || r.light >= header.lights) {
        bad("light " + std::to_string(r.light) + " out of range");
      }
    } else if (r.light != 0) {
      bad("light " + std::to_string(r.light) + " but the header has no light column");
    }
    if (header.has_xy) {
      if (r.x < 0 || r.y < 0) bad("pixel coordinates must be >= 0");
    } else if (r.x != -1 || r.y != -1) {
      bad("pixel coordinates given but the header has no x y columns");
    }
    append_double(buf, r.t);
    buf += ' ';
    buf += header.materials[r.material].name;
    if (header.has_light) {
      buf += ' ';
      append_int(buf, r.light);
    }
    if (header.has_xy) {
      buf += ' ';
      append_int(buf, r.x);
      buf += ' ';
      append_int(buf, r.y);
    }
    buf += '\n';
    ++rows;
    if (buf.size() >= kFlushBytes) flush();
  }

  void commit() {
    if (committed) throw std::logic_error("VectorWriter::commit called twice");
    flush();
    if (file) {
      file->commit();
    } else {
      out->flush();
      if (!*out) throw std::runtime_error("VectorWriter: cannot write '" + where + "'");
    }
    committed = true;
  }
};

VectorWriter::VectorWriter(const std::string& path, const VectorHeader& header)
    : impl_(std::make_unique<Impl>(path, header)) {
  impl_->file = std::make_unique<AtomicOutputFile>(path);
  impl_->out = &impl_->file->stream();
  impl_->write_header();
}

VectorWriter::VectorWriter(std::ostream& out, const VectorHeader& header)
    : impl_(std::make_unique<Impl>("<stream>", header)) {
  impl_->out = &out;
  impl_->write_header();
}

VectorWriter::~VectorWriter() = default;

void VectorWriter::write(const VectorRow& row) {
  impl_->write(row);
}
void VectorWriter::commit() {
  impl_->commit();
}
const VectorHeader& VectorWriter::header() const {
  return impl_->header;
}
std::uint64_t VectorWriter::rows_written() const {
  return impl_->rows;
}

}  // namespace glint
