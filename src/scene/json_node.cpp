#include "scene/json_node.h"

#include <cmath>
#include <nlohmann/json.hpp>

#include "io/input_error.h"
#include "io/vector_syntax.h"

namespace glint::scene_json {

namespace {

// A value as the user wrote it, cut short: for "must be ..., not X" messages.
std::string shown(const nlohmann::json& value) {
  return quote_input(value.dump(), 40);
}

}  // namespace

Node::Node(const nlohmann::json& value, std::string path, const std::string& file)
    : value_(&value), path_(std::move(path)), file_(&file) {}

void Node::fail(const std::string& message) const {
  throw InputError(*file_, 0, path_.empty() ? "scene" : path_, message);
}

bool Node::is_object() const {
  return value_->is_object();
}

bool Node::is_number() const {
  return value_->is_number();
}

Node Node::child(std::string path, const nlohmann::json& value) const {
  return Node(value, std::move(path), *file_);
}

void Node::expect_object(std::initializer_list<const char*> allowed) const {
  if (!value_->is_object()) fail(std::string("must be an object, not ") + value_->type_name());
  for (const auto& item : value_->items()) {
    bool known = false;
    for (const char* key : allowed) known = known || item.key() == key;
    if (known) continue;
    std::string list;
    for (const char* key : allowed) list += (list.empty() ? "" : ", ") + std::string(key);
    const std::string field = path_.empty() ? item.key() : path_ + "." + item.key();
    throw InputError(*file_, 0, field,
                     "unknown key " + quote_input(item.key()) + " (allowed here: " + list + ")");
  }
}

Node Node::at(const char* key) const {
  auto found = find(key);
  if (!found) {
    throw InputError(*file_, 0, path_.empty() ? key : path_ + "." + key, "missing (required)");
  }
  return *found;
}

std::optional<Node> Node::find(const char* key) const {
  const auto it = value_->find(key);
  if (it == value_->end()) return std::nullopt;
  return child(path_.empty() ? key : path_ + "." + key, *it);
}

std::size_t Node::array_size(std::size_t min, std::size_t max, const char* what) const {
  if (!value_->is_array()) fail(std::string("must be an array, not ") + value_->type_name());
  const std::size_t n = value_->size();
  if (n < min) {
    fail(min == 1 ? std::string("is empty: at least one of the ") + what + " is required"
                  : "has " + std::to_string(n) + " elements, at least " + std::to_string(min) +
                        " required");
  }
  if (n > max) {
    fail("has " + std::to_string(n) + " " + what + ", at most " + std::to_string(max) +
         " are allowed");
  }
  return n;
}

Node Node::operator[](std::size_t index) const {
  return child(path_ + "[" + std::to_string(index) + "]", (*value_)[index]);
}

double Node::number() const {
  // JSON booleans are not numbers here, although nlohmann would convert them.
  if (!value_->is_number()) fail(std::string("must be a number, not ") + value_->type_name());
  const double v = value_->get<double>();
  // A literal beyond the range of a double (1e999) parses as an infinity.
  if (!std::isfinite(v)) fail("must be finite, not " + shown(*value_));
  return v;
}

double Node::positive() const {
  const double v = number();
  if (!(v > 0)) fail("must be > 0, not " + format_double(v));
  return v;
}

std::int64_t Node::integer(std::int64_t lo, std::int64_t hi) const {
  const std::string range = std::to_string(lo) + ".." + std::to_string(hi);
  if (!value_->is_number_integer()) {
    fail("must be an integer in " + range + ", not " +
         (value_->is_number() ? shown(*value_) : std::string(value_->type_name())));
  }
  // Unsigned values above INT64_MAX would wrap in get<int64_t>.
  if (value_->is_number_unsigned() &&
      value_->get<std::uint64_t>() > static_cast<std::uint64_t>(hi)) {
    fail("must be an integer in " + range + ", not " + shown(*value_));
  }
  const auto v = value_->get<std::int64_t>();
  if (v < lo || v > hi) fail("must be an integer in " + range + ", not " + std::to_string(v));
  return v;
}

std::string Node::string() const {
  if (!value_->is_string()) fail(std::string("must be a string, not ") + value_->type_name());
  auto s = value_->get<std::string>();
  if (s.empty()) fail("must not be empty");
  return s;
}

void Node::expect_triple() const {
  if (!value_->is_array() || value_->size() != 3) {
    fail("must be an array of 3 numbers, not " + (value_->is_array()
                                                      ? std::to_string(value_->size()) + " elements"
                                                      : std::string(value_->type_name())));
  }
}

Vec3 Node::vec3() const {
  expect_triple();
  return {(*this)[0].number(), (*this)[1].number(), (*this)[2].number()};
}

Rgb Node::colour() const {
  expect_triple();
  double c[3];
  for (std::size_t i = 0; i < 3; ++i) {
    const Node component = (*this)[i];
    c[i] = component.number();
    if (c[i] < 0) component.fail("a colour component must be >= 0, not " + format_double(c[i]));
  }
  return {c[0], c[1], c[2]};
}

}  // namespace glint::scene_json
