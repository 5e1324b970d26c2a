// Vertex normals for a mesh file without them: angle-weighted, with a crease angle.
//
// Each corner's normal is the sum of the unit normals of the faces around its position, each
// weighted by the face's angle at that corner (Thürmer & Wüthrich, "Computing Vertex Normals from
// Polygonal Facets", 1998: unlike area weights, the result does not change when a face is split),
// over the faces whose normal is within the crease angle of the corner's own face; faces meeting
// at more than the crease angle keep apart, so a box keeps its edges. Positions are shared by
// value (a file that repeats a vertex per face, as STL does, is smoothed the same as one that
// indexes it); each distinct (position, normal) becomes one vertex of the result.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene.h"

namespace glint {

// At most this many differently oriented faces may share one position (the work per position
// grows with its square): a cone's apex of 1024 sides is far beyond any real mesh's valence.
inline constexpr std::size_t kMaxNormalsPerPosition = 1024;

// The mesh of `faces` (indices into `positions`, counter-clockwise) with generated normals:
// positions, normals and faces filled in, normal_source kGenerated, crease_degrees set; faces of
// zero area (no ray can hit them, and they have no normal) are dropped. crease_degrees is in
// [0, 180]. Throws InputError(path, 0, "f", ...) when no face has an area, or when a position is
// shared by more than kMaxNormalsPerPosition face normals (naming the vertex).
Mesh smooth_normals(const std::vector<Vec3>& positions,
                    const std::vector<std::array<std::uint32_t, 3>>& faces, double crease_degrees,
                    const std::string& path);

// A mesh file's triangles: with the file's normals (one per position) when `file_normals`,
// normal_source kFile; else smooth_normals' of them with `crease_degrees`.
Mesh mesh_with_normals(std::vector<Vec3> positions, std::vector<Vec3> normals,
                       std::vector<std::array<std::uint32_t, 3>> faces, bool file_normals,
                       double crease_degrees, const std::string& path);

}  // namespace glint
