#include "scene/bezier.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <stdexcept>
#include <string_view>

#include "io/input_error.h"
#include "io/line_reader.h"
#include "io/vector_syntax.h"
#include "scene/mesh_file.h"

namespace glint {

namespace {

// Reads the file's significant lines as tokens, keeping line numbers for errors. LineReader
// refuses a long line before reading it all, where std::getline would hold any length.
class TokenLines {
 public:
  TokenLines(const std::string& path, std::uint64_t max_bytes)
      : in_(path, std::ios::binary), lines_(in_, path) {
    if (!in_) throw InputError(path, 0, "file", "cannot open the patch file");
    check_file_bytes(path, max_bytes, "patch file");
  }

  // The next non-blank line's tokens; false at the end of the file.
  bool next(std::vector<std::string_view>& tokens) {
    std::string_view text;
    while (lines_.next(text)) {
      split_header_tokens(text, tokens);
      if (!tokens.empty()) return true;
    }
    return false;
  }

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    lines_.fail(field.c_str(), message);
  }

  template <class T>
  T number(std::string_view token, const char* field) const {
    T v{};
    const NumberStatus status = parse_number(token, v);
    if (status != NumberStatus::kOk) {
      fail(field, number_problem(status, token, std::is_integral_v<T>));
    }
    return v;
  }

 private:
  std::ifstream in_;
  LineReader lines_;
};

// Bernstein basis of degree 3 and its derivative.
void bernstein(double t, double b[4], double d[4]) {
  const double s = 1 - t;
  b[0] = s * s * s;
  b[1] = 3 * t * s * s;
  b[2] = 3 * t * t * s;
  b[3] = t * t * t;
  d[0] = -3 * s * s;
  d[1] = 3 * s * s - 6 * t * s;
  d[2] = 6 * t * s - 3 * t * t;
  d[3] = 3 * t * t;
}

// The unit normal at (u, v). A collapsed edge (a pole) has a zero derivative along it; the
// normal's limit there is the normal just inside the patch, so step towards the centre until the
// derivatives span a plane. False if they never do (the patch is degenerate).
bool patch_normal(const BezierPatch& patch, double u, double v, Vec3& n) {
  for (double step = 0; step <= 0.5; step = step == 0 ? 1e-4 : step * 10) {
    const PatchPoint q = evaluate(patch, u + step * (0.5 - u), v + step * (0.5 - v));
    // dP/dv x dP/du: Newell's patches are parametrised so that this one points outwards.
    const Vec3 c = cross(q.dv, q.du);
    const double scale = std::max(length(q.du), length(q.dv));
    if (length(c) > 1e-9 * scale * scale) {
      n = normalize(c);
      return true;
    }
  }
  return false;
}

}  // namespace

std::vector<BezierPatch> read_bezier_patches(const std::string& path, std::uint64_t max_bytes) {
  TokenLines lines(path, max_bytes);
  std::vector<std::string_view> tokens;
  if (!lines.next(tokens)) lines.fail("patches", "empty file: no patch count");
  if (tokens.size() != 1) lines.fail("patches", "the first line must be the number of patches");
  const auto count = lines.number<std::int64_t>(tokens[0], "patches");
  if (count < 1 || count > static_cast<std::int64_t>(kSceneMaxBezierPatches)) {
    lines.fail("patches",
               "the number of patches must be in 1.." + std::to_string(kSceneMaxBezierPatches));
  }
  std::vector<BezierPatch> patches(static_cast<std::size_t>(count));
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const std::string which = "patch " + std::to_string(p + 1) + " of " + std::to_string(count);
    if (!lines.next(tokens)) lines.fail("degree", "the file ends before " + which);
    if (tokens.size() != 2 || lines.number<std::int64_t>(tokens[0], "degree") != 3 ||
        lines.number<std::int64_t>(tokens[1], "degree") != 3) {
      lines.fail("degree", which + ": expected \"3 3\" (only bicubic patches)");
    }
    for (Vec3& point : patches[p]) {
      if (!lines.next(tokens)) lines.fail("point", "the file ends inside " + which);
      if (tokens.size() != 3) lines.fail("point", which + ": a control point is \"x y z\"");
      point = {lines.number<double>(tokens[0], "point"), lines.number<double>(tokens[1], "point"),
               lines.number<double>(tokens[2], "point")};
    }
  }
  if (lines.next(tokens)) lines.fail("patches", "data after the last patch");
  return patches;
}

PatchPoint evaluate(const BezierPatch& patch, double u, double v) {
  double bu[4], du[4], bv[4], dv[4];
  bernstein(u, bu, du);
  bernstein(v, bv, dv);
  PatchPoint q;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      const Vec3& c = patch[static_cast<std::size_t>(4 * i + j)];
      q.p = q.p + c * (bu[i] * bv[j]);
      q.du = q.du + c * (du[i] * bv[j]);
      q.dv = q.dv + c * (bu[i] * dv[j]);
    }
  }
  return q;
}

Mesh tessellate_bezier(const std::vector<BezierPatch>& patches, int subdivisions,
                       const std::string& path) {
  const auto s = static_cast<std::size_t>(subdivisions);
  // Vertex indices are 32-bit; a scene's triangle limit keeps loaded patches far below this.
  if (subdivisions < 1 || patches.size() * (s + 1) * (s + 1) > 0xffffffffu) {
    throw std::invalid_argument("tessellate_bezier: subdivisions out of range");
  }
  Mesh mesh;
  mesh.positions.reserve(patches.size() * (s + 1) * (s + 1));
  mesh.normals.reserve(mesh.positions.capacity());
  mesh.faces.reserve(patches.size() * s * s * 2);
  for (std::size_t p = 0; p < patches.size(); ++p) {
    const auto base = static_cast<std::uint32_t>(mesh.positions.size());
    for (std::size_t i = 0; i <= s; ++i) {
      for (std::size_t j = 0; j <= s; ++j) {
        const double u = static_cast<double>(i) / static_cast<double>(s);
        const double v = static_cast<double>(j) / static_cast<double>(s);
        Vec3 n;
        if (!patch_normal(patches[p], u, v, n)) {
          throw InputError(path, 0, "point",
                           "patch " + std::to_string(p + 1) + " is degenerate: no normal near (" +
                               format_double(u) + ", " + format_double(v) + ")");
        }
        mesh.positions.push_back(evaluate(patches[p], u, v).p);
        mesh.normals.push_back(n);
      }
    }
    const auto row = static_cast<std::uint32_t>(s + 1);
    for (std::uint32_t i = 0; i < s; ++i) {
      for (std::uint32_t j = 0; j < s; ++j) {
        const std::uint32_t a = base + i * row + j, b = a + 1, c = a + row, d = c + 1;
        for (std::array<std::uint32_t, 3> f : {std::array<std::uint32_t, 3>{a, c, d}, {a, d, b}}) {
          const Vec3 g = cross(mesh.positions[f[1]] - mesh.positions[f[0]],
                               mesh.positions[f[2]] - mesh.positions[f[0]]);
          const Vec3 n = mesh.normals[f[0]] + mesh.normals[f[1]] + mesh.normals[f[2]];
          if (dot(g, n) < 0) std::swap(f[1], f[2]);
          mesh.faces.push_back(f);
        }
      }
    }
  }
  return mesh;
}

}  // namespace glint
