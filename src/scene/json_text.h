// Reading a scene file into a JSON document, defensively: a size limit, a nesting limit checked
// before the parser sees the text, parse errors reported with their line, and duplicate keys
// (which nlohmann would silently resolve to the last one) rejected like unknown keys.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace glint {

inline constexpr std::size_t kSceneMaxFileBytes = std::size_t{64} << 20;
inline constexpr int kSceneMaxJsonDepth = 64;

// The bytes of `path`; InputError (field "file") if it cannot be read or exceeds the limit.
std::string read_scene_text(const std::string& path, std::size_t max_bytes = kSceneMaxFileBytes);

// The document in `text`. `file` names it in InputError: field "json" (nesting deeper than
// kSceneMaxJsonDepth, syntax errors, with the 1-based line) or the JSON path of a duplicate key.
nlohmann::json parse_scene_json(const std::string& text, const std::string& file);

}  // namespace glint
