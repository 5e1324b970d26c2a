#include <algorithm>
#include <stdexcept>
#include <string>

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
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      unsigned sum[3] = {0, 0, 0}, n = 0;
      for (int sy = y * factor; sy < std::min(image.height, (y + 1) * factor); ++sy)
        for (int sx = x * factor; sx < std::min(image.width, (x + 1) * factor); ++sx) {
          const Rgb8 c = image.at(sx, sy);
          for (int k = 0; k < 3; ++k) sum[k] += c[k];
          ++n;
        }
      out.set(x, y,
              {static_cast<std::uint8_t>((sum[0] + n / 2) / n),
               static_cast<std::uint8_t>((sum[1] + n / 2) / n),
               static_cast<std::uint8_t>((sum[2] + n / 2) / n)});
    }
  return out;
}

}  // namespace glint
