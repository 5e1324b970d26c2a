// Hand-written rather than through a font library: the check must follow stb_truetype's reads
// (which tables, in which order, which counts it trusts), not a font's validity in general.
// FreeType accepting a font says nothing about where stb will read; the PNGs keep stb's rasteriser.
//
// Offsets are absolute (from the start of the file), held in 64 bits, so no sum of file values can
// wrap; every read is checked against the table it belongs to, which is itself inside the file.
#include "image/truetype_check.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

namespace glint {

namespace {

using u64 = std::uint64_t;
using i64 = std::int64_t;

// A table as stb sees it: present when its directory entry has a non-zero offset, even if its
// length is 0 (then every read of it is refused).
struct Table {
  std::string tag;
  u64 begin = 0, end = 0;
  bool present() const { return begin > 0; }
};

// A composite's state in the depth-first walk over glyphs.
enum class Visit : std::uint8_t { kNew, kOpen, kDone };

struct GlyphSize {
  i64 extent = 0;    // largest |coordinate| of its outline, font units
  i64 vertices = 0;  // what stb allocates for it (its own bound: points + 2 per contour)
};

class Checker {
 public:
  Checker(const unsigned char* data, std::size_t size) : d_(data), size_(size) {}

  TrueTypeFacts run() {
    const u64 start = font_start();
    table_directory(start);
    const Table cmap = required("cmap"), head = required("head"), hhea = required("hhea"),
                hmtx = required("hmtx"), maxp = required("maxp");
    glyf_ = find("glyf");
    if (!glyf_.present()) {
      fail(find("CFF ").present() || find("CFF2").present()
               ? "OpenType CFF outlines: only TrueType ('glyf') outlines are supported"
               : "no 'glyf' table (TrueType outlines)");
    }
    loca_ = required("loca");

    need(head, head.begin, 54, "the header");
    loca_format_ = u16(head.begin + 50);
    if (loca_format_ > 1) fail("table 'head': unknown indexToLocFormat " + num(loca_format_));
    need(maxp, maxp.begin, 6, "the glyph count");
    glyphs_ = u16(maxp.begin + 4);
    if (glyphs_ == 0) fail("table 'maxp': no glyphs");
    horizontal(hhea, hmtx);
    glyph_table();
    character_map(cmap);
    const Table gpos = find("GPOS");
    // stb kerns with GPOS when the font has it and never reads 'kern' then.
    if (gpos.present()) {
      positioning(gpos);
    } else if (const Table kern = find("kern"); kern.present()) {
      kerning(kern);
    }
    return {static_cast<int>(start), static_cast<int>(glyphs_)};
  }

 private:
  [[noreturn]] static void fail(const std::string& what) { throw FontError(what); }
  static std::string num(i64 v) { return std::to_string(v); }

  unsigned u8(u64 at) const { return d_[at]; }
  unsigned u16(u64 at) const { return (u8(at) << 8) | u8(at + 1); }
  int s16(u64 at) const { return static_cast<std::int16_t>(u16(at)); }
  u64 u32(u64 at) const { return (u64{u16(at)} << 16) | u16(at + 2); }

  // [at, at + len) must lie in the table.
  void need(const Table& t, u64 at, u64 len, const std::string& what) const {
    if (at < t.begin || at > t.end || len > t.end - at) {
      fail("table '" + t.tag + "': " + what + " (" + num(static_cast<i64>(len)) +
           " bytes at offset " + num(static_cast<i64>(at - std::min(at, t.begin))) +
           ") runs past the table's end (" + num(static_cast<i64>(t.end - t.begin)) + " bytes)");
    }
  }

  u64 font_start() {
    if (size_ < 12) fail("shorter than a font's header (12 bytes)");
    u64 start = 0;
    if (std::memcmp(d_, "ttcf", 4) == 0) {
      if (size_ < 16) fail("a font collection cut short in its header");
      const u64 version = u32(4);
      if (version != 0x10000 && version != 0x20000)
        fail("a font collection of unknown version " + num(static_cast<i64>(version)));
      if (static_cast<std::int32_t>(u32(8)) < 1) fail("a font collection without fonts");
      start = u32(12);
      if (start > size_ || size_ - start < 12)
        fail("the collection's first font (offset " + num(static_cast<i64>(start)) +
             ") runs past the end of the file");
    }
    const u64 version = u32(start);
    if (std::memcmp(d_ + start, "OTTO", 4) == 0)
      fail("OpenType CFF outlines: only TrueType ('glyf') outlines are supported");
    if (version != 0x10000 && version != 0x31000000 && std::memcmp(d_ + start, "true", 4) != 0)
      fail("not a TrueType font (its first bytes are no sfnt version)");
    return start;
  }

  void table_directory(u64 start) {
    dir_ = start + 12;
    tables_ = u16(start + 4);
    if (16 * tables_ > size_ - dir_)
      fail("the table directory (" + num(tables_) + " tables) runs past the end of the file");
  }

  // The first entry with the tag, as stb finds it; an offset of 0 is no table to stb either.
  Table find(const char* tag) const {
    for (u64 i = 0; i < tables_; ++i) {
      const u64 entry = dir_ + 16 * i;
      if (std::memcmp(d_ + entry, tag, 4) != 0) continue;
      const u64 offset = u32(entry + 8), length = u32(entry + 12);
      if (offset == 0) return {tag, 0, 0};
      if (offset > size_ || length > size_ - offset)
        fail(std::string("table '") + tag + "' (" + num(static_cast<i64>(length)) +
             " bytes at offset " + num(static_cast<i64>(offset)) +
             ") runs past the end of the file (" + num(static_cast<i64>(size_)) + " bytes)");
      return {tag, offset, offset + length};
    }
    return {tag, 0, 0};
  }

  Table required(const char* tag) const {
    Table t = find(tag);
    if (!t.present()) fail(std::string("no '") + tag + "' table");
    return t;
  }

  i64 limit() const { return i64{kMaxGlyphExtent} * height_; }

  void bounded(i64 value, const std::string& what) const {
    if (value > limit() || value < -limit())
      fail(what + " " + num(value) + " is more than " + num(kMaxGlyphExtent) +
           " times the font's height (" + num(height_) + " units)");
  }

  void horizontal(const Table& hhea, const Table& hmtx) {
    need(hhea, hhea.begin, 36, "the header");
    const int ascent = s16(hhea.begin + 4), descent = s16(hhea.begin + 6);
    height_ = i64{ascent} - descent;
    if (height_ < 1)
      fail("table 'hhea': ascent " + num(ascent) + " and descent " + num(descent) +
           " leave no height");
    metrics_ = u16(hhea.begin + 34);
    if (metrics_ == 0) fail("table 'hhea': no horizontal metrics");
    const u64 shorts = glyphs_ > metrics_ ? glyphs_ - metrics_ : 0;
    need(hmtx, hmtx.begin, 4 * metrics_ + 2 * shorts, "the metrics of " + num(glyphs_) + " glyphs");
    for (u64 g = 0; g < metrics_; ++g)
      bounded(u16(hmtx.begin + 4 * g),
              "table 'hmtx': glyph " + num(static_cast<i64>(g)) + "'s advance");
  }

  u64 glyph_offset(u64 g) const {
    return loca_format_ == 0 ? 2 * u64{u16(loca_.begin + 2 * g)} : u32(loca_.begin + 4 * g);
  }

  void glyph_table() {
    need(loca_, loca_.begin, (glyphs_ + 1) * (loca_format_ == 0 ? 2 : 4),
         "the offsets of " + num(glyphs_) + " glyphs");
    for (u64 g = 0; g < glyphs_; ++g) {
      const u64 begin = glyph_offset(g), end = glyph_offset(g + 1);
      if (end < begin || end > glyf_.end - glyf_.begin)
        fail("table 'loca': glyph " + num(static_cast<i64>(g)) + " (bytes " +
             num(static_cast<i64>(begin)) + ".." + num(static_cast<i64>(end)) +
             ") is not inside table 'glyf' (" + num(static_cast<i64>(glyf_.end - glyf_.begin)) +
             " bytes)");
    }
    visit_.assign(glyphs_, Visit::kNew);
    sizes_.assign(glyphs_, GlyphSize{});
    i64 total = 0;
    for (u64 g = 0; g < glyphs_; ++g) {
      glyph(g, 0);
      total += sizes_[g].vertices;
      if (total > kMaxFontVertices)
        fail("table 'glyf': the outlines have more than " + num(kMaxFontVertices) +
             " points in all");
    }
  }

  void glyph(u64 g, int depth) {
    if (visit_[g] == Visit::kDone) return;
    const u64 begin = glyf_.begin + glyph_offset(g), end = glyf_.begin + glyph_offset(g + 1);
    visit_[g] = Visit::kOpen;
    if (begin != end) {  // stb draws nothing for an empty glyph and reads none of it
      const Table t{"glyf", begin, end};
      const std::string name = "glyph " + num(static_cast<i64>(g));
      need(t, begin, 10, name + "'s header");
      for (int k = 0; k < 4; ++k) bounded(s16(begin + 2 + 2 * k), name + "'s bounding box");
      const int contours = s16(begin);
      if (contours > 0) sizes_[g] = simple_glyph(t, name, static_cast<u64>(contours));
      if (contours < 0) sizes_[g] = composite_glyph(t, name, depth);
    }
    visit_[g] = Visit::kDone;
  }

  GlyphSize simple_glyph(const Table& t, const std::string& name, u64 contours) {
    u64 at = t.begin + 10;
    need(t, at, 2 * contours + 2, name + "'s contour ends");
    i64 previous = -1;
    std::vector<u64> firsts(contours);
    for (u64 c = 0; c < contours; ++c) {
      const i64 last = u16(at + 2 * c);
      if (last <= previous) fail("table 'glyf': " + name + "'s contour ends are not increasing");
      firsts[c] = static_cast<u64>(previous + 1);
      previous = last;
    }
    const u64 points = static_cast<u64>(previous) + 1;
    at += 2 * contours;
    at += 2 + u16(at);  // the instructions
    need(t, at, 0, name + "'s instructions");
    // Flags: one byte, then a repeat count when bit 3 is set; stb reads exactly this.
    std::vector<unsigned char> flags(points);
    unsigned repeat = 0, f = 0;
    for (u64 i = 0; i < points; ++i) {
      if (repeat == 0) {
        need(t, at, 1, name + "'s point flags");
        f = u8(at++);
        if (f & 8) {
          need(t, at, 1, name + "'s point flags");
          repeat = u8(at++);
        }
      } else {
        --repeat;
      }
      flags[i] = static_cast<unsigned char>(f);
    }
    // A contour starting off the curve makes stb read the point after it as well: past the
    // outline (or into the next contour) when the contour has only that point.
    for (u64 c = 0; c < contours; ++c) {
      const u64 last = c + 1 < contours ? firsts[c + 1] - 1 : points - 1;
      if (!(flags[firsts[c]] & 1) && last == firsts[c])
        fail("table 'glyf': " + name + " has a one-point contour off the curve");
    }
    i64 extent = 0;
    // x with bits 1 (a byte) and 4 (its sign, or "same as before"), then y with bits 2 and 5.
    for (const unsigned short_bit : {2u, 4u}) {
      const unsigned same_bit = short_bit << 3;
      std::int32_t v = 0;
      for (u64 i = 0; i < points; ++i) {
        if (flags[i] & short_bit) {
          need(t, at, 1, name + "'s coordinates");
          const std::int32_t dv = static_cast<std::int32_t>(u8(at++));
          v += (flags[i] & same_bit) ? dv : -dv;
        } else if (!(flags[i] & same_bit)) {
          need(t, at, 2, name + "'s coordinates");
          v += s16(at);
          at += 2;
        }
        extent = std::max<i64>(extent, std::abs(i64{static_cast<std::int16_t>(v)}));
      }
    }
    bounded(extent, "table 'glyf': " + name + "'s outline reaches");
    return {extent, static_cast<i64>(points + 2 * contours)};
  }

  GlyphSize composite_glyph(const Table& t, const std::string& name, int depth) {
    GlyphSize size;
    u64 at = t.begin + 10;
    for (bool more = true; more;) {
      need(t, at, 4, name + "'s components");
      const unsigned flags = u16(at), component = u16(at + 2);
      at += 4;
      // stb asserts on components placed by matching points: refused here instead.
      if (!(flags & 2))
        fail("table 'glyf': " + name + " places a component by matching points (unsupported)");
      double e = 0, f = 0, a = 1, b = 0, c = 0, dd = 1;
      if (flags & 1) {
        need(t, at, 4, name + "'s component offset");
        e = s16(at), f = s16(at + 2), at += 4;
      } else {
        need(t, at, 2, name + "'s component offset");
        e = static_cast<signed char>(u8(at)), f = static_cast<signed char>(u8(at + 1)), at += 2;
      }
      const auto f2dot14 = [&](u64 p) { return s16(p) / 16384.0; };
      if (flags & 8) {
        need(t, at, 2, name + "'s component scale");
        a = dd = f2dot14(at), at += 2;
      } else if (flags & 0x40) {
        need(t, at, 4, name + "'s component scale");
        a = f2dot14(at), dd = f2dot14(at + 2), at += 4;
      } else if (flags & 0x80) {
        need(t, at, 8, name + "'s component transform");
        a = f2dot14(at), b = f2dot14(at + 2), c = f2dot14(at + 4), dd = f2dot14(at + 6), at += 8;
      }
      more = flags & 0x20;
      if (component >= glyphs_) continue;  // stb draws nothing for it
      if (visit_[component] == Visit::kOpen)
        fail("table 'glyf': " + name + " contains itself (through glyph " + num(component) + ")");
      if (depth + 1 > kMaxCompositeDepth)
        fail("table 'glyf': " + name + " nests composites more than " + num(kMaxCompositeDepth) +
             " deep");
      glyph(component, depth + 1);
      const GlyphSize& part = sizes_[component];
      // stb scales x by |(a, b)| and y by |(c, d)| on top of the matrix, in float, and stores the
      // result in int16: bound it well inside that range.
      const double x = std::hypot(a, b) * ((std::abs(a) + std::abs(c)) * part.extent + std::abs(e));
      const double y =
          std::hypot(c, dd) * ((std::abs(b) + std::abs(dd)) * part.extent + std::abs(f));
      const double reach = std::ceil(std::max(x, y));
      if (reach > 32000) fail("table 'glyf': " + name + "'s components reach past 32000 units");
      bounded(static_cast<i64>(reach), "table 'glyf': " + name + "'s outline reaches");
      size.extent = std::max(size.extent, static_cast<i64>(reach));
      size.vertices += part.vertices;
      if (size.vertices > kMaxGlyphVertices)
        fail("table 'glyf': " + name + " has more than " + num(kMaxGlyphVertices) +
             " outline points");
    }
    return size;
  }

  void character_map(const Table& cmap) {
    need(cmap, cmap.begin, 4, "the header");
    const u64 count = u16(cmap.begin + 2);
    need(cmap, cmap.begin + 4, 8 * count, "the encoding records");
    // stb takes the last Unicode subtable: platform 0, or platform 3 with encoding 1 or 10.
    u64 sub = 0;
    bool found = false;
    for (u64 i = 0; i < count; ++i) {
      const u64 record = cmap.begin + 4 + 8 * i;
      const unsigned platform = u16(record), encoding = u16(record + 2);
      if (platform == 0 || (platform == 3 && (encoding == 1 || encoding == 10))) {
        sub = u32(record + 4);
        found = true;
      }
    }
    if (!found) fail("table 'cmap': no Unicode subtable");
    const u64 at = cmap.begin + sub;
    need(cmap, at, 2, "the Unicode subtable");
    const unsigned format = u16(at);
    const std::string what = "the format " + num(format) + " subtable";
    switch (format) {
      case 0:
        need(cmap, at, 4, what);
        need(cmap, at, std::max<u64>(6, u16(at + 2)), what);
        break;
      case 6:
        need(cmap, at, 10, what);
        need(cmap, at + 10, 2 * u64{u16(at + 8)}, what + "'s glyphs");
        break;
      case 4:
        segment_map(cmap, at);
        break;
      case 12:
      case 13:
        need(cmap, at, 16, what);
        need(cmap, at + 16, 12 * u32(at + 12), what + "'s groups");
        break;
      default:
        fail("table 'cmap': the Unicode subtable has format " + num(format) +
             " (supported: 0, 4, 6, 12, 13)");
    }
  }

  void segment_map(const Table& cmap, u64 at) {
    need(cmap, at, 14, "the format 4 subtable");
    const unsigned seg_x2 = u16(at + 6);
    const u64 segments = seg_x2 / 2;
    if (segments == 0 || seg_x2 % 2 != 0)
      fail("table 'cmap': format 4 with segCountX2 " + num(seg_x2));
    // stb's binary search trusts searchRange, entrySelector and rangeShift: they must be the
    // values the segment count implies, which keep it inside the segments.
    unsigned selector = 0;
    while ((u64{2} << selector) <= segments) ++selector;
    const u64 range = u64{2} << selector;
    if (u16(at + 8) != range || u16(at + 10) != selector || u16(at + 12) != 2 * segments - range)
      fail("table 'cmap': format 4's searchRange, entrySelector and rangeShift do not match its " +
           num(static_cast<i64>(segments)) + " segments");
    need(cmap, at, 16 + 8 * segments, "the format 4 segments");
    const u64 ends = at + 14, starts = ends + 2 * segments + 2,
              range_offsets = starts + 4 * segments;
    for (u64 i = 0; i < segments; ++i) {
      const u64 first = u16(starts + 2 * i), last = u16(ends + 2 * i);
      const u64 offset = u16(range_offsets + 2 * i);
      if (offset == 0 || first > last) continue;
      need(cmap, range_offsets + 2 * i + offset, 2 * (last - first + 1),
           "the glyphs of format 4's segment " + num(static_cast<i64>(i)));
    }
  }

  // stb's GPOS kerning: pair adjustments (lookup type 2) whose values are one x advance.
  void positioning(const Table& gpos) {
    need(gpos, gpos.begin, 4, "the version");
    if (u16(gpos.begin) != 1 || u16(gpos.begin + 2) != 0) return;  // stb reads no further
    need(gpos, gpos.begin, 10, "the header");
    const u64 list = gpos.begin + u16(gpos.begin + 8);
    need(gpos, list, 2, "the lookup list");
    const u64 lookups = u16(list);
    need(gpos, list + 2, 2 * lookups, "the lookup list");
    for (u64 i = 0; i < lookups; ++i) {
      const u64 lookup = list + u16(list + 2 + 2 * i);
      need(gpos, lookup, 6, "a lookup");
      if (u16(lookup) != 2) continue;
      const u64 subtables = u16(lookup + 4);
      need(gpos, lookup + 6, 2 * subtables, "a lookup's subtables");
      for (u64 s = 0; s < subtables; ++s) pair_adjustment(gpos, lookup + u16(lookup + 6 + 2 * s));
    }
  }

  // The largest coverage index a glyph may get, or -1 for a coverage stb does not read.
  i64 coverage(const Table& gpos, u64 at) {
    need(gpos, at, 4, "a coverage table");
    const u64 count = u16(at + 2);
    switch (u16(at)) {
      case 1:
        need(gpos, at + 4, 2 * count, "a coverage table's glyphs");
        return static_cast<i64>(count) - 1;
      case 2: {
        need(gpos, at + 4, 6 * count, "a coverage table's ranges");
        i64 largest = -1;
        for (u64 r = 0; r < count; ++r) {
          const u64 range = at + 4 + 6 * r;
          const i64 first = u16(range), last = u16(range + 2), index = u16(range + 4);
          if (first <= last) largest = std::max(largest, index + last - first);
        }
        return largest;
      }
      default:
        return -1;
    }
  }

  void class_definition(const Table& gpos, u64 at) {
    need(gpos, at, 2, "a class definition");
    if (u16(at) == 1) {
      need(gpos, at, 6, "a class definition");
      need(gpos, at + 6, 2 * u64{u16(at + 4)}, "a class definition's classes");
    } else if (u16(at) == 2) {
      need(gpos, at, 4, "a class definition");
      need(gpos, at + 4, 6 * u64{u16(at + 2)}, "a class definition's ranges");
    }
  }

  void pair_adjustment(const Table& gpos, u64 at) {
    need(gpos, at, 4, "a pair adjustment");
    // stb looks the first glyph up in the coverage before it looks at the format.
    const i64 largest = coverage(gpos, at + u16(at + 2));
    if (largest < 0) return;
    const unsigned format = u16(at);
    if (format != 1 && format != 2) return;
    need(gpos, at, 8, "a pair adjustment");
    if (u16(at + 4) != 4 || u16(at + 6) != 0) return;  // stb kerns only with these value formats
    if (format == 1) {
      need(gpos, at, 10, "a pair adjustment");
      const u64 sets = u16(at + 8);
      // stb reads a pair set's offset and count for any coverage index before comparing it with
      // the number of sets.
      need(gpos, at + 10, 2 * static_cast<u64>(largest + 1), "a pair adjustment's pair sets");
      for (u64 i = 0; i <= static_cast<u64>(largest); ++i) {
        const u64 set = at + u16(at + 10 + 2 * i);
        need(gpos, set, 2, "a pair set");
        if (i >= sets) continue;
        const u64 pairs = u16(set);
        need(gpos, set + 2, 4 * pairs, "a pair set's pairs");
        for (u64 p = 0; p < pairs; ++p) bounded(s16(set + 4 + 4 * p), "table 'GPOS': a kerning");
      }
      return;
    }
    need(gpos, at, 16, "a class pair adjustment");
    class_definition(gpos, at + u16(at + 8));
    class_definition(gpos, at + u16(at + 10));
    const u64 values = u64{u16(at + 12)} * u16(at + 14);
    need(gpos, at + 16, 2 * values, "a class pair adjustment's values");
    for (u64 v = 0; v < values; ++v) bounded(s16(at + 16 + 2 * v), "table 'GPOS': a kerning");
  }

  void kerning(const Table& kern) {
    need(kern, kern.begin, 4, "the header");
    if (u16(kern.begin + 2) < 1) return;
    need(kern, kern.begin, 10, "the first subtable");
    if (u16(kern.begin + 8) != 1) return;
    need(kern, kern.begin, 12, "the first subtable");
    const u64 pairs = u16(kern.begin + 10);
    need(kern, kern.begin + 18, 6 * pairs, "the kerning pairs");
    for (u64 p = 0; p < pairs; ++p)
      bounded(s16(kern.begin + 22 + 6 * p), "table 'kern': a kerning");
  }

  const unsigned char* d_;
  u64 size_;
  u64 dir_ = 0, tables_ = 0;
  Table glyf_, loca_;
  unsigned loca_format_ = 0;
  u64 glyphs_ = 0, metrics_ = 0;
  i64 height_ = 1;
  std::vector<Visit> visit_;
  std::vector<GlyphSize> sizes_;
};

}  // namespace

TrueTypeFacts check_truetype(const unsigned char* data, std::size_t size) {
  return Checker(data, size).run();
}

}  // namespace glint
