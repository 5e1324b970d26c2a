// scene_vector_header: the vector-file header of a scene's shading requests.
#include <algorithm>
#include <stdexcept>

#include "io/input_error.h"
#include "scene/scene.h"

namespace glint {

VectorHeader scene_vector_header(const Scene& scene) {
  VectorHeader h;
  h.eps = scene.eps;
  h.display = scene.display;
  // Clamped so that an oversized count stays oversized (validate() rejects it) instead of wrapping.
  h.lights = static_cast<int>(std::min<std::size_t>(scene.lights.size(), kVectorMaxLights + 1));
  for (const SceneLight& light : scene.lights) {
    h.light_intensity.push_back({light.intensity.r, light.intensity.g, light.intensity.b});
  }
  for (const SceneMaterial& m : scene.materials) {
    VectorMaterial v;
    v.name = m.name;
    v.specular = {m.specular.r, m.specular.g, m.specular.b};
    v.shininess = m.shininess;
    v.lobe = m.lobe;
    v.roughness = m.roughness;
    h.materials.push_back(std::move(v));
  }
  h.has_light = true;
  h.has_xy = true;
  try {
    validate(h);
  } catch (const std::invalid_argument& e) {
    // A loaded scene always passes; a Scene built or edited in code may not.
    throw InputError(scene.file, 0, "scene", std::string("not a valid vector header: ") + e.what());
  }
  return h;
}

}  // namespace glint
