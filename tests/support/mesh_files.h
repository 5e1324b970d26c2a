// Small mesh files written by the tests, in every format glint reads: the same triangles as OBJ,
// PLY (ASCII and binary), STL (ASCII and binary) and glTF 2.0 (.gltf with an embedded or an
// external buffer, .glb). Coordinates are written as float32 where the format is binary, so tests
// use coordinates a float holds exactly.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

namespace glint::test {

struct MeshData {
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<float, 3>> normals;  // empty, or one per position
  std::vector<std::array<std::uint32_t, 3>> faces;
};

inline std::string fmt_float(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(v));
  return buf;
}

inline std::string to_obj(const MeshData& m) {
  std::string s = "# test mesh\n";
  for (const auto& p : m.positions)
    s += "v " + fmt_float(p[0]) + " " + fmt_float(p[1]) + " " + fmt_float(p[2]) + "\n";
  for (const auto& n : m.normals)
    s += "vn " + fmt_float(n[0]) + " " + fmt_float(n[1]) + " " + fmt_float(n[2]) + "\n";
  for (const auto& f : m.faces) {
    s += "f";
    for (const std::uint32_t v : f)
      s += " " + std::to_string(v + 1) + (m.normals.empty() ? "" : "//" + std::to_string(v + 1));
    s += "\n";
  }
  return s;
}

inline std::string to_ply_ascii(const MeshData& m) {
  const bool n = !m.normals.empty();
  std::string s = "ply\nformat ascii 1.0\nelement vertex " + std::to_string(m.positions.size()) +
                  "\nproperty float x\nproperty float y\nproperty float z\n";
  if (n) s += "property float nx\nproperty float ny\nproperty float nz\n";
  s += "element face " + std::to_string(m.faces.size()) +
       "\nproperty list uchar int vertex_indices\nend_header\n";
  for (std::size_t i = 0; i < m.positions.size(); ++i) {
    const auto& p = m.positions[i];
    s += fmt_float(p[0]) + " " + fmt_float(p[1]) + " " + fmt_float(p[2]);
    if (n) {
      for (const float c : m.normals[i]) s += " " + fmt_float(c);
    }
    s += "\n";
  }
  for (const auto& f : m.faces)
    s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) +
         "\n";
  return s;
}

template <typename T>
void put_le(std::string& s, T v) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));  // the tests run on little-endian machines (x86-64, arm64)
  s.append(b, sizeof(T));
}

inline std::string to_ply_binary(const MeshData& m) {
  std::string s =
      "ply\nformat binary_little_endian 1.0\nelement vertex " + std::to_string(m.positions.size()) +
      "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
      std::to_string(m.faces.size()) + "\nproperty list uchar int vertex_indices\nend_header\n";
  for (const auto& p : m.positions)
    for (const float c : p) put_le(s, c);
  for (const auto& f : m.faces) {
    s += '\3';
    for (const std::uint32_t v : f) put_le(s, static_cast<std::int32_t>(v));
  }
  return s;
}

inline std::array<float, 3> facet_normal(const MeshData& m, const std::array<std::uint32_t, 3>& f) {
  const auto& a = m.positions[f[0]];
  const auto& b = m.positions[f[1]];
  const auto& c = m.positions[f[2]];
  const float u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
  const float v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
}

inline std::string to_stl_ascii(const MeshData& m) {
  std::string s = "solid test\n";
  for (const auto& f : m.faces) {
    const auto n = facet_normal(m, f);
    s += "facet normal " + fmt_float(n[0]) + " " + fmt_float(n[1]) + " " + fmt_float(n[2]) +
         "\n outer loop\n";
    for (const std::uint32_t v : f) {
      const auto& p = m.positions[v];
      s += "  vertex " + fmt_float(p[0]) + " " + fmt_float(p[1]) + " " + fmt_float(p[2]) + "\n";
    }
    s += " endloop\nendfacet\n";
  }
  return s + "endsolid test\n";
}

inline std::string to_stl_binary(const MeshData& m) {
  std::string s(80, ' ');
  s.replace(0, 11, "binary test");
  put_le(s, static_cast<std::uint32_t>(m.faces.size()));
  for (const auto& f : m.faces) {
    for (const float c : facet_normal(m, f)) put_le(s, c);
    for (const std::uint32_t v : f)
      for (const float c : m.positions[v]) put_le(s, c);
    put_le(s, std::uint16_t{0});
  }
  return s;
}

// The binary buffer of a glTF: positions, [normals,] then uint32 indices.
inline std::string gltf_buffer(const MeshData& m) {
  std::string b;
  for (const auto& p : m.positions)
    for (const float c : p) put_le(b, c);
  for (const auto& n : m.normals)
    for (const float c : n) put_le(b, c);
  for (const auto& f : m.faces)
    for (const std::uint32_t v : f) put_le(b, v);
  return b;
}

inline std::string base64(const std::string& in) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  std::size_t i = 0;
  for (; i + 2 < in.size(); i += 3) {
    const std::uint32_t v = static_cast<std::uint8_t>(in[i]) << 16 |
                            static_cast<std::uint8_t>(in[i + 1]) << 8 |
                            static_cast<std::uint8_t>(in[i + 2]);
    for (int s = 18; s >= 0; s -= 6) out += k[v >> s & 63];
  }
  if (i + 1 == in.size()) {
    const std::uint32_t v = static_cast<std::uint8_t>(in[i]) << 16;
    out += std::string{k[v >> 18 & 63], k[v >> 12 & 63]} + "==";
  } else if (i + 2 == in.size()) {
    const std::uint32_t v =
        static_cast<std::uint8_t>(in[i]) << 16 | static_cast<std::uint8_t>(in[i + 1]) << 8;
    out += std::string{k[v >> 18 & 63], k[v >> 12 & 63], k[v >> 6 & 63]} + "=";
  }
  return out;
}

// The glTF JSON; `uri` is the buffer's (empty: none, the buffer of a .glb).
inline std::string gltf_json(const MeshData& m, const std::string& uri) {
  float lo[3] = {m.positions[0][0], m.positions[0][1], m.positions[0][2]};
  float hi[3] = {lo[0], lo[1], lo[2]};
  for (const auto& p : m.positions)
    for (int i = 0; i < 3; ++i) {
      lo[i] = std::min(lo[i], p[i]);
      hi[i] = std::max(hi[i], p[i]);
    }
  const std::size_t nv = m.positions.size(), pos_bytes = nv * 12;
  const std::size_t nrm_bytes = m.normals.size() * 12, idx_bytes = m.faces.size() * 12;
  const std::size_t total = pos_bytes + nrm_bytes + idx_bytes;
  const auto num = [](std::size_t v) { return std::to_string(v); };
  std::string views = "{\"buffer\":0,\"byteOffset\":0,\"byteLength\":" + num(pos_bytes) + "}";
  std::string accessors = "{\"bufferView\":0,\"componentType\":5126,\"count\":" + num(nv) +
                          ",\"type\":\"VEC3\",\"min\":[" + fmt_float(lo[0]) + "," +
                          fmt_float(lo[1]) + "," + fmt_float(lo[2]) + "],\"max\":[" +
                          fmt_float(hi[0]) + "," + fmt_float(hi[1]) + "," + fmt_float(hi[2]) + "]}";
  std::string attributes = "{\"POSITION\":0";
  std::size_t index_accessor = 1;
  if (!m.normals.empty()) {
    views += ",{\"buffer\":0,\"byteOffset\":" + num(pos_bytes) +
             ",\"byteLength\":" + num(nrm_bytes) + "}";
    accessors +=
        ",{\"bufferView\":1,\"componentType\":5126,\"count\":" + num(nv) + ",\"type\":\"VEC3\"}";
    attributes += ",\"NORMAL\":1";
    index_accessor = 2;
  }
  attributes += "}";
  views += ",{\"buffer\":0,\"byteOffset\":" + num(pos_bytes + nrm_bytes) +
           ",\"byteLength\":" + num(idx_bytes) + "}";
  accessors += ",{\"bufferView\":" + num(index_accessor) +
               ",\"componentType\":5125,\"count\":" + num(m.faces.size() * 3) +
               ",\"type\":\"SCALAR\"}";
  const std::string buffer =
      "{\"byteLength\":" + num(total) + (uri.empty() ? "" : ",\"uri\":\"" + uri + "\"") + "}";
  return "{\"asset\":{\"version\":\"2.0\"},\"scene\":0,\"scenes\":[{\"nodes\":[0]}],"
         "\"nodes\":[{\"mesh\":0}],\"meshes\":[{\"primitives\":[{\"attributes\":" +
         attributes + ",\"indices\":" + num(index_accessor) + ",\"mode\":4}]}],\"buffers\":[" +
         buffer + "],\"bufferViews\":[" + views + "],\"accessors\":[" + accessors + "]}";
}

inline std::string to_gltf_embedded(const MeshData& m) {
  return gltf_json(m, "data:application/octet-stream;base64," + base64(gltf_buffer(m)));
}

inline std::string to_glb(const MeshData& m) {
  std::string json = gltf_json(m, "");
  while (json.size() % 4 != 0) json += ' ';
  std::string bin = gltf_buffer(m);
  while (bin.size() % 4 != 0) bin += '\0';
  std::string s = "glTF";
  put_le(s, std::uint32_t{2});
  put_le(s, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  put_le(s, static_cast<std::uint32_t>(json.size()));
  s += "JSON" + json;
  put_le(s, static_cast<std::uint32_t>(bin.size()));
  s += std::string("BIN\0", 4) + bin;
  return s;
}

}  // namespace glint::test
