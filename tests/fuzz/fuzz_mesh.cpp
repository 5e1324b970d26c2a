// Mesh files other than OBJ (scene/assimp_mesh.h): PLY (glint's own reader, scene/ply_mesh.h),
// glTF 2.0 (.gltf, .glb) and STL (Assimp). The input's first byte picks the format (its value
// mod 4: PLY, glTF, glb, STL), the second the crease angle (its value mod 181, in degrees) for
// generated normals; the rest is the file, written as mesh.<ext> in a temporary folder of this
// process ($TMPDIR, else /dev/shm). A loaded mesh must hold glint's invariants: every face's
// indices within its vertices, every position finite, every normal finite and of unit length, at
// most the harness's triangle limit. InputError is a refusal (exit 2); anything else is a finding.
// Work per input is bounded by the limits below (a 1 MiB file of at most 100 000 triangles and
// vertices).

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "fuzz.h"
#include "io/input_error.h"
#include "scene/assimp_mesh.h"

namespace glint::fuzz {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxTriangles = 100000;
constexpr ObjLimits kLimits{std::uint64_t{1} << 20, 100000};

bool finite(Vec3 v) {
  return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z);
}

}  // namespace

int mesh(const std::uint8_t* data, std::size_t size) {
  if (size < 2) return 0;
  static constexpr MeshFormat kFormats[] = {MeshFormat::kPly, MeshFormat::kGltf, MeshFormat::kGlb,
                                            MeshFormat::kStl};
  const MeshFormat format = kFormats[data[0] % 4];
  const double crease = data[1] % 181;
  const fs::path path = temp_folder("mesh") / (std::string("mesh.") + to_string(format));
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data + 2), static_cast<std::streamsize>(size - 2));
    if (!out) fail("cannot write " + path.string());
  }
  Mesh m;
  try {
    m = load_mesh_file(path.string(), format, kMaxTriangles, kLimits, crease);
  } catch (const InputError&) {
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("load_mesh_file threw something other than InputError: ") + e.what());
  }
  if (m.faces.empty() || m.faces.size() > kMaxTriangles) fail("a loaded mesh's triangle count");
  if (m.normals.size() != m.positions.size()) fail("a loaded mesh without a normal per vertex");
  for (const auto& f : m.faces)
    for (const std::uint32_t v : f)
      if (v >= m.positions.size()) fail("a face index beyond the vertices");
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    if (!finite(m.positions[i])) fail("a position that is not finite");
    if (!finite(m.normals[i]) || std::abs(length(m.normals[i]) - 1) > 1e-9)
      fail("a normal that is not of unit length");
  }
  if (m.normal_source == NormalSource::kGenerated && m.crease_degrees != crease)
    fail("generated normals with another crease angle");
  return 0;
}

}  // namespace glint::fuzz

GLINT_FUZZ_TARGET(mesh)
