#include "scene/mesh_file.h"

#include <filesystem>
#include <string_view>
#include <vector>

#include "io/input_error.h"
#include "io/line_reader.h"
#include "io/vector_syntax.h"
#include "scene/scene.h"

namespace glint {

namespace {

std::string bytes_text(std::uint64_t bytes) {
  return std::to_string(bytes) + " bytes";
}

// How many coordinates a line of each kind holds: v x y z, then optionally w and a colour (up to
// 7, as tinyobjloader reads them); vn x y z; vt u [v [w]].
bool coordinate_count_ok(std::string_view keyword, std::size_t n) {
  if (keyword == "v") return n >= 3 && n <= 7;
  if (keyword == "vn") return n == 3;
  return n >= 1 && n <= 3;
}

const char* coordinate_rule(std::string_view keyword) {
  if (keyword == "v") return "expected \"v x y z\" and at most 4 more numbers (w, a colour)";
  if (keyword == "vn") return "expected \"vn x y z\"";
  return "expected \"vt u [v [w]]\"";
}

}  // namespace

void check_file_bytes(const std::string& path, std::uint64_t max_bytes, const char* what) {
  std::error_code ec;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) throw InputError(path, 0, "file", std::string("cannot read the size of the ") + what);
  if (size > max_bytes) {
    throw InputError(path, 0, "file",
                     "the " + std::string(what) + " is " + bytes_text(size) +
                         ", more than the limit of " + bytes_text(max_bytes));
  }
}

void scan_obj(std::istream& in, const std::string& path, std::size_t max_triangles,
              const ObjLimits& limits) {
  LineReader lines(in, path);
  std::string_view line;
  std::vector<std::string_view> tokens;
  std::uint64_t bytes = 0, triangles = 0, positions = 0, normals = 0, texcoords = 0;
  while (lines.next(line)) {
    // The file may have grown since its size was checked: count what is read.
    bytes += line.size() + 1;
    if (bytes > limits.max_bytes + 1) {
      lines.fail("file", "more than the limit of " + bytes_text(limits.max_bytes));
    }
    split_header_tokens(line, tokens);
    if (tokens.empty()) continue;
    const std::string_view keyword = tokens[0];
    if (keyword == "f") {
      const std::size_t n = tokens.size() - 1;
      if (n >= 3) triangles += n - 2;
      if (triangles > max_triangles) {
        lines.fail("f", "more than " + std::to_string(max_triangles) +
                            " triangles (what is left of the scene's limit of " +
                            std::to_string(kSceneMaxTriangles) + ")");
      }
      continue;
    }
    std::uint64_t* count = keyword == "v"    ? &positions
                           : keyword == "vn" ? &normals
                           : keyword == "vt" ? &texcoords
                                             : nullptr;
    if (count == nullptr) continue;
    const std::string field(keyword);
    if (++*count > limits.max_vertices) {
      lines.fail(field.c_str(), "more than " + std::to_string(limits.max_vertices) + " '" + field +
                                    "' lines (the limit per OBJ file)");
    }
    if (!coordinate_count_ok(keyword, tokens.size() - 1)) {
      lines.fail(field.c_str(), coordinate_rule(keyword));
    }
    for (std::size_t i = 1; i < tokens.size(); ++i) {
      double v = 0;
      const NumberStatus status = parse_number(tokens[i], v);
      if (status != NumberStatus::kOk) {
        lines.fail(field.c_str(), number_problem(status, tokens[i], false));
      }
    }
  }
}

}  // namespace glint
