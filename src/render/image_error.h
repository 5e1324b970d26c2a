// Image-level error, accumulated a tile at a time (render.h's ImageError).
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>

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
  // Inline: a scene sweep calls it for every lit pixel of hundreds of units.
  int add(const Rgb8& reference, const Rgb8& image, Highlight reference_hl, Highlight image_hl) {
    // The pixel error (reference/pixel_error.h): the largest channel's code difference. The mean
    // is of that figure; PSNR stays the usual one over every channel.
    int worst = 0;
    for (int c = 0; c < 3; ++c) {
      const int d = std::abs(int{image[c]} - int{reference[c]});
      worst = d > worst ? d : worst;
      sum_sq_ += static_cast<std::uint64_t>(d * d);
    }
    sum_abs_ += static_cast<std::uint64_t>(worst);
    max_ = worst > max_ ? worst : max_;
    differing_ += worst > 0;
    ++pixels_;
    lit_ += image_hl.lit;
    reference_lit_ += reference_hl.lit;
    core_ += image_hl.core;
    reference_core_ += reference_hl.core;
    return worst;
  }
  // n pixels equal to the reference's, neither of them in a highlight: add's figures for them.
  void add_equal_unlit(std::size_t n) { pixels_ += n; }
  ImageError result() const;

 private:
  int max_ = 0;
  std::uint64_t sum_abs_ = 0, sum_sq_ = 0, differing_ = 0, pixels_ = 0;
  std::uint64_t lit_ = 0, reference_lit_ = 0, core_ = 0, reference_core_ = 0;
};

}  // namespace glint
