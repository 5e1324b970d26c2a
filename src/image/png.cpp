// PNG through stb_image_write (libstb-dev), the library that also rasterises glint's text. Its
// encoder writes exactly IHDR, IDAT and IEND (no time, text or gamma chunks to suppress) and its
// deflate has no randomness, so equal pixels give equal bytes. Its knobs are process-wide globals,
// though, so every call pins them under one lock.
#include <stb_image_write.h>

#include <climits>
#include <mutex>
#include <stdexcept>
#include <string>

#include "image/image.h"
#include "io/atomic_file.h"

namespace glint {

namespace {

// stb's own default level, pinned so the bytes do not depend on whoever else set the global (9
// saves under 1% on heat maps; stb's deflate gives files ~1.6x zlib's, fine for a few images).
constexpr int kCompressionLevel = 8;
// -1: stb picks each row's filter by a fixed rule (smallest sum of residuals), deterministic.
constexpr int kFilter = -1;

void append_bytes(void* context, void* data, int size) {
  auto* out = static_cast<std::vector<std::uint8_t>*>(context);
  const auto* bytes = static_cast<const std::uint8_t*>(data);
  out->insert(out->end(), bytes, bytes + size);
}

}  // namespace

std::vector<std::uint8_t> encode_png(const Image8& image) {
  if (image.width <= 0 || image.height <= 0) {
    throw std::invalid_argument("encode_png: a PNG needs at least one pixel, the image is " +
                                std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  if (image.pixels.size() !=
      3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
    throw std::invalid_argument("encode_png: pixel buffer does not match " +
                                std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  // stb works in int: the filtered rows (1 + 3w bytes each) must fit.
  if ((3 * static_cast<long long>(image.width) + 1) * image.height > INT_MAX / 2) {
    throw std::invalid_argument("encode_png: image too large for the encoder");
  }
  static std::mutex stb_globals;
  std::vector<std::uint8_t> out;
  int ok = 0;
  {
    const std::lock_guard<std::mutex> lock(stb_globals);
    stbi_write_png_compression_level = kCompressionLevel;
    stbi_write_force_png_filter = kFilter;
    stbi_flip_vertically_on_write(0);
    ok = stbi_write_png_to_func(append_bytes, &out, image.width, image.height, 3,
                                image.pixels.data(), 3 * image.width);
  }
  if (!ok || out.empty()) throw std::runtime_error("encode_png: out of memory");
  return out;
}

void write_png(const std::string& path, const Image8& image) {
  // Encode first: a failure here leaves no temporary file behind either.
  const std::vector<std::uint8_t> bytes = encode_png(image);
  AtomicOutputFile file(path);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

}  // namespace glint
