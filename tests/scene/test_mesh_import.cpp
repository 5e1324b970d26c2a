// Mesh files in every format glint reads (OBJ through tinyobjloader; PLY, glTF 2.0 and STL through
// Assimp) and the normals glint generates for a mesh without them (scene/smooth_normals.h):
// the same triangles from every format, angle weighting and the crease angle, and the errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <tuple>

#include "io/input_error.h"
#include "mesh_files.h"
#include "scene/assimp_mesh.h"
#include "scene/obj_mesh.h"
#include "scene/scene.h"
#include "scene/smooth_normals.h"
#include "test_support.h"

namespace glint {
namespace {

using glint::test::MeshData;
using glint::test::TempDir;
using nlohmann::json;

constexpr double kPi = 3.14159265358979323846;

// A unit cube, 8 shared corners, 12 triangles wound outwards.
MeshData cube() {
  MeshData m;
  for (int i = 0; i < 8; ++i)
    m.positions.push_back({static_cast<float>(i & 1), static_cast<float>(i >> 1 & 1),
                           static_cast<float>(i >> 2 & 1)});
  m.faces = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
             {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
  return m;
}

std::string write(const TempDir& dir, const std::string& name, const std::string& bytes) {
  const std::string path = dir.file(name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path;
}

Mesh load(const std::string& path, double crease = kSceneDefaultCreaseDegrees) {
  return load_mesh_file(path, mesh_format(path), 1000, ObjLimits{}, crease);
}

std::optional<InputError> error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

void expect_error(const std::function<void()>& f, const std::string& file, const std::string& field,
                  const std::string& needle) {
  const auto e = error_of(f);
  ASSERT_TRUE(e.has_value()) << "no error, expected " << needle;
  EXPECT_EQ(e->file(), file) << e->what();
  EXPECT_EQ(e->field(), field) << e->what();
  EXPECT_NE(e->message().find(needle), std::string::npos) << e->what();
}

// A mesh's triangles as (corner position, corner normal) triples, each rotated to start at its
// smallest corner (winding kept), sorted: equal for the same surface whatever the vertex order.
using Corner = std::array<double, 6>;
std::vector<std::array<Corner, 3>> triangles(const Mesh& m) {
  std::vector<std::array<Corner, 3>> out;
  for (const auto& f : m.faces) {
    std::array<Corner, 3> t;
    for (int k = 0; k < 3; ++k) {
      const Vec3 p = m.positions[f[k]], n = m.normals[f[k]];
      t[k] = {p.x, p.y, p.z, n.x, n.y, n.z};
    }
    const auto first = std::min_element(t.begin(), t.end()) - t.begin();
    std::rotate(t.begin(), t.begin() + first, t.end());
    out.push_back(t);
  }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(MeshImport, EveryFormatGivesTheSameTriangles) {
  TempDir dir;
  const MeshData m = cube();
  const Mesh want = load(write(dir, "cube.obj", test::to_obj(m)));
  EXPECT_EQ(want.format, "obj");
  EXPECT_EQ(want.normal_source, NormalSource::kGenerated);
  ASSERT_EQ(want.faces.size(), 12u);
  const std::vector<std::pair<std::string, std::string>> files = {
      {"cube_ascii.ply", test::to_ply_ascii(m)}, {"cube_binary.ply", test::to_ply_binary(m)},
      {"cube_ascii.stl", test::to_stl_ascii(m)}, {"cube_binary.stl", test::to_stl_binary(m)},
      {"cube.gltf", test::to_gltf_embedded(m)},  {"cube.glb", test::to_glb(m)},
      {"CUBE.PLY", test::to_ply_ascii(m)}};
  for (const auto& [name, bytes] : files) {
    SCOPED_TRACE(name);
    const Mesh got = load(write(dir, name, bytes));
    EXPECT_EQ(got.normal_source, NormalSource::kGenerated);
    EXPECT_EQ(got.crease_degrees, kSceneDefaultCreaseDegrees);
    EXPECT_EQ(triangles(got), triangles(want));
  }
  // A glTF whose buffer is a file beside it.
  write(dir, "cube.bin", test::gltf_buffer(m));
  const Mesh external = load(write(dir, "external.gltf", test::gltf_json(m, "cube.bin")));
  EXPECT_EQ(external.format, "gltf");
  EXPECT_EQ(triangles(external), triangles(want));
}

TEST(MeshImport, NormalsFromTheFileAreKept) {
  TempDir dir;
  MeshData m = cube();
  // Deliberately not the generated ones: every normal points along +y, scaled.
  m.normals.assign(m.positions.size(), {0, 2, 0});
  for (const auto& [name, bytes] :
       std::vector<std::pair<std::string, std::string>>{{"n.obj", test::to_obj(m)},
                                                        {"n.ply", test::to_ply_ascii(m)},
                                                        {"n.gltf", test::to_gltf_embedded(m)},
                                                        {"n.glb", test::to_glb(m)}}) {
    SCOPED_TRACE(name);
    const Mesh got = load(write(dir, name, bytes));
    EXPECT_EQ(got.normal_source, NormalSource::kFile);
    EXPECT_EQ(got.faces.size(), 12u);
    for (const Vec3& n : got.normals) {
      EXPECT_EQ(n.x, 0);
      EXPECT_EQ(n.y, 1);
      EXPECT_EQ(n.z, 0);
    }
  }
  // STL's facet normals are per face, not per vertex: glint generates smooth ones.
  EXPECT_EQ(load(write(dir, "n.stl", test::to_stl_binary(m))).normal_source,
            NormalSource::kGenerated);
}

// ---- Normals generation --------------------------------------------------------------------

Mesh generate(const MeshData& m, double crease) {
  std::vector<Vec3> p;
  for (const auto& q : m.positions) p.push_back({q[0], q[1], q[2]});
  return smooth_normals(p, m.faces, crease, "test");
}

TEST(SmoothNormals, FlatQuadSharesItsFourCorners) {
  MeshData quad;
  quad.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  quad.faces = {{0, 1, 2}, {0, 2, 3}};
  for (const double crease : {0.0, 30.0, 180.0}) {
    const Mesh m = generate(quad, crease);
    EXPECT_EQ(m.positions.size(), 4u) << crease;
    for (const Vec3& n : m.normals) {
      EXPECT_EQ(n.x, 0);
      EXPECT_EQ(n.y, 0);
      EXPECT_EQ(n.z, 1);
    }
  }
}

TEST(SmoothNormals, CubeIsSharpBelowItsEdgeAngleAndSmoothAbove) {
  // Sharp: 90-degree edges exceed a 30-degree crease: each corner splits into its 3 faces' normals.
  const Mesh sharp = generate(cube(), 30);
  EXPECT_EQ(sharp.positions.size(), 24u);
  for (std::size_t f = 0; f < sharp.faces.size(); ++f) {
    const auto& t = sharp.faces[f];
    const Vec3 face = normalize(cross(sharp.positions[t[1]] - sharp.positions[t[0]],
                                      sharp.positions[t[2]] - sharp.positions[t[0]]));
    for (const std::uint32_t v : t) {
      EXPECT_NEAR(dot(sharp.normals[v], face), 1, 1e-15) << f;
    }
  }
  // Smooth at 100 degrees: one vertex per corner, the diagonal direction out of the cube (each
  // face contributes its 90-degree corner, whether as one triangle or two of 45).
  const Mesh smooth = generate(cube(), 100);
  ASSERT_EQ(smooth.positions.size(), 8u);
  for (std::size_t v = 0; v < 8; ++v) {
    const Vec3 p = smooth.positions[v], n = smooth.normals[v];
    const Vec3 out = normalize(Vec3{p.x - 0.5, p.y - 0.5, p.z - 0.5});
    EXPECT_NEAR(n.x, out.x, 1e-15);
    EXPECT_NEAR(n.y, out.y, 1e-15);
    EXPECT_NEAR(n.z, out.z, 1e-15);
  }
}

TEST(SmoothNormals, FanIsAngleWeightedNotAreaWeighted) {
  // Two faces at the origin: F1 in z = 0 (normal +z, 90 degrees there, area 1/2) and F2 in x = 0
  // (normal +x, 45 degrees there, area 2). Angle weights give (pi/4, 0, pi/2) ~ (1, 0, 2); area
  // weights would give (4, 0, 1), equal weights (1, 0, 1).
  MeshData fan;
  fan.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 2, 0}, {0, 2, 2}};
  fan.faces = {{0, 1, 2}, {0, 3, 4}};
  const Mesh m = generate(fan, 180);
  const Vec3 want = normalize(Vec3{1, 0, 2});
  ASSERT_EQ(m.positions[0].x, 0);
  ASSERT_EQ(m.positions[0].y, 0);
  ASSERT_EQ(m.positions[0].z, 0);
  EXPECT_NEAR(m.normals[0].x, want.x, 1e-15);
  EXPECT_NEAR(m.normals[0].y, 0, 1e-15);
  EXPECT_NEAR(m.normals[0].z, want.z, 1e-15);
  // Below their 90-degree fold the two faces keep apart: the origin is two vertices.
  const Mesh apart = generate(fan, 60);
  EXPECT_EQ(apart.positions.size(), m.positions.size() + 1);
  // The weights are the corner angles: a face's angle at the origin doubled (F2 made 90 degrees
  // wide, as wide as F1) makes the normal the bisector (1, 0, 1).
  fan.positions[4] = {0, 0, 2};
  const Mesh even = generate(fan, 180);
  EXPECT_NEAR(even.normals[0].x, std::sqrt(0.5), 1e-15);
  EXPECT_NEAR(even.normals[0].z, std::sqrt(0.5), 1e-15);
}

TEST(SmoothNormals, ZeroAreaFacesAreDroppedAndAllOfThemAnError) {
  MeshData m;
  m.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {2, 0, 0}};
  m.faces = {{0, 1, 2}, {0, 1, 3}};  // the second is a line
  EXPECT_EQ(generate(m, 60).faces.size(), 1u);
  m.faces = {{0, 1, 3}};
  const auto e = error_of([&] { generate(m, 60); });
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->field(), "f");
  EXPECT_NE(e->message().find("no face has an area"), std::string::npos);
}

TEST(SmoothNormals, TooManyOrientationsAtOneVertexIsAnError) {
  // A cone of 1100 sides: its apex is shared by 1100 faces of different normals.
  MeshData m;
  m.positions.push_back({0, 0, 1});
  const int n = static_cast<int>(kMaxNormalsPerPosition) + 76;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * kPi * i / n;
    m.positions.push_back({static_cast<float>(std::cos(a)), static_cast<float>(std::sin(a)), 0});
  }
  for (int i = 0; i < n; ++i)
    m.faces.push_back(
        {0, static_cast<std::uint32_t>(1 + i), static_cast<std::uint32_t>(1 + (i + 1) % n)});
  const auto e = error_of([&] { generate(m, 60); });
  ASSERT_TRUE(e.has_value());
  EXPECT_NE(e->message().find("vertex 1 is shared by faces of more than 1024"), std::string::npos)
      << e->what();
}

// ---- Errors ----------------------------------------------------------------------------------

TEST(MeshImport, UnknownFormatsAreRefusedNamingTheFormats) {
  TempDir dir;
  const std::string off = write(dir, "m.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expect_error([&] { mesh_format(off); }, off, "file", "glint reads OBJ (.obj), PLY (.ply)");
  const std::string ply = write(dir, "m.dat", test::to_ply_ascii(cube()));
  expect_error([&] { mesh_format(ply); }, ply, "file", "starts like a PLY file: name it .ply");
  const std::string glb = write(dir, "m", test::to_glb(cube()));
  expect_error([&] { mesh_format(glb); }, glb, "file", "'(no extension)'");
  expect_error([&] { mesh_format(glb); }, glb, "file", "name it .glb");
}

TEST(MeshImport, NonFiniteCoordinatesAreRefusedInEveryTextFormat) {
  TempDir dir;
  MeshData m = cube();
  const std::string ply = test::to_ply_ascii(m);
  for (const char* bad : {"nan", "inf", "-inf", "1e999"}) {
    SCOPED_TRACE(bad);
    std::string text = ply;
    // The third vertex's y.
    const auto body = text.find("end_header\n") + 11;
    std::size_t line = body;
    for (int i = 0; i < 2; ++i) line = text.find('\n', line) + 1;
    const auto space = text.find(' ', line);
    text.replace(space + 1, text.find(' ', space + 1) - space - 1, bad);
    const std::string path = write(dir, "bad.ply", text);
    expect_error([&] { load(path); }, path, "vertex", "vertex 3: a coordinate is not finite");
    std::string stl = test::to_stl_ascii(m);
    const auto v = stl.find("vertex ") + 7;
    stl.replace(v, stl.find(' ', v) - v, bad);
    const std::string stl_path = write(dir, "bad.stl", stl);
    expect_error([&] { load(stl_path); }, stl_path, "vertex",
                 "vertex 1: a coordinate is not finite");
  }
}

TEST(MeshImport, LimitsAreCheckedBeforeAssimpReads) {
  TempDir dir;
  const MeshData m = cube();
  const std::string ply = write(dir, "m.ply", test::to_ply_binary(m));
  EXPECT_EQ(load_mesh_file(ply, MeshFormat::kPly, 12).faces.size(), 12u);
  expect_error([&] { load_mesh_file(ply, MeshFormat::kPly, 11); }, ply, "header",
               "more than 11 faces");
  expect_error(
      [&] {
        load_mesh_file(ply, MeshFormat::kPly, 100, ObjLimits{1000000, 7});
      },
      ply, "header", "more than 7 vertices");
  EXPECT_EQ(error_of([&] { load_mesh_file(ply, MeshFormat::kPly, 11); })->line(), 7u);
  const std::string stl = write(dir, "m.stl", test::to_stl_binary(m));
  expect_error([&] { load_mesh_file(stl, MeshFormat::kStl, 11); }, stl, "f",
               "the header declares 12 triangles");
  // A header that claims 2^32 - 1 triangles in a file of a few bytes.
  std::string huge = test::to_stl_binary(m);
  huge.replace(80, 4, "\xff\xff\xff\xff");
  const std::string huge_path = write(dir, "huge.stl", huge);
  expect_error([&] { load(huge_path); }, huge_path, "f", "the header declares 4294967295");
  const std::string glb = write(dir, "m.glb", test::to_glb(m));
  expect_error([&] { load_mesh_file(glb, MeshFormat::kGlb, 11); }, glb, "f",
               "12 triangles, more than");
  const auto size = test::to_glb(m).size();
  expect_error(
      [&] {
        load_mesh_file(glb, MeshFormat::kGlb, 100, ObjLimits{size - 1, 100});
      },
      glb, "file", "more than the limit of");
}

TEST(MeshImport, BrokenFilesGiveErrorsNamingTheFileAndElement) {
  TempDir dir;
  const MeshData m = cube();
  std::string glb = test::to_glb(m);
  const std::string cut = write(dir, "cut.glb", glb.substr(0, glb.size() / 2));
  expect_error([&] { load(cut); }, cut, "header", "its header says");
  std::string huge_json = glb;
  huge_json.replace(12, 4, "\x9c\xff\xff\xff");  // a JSON chunk of 4 GiB
  const std::string claim = write(dir, "claim.glb", huge_json);
  expect_error([&] { load(claim); }, claim, "header", "runs past the file's end");
  std::string v1 = glb;
  v1[4] = 1;
  const std::string old = write(dir, "v1.glb", v1);
  expect_error([&] { load(old); }, old, "header", "version 1, not 2");
  // A glb whose JSON is broken, and glTF documents that name what is not there: glint's checks
  // before Assimp (gltf_check.h), naming the JSON path.
  std::string bad_json = glb;
  bad_json[20] = ']';
  const std::string broken = write(dir, "broken.glb", bad_json);
  expect_error([&] { load(broken); }, broken, "json", "");
  const auto gltf_error = [&](const std::string& from, const std::string& to,
                              const std::string& needle) {
    std::string text = test::to_gltf_embedded(m);
    const auto at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
    const std::string p = write(dir, "bad.gltf", text);
    SCOPED_TRACE(to);
    expect_error([&] { load(p); }, p, "gltf", needle);
  };
  gltf_error("\"POSITION\"", "\"POSPTION\"",
             "meshes[0].primitives[0].attributes.POSITION: missing");
  gltf_error("\"mode\":4", "\"mode\":2", "points and lines are not read");
  gltf_error("\"indices\":1", "\"indices\":7",
             "meshes[0].primitives[0].indices: must be a whole number in 0..1");
  gltf_error("\"count\":8", "\"count\":9", "accessors[0]: its 9 elements run past the end");
  gltf_error("\"nodes\":[{\"mesh\":0}]", "\"nodes\":[{\"mesh\":0,\"children\":[0]}]",
             "nodes[0]: is in a cycle");
  gltf_error("\"version\":\"2.0\"", "\"version\":\"1.0\"", "asset.version");
  // PLY headers are read by glint first (Assimp 5.2 never returns from the first of these).
  const std::string junk = write(dir, "junk.ply", "ply\nformat ascii 1.0\nelement vertex x\n");
  expect_error([&] { load(junk); }, junk, "header", "COUNT a whole number");
  EXPECT_EQ(error_of([&] { load(junk); })->line(), 3u);
  const std::string open = write(dir, "open.ply", "ply\nformat ascii 1.0\nelement vertex 3\n");
  expect_error([&] { load(open); }, open, "header", "no \"end_header\"");
  const std::string odd = write(dir, "odd.ply", "ply\nformat ascii 1.0\nvertices 3\n");
  expect_error([&] { load(odd); }, odd, "header", "unknown header line 'vertices 3'");
  const std::string truncated = write(dir, "short.ply", test::to_ply_binary(m).substr(0, 200));
  expect_error([&] { load(truncated); }, truncated, "vertex", "the file ends inside it");
  // Face indices beyond the vertices.
  MeshData wild = m;
  wild.faces[3] = {0, 1, 99};
  const std::string ply = write(dir, "wild.ply", test::to_ply_ascii(wild));
  const auto e = error_of([&] { load(ply); });
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->file(), ply);
  // A glTF buffer outside the mesh's folder is not opened.
  std::filesystem::create_directories(dir.path() / "sub");
  write(dir, "outside.bin", test::gltf_buffer(m));
  const std::string escape = write(dir, "sub/escape.gltf", test::gltf_json(m, "../outside.bin"));
  expect_error([&] { load(escape); }, escape, "gltf",
               "buffers[0].uri: must name a file in the mesh file's own folder");
  // A zero normal in the file.
  MeshData zero = m;
  zero.normals.assign(m.positions.size(), {0, 0, 1});
  zero.normals[5] = {0, 0, 0};
  const std::string zpath = write(dir, "zero.ply", test::to_ply_ascii(zero));
  expect_error([&] { load(zpath); }, zpath, "normal", "vertex 6: its normal is zero");
  EXPECT_EQ(error_of([&] { load(zpath); })->line(), 18u);  // ASCII PLY errors name the line
}

// ---- In a scene --------------------------------------------------------------------------------

class MeshScene : public ::testing::Test {
 protected:
  std::string scene_with(const std::string& file, const json& extra = json::object()) {
    json object = {{"type", "mesh"}, {"file", file}, {"material", "a"}};
    object.update(extra);
    json s = {
        {"glint_scene", 1},
        {"camera",
         {{"position", {3, 2, 4}},
          {"look_at", {0.5, 0.5, 0.5}},
          {"fov_y", 40},
          {"resolution", {16, 12}}}},
        {"lights", json::array({{{"name", "l"}, {"type", "point"}, {"position", {2, 4, 3}}}})},
        {"materials",
         json::array(
             {{{"name", "a"}, {"specular", {1, 1, 1}}, {"lobe", "phong"}, {"shininess", 20}}})},
        {"objects", json::array({object})}};
    return write(dir_, "scene.json", s.dump());
  }
  TempDir dir_;
};

TEST_F(MeshScene, CreaseAngleIsReadAndChecked) {
  write(dir_, "cube.stl", test::to_stl_binary(cube()));
  const Scene s = load_scene(scene_with("cube.stl", {{"crease_angle", 100}}));
  EXPECT_EQ(s.meshes[0].crease_degrees, 100);
  EXPECT_EQ(s.meshes[0].positions.size(), 8u);
  EXPECT_EQ(s.meshes[0].format, "stl");
  EXPECT_EQ(s.meshes[0].name, "cube");
  EXPECT_EQ(load_scene(scene_with("cube.stl")).meshes[0].positions.size(), 24u);
  for (const json& bad : {json(-1), json(180.5), json("30"), json(nullptr)}) {
    SCOPED_TRACE(bad.dump());
    const std::string path = scene_with("cube.stl", {{"crease_angle", bad}});
    const auto e = error_of([&] { load_scene(path); });
    ASSERT_TRUE(e.has_value());
    EXPECT_EQ(e->field(), "objects[0].crease_angle") << e->what();
  }
  MeshData with_normals = cube();
  with_normals.normals.assign(8, {0, 1, 0});
  write(dir_, "n.ply", test::to_ply_ascii(with_normals));
  const std::string path = scene_with("n.ply", {{"crease_angle", 45}});
  const auto e = error_of([&] { load_scene(path); });
  ASSERT_TRUE(e.has_value());
  EXPECT_EQ(e->field(), "objects[0].crease_angle");
  EXPECT_NE(e->message().find("the mesh file has its own normals"), std::string::npos);
  write(dir_, "m.off", "OFF\n");
  const auto off = error_of([&] { load_scene(scene_with("m.off")); });
  ASSERT_TRUE(off.has_value());
  EXPECT_EQ(off->file(), dir_.file("m.off"));
  EXPECT_EQ(off->field(), "file");
}

}  // namespace
}  // namespace glint
