// A read-only view of one value in a parsed scene document, with its JSON path
// ("materials[2].shininess"). Every accessor checks the value's JSON type and rule and throws
// InputError(file, 0, path, message), so the loader reads a field and validates it in one call.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>

#include "reference/reference.h"
#include "scene/vec3.h"

namespace glint::scene_json {

class Node {
 public:
  Node(const nlohmann::json& value, std::string path, const std::string& file);

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  [[noreturn]] void fail(const std::string& message) const;
  bool is_object() const;
  bool is_number() const;

  // An object whose keys are all in `allowed` (unknown keys are typos: they are errors).
  void expect_object(std::initializer_list<const char*> allowed) const;
  Node at(const char* key) const;  // a required member
  std::optional<Node> find(const char* key) const;

  // An array of min..max elements; `what` names an element for messages ("lights").
  std::size_t array_size(std::size_t min, std::size_t max, const char* what) const;
  Node operator[](std::size_t index) const;

  double number() const;    // a finite JSON number
  double positive() const;  // finite and > 0
  std::int64_t integer(std::int64_t lo, std::int64_t hi) const;
  std::string string() const;  // a non-empty string
  Vec3 vec3() const;           // [x, y, z], finite
  Rgb colour() const;          // [r, g, b], finite and >= 0

 private:
  Node child(std::string path, const nlohmann::json& value) const;
  void expect_triple() const;

  const nlohmann::json* value_;
  std::string path_;
  const std::string* file_;
};

}  // namespace glint::scene_json
