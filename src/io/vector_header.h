// The header of a vector file (traces/README.md, "Header"): from the magic line through `data`.
#pragma once

#include <cstdint>
#include <vector>

#include "io/line_reader.h"
#include "io/vectors.h"

namespace glint {

// The row fields a `columns` line can list.
enum class VectorColumn : std::uint8_t { kT, kMaterial, kLight, kX, kY };
const char* column_name(VectorColumn column);  // as spelt in the file: "t", "material", ...

// A header as read from a file: the public VectorHeader plus the order of the row fields, which
// only the row parser needs.
struct VectorFileHeader {
  VectorHeader header;  // light_intensity has exactly `lights` entries
  std::vector<VectorColumn> columns;
};

// Reads header lines from `lines` up to and including `data`, leaving it at the first row.
// Throws InputError for anything the format refuses.
VectorFileHeader read_vector_header(LineReader& lines);

}  // namespace glint
