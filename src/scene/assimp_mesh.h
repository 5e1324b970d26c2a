// Mesh files by format: glTF 2.0 (.gltf, .glb) and STL through Assimp (Debian libassimp-dev), PLY
// through glint's own reader (ply_mesh.h: Assimp 5.2's hangs and aborts on malformed files), OBJ
// through tinyobjloader (obj_mesh.h), whose first pass names the line of every error.
#pragma once

#include <cstddef>
#include <string>

#include "scene/mesh_file.h"
#include "scene/scene.h"

namespace glint {

enum class MeshFormat : std::uint8_t { kObj, kPly, kGltf, kGlb, kStl };
const char* to_string(MeshFormat format);  // "obj", "ply", "gltf", "glb", "stl"

// The format of the mesh file `path`, by its extension (case-insensitive). An unknown extension
// is an InputError (field "file") naming the formats glint reads, and, when the content starts
// like one of them (PLY's "ply", glb's "glTF"), the extension to give it.
MeshFormat mesh_format(const std::string& path);

// Loads a mesh file of `format` into one mesh in the file's own coordinates, every node transform
// of a glTF scene applied (OBJ: load_obj_mesh, PLY: load_ply_mesh). Normals come from the file
// when every vertex has one (STL's facet normals are not vertex normals: they are never used),
// else they are generated (smooth_normals.h) with `crease_degrees`. Limits as for OBJ: the byte
// size before reading, a binary STL's triangle count before Assimp reads it, then the triangles
// and vertices read; every coordinate and normal finite. Throws InputError naming `path` and the
// element (field "vertex", "normal", "f", "file", "header" for PLY, or "mesh": Assimp's error).
Mesh load_mesh_file(const std::string& path, MeshFormat format, std::size_t max_triangles,
                    const ObjLimits& limits = ObjLimits{},
                    double crease_degrees = kSceneDefaultCreaseDegrees);

}  // namespace glint
