// A TrueType font's tables checked before stb_truetype may read them. stb does no bounds checking:
// it follows every offset and count in the file, and a truncated or hostile font makes it read
// outside the buffer, recurse without end through composite glyphs or allocate without limit.
// check_truetype walks every table, offset and count that the stb calls of text.cpp read (the
// table directory, cmap's subtable, head, hhea, maxp, hmtx, loca, every glyph of glyf, and GPOS
// or kern for kerning) and refuses the font unless each read stays inside its table; it also
// bounds the glyphs' extents, composite depth and outline sizes, so that drawing any glyph at a
// label's height takes bounded memory and time. tests/fuzz/fuzz_font.cpp holds it to that under
// ASan, with the font between guard pages.
#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>

namespace glint {

// What is wrong with a font, in a phrase ("table 'glyf': glyph 36 ends past the table").
class FontError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Limits on what is accepted, stated in the user guide (src/cli/README.md).
inline constexpr int kMaxCompositeDepth = 16;               // composite glyphs within composites
inline constexpr std::int64_t kMaxGlyphVertices = 1 << 18;  // outline points of one glyph
// Of all glyphs together (composites count their components' points): Font builds every outline
// once when it loads (DejaVu Sans: about 240 000).
inline constexpr std::int64_t kMaxFontVertices = 1 << 24;
// Glyph coordinates, advances and kerning, in multiples of the font's height (ascent - descent):
// DejaVu's widest glyphs are under 3 heights, so a label glyph stays within a few label heights.
inline constexpr int kMaxGlyphExtent = 16;

struct TrueTypeFacts {
  int offset = 0;  // of the font in the file (a collection holds several; glint takes the first)
  int glyph_count = 0;  // glyph ids 0..glyph_count-1 are safe to hand to stb; no other is
};

// Checks the font in data[0, size); throws FontError saying what is wrong.
TrueTypeFacts check_truetype(const unsigned char* data, std::size_t size);

}  // namespace glint
