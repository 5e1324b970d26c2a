// The composed images: an error heat map with its colour bar, and a labelled contact sheet. Both
// use one dark background, so that a heat map placed on a sheet looks the same as alone.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "image/image.h"

namespace glint {

namespace {

constexpr Rgb8 kBackground{24, 24, 28};
constexpr Rgb8 kText{230, 230, 230};
constexpr Rgb8 kFrame{110, 110, 118};  // colour bar outline and tick marks

constexpr int kPad = 8;
constexpr int kTitleHeight = 14;
constexpr int kTickHeight = 12;
constexpr int kBarWidth = 14;
constexpr int kTickLength = 4;
constexpr int kMinBarHeight = 64;  // room for three labels however small the map
constexpr int kTitleWrap = 160;    // titles wrap to this width
constexpr int kLabelHeight = 14;   // contact sheet labels
constexpr int kLabelGap = 4;
constexpr int kSheetTitle = 18;  // a contact sheet's first title line

void fill_rect(Image8& image, int x, int y, int w, int h, Rgb8 c) {
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = std::min(x + w, image.width), y1 = std::min(y + h, image.height);
  for (int py = y0; py < y1; ++py) {
    for (int px = x0; px < x1; ++px) image.set(px, py, c);
  }
}

void blit(Image8& dst, const Image8& src, int x, int y) {
  for (int sy = 0; sy < src.height; ++sy) {
    const int dy = y + sy;
    if (dy < 0 || dy >= dst.height) continue;
    for (int sx = 0; sx < src.width; ++sx) {
      const int dx = x + sx;
      if (dx >= 0 && dx < dst.width) dst.set(dx, dy, src.at(sx, sy));
    }
  }
}

// Greedy word wrap to `max_width`; a word wider than that alone is cut with an ellipsis.
std::vector<std::string> wrap(const std::string& text, int max_width, int height) {
  std::vector<std::string> lines;
  std::string line;
  std::size_t i = 0;
  while (i < text.size()) {
    const std::size_t start = text.find_first_not_of(' ', i);
    if (start == std::string::npos) break;
    const std::size_t stop = std::min(text.find(' ', start), text.size());
    const std::string word = text.substr(start, stop - start);
    i = stop;
    const std::string joined = line.empty() ? word : line + " " + word;
    if (line.empty() || text_width(joined, height) <= max_width) {
      line = joined;
    } else {
      lines.push_back(fit_text(line, max_width, height));
      line = word;
    }
  }
  if (!line.empty()) lines.push_back(fit_text(line, max_width, height));
  return lines;
}

std::string trim_number(std::string s) {
  if (s.find('.') != std::string::npos && s.find('e') == std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

std::string format_fixed(double v, int decimals) {
  char buf[64];
  // Beyond 6 decimals a fixed format gets unreadable: switch to "5e-07".
  if (decimals > 6) {
    std::snprintf(buf, sizeof buf, "%.3g", v);
  } else {
    std::snprintf(buf, sizeof buf, "%.*f", decimals, v);
  }
  return trim_number(buf);
}

struct Tick {
  double value;
  std::string label;
};

// 3 to 5 labels: 0, multiples of a round step (1, 2, 2.5 or 5 times a power of ten) and the top
// of the scale, always labelled, with its unit, so the range is never guessed. Labels are at least
// a line of text apart, so a step that does not land on the top leaves out the multiple too close
// to it. Preferred: a step that lands on the top (evenly spaced labels), then the fewest
// decimals, then the most labels, then the least of the bar's top left unlabelled.
std::vector<Tick> make_ticks(double scale_max, int bar_height) {
  const double min_gap = (kTickHeight + 2) * scale_max / (bar_height - 1);
  std::vector<Tick> best;
  double best_score = -1;
  const int top_exp = static_cast<int>(std::floor(std::log10(scale_max)));
  for (int e = top_exp - 2; e <= top_exp; ++e) {
    for (const double m : {1.0, 2.0, 2.5, 5.0}) {
      const double step = m * std::pow(10.0, e);
      if (step < min_gap) continue;
      const int decimals = std::max(0, -e + (m == 2.5 ? 1 : 0));
      const double n = scale_max / step;
      const bool exact = std::fabs(n - std::round(n)) < 1e-9 * n;
      std::vector<Tick> ticks;
      for (int k = 0; ticks.size() <= 5; ++k) {
        const double v = k * step;
        if (exact ? k >= std::lround(n) : v > scale_max - min_gap) break;
        ticks.push_back({v, format_fixed(v, decimals)});
      }
      std::string top = format_fixed(scale_max, decimals);
      if (!exact) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.3g", scale_max);
        top = buf;
      }
      ticks.push_back({scale_max, top + " LSB"});
      const int count = static_cast<int>(ticks.size());
      if (count < 3 || count > 5) continue;
      const double unlabelled = (scale_max - ticks[ticks.size() - 2].value) / scale_max;
      const double score =
          (exact ? 1000 : 0) + (20 - std::min(decimals, 19)) * 10 + count - unlabelled;
      if (score > best_score) {
        best_score = score;
        best = ticks;
      }
    }
  }
  if (best.empty()) {
    // A scale no round step divides into 3 to 5 labels: its ends and middle, as they are.
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3g", scale_max / 2);
    std::string mid = buf;
    std::snprintf(buf, sizeof buf, "%.3g LSB", scale_max);
    best = {{0.0, "0"}, {scale_max / 2, mid}, {scale_max, buf}};
  }
  return best;
}

}  // namespace

Image8 heatmap_with_scale(const std::vector<double>& error_lsb, int width, int height,
                          double scale_max, const std::string& title) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("heatmap_with_scale: size " + std::to_string(width) + "x" +
                                std::to_string(height) + " has no pixels");
  }
  if (error_lsb.size() != static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
    throw std::invalid_argument("heatmap_with_scale: " + std::to_string(error_lsb.size()) +
                                " errors for " + std::to_string(width) + "x" +
                                std::to_string(height) + " pixels");
  }
  if (!(scale_max > 0) || !std::isfinite(scale_max)) {
    throw std::invalid_argument("heatmap_with_scale: scale_max must be positive and finite");
  }
  const bool any_nan =
      std::any_of(error_lsb.begin(), error_lsb.end(), [](double e) { return std::isnan(e); });

  // The margin's column: title lines, then the bar with its ticks and labels, then the NaN key.
  // The bar takes whatever height the map leaves, but never less than kMinBarHeight: a small map
  // makes the image taller than the map rather than the labels unreadable.
  const std::vector<std::string> title_lines =
      title.empty() ? std::vector<std::string>{} : wrap(title, kTitleWrap, kTitleHeight);
  const int bar_top = kPad + kTickHeight / 2 +
                      static_cast<int>(title_lines.size()) * (kTitleHeight + 2) +
                      (title_lines.empty() ? 0 : kPad / 2);
  const int nan_key = any_nan ? kTickHeight + kPad : 0;
  const int bar_height =
      std::max(kMinBarHeight, height - bar_top - kTickHeight / 2 - nan_key - kPad);
  const std::vector<Tick> ticks = make_ticks(scale_max, bar_height);
  int label_width = any_nan ? text_width("NaN", kTickHeight) : 0;
  for (const Tick& t : ticks) label_width = std::max(label_width, text_width(t.label, kTickHeight));
  int column_width = kBarWidth + 2 + kTickLength + 3 + label_width;
  for (const std::string& line : title_lines) {
    column_width = std::max(column_width, text_width(line, kTitleHeight));
  }
  const int out_width = width + kPad + column_width + kPad;
  const int out_height = std::max(height, bar_top + bar_height + kTickHeight / 2 + nan_key + kPad);

  Image8 out(out_width, out_height, kBackground);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double e = error_lsb[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) +
                                 static_cast<std::size_t>(x)];
      // Magnitudes: a signed error shows as large as it is, whichever way it points.
      out.set(x, y, std::isnan(e) ? kHeatNan : heat_colour(std::fabs(e) / scale_max));
    }
  }

  const int col_x = width + kPad;
  int y = kPad;
  for (const std::string& line : title_lines) {
    draw_text(out, col_x, y, line, kText, kTitleHeight);
    y += kTitleHeight + 2;
  }
  // The bar inside a 1-pixel frame: top row scale_max, bottom row 0, linear in between.
  const int bar_x = col_x + 1;
  fill_rect(out, bar_x - 1, bar_top - 1, kBarWidth + 2, bar_height + 2, kFrame);
  for (int r = 0; r < bar_height; ++r) {
    const Rgb8 c = heat_colour(1.0 - static_cast<double>(r) / (bar_height - 1));
    fill_rect(out, bar_x, bar_top + r, kBarWidth, 1, c);
  }
  const int tick_x = bar_x + kBarWidth + 1;
  for (const Tick& t : ticks) {
    const int row =
        bar_top + static_cast<int>(std::lround((1.0 - t.value / scale_max) * (bar_height - 1)));
    fill_rect(out, tick_x, row, kTickLength, 1, kFrame);
    draw_text(out, tick_x + kTickLength + 3, row - kTickHeight / 2, t.label, kText, kTickHeight);
  }
  if (any_nan) {
    const int key_y = bar_top + bar_height + kTickHeight / 2 + kPad;
    fill_rect(out, bar_x - 1, key_y - 1, kBarWidth + 2, kTickHeight, kFrame);
    fill_rect(out, bar_x, key_y, kBarWidth, kTickHeight - 2, kHeatNan);
    draw_text(out, tick_x + kTickLength + 3, key_y - 1, "NaN", kText, kTickHeight);
  }
  return out;
}

Rgb8 error_colour(double error_lsb, double scale_max) {
  if (std::isnan(error_lsb)) return kHeatNan;
  const double e = std::fabs(error_lsb);
  if (e == 0) return kErrorMapZero;
  return heat_colour(kErrorMapLow + (1.0 - kErrorMapLow) * std::min(1.0, e / scale_max));
}

Image8 error_map(const std::vector<double>& error_lsb, const std::vector<std::uint8_t>& object,
                 int width, int height, double scale_max) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("error_map: size " + std::to_string(width) + "x" +
                                std::to_string(height) + " has no pixels");
  }
  const std::size_t n = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  if (error_lsb.size() != n || object.size() != n) {
    throw std::invalid_argument("error_map: " + std::to_string(error_lsb.size()) + " errors and " +
                                std::to_string(object.size()) + " object flags for " +
                                std::to_string(width) + "x" + std::to_string(height) + " pixels");
  }
  if (!(scale_max > 0) || !std::isfinite(scale_max)) {
    throw std::invalid_argument("error_map: scale_max must be positive and finite");
  }
  Image8 out(width, height, kErrorMapBackground);
  for (std::size_t i = 0; i < n; ++i) {
    // An error where no object is (none should be) still shows: only a zero there is background.
    if (!object[i] && error_lsb[i] == 0) continue;
    const Rgb8 c = error_colour(error_lsb[i], scale_max);
    std::copy(c.begin(), c.end(), out.pixels.begin() + static_cast<std::ptrdiff_t>(3 * i));
  }
  return out;
}

namespace {

// A swatch with a frame, `size` pixels square, and its text to the right; returns the width used.
int draw_swatch(Image8& image, int x, int y, Rgb8 colour, const std::string& text) {
  fill_rect(image, x, y, kTickHeight, kTickHeight, kFrame);
  fill_rect(image, x + 1, y + 1, kTickHeight - 2, kTickHeight - 2, colour);
  return kTickHeight + 4 + draw_text(image, x + kTickHeight + 4, y, text, kText, kTickHeight);
}

int swatch_width(const std::string& text) {
  return kTickHeight + 4 + text_width(text, kTickHeight);
}

}  // namespace

Image8 heat_legend(int width, double scale_max, const std::string& title, const std::string& unit) {
  if (width < 160) throw std::invalid_argument("heat_legend: width below 160 pixels");
  if (!(scale_max > 0) || !std::isfinite(scale_max)) {
    throw std::invalid_argument("heat_legend: scale_max must be positive and finite");
  }
  const std::vector<std::string> title_lines = wrap(title, width - 2 * kPad, kTitleHeight);
  const int swatches_y = kPad + static_cast<int>(title_lines.size()) * (kTitleHeight + 2);
  const int bar_y = swatches_y + kTickHeight + kPad;
  const int bar_h = 10;
  const int height = bar_y + bar_h + kTickLength + 2 + kTickHeight + kPad;
  Image8 out(width, height, kBackground);
  int y = kPad;
  for (const std::string& line : title_lines) {
    draw_text(out, kPad, y, line, kText, kTitleHeight);
    y += kTitleHeight + 2;
  }
  int x = kPad;
  x += draw_swatch(out, x, swatches_y, kErrorMapBackground, "no object") + 2 * kPad;
  draw_swatch(out, x, swatches_y, kErrorMapZero, "object, 0 " + unit);
  // The bar: column c shows error_colour of its value, 0 at the left end (one column of the zero
  // colour), scale_max at the right. Labels sit under their ticks; make_ticks spaces them for
  // text about 4 times as wide as tall.
  const int bar_x = kPad + 1, bar_w = width - 2 * kPad - 2 - text_width(" " + unit, kTickHeight);
  fill_rect(out, bar_x - 1, bar_y - 1, bar_w + 2, bar_h + 2, kFrame);
  for (int c = 0; c < bar_w; ++c) {
    const double v = static_cast<double>(c) / (bar_w - 1) * scale_max;
    fill_rect(out, bar_x + c, bar_y, 1, bar_h, error_colour(v, scale_max));
  }
  const std::vector<Tick> ticks = make_ticks(scale_max, std::max(kMinBarHeight, bar_w / 4));
  for (const Tick& t : ticks) {
    const int col = bar_x + static_cast<int>(std::lround(t.value / scale_max * (bar_w - 1)));
    fill_rect(out, col, bar_y + bar_h + 1, 1, kTickLength, kFrame);
    const int w = text_width(t.label, kTickHeight);
    // The first label starts at its tick, the last ends near it, the others are centred.
    const int lx = t.value == 0 ? col : t.value == scale_max ? col - w + 1 : col - w / 2;
    draw_text(out, std::min(lx, width - w - 1), bar_y + bar_h + kTickLength + 2, t.label, kText,
              kTickHeight);
  }
  return out;
}

Image8 swatch_legend(int width, const std::string& title,
                     const std::vector<std::pair<Rgb8, std::string>>& items) {
  if (width < 64) throw std::invalid_argument("swatch_legend: width below 64 pixels");
  const std::vector<std::string> title_lines = wrap(title, width - 2 * kPad, kTitleHeight);
  // Lay the swatches out in rows first, to know the height.
  std::vector<std::pair<int, int>> at;
  int x = kPad, y = kPad + static_cast<int>(title_lines.size()) * (kTitleHeight + 2);
  for (const auto& item : items) {
    const int w = swatch_width(item.second);
    if (x > kPad && x + w > width - kPad) {
      x = kPad;
      y += kTickHeight + 4;
    }
    at.emplace_back(x, y);
    x += w + 2 * kPad;
  }
  const int height = (items.empty() ? y : y + kTickHeight) + kPad;
  Image8 out(width, height, kBackground);
  int ty = kPad;
  for (const std::string& line : title_lines) {
    draw_text(out, kPad, ty, line, kText, kTitleHeight);
    ty += kTitleHeight + 2;
  }
  for (std::size_t i = 0; i < items.size(); ++i)
    draw_swatch(
        out, at[i].first, at[i].second, items[i].first,
        fit_text(items[i].second, width - kPad - at[i].first - kTickHeight - 4, kTickHeight));
  return out;
}

Image8 stack_images(const std::vector<const Image8*>& images) {
  int width = 1, height = 0;
  for (const Image8* image : images) {
    if (!image) throw std::invalid_argument("stack_images: a null image");
    width = std::max(width, image->width);
    height += image->height;
  }
  if (!images.empty()) height += kLabelGap * (static_cast<int>(images.size()) - 1);
  Image8 out(width, std::max(height, 1), kBackground);
  int y = 0;
  for (const Image8* image : images) {
    blit(out, *image, 0, y);
    y += image->height + kLabelGap;
  }
  return out;
}

Image8 contact_sheet(const std::vector<std::pair<std::string, const Image8*>>& tiles, int columns) {
  return contact_sheet(tiles, columns, {}, nullptr);
}

Image8 contact_sheet(const std::vector<std::pair<std::string, const Image8*>>& tiles, int columns,
                     const std::vector<std::string>& title, const Image8* footer) {
  if (tiles.empty()) throw std::invalid_argument("contact_sheet: no tiles");
  if (columns <= 0) {
    throw std::invalid_argument("contact_sheet: " + std::to_string(columns) + " columns");
  }
  int cell_w = 1, image_h = 0;
  for (const auto& [label, image] : tiles) {
    if (!image) throw std::invalid_argument("contact_sheet: tile '" + label + "' has no image");
    cell_w = std::max(cell_w, image->width);
    image_h = std::max(image_h, image->height);
  }
  const int n = static_cast<int>(tiles.size());
  const int cols = std::min(columns, n);
  const int rows = (n + cols - 1) / cols;
  const int cell_h = kLabelHeight + kLabelGap + image_h;
  const int grid_w = kPad + cols * (cell_w + kPad);
  const int grid_h = kPad + rows * (cell_h + kPad);
  const int width = std::max(grid_w, footer ? footer->width + 2 * kPad : 0);
  // Title lines wrap to the sheet's width: a small render's sheet is narrower than its title.
  std::vector<std::pair<std::string, int>> lines;  // text, height
  for (std::size_t i = 0; i < title.size(); ++i) {
    const int h = i == 0 ? kSheetTitle : kLabelHeight;
    for (const std::string& line : wrap(title[i], width - 2 * kPad, h)) lines.emplace_back(line, h);
  }
  int title_h = 0;
  for (const auto& line : lines) title_h += line.second + 2;
  if (title_h > 0) title_h += kPad;
  Image8 sheet(width, title_h + grid_h + (footer ? footer->height + kPad : 0), kBackground);
  int ty = kPad;
  for (const auto& [text, h] : lines) {
    draw_text(sheet, kPad, ty, text, kText, h);
    ty += h + 2;
  }
  for (int i = 0; i < n; ++i) {
    const int cell_x = kPad + (i % cols) * (cell_w + kPad);
    const int cell_y = title_h + kPad + (i / cols) * (cell_h + kPad);
    const Image8& image = *tiles[static_cast<std::size_t>(i)].second;
    // Centred across the cell, top-aligned under the label: labels stay on one line per row.
    const std::string label =
        fit_text(tiles[static_cast<std::size_t>(i)].first, cell_w, kLabelHeight);
    draw_text(sheet, cell_x + (cell_w - text_width(label, kLabelHeight)) / 2, cell_y, label, kText,
              kLabelHeight);
    blit(sheet, image, cell_x + (cell_w - image.width) / 2, cell_y + kLabelHeight + kLabelGap);
  }
  if (footer) blit(sheet, *footer, kPad, title_h + grid_h);
  return sheet;
}

}  // namespace glint
