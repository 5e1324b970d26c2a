// The font text is drawn with (image.h's draw_text): a TrueType file read as an input, with a size
// cap and only if it is a regular file, then checked table by table (truetype_check.h) before
// stb_truetype sees it. Exposed for the fuzz harness (tests/fuzz/fuzz_font.cpp), which draws with
// fonts it makes.
#pragma once

#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "image/image.h"

struct stbtt_fontinfo;

namespace glint {

// Real TrueType fonts are a few MiB at most (DejaVu Sans: 0.7 MiB; large CJK TrueType fonts
// stay under 30 MiB); a larger file is refused before it is read.
inline constexpr std::size_t kMaxFontBytes = std::size_t{32} << 20;
inline constexpr const char* kDefaultFont = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

class Font {
 public:
  // The font in data[0, size), which must outlive the Font (it is not copied); `bytes` is kept.
  // A font check_truetype refuses throws InputError(file, 0, field, what is wrong).
  Font(const unsigned char* data, std::size_t size, const std::string& file,
       const std::string& field);
  Font(std::vector<unsigned char> bytes, const std::string& file, const std::string& field);
  ~Font();
  Font(const Font&) = delete;
  Font& operator=(const Font&) = delete;

  const stbtt_fontinfo& info() const { return *info_; }
  int ascent() const { return ascent_; }
  int glyph_count() const { return glyphs_; }
  // The glyph drawn for a code point: '?' for control characters and for what the font lacks.
  int glyph(char32_t cp) const;
  bool has(char32_t cp) const;

  // A glyph's box in font units (y up).
  struct Box {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  };
  // The box holding a glyph's outline when that leaves the box of the glyph's header, which stb
  // sizes bitmaps by; nullptr when the header's box holds it (nearly always).
  const Box* grown_box(int glyph) const;
  // A glyph stb_truetype failed to rasterise (stb_guard.h): warns on stderr, once per glyph.
  void left_blank(int glyph, int height, const char* why) const;

 private:
  void init(const unsigned char* data, std::size_t size, const std::string& file,
            const std::string& field);
  int lookup(char32_t cp) const;  // 0 (missing) unless a glyph id stb may be given

  std::vector<unsigned char> bytes_;  // stbtt_fontinfo points into it: never reallocated
  std::unique_ptr<stbtt_fontinfo> info_;
  std::string file_;
  mutable std::mutex blank_mutex_;  // heat maps are drawn on several threads
  mutable std::set<int> blank_;
  int ascent_ = 0;
  int glyphs_ = 0;
  int question_ = 0;
  std::map<int, Box> grown_;
};

// Reads the font file at `path`: a regular file (a folder, FIFO, device or socket is refused
// without being opened) of 1..kMaxFontBytes bytes, read with a bounded read, then checked. Throws
// InputError(path, 0, field, ...).
std::unique_ptr<Font> read_font(const std::string& path, const std::string& field);

// The font of draw_text: GLINT_FONT if set and not empty (field 'GLINT_FONT'), else kDefaultFont
// (field 'font'); loaded by the first call that succeeds, the errors naming the Debian package.
const Font& text_font();

// draw_text and text_width with a given font.
int draw_text(Image8& image, const Font& font, int x, int y, std::string_view text, Rgb8 colour,
              int height);
int text_width(const Font& font, std::string_view text, int height);
// Glyphs by id, laid out and drawn as draw_text does (kerning included); an id outside
// 0..glyph_count()-1 throws std::invalid_argument.
int draw_glyphs(Image8& image, const Font& font, int x, int y, std::vector<int> glyphs, Rgb8 colour,
                int height);

}  // namespace glint
