// The font check (image/truetype_check.h) on DejaVu and on DejaVu subsets (tests/fuzz/corpus/font)
// changed in one field each: what stb_truetype would read out of bounds, recurse on or assert on
// is refused with InputError naming the file, the field and what is wrong.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "image/font.h"
#include "image/truetype_check.h"
#include "io/input_error.h"
#include "test_support.h"

namespace glint {
namespace {

const std::string kSeeds = std::string(GLINT_SOURCE_DIR) + "/tests/fuzz/corpus/font/";

// A font's bytes with the few table lookups the cases need.
struct Bytes {
  std::string b;

  unsigned u16(std::size_t at) const {
    return (static_cast<unsigned char>(b[at]) << 8) | static_cast<unsigned char>(b[at + 1]);
  }
  std::uint32_t u32(std::size_t at) const { return (std::uint32_t{u16(at)} << 16) | u16(at + 2); }
  void set16(std::size_t at, unsigned v) {
    b[at] = static_cast<char>(v >> 8);
    b[at + 1] = static_cast<char>(v & 0xff);
  }
  std::size_t table(const std::string& tag) const {
    for (unsigned i = 0; i < u16(4); ++i)
      if (b.compare(12 + 16 * i, 4, tag) == 0) return u32(12 + 16 * i + 8);
    ADD_FAILURE() << "no table " << tag;
    return 0;
  }
  // The offset of glyph g's data.
  std::size_t glyph(int g) const {
    const std::size_t loca = table("loca");
    const bool longs = u16(table("head") + 50) == 1;
    const std::size_t offset = longs ? u32(loca + 4 * static_cast<std::size_t>(g))
                                     : 2 * std::size_t{u16(loca + 2 * static_cast<std::size_t>(g))};
    return table("glyf") + offset;
  }
};

Bytes seed(const std::string& name) {
  return {test::read_file(kSeeds + name)};
}

std::unique_ptr<Font> parse(const Bytes& f) {
  return std::make_unique<Font>(std::vector<unsigned char>(f.b.begin(), f.b.end()), "f.ttf",
                                "GLINT_FONT");
}

// The message of the refusal, or "" if the font was accepted.
std::string refusal(const Bytes& f) {
  try {
    parse(f);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "f.ttf");
    EXPECT_EQ(e.field(), "GLINT_FONT");
    return e.message();
  }
  return "";
}

TEST(FontCheck, AcceptsDejaVuAndTheSeeds) {
  const std::unique_ptr<Font> dejavu = read_font(kDefaultFont, "font");
  EXPECT_GT(dejavu->glyph_count(), 5000);
  EXPECT_TRUE(dejavu->has(0x2026));
  for (const char* name :
       {"dejavu_sans_labels_gpos.ttf", "dejavu_sans_accents_kern.ttf", "dejavu_mono_digits.ttf",
        "dejavu_math_cmap12.ttf", "dejavu_collection.ttc"}) {
    EXPECT_EQ(refusal(seed(name)), "") << name;
  }
}

TEST(FontCheck, RefusesCffOutlines) {
  Bytes f = seed("dejavu_mono_digits.ttf");
  f.b.replace(0, 4, "OTTO");
  EXPECT_NE(refusal(f).find("OpenType CFF outlines"), std::string::npos);
}

TEST(FontCheck, RefusesACompositeThatContainsItself) {
  Bytes f = seed("dejavu_sans_accents_kern.ttf");
  const int g = parse(f)->glyph(0xc0);  // À: A and a grave accent
  const std::size_t at = f.glyph(g);
  ASSERT_LT(static_cast<std::int16_t>(f.u16(at)), 0) << "not a composite";
  f.set16(at + 12, static_cast<unsigned>(g));  // its first component: itself
  EXPECT_NE(refusal(f).find("contains itself"), std::string::npos) << refusal(f);
}

TEST(FontCheck, RefusesPointMatchedComponents) {
  Bytes f = seed("dejavu_sans_accents_kern.ttf");
  const std::size_t at = f.glyph(parse(f)->glyph(0xc0));
  f.set16(at + 10, f.u16(at + 10) & ~2u);  // ARGS_ARE_XY_VALUES cleared: stb asserts
  EXPECT_NE(refusal(f).find("matching points"), std::string::npos) << refusal(f);
}

TEST(FontCheck, RefusesACmapFormatStbAssertsOn) {
  Bytes f = seed("dejavu_mono_digits.ttf");
  const std::size_t cmap = f.table("cmap");
  for (unsigned i = 0; i < f.u16(cmap + 2); ++i) f.set16(cmap + f.u32(cmap + 4 + 8 * i + 4), 2);
  EXPECT_NE(refusal(f).find("format 2"), std::string::npos) << refusal(f);
}

TEST(FontCheck, RefusesAFontWithoutHeight) {
  Bytes f = seed("dejavu_mono_digits.ttf");
  const std::size_t hhea = f.table("hhea");
  f.set16(hhea + 6, f.u16(hhea + 4));  // descent = ascent
  EXPECT_NE(refusal(f).find("leave no height"), std::string::npos) << refusal(f);
}

// A font 1 unit high: its glyphs (and their bitmaps) would be a thousand label heights wide.
TEST(FontCheck, RefusesGlyphsFarOutsideTheLine) {
  Bytes f = seed("dejavu_mono_digits.ttf");
  const std::size_t hhea = f.table("hhea");
  f.set16(hhea + 4, 1);
  f.set16(hhea + 6, 0);
  EXPECT_NE(refusal(f).find("is more than 16 times the font's height (1 units)"), std::string::npos)
      << refusal(f);
}

TEST(FontCheck, RefusesAGlyphTableShorterThanItsGlyphs) {
  Bytes f = seed("dejavu_sans_labels_gpos.ttf");
  // The file is whole; only the table directory says 'glyf' is 100 bytes.
  for (unsigned i = 0; i < f.u16(4); ++i) {
    if (f.b.compare(12 + 16 * i, 4, "glyf") != 0) continue;
    f.set16(12 + 16 * i + 12, 0);
    f.set16(12 + 16 * i + 14, 100);
  }
  EXPECT_NE(refusal(f).find("is not inside table 'glyf'"), std::string::npos) << refusal(f);
}

// maxp counting fewer glyphs than the cmap names: those ids are never handed to stb.
TEST(FontCheck, GlyphIdsBeyondTheCountAreQuestionMarks) {
  Bytes f = seed("dejavu_sans_labels_gpos.ttf");
  const int cut = parse(f)->glyph('Z');
  f.set16(f.table("maxp") + 4, static_cast<unsigned>(cut));
  const std::unique_ptr<Font> font = parse(f);
  EXPECT_EQ(font->glyph_count(), cut);
  EXPECT_EQ(font->glyph('Z'), font->glyph('?'));
  EXPECT_FALSE(font->has('Z'));
  for (char32_t c = 0x20; c < 0x7f; ++c) EXPECT_LT(font->glyph(c), cut) << static_cast<int>(c);
}

// DejaVu Sans Mono Bold (fonts-dejavu-core) has glyphs whose outline, as stb builds it, leaves the
// box in their header, which stb sizes bitmaps by (its rasteriser asserts on edges outside). They
// are drawn in a box grown to hold the outline, and something is drawn.
TEST(FontCheck, OutlinesOutsideTheirBoxAreDrawnInAGrownBox) {
  const std::unique_ptr<Font> font =
      read_font("/usr/share/fonts/truetype/dejavu/DejaVuSansMono-Bold.ttf", "GLINT_FONT");
  int grown = 0;
  for (int g = 0; g < font->glyph_count(); ++g) {
    if (font->grown_box(g) == nullptr) continue;
    ++grown;
    Image8 image(200, 200);
    draw_glyphs(image, *font, 100, 90, {g}, {255, 255, 255}, 14);
    EXPECT_NE(std::count(image.pixels.begin(), image.pixels.end(), 0), image.pixels.size())
        << "glyph " << g;
  }
  EXPECT_GT(grown, 0);
  // The default font has none: its text takes stb's own path, pixel for pixel as before.
  for (int g = 0; g < text_font().glyph_count(); ++g) EXPECT_EQ(text_font().grown_box(g), nullptr);
}

// Every prefix of a font is accepted or refused with InputError, never read past its end (the
// sanitizer builds would report that).
TEST(FontCheck, EveryPrefixIsAcceptedOrRefused) {
  const Bytes whole = seed("dejavu_mono_digits.ttf");
  int refused = 0;
  for (std::size_t n = 0; n < whole.b.size(); n += 7) {
    if (!refusal({whole.b.substr(0, n)}).empty()) ++refused;
  }
  EXPECT_GT(refused, 0);
  EXPECT_EQ(refusal({whole.b.substr(0, 11)}), "shorter than a font's header (12 bytes)");
}

}  // namespace
}  // namespace glint
