// The value rules of vector files v1 (traces/README.md, "Header", "Columns", "Limits"), defined
// once: the reader checks what it parses against them, validate() a header in memory, the writer
// each row. The limits themselves are the constants in io/vectors.h; the *_text() functions spell
// them for messages, so a message never disagrees with the check it reports.
//
// Values reach the reader's checks already parsed, hence finite; the predicates reject non-finite
// values themselves for validate() and the writer, whose values come from callers.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "io/vectors.h"

namespace glint {

// The first line of every vector file: the magic word and the format version.
inline constexpr std::string_view kVectorMagic = "glint-vectors";
std::string magic_line();  // "glint-vectors 1"

inline bool valid_eps(double eps) {
  return std::isfinite(eps) && eps > 0;
}

inline bool valid_light_count(std::int64_t lights) {
  return lights >= 1 && lights <= kVectorMaxLights;
}
std::string light_count_range_text();  // "1..1024"

// Light indices run over 0..lights-1. A `light` header line may come before `lights`, so the
// reader first holds its index to the most lights a file can have.
inline bool valid_light_index(std::int64_t index, std::int64_t lights) {
  return index >= 0 && index < lights;
}

inline bool valid_material_count(std::size_t materials) {
  return materials >= 1 && materials <= kVectorMaxMaterials;
}

// Light intensities and specular colours: finite, >= 0 (-0 included).
inline bool valid_colour_component(double v) {
  return std::isfinite(v) && !(v < 0);
}

// Which attributes a lobe has: a Gaussian lobe requires a roughness and may have a shininess (0 in
// VectorMaterial when not given); phong and blinn require a shininess and take no roughness.
inline bool takes_roughness(VectorLobe lobe) {
  return lobe == VectorLobe::kGaussian;
}

inline bool valid_shininess(double n) {
  return std::isfinite(n) && n > 0;
}

inline bool valid_roughness(double w) {
  return w > 0 && w <= kVectorMaxRoughness;
}
std::string roughness_range_text();  // "(0, 1]"

// The cosine a row feeds the unit; NaN and infinities fail the comparisons.
inline bool valid_t(double t) {
  return t >= kVectorTMin && t <= kVectorTMax;
}
std::string t_range_text();  // "[-1, 1.001]"

inline bool valid_pixel(std::int64_t coordinate) {
  return coordinate >= 0;
}

std::string line_too_long_text();  // "line longer than 4096 bytes"

}  // namespace glint
