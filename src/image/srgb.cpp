#include <cmath>

#include "image/image.h"

namespace glint {

std::uint8_t srgb8(double linear) {
  // NaN fails both comparisons, so it would survive a plain clamp: map it to black explicitly.
  if (!(linear > 0.0)) return 0;
  if (linear >= 1.0) return 255;
  // IEC 61966-2-1: the linear segment below 0.0031308, the 1/2.4 power above. Computed in double
  // for every call (not a table) so that a value just either side of a rounding boundary lands on
  // the code the formula gives; the two segments meet within 1e-8, far from any boundary.
  const double encoded =
      linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
  // Round half up (encoded is in [0, 1], so this is round-to-nearest on the 255 scale).
  return static_cast<std::uint8_t>(std::floor(encoded * 255.0 + 0.5));
}

}  // namespace glint
