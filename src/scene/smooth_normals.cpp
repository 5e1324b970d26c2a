#include "scene/smooth_normals.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <unordered_map>
#include <utility>

#include "io/input_error.h"

namespace glint {

namespace {

constexpr double kPi = 3.14159265358979323846;

// a / |a| without overflow for any finite a (coordinates may be up to the largest double).
Vec3 unit(Vec3 a) {
  const double m = std::max({std::abs(a.x), std::abs(a.y), std::abs(a.z)});
  if (m == 0) return {};
  return normalize(Vec3{a.x / m, a.y / m, a.z / m});
}

double angle_between(Vec3 u, Vec3 v) {
  const Vec3 a = unit(u), b = unit(v);
  return std::atan2(length(cross(a, b)), dot(a, b));
}

// Positions are shared by value; -0 and +0 are the same place.
struct PositionKey {
  std::uint64_t bits[3];
  explicit PositionKey(Vec3 p) {
    const double c[3] = {p.x + 0.0, p.y + 0.0, p.z + 0.0};
    std::memcpy(bits, c, sizeof bits);
  }
  bool operator==(const PositionKey& o) const {
    return bits[0] == o.bits[0] && bits[1] == o.bits[1] && bits[2] == o.bits[2];
  }
};
struct PositionHash {
  std::size_t operator()(const PositionKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (const std::uint64_t b : k.bits) h = (h ^ b) * 1099511628211ull ^ (b >> 29);
    return static_cast<std::size_t>(h);
  }
};

bool same(Vec3 a, Vec3 b) {
  return a.x == b.x && a.y == b.y && a.z == b.z;
}

// A face normal at one position and the sum of the angle-weighted normals of the faces around
// that position with exactly this normal (a flat fan is one group).
struct Group {
  Vec3 normal, weighted;
  std::uint32_t vertex = UINT32_MAX;  // the output vertex, made on first use
};

}  // namespace

Mesh smooth_normals(const std::vector<Vec3>& positions,
                    const std::vector<std::array<std::uint32_t, 3>>& faces, double crease_degrees,
                    const std::string& path) {
  // Weld: one id per distinct position value.
  std::unordered_map<PositionKey, std::uint32_t, PositionHash> id_of;
  std::vector<std::uint32_t> weld(positions.size());
  std::vector<Vec3> welded;
  std::vector<std::size_t> file_index;  // of each welded position's first vertex
  for (std::size_t i = 0; i < positions.size(); ++i) {
    const auto [it, added] =
        id_of.emplace(PositionKey(positions[i]), static_cast<std::uint32_t>(welded.size()));
    if (added) {
      welded.push_back(positions[i]);
      file_index.push_back(i);
    }
    weld[i] = it->second;
  }

  // The faces with an area: their corners (welded), unit normals and corner angles.
  struct Face {
    std::array<std::uint32_t, 3> w;
    Vec3 normal;
    double angle[3];
  };
  std::vector<Face> kept;
  kept.reserve(faces.size());
  for (const auto& f : faces) {
    const Vec3 a = positions[f[0]], b = positions[f[1]], c = positions[f[2]];
    const Vec3 n = unit(cross(unit(b - a), unit(c - a)));
    if (length(n) == 0) continue;
    kept.push_back(
        {{weld[f[0]], weld[f[1]], weld[f[2]]},
         n,
         {angle_between(b - a, c - a), angle_between(c - b, a - b), angle_between(a - c, b - c)}});
  }
  if (kept.empty()) throw InputError(path, 0, "f", "no face has an area (a mesh needs triangles)");

  // The faces around each welded position (compressed rows).
  std::vector<std::uint32_t> first(welded.size() + 1, 0);
  for (const Face& f : kept)
    for (const std::uint32_t w : f.w) ++first[w + 1];
  for (std::size_t i = 0; i < welded.size(); ++i) first[i + 1] += first[i];
  std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
  std::vector<std::uint32_t> around(first.back());
  std::vector<std::uint8_t> corner_of(first.back());
  for (std::uint32_t fi = 0; fi < kept.size(); ++fi)
    for (std::uint8_t k = 0; k < 3; ++k) {
      const std::uint32_t slot = fill[kept[fi].w[k]]++;
      around[slot] = fi;
      corner_of[slot] = k;
    }

  // Per position, the groups of equal face normals; each face corner's group.
  const double cos_crease = std::cos(crease_degrees * kPi / 180);
  std::vector<std::uint32_t> group_first(welded.size() + 1, 0);
  std::vector<Group> groups;
  std::vector<std::uint32_t> corner_group(kept.size() * 3);
  for (std::uint32_t w = 0; w < welded.size(); ++w) {
    const std::size_t begin = groups.size();
    for (std::uint32_t s = first[w]; s < first[w + 1]; ++s) {
      const Face& f = kept[around[s]];
      const std::uint8_t k = corner_of[s];
      std::size_t g = begin;
      while (g < groups.size() && !same(groups[g].normal, f.normal)) ++g;
      if (g == groups.size()) {
        if (g - begin == kMaxNormalsPerPosition) {
          throw InputError(path, 0, "f",
                           "vertex " + std::to_string(file_index[w] + 1) +
                               " is shared by faces of more than " +
                               std::to_string(kMaxNormalsPerPosition) +
                               " orientations; glint generates normals only up to that (give "
                               "the file its normals)");
        }
        groups.push_back({f.normal, {}, UINT32_MAX});
      }
      groups[g].weighted = groups[g].weighted + f.normal * f.angle[k];
      corner_group[3 * std::size_t{around[s]} + k] = static_cast<std::uint32_t>(g);
    }
    group_first[w + 1] = static_cast<std::uint32_t>(groups.size());
  }

  // Each group's normal: the weighted normals of the groups within the crease angle of its own.
  std::vector<Vec3> group_normal(groups.size());
  for (std::uint32_t w = 0; w < welded.size(); ++w) {
    for (std::uint32_t g = group_first[w]; g < group_first[w + 1]; ++g) {
      Vec3 sum;
      for (std::uint32_t h = group_first[w]; h < group_first[w + 1]; ++h)
        if (dot(groups[g].normal, groups[h].normal) >= cos_crease) sum = sum + groups[h].weighted;
      // Faces folded back onto each other (within a crease angle near 180) can cancel: the
      // corner then keeps its face's normal.
      const Vec3 n = unit(sum);
      group_normal[g] = length(n) > 0 ? n : groups[g].normal;
    }
  }

  Mesh mesh;
  mesh.normal_source = NormalSource::kGenerated;
  mesh.crease_degrees = crease_degrees;
  mesh.faces.reserve(kept.size());
  for (std::size_t fi = 0; fi < kept.size(); ++fi) {
    std::array<std::uint32_t, 3> face{};
    for (std::size_t k = 0; k < 3; ++k) {
      const std::uint32_t w = kept[fi].w[k], gi = corner_group[3 * fi + k];
      Group& g = groups[gi];
      if (g.vertex == UINT32_MAX) {
        // Groups of one position that came out with the same normal share a vertex.
        for (std::uint32_t h = group_first[w]; h < group_first[w + 1]; ++h)
          if (groups[h].vertex != UINT32_MAX && same(group_normal[h], group_normal[gi])) {
            g.vertex = groups[h].vertex;
            break;
          }
      }
      if (g.vertex == UINT32_MAX) {
        g.vertex = static_cast<std::uint32_t>(mesh.positions.size());
        mesh.positions.push_back(welded[w]);
        mesh.normals.push_back(group_normal[gi]);
      }
      face[k] = g.vertex;
    }
    mesh.faces.push_back(face);
  }
  return mesh;
}

Mesh mesh_with_normals(std::vector<Vec3> positions, std::vector<Vec3> normals,
                       std::vector<std::array<std::uint32_t, 3>> faces, bool file_normals,
                       double crease_degrees, const std::string& path) {
  if (!file_normals) return smooth_normals(positions, faces, crease_degrees, path);
  Mesh out;
  out.positions = std::move(positions);
  out.normals = std::move(normals);
  out.faces = std::move(faces);
  out.normal_source = NormalSource::kFile;
  return out;
}

}  // namespace glint
