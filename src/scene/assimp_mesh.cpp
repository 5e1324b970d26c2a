#include "scene/assimp_mesh.h"

#include <assimp/BaseImporter.h>
#include <assimp/DefaultIOSystem.h>
#include <assimp/MemoryIOWrapper.h>
#include <assimp/importerdesc.h>
#include <assimp/scene.h>

#include <algorithm>
#include <assimp/Importer.hpp>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <vector>

#include "io/input_error.h"
#include "io/json_text.h"
#include "scene/gltf_check.h"
#include "scene/obj_mesh.h"
#include "scene/ply_mesh.h"
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
  // `replacement`, when not empty, is served for `path` itself (a reduced glTF, gltf_check.h).
  FolderIo(const std::string& path, std::uint64_t max_bytes, std::string replacement = "")
      : main_(fs::absolute(path).lexically_normal()),
        folder_(main_.parent_path()),
        max_bytes_(max_bytes),
        replacement_(std::move(replacement)) {}

  bool Exists(const char* file) const override {
    return allowed(file) && DefaultIOSystem::Exists(file);
  }
  Assimp::IOStream* Open(const char* file, const char* mode) override {
    if (!allowed(file) || std::strchr(mode, 'w') != nullptr) return nullptr;
    std::error_code ec;
    if (!replacement_.empty() && fs::absolute(file, ec).lexically_normal() == main_) {
      return new Assimp::MemoryIOStream(reinterpret_cast<const std::uint8_t*>(replacement_.data()),
                                        replacement_.size(), false);
    }
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

  fs::path main_, folder_;
  std::uint64_t max_bytes_;
  std::string replacement_;
};

std::uint32_t le32(const std::string& b, std::size_t at) {
  std::uint32_t v = 0;
  for (int i = 3; i >= 0; --i) v = v << 8 | static_cast<unsigned char>(b[at + i]);
  return v;
}

// The glTF Assimp is given: the document reduced by reduce_gltf (gltf_check.h), and for a .glb
// its header and chunk lengths checked against the file's size first (a JSON chunk claiming
// 4 GiB in a file of 1 KiB made Assimp allocate 4 GiB: fuzz_mesh), its BIN chunk kept as it is.
std::string reduced_gltf(const std::string& path, MeshFormat format, std::uint64_t max_bytes) {
  const std::string folder = fs::absolute(path).lexically_normal().parent_path().string();
  // A .gltf is JSON alone, held to a scene file's 64 MiB; a .glb holds its buffer too.
  const std::string bytes =
      read_text_file(path, format == MeshFormat::kGltf ? kSceneMaxFileBytes : max_bytes,
                     format == MeshFormat::kGltf ? "glTF file" : "binary glTF file");
  if (format == MeshFormat::kGltf) return reduce_gltf(bytes, -1, folder, path);
  const std::uint64_t size = bytes.size();
  const auto fail = [&](const std::string& what) {
    throw InputError(path, 0, "header", "not a binary glTF 2.0 file: " + what);
  };
  if (size < 20 || bytes.compare(0, 4, "glTF") != 0) fail("it does not start with glTF");
  if (le32(bytes, 4) != 2) fail("version " + std::to_string(le32(bytes, 4)) + ", not 2");
  if (le32(bytes, 8) != size)
    fail("its header says " + std::to_string(le32(bytes, 8)) + " bytes, the file has " +
         std::to_string(size));
  if (bytes.compare(16, 4, "JSON") != 0) fail("its first chunk is not JSON");
  const std::uint64_t json_bytes = le32(bytes, 12);
  if (json_bytes + 20 > size)
    fail("its JSON chunk of " + std::to_string(json_bytes) + " bytes runs past the file's end");
  std::int64_t bin_bytes = -1;
  std::string bin;
  const std::uint64_t at = 20 + json_bytes;
  if (at + 8 <= size && bytes.compare(at + 4, 4, std::string("BIN\0", 4)) == 0) {
    const std::uint64_t n = le32(bytes, at);
    if (at + 8 + n > size)
      fail("its BIN chunk of " + std::to_string(n) + " bytes runs past the end");
    bin_bytes = static_cast<std::int64_t>(n);
    bin = bytes.substr(at, 8 + n);
  }
  std::string json = reduce_gltf(bytes.substr(20, json_bytes), bin_bytes, folder, path);
  while (json.size() % 4 != 0) json += ' ';
  std::string out = "glTF";
  const auto put = [&](std::uint64_t v) {
    for (int i = 0; i < 4; ++i) out += static_cast<char>(v >> (8 * i) & 0xff);
  };
  put(2);
  put(12 + 8 + json.size() + bin.size());
  put(json.size());
  out += "JSON" + json + bin;
  return out;
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

// A node's accumulated transform in double: points by the matrix, normals by its inverse
// transpose (the cofactor matrix, up to a factor that normalising removes, and the sign of the
// determinant, kept so that a mirroring node keeps normals outwards).
struct Affine {
  double m[3][4] = {{1, 0, 0, 0}, {0, 1, 0, 0}, {0, 0, 1, 0}};

  static Affine of(const aiMatrix4x4& a) {
    Affine t;
    const ai_real* r[3] = {a[0], a[1], a[2]};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) t.m[i][j] = r[i][j];
    return t;
  }
  Affine then(const Affine& child) const {  // this * child
    Affine t;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 4; ++j) {
        double v = j == 3 ? m[i][3] : 0;
        for (int k = 0; k < 3; ++k) v += m[i][k] * child.m[k][j];
        t.m[i][j] = v;
      }
    return t;
  }
  Vec3 point(Vec3 p) const {
    return {m[0][0] * p.x + m[0][1] * p.y + m[0][2] * p.z + m[0][3],
            m[1][0] * p.x + m[1][1] * p.y + m[1][2] * p.z + m[1][3],
            m[2][0] * p.x + m[2][1] * p.y + m[2][2] * p.z + m[2][3]};
  }
  Vec3 normal(Vec3 n) const {
    const Vec3 c0{m[1][1] * m[2][2] - m[1][2] * m[2][1], m[1][2] * m[2][0] - m[1][0] * m[2][2],
                  m[1][0] * m[2][1] - m[1][1] * m[2][0]};
    const Vec3 c1{m[0][2] * m[2][1] - m[0][1] * m[2][2], m[0][0] * m[2][2] - m[0][2] * m[2][0],
                  m[0][1] * m[2][0] - m[0][0] * m[2][1]};
    const Vec3 c2{m[0][1] * m[1][2] - m[0][2] * m[1][1], m[0][2] * m[1][0] - m[0][0] * m[1][2],
                  m[0][0] * m[1][1] - m[0][1] * m[1][0]};
    const double det = m[0][0] * c0.x + m[0][1] * c0.y + m[0][2] * c0.z;
    const Vec3 out = c0 * n.x + c1 * n.y + c2 * n.z;
    return det < 0 ? -out : out;
  }
};

struct Instance {
  unsigned mesh;
  Affine transform;
};

constexpr int kMaxNodeDepth = 64;
constexpr std::size_t kMaxInstances = 65536;

// Appends the meshes of `node` and its children, depth first, each with its accumulated
// transform; counts their triangles and vertices against the limits as it goes.
void collect(const aiScene& scene, const aiNode& node, const Affine& parent, int depth,
             std::vector<Instance>& out, const std::vector<std::uint64_t>& mesh_triangles,
             std::uint64_t& triangles, std::uint64_t& vertices, std::size_t max_triangles,
             const ObjLimits& limits, const std::string& path) {
  if (depth > kMaxNodeDepth)
    throw InputError(path, 0, "mesh", "nodes nested deeper than " + std::to_string(kMaxNodeDepth));
  const Affine here = parent.then(Affine::of(node.mTransformation));
  for (unsigned i = 0; i < node.mNumMeshes; ++i) {
    const unsigned m = node.mMeshes[i];
    if (m >= scene.mNumMeshes) throw InputError(path, 0, "mesh", "a node names no mesh");
    if (out.size() == kMaxInstances)
      throw InputError(path, 0, "mesh",
                       "more than " + std::to_string(kMaxInstances) + " mesh instances");
    triangles += mesh_triangles[m];
    vertices += scene.mMeshes[m]->mNumVertices;
    if (triangles > max_triangles) {
      throw InputError(path, 0, "f",
                       std::to_string(triangles) + " triangles, more than the scene's remaining " +
                           "limit of " + std::to_string(max_triangles));
    }
    if (vertices > limits.max_vertices) {
      throw InputError(path, 0, "vertex",
                       "more than " + std::to_string(limits.max_vertices) +
                           " vertices (the limit per mesh file)");
    }
    out.push_back({m, here});
  }
  for (unsigned c = 0; c < node.mNumChildren; ++c) {
    if (node.mChildren[c] == nullptr) continue;
    collect(scene, *node.mChildren[c], here, depth + 1, out, mesh_triangles, triangles, vertices,
            max_triangles, limits, path);
  }
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

Mesh load_mesh_file(const std::string& path, MeshFormat format, std::size_t max_triangles,
                    const ObjLimits& limits, double crease_degrees) {
  if (format == MeshFormat::kObj) return load_obj_mesh(path, max_triangles, limits, crease_degrees);
  if (format == MeshFormat::kPly) return load_ply_mesh(path, max_triangles, limits, crease_degrees);
  check_file_bytes(path, limits.max_bytes, "mesh file");
  if (format == MeshFormat::kStl) check_stl_header(path, max_triangles);
  std::string replacement;
  if (format == MeshFormat::kGltf || format == MeshFormat::kGlb)
    replacement = reduced_gltf(path, format, limits.max_bytes);

  // Only the importer of the file's format reads it: Importer::ReadFile falls back to every
  // other importer whose signature matches when the extension's one declines (a .gltf holding PLY
  // text went to the PLY reader, past glint's PLY header check, and hung). No post-processing
  // step either: Debian's Assimp keeps its assertions, and its triangulation aborts the process
  // on faces a hostile PLY makes. glint splits polygons, applies node transforms and checks
  // indices itself, below. (Both found by fuzz_mesh in its first minute.)
  Assimp::Importer importer;
  Assimp::BaseImporter* reader = nullptr;
  const char* wanted =
      format == MeshFormat::kStl ? "Stereolithography (STL) Importer" : "glTF2 Importer";
  for (std::size_t i = 0; i < importer.GetImporterCount(); ++i) {
    const aiImporterDesc* d = importer.GetImporterInfo(i);
    if (d != nullptr && std::strcmp(d->mName, wanted) == 0) reader = importer.GetImporter(i);
  }
  if (reader == nullptr)
    throw InputError(path, 0, "mesh", std::string("this Assimp has no ") + wanted);
  FolderIo io(path, limits.max_bytes, std::move(replacement));
  const std::unique_ptr<aiScene> owned(reader->ReadFile(&importer, path, &io));
  const aiScene* scene = owned.get();
  if (scene == nullptr || scene->mRootNode == nullptr) {
    std::string why = reader->GetErrorText();
    if (why.empty()) why = "no scene";
    throw InputError(path, 0, "mesh",
                     "Assimp cannot read it as " + std::string(to_string(format)) + ": " + why);
  }

  // Every mesh every node reaches, with the node's transform (a glTF's node tree; PLY and STL
  // have one node). Triangles counted per instance, before anything is allocated for them.
  std::vector<std::uint64_t> mesh_triangles(scene->mNumMeshes, 0);
  for (unsigned m = 0; m < scene->mNumMeshes; ++m) {
    const aiMesh* mesh = scene->mMeshes[m];
    if (mesh == nullptr || (mesh->mNumVertices > 0 && mesh->mVertices == nullptr) ||
        (mesh->mNumFaces > 0 && mesh->mFaces == nullptr))
      throw InputError(path, 0, "mesh", "mesh " + std::to_string(m + 1) + " is incomplete");
    for (unsigned f = 0; f < mesh->mNumFaces; ++f) {
      const unsigned n = mesh->mFaces[f].mNumIndices;
      if (n >= 3) mesh_triangles[m] += n - 2;
    }
  }
  std::vector<Instance> instances;
  std::uint64_t triangles = 0, vertices = 0;
  collect(*scene, *scene->mRootNode, Affine(), 0, instances, mesh_triangles, triangles, vertices,
          max_triangles, limits, path);
  if (triangles == 0) throw InputError(path, 0, "f", "no triangles (a mesh needs faces)");
  bool all_normals = format != MeshFormat::kStl;
  for (const Instance& i : instances)
    all_normals = all_normals && scene->mMeshes[i.mesh]->HasNormals();

  // Vertices numbered through each of the file's meshes, 1-based in messages.
  std::vector<Vec3> positions, normals;
  std::vector<std::array<std::uint32_t, 3>> faces;
  positions.reserve(vertices);
  faces.reserve(triangles);
  for (const Instance& instance : instances) {
    const aiMesh& mesh = *scene->mMeshes[instance.mesh];
    const std::string which =
        scene->mNumMeshes == 1 ? "" : "mesh " + std::to_string(instance.mesh + 1) + ", ";
    const Affine& t = instance.transform;
    const auto base = static_cast<std::uint32_t>(positions.size());
    for (unsigned v = 0; v < mesh.mNumVertices; ++v) {
      const std::string where = which + "vertex " + std::to_string(v + 1);
      const aiVector3D& p = mesh.mVertices[v];
      if (!finite(p)) throw InputError(path, 0, "vertex", where + ": a coordinate is not finite");
      const Vec3 q = t.point({p.x, p.y, p.z});
      if (!(std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z)))
        throw InputError(path, 0, "vertex", where + ": not finite after its node's transform");
      positions.push_back(q);
      if (!all_normals) continue;
      const aiVector3D& n = mesh.mNormals[v];
      const Vec3 m = t.normal({n.x, n.y, n.z});
      if (!finite(n) || !(std::isfinite(m.x) && std::isfinite(m.y) && std::isfinite(m.z)) ||
          length(m) == 0)
        throw InputError(path, 0, "normal", where + ": its normal is zero or not finite");
      normals.push_back(normalize(m));
    }
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices < 3) continue;  // points and lines
      if (face.mIndices == nullptr)
        throw InputError(path, 0, "f", which + "face " + std::to_string(f + 1) + ": no indices");
      for (unsigned k = 0; k < face.mNumIndices; ++k) {
        if (face.mIndices[k] >= mesh.mNumVertices) {
          throw InputError(path, 0, "f",
                           which + "face " + std::to_string(f + 1) +
                               ": vertex index out of range (the mesh has " +
                               std::to_string(mesh.mNumVertices) + " vertices)");
        }
      }
      // Polygons as fans from their first corner, as OBJ's are.
      for (unsigned k = 2; k < face.mNumIndices; ++k)
        faces.push_back(
            {base + face.mIndices[0], base + face.mIndices[k - 1], base + face.mIndices[k]});
    }
  }

  Mesh out = mesh_with_normals(std::move(positions), std::move(normals), std::move(faces),
                               all_normals, crease_degrees, path);
  out.format = to_string(format);
  return out;
}

}  // namespace glint
