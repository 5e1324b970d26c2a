#include "image/image.h"
#include "reference/pixel_error.h"

namespace glint {

std::uint8_t srgb8(double linear) {
  // The display's sRGB code, as the pixel error measures it (reference/pixel_error.h). Computed in
  // double for every call (not a table) so that a value just either side of a rounding boundary
  // lands on the code the formula gives; the two segments meet within 1e-8, far from any boundary.
  return display_code8(DisplayEncoding::kSrgb8, linear);
}

}  // namespace glint
