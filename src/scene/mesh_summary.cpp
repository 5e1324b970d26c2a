#include "scene/mesh_summary.h"

#include <cstdio>

namespace glint {

nlohmann::json meshes_json(const Scene& scene) {
  nlohmann::json out = nlohmann::json::array();
  for (const Mesh& m : scene.meshes) {
    const bool generated = m.normal_source == NormalSource::kGenerated;
    out.push_back({{"name", m.name},
                   {"format", m.format},
                   {"triangles", m.faces.size()},
                   {"normals", to_string(m.normal_source)},
                   {"crease_angle", generated ? nlohmann::json(m.crease_degrees) : nullptr}});
  }
  return out;
}

std::string meshes_text(const nlohmann::json& meshes) {
  if (meshes.empty()) return "";
  std::string line = "meshes:";
  for (std::size_t i = 0; i < meshes.size(); ++i) {
    const nlohmann::json& m = meshes[i];
    const std::string normals = m.at("normals").get<std::string>();
    std::string how = "normals from the file";
    if (normals == "patches") how = "normals from the patches";
    if (normals == "generated") {
      char degrees[32];
      std::snprintf(degrees, sizeof degrees, "%g", m.at("crease_angle").get<double>());
      how = std::string("normals generated, angle-weighted, crease ") + degrees + " deg";
    }
    line += (i ? "; " : " ") + m.at("name").get<std::string>() + " (" +
            m.at("format").get<std::string>() + ", " +
            std::to_string(m.at("triangles").get<std::size_t>()) + " triangles, " + how + ")";
  }
  return line + "\n";
}

}  // namespace glint
