// Image-level error, accumulated a tile at a time (render.h's ImageError).
#pragma once

#include <cstdint>

#include "image/image.h"
#include "render/render.h"

namespace glint {

class ImageErrorAccumulator {
 public:
  // Whether a pixel's specular term reaches a tenth (lit) and half (core) of its material's peak.
  struct Highlight {
    bool lit = false, core = false;
  };
  // One pixel: the reference's and the image's final 8-bit colour and highlight. Returns the
  // pixel's error in LSBs (its largest channel).
  int add(const Rgb8& reference, const Rgb8& image, Highlight reference_hl, Highlight image_hl);
  ImageError result() const;

 private:
  int max_ = 0;
  std::uint64_t sum_abs_ = 0, sum_sq_ = 0, differing_ = 0, pixels_ = 0;
  std::uint64_t lit_ = 0, reference_lit_ = 0, core_ = 0, reference_core_ = 0;
};

}  // namespace glint
