#include "scene/gltf_check.h"

#include <filesystem>
#include <nlohmann/json.hpp>
#include <set>

#include "io/input_error.h"
#include "io/json_text.h"

namespace glint {

namespace {

using nlohmann::json;

class Reducer {
 public:
  Reducer(const json& doc, std::int64_t bin_bytes, std::string folder, const std::string& path)
      : doc_(doc), bin_bytes_(bin_bytes), folder_(std::move(folder)), path_(path) {}

  json run() {
    if (!doc_.is_object()) fail("", "the document is not a JSON object");
    const json* asset = member(doc_, "asset", "");
    if (asset == nullptr || !asset->is_object() || !asset->contains("version") ||
        (*asset)["version"] != "2.0")
      fail("asset.version", "must be \"2.0\" (glint reads glTF 2.0)");
    if (const json* req = member(doc_, "extensionsRequired", "")) {
      if (req->is_array() && !req->empty())
        fail("extensionsRequired", "needs " + req->dump() + ", which glint does not read");
    }
    json out = {{"asset", {{"version", "2.0"}}}};
    buffers_ = array(doc_, "buffers");
    views_ = array(doc_, "bufferViews");
    accessors_ = array(doc_, "accessors");
    const json nodes = array(doc_, "nodes"), meshes = array(doc_, "meshes");
    const json scenes = array(doc_, "scenes");
    out["buffers"] = json::array();
    for (std::size_t i = 0; i < buffers_.size(); ++i) out["buffers"].push_back(buffer(i));
    out["bufferViews"] = json::array();
    for (std::size_t i = 0; i < views_.size(); ++i) out["bufferViews"].push_back(view(i));
    out["accessors"] = json::array();
    for (std::size_t i = 0; i < accessors_.size(); ++i) out["accessors"].push_back(accessor(i));
    out["meshes"] = json::array();
    for (std::size_t i = 0; i < meshes.size(); ++i) out["meshes"].push_back(mesh(meshes[i], i));
    out["nodes"] = json::array();
    for (std::size_t i = 0; i < nodes.size(); ++i)
      out["nodes"].push_back(node(nodes[i], i, nodes.size(), meshes.size()));
    check_tree(out["nodes"]);
    out["scenes"] = json::array();
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      const std::string at = "scenes[" + std::to_string(i) + "]";
      json s = {{"nodes", json::array()}};
      if (const json* list = member(scenes[i], "nodes", at)) {
        if (!list->is_array()) fail(at + ".nodes", "must be an array");
        for (std::size_t k = 0; k < list->size(); ++k)
          s["nodes"].push_back(index((*list)[k], nodes.size(), at + ".nodes"));
      }
      out["scenes"].push_back(s);
    }
    if (const json* s = member(doc_, "scene", "")) out["scene"] = index(*s, scenes.size(), "scene");
    return out;
  }

 private:
  [[noreturn]] void fail(const std::string& at, const std::string& what) const {
    throw InputError(path_, 0, "gltf", (at.empty() ? "" : at + ": ") + what);
  }
  const json* member(const json& o, const char* key, const std::string& at) const {
    if (!o.is_object()) fail(at, "must be an object");
    const auto it = o.find(key);
    return it == o.end() ? nullptr : &*it;
  }
  json array(const json& o, const char* key) const {
    const json* a = member(o, key, "");
    if (a == nullptr) return json::array();
    if (!a->is_array()) fail(key, "must be an array");
    if (a->size() > 1000000) fail(key, "more than 1000000 entries");
    return *a;
  }
  std::uint64_t whole(const json& v, const std::string& at, std::uint64_t max) const {
    if (!v.is_number_integer() || v.get<std::int64_t>() < 0 || v.get<std::uint64_t>() > max)
      fail(at, "must be a whole number in 0.." + std::to_string(max));
    return v.get<std::uint64_t>();
  }
  std::uint64_t index(const json& v, std::size_t size, const std::string& at) const {
    if (size == 0) fail(at, "refers to an empty list");
    return whole(v, at, size - 1);
  }
  std::uint64_t field(const json& o, const char* key, const std::string& at, std::uint64_t max,
                      std::uint64_t fallback, bool required) const {
    const json* v = member(o, key, at);
    if (v == nullptr) {
      if (required) fail(at + "." + key, "missing");
      return fallback;
    }
    return whole(*v, at + "." + key, max);
  }

  json buffer(std::size_t i) {
    const std::string at = "buffers[" + std::to_string(i) + "]";
    const json& b = buffers_[i];
    const std::uint64_t length = field(b, "byteLength", at, std::uint64_t{1} << 32, 0, true);
    json out = {{"byteLength", length}};
    std::uint64_t available = 0;
    if (const json* uri = member(b, "uri", at)) {
      if (!uri->is_string()) fail(at + ".uri", "must be a string");
      const std::string u = uri->get<std::string>();
      if (u.rfind("data:", 0) == 0) {
        const auto comma = u.find(',');
        if (comma == std::string::npos || u.find(";base64", 0) > comma)
          fail(at + ".uri", "a data URI must be base64");
        available = (u.size() - comma - 1) / 4 * 3;
      } else {
        std::error_code ec;
        const auto p = (std::filesystem::path(folder_) / u).lexically_normal();
        if (p.parent_path() != std::filesystem::path(folder_).lexically_normal() ||
            !std::filesystem::is_regular_file(p, ec))
          fail(at + ".uri", "must name a file in the mesh file's own folder");
        available = std::filesystem::file_size(p, ec);
      }
      out["uri"] = u;
    } else {
      if (i != 0 || bin_bytes_ < 0) fail(at, "no uri (only a .glb's first buffer may have none)");
      available = static_cast<std::uint64_t>(bin_bytes_);
    }
    if (length > available)
      fail(at + ".byteLength",
           std::to_string(length) + " bytes, more than its data's " + std::to_string(available));
    sizes_.push_back(length);
    return out;
  }

  json view(std::size_t i) {
    const std::string at = "bufferViews[" + std::to_string(i) + "]";
    const json& v = views_[i];
    const json* b = member(v, "buffer", at);
    if (b == nullptr) fail(at + ".buffer", "missing");
    const auto buf = index(*b, sizes_.size(), at + ".buffer");
    const auto offset = field(v, "byteOffset", at, sizes_[buf], 0, false);
    const auto length = field(v, "byteLength", at, sizes_[buf], 0, true);
    if (offset + length > sizes_[buf]) fail(at, "runs past the end of its buffer");
    json out = {{"buffer", buf}, {"byteOffset", offset}, {"byteLength", length}};
    const auto stride = field(v, "byteStride", at, 252, 0, false);
    if (stride != 0) {
      if (stride < 4 || stride % 4 != 0)
        fail(at + ".byteStride", "must be a multiple of 4 in 4..252");
      out["byteStride"] = stride;
    }
    view_lengths_.push_back(length);
    view_strides_.push_back(stride);
    return out;
  }

  json accessor(std::size_t i) {
    const std::string at = "accessors[" + std::to_string(i) + "]";
    const json& a = accessors_[i];
    if (member(a, "sparse", at) != nullptr) fail(at + ".sparse", "sparse accessors are not read");
    const json* vp = member(a, "bufferView", at);
    if (vp == nullptr) fail(at + ".bufferView", "missing (glint reads accessors with data only)");
    const auto v = index(*vp, view_lengths_.size(), at + ".bufferView");
    const json* ct = member(a, "componentType", at);
    const int type = ct != nullptr && ct->is_number_integer() ? ct->get<int>() : 0;
    const int component = type == 5120 || type == 5121   ? 1
                          : type == 5122 || type == 5123 ? 2
                          : type == 5125 || type == 5126 ? 4
                                                         : 0;
    if (component == 0) fail(at + ".componentType", "must be 5120..5123, 5125 or 5126");
    const json* tp = member(a, "type", at);
    const std::string t = tp != nullptr && tp->is_string() ? tp->get<std::string>() : "";
    const int n = t == "SCALAR" ? 1 : t == "VEC2" ? 2 : t == "VEC3" ? 3 : t == "VEC4" ? 4 : 0;
    if (n == 0) fail(at + ".type", "must be SCALAR, VEC2, VEC3 or VEC4");
    const auto count = field(a, "count", at, std::uint64_t{1} << 32, 0, true);
    const auto offset = field(a, "byteOffset", at, view_lengths_[v], 0, false);
    const std::uint64_t element = std::uint64_t(component) * n;
    const std::uint64_t stride = view_strides_[v] != 0 ? view_strides_[v] : element;
    if (count > 0 && offset + (count - 1) * stride + element > view_lengths_[v])
      fail(at, "its " + std::to_string(count) + " elements run past the end of its buffer view");
    accessor_info_.push_back({type, n, count});
    json out = {{"bufferView", v},
                {"componentType", type},
                {"type", t},
                {"count", count},
                {"byteOffset", offset}};
    if (const json* nm = member(a, "normalized", at); nm != nullptr && nm->is_boolean())
      out["normalized"] = *nm;
    return out;
  }

  json mesh(const json& m, std::size_t i) const {
    const std::string at = "meshes[" + std::to_string(i) + "]";
    const json* prims = member(m, "primitives", at);
    if (prims == nullptr || !prims->is_array() || prims->empty())
      fail(at + ".primitives", "must be a non-empty array");
    json out = {{"primitives", json::array()}};
    for (std::size_t k = 0; k < prims->size(); ++k) {
      const std::string pat = at + ".primitives[" + std::to_string(k) + "]";
      const json& p = (*prims)[k];
      const auto mode = field(p, "mode", pat, 6, 4, false);
      if (mode < 4) fail(pat + ".mode", "points and lines are not read (glint reads 4, 5, 6)");
      const json* attrs = member(p, "attributes", pat);
      if (attrs == nullptr || !attrs->is_object()) fail(pat + ".attributes", "missing");
      json pout = {{"mode", mode}, {"attributes", json::object()}};
      std::uint64_t vertices = 0;
      for (const char* name : {"POSITION", "NORMAL"}) {
        const json* a = member(*attrs, name, pat + ".attributes");
        if (a == nullptr) {
          if (std::string(name) == "POSITION") fail(pat + ".attributes.POSITION", "missing");
          continue;
        }
        const std::string aat = pat + ".attributes." + name;
        const auto ai = index(*a, accessor_info_.size(), aat);
        const Info& info = accessor_info_[ai];
        if (info.type != 5126 || info.n != 3) fail(aat, "must be a VEC3 of floats (5126)");
        if (std::string(name) == "POSITION")
          vertices = info.count;
        else if (info.count != vertices)
          fail(aat, "has another count than POSITION");
        pout["attributes"][name] = ai;
      }
      if (const json* ix = member(p, "indices", pat)) {
        const auto ii = index(*ix, accessor_info_.size(), pat + ".indices");
        const Info& info = accessor_info_[ii];
        if (info.n != 1 || (info.type != 5121 && info.type != 5123 && info.type != 5125))
          fail(pat + ".indices", "must be a SCALAR of 5121, 5123 or 5125");
        pout["indices"] = ii;
      }
      out["primitives"].push_back(pout);
    }
    return out;
  }

  json node(const json& n, std::size_t i, std::size_t nodes, std::size_t meshes) const {
    const std::string at = "nodes[" + std::to_string(i) + "]";
    json out = json::object();
    if (const json* m = member(n, "mesh", at)) out["mesh"] = index(*m, meshes, at + ".mesh");
    if (const json* c = member(n, "children", at)) {
      if (!c->is_array()) fail(at + ".children", "must be an array");
      out["children"] = json::array();
      for (std::size_t k = 0; k < c->size(); ++k)
        out["children"].push_back(index((*c)[k], nodes, at + ".children"));
    }
    const auto numbers = [&](const char* key, std::size_t count) {
      const json* v = member(n, key, at);
      if (v == nullptr) return;
      if (!v->is_array() || v->size() != count)
        fail(at + "." + key, "must be an array of " + std::to_string(count) + " numbers");
      for (const json& x : *v)
        if (!x.is_number()) fail(at + "." + key, "must be an array of numbers");
      out[key] = *v;
    };
    numbers("matrix", 16);
    numbers("translation", 3);
    numbers("rotation", 4);
    numbers("scale", 3);
    return out;
  }

  // glTF's nodes form trees: no node is the child of two, none its own ancestor.
  void check_tree(const json& nodes) const {
    std::vector<int> parents(nodes.size(), 0);
    for (const json& n : nodes)
      if (n.contains("children"))
        for (const json& c : n["children"])
          if (++parents[c.get<std::size_t>()] > 1)
            fail("nodes[" + std::to_string(c.get<std::size_t>()) + "]",
                 "is the child of more than one node");
    // With one parent each, a cycle is a set of nodes no root reaches.
    std::vector<bool> seen(nodes.size(), false);
    std::vector<std::size_t> stack;
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (parents[i] == 0) stack.push_back(i);
    while (!stack.empty()) {
      const std::size_t i = stack.back();
      stack.pop_back();
      seen[i] = true;
      if (nodes[i].contains("children"))
        for (const json& c : nodes[i]["children"]) stack.push_back(c.get<std::size_t>());
    }
    for (std::size_t i = 0; i < nodes.size(); ++i)
      if (!seen[i]) fail("nodes[" + std::to_string(i) + "]", "is in a cycle of children");
  }

  struct Info {
    int type, n;
    std::uint64_t count;
  };
  const json& doc_;
  std::int64_t bin_bytes_;
  std::string folder_;
  const std::string& path_;
  json buffers_, views_, accessors_;
  std::vector<std::uint64_t> sizes_, view_lengths_, view_strides_;
  std::vector<Info> accessor_info_;
};

}  // namespace

std::string reduce_gltf(const std::string& text, std::int64_t bin_bytes, const std::string& folder,
                        const std::string& path) {
  // Depth checked on the text before parsing (64 levels; glTF needs 6), duplicates refused.
  const json doc = parse_json_text(text, path, 64);
  return Reducer(doc, bin_bytes, folder, path).run().dump();
}

}  // namespace glint
