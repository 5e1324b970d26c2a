#include "io/vector_rules.h"

#include <stdexcept>
#include <unordered_set>

#include "io/vector_syntax.h"

namespace glint {

std::string magic_line() {
  return std::string(kVectorMagic) + ' ' + std::to_string(kVectorFormatVersion);
}

std::string light_count_range_text() {
  return "1.." + std::to_string(kVectorMaxLights);
}

std::string roughness_range_text() {
  return "(0, " + format_double(kVectorMaxRoughness) + "]";
}

std::string t_range_text() {
  return "[" + format_double(kVectorTMin) + ", " + format_double(kVectorTMax) + "]";
}

std::string line_too_long_text() {
  return "line longer than " + std::to_string(kVectorMaxLineBytes) + " bytes";
}

void validate(const VectorHeader& h) {
  const auto bad = [](const std::string& msg) {
    throw std::invalid_argument("invalid vector header: " + msg);
  };
  const auto valid_colour = [](const std::array<double, 3>& c) {
    for (double v : c) {
      if (!valid_colour_component(v)) return false;
    }
    return true;
  };
  if (h.version != kVectorFormatVersion) {
    bad("version must be " + std::to_string(kVectorFormatVersion));
  }
  if (!valid_eps(h.eps)) bad("eps must be finite and > 0");
  if (!valid_light_count(h.lights)) bad("lights must be in " + light_count_range_text());
  if (!h.light_intensity.empty()) {
    if (h.light_intensity.size() != static_cast<std::size_t>(h.lights)) {
      bad("light_intensity must be empty or have one entry per light");
    }
    for (const auto& c : h.light_intensity) {
      if (!valid_colour(c)) bad("light intensities must be finite and >= 0");
    }
  }
  if (h.materials.empty()) bad("at least one material is required");
  if (!valid_material_count(h.materials.size())) bad("too many materials");
  std::unordered_set<std::string_view> names;
  for (const auto& m : h.materials) {
    const std::string who = "material '" + m.name + "': ";
    if (!valid_name(m.name)) bad(who + name_rule());
    if (!names.insert(m.name).second) bad(who + "duplicate name");
    if (!valid_colour(m.specular)) bad(who + "specular must be finite and >= 0");
    if (m.lobe != VectorLobe::kPhong && m.lobe != VectorLobe::kBlinn &&
        m.lobe != VectorLobe::kGaussian) {
      bad(who + "unknown lobe");
    }
    if (takes_roughness(m.lobe)) {
      if (!valid_roughness(m.roughness)) {
        bad(who + "roughness must be in " + roughness_range_text());
      }
      if (m.shininess != 0 && !valid_shininess(m.shininess)) {
        bad(who + "shininess must be > 0 (or 0 = not given) for gaussian");
      }
    } else {
      if (!valid_shininess(m.shininess)) bad(who + "shininess must be > 0");
      if (m.roughness != 0) bad(who + "roughness only applies to lobe=gaussian");
    }
  }
}

}  // namespace glint
