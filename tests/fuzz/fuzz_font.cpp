// The font harness: a TrueType file as GLINT_FONT would give it. Font (image/font.h) accepts it or
// refuses it with InputError, as glint does with exit 2; an accepted font then has the characters
// of glint's labels and its first glyphs laid out, kerned and rasterised the way draw_text does.
//
// stb_truetype does no bounds checking, so the harness proves the check's claim: the font's bytes
// lie between guard pages, 8 GiB of inaccessible address space on either side (stb adds 32-bit
// offsets from the file to the font's start), with the bytes before the font in its first page
// poisoned for ASan and the font ending on a page boundary. Any read stb makes outside the font is
// a fault. stb's implementation is glint's own compilation of Debian's header (image/stb_guard.h),
// instrumented like the rest of glint_image: in the fuzz build ASan and UBSan check it too. An
// assertion stb fails throws StbAssertion: Font refuses the font (InputError) or the glyph is left
// blank with a warning; an StbAssertion that escapes anywhere else is a finding.
//
// Work per input: at most 64 pairs of glyphs and a line of text, each glyph bounded by the check
// (truetype_check.h: extent, points, depth).
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "fuzz.h"
#include "image/font.h"
#include "io/input_error.h"

#if defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GLINT_FUZZ_ASAN 1
#endif
#endif
#if defined(__SANITIZE_ADDRESS__)
#define GLINT_FUZZ_ASAN 1
#endif
#ifdef GLINT_FUZZ_ASAN
#include <sanitizer/asan_interface.h>
#endif

namespace glint::fuzz {

namespace {

// Address space reserved once, PROT_NONE but for the pages holding the current input.
class GuardedBytes {
 public:
  GuardedBytes() : page_(static_cast<std::size_t>(::sysconf(_SC_PAGESIZE))) {
    room_ = (kMaxFontBytes + page_ - 1) / page_ * page_;
    void* p = ::mmap(nullptr, 2 * kGuard + room_, PROT_NONE,
                     MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) fail("font: cannot reserve the guard pages");
    end_ = static_cast<unsigned char*>(p) + kGuard + room_;  // followed by kGuard of guard
  }
  GuardedBytes(const GuardedBytes&) = delete;
  GuardedBytes& operator=(const GuardedBytes&) = delete;

  // The input copied so that its last byte is the last before the guard.
  const unsigned char* place(const std::uint8_t* data, std::size_t size) {
    used_ = (size + page_ - 1) / page_ * page_;
    unsigned char* first = end_ - used_;
    if (used_ > 0 && ::mprotect(first, used_, PROT_READ | PROT_WRITE) != 0) fail("font: mprotect");
    unsigned char* start = end_ - size;
    if (size > 0) std::memcpy(start, data, size);
#ifdef GLINT_FUZZ_ASAN
    ASAN_POISON_MEMORY_REGION(first, static_cast<std::size_t>(start - first));
#endif
    if (used_ > 0 && ::mprotect(first, used_, PROT_READ) != 0) fail("font: mprotect");
    return start;
  }

  void clear() {
    if (used_ == 0) return;
    unsigned char* first = end_ - used_;
#ifdef GLINT_FUZZ_ASAN
    ASAN_UNPOISON_MEMORY_REGION(first, used_);
#endif
    ::madvise(first, used_, MADV_DONTNEED);
    ::mprotect(first, used_, PROT_NONE);
    used_ = 0;
  }

 private:
  static constexpr std::size_t kGuard = std::size_t{8} << 30;
  std::size_t page_, room_ = 0, used_ = 0;
  unsigned char* end_ = nullptr;
};

// Every printable ASCII character, what glint's labels use beyond it, and bytes drawn as '?'.
std::string sample_text() {
  std::string s;
  for (char c = 0x20; c < 0x7f; ++c) s += c;
  return s + "\xc2\xb1\xc3\x97\xe2\x80\xa6\xe2\x88\x92\xc2\xb5\xc2\xb0\xc3\xa9\x01\xff";
}

void draw(const Font& font) {
  // One image for every input: building a 1280 x 640 image took most of an execution under the
  // fuzzer's coverage instrumentation. What earlier inputs drew does not matter to what is checked.
  static Image8 image(1280, 640);  // the text at 14 pixels is about 900 wide
  const std::string text = sample_text();
  const int drawn = draw_text(image, font, 2, 2, text, {255, 255, 255}, 14);
  if (drawn != text_width(font, text, 14)) fail("font: draw_text's width differs from text_width");
  text_width(font, text, 12);  // the tick labels' height: layout only, the glyphs are the same
  // Glyphs the cmap may not reach (components, unmapped glyphs), each after another so that
  // kerning is looked up too; at the middle, where any glyph the check accepts is (partly) seen.
  const int n = std::min(font.glyph_count(), 64);
  for (int g = 0; g < n; ++g) {
    draw_glyphs(image, font, 640, 313, {(g * 7 + 1) % font.glyph_count(), g}, {200, 100, 50}, 14);
  }
}

}  // namespace

int font(const std::uint8_t* data, std::size_t size) {
  if (size > kMaxFontBytes) return 0;  // read_font refuses it before reading
  static GuardedBytes guarded;
  const unsigned char* bytes = guarded.place(data, size);
  try {
    const Font f(bytes, size, "fuzz.ttf", "GLINT_FONT");
    draw(f);
  } catch (const InputError&) {
    // refused as glint refuses it (exit 2)
  } catch (const std::exception& e) {
    fail(std::string("font: ") + e.what());
  }
  guarded.clear();
  return 0;
}

}  // namespace glint::fuzz

GLINT_FUZZ_TARGET(font)
