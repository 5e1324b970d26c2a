// PLY meshes (ASCII, binary little- and big-endian) read by glint itself. Assimp 5.2's PLY reader
// hangs on some malformed bodies and aborts in its triangulation on others (both found by
// tests/fuzz/fuzz_mesh in its first minutes); a reader of our own also names the line of an
// ASCII file's errors, as OBJ's do.
#pragma once

#include <cstddef>
#include <string>

#include "scene/mesh_file.h"
#include "scene/scene.h"

namespace glint {

// Loads the PLY file `path`: the `vertex` element's x, y, z and, when it has all three, nx, ny,
// nz (then the file's normals, else generated with `crease_degrees`); the `face` element's
// `vertex_indices` (or `vertex_index`) lists, polygons as fans from their first corner; other
// elements and properties are read past. Limits as for OBJ: the byte size before reading, the
// header's counts before the body, at most max_triangles triangles. Throws InputError naming
// `path`, the line for ASCII files, and the element: field "header", "vertex", "normal" or "f".
Mesh load_ply_mesh(const std::string& path, std::size_t max_triangles,
                   const ObjLimits& limits = ObjLimits{},
                   double crease_degrees = kSceneDefaultCreaseDegrees);

}  // namespace glint
