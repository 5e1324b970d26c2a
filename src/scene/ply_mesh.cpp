#include "scene/ply_mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/input_error.h"
#include "scene/smooth_normals.h"

namespace glint {

namespace {

// At most this many corners per face (a uchar count allows 255; real files use 3 or 4).
constexpr std::uint64_t kMaxCorners = 1024;
constexpr std::size_t kMaxHeaderBytes = 64 * 1024;
constexpr std::size_t kMaxAsciiLine = 1 << 20;

enum class Encoding { kAscii, kLittle, kBig };

struct Property {
  std::string name;
  int size = 0;     // bytes of the value
  char kind = 'i';  // 'i' signed, 'u' unsigned, 'f' floating
  bool list = false;
  int count_size = 0;
  char count_kind = 'u';
};

struct Element {
  std::string name;
  std::uint64_t count = 0;
  std::vector<Property> properties;
};

bool scalar_type(const std::string& t, int& size, char& kind) {
  static const struct {
    const char* name;
    int size;
    char kind;
  } kTypes[] = {{"char", 1, 'i'},  {"int8", 1, 'i'},    {"uchar", 1, 'u'},  {"uint8", 1, 'u'},
                {"short", 2, 'i'}, {"int16", 2, 'i'},   {"ushort", 2, 'u'}, {"uint16", 2, 'u'},
                {"int", 4, 'i'},   {"int32", 4, 'i'},   {"uint", 4, 'u'},   {"uint32", 4, 'u'},
                {"float", 4, 'f'}, {"float32", 4, 'f'}, {"double", 8, 'f'}, {"float64", 8, 'f'}};
  for (const auto& k : kTypes)
    if (t == k.name) {
      size = k.size;
      kind = k.kind;
      return true;
    }
  return false;
}

bool all_digits(const std::string& s) {
  return !s.empty() && s.size() <= 19 &&
         std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// The body after the header: values one at a time, as text tokens or binary numbers.
class Body {
 public:
  Body(std::ifstream& in, const std::string& path, Encoding enc, std::uint64_t line)
      : in_(in), path_(path), enc_(enc), line_(line) {}

  std::uint64_t line() const { return enc_ == Encoding::kAscii ? line_ : 0; }

  // The next value of a property's type; false at the end of the file.
  bool next(int size, char kind, double& out) {
    if (enc_ == Encoding::kAscii) return next_token(out);
    unsigned char b[8];
    if (!in_.read(reinterpret_cast<char*>(b), size)) return false;
    if (enc_ == Encoding::kBig) std::reverse(b, b + size);
    std::uint64_t u = 0;
    for (int i = size - 1; i >= 0; --i) u = u << 8 | b[i];
    if (kind == 'f') {
      if (size == 4) {
        float f;
        const auto u32 = static_cast<std::uint32_t>(u);
        std::memcpy(&f, &u32, 4);
        out = f;
      } else {
        std::memcpy(&out, &u, 8);
      }
    } else if (kind == 'u') {
      out = static_cast<double>(u);
    } else {
      const int shift = 64 - 8 * size;  // sign-extend
      out = static_cast<double>(static_cast<std::int64_t>(u << shift) >> shift);
    }
    return true;
  }

 private:
  bool next_token(double& out) {
    while (pos_ >= text_.size() || !skip_space()) {
      if (!std::getline(in_, text_)) return false;
      ++line_;
      if (text_.size() > kMaxAsciiLine)
        throw InputError(path_, line_, "line", "longer than " + std::to_string(kMaxAsciiLine));
      pos_ = 0;
    }
    const std::size_t end = text_.find_first_of(" \t\r\v\f", pos_);
    const std::string token = text_.substr(pos_, end == std::string::npos ? end : end - pos_);
    pos_ = end == std::string::npos ? text_.size() : end;
    char* stop = nullptr;
    out = std::strtod(token.c_str(), &stop);
    if (stop == token.c_str() || *stop != '\0')
      throw InputError(path_, line_, "line", "not a number: " + quote_input(token));
    return true;
  }
  bool skip_space() {
    while (pos_ < text_.size() && std::strchr(" \t\r\v\f", text_[pos_]) != nullptr) ++pos_;
    return pos_ < text_.size();
  }

  std::ifstream& in_;
  const std::string& path_;
  Encoding enc_;
  std::uint64_t line_;
  std::string text_;
  std::size_t pos_ = 0;
};

const char* field_of(const std::string& element) {
  return element == "vertex" ? "vertex" : element == "face" ? "f" : "element";
}

}  // namespace

Mesh load_ply_mesh(const std::string& path, std::size_t max_triangles, const ObjLimits& limits,
                   double crease_degrees) {
  check_file_bytes(path, limits.max_bytes, "mesh file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "file", "cannot open the mesh file");

  // The header, line by line.
  Encoding enc = Encoding::kAscii;
  std::vector<Element> elements;
  std::uint64_t number = 0, header_bytes = 0;
  const auto fail = [&](const std::string& what) {
    throw InputError(path, number, "header", what);
  };
  for (std::string line;;) {
    if (!std::getline(in, line)) fail("no \"end_header\" line");
    ++number;
    header_bytes += line.size() + 1;
    if (header_bytes > kMaxHeaderBytes) fail("no \"end_header\" line in the first 64 KiB");
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words_in(line);
    std::vector<std::string> w;
    for (std::string x; words_in >> x;) w.push_back(x);
    if (number == 1) {
      if (line != "ply") fail("a PLY file starts with the line \"ply\"");
      continue;
    }
    const std::string keyword = w.empty() ? "" : w[0];
    if (keyword == "end_header") break;
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      if (w.size() != 3 || w[2] != "1.0" ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
        fail("expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
      enc = w[1] == "ascii"                  ? Encoding::kAscii
            : w[1] == "binary_little_endian" ? Encoding::kLittle
                                             : Encoding::kBig;
      continue;
    }
    if (keyword == "property") {
      if (elements.empty()) fail("a property before any element");
      Property p;
      const bool ok = w.size() == 3 ? scalar_type(w[1], p.size, p.kind)
                      : w.size() == 5 && w[1] == "list"
                          ? scalar_type(w[2], p.count_size, p.count_kind) && p.count_kind != 'f' &&
                                scalar_type(w[3], p.size, p.kind)
                          : false;
      if (!ok)
        fail(
            "expected \"property TYPE NAME\" or \"property list TYPE TYPE NAME\" (an integer "
            "count type), TYPE one of char uchar short ushort int uint float double");
      p.list = w.size() == 5;
      p.name = w.back();
      elements.back().properties.push_back(p);
      continue;
    }
    if (keyword != "element") fail("unknown header line " + quote_input(line));
    if (w.size() != 3 || !all_digits(w[2]))
      fail("expected \"element NAME COUNT\", COUNT a whole number");
    Element e{w[1], std::stoull(w[2]), {}};
    if (e.name == "vertex" && e.count > limits.max_vertices)
      fail("more than " + std::to_string(limits.max_vertices) +
           " vertices (the limit per mesh file)");
    if (e.name == "face" && e.count > max_triangles)
      fail("more than " + std::to_string(max_triangles) +
           " faces (what is left of the scene's limit of " + std::to_string(kSceneMaxTriangles) +
           " triangles)");
    elements.push_back(e);
  }

  // Which properties matter.
  const Element* vertex = nullptr;
  for (const Element& e : elements)
    if (e.name == "vertex") vertex = &e;
  if (vertex == nullptr) throw InputError(path, number, "header", "no \"element vertex\"");
  const auto find = [](const Element& e, const char* name) {
    for (std::size_t i = 0; i < e.properties.size(); ++i)
      if (e.properties[i].name == name && !e.properties[i].list) return static_cast<int>(i);
    return -1;
  };
  const int xyz[3] = {find(*vertex, "x"), find(*vertex, "y"), find(*vertex, "z")};
  if (xyz[0] < 0 || xyz[1] < 0 || xyz[2] < 0)
    throw InputError(path, number, "header", "the vertex element needs properties x, y and z");
  const int nxyz[3] = {find(*vertex, "nx"), find(*vertex, "ny"), find(*vertex, "nz")};
  const bool has_normals = nxyz[0] >= 0 && nxyz[1] >= 0 && nxyz[2] >= 0;

  std::vector<Vec3> positions, normals;
  std::vector<std::array<std::uint32_t, 3>> faces;
  Body body(in, path, enc, number);
  std::vector<std::uint32_t> corners;
  for (const Element& e : elements) {
    const bool is_vertex = &e == vertex, is_face = e.name == "face";
    if (e.properties.empty()) continue;  // nothing to read, however many
    for (std::uint64_t item = 0; item < e.count; ++item) {
      const std::string where = (is_face ? "face " : e.name + " ") + std::to_string(item + 1);
      double values[3] = {0, 0, 0}, n[3] = {0, 0, 0};
      for (std::size_t pi = 0; pi < e.properties.size(); ++pi) {
        const Property& p = e.properties[pi];
        const auto read = [&](int size, char kind, double& v) {
          if (!body.next(size, kind, v))
            throw InputError(path, body.line(), field_of(e.name),
                             where + ": the file ends inside it");
        };
        if (!p.list) {
          double v = 0;
          read(p.size, p.kind, v);
          if (is_vertex)
            for (int k = 0; k < 3; ++k) {
              if (xyz[k] == static_cast<int>(pi)) values[k] = v;
              if (nxyz[k] == static_cast<int>(pi)) n[k] = v;
            }
          continue;
        }
        double count = 0;
        read(p.count_size, p.count_kind, count);
        if (!(count >= 0 && count <= static_cast<double>(kMaxCorners) &&
              count == std::floor(count)))
          throw InputError(path, body.line(), field_of(e.name),
                           where + ": a list of " + std::to_string(count) + " values (at most " +
                               std::to_string(kMaxCorners) + ")");
        const bool indices = is_face && (p.name == "vertex_indices" || p.name == "vertex_index");
        corners.clear();
        for (int c = 0; c < static_cast<int>(count); ++c) {
          double v = 0;
          read(p.size, p.kind, v);
          if (!indices) continue;
          if (!(v >= 0 && v < static_cast<double>(vertex->count) && v == std::floor(v)))
            throw InputError(path, body.line(), "f",
                             where + ": vertex index " + std::to_string(v) +
                                 " out of range (the file has " + std::to_string(vertex->count) +
                                 " vertices)");
          corners.push_back(static_cast<std::uint32_t>(v));
        }
        if (corners.size() >= 3) {
          if (faces.size() + corners.size() - 2 > max_triangles)
            throw InputError(path, body.line(), "f",
                             where + ": more than " + std::to_string(max_triangles) +
                                 " triangles (what is left of the scene's limit of " +
                                 std::to_string(kSceneMaxTriangles) + ")");
          for (std::size_t k = 2; k < corners.size(); ++k)
            faces.push_back({corners[0], corners[k - 1], corners[k]});
        }
      }
      if (!is_vertex) continue;
      if (!(std::isfinite(values[0]) && std::isfinite(values[1]) && std::isfinite(values[2])))
        throw InputError(path, body.line(), "vertex", where + ": a coordinate is not finite");
      positions.push_back({values[0], values[1], values[2]});
      if (!has_normals) continue;
      const Vec3 nv{n[0], n[1], n[2]};
      if (!(std::isfinite(nv.x) && std::isfinite(nv.y) && std::isfinite(nv.z)) || length(nv) == 0)
        throw InputError(path, body.line(), "normal", where + ": its normal is zero or not finite");
      normals.push_back(normalize(nv));
    }
  }
  // Faces may come before the vertices: every index was checked against the declared count, and
  // every declared vertex has been read by now.
  if (faces.empty()) throw InputError(path, 0, "f", "no triangles (a mesh needs faces)");

  Mesh out = mesh_with_normals(std::move(positions), std::move(normals), std::move(faces),
                               has_normals, crease_degrees, path);
  out.format = "ply";
  return out;
}

}  // namespace glint
