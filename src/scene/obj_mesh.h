// OBJ meshes through tinyobjloader: positions, normals and faces only (materials come from the
// scene, .mtl files are never opened). Every face vertex must name a normal (`f v//vn` or
// `f v/vt/vn`): glint does not invent normals. Polygons are split into fans (convex polygons).
#pragma once

#include <cstddef>
#include <string>

#include "scene/mesh_file.h"
#include "scene/scene.h"

namespace glint {

// Loads `path` into a Mesh with one vertex per distinct (position, normal) index pair, in order
// of first use. Throws InputError naming `path` for anything wrong inside the file, or when the
// mesh would have more than `max_triangles` triangles or the file crosses `limits` (scan_obj: with
// the line, before tinyobjloader reads it); the caller reports a missing file.
Mesh load_obj_mesh(const std::string& path, std::size_t max_triangles,
                   const ObjLimits& limits = ObjLimits{});

}  // namespace glint
