// The pixel error: the one definition of "an error of N LSB" that every glint report uses (eval and
// sim's `weighted` errors and their bounds, the render's image errors, heat maps, mean and max,
// `glint size`'s budgets, the skip guarantee).
//
// Definition. A request of light i on a material of specular colour m adds s = x * w to its pixel
// per channel c in {R, G, B}, where x is the scalar lobe (the unit's result, or the reference
// max(0,t)^n) and w_c = i_c m_c its channel weight (Källberg & Larsson, "Optimized Phong and
// Blinn-Phong Glossy Highlights", JCGT 2014, eq.1). The display stores each channel in its
// encoding E at 8 bits (or the report's display depth): linear (E(v) = v) or sRGB (IEC 61966-2-1,
// E clamped to [0, 1]). The pixel error is the largest channel's difference in that encoding:
//
//   error = max_c |E(base_c + w_c x_unit) - E(base_c + w_c x_ref)|, in LSB = 1 / (2^bits - 1).
//
// - A request (eval, sim, a render's request statistics) has no base (black, base = 0) and no
//   rounding: its error is the value above, before the display rounds it to a code. In the linear
//   encoding it is max_c w_c |x_unit - x_ref|: the largest channel weight times the scalar error
//   (before the display's clamp, which only shrinks a difference).
// - An image pixel (the render) holds every light's requests over the diffuse term, rounded to
//   8-bit codes: its error is the largest channel's code difference. Mean and max of an image are
//   of that same per-pixel figure, and its heat map shows it.
//
// eps (Källberg eq.4-5, tau = (eps/c_y)^(1/n)) keeps the paper's definition by default: the
// luminance c_y = 0.2126 w_R + 0.7152 w_G + 0.0722 w_B (eq.3; eq.6 for white lights). Under an
// orange light c_y understates the red channel (w_R / c_y up to 1 / 0.2126), so a skipped lobe may
// reach eps * w_R / c_y on the red channel. EpsMeasure::kChannel puts the largest channel weight in
// place of c_y: every channel of a skipped lobe stays within eps.
#pragma once

#include <cstdint>
#include <optional>
#include <string_view>

#include "reference/reference.h"

namespace glint {

// How a display encodes a channel. Vector files default to linear (a term over black, as glint
// measured it before this definition), scenes to sRGB (their images are sRGB PNGs).
enum class DisplayEncoding : std::uint8_t { kLinear8, kSrgb8 };
const char* to_string(DisplayEncoding e);  // "linear8", "srgb8"
std::optional<DisplayEncoding> try_parse_display(std::string_view text);

// What eps is a threshold of (above).
enum class EpsMeasure : std::uint8_t { kLuminance, kChannel };
const char* to_string(EpsMeasure m);  // "luminance", "channel"
std::optional<EpsMeasure> try_parse_eps_measure(std::string_view text);

// The channel weights w = i * m of a light and a specular colour, and the largest of them.
Rgb channel_weights(const Rgb& light, const Rgb& material);
double largest_channel(const Rgb& w);

// The weight eps is compared against in tau = (eps / weight)^(1/n): c_y (eq.3) or the largest
// channel weight.
double threshold_weight(EpsMeasure m, const Rgb& light, const Rgb& material);

// The encoding's transfer of a linear value, in [0, 1] display units (times 2^bits - 1 for LSB).
// Linear: the value itself, unclamped; sRGB: IEC 61966-2-1 on the value clamped to [0, 1].
double encode(DisplayEncoding e, double linear);

// The 8-bit code a display stores for a linear value: encode() of the value clamped to [0, 1],
// times 255, rounded half up (NaN: 0). image/srgb.cpp's srgb8 is the sRGB case.
std::uint8_t display_code8(DisplayEncoding e, double linear);

// The largest slope of the encoding's transfer: 1 (linear), 12.92 (sRGB, its linear toe; the power
// segment's slope is below it). |E(a) - E(b)| <= slope * |a - b| for every a, b.
double encoding_slope(DisplayEncoding e);

// The error of one request over black (above), in display units: max_c |E(w_c x) - E(w_c r)|.
double request_pixel_error(DisplayEncoding e, const Rgb& w, double x, double r);

// A bound on request_pixel_error for any x, r with |x - r| <= scalar_bound and largest channel
// weight w_max: slope * w_max * scalar_bound (at most 1 when the encoding clamps).
double pixel_error_bound(DisplayEncoding e, double w_max, double scalar_bound);

// The skip's guarantee on an image of `bits` bits per channel: when every skipped request's lobe
// is at most eps_K / weight_s (Källberg eq.4, eps_K = eps / K over K lights) and its channel
// weights at most ratio * weight_s, a pixel's channels lose at most eps * ratio in linear light,
// so its code differs by at most floor(slope * eps * ratio * (2^bits - 1)) + 1 (the +1: rounding
// of the two sides). ratio is the largest w_max / weight over the scene's slots: 1 with
// EpsMeasure::kChannel, up to 1 / 0.0722 with kLuminance.
int skip_guarantee_lsb(DisplayEncoding e, double eps, double ratio, int bits = 8);

}  // namespace glint
