// Scene files (scene/scene.h, traces/scenes/README.md) through load_scene, with an OBJ mesh and a
// Bezier patch file beside them. The input is the scene's JSON, then optionally a line "#%obj"
// followed by the OBJ file (written as mesh.obj) and a line "#%bpt" followed by the patch file
// (mesh.bpt), in a temporary folder of this process: a scene's objects name "mesh.obj" or
// "mesh.bpt" to load them.
//
// Two harnesses over the same inputs (seeds, dictionary and findings of `scene`):
// - `scene`, the parser: a loaded scene must give a vector header validate() accepts, and a small
//   one (at most 200 000 triangles) is ray-cast at 8x6 pixels with every light sampled, so the
//   geometry the loader lets through reaches the BVH and the tracer;
// - `scene_render` (fuzz_scene_render, built from this file with GLINT_FUZZ_SCENE_RENDER): the
//   same, then a scene of at most 16 slots is rendered through pow (the evaluation engine, the
//   accuracy contracts, the cost model, the images), ~20x the parser's time per input, so that
//   the parser gets its executions and the pipeline its own runs.
// InputError and std::invalid_argument are refusals (exit 2); anything else is a finding.

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "fuzz.h"
#include "io/input_error.h"
#include "io/vectors.h"
#include "render/render.h"
#include "scene/scene.h"
#include "scene/tracer.h"

namespace glint::fuzz {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kMaxTracedTriangles = 200000;
constexpr std::size_t kMaxRenderedSlots = 16;

const fs::path& folder() {
  return temp_folder("scene");
}

// Writes `text` to `name` in the folder, or removes the file when the input has no such part.
void put(const std::string& name, const std::string& text, bool present) {
  const fs::path p = folder() / name;
  if (!present) {
    std::error_code ec;
    fs::remove(p, ec);
    return;
  }
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
  if (!out) fail("cannot write " + p.string());
}

// The part after the line `marker` up to the next marker line (or the end).
bool part(const std::string& text, const std::string& marker, std::string& out) {
  const std::string line = "\n" + marker + "\n";
  const auto at = text.find(line);
  if (at == std::string::npos) return false;
  const auto begin = at + line.size();
  const auto end = text.find("\n#%", begin);
  out = text.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
  return true;
}

std::size_t triangles(const Scene& s) {
  std::size_t n = 0;
  for (const Mesh& m : s.meshes) n += m.faces.size();
  return n;
}

void trace_and_render(Scene& s, bool render) {
  // Every camera the loader accepts, at a size that costs nothing.
  s.camera.width = 8;
  s.camera.height = 6;
  {
    SceneTracer tracer(s);
    std::vector<SurfaceSample> samples(8 * 6);
    tracer.trace_rows(0, 6, samples.data());
    for (const SurfaceSample& sample : samples)
      if (sample.hit)
        for (std::size_t l = 0; l < s.lights.size(); ++l) (void)light_sample(s, sample, l);
  }
  if (!render || s.lights.size() * s.materials.size() > kMaxRenderedSlots) return;
  RenderOptions options;
  options.units = {parse_unit_spec("pow")};
  options.tile_rows = 3;
  try {
    (void)render_scene(s, options).to_json().dump();
  } catch (const std::invalid_argument&) {
    // a material pow cannot be built for (e.g. a shininess beyond its n register): exit 2
  }
}

int load_and_check(const std::uint8_t* data, std::size_t size, bool render) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string obj, bpt;
  const bool has_obj = part(text, "#%obj", obj);
  const bool has_bpt = part(text, "#%bpt", bpt);
  const auto json_end = text.find("\n#%");
  put("scene.json", text.substr(0, json_end), true);
  put("mesh.obj", obj, has_obj);
  put("mesh.bpt", bpt, has_bpt);
  Scene s;
  try {
    s = load_scene((folder() / "scene.json").string());
  } catch (const InputError&) {
    return 0;
  } catch (const std::exception& e) {
    fail(std::string("load_scene threw something other than InputError: ") + e.what());
  }
  try {
    validate(scene_vector_header(s));
  } catch (const std::invalid_argument& e) {
    fail(std::string("a loaded scene's vector header is invalid: ") + e.what());
  }
  if (triangles(s) <= kMaxTracedTriangles) trace_and_render(s, render);
  return 0;
}

}  // namespace

int scene(const std::uint8_t* data, std::size_t size) {
  return load_and_check(data, size, false);
}

int scene_render(const std::uint8_t* data, std::size_t size) {
  return load_and_check(data, size, true);
}

}  // namespace glint::fuzz

#ifdef GLINT_FUZZ_SCENE_RENDER
GLINT_FUZZ_TARGET(scene_render)
#else
GLINT_FUZZ_TARGET(scene)
#endif
