#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.h"

namespace glint {

Image8::Image8(int w, int h, Rgb8 fill) : width(w), height(h) {
  if (w < 0 || h < 0) {
    throw std::invalid_argument("Image8: negative size " + std::to_string(w) + "x" +
                                std::to_string(h));
  }
  pixels.resize(3 * static_cast<std::size_t>(w) * static_cast<std::size_t>(h));
  for (std::size_t i = 0; i < pixels.size(); i += 3) {
    pixels[i] = fill[0];
    pixels[i + 1] = fill[1];
    pixels[i + 2] = fill[2];
  }
}

namespace {

// Checked, because a renderer's off-by-one would otherwise write past the buffer silently.
std::size_t offset(const Image8& image, int x, int y) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) {
    throw std::out_of_range("Image8: pixel (" + std::to_string(x) + ", " + std::to_string(y) +
                            ") outside " + std::to_string(image.width) + "x" +
                            std::to_string(image.height));
  }
  return 3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(image.width) +
              static_cast<std::size_t>(x));
}

}  // namespace

Rgb8 Image8::at(int x, int y) const {
  const std::size_t i = offset(*this, x, y);
  return {pixels[i], pixels[i + 1], pixels[i + 2]};
}

void Image8::set(int x, int y, Rgb8 c) {
  const std::size_t i = offset(*this, x, y);
  pixels[i] = c[0];
  pixels[i + 1] = c[1];
  pixels[i + 2] = c[2];
}

}  // namespace glint

namespace glint {

Image8 downscale(const Image8& image, int factor) {
  if (factor < 1) throw std::invalid_argument("downscale: factor must be >= 1");
  const int w = (image.width + factor - 1) / factor, h = (image.height + factor - 1) / factor;
  Image8 out(w, h);
  // A row of block sums at a time, each source pixel read once in memory order (a render reduces
  // every strip of every image for its contact sheet: this loop is a tenth of a render's work).
  std::vector<unsigned> sum(3 * static_cast<std::size_t>(w));
  const std::size_t row_bytes = 3 * static_cast<std::size_t>(image.width);
  for (int y = 0; y < h; ++y) {
    std::fill(sum.begin(), sum.end(), 0u);
    const int y_end = std::min(image.height, (y + 1) * factor);
    for (int sy = y * factor; sy < y_end; ++sy) {
      const std::uint8_t* row = image.pixels.data() + static_cast<std::size_t>(sy) * row_bytes;
      for (int sx = 0; sx < image.width; ++sx) {
        unsigned* s = &sum[3 * static_cast<std::size_t>(sx / factor)];
        s[0] += row[3 * sx];
        s[1] += row[3 * sx + 1];
        s[2] += row[3 * sx + 2];
      }
    }
    std::uint8_t* o = out.pixels.data() + 3 * static_cast<std::size_t>(y) * w;
    for (int x = 0; x < w; ++x) {
      const unsigned n = static_cast<unsigned>(
          (y_end - y * factor) * (std::min(image.width, (x + 1) * factor) - x * factor));
      for (int k = 0; k < 3; ++k)
        o[3 * x + k] =
            static_cast<std::uint8_t>((sum[3 * static_cast<std::size_t>(x) + k] + n / 2) / n);
    }
  }
  return out;
}

}  // namespace glint
