#include <cmath>
#include <cstddef>

#include "image/image.h"

namespace glint {

namespace {

// "inferno", by Nathaniel J. Smith and Stéfan van der Walt (2015), released by them under CC0 and
// shipped by matplotlib as 256 sRGB entries (lib/matplotlib/_cm_listed.py): perceptually uniform,
// its luminance rises monotonically from near-black to pale yellow, and it stays ordered in grey
// and for colour-blind viewers. A table because no short formula follows its hue path. Kept here:
// every 5th entry (0, 5, ..., 255), 52 knots whose linear interpolation stays within 0.72/255 of
// all 256 published entries, under one 8-bit step; every 15th (18 knots) would be off by up to
// 5/255 in the orange bend.
constexpr std::size_t kKnots = 52;
constexpr double kInferno[kKnots][3] = {
    {0.001462, 0.000466, 0.013866}, {0.007676, 0.006136, 0.046836}, {0.019373, 0.015133, 0.088767},
    {0.037668, 0.025921, 0.132232}, {0.061340, 0.036590, 0.177642}, {0.087411, 0.044556, 0.224813},
    {0.116656, 0.047574, 0.272321}, {0.149073, 0.045468, 0.317085}, {0.183429, 0.040329, 0.354971},
    {0.217949, 0.036615, 0.383522}, {0.251620, 0.037705, 0.403378}, {0.284321, 0.043933, 0.416608},
    {0.316282, 0.053490, 0.425116}, {0.347771, 0.064616, 0.430217}, {0.379001, 0.076253, 0.432719},
    {0.410113, 0.087896, 0.433098}, {0.441207, 0.099338, 0.431594}, {0.472328, 0.110547, 0.428334},
    {0.503493, 0.121575, 0.423356}, {0.534683, 0.132534, 0.416667}, {0.565854, 0.143567, 0.408258},
    {0.596940, 0.154848, 0.398125}, {0.627847, 0.166575, 0.386276}, {0.658463, 0.178962, 0.372748},
    {0.688653, 0.192239, 0.357603}, {0.718264, 0.206636, 0.340931}, {0.747127, 0.222378, 0.322856},
    {0.775059, 0.239667, 0.303526}, {0.801871, 0.258674, 0.283099}, {0.827372, 0.279517, 0.261750},
    {0.851384, 0.302260, 0.239636}, {0.873741, 0.326906, 0.216886}, {0.894305, 0.353399, 0.193584},
    {0.912966, 0.381636, 0.169755}, {0.929644, 0.411479, 0.145367}, {0.944285, 0.442772, 0.120354},
    {0.956852, 0.475356, 0.094695}, {0.967322, 0.509078, 0.068659}, {0.975677, 0.543798, 0.043618},
    {0.981895, 0.579392, 0.026250}, {0.985952, 0.615750, 0.025592}, {0.987819, 0.652773, 0.045581},
    {0.987464, 0.690366, 0.079990}, {0.984865, 0.728427, 0.120785}, {0.980032, 0.766837, 0.166353},
    {0.973088, 0.805409, 0.216877}, {0.964394, 0.843848, 0.273391}, {0.954997, 0.881569, 0.337475},
    {0.947594, 0.917399, 0.410665}, {0.947937, 0.949318, 0.491426}, {0.961812, 0.975924, 0.571925},
    {0.988362, 0.998364, 0.644924},
};

std::uint8_t to_byte(double c) {
  return static_cast<std::uint8_t>(std::floor(c * 255.0 + 0.5));
}

}  // namespace

Rgb8 heat_colour(double value01) {
  if (std::isnan(value01)) return kHeatNan;
  const double v = value01 < 0.0 ? 0.0 : value01 > 1.0 ? 1.0 : value01;
  // Interpolated in the table's own (sRGB-encoded) space: between knots 5 entries apart, this only
  // fills in the entries left out.
  const double pos = v * static_cast<double>(kKnots - 1);
  std::size_t k = static_cast<std::size_t>(pos);
  if (k > kKnots - 2) k = kKnots - 2;
  const double f = pos - static_cast<double>(k);
  Rgb8 out{};
  for (int c = 0; c < 3; ++c) {
    const double a = kInferno[k][c], b = kInferno[k + 1][c];
    out[c] = to_byte(a + (b - a) * f);
  }
  return out;
}

}  // namespace glint
