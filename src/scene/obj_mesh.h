// OBJ meshes through tinyobjloader: positions, normals and faces only (materials come from the
// scene, .mtl files are never opened). When every face vertex names a normal (`f v//vn` or
// `f v/vt/vn`) the file's normals are used; otherwise every normal is generated
// (smooth_normals.h). Polygons are split into fans (convex polygons). OBJ stays on tinyobjloader
// rather than Assimp: a first pass of glint's own (scan_obj) names the line of every bad number
// and limit, where Assimp's OBJ reader gives no line and reads `nan` as a number.
#pragma once

#include <cstddef>
#include <string>

#include "scene/mesh_file.h"
#include "scene/scene.h"

namespace glint {

// Loads `path` into a Mesh with one vertex per distinct (position, normal) index pair, in order
// of first use, or, without normals, smooth_normals' vertices with `crease_degrees`. Throws
// InputError naming `path` for anything wrong inside the file, or when the mesh would have more
// than `max_triangles` triangles or the file crosses `limits` (scan_obj: with the line, before
// tinyobjloader reads it); the caller reports a missing file.
Mesh load_obj_mesh(const std::string& path, std::size_t max_triangles,
                   const ObjLimits& limits = ObjLimits{},
                   double crease_degrees = kSceneDefaultCreaseDegrees);

}  // namespace glint
