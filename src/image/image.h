// 8-bit RGB images and what glint draws on them: sRGB encoding, PNG output, an error colour map
// with its scale, text labels and a labelled contact sheet. Everything is deterministic: the same
// pixels give the same PNG bytes on every run.
#pragma once

#include <array>
#include <cstdint>
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
  Image8(int w, int h, Rgb8 fill = {0, 0, 0});
  Rgb8 at(int x, int y) const;
  void set(int x, int y, Rgb8 c);
};

// Linear [0, 1] -> sRGB 8-bit (IEC 61966-2-1 transfer function), clamped, rounded to nearest. A
// 4096-entry table would be faster but is not bit-exact for every double; this is exact.
std::uint8_t srgb8(double linear);

// Writes a PNG (8-bit RGB, no time or text chunks, fixed compression) atomically: the file
// appears complete or not at all. Throws OutputError when the file cannot be written.
void write_png(const std::string& path, const Image8& image);
// The PNG bytes themselves (for tests and in-memory use).
std::vector<std::uint8_t> encode_png(const Image8& image);

// A perceptually ordered colour map for errors (0 = black-ish, 1 = brightest); value clamped.
Rgb8 heat_colour(double value01);

// Draws text with its top-left corner at (x, y), `height` pixels tall (a bundled-with-Debian font
// rendered by stb_truetype); clipped to the image. Returns the width drawn.
int draw_text(Image8& image, int x, int y, std::string_view text, Rgb8 colour, int height = 14);
int text_width(std::string_view text, int height = 14);

// An error heat map: each pixel's error in LSBs mapped by heat_colour over [0, scale_max] (values
// above clamp), pixels with no error colour, and a colour bar with tick labels ("0", ...,
// "N LSB") and a title drawn to the right of the image. error_lsb has width * height entries.
Image8 heatmap_with_scale(const std::vector<double>& error_lsb, int width, int height,
                          double scale_max, const std::string& title);

// A contact sheet: the images in a grid of `columns`, each with its label drawn above it, on a
// dark background. Images of different sizes are placed in cells of the largest size.
Image8 contact_sheet(const std::vector<std::pair<std::string, const Image8*>>& tiles,
                     int columns);

}  // namespace glint
