// A glTF 2.0 document reduced to what glint reads, every index and byte range checked, before
// Assimp sees it. Assimp 5.2's glTF2 importer dereferences what a document names without checking
// it (a primitive without POSITION crashed it: fuzz_mesh), so glint hands it a copy that holds
// only the scene, nodes, meshes (triangle primitives: POSITION, NORMAL, indices), accessors,
// buffer views and buffers, each checked.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace glint {

// `json` is the document (a .gltf file, or a .glb's JSON chunk); `bin_bytes` the size of a .glb's
// BIN chunk (or -1 without one); `folder` the mesh file's folder (external buffers must be files
// there). Returns the reduced document. Throws InputError(path, 0, "gltf", "<JSON path>: ...").
std::string reduce_gltf(const std::string& json, std::int64_t bin_bytes, const std::string& folder,
                        const std::string& path);

}  // namespace glint
