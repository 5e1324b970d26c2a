// Scenes: the JSON scene format (traces/scenes/README.md) and its loader.
//
// A scene is a camera, lights (point or directional, RGB intensity, no fall-off: the papers'
// Phong model, so a light's tau depends on its colour only), materials (diffuse and specular
// colour, a lobe with its shininess or roughness) and objects: OBJ meshes (tinyobjloader) with
// smooth per-vertex normals, built-in spheres and planes. Every mistake a user can make in a scene
// raises InputError naming the scene file (or the OBJ file) and the field, e.g.
// "scenes/x.json: field 'materials[2].shininess': must be finite and > 0".
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "io/vectors.h"
#include "reference/reference.h"
#include "scene/vec3.h"

namespace glint {

inline constexpr int kSceneFormatVersion = 1;
inline constexpr int kSceneMaxResolution = 16384;  // per axis
inline constexpr std::size_t kSceneMaxTriangles = 20'000'000;
// A scene's shading requests form one vector file: its lights and materials fit one header.
inline constexpr std::size_t kSceneMaxLights = kVectorMaxLights;
inline constexpr std::size_t kSceneMaxMaterials = kVectorMaxMaterials;
inline constexpr std::size_t kSceneMaxObjects = 65536;  // entries of "objects"
inline constexpr std::size_t kSceneMaxPlanes = 64;      // planes are not in the BVH
// World coordinates of every vertex (after its object's transform) and sphere bound: far beyond
// any scene, and far enough from DBL_MAX that the ray caster's boxes, extents and areas stay finite
// (a vertex at 1e308 made the BVH's binning divide infinities).
inline constexpr double kSceneMaxCoordinate = 1e9;
inline constexpr std::size_t kSceneMaxFileBytes = std::size_t{64} << 20;  // the JSON file
inline constexpr int kSceneMaxJsonDepth = 64;  // nested arrays and objects

struct SceneCamera {
  Vec3 position, look_at, up{0, 1, 0};
  double fov_y_degrees = 45;  // vertical field of view, in (0, 180)
  int width = 640, height = 480;
};

enum class LightKind : std::uint8_t { kPoint, kDirectional };

struct SceneLight {
  std::string name;
  LightKind kind = LightKind::kPoint;
  Vec3 position;   // point light
  Vec3 direction;  // directional light: the direction the light travels (unit length)
  Rgb intensity{1, 1, 1};
};

struct SceneMaterial {
  std::string name;  // a vector-file name ([A-Za-z_][A-Za-z0-9_.-]*), unique
  Rgb diffuse{0.5, 0.5, 0.5};
  Rgb specular{1, 1, 1};
  Lobe lobe = Lobe::kPhong;
  double shininess = 0;  // phong/blinn: > 0
  double roughness = 0;  // gaussian: in (0, 1]
};

// A triangle mesh with one normal per vertex (smooth shading). Loaded meshes are transformed to
// world space at load time (the scene's scale/translate), normals renormalised.
struct Mesh {
  std::string name;
  std::vector<Vec3> positions;
  std::vector<Vec3> normals;                        // same size as positions, unit length
  std::vector<std::array<std::uint32_t, 3>> faces;  // vertex indices, counter-clockwise
  std::uint32_t material = 0;                       // index into Scene::materials
};

struct Sphere {
  Vec3 center;
  double radius = 1;
  std::uint32_t material = 0;
};

struct Plane {
  Vec3 point;
  Vec3 normal{0, 1, 0};  // unit length; the plane is two-sided
  std::uint32_t material = 0;
};

// A paper's figure the scene reproduces, and the paper's number for one quantity glint also
// measures on the render (render_report.md: reproduces), so that both are shown side by side.
struct SceneReproduces {
  std::string paper, figure;
  std::string quantity;  // one of kReproducibleQuantities
  double value = 0;      // the paper's figure for it
};
// "tau": the scene's threshold (it must have exactly one slot); "skipped_fraction_tau": the
// share of light x pixel pairs skipped with tau.
inline constexpr const char* kReproducibleQuantities[] = {"tau", "skipped_fraction_tau"};

struct Scene {
  std::string file;   // the path it was loaded from (for messages and reports)
  std::string name;   // "name" in the file, else the file's stem
  double eps = 1e-3;  // perceptibility threshold (Källberg), > 0
  // The display its images are encoded for, and its pixel errors measured in
  // (reference/pixel_error.h): "display" in the file, sRGB unless it says linear8.
  DisplayEncoding display = DisplayEncoding::kSrgb8;
  Rgb ambient{0, 0, 0};
  Rgb background{0, 0, 0};
  SceneCamera camera;
  std::vector<SceneLight> lights;        // at least one
  std::vector<SceneMaterial> materials;  // at least one
  std::vector<Mesh> meshes;
  std::vector<Sphere> spheres;
  std::vector<Plane> planes;
  std::optional<SceneReproduces> reproduces;  // "reproduces" in the file
};

// Loads and validates a scene; OBJ paths are relative to the scene file's folder. Throws
// InputError (file, line 0 or the JSON line when known, field, message).
Scene load_scene(const std::string& path);

// The vector-file header of the scene's shading requests: eps, the lights' intensities, the
// materials (specular colour, lobe, shininess/roughness), columns t material light x y.
VectorHeader scene_vector_header(const Scene& scene);

}  // namespace glint
