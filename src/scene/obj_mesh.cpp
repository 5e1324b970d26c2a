#include "scene/obj_mesh.h"

#include <tiny_obj_loader.h>

#include <cmath>
#include <fstream>
#include <unordered_map>

#include "io/input_error.h"
#include "scene/mesh_file.h"
#include "scene/smooth_normals.h"

namespace glint {

namespace {

// Ignores `mtllib`: the scene gives materials, and an OBJ must not make glint open other files.
class NoMaterials : public tinyobj::MaterialReader {
 public:
  bool operator()(const std::string&, std::vector<tinyobj::material_t>*,
                  std::map<std::string, int>*, std::string*, std::string*) override {
    return true;
  }
};

std::string first_line(const std::string& text) {
  std::string s = text.substr(0, text.find('\n'));
  return s.empty() ? "unknown error" : s;
}

Vec3 triple(const std::vector<tinyobj::real_t>& values, std::size_t index) {
  return {values[3 * index], values[3 * index + 1], values[3 * index + 2]};
}

bool finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

Mesh load_obj_mesh(const std::string& path, std::size_t max_triangles, const ObjLimits& limits,
                   double crease_degrees) {
  check_file_bytes(path, limits.max_bytes, "OBJ file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "file", "cannot open the OBJ file");
  // A first pass holds every limit and every number to glint's rules, with the line; then
  // tinyobjloader reads the same open file again (it has neither limits nor line numbers).
  scan_obj(in, path, max_triangles, limits);
  in.clear();
  if (!in.seekg(0))
    throw InputError(path, 0, "file", "cannot read the OBJ file again (not seekable)");
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> materials;
  std::string warn, err;
  NoMaterials no_materials;
  // No triangulation by tinyobjloader: its polygon code reads vertex positions before any index
  // is checked. glint checks every index first, then splits polygons itself.
  if (!tinyobj::LoadObj(&attrib, &shapes, &materials, &warn, &err, &in, &no_materials,
                        /*triangulate=*/false, /*default_vcols_fallback=*/false)) {
    throw InputError(path, 0, "obj", "tinyobjloader cannot read it: " + first_line(err));
  }
  const std::size_t n_positions = attrib.vertices.size() / 3;
  const std::size_t n_normals = attrib.normals.size() / 3;

  std::size_t triangles = 0;
  for (const auto& shape : shapes) {
    for (const unsigned n : shape.mesh.num_face_vertices) triangles += n >= 3 ? n - 2 : 0;
  }
  if (triangles > max_triangles) {
    throw InputError(path, 0, "f",
                     std::to_string(triangles) + " triangles, more than the scene's remaining " +
                         "limit of " + std::to_string(max_triangles));
  }
  if (triangles == 0) throw InputError(path, 0, "f", "no faces (a mesh needs triangles)");

  // The file's normals only when every face vertex names one: a mesh half with normals and half
  // without is smoothed whole, so that the report's one word for it is true.
  bool all_normals = true;
  for (const auto& shape : shapes)
    for (const tinyobj::index_t& ix : shape.mesh.indices) all_normals &= ix.normal_index != -1;
  std::vector<Vec3> positions;  // without normals: every v, for smooth_normals
  std::vector<std::array<std::uint32_t, 3>> plain_faces;
  if (!all_normals) {
    positions.reserve(n_positions);
    for (std::size_t v = 0; v < n_positions; ++v) positions.push_back(triple(attrib.vertices, v));
    plain_faces.reserve(triangles);
  }

  Mesh mesh;
  mesh.faces.reserve(triangles);
  std::unordered_map<std::uint64_t, std::uint32_t> vertex_of;  // (v << 32 | vn) -> vertex
  std::size_t face_number = 0;
  for (const auto& shape : shapes) {
    std::size_t offset = 0;
    for (const unsigned count : shape.mesh.num_face_vertices) {
      ++face_number;
      const std::string where = "face " + std::to_string(face_number) +
                                (shape.name.empty() ? "" : " (object '" + shape.name + "')");
      std::vector<std::uint32_t> corners;
      for (unsigned k = 0; k < count; ++k) {
        const tinyobj::index_t& ix = shape.mesh.indices[offset + k];
        // tinyobjloader resolves relative (negative) indices but does not bound-check them.
        if (ix.vertex_index < 0 || static_cast<std::size_t>(ix.vertex_index) >= n_positions) {
          throw InputError(path, 0, "f",
                           where + ": vertex index out of range (the file has " +
                               std::to_string(n_positions) + " vertices)");
        }
        if (ix.normal_index != -1 &&
            (ix.normal_index < 0 || static_cast<std::size_t>(ix.normal_index) >= n_normals)) {
          throw InputError(path, 0, "f",
                           where + ": normal index out of range (the file has " +
                               std::to_string(n_normals) + " normals)");
        }
        const auto v = static_cast<std::uint32_t>(ix.vertex_index);
        if (!all_normals) {
          corners.push_back(v);
          continue;
        }
        const auto vn = static_cast<std::uint32_t>(ix.normal_index);
        const auto [it, added] = vertex_of.emplace(
            std::uint64_t{v} << 32 | vn, static_cast<std::uint32_t>(mesh.positions.size()));
        if (added) {
          const Vec3 p = triple(attrib.vertices, v);
          const Vec3 n = triple(attrib.normals, vn);
          if (!finite(p)) throw InputError(path, 0, "v", where + ": a position is not finite");
          if (!finite(n) || length(n) == 0) {
            throw InputError(path, 0, "vn", where + ": a normal is zero or not finite");
          }
          mesh.positions.push_back(p);
          mesh.normals.push_back(normalize(n));
        }
        corners.push_back(it->second);
      }
      offset += count;
      auto& into = all_normals ? mesh.faces : plain_faces;
      for (std::size_t k = 2; k < corners.size(); ++k) {
        into.push_back({corners[0], corners[k - 1], corners[k]});
      }
    }
  }
  if (!all_normals) mesh = smooth_normals(positions, plain_faces, crease_degrees, path);
  mesh.format = "obj";
  return mesh;
}

}  // namespace glint
