// Anti-aliased chart shapes (image.h): coverage from the distance of each pixel centre to the
// shape's edge, 1 inside by more than half a pixel, 0 outside by more than half a pixel.
#include <algorithm>
#include <cmath>

#include "image/image.h"

namespace glint {
namespace {

void blend_pixel(Image8& image, int x, int y, Rgb8 colour, double coverage) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height || coverage <= 0) return;
  const auto a = static_cast<unsigned>(std::lround(std::min(coverage, 1.0) * 255));
  std::uint8_t* p = image.pixels.data() + 3 * (static_cast<std::size_t>(y) * image.width + x);
  for (int k = 0; k < 3; ++k)
    p[k] = static_cast<std::uint8_t>((p[k] * (255 - a) + colour[k] * a + 127) / 255);
}

// Visits the pixels whose centres lie in [x0, x1] x [y0, y1], clipped to the image.
template <class F>
void for_pixels(const Image8& image, double x0, double y0, double x1, double y1, F f) {
  const int xa = std::max(0, static_cast<int>(std::floor(x0)));
  const int ya = std::max(0, static_cast<int>(std::floor(y0)));
  const int xb = std::min(image.width - 1, static_cast<int>(std::ceil(x1)));
  const int yb = std::min(image.height - 1, static_cast<int>(std::ceil(y1)));
  for (int y = ya; y <= yb; ++y)
    for (int x = xa; x <= xb; ++x) f(x, y, x + 0.5, y + 0.5);
}

}  // namespace

void draw_line(Image8& image, double x0, double y0, double x1, double y1, Rgb8 colour,
               double width) {
  const double h = width / 2;
  const double dx = x1 - x0, dy = y1 - y0;
  const double len2 = dx * dx + dy * dy;
  for_pixels(image, std::min(x0, x1) - h - 1, std::min(y0, y1) - h - 1, std::max(x0, x1) + h + 1,
             std::max(y0, y1) + h + 1, [&](int x, int y, double px, double py) {
               // Distance from the pixel centre to the segment.
               double t = len2 > 0 ? ((px - x0) * dx + (py - y0) * dy) / len2 : 0.0;
               t = std::clamp(t, 0.0, 1.0);
               const double ex = px - (x0 + t * dx), ey = py - (y0 + t * dy);
               blend_pixel(image, x, y, colour, h + 0.5 - std::sqrt(ex * ex + ey * ey));
             });
}

void fill_circle(Image8& image, double cx, double cy, double radius, Rgb8 colour) {
  for_pixels(image, cx - radius - 1, cy - radius - 1, cx + radius + 1, cy + radius + 1,
             [&](int x, int y, double px, double py) {
               const double d = std::hypot(px - cx, py - cy);
               blend_pixel(image, x, y, colour, radius + 0.5 - d);
             });
}

void fill_rect(Image8& image, double x0, double y0, double x1, double y1, Rgb8 colour) {
  for_pixels(image, x0 - 1, y0 - 1, x1 + 1, y1 + 1, [&](int x, int y, double px, double py) {
    // Coverage of the pixel square [x, x+1) x [y, y+1) by the rectangle, per axis.
    const double cover_x = std::clamp(std::min(x1, px + 0.5) - std::max(x0, px - 0.5), 0.0, 1.0);
    const double cover_y = std::clamp(std::min(y1, py + 0.5) - std::max(y0, py - 0.5), 0.0, 1.0);
    blend_pixel(image, x, y, colour, cover_x * cover_y);
  });
}

}  // namespace glint
