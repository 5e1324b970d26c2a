// Vector files v1: streams of shading requests for the specular units (format: traces/README.md).
//
// A vector file is a text header (format version, perceptibility threshold eps, number of lights,
// light intensities, materials, the row columns) followed by one row per shading request:
//
//   glint-vectors 1
//   eps 1e-3
//   lights 2
//   light 1 1,0.5,0.25
//   material gold specular=1,0.77,0.34 shininess=64 lobe=blinn
//   columns t material light
//   data
//   0.97 gold 1
//
// VectorReader streams the rows in constant memory (a fixed 1 MiB block buffer; no row is kept),
// parsing at several hundred MB/s. Every malformed input raises glint::InputError naming the file,
// the 1-based line and the field. VectorWriter writes the same format through an
// AtomicOutputFile, so a file either appears complete or not at all.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "io/input_error.h"
#include "reference/pixel_error.h"
#include "reference/reference.h"

namespace glint {

// The lobe of a material is the reference model's (reference.h).
using VectorLobe = Lobe;

// Format limits of version 1 (documented in traces/README.md). The reader, validate() and the
// writer check against these through io/vector_rules.h, and their messages quote them from here.
inline constexpr int kVectorFormatVersion = 1;
inline constexpr std::size_t kVectorMaxLineBytes = 4096;  // excluding "\n" / "\r\n"
inline constexpr int kVectorMaxLights = 1024;
inline constexpr std::size_t kVectorMaxMaterials = 65536;
inline constexpr std::size_t kVectorMaxNameLength = 64;
inline constexpr double kVectorTMin = -1.0;
inline constexpr double kVectorTMax = 1.001;        // 1 + 1e-3: slack for t computed in float
inline constexpr double kVectorMaxRoughness = 1.0;  // a Gaussian lobe's width is in (0, 1]

struct VectorMaterial {
  std::string name;  // [A-Za-z_][A-Za-z0-9_.-]*, at most kVectorMaxNameLength bytes
  std::array<double, 3> specular{1, 1, 1};  // linear RGB specular colour, finite, >= 0
  double shininess = 0;                     // phong/blinn: > 0; gaussian: > 0 or 0 = not given
  VectorLobe lobe = VectorLobe::kPhong;
  double roughness = 0;  // gaussian: in (0, 1]; phong/blinn: 0 (not allowed in the file)

  friend bool operator==(const VectorMaterial& a, const VectorMaterial& b) {
    return a.name == b.name && a.specular == b.specular && a.shininess == b.shininess &&
           a.lobe == b.lobe && a.roughness == b.roughness;
  }
  friend bool operator!=(const VectorMaterial& a, const VectorMaterial& b) { return !(a == b); }
};

struct VectorHeader {
  static constexpr std::size_t npos = static_cast<std::size_t>(-1);

  int version = kVectorFormatVersion;
  double eps = 0;  // perceptibility threshold, > 0
  int lights = 1;  // 1 .. kVectorMaxLights
  // Per-light RGB intensity. The reader always fills exactly `lights` entries (white 1,1,1 unless
  // a `light` line says otherwise). For the writer an empty vector means "all white".
  std::vector<std::array<double, 3>> light_intensity;
  std::vector<VectorMaterial> materials;  // at least one; names unique
  bool has_light = false;                 // rows carry a light index column
  bool has_xy = false;                    // rows carry pixel coordinates x y
  // The display the requests' pixel errors are measured in (reference/pixel_error.h): the
  // optional `display` line, linear8 when absent.
  DisplayEncoding display = DisplayEncoding::kLinear8;
  // What eps is a threshold of: not a line of the file but the run's --eps-measure, which the
  // command sets after reading the header.
  EpsMeasure eps_measure = EpsMeasure::kLuminance;

  // Index of the material called `name`, or npos.
  std::size_t material_index(std::string_view name) const;
  // Intensity of light `index` (white when light_intensity is empty).
  std::array<double, 3> intensity(int index) const;
};

// Throws std::invalid_argument naming the problem unless the header satisfies every rule the
// reader enforces (so whatever VectorWriter accepts, VectorReader reads back).
void validate(const VectorHeader& header);

struct VectorRow {
  double t = 0;                 // in [kVectorTMin, kVectorTMax]
  std::uint32_t material = 0;   // index into VectorHeader::materials
  std::int32_t light = 0;       // 0 when the file has no light column
  std::int32_t x = -1, y = -1;  // -1 when the file has no x y columns; otherwise >= 0
  std::uint64_t line = 0;       // 1-based source line (set by the reader; ignored by the writer)
};

class VectorReader {
 public:
  // Opens and reads the header; throws InputError (line 0, field "file" if it cannot be opened).
  // "-" is standard input (named "<stdin>" in errors).
  explicit VectorReader(const std::string& path);
  // Reads from `in` (which must outlive the reader); `name` is used as the file name in errors.
  VectorReader(std::istream& in, std::string name);
  // Reads from `in`, which the reader owns.
  VectorReader(std::unique_ptr<std::istream> in, std::string name);
  ~VectorReader();

  VectorReader(const VectorReader&) = delete;
  VectorReader& operator=(const VectorReader&) = delete;

  const VectorHeader& header() const;
  const std::string& name() const;

  // Reads the next row into `row`; false at the end of the data. Throws InputError on a malformed
  // row; after an error every further call rethrows the same error.
  bool next(VectorRow& row);
  // The rows of the next block of input (about a megabyte of it) into `rows` (cleared first),
  // parsed on up to `threads` threads; false at the end of the data. The rows, their line numbers
  // and errors are next()'s: the rows before a malformed one come back, and the next call throws.
  bool next_block(std::vector<VectorRow>& rows, int threads);
  // The same, the rows appended to those `rows` holds.
  bool append_block(std::vector<VectorRow>& rows, int threads);

  std::uint64_t rows_read() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

class VectorWriter {
 public:
  // Writes to a temporary file beside `path`, renamed to `path` by commit(). Throws
  // std::invalid_argument if the header is invalid, OutputError if the file can't be made.
  VectorWriter(const std::string& path, const VectorHeader& header);
  // Writes to `out` (which must outlive the writer; `name` names it in errors); commit() flushes
  // it.
  VectorWriter(std::ostream& out, const VectorHeader& header, std::string name = "<stream>");
  // Without commit(), a path writer removes its temporary file (no output appears).
  ~VectorWriter();

  VectorWriter(const VectorWriter&) = delete;
  VectorWriter& operator=(const VectorWriter&) = delete;

  // Appends a row. Throws std::invalid_argument for a row the reader would reject (t not finite or
  // out of range, unknown material index, light out of range, or a light/x/y value that the
  // header's columns cannot carry). Doubles are written in shortest round-trip form, so reading
  // the file back yields bit-identical values.
  void write(const VectorRow& row);
  // Flushes everything; for a path writer, fsyncs and renames into place. Throws
  // OutputError on I/O failure. No write() after commit().
  void commit();

  const VectorHeader& header() const;
  std::uint64_t rows_written() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace glint
