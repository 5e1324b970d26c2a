#include "scene/assimp_mesh.h"

#include <assimp/DefaultIOSystem.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "io/input_error.h"
#include "scene/smooth_normals.h"

namespace fs = std::filesystem;

namespace glint {

namespace {

constexpr const char* kFormats = "OBJ (.obj), PLY (.ply), glTF 2.0 (.gltf, .glb) or STL (.stl)";

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string head(const std::string& path, std::size_t n) {
  std::ifstream in(path, std::ios::binary);
  std::string bytes(n, '\0');
  in.read(bytes.data(), static_cast<std::streamsize>(n));
  bytes.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return bytes;
}

// Assimp opens other files of a glTF (its .bin buffers) through this: only files in the mesh's
// own folder, each within the byte limit, so a mesh cannot make glint read elsewhere.
class FolderIo : public Assimp::DefaultIOSystem {
 public:
  FolderIo(const std::string& path, std::uint64_t max_bytes)
      : folder_(fs::absolute(path).lexically_normal().parent_path()), max_bytes_(max_bytes) {}

  bool Exists(const char* file) const override {
    return allowed(file) && DefaultIOSystem::Exists(file);
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!allowed(file) || std::strchr(mode, 'w') != nullptr) return nullptr;
    std::error_code ec;
    const std::uintmax_t size = fs::file_size(file, ec);
    if (ec || size > max_bytes_) return nullptr;
    return DefaultIOSystem::Open(file, mode);
  }

 private:
  bool allowed(const char* file) const {
    std::error_code ec;
    const fs::path p = fs::absolute(file, ec).lexically_normal();
    return !ec && p.parent_path() == folder_ && fs::is_regular_file(p, ec);
  }

  fs::path folder_;
  std::uint64_t max_bytes_;
};

bool all_digits(const std::string& s) {
  return !s.empty() && s.size() <= 19 &&
         std::all_of(s.begin(), s.end(), [](char c) { return c >= '0' && c <= '9'; });
}

// A PLY header read to glint's rules before Assimp sees the file: Assimp 5.2's PLY reader never
// returns from some malformed headers (a count that is not a number), and it allocates for the
// declared counts, so those are held to the limits first. Errors name the header's line.
void check_ply_header(const std::string& path, std::size_t max_triangles, const ObjLimits& limits) {
  std::istringstream header(head(path, 64 * 1024));
  std::string line;
  std::uint64_t number = 0;
  const auto fail = [&](const std::string& what) {
    throw InputError(path, number, "header", what);
  };
  while (std::getline(header, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream in(line);
    std::vector<std::string> words;
    for (std::string w; in >> w;) words.push_back(w);
    if (number == 1) {
      if (line != "ply") fail("a PLY file starts with the line \"ply\"");
      continue;
    }
    const std::string keyword = words.empty() ? "" : words[0];
    if (keyword == "end_header") return;
    if (keyword == "comment" || keyword == "obj_info") continue;
    if (keyword == "format") {
      if (words.size() != 3 || (words[1] != "ascii" && words[1] != "binary_little_endian" &&
                                words[1] != "binary_big_endian"))
        fail("expected \"format ascii|binary_little_endian|binary_big_endian 1.0\"");
      continue;
    }
    if (keyword == "property") {
      if (!(words.size() == 3 || (words.size() == 5 && words[1] == "list")))
        fail("expected \"property TYPE NAME\" or \"property list TYPE TYPE NAME\"");
      continue;
    }
    if (keyword != "element") fail("unknown header line " + quote_input(line));
    if (words.size() != 3 || !all_digits(words[2]))
      fail("expected \"element NAME COUNT\", COUNT a whole number");
    const std::uint64_t count = std::stoull(words[2]);
    if (words[1] == "vertex" && count > limits.max_vertices) {
      fail("more than " + std::to_string(limits.max_vertices) +
           " vertices (the limit per mesh file)");
    }
    if (words[1] == "face" && count > max_triangles) {
      fail("more than " + std::to_string(max_triangles) +
           " faces (what is left of the scene's limit of " + std::to_string(kSceneMaxTriangles) +
           " triangles)");
    }
  }
  fail("no \"end_header\" line in the first 64 KiB");
}

// A binary STL's triangle count (bytes 80..83) against the limit and the file's size.
void check_stl_header(const std::string& path, std::size_t max_triangles) {
  const std::string bytes = head(path, 84);
  if (bytes.size() < 84 || lower(bytes.substr(0, 5)) == "solid") return;  // ASCII: Assimp reads
  std::uint32_t n = 0;
  for (int i = 3; i >= 0; --i) n = n << 8 | static_cast<unsigned char>(bytes[80 + i]);
  if (n > max_triangles) {
    throw InputError(path, 0, "f",
                     "the header declares " + std::to_string(n) + " triangles, more than the " +
                         std::to_string(max_triangles) + " left of the scene's limit of " +
                         std::to_string(kSceneMaxTriangles));
  }
}

bool finite(const aiVector3D& v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

const char* to_string(MeshFormat format) {
  switch (format) {
    case MeshFormat::kObj:
      return "obj";
    case MeshFormat::kPly:
      return "ply";
    case MeshFormat::kGltf:
      return "gltf";
    case MeshFormat::kGlb:
      return "glb";
    case MeshFormat::kStl:
      return "stl";
  }
  return "?";
}

MeshFormat mesh_format(const std::string& path) {
  const std::string ext = lower(fs::path(path).extension().string());
  if (ext == ".obj") return MeshFormat::kObj;
  if (ext == ".ply") return MeshFormat::kPly;
  if (ext == ".gltf") return MeshFormat::kGltf;
  if (ext == ".glb") return MeshFormat::kGlb;
  if (ext == ".stl") return MeshFormat::kStl;
  const std::string start = head(path, 4);
  std::string hint;
  if (start.rfind("ply", 0) == 0) hint = "; it starts like a PLY file: name it .ply";
  if (start == "glTF") hint = "; it starts like a binary glTF file: name it .glb";
  throw InputError(path, 0, "file",
                   "unknown mesh format " + quote_input(ext.empty() ? "(no extension)" : ext) +
                       ": glint reads " + kFormats + ", by the file's extension" + hint);
}

Mesh load_assimp_mesh(const std::string& path, MeshFormat format, std::size_t max_triangles,
                      const ObjLimits& limits, double crease_degrees) {
  check_file_bytes(path, limits.max_bytes, "mesh file");
  if (format == MeshFormat::kPly) check_ply_header(path, max_triangles, limits);
  if (format == MeshFormat::kStl) check_stl_header(path, max_triangles);

  Assimp::Importer importer;
  importer.SetIOHandler(new FolderIo(path, limits.max_bytes));  // the importer owns it
  // Points and lines are dropped at import; polygons are split into triangles, and every node's
  // transform is applied (one mesh in the file's coordinates, as an OBJ gives).
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  const aiScene* scene =
      importer.ReadFile(path, aiProcess_Triangulate | aiProcess_SortByPType |
                                  aiProcess_PreTransformVertices | aiProcess_ValidateDataStructure);
  if (scene == nullptr) {
    std::string why = importer.GetErrorString();
    if (why.empty()) why = "unknown error";
    throw InputError(path, 0, "mesh",
                     "Assimp cannot read it as " + std::string(to_string(format)) + ": " + why);
  }

  std::uint64_t triangles = 0, vertices = 0;
  bool all_normals = format != MeshFormat::kStl;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) triangles += mesh.mFaces[f].mNumIndices == 3;
    vertices += mesh.mNumVertices;
    all_normals = all_normals && mesh.HasNormals();
  }
  if (triangles > max_triangles) {
    throw InputError(path, 0, "f",
                     std::to_string(triangles) + " triangles, more than the scene's remaining " +
                         "limit of " + std::to_string(max_triangles));
  }
  if (vertices > limits.max_vertices) {
    throw InputError(path, 0, "vertex",
                     std::to_string(vertices) + " vertices, more than the limit of " +
                         std::to_string(limits.max_vertices) + " per mesh file");
  }
  if (triangles == 0) throw InputError(path, 0, "f", "no triangles (a mesh needs faces)");

  // Vertices and faces numbered through the file's meshes, 1-based in messages.
  std::vector<Vec3> positions, normals;
  std::vector<std::array<std::uint32_t, 3>> faces;
  positions.reserve(vertices);
  faces.reserve(triangles);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh& mesh = *scene->mMeshes[m];
    const auto base = static_cast<std::uint32_t>(positions.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const std::string where = "vertex " + std::to_string(positions.size() + 1);
      const aiVector3D& p = mesh.mVertices[v];
      if (!finite(p)) throw InputError(path, 0, "vertex", where + ": a coordinate is not finite");
      positions.push_back({p.x, p.y, p.z});
      if (!all_normals) continue;
      const aiVector3D& n = mesh.mNormals[v];
      if (!finite(n) || (n.x == 0 && n.y == 0 && n.z == 0))
        throw InputError(path, 0, "normal", where + ": its normal is zero or not finite");
      normals.push_back(normalize(Vec3{n.x, n.y, n.z}));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;
      std::array<std::uint32_t, 3> tri{};
      for (unsigned k = 0; k < 3; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          throw InputError(
              path, 0, "f",
              "face " + std::to_string(faces.size() + 1) + ": vertex index out of range");
        }
        tri[k] = base + face.mIndices[k];
      }
      faces.push_back(tri);
    }
  }

  Mesh out;
  if (all_normals) {
    out.positions = std::move(positions);
    out.normals = std::move(normals);
    out.faces = std::move(faces);
    out.normal_source = NormalSource::kFile;
  } else {
    out = smooth_normals(positions, faces, crease_degrees, path);
  }
  out.format = to_string(format);
  return out;
}

}  // namespace glint
