// Bicubic Bezier patches (Newell's teapot) and their tessellation into a smooth-shaded mesh.
//
// Patch files (.bpt, documented in traces/scenes/README.md): the number of patches, then per
// patch a line "3 3" (the degrees in u and v: only bicubic patches) and 16 lines "x y z", the
// control points row by row (u major). '#' starts a comment, blank lines are ignored.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scene/mesh_file.h"
#include "scene/scene.h"
#include "scene/vec3.h"

namespace glint {

inline constexpr std::size_t kSceneMaxBezierPatches = 65536;
inline constexpr int kSceneMaxBezierSubdivisions = 256;

using BezierPatch = std::array<Vec3, 16>;  // control point (i, j) at [4 * i + j], i along u

// Throws InputError naming `path` and the 1-based line, or with field "file" and no line when the
// file is larger than `max_bytes` (checked before it is read).
std::vector<BezierPatch> read_bezier_patches(const std::string& path,
                                             std::uint64_t max_bytes = kSceneMaxPatchFileBytes);

// Each patch as subdivisions x subdivisions quads, two triangles each (a quad collapsed at a pole
// keeps its zero-area triangle: the count is always patches * subdivisions^2 * 2). Normals are
// dP/dv x dP/du normalised (outwards on the teapot); where a derivative vanishes (the lid's and
// bottom's poles) they are taken slightly inside the patch. Windings follow the normals. Throws
// InputError (naming `path`) for a patch that is degenerate everywhere, std::invalid_argument
// unless subdivisions >= 1 and the vertices fit 32-bit indices.
Mesh tessellate_bezier(const std::vector<BezierPatch>& patches, int subdivisions,
                       const std::string& path);

// The surface point and the partial derivatives at (u, v) in [0, 1]^2.
struct PatchPoint {
  Vec3 p, du, dv;
};
PatchPoint evaluate(const BezierPatch& patch, double u, double v);

}  // namespace glint
