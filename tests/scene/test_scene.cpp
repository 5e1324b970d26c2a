// Scenes: the shipped scenes, every class of bad scene, OBJ and patch files, the teapot's
// tessellation. The ray caster's own tests are in test_scene_tracer.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "io/input_error.h"
#include "io/vectors.h"
#include "reference/reference.h"
#include "scene/bezier.h"
#include "scene/scene.h"
#include "scene/tracer.h"
#include "test_support.h"

namespace glint {
namespace {

using glint::test::TempDir;
using nlohmann::json;

const std::string kScenes = std::string(GLINT_SOURCE_DIR) + "/traces/scenes";

std::optional<InputError> load_error(const std::string& path) {
  try {
    load_scene(path);
  } catch (const InputError& e) {
    return e;
  }
  return std::nullopt;
}

// ---- Shipped scenes ------------------------------------------------------------------------

TEST(ShippedScenes, TeapotIsKallbergFigure1) {
  const Scene s = load_scene(kScenes + "/teapot.json");
  EXPECT_EQ(s.name, "teapot");
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_EQ(s.camera.height, 480);
  ASSERT_EQ(s.lights.size(), 1u);
  ASSERT_EQ(s.materials.size(), 1u);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].faces.size(), 32u * 16 * 16 * 2);
  // Källberg & Larsson 2014, Fig.1: Phong, i = m = 1 (white), shininess 50, eps = 1e-3.
  const VectorHeader h = scene_vector_header(s);
  EXPECT_NO_THROW(validate(h));
  ASSERT_EQ(h.materials.size(), 1u);
  EXPECT_EQ(h.materials[0].lobe, Lobe::kPhong);
  EXPECT_EQ(h.materials[0].shininess, 50);
  const auto& m = h.materials[0].specular;
  const auto i = h.intensity(0);
  const TauResult tau =
      tau_power(h.materials[0].shininess, h.eps, c_y({i[0], i[1], i[2]}, {m[0], m[1], m[2]}));
  EXPECT_EQ(h.eps, 1e-3);
  EXPECT_NEAR(tau.tau, 0.8710, 1e-4);  // "tau ~ 0.87"
}

TEST(ShippedScenes, MultiHasColouredLightsAndEveryLobe) {
  const Scene s = load_scene(kScenes + "/multi.json");
  ASSERT_EQ(s.lights.size(), 3u);
  bool coloured = false, directional = false;
  for (const SceneLight& l : s.lights) {
    coloured = coloured || l.intensity.r != l.intensity.g || l.intensity.g != l.intensity.b;
    directional = directional || l.kind == LightKind::kDirectional;
  }
  EXPECT_TRUE(coloured);
  EXPECT_TRUE(directional);
  ASSERT_GE(s.materials.size(), 4u);
  int lobes[3] = {0, 0, 0};
  for (const SceneMaterial& m : s.materials) ++lobes[static_cast<int>(m.lobe)];
  EXPECT_GT(lobes[0], 0);
  EXPECT_GT(lobes[1], 0);
  EXPECT_GT(lobes[2], 0);
  EXPECT_EQ(s.meshes.size(), 2u);  // the teapot and the OBJ torus
  EXPECT_EQ(s.meshes[1].name, "torus");
  EXPECT_EQ(s.meshes[1].faces.size(), 48u * 24 * 2);
  EXPECT_FALSE(s.spheres.empty());
  EXPECT_EQ(s.planes.size(), 1u);
  EXPECT_NO_THROW(validate(scene_vector_header(s)));
}

TEST(ShippedScenes, SmallIsTiny) {
  const Scene s = load_scene(kScenes + "/small.json");
  EXPECT_EQ(s.camera.width, 64);
  EXPECT_EQ(s.camera.height, 48);
  EXPECT_EQ(s.lights.size(), 2u);
  EXPECT_EQ(s.materials.size(), 3u);
  EXPECT_EQ(s.spheres.size(), 2u);
  EXPECT_EQ(s.planes.size(), 1u);
  const VectorHeader h = scene_vector_header(s);
  EXPECT_TRUE(h.has_light);
  EXPECT_TRUE(h.has_xy);
  EXPECT_EQ(h.lights, 2);
  EXPECT_EQ(h.light_intensity[1], (std::array<double, 3>{1, 0.8, 0.6}));
}

// Every material is seen, and every glossy material shows a highlight above its threshold.
TEST(ShippedScenes, EveryMaterialIsSeenWithAHighlight) {
  for (const char* name : {"teapot", "multi", "small"}) {
    SCOPED_TRACE(name);
    const Scene s = load_scene(kScenes + "/" + name + ".json");
    const SceneTracer tracer(s);
    std::vector<SurfaceSample> px(static_cast<std::size_t>(s.camera.width) * s.camera.height);
    tracer.trace_rows(0, s.camera.height, px.data());
    std::vector<int> seen(s.materials.size()), bright(s.materials.size());
    for (const SurfaceSample& p : px) {
      if (!p.hit) continue;
      const SceneMaterial& m = s.materials[p.material];
      ++seen[p.material];
      for (std::size_t l = 0; l < s.lights.size(); ++l) {
        const LightSample ls = light_sample(s, p, l);
        const double t = m.lobe == Lobe::kPhong ? ls.t_phong : ls.t_blinn;
        const double c = c_y(s.lights[l].intensity, m.specular);
        const TauResult tau = m.lobe == Lobe::kGaussian ? tau_gaussian(m.roughness, s.eps, c)
                                                        : tau_power(m.shininess, s.eps, c);
        if (ls.n_dot_l > 0 && !tau.skip(t)) ++bright[p.material];
      }
    }
    for (std::size_t m = 0; m < s.materials.size(); ++m) {
      EXPECT_GT(seen[m], 0) << s.materials[m].name;
      EXPECT_GT(bright[m], 0) << s.materials[m].name;
    }
  }
}

// ---- Bad scenes ------------------------------------------------------------------------------

// A valid scene to break one field at a time.
json base_scene() {
  return R"({
    "glint_scene": 1,
    "camera": {"position": [0, 1, 5], "look_at": [0, 0, 0], "fov_y": 40, "resolution": [32, 24]},
    "lights": [
      {"name": "key", "type": "point", "position": [2, 4, 3]},
      {"name": "sun", "type": "directional", "direction": [0, -1, 0], "intensity": [1, 0.5, 0.2]}
    ],
    "materials": [
      {"name": "a", "specular": [1, 1, 1], "lobe": "phong", "shininess": 20},
      {"name": "b", "specular": [1, 1, 1], "lobe": "blinn", "shininess": 40},
      {"name": "c", "specular": [0.5, 0.5, 0.5], "lobe": "gaussian", "roughness": 0.3}
    ],
    "objects": [
      {"type": "plane", "point": [0, 0, 0], "normal": [0, 1, 0], "material": "c"},
      {"type": "sphere", "center": [0, 1, 0], "radius": 1, "material": "a"}
    ]
  })"_json;
}

class BadScene : public ::testing::Test {
 protected:
  std::string write(const std::string& name, const std::string& text) const {
    const std::string path = dir_.file(name);
    std::ofstream(path, std::ios::binary) << text;
    return path;
  }
  std::string write(const json& scene) const { return write("scene.json", scene.dump(2)); }

  // Loading `path` fails with InputError naming `file` (default: path) and `field`, and the
  // message contains `needle`.
  void expect_error(const std::string& path, const std::string& field, const std::string& needle,
                    std::string file = "") const {
    const auto e = load_error(path);
    ASSERT_TRUE(e.has_value()) << "no error for " << path;
    EXPECT_EQ(e->file(), file.empty() ? path : file) << e->what();
    EXPECT_EQ(e->field(), field) << e->what();
    EXPECT_NE(e->message().find(needle), std::string::npos) << e->what();
  }
  void expect_error(const json& scene, const std::string& field, const std::string& needle) const {
    SCOPED_TRACE(scene.dump());
    expect_error(write(scene), field, needle);
  }

  TempDir dir_;
};

TEST_F(BadScene, BaseSceneLoads) {
  const Scene s = load_scene(write(base_scene()));
  EXPECT_EQ(s.name, "scene");
  EXPECT_EQ(s.eps, 1e-3);
  EXPECT_EQ(s.lights[1].direction.y, -1);
}

TEST_F(BadScene, MissingFile) {
  expect_error(dir_.file("nope.json"), "file", "cannot open");
}

TEST_F(BadScene, NotJsonOrTruncated) {
  expect_error(write("a.json", "hello"), "json", "not valid JSON");
  const std::string text = base_scene().dump(2);
  const std::string cut = write("b.json", text.substr(0, text.size() / 2));
  expect_error(cut, "json", "not valid JSON");
  EXPECT_GT(load_error(cut)->line(), 1u);  // the line where the text stops
  expect_error(write("c.json", "{\"glint_scene\": 1,\n\"eps\": NaN}"), "json", "not valid JSON");
  EXPECT_EQ(load_error(dir_.file("c.json"))->line(), 2u);
  expect_error(write("d.json", "{\"glint_scene\": 1, \"eps\": 1e999}"), "json", "overflow");
  expect_error(write("e.json", "[1, 2]"), "scene", "must be a JSON object");
  expect_error(write("f.json", ""), "json", "not valid JSON");
}

TEST_F(BadScene, WrongVersion) {
  json s = base_scene();
  s["glint_scene"] = 2;
  expect_error(s, "glint_scene", "unsupported scene format version 2");
  s["glint_scene"] = "1";
  expect_error(s, "glint_scene", "must be an integer");
  s.erase("glint_scene");
  expect_error(s, "glint_scene", "missing");
}

TEST_F(BadScene, UnknownKeysAndDuplicates) {
  json s = base_scene();
  s["ambiant"] = {0, 0, 0};
  expect_error(s, "ambiant", "unknown key");
  s = base_scene();
  s["materials"][1]["shinyness"] = 3;
  expect_error(s, "materials[1].shinyness", "unknown key");
  s = base_scene();
  s["camera"]["fov"] = 3;
  expect_error(s, "camera.fov", "unknown key");
  s = base_scene();
  s["objects"][1]["centre"] = {0, 0, 0};
  expect_error(s, "objects[1].centre", "unknown key");
  // nlohmann keeps the last of two equal keys; glint refuses them.
  std::string text = base_scene().dump();
  text.insert(1, "\"eps\": 0.5, \"eps\": 0.1, ");
  expect_error(write("dup.json", text), "eps", "duplicate key");
  text = base_scene().dump();
  text.insert(text.find("\"lobe\":\"blinn\""), "\"lobe\":\"phong\",");
  expect_error(write("dup2.json", text), "materials[1].lobe", "duplicate key");
}

TEST_F(BadScene, UnknownReferencesAndTypes) {
  json s = base_scene();
  s["objects"][1]["material"] = "nope";
  expect_error(s, "objects[1].material", "unknown material 'nope'");
  s = base_scene();
  s["objects"][0]["type"] = "cube";
  expect_error(s, "objects[0].type", "unknown object type");
  s = base_scene();
  s["lights"][0]["type"] = "spot";
  expect_error(s, "lights[0].type", "unknown light type");
  s = base_scene();
  s["lights"][0]["direction"] = {0, 1, 0};
  expect_error(s, "lights[0].direction", "not allowed for a point light");
  s = base_scene();
  s["lights"][1]["direction"] = {0, 0, 0};
  expect_error(s, "lights[1].direction", "zero vector");
  s = base_scene();
  s["materials"][0]["lobe"] = "cook-torrance";
  expect_error(s, "materials[0].lobe", "\"phong\", \"blinn\" or \"gaussian\"");
  s = base_scene();
  s["materials"][1]["name"] = "a";
  expect_error(s, "materials[1].name", "duplicate name");
  s = base_scene();
  s["materials"][0]["name"] = "1st";
  expect_error(s, "materials[0].name", "invalid name");
  s = base_scene();
  s["lights"][1]["name"] = "key";
  expect_error(s, "lights[1].name", "duplicate name");
  s = base_scene();
  s["objects"][0] = 3;
  expect_error(s, "objects[0]", "must be an object");
}

TEST_F(BadScene, BadNumbers) {
  const auto with = [](const char* pointer, json value) {
    json s = base_scene();
    s[json::json_pointer(pointer)] = std::move(value);
    return s;
  };
  expect_error(with("/objects/1/radius", -1), "objects[1].radius", "must be > 0");
  expect_error(with("/objects/1/radius", 0), "objects[1].radius", "must be > 0");
  expect_error(with("/objects/1/radius", "1"), "objects[1].radius", "must be a number, not string");
  expect_error(with("/objects/1/radius", true), "objects[1].radius", "not boolean");
  expect_error(with("/eps", 0), "eps", "must be > 0");
  expect_error(with("/eps", nullptr), "eps", "must be a number, not null");
  expect_error(with("/camera/resolution", {0, 24}), "camera.resolution[0]", "1..16384");
  expect_error(with("/camera/resolution", {32, 100000}), "camera.resolution[1]", "1..16384");
  expect_error(with("/camera/resolution", {32.5, 24}), "camera.resolution[0]", "integer");
  expect_error(with("/camera/resolution", {32}), "camera.resolution", "at least 2");
  expect_error(with("/camera/resolution", json::parse("[18446744073709551615, 24]")),
               "camera.resolution[0]", "1..16384");
  expect_error(with("/materials/0/shininess", 0), "materials[0].shininess", "must be > 0");
  expect_error(with("/materials/2/roughness", 1.5), "materials[2].roughness", "(0, 1]");
  expect_error(with("/materials/0/roughness", 0.5), "materials[0].roughness", "only a gaussian");
  expect_error(with("/materials/1/specular", {1, -0.5, 1}), "materials[1].specular[1]", ">= 0");
  expect_error(with("/materials/1/specular", {1, 1}), "materials[1].specular", "3 numbers");
  expect_error(with("/lights/0/intensity", {1, 1, -1}), "lights[0].intensity[2]", ">= 0");
  expect_error(with("/objects/0/normal", {0, 0, 0}), "objects[0].normal", "zero vector");
  json s = base_scene();
  s["materials"][0].erase("shininess");
  expect_error(s, "materials[0].shininess", "missing");
  s = base_scene();
  s["materials"][2].erase("roughness");
  expect_error(s, "materials[2].roughness", "missing");
}

TEST_F(BadScene, DegenerateCamera) {
  json s = base_scene();
  s["camera"]["look_at"] = s["camera"]["position"];
  expect_error(s, "camera.look_at", "no view direction");
  s = base_scene();
  s["camera"]["up"] = {0, 2, 10};  // parallel to look_at - position = (0, -1, -5)
  expect_error(s, "camera.up", "parallel");
  s["camera"]["up"] = {0, 0, 0};
  expect_error(s, "camera.up", "zero vector");
  s = base_scene();
  s["camera"]["position"] = {0, 5, 0};  // looking straight down with the default up
  expect_error(s, "camera", "vertical");
  for (const double fov : {0.0, 180.0, -10.0, 200.0}) {
    s = base_scene();
    s["camera"]["fov_y"] = fov;
    expect_error(s, "camera.fov_y", "(0, 180)");
  }
}

TEST_F(BadScene, EmptyScene) {
  for (const char* key : {"objects", "lights", "materials"}) {
    json s = base_scene();
    s[key] = json::array();
    expect_error(s, key, "is empty");
    s.erase(key);
    expect_error(s, key, "missing");
  }
}

TEST_F(BadScene, DeepNesting) {
  // Far deeper than any recursion could take: an error, not a stack overflow.
  const std::size_t deep = 200000;
  expect_error(write("deep.json", std::string(deep, '[') + std::string(deep, ']')), "json",
               "nested deeper than 64");
  // The limit is exact: 64 levels reach the loader (which then rejects the value), 65 do not.
  json s = base_scene();
  const auto nested = [](int levels) {
    return std::string(levels, '[') + std::string(levels, ']');
  };
  std::string text = s.dump();
  text.insert(1, "\"name\": " + nested(63) + ",");
  expect_error(write("d64.json", text), "name", "must be a string");
  text = s.dump();
  text.insert(1, "\"name\":\n" + nested(64) + ",");
  expect_error(write("d65.json", text), "json", "nested deeper than 64");
  EXPECT_EQ(load_error(dir_.file("d65.json"))->line(), 2u);
  // Brackets inside strings do not count.
  s["name"] = std::string(200, '[');
  EXPECT_NO_THROW(load_scene(write(s)));
}

TEST_F(BadScene, Limits) {
  json s = base_scene();
  for (int i = 0; i < 65; ++i) s["objects"].push_back(s["objects"][0]);
  expect_error(s, "objects[65]", "more than 64 planes");
  s = base_scene();
  s["lights"] = json::array();
  for (int i = 0; i < 1025; ++i) {
    s["lights"].push_back(
        {{"name", "l" + std::to_string(i)}, {"type", "point"}, {"position", {0, 1, 0}}});
  }
  expect_error(s, "lights", "at most 1024");
  // 200 patches at 256 x 256 quads: 26.2 million triangles, over kSceneMaxTriangles.
  std::string bpt = "200\n";
  for (int p = 0; p < 200; ++p) {
    bpt += "3 3\n";
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) bpt += std::to_string(i) + " " + std::to_string(j) + " 0\n";
    }
  }
  write("many.bpt", bpt);
  s = base_scene();
  s["objects"] = {
      {{"type", "bezier"}, {"file", "many.bpt"}, {"subdivisions", 256}, {"material", "a"}}};
  expect_error(s, "objects[0].subdivisions", "would exceed 20000000");
  s["objects"][0]["subdivisions"] = 257;
  expect_error(s, "objects[0].subdivisions", "1..256");
  s["objects"][0]["subdivisions"] = 2;
  EXPECT_EQ(load_scene(write(s)).meshes[0].faces.size(), 200u * 2 * 2 * 2);
}

// The world's extent (kSceneMaxCoordinate): a vertex at 1e308, scaled, once made the ray caster's
// BVH bin NaNs (found by fuzz_scene); spheres and planes are held to it too.
TEST_F(BadScene, CoordinatesBeyondTheExtent) {
  write("tri.obj", "v 0 0 0\nv 1 0 0\nv 0 -1e8 1\nvn 0 0 1\nf 1//1 2//1 3//1\n");
  json s = base_scene();
  s["objects"] = {{{"type", "mesh"}, {"file", "tri.obj"}, {"material", "a"}, {"scale", 5}}};
  EXPECT_EQ(load_scene(write(s)).meshes.size(), 1u);  // 5e8: inside
  s["objects"][0]["scale"] = 11;
  expect_error(s, "objects[0]", "a vertex is beyond the scene's extent");
  s["objects"][0]["scale"] = 1;
  s["objects"][0]["translate"] = {0, 0, 2e9};
  expect_error(s, "objects[0]", "beyond the scene's extent");
  s = base_scene();
  s["objects"][1]["radius"] = 1e9;
  expect_error(s, "objects[1]", "the sphere reaches beyond");
  s = base_scene();
  s["objects"][0]["point"] = {0, -1e300, 0};
  expect_error(s, "objects[0].point", "the point is beyond");
}

// ---- OBJ meshes --------------------------------------------------------------------------------

class ObjScene : public BadScene {
 protected:
  // A scene whose only object is the OBJ `text`, with `extra` keys on the object.
  std::string scene_with_obj(const std::string& text, const json& extra = json::object()) {
    write("m.obj", text);
    json s = base_scene();
    json object = {{"type", "mesh"}, {"file", "m.obj"}, {"material", "b"}};
    object.update(extra);
    s["objects"] = json::array({object});  // {object} alone is a copy under clang
    return write(s);
  }
  std::string obj_path() const { return dir_.file("m.obj"); }
};

constexpr const char* kQuadObj =
    "mtllib nowhere/missing.mtl\n"
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
    "vn 0 0 1\nvn 0 0 2\n"
    "usemtl ignored\n"
    "f 1//1 2//1 3//2 4//2\n";

TEST_F(ObjScene, QuadIsSplitAndVerticesShared) {
  const Scene s = load_scene(scene_with_obj(kQuadObj));
  ASSERT_EQ(s.meshes.size(), 1u);
  const Mesh& m = s.meshes[0];
  EXPECT_EQ(m.name, "m");
  EXPECT_EQ(m.material, 1u);
  EXPECT_EQ(m.faces.size(), 2u);
  EXPECT_EQ(m.positions.size(), 4u);  // four distinct (v, vn) pairs
  for (const Vec3& n : m.normals) EXPECT_DOUBLE_EQ(length(n), 1);
  EXPECT_EQ(m.faces[0], (std::array<std::uint32_t, 3>{0, 1, 2}));
  EXPECT_EQ(m.faces[1], (std::array<std::uint32_t, 3>{0, 2, 3}));
}

TEST_F(ObjScene, TransformMovesPointsAndNormals) {
  const json t = {{"scale", {2, 1, 1}}, {"rotate", {0, 0, 90}}, {"translate", {10, 0, 0}}};
  const Scene s =
      load_scene(scene_with_obj("v 1 0 0\nv 0 1 0\nv 0 0 1\nvn 1 1 0\nf 1//1 2//1 3//1\n", t));
  const Mesh& m = s.meshes[0];
  // (1,0,0) scaled to (2,0,0), turned 90 degrees about z to (0,2,0), moved to (10,2,0).
  EXPECT_EQ(m.positions[0].x, 10);
  EXPECT_EQ(m.positions[0].y, 2);
  EXPECT_EQ(m.positions[0].z, 0);
  // The normal (1,1,0) through the inverse transpose: (1/2, 1, 0), turned: (-1, 1/2, 0).
  const Vec3 n = m.normals[0];
  const double k = 1 / std::sqrt(1.25);
  EXPECT_NEAR(n.x, -k, 1e-15);
  EXPECT_NEAR(n.y, 0.5 * k, 1e-15);
  EXPECT_EQ(n.z, 0);
}

TEST_F(ObjScene, MeshWithoutNormalsGetsGeneratedOnes) {
  // No face vertex names a normal, or only some do: every normal is generated (smooth_normals.h).
  for (const char* text : {"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n",
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/1\n",
                           "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 -1\nvn 1 0 0\n"
                           "f 1 2 3\nf 1//1 3//1 4//1\n"}) {
    SCOPED_TRACE(text);
    const Scene s = load_scene(scene_with_obj(text));
    const Mesh& m = s.meshes[0];
    EXPECT_EQ(m.normal_source, NormalSource::kGenerated);
    EXPECT_EQ(m.crease_degrees, kSceneDefaultCreaseDegrees);
    EXPECT_EQ(m.normals[0].z, 1);  // the first face's own, unshared at a 90-degree fold
  }
  EXPECT_EQ(load_scene(scene_with_obj(kQuadObj)).meshes[0].normal_source, NormalSource::kFile);
}

TEST_F(ObjScene, IndexOutOfRange) {
  expect_error(scene_with_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 9//1\n"), "f",
               "vertex index out of range", obj_path());
  expect_error(scene_with_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 3//4\n"), "f",
               "normal index out of range", obj_path());
  expect_error(scene_with_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 1//1 2//1 -7//1\n"), "f",
               "vertex index out of range", obj_path());
  // Out-of-range corners of a polygon are caught before anything reads them.
  expect_error(scene_with_obj("v 0 0 0\nvn 0 0 1\nf 1//1 1//1 1//1 1//1 99//1 1//1\n"), "f",
               "out of range", obj_path());
}

TEST_F(ObjScene, ObjThatFailsToLoad) {
  expect_error(scene_with_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 1\nf 0//1 1//1 2//1\n"), "obj",
               "tinyobjloader cannot read it", obj_path());
  expect_error(scene_with_obj("# nothing\n"), "f", "no faces", obj_path());
  expect_error(scene_with_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nvn 0 0 0\nf 1//1 2//1 3//1\n"), "vn",
               "zero", obj_path());
  // A file that is not there is the scene's error, in the field that names it.
  json s = base_scene();
  s["objects"] = {{{"type", "mesh"}, {"file", "absent.obj"}, {"material", "a"}}};
  expect_error(s, "objects[0].file", "cannot open");
  s["objects"][0]["file"] = ".";  // a folder, not a file
  expect_error(s, "objects[0].file", "cannot open");
}

// ---- Patch files and the teapot ------------------------------------------------------------

TEST_F(BadScene, PatchFileErrors) {
  const auto expect_patch_error = [&](const std::string& text, const std::string& field,
                                      std::uint64_t line, const std::string& needle) {
    const std::string path = write("p.bpt", text);
    json s = base_scene();
    s["objects"] = {
        {{"type", "bezier"}, {"file", "p.bpt"}, {"subdivisions", 2}, {"material", "a"}}};
    SCOPED_TRACE(text);
    expect_error(write(s), field, needle, path);
    EXPECT_EQ(load_error(dir_.file("scene.json"))->line(), line);
  };
  std::string patch = "3 3\n";
  for (int i = 0; i < 16; ++i)
    patch += std::to_string(i % 4) + " " + std::to_string(i / 4) + " 0\n";
  expect_patch_error("", "patches", 0, "empty file");
  expect_patch_error("# c\n\n0\n", "patches", 3, "1..65536");
  expect_patch_error("1\n2 3\n", "degree", 2, "only bicubic");
  expect_patch_error("1\n3 3\n0 0 0\n", "point", 3, "the file ends inside patch 1");
  expect_patch_error("1\n3 3\n0 0 zero\n", "point", 3, "zero");
  expect_patch_error("1\n3 3\n0 0 1e999\n", "point", 3, "");
  expect_patch_error("1\n" + patch + "7\n", "patches", 19, "data after the last patch");
  expect_patch_error("2\n" + patch, "degree", 18, "the file ends before patch 2");
  // All 16 control points in one spot: no normal anywhere.
  std::string flat = "1\n3 3\n";
  for (int i = 0; i < 16; ++i) flat += "1 1 1\n";
  expect_patch_error(flat, "point", 0, "degenerate");
}

TEST(Teapot, TessellationCountsAndUnitNormals) {
  const auto patches = read_bezier_patches(kScenes + "/teapot.bpt");
  ASSERT_EQ(patches.size(), 32u);
  for (const int s : {1, 3, 8}) {
    SCOPED_TRACE(s);
    const Mesh m = tessellate_bezier(patches, s, "teapot.bpt");
    EXPECT_EQ(m.faces.size(), static_cast<std::size_t>(32 * s * s * 2));
    ASSERT_EQ(m.normals.size(), m.positions.size());
    for (const Vec3& n : m.normals) {
      ASSERT_TRUE(std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z));
      ASSERT_NEAR(length(n), 1, 1e-12);
    }
    for (const auto& f : m.faces) {
      for (const std::uint32_t v : f) ASSERT_LT(v, m.positions.size());
    }
  }
}

TEST(Teapot, KnownDimensionsAndOutwardNormals) {
  const Mesh m = tessellate_bezier(read_bezier_patches(kScenes + "/teapot.bpt"), 12, "t");
  Vec3 lo = m.positions[0], hi = lo;
  for (const Vec3& p : m.positions) {
    lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
    hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
  }
  // Newell's units, z up: the body's widest ring has radius 2, the handle reaches x = -3, the
  // spout's tip x ~ 3.43, the base is at z = 0 and the knob at z = 3.15.
  EXPECT_NEAR(lo.x, -3, 1e-12);
  EXPECT_NEAR(hi.x, 3.434, 0.01);
  EXPECT_NEAR(lo.y, -2, 1e-12);
  EXPECT_NEAR(hi.y, 2, 1e-12);
  EXPECT_NEAR(lo.z, 0, 1e-12);
  EXPECT_NEAR(hi.z, 3.15, 1e-12);
  // The body (patches 5..12) faces away from the z axis; the lid's pole faces up, the bottom's
  // pole down (both evaluated just inside the patch).
  const std::size_t per_patch = 13 * 13;
  for (std::size_t k = 4 * per_patch; k < 12 * per_patch; ++k) {
    const Vec3 p = m.positions[k];
    ASSERT_GT(dot(m.normals[k], Vec3{p.x, p.y, 0}), 0) << k;
  }
  EXPECT_GT(m.normals[20 * per_patch].z, 0.999);   // patch 21, (u, v) = (0, 0): the knob's top
  EXPECT_LT(m.normals[28 * per_patch].z, -0.999);  // patch 29: the centre of the bottom
}

}  // namespace
}  // namespace glint
