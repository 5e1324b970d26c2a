// Bounds on the mesh files a scene names (OBJ meshes, Bezier patch files), checked as they stream
// in: the byte size before anything is read, then counts and numbers line by line, so a file
// beyond a limit is refused with its line before its contents take memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <string>

namespace glint {

// At most 4 GiB per OBJ file: a mesh at the scene's 20 000 000 triangles, written with shared
// vertices and full-precision numbers, is about 1.7 GB (about 85 bytes per triangle).
inline constexpr std::uint64_t kSceneMaxObjBytes = std::uint64_t{4} << 30;
// Each of v, vn and vt at most 3 per triangle of the scene's limit: a mesh whose triangles share
// no vertex (60 000 000).
inline constexpr std::uint64_t kSceneMaxObjVertices = 60'000'000;
// A patch file at the 65 536-patch limit with 17-digit coordinates is about 61 MB (930 bytes a
// patch); twice that leaves room for comments. Reading takes constant memory (LineReader) and the
// patches 400 bytes each, so the cap bounds the time a file of comments can take.
inline constexpr std::uint64_t kSceneMaxPatchFileBytes = std::uint64_t{128} << 20;

// The limits an OBJ file is read under. Tests lower them to reach them with small files.
struct ObjLimits {
  std::uint64_t max_bytes = kSceneMaxObjBytes;
  std::uint64_t max_vertices = kSceneMaxObjVertices;  // each of v, vn, vt
};

// Throws InputError(path, 0, "file", ...) when the file at `path` is larger than `max_bytes`
// (or its size cannot be read); `what` names the kind of file in the message.
void check_file_bytes(const std::string& path, std::uint64_t max_bytes, const char* what);

// Reads `in` (the OBJ file `path`) to its end, line by line in constant memory, and throws
// InputError at the first line that crosses a limit: more than limits.max_bytes bytes (field
// "file"), more than max_triangles triangles in its faces ("f", each face of n >= 3 vertices
// counting n - 2), more than limits.max_vertices `v`, `vn` or `vt` lines (that field), or a `v`,
// `vn` or `vt` whose coordinates are not finite decimal numbers (nan, inf, 1e999, text). Lines are
// at most 4096 bytes and hold no NUL byte ("line"). tinyobjloader, which reads the file after
// this, has no limits and reads a number it cannot parse (nan, inf) as 0.
void scan_obj(std::istream& in, const std::string& path, std::size_t max_triangles,
              const ObjLimits& limits);

}  // namespace glint
