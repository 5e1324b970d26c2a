#include "reference/pixel_error.h"

#include <algorithm>
#include <cmath>

namespace glint {

const char* to_string(DisplayEncoding e) {
  return e == DisplayEncoding::kSrgb8 ? "srgb8" : "linear8";
}

std::optional<DisplayEncoding> try_parse_display(std::string_view text) {
  if (text == "linear8") return DisplayEncoding::kLinear8;
  if (text == "srgb8") return DisplayEncoding::kSrgb8;
  return std::nullopt;
}

const char* to_string(EpsMeasure m) {
  return m == EpsMeasure::kChannel ? "channel" : "luminance";
}

std::optional<EpsMeasure> try_parse_eps_measure(std::string_view text) {
  if (text == "luminance") return EpsMeasure::kLuminance;
  if (text == "channel") return EpsMeasure::kChannel;
  return std::nullopt;
}

Rgb channel_weights(const Rgb& light, const Rgb& material) {
  return Rgb{light.r * material.r, light.g * material.g, light.b * material.b};
}

double largest_channel(const Rgb& w) {
  return std::max({w.r, w.g, w.b});
}

double threshold_weight(EpsMeasure m, const Rgb& light, const Rgb& material) {
  return m == EpsMeasure::kChannel ? largest_channel(channel_weights(light, material))
                                   : c_y(light, material);
}

double encode(DisplayEncoding e, double linear) {
  if (e == DisplayEncoding::kLinear8) return linear;
  // NaN fails both comparisons: black, as image/srgb.cpp's srgb8 maps it.
  if (!(linear > 0.0)) return 0.0;
  if (linear >= 1.0) return 1.0;
  // IEC 61966-2-1, the same segments as srgb8 (image/srgb.cpp), which rounds this to a code.
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

std::uint8_t display_code8(DisplayEncoding e, double linear) {
  // NaN fails both comparisons, so it would survive a plain clamp: black, explicitly.
  if (!(linear > 0.0)) return 0;
  if (linear >= 1.0) return 255;
  // Round half up (encoded is in [0, 1], so this is round-to-nearest on the 255 scale).
  return static_cast<std::uint8_t>(std::floor(encode(e, linear) * 255.0 + 0.5));
}

double encoding_slope(DisplayEncoding e) {
  return e == DisplayEncoding::kSrgb8 ? 12.92 : 1.0;
}

double request_pixel_error(DisplayEncoding e, const Rgb& w, double x, double r) {
  if (e == DisplayEncoding::kLinear8) return largest_channel(w) * std::fabs(x - r);
  // Every channel is encoded: sRGB clamps at full scale, so a channel of weight above 1 may
  // saturate and show less of the difference than a dimmer one.
  return std::max({std::fabs(encode(e, w.r * x) - encode(e, w.r * r)),
                   std::fabs(encode(e, w.g * x) - encode(e, w.g * r)),
                   std::fabs(encode(e, w.b * x) - encode(e, w.b * r))});
}

double pixel_error_bound(DisplayEncoding e, double w_max, double scalar_bound) {
  const double b = encoding_slope(e) * w_max * scalar_bound;
  return e == DisplayEncoding::kSrgb8 ? std::min(b, 1.0) : b;
}

int skip_guarantee_lsb(DisplayEncoding e, double eps, double ratio, int bits) {
  const double scale = std::ldexp(1.0, bits) - 1.0;
  // A relative margin for tau's rounding (t <= tau gives t^n <= eps_K / weight within an ulp or
  // two of pow).
  const double d = encoding_slope(e) * eps * ratio * scale * (1.0 + 1e-9);
  const double capped = std::min(d, scale);
  return static_cast<int>(std::floor(capped)) + (capped < scale ? 1 : 0);
}

}  // namespace glint
