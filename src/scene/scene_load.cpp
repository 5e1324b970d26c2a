// load_scene: the top level, the camera, lights and materials (objects: scene_objects.cpp).
#include <cstdint>
#include <filesystem>
#include <limits>
#include <set>

#include "io/input_error.h"
#include "io/json_text.h"
#include "io/vector_rules.h"
#include "io/vector_syntax.h"
#include "scene/json_node.h"
#include "scene/scene.h"
#include "scene/scene_objects.h"

namespace glint {

namespace {

using scene_json::Node;

void check_version(const Node& root) {
  const auto version = root.find("glint_scene");
  if (!version) {
    throw InputError(root.file(), 0, "glint_scene",
                     "missing: a scene is a JSON object with \"glint_scene\": " +
                         std::to_string(kSceneFormatVersion));
  }
  const auto v = version->integer(0, std::numeric_limits<std::int32_t>::max());
  if (v != kSceneFormatVersion) {
    version->fail("unsupported scene format version " + std::to_string(v) + " (glint reads " +
                  std::to_string(kSceneFormatVersion) + ")");
  }
}

// A name by the vector-file rule, unique among `taken`.
std::string unique_name(const Node& node, std::set<std::string>& taken) {
  std::string name = node.string();
  if (!valid_name(name)) node.fail("invalid name " + quote_input(name) + ": " + name_rule());
  if (!taken.insert(name).second) node.fail("duplicate name " + quote_input(name));
  return name;
}

SceneCamera read_camera(const Node& node) {
  node.expect_object({"position", "look_at", "up", "fov_y", "resolution"});
  SceneCamera c;
  c.position = node.at("position").vec3();
  c.look_at = node.at("look_at").vec3();
  const Vec3 view = c.look_at - c.position;
  if (!(length(view) > 0)) node.at("look_at").fail("equals camera.position: no view direction");
  if (const auto up = node.find("up")) {
    c.up = up->vec3();
    if (!(length(c.up) > 0)) up->fail("must not be the zero vector");
    if (length(cross(normalize(view), normalize(c.up))) < 1e-6) {
      up->fail("is parallel to the view direction (look_at - position)");
    }
  } else if (length(cross(normalize(view), c.up)) < 1e-6) {
    node.fail("the view direction is vertical: give an \"up\" that is not parallel to it");
  }
  const Node fov = node.at("fov_y");
  c.fov_y_degrees = fov.number();
  if (!(c.fov_y_degrees > 0 && c.fov_y_degrees < 180)) {
    fov.fail("must be in (0, 180) degrees, not " + format_double(c.fov_y_degrees));
  }
  const Node res = node.at("resolution");
  res.array_size(2, 2, "values ([width, height])");
  c.width = static_cast<int>(res[0].integer(1, kSceneMaxResolution));
  c.height = static_cast<int>(res[1].integer(1, kSceneMaxResolution));
  return c;
}

SceneLight read_light(const Node& node, std::set<std::string>& names) {
  node.expect_object({"name", "type", "position", "direction", "intensity"});
  SceneLight light;
  light.name = unique_name(node.at("name"), names);
  const Node type = node.at("type");
  const std::string kind = type.string();
  const char* unused = nullptr;
  if (kind == "point") {
    light.kind = LightKind::kPoint;
    light.position = node.at("position").vec3();
    unused = "direction";
  } else if (kind == "directional") {
    light.kind = LightKind::kDirectional;
    const Node direction = node.at("direction");
    light.direction = direction.vec3();
    if (!(length(light.direction) > 0)) direction.fail("must not be the zero vector");
    light.direction = normalize(light.direction);
    unused = "position";
  } else {
    type.fail("unknown light type " + quote_input(kind) + " (point or directional)");
  }
  if (const auto extra = node.find(unused)) extra->fail("not allowed for a " + kind + " light");
  if (const auto intensity = node.find("intensity")) light.intensity = intensity->colour();
  return light;
}

SceneMaterial read_material(const Node& node, std::set<std::string>& names) {
  node.expect_object({"name", "diffuse", "specular", "lobe", "shininess", "roughness"});
  SceneMaterial m;
  m.name = unique_name(node.at("name"), names);
  if (const auto diffuse = node.find("diffuse")) m.diffuse = diffuse->colour();
  m.specular = node.at("specular").colour();
  const Node lobe = node.at("lobe");
  const auto parsed = try_parse_lobe(lobe.string());
  if (!parsed) lobe.fail("must be \"phong\", \"blinn\" or \"gaussian\"");
  m.lobe = *parsed;
  const auto shininess = node.find("shininess");
  const auto roughness = node.find("roughness");
  if (takes_roughness(m.lobe)) {
    const Node w = node.at("roughness");
    m.roughness = w.number();
    if (!valid_roughness(m.roughness)) {
      w.fail("must be in " + roughness_range_text() + ", not " + format_double(m.roughness));
    }
    if (shininess) m.shininess = shininess->positive();  // optional hint, as in vector files
  } else {
    m.shininess = node.at("shininess").positive();
    if (roughness) roughness->fail("only a gaussian lobe has a roughness");
  }
  return m;
}

SceneReproduces read_reproduces(const Node& node) {
  node.expect_object({"paper", "figure", "quantity", "value"});
  SceneReproduces r;
  r.paper = node.at("paper").string();
  r.figure = node.at("figure").string();
  // A figure may come without a number (Källberg & Larsson's Fig. 2 gives none): then neither key.
  const std::optional<Node> quantity_node = node.find("quantity");
  const std::optional<Node> value_node = node.find("value");
  if (!quantity_node && !value_node) return r;
  if (!quantity_node || !value_node)
    node.fail(
        "\"quantity\" and \"value\" go together: the paper's number for a quantity, or neither");
  const Node& quantity = *quantity_node;
  r.quantity = quantity.string();
  std::string known;
  bool found = false;
  for (const char* q : kReproducibleQuantities) {
    found = found || r.quantity == q;
    known += (known.empty() ? "" : " or ") + std::string("\"") + q + "\"";
  }
  if (!found) quantity.fail("unknown quantity " + quote_input(r.quantity) + " (" + known + ")");
  r.value = value_node->number();
  return r;
}

}  // namespace

Scene load_scene(const std::string& path) {
  const nlohmann::json doc = parse_json_text(read_text_file(path, kSceneMaxFileBytes, "scene file"),
                                             path, kSceneMaxJsonDepth);
  const Node root(doc, "", path);
  if (!doc.is_object()) root.fail(std::string("must be a JSON object, not ") + doc.type_name());
  check_version(root);
  root.expect_object({"glint_scene", "name", "eps", "display", "camera", "ambient", "background",
                      "lights", "materials", "objects", "reproduces"});
  Scene scene;
  scene.file = path;
  scene.name = std::filesystem::path(path).stem().string();
  if (const auto name = root.find("name")) {
    scene.name = name->string();
    if (scene.name.size() > 256) name->fail("longer than 256 bytes");
  }
  if (const auto eps = root.find("eps")) scene.eps = eps->positive();
  if (const auto display = root.find("display")) {
    const auto e = try_parse_display(display->string());
    if (!e) display->fail("expected \"srgb8\" or \"linear8\"");
    scene.display = *e;
  }
  if (const auto ambient = root.find("ambient")) scene.ambient = ambient->colour();
  if (const auto background = root.find("background")) scene.background = background->colour();
  scene.camera = read_camera(root.at("camera"));

  const Node lights = root.at("lights");
  const std::size_t n_lights = lights.array_size(1, kSceneMaxLights, "lights");
  std::set<std::string> light_names;
  for (std::size_t i = 0; i < n_lights; ++i) {
    scene.lights.push_back(read_light(lights[i], light_names));
  }
  const Node materials = root.at("materials");
  const std::size_t n_materials = materials.array_size(1, kSceneMaxMaterials, "materials");
  std::set<std::string> material_names;
  for (std::size_t i = 0; i < n_materials; ++i) {
    scene.materials.push_back(read_material(materials[i], material_names));
  }
  read_objects(root.at("objects"), scene);
  if (const auto r = root.find("reproduces")) scene.reproduces = read_reproduces(*r);
  return scene;
}

}  // namespace glint
