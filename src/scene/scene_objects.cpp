#include "scene/scene_objects.h"

#include <cmath>
#include <filesystem>
#include <string>

#include "io/input_error.h"
#include "scene/assimp_mesh.h"
#include "scene/bezier.h"
#include "scene/transform.h"

namespace fs = std::filesystem;

namespace glint {

namespace {

using scene_json::Node;

// Every coordinate of the ball of radius r around p within kSceneMaxCoordinate (false for NaN).
bool within_extent(Vec3 p, double r) {
  for (const double v : {p.x, p.y, p.z}) {
    if (!(std::abs(v) + r <= kSceneMaxCoordinate)) return false;
  }
  return true;
}

std::string beyond_extent(const std::string& what) {
  return what + " beyond the scene's extent (every world coordinate within +-" +
         std::to_string(static_cast<long long>(kSceneMaxCoordinate)) + ")";
}

class ObjectReader {
 public:
  explicit ObjectReader(Scene& scene) : scene_(scene) {}

  void read(const Node& node) {
    if (!node.is_object()) node.fail("must be an object with a \"type\"");
    const Node type = node.at("type");
    const std::string kind = type.string();
    if (kind == "mesh") {
      node.expect_object(
          {"type", "name", "file", "material", "crease_angle", "scale", "rotate", "translate"});
      add_mesh(node, read_mesh(node));
    } else if (kind == "bezier") {
      node.expect_object(
          {"type", "name", "file", "subdivisions", "material", "scale", "rotate", "translate"});
      add_mesh(node, read_bezier(node));
    } else if (kind == "sphere") {
      node.expect_object({"type", "center", "radius", "material"});
      const Vec3 c = node.at("center").vec3();
      const double r = node.at("radius").positive();
      if (!within_extent(c, r)) node.fail(beyond_extent("the sphere reaches"));
      scene_.spheres.push_back({c, r, material(node)});
    } else if (kind == "plane") {
      node.expect_object({"type", "point", "normal", "material"});
      if (scene_.planes.size() == kSceneMaxPlanes) {
        node.fail("more than " + std::to_string(kSceneMaxPlanes) + " planes");
      }
      const Node normal = node.at("normal");
      const Vec3 n = normal.vec3();
      if (!(length(n) > 0)) normal.fail("must not be the zero vector");
      const Vec3 p = node.at("point").vec3();
      if (!within_extent(p, 0)) node.at("point").fail(beyond_extent("the point is"));
      scene_.planes.push_back({p, normalize(n), material(node)});
    } else {
      type.fail("unknown object type " + quote_input(kind) + " (mesh, bezier, sphere or plane)");
    }
  }

 private:
  std::uint32_t material(const Node& node) const {
    const Node ref = node.at("material");
    const std::string name = ref.string();
    for (std::size_t i = 0; i < scene_.materials.size(); ++i) {
      if (scene_.materials[i].name == name) return static_cast<std::uint32_t>(i);
    }
    ref.fail("unknown material " + quote_input(name) + " (not in \"materials\")");
  }

  // The file named by node.file, relative to the scene's folder; it must exist.
  std::string file(const Node& node) const {
    const Node field = node.at("file");
    const fs::path p = fs::path(scene_.file).parent_path() / field.string();
    std::error_code ec;
    if (!fs::is_regular_file(p, ec)) field.fail("cannot open " + quote_input(p.string(), 200));
    return p.string();
  }

  std::size_t triangles_left() const { return kSceneMaxTriangles - triangles_; }

  Mesh read_mesh(const Node& node) const {
    const std::string path = file(node);
    const auto crease = node.find("crease_angle");
    double degrees = kSceneDefaultCreaseDegrees;
    if (crease) {
      degrees = crease->number();
      if (!(degrees >= 0 && degrees <= 180))
        crease->fail("must be an angle in degrees in [0, 180], not " + std::to_string(degrees));
    }
    const MeshFormat format = mesh_format(path);
    Mesh mesh = load_mesh_file(path, format, triangles_left(), ObjLimits{}, degrees);
    if (crease && mesh.normal_source == NormalSource::kFile) {
      crease->fail(
          "the mesh file has its own normals; a crease angle applies only to a mesh "
          "whose normals glint generates (remove it, or the file's normals)");
    }
    mesh.name = fs::path(path).stem().string();
    return mesh;
  }

  Mesh read_bezier(const Node& node) const {
    const std::string path = file(node);
    const auto patches = read_bezier_patches(path);
    const Node sub = node.at("subdivisions");
    const auto s = static_cast<std::size_t>(sub.integer(1, kSceneMaxBezierSubdivisions));
    const std::size_t triangles = patches.size() * s * s * 2;
    if (triangles > triangles_left()) {
      sub.fail(std::to_string(triangles) + " triangles: the scene's triangles would exceed " +
               std::to_string(kSceneMaxTriangles));
    }
    Mesh mesh = tessellate_bezier(patches, static_cast<int>(s), path);
    mesh.format = "bpt";
    mesh.normal_source = NormalSource::kPatches;
    mesh.name = fs::path(path).stem().string();
    return mesh;
  }

  void add_mesh(const Node& node, Mesh mesh) {
    if (const auto name = node.find("name")) mesh.name = name->string();
    mesh.material = material(node);
    apply(read_transform(node), mesh);
    for (const Vec3& p : mesh.positions) {
      if (!within_extent(p, 0)) node.fail(beyond_extent("after its transform, a vertex is"));
    }
    triangles_ += mesh.faces.size();
    scene_.meshes.push_back(std::move(mesh));
  }

  static Transform read_transform(const Node& node) {
    Transform t;
    if (const auto scale = node.find("scale")) {
      if (scale->is_number()) {
        const double s = scale->positive();
        t.scale = {s, s, s};
      } else {
        t.scale = scale->vec3();
        for (std::size_t i = 0; i < 3; ++i) (*scale)[i].positive();
      }
    }
    if (const auto rotate = node.find("rotate")) t.rotate_degrees = rotate->vec3();
    if (const auto translate = node.find("translate")) t.translate = translate->vec3();
    return t;
  }

  Scene& scene_;
  std::size_t triangles_ = 0;
};

}  // namespace

const char* to_string(NormalSource source) {
  switch (source) {
    case NormalSource::kFile:
      return "file";
    case NormalSource::kGenerated:
      return "generated";
    case NormalSource::kPatches:
      return "patches";
  }
  return "?";
}

void read_objects(const Node& objects, Scene& scene) {
  const std::size_t n = objects.array_size(1, kSceneMaxObjects, "objects");
  ObjectReader reader(scene);
  for (std::size_t i = 0; i < n; ++i) reader.read(objects[i]);
}

}  // namespace glint
