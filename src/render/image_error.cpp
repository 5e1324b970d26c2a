#include "render/image_error.h"

#include <cmath>
#include <limits>

namespace glint {

namespace {

double ratio(std::uint64_t n, std::uint64_t reference) {
  if (reference == 0) return n ? std::numeric_limits<double>::infinity() : 1.0;
  return static_cast<double>(n) / static_cast<double>(reference);
}

}  // namespace

ImageError ImageErrorAccumulator::result() const {
  ImageError e;
  if (pixels_ == 0) return e;
  const double channels = 3.0 * static_cast<double>(pixels_);
  e.max_lsb = max_;
  e.mean_lsb = static_cast<double>(sum_abs_) / static_cast<double>(pixels_);
  // Integer sums, so the figures are exact whatever order the tiles were added in.
  if (sum_sq_ > 0) e.psnr_db = 10.0 * std::log10(255.0 * 255.0 * channels / sum_sq_);
  e.differing_fraction = static_cast<double>(differing_) / static_cast<double>(pixels_);
  e.highlight_pixels = lit_;
  e.highlight_ratio = ratio(lit_, reference_lit_);
  e.core_pixels = core_;
  e.core_ratio = ratio(core_, reference_core_);
  return e;
}

}  // namespace glint
