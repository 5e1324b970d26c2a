// 8-bit RGB images and what glint draws on them: sRGB encoding, PNG output, an error colour map
// with its scale, text labels and a labelled contact sheet. Everything is deterministic: the same
// pixels give the same PNG bytes on every run.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace glint {

using Rgb8 = std::array<std::uint8_t, 3>;

struct Image8 {
  int width = 0, height = 0;
  std::vector<std::uint8_t> pixels;  // RGB, row-major, top row first: 3 * width * height bytes

  Image8() = default;
  Image8(int w, int h, Rgb8 fill = {0, 0, 0});  // a negative size throws std::invalid_argument
  // Both throw std::out_of_range outside the image (drawing functions clip instead).
  Rgb8 at(int x, int y) const;
  void set(int x, int y, Rgb8 c);
};

// Linear [0, 1] -> sRGB 8-bit (IEC 61966-2-1 transfer function), clamped, rounded to nearest. A
// 4096-entry table would be faster but is not bit-exact for every double; this is exact.
std::uint8_t srgb8(double linear);

// Writes a PNG (8-bit RGB, no time or text chunks, fixed compression) atomically: the file
// appears complete or not at all. Throws OutputError when the file cannot be written.
void write_png(const std::string& path, const Image8& image);
// The PNG bytes themselves (for tests and in-memory use). An image without pixels (0 wide or
// high), which PNG cannot hold, throws std::invalid_argument, from write_png too.
std::vector<std::uint8_t> encode_png(const Image8& image);

// A PNG encoded as its rows arrive, top row first, its bytes handed to `sink` as they are made:
// the same bytes as encode_png of the whole image, with only a few rows in memory. Writers share
// no state, so any number may run at once on different threads. A size without pixels throws
// std::invalid_argument; more rows than the image has, std::logic_error; an exception the sink
// throws comes out of the call that fed it (the constructor writes the file's header).
class PngRowWriter {
 public:
  using Sink = std::function<void(const std::uint8_t* data, std::size_t size)>;
  PngRowWriter(int width, int height, Sink sink);
  ~PngRowWriter();
  PngRowWriter(PngRowWriter&&) noexcept;
  PngRowWriter& operator=(PngRowWriter&&) noexcept;
  // `rows` rows of 3 * width bytes each (RGB); the last row finishes the file.
  void add_rows(const std::uint8_t* rgb, int rows);
  bool done() const;  // every row added: the sink has had the whole file

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// A perceptually ordered colour map for errors (0 = black-ish, 1 = brightest); value clamped.
// It is matplotlib's "inferno" (CC0): near-black, purple, red, orange, pale yellow, luminance
// rising throughout. NaN gives kHeatNan.
Rgb8 heat_colour(double value01);
// The colour of a NaN error: cyan, a hue inferno never takes (it passes through magenta-like
// purples, so magenta would not stand out).
inline constexpr Rgb8 kHeatNan{0, 255, 255};

// Draws text with its top-left corner at (x, y), `height` pixels tall (a bundled-with-Debian font
// rendered by stb_truetype); clipped to the image. Returns the width drawn.
// The font is DejaVu Sans (/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf, Debian package
// fonts-dejavu-core), or the TrueType file named by the environment variable GLINT_FONT; it is
// read once, on first use, and checked (image/font.h): a missing, unreadable or malformed font
// throws InputError (a std::runtime_error) naming the file, GLINT_FONT or 'font', what is wrong
// and the package. `height` spans the font's ascent to descent; text is UTF-8, anti-aliased
// and blended over the pixels beneath in `colour`; control characters, invalid UTF-8 bytes and
// characters the font lacks are drawn as '?'. The returned width is the text's advance (the same
// as text_width), however much of it was clipped. A height <= 0 throws std::invalid_argument.
int draw_text(Image8& image, int x, int y, std::string_view text, Rgb8 colour, int height = 14);
int text_width(std::string_view text, int height = 14);
// `text` if it fits in max_width pixels, else its longest prefix (whole characters) followed by
// an ellipsis that fits; empty if not even the ellipsis fits.
std::string fit_text(std::string_view text, int max_width, int height = 14);
// Reads and checks the font now, so that a command refuses a bad one before any work; throws as
// draw_text would.
void load_text_font();

// Shapes for charts (glint sweep's plots), anti-aliased: each pixel is blended with the colour by
// the fraction of it the shape covers (estimated from the distance of its centre to the shape's
// edge), in the stored sRGB values as text is; clipped to the image; deterministic. Coordinates
// are in pixels, (0, 0) the top-left corner of the top-left pixel, so pixel (x, y) has its centre
// at (x + 0.5, y + 0.5).
// A straight segment `width` pixels wide (round caps).
void draw_line(Image8& image, double x0, double y0, double x1, double y1, Rgb8 colour,
               double width = 1.0);
// A filled disc.
void fill_circle(Image8& image, double cx, double cy, double radius, Rgb8 colour);
// A filled axis-aligned rectangle [x0, x1) x [y0, y1), edges anti-aliased.
void fill_rect(Image8& image, double x0, double y0, double x1, double y1, Rgb8 colour);

// An error heat map: each pixel's error in LSBs mapped by heat_colour over [0, scale_max] (values
// above clamp), pixels with no error colour, and a colour bar with tick labels ("0", ...,
// "N LSB") and a title drawn to the right of the image. error_lsb has width * height entries.
// Layout: the map is the image's top-left width x height pixels (pixel (x, y) is
// heat_colour(|error| / scale_max), kHeatNan for NaN; signed errors show by magnitude); to its
// right, on a dark background, the title (word-wrapped) above a vertical bar, scale_max at the top
// and 0 at the bottom, with 3 to 5 labels: 0, round steps and scale_max itself ("1 LSB"), plus a
// "NaN" key when a NaN is present. The bar is at least 64 pixels tall, so a small map (64x48)
// gives an image taller than the map. Throws std::invalid_argument on a size that does not match
// error_lsb, or a scale_max that is not positive and finite.
Image8 heatmap_with_scale(const std::vector<double>& error_lsb, int width, int height,
                          double scale_max, const std::string& title);

// Error maps that tell "no error" from "no object": a pixel showing no object is
// kErrorMapBackground, an object's pixel without error kErrorMapZero (a dark slate no error colour
// takes), and an error e > 0 LSB is heat_colour(kErrorMapLow + (1 - kErrorMapLow) * e / scale_max)
// (clamped), so that even 1 LSB on a large scale is a visible purple, not near-black. NaN is
// kHeatNan.
inline constexpr Rgb8 kErrorMapBackground{0, 0, 0};
inline constexpr Rgb8 kErrorMapZero{40, 52, 80};
inline constexpr double kErrorMapLow = 0.2;
Rgb8 error_colour(double error_lsb, double scale_max);
// A width x height map of error_lsb (row-major); `object` (same size) nonzero where a pixel shows
// an object. No colour bar: the map is the size of the image it measures (heat_legend draws the
// scale). Throws std::invalid_argument as heatmap_with_scale does.
Image8 error_map(const std::vector<double>& error_lsb, const std::vector<std::uint8_t>& object,
                 int width, int height, double scale_max);
// A horizontal colour bar `width` pixels wide for error_map's colours: the title, then swatches
// for "no object" and "0", then the bar from 1 LSB... to scale_max with round tick labels, the top
// labelled with `unit`. Throws std::invalid_argument for a width < 160 or a bad scale_max.
Image8 heat_legend(int width, double scale_max, const std::string& title,
                   const std::string& unit = "LSB");
// A legend of colour swatches, each with its text, under a title, wrapped to `width` pixels.
Image8 swatch_legend(int width, const std::string& title,
                     const std::vector<std::pair<Rgb8, std::string>>& items);
// Images one above the other, left-aligned, 4 pixels apart, on the sheets' background.
Image8 stack_images(const std::vector<const Image8*>& images);

// The image reduced by an integer factor: each output pixel the rounded mean of its factor x
// factor block (edge blocks over the pixels they have), in the encoded values (a thumbnail, not a
// photometric resampling). factor 1 returns a copy. Throws std::invalid_argument for factor < 1.
Image8 downscale(const Image8& image, int factor);

// A contact sheet: the images in a grid of `columns`, each with its label drawn above it, on a
// dark background. Images of different sizes are placed in cells of the largest size.
// Each cell is as wide as the widest image and as tall as a 14-pixel label, 4 pixels and the
// tallest image; images are centred across their cell under the label, and a label wider than
// the cell ends in an ellipsis. Cells are 8 pixels apart and from the edges. With fewer tiles than
// columns there are as many columns as tiles. Throws std::invalid_argument for no tiles, columns
// < 1 or a null image.
Image8 contact_sheet(const std::vector<std::pair<std::string, const Image8*>>& tiles, int columns);
// The same under a title (its first line 18 pixels tall, the others 14, each word-wrapped to the
// sheet's width) and above a footer image (e.g. a legend), both left-aligned; the sheet
// is widened to the footer if need be. Without title and footer it is the sheet above.
Image8 contact_sheet(const std::vector<std::pair<std::string, const Image8*>>& tiles, int columns,
                     const std::vector<std::string>& title, const Image8* footer);

}  // namespace glint
