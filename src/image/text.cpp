// Text through stb_truetype (libstb-dev) and DejaVu Sans (fonts-dejavu-core): a Debian font and
// rasteriser rather than a bitmap font compiled in, so labels are anti-aliased at any height and
// nothing is vendored. Glyphs are placed at fractional pen positions (subpixel shifts) with the
// font's kerning, all in float arithmetic that does not depend on the machine's state, so the same
// text gives the same pixels on every run.
#include <stb_truetype.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "image/font.h"
#include "image/image.h"
#include "image/stb_guard.h"

namespace glint {

namespace {

// UTF-8 to code points, so that labels may use the font's other characters (e.g. "±", "×"); a
// byte that does not start a valid sequence is one '?', so any string can be drawn.
std::vector<char32_t> decode_utf8(std::string_view s) {
  std::vector<char32_t> out;
  out.reserve(s.size());
  std::size_t i = 0;
  while (i < s.size()) {
    const auto b = static_cast<unsigned char>(s[i]);
    int len = 0;
    char32_t cp = 0, min = 0;
    if (b < 0x80) {
      len = 1, cp = b;
    } else if ((b & 0xe0) == 0xc0) {
      len = 2, cp = b & 0x1f, min = 0x80;
    } else if ((b & 0xf0) == 0xe0) {
      len = 3, cp = b & 0x0f, min = 0x800;
    } else if ((b & 0xf8) == 0xf0) {
      len = 4, cp = b & 0x07, min = 0x10000;
    }
    bool valid = len > 0 && i + static_cast<std::size_t>(len) <= s.size();
    for (int k = 1; valid && k < len; ++k) {
      const auto c = static_cast<unsigned char>(s[i + static_cast<std::size_t>(k)]);
      valid = (c & 0xc0) == 0x80;
      cp = (cp << 6) | (c & 0x3f);
    }
    valid = valid && cp >= min && cp <= 0x10ffff && !(cp >= 0xd800 && cp <= 0xdfff);
    if (valid) {
      out.push_back(cp);
      i += static_cast<std::size_t>(len);
    } else {
      out.push_back('?');
      ++i;
    }
  }
  return out;
}

struct Layout {
  float scale = 0;
  int baseline = 0;
  std::vector<int> glyphs;
  std::vector<float> pen;  // x of each glyph's origin
  float end = 0;           // pen after the last glyph
  int width() const { return static_cast<int>(std::ceil(end)); }
};

std::vector<int> glyphs_of(const Font& f, std::string_view text) {
  std::vector<int> glyphs;
  for (const char32_t cp : decode_utf8(text)) glyphs.push_back(f.glyph(cp));
  return glyphs;
}

Layout layout(const Font& f, std::vector<int> glyphs, int height) {
  if (height <= 0) {
    throw std::invalid_argument("text height must be positive, not " + std::to_string(height));
  }
  Layout l;
  // Pixel height = ascent - descent, so a line of `height` pixels holds every glyph of the font.
  l.scale = stbtt_ScaleForPixelHeight(&f.info(), static_cast<float>(height));
  l.baseline = static_cast<int>(std::floor(static_cast<float>(f.ascent()) * l.scale + 0.5f));
  l.glyphs = std::move(glyphs);
  float x = 0;
  for (std::size_t i = 0; i < l.glyphs.size(); ++i) {
    if (i > 0) {
      x += l.scale *
           static_cast<float>(stbtt_GetGlyphKernAdvance(&f.info(), l.glyphs[i - 1], l.glyphs[i]));
    }
    l.pen.push_back(x);
    int advance = 0, bearing = 0;
    stbtt_GetGlyphHMetrics(&f.info(), l.glyphs[i], &advance, &bearing);
    x += l.scale * static_cast<float>(advance);
  }
  l.end = x;
  return l;
}

std::uint8_t blend(std::uint8_t under, std::uint8_t over, unsigned coverage) {
  // Straight alpha in the stored (sRGB) values, as text is usually blended; integer and rounded.
  return static_cast<std::uint8_t>((under * (255u - coverage) + over * coverage + 127u) / 255u);
}

}  // namespace

int text_width(const Font& font, std::string_view text, int height) {
  return layout(font, glyphs_of(font, text), height).width();
}

int text_width(std::string_view text, int height) {
  return text_width(text_font(), text, height);
}

int draw_text(Image8& image, int x, int y, std::string_view text, Rgb8 colour, int height) {
  return draw_text(image, text_font(), x, y, text, colour, height);
}

int draw_text(Image8& image, const Font& font, int x, int y, std::string_view text, Rgb8 colour,
              int height) {
  return draw_glyphs(image, font, x, y, glyphs_of(font, text), colour, height);
}

int draw_glyphs(Image8& image, const Font& font, int x, int y, std::vector<int> glyphs, Rgb8 colour,
                int height) {
  for (const int g : glyphs) {
    if (g < 0 || g >= font.glyph_count())
      throw std::invalid_argument("glyph " + std::to_string(g) + " is not in the font");
  }
  const Layout l = layout(font, std::move(glyphs), height);
  const stbtt_fontinfo& info = font.info();
  std::vector<unsigned char> bitmap;
  for (std::size_t i = 0; i < l.glyphs.size(); ++i) {
    const float whole = std::floor(l.pen[i]);
    const float shift = l.pen[i] - whole;
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    const Font::Box* grown = font.grown_box(l.glyphs[i]);
    if (grown) {
      // stb's own rounding of a box to pixels (stbtt_GetGlyphBitmapBoxSubpixel), on the box
      // that holds the outline.
      x0 = static_cast<int>(std::floor(static_cast<float>(grown->x0) * l.scale + shift));
      y0 = static_cast<int>(std::floor(static_cast<float>(-grown->y1) * l.scale));
      x1 = static_cast<int>(std::ceil(static_cast<float>(grown->x1) * l.scale + shift));
      y1 = static_cast<int>(std::ceil(static_cast<float>(-grown->y0) * l.scale));
    } else {
      stbtt_GetGlyphBitmapBoxSubpixel(&info, l.glyphs[i], l.scale, l.scale, shift, 0.0f, &x0, &y0,
                                      &x1, &y1);
    }
    const int w = x1 - x0, h = y1 - y0;
    if (w <= 0 || h <= 0) continue;  // a space
    const int left = x + static_cast<int>(whole) + x0, top = y + l.baseline + y0;
    if (left >= image.width || top >= image.height || left + w <= 0 || top + h <= 0) continue;
    bitmap.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), 0);
    try {
      const StbScope scope;
      if (grown) {
        // What stbtt_MakeGlyphBitmapSubpixel does, with the grown box's corner as the offset.
        stbtt_vertex* vertices = nullptr;
        const int n = stbtt_GetGlyphShape(&info, l.glyphs[i], &vertices);
        stbtt__bitmap out{w, h, w, bitmap.data()};
        stbtt_Rasterize(&out, 0.35f, vertices, n, l.scale, l.scale, shift, 0.0f, x0, y0, 1,
                        nullptr);
        stbtt_FreeShape(&info, vertices);
      } else {
        stbtt_MakeGlyphBitmapSubpixel(&info, bitmap.data(), w, h, w, l.scale, l.scale, shift, 0.0f,
                                      l.glyphs[i]);
      }
    } catch (const StbAssertion& e) {
      font.left_blank(l.glyphs[i], height, e.what());
      continue;
    }
    for (int r = 0; r < h; ++r) {
      const int py = top + r;
      if (py < 0 || py >= image.height) continue;
      for (int c = 0; c < w; ++c) {
        const int px = left + c;
        const unsigned a = bitmap[static_cast<std::size_t>(r) * static_cast<std::size_t>(w) +
                                  static_cast<std::size_t>(c)];
        if (px < 0 || px >= image.width || a == 0) continue;
        std::uint8_t* p =
            &image
                 .pixels[3 * (static_cast<std::size_t>(py) * static_cast<std::size_t>(image.width) +
                              static_cast<std::size_t>(px))];
        for (int k = 0; k < 3; ++k) p[k] = blend(p[k], colour[k], a);
      }
    }
  }
  return l.width();
}

std::string fit_text(std::string_view text, int max_width, int height) {
  if (text_width(text, height) <= max_width) return std::string(text);
  // U+2026 when the font has it (DejaVu does); three dots otherwise.
  const std::string ellipsis = text_font().has(0x2026) ? "\xe2\x80\xa6" : "...";
  std::size_t cut = text.size();
  while (cut > 0) {
    // Step back one code point: over continuation bytes (10xxxxxx) to the byte starting it.
    do {
      --cut;
    } while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xc0) == 0x80);
    std::string candidate(text.substr(0, cut));
    while (!candidate.empty() && candidate.back() == ' ') candidate.pop_back();
    candidate += ellipsis;
    if (text_width(candidate, height) <= max_width) return candidate;
  }
  return text_width(ellipsis, height) <= max_width ? ellipsis : std::string();
}

}  // namespace glint
