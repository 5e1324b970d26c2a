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
