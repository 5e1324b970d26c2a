// Reading a JSON input file (a scene, a regression golden, a sweep report to merge) into a
// document, defensively: a size limit, a nesting limit checked before the parser sees the text,
// parse errors reported with their line, and duplicate keys (which nlohmann would silently resolve
// to the last one) rejected like unknown keys.
#pragma once

#include <cstddef>
#include <nlohmann/json.hpp>
#include <string>

namespace glint {

// The bytes of `path`; InputError (field "file") if it cannot be read or exceeds `max_bytes`.
// `what` names the kind of file in messages ("scene file", "golden").
std::string read_text_file(const std::string& path, std::size_t max_bytes, const std::string& what);

// The document in `text`. `file` names it in InputError: field "json" (nesting deeper than
// `max_depth` arrays and objects, syntax errors, with the 1-based line) or the JSON path of a
// duplicate key. The depth is checked on the text, before nlohmann's parser builds anything, so
// that no recursive code downstream (dump(), a loader's walk) can exhaust the stack.
nlohmann::json parse_json_text(const std::string& text, const std::string& file, int max_depth);

}  // namespace glint
