#include "render/render_sheet.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

namespace glint {
namespace {

// Tiles are at most this wide: a 4K render's sheet of full-size tiles would take ~450 MB.
constexpr int kSheetTileWidth = 640;
constexpr int kSheetColumns = 3;

// The largest value of each factor x factor block of a width x height map: an error of one pixel
// still shows on the reduced map.
std::vector<double> block_max(const std::vector<std::uint8_t>& map, int width, int height,
                              int factor) {
  const int w = (width + factor - 1) / factor, h = (height + factor - 1) / factor;
  std::vector<double> out(static_cast<std::size_t>(w) * h, 0.0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      double& m = out[static_cast<std::size_t>(y / factor) * w + x / factor];
      m = std::max(m, static_cast<double>(map[static_cast<std::size_t>(y) * width + x]));
    }
  return out;
}

std::vector<std::uint8_t> block_any(const std::vector<std::uint8_t>& map, int width, int height,
                                    int factor) {
  const int w = (width + factor - 1) / factor, h = (height + factor - 1) / factor;
  std::vector<std::uint8_t> out(static_cast<std::size_t>(w) * h, 0);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      if (map[static_cast<std::size_t>(y) * width + x])
        out[static_cast<std::size_t>(y / factor) * w + x / factor] = 1;
  return out;
}

const char* kErrorUnit = "pixel error: 8-bit LSB of the display's largest channel";

Image8 make_legend(const RenderResult& r, int width) {
  std::vector<Image8> parts;
  const std::size_t k = r.lights.size();
  const SkipCounts total = r.skip_total();
  const double skipped = total.total()
                             ? static_cast<double>(total.facing_away + total.zero + total.tau) /
                                   static_cast<double>(total.total())
                             : 0.0;
  // The combined mask's classes: the count of a pixel's lights skipped (up to 8 swatches).
  std::vector<std::pair<Rgb8, std::string>> combined;
  const auto swatch = [&](std::size_t n) { return combined_skip_colour(n, k, 128); };
  const std::size_t steps = std::min<std::size_t>(k, 8);
  for (std::size_t i = 0; i <= steps; ++i) {
    const std::size_t n = k <= 8 ? i : (i * k + steps / 2) / steps;
    combined.emplace_back(swatch(n), fmt::format("{}/{}", n, k));
  }
  combined.emplace_back(Rgb8{0, 0, 0}, "no object");
  parts.push_back(swatch_legend(
      width,
      fmt::format("skip_mask: lights skipped per pixel (facing away, t <= 0 or tau); over the "
                  "image {:.1f}% of the {} light x pixel pairs",
                  100.0 * skipped, total.total()),
      combined));
  // Per-light masks are written whenever the scene has a light (kStream keeps none in the result).
  if (!r.lights.empty())
    parts.push_back(swatch_legend(width, "skip_mask_LIGHT: that light's pair",
                                  {{{128, 128, 128}, "computed (grey, shaded)"},
                                   {kSkipTauColour, "skipped by tau alone"},
                                   {kSkipZeroColour, "t <= 0 or light behind"},
                                   {{0, 0, 0}, "no object"}}));
  if (r.heat_scale == HeatScale::kShared || r.units.empty()) {
    const double scale = r.units.empty() ? 1.0 : r.units.front().heatmap_scale;
    parts.push_back(heat_legend(
        width, scale, fmt::format("error maps, one scale for every unit; {}", kErrorUnit)));
  } else {
    for (const UnitRender& u : r.units)
      parts.push_back(heat_legend(width, u.heatmap_scale,
                                  fmt::format("{} error, its own scale; {}", u.label, kErrorUnit)));
  }
  std::vector<const Image8*> pointers;
  for (const Image8& p : parts) pointers.push_back(&p);
  return stack_images(pointers);
}

}  // namespace

Rgb8 combined_skip_colour(std::size_t skipped, std::size_t lights, std::uint8_t grey) {
  if (skipped == 0) {
    const auto g = static_cast<std::uint8_t>(70 + grey * 150 / 255);
    return {g, g, g};
  }
  const double f =
      lights > 1 ? static_cast<double>(skipped - 1) / static_cast<double>(lights - 1) : 1.0;
  const auto mix = [f](std::uint8_t a, std::uint8_t b) {
    return static_cast<std::uint8_t>(std::lround(a + (b - a) * f));
  };
  return {mix(kSkipSomeColour[0], kSkipTauColour[0]), mix(kSkipSomeColour[1], kSkipTauColour[1]),
          mix(kSkipSomeColour[2], kSkipTauColour[2])};
}

std::vector<std::string> render_title(const RenderResult& r) {
  std::vector<std::string> lines;
  std::string taus;
  double lo = 2, hi = -1;
  for (const auto& slot : r.slots) {
    lo = std::min(lo, slot["tau"].get<double>());
    hi = std::max(hi, slot["tau"].get<double>());
  }
  if (r.slots.size() == 1)
    taus = fmt::format(", tau {:.4f}", lo);
  else if (!r.slots.empty())
    taus = fmt::format(", tau {:.4f}..{:.4f} over {} slots", lo, hi, r.slots.size());
  lines.push_back(fmt::format("{}: {}x{}, {} light{} ({}), eps {:g}{}, chip {}", r.scene_name,
                              r.width, r.height, r.lights.size(), r.lights.size() == 1 ? "" : "s",
                              fmt::join(r.lights, ", "), r.eps, taus,
                              r.chip.value("spec", std::string("?"))));
  if (const std::string line = reproduces_line(r); !line.empty()) lines.push_back(line);
  return lines;
}

int sheet_factor(int width) {
  return (width + kSheetTileWidth - 1) / kSheetTileWidth;
}

Image8 error_thumb(const std::vector<std::uint8_t>& error_lsb,
                   const std::vector<std::uint8_t>& object, int width, int height, int factor,
                   double scale) {
  const int w = (width + factor - 1) / factor, h = (height + factor - 1) / factor;
  return error_map(block_max(error_lsb, width, height, factor),
                   factor > 1 ? block_any(object, width, height, factor) : object, w, h, scale);
}

void compose_sheet(RenderResult& out, std::vector<Image8> thumbs) {
  const std::size_t masks = std::min(out.lights.size(), kMaxLightSkipMasks);
  if (thumbs.size() != 3 + masks + 3 * out.units.size())
    throw std::logic_error("compose_sheet: one tile per image of the sheet");
  const Image8 blank(1, 1, {24, 24, 28});
  std::vector<std::pair<std::string, const Image8*>> tiles{
      {"reference", &thumbs[0]},
      {"reference specular", &thumbs[1]},
      {"skip mask: lights skipped", &thumbs[2]}};
  for (std::size_t l = 0; l < masks; ++l)
    tiles.emplace_back("skip mask: " + out.lights[l], &thumbs[3 + l]);
  // The unit rows start on a row of their own.
  while (tiles.size() % kSheetColumns) tiles.emplace_back("", &blank);
  for (std::size_t u = 0; u < out.units.size(); ++u) {
    const UnitRender& r = out.units[u];
    const std::size_t t = 3 + masks + 3 * u;
    tiles.emplace_back(r.label, &thumbs[t]);
    tiles.emplace_back(r.label + " specular", &thumbs[t + 1]);
    tiles.emplace_back(fmt::format("{} error (max {:g} LSB)", r.label, r.error.max_lsb),
                       &thumbs[t + 2]);
  }
  const int factor = sheet_factor(out.width);
  const int tile_w = (out.width + factor - 1) / factor;
  out.legend = make_legend(out, std::max(320, kSheetColumns * tile_w + (kSheetColumns - 1) * 8));
  out.contact_sheet = contact_sheet(tiles, kSheetColumns, render_title(out), &out.legend);
}

}  // namespace glint
