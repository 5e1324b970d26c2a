// GLINT_FONT is an input like any file glint reads: a path from the environment may name a FIFO
// (an open would block), a device (/dev/zero never ends), a 10 GB sparse file or a truncated font,
// so the file is stat'ed before it is opened, opened without blocking, read with a bound, and
// checked before stb_truetype reads it.
#include "image/font.h"

#include <fcntl.h>
#include <stb_truetype.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

#include "image/stb_guard.h"
#include "image/truetype_check.h"
#include "io/input_error.h"

namespace glint {

namespace {

std::string file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a file";
}

// Refuses what is not a regular file of 1..kMaxFontBytes bytes.
void check_stat(const struct stat& st, const std::string& path, const std::string& field) {
  if (!S_ISREG(st.st_mode))
    throw InputError(path, 0, field, "not a regular file (" + file_kind(st.st_mode) + ")");
  if (st.st_size == 0) throw InputError(path, 0, field, "empty");
  if (static_cast<std::uintmax_t>(st.st_size) > kMaxFontBytes)
    throw InputError(path, 0, field,
                     std::to_string(st.st_size) + " bytes, more than a font may have (" +
                         std::to_string(kMaxFontBytes >> 20) + " MiB)");
}

class Fd {
 public:
  explicit Fd(int fd) : fd_(fd) {}
  ~Fd() {
    if (fd_ >= 0) ::close(fd_);
  }
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  int get() const { return fd_; }

 private:
  int fd_;
};

}  // namespace

Font::Font(const unsigned char* data, std::size_t size, const std::string& file,
           const std::string& field) {
  init(data, size, file, field);
}

Font::Font(std::vector<unsigned char> bytes, const std::string& file, const std::string& field)
    : bytes_(std::move(bytes)) {
  init(bytes_.data(), bytes_.size(), file, field);
}

Font::~Font() = default;

void Font::init(const unsigned char* data, std::size_t size, const std::string& file,
                const std::string& field) {
  TrueTypeFacts facts;
  try {
    facts = check_truetype(data, size);
  } catch (const FontError& e) {
    throw InputError(file, 0, field, e.what());
  }
  file_ = file;
  info_ = std::make_unique<stbtt_fontinfo>();
  int g = -1;  // the glyph being measured, for the message
  try {
    StbScope scope;
    if (!stbtt_InitFont(info_.get(), data, facts.offset))
      throw InputError(file, 0, field, "not a TrueType font stb_truetype can read");
    glyphs_ = facts.glyph_count;
    // stb sizes a glyph's bitmap by the box in its header, and its rasteriser asserts (Debian's
    // libstb keeps assertions) when the outline leaves that box: real fonts have such glyphs (stb
    // scales transformed components twice; DejaVu Sans Condensed, Mono Bold). Each outline, as stb
    // builds it, is measured once here (check_truetype made the calls safe and bounded).
    for (g = 0; g < glyphs_; ++g) {
      stbtt_vertex* v = nullptr;
      const int n = stbtt_GetGlyphShape(info_.get(), g, &v);
      Box box;
      stbtt_GetGlyphBox(info_.get(), g, &box.x0, &box.y0, &box.x1, &box.y1);
      const Box header = box;
      const auto grow = [&box](int x, int y) {
        box = {std::min(box.x0, x), std::min(box.y0, y), std::max(box.x1, x), std::max(box.y1, y)};
      };
      for (int i = 0; i < n; ++i) {
        grow(v[i].x, v[i].y);
        if (v[i].type == STBTT_vcurve || v[i].type == STBTT_vcubic) grow(v[i].cx, v[i].cy);
      }
      stbtt_FreeShape(info_.get(), v);
      if (box.x0 != header.x0 || box.y0 != header.y0 || box.x1 != header.x1 || box.y1 != header.y1)
        grown_.emplace(g, box);
    }
    g = -1;
    int descent = 0, line_gap = 0;
    stbtt_GetFontVMetrics(info_.get(), &ascent_, &descent, &line_gap);
    question_ = lookup('?');
  } catch (const StbAssertion& e) {
    throw InputError(file, 0, field,
                     (g >= 0 ? "glyph " + std::to_string(g) + ": " : std::string()) + e.what());
  }
}

void Font::left_blank(int glyph, int height, const char* why) const {
  const std::lock_guard<std::mutex> lock(blank_mutex_);
  if (!blank_.insert(glyph).second) return;
  std::fprintf(stderr,
               "glint: warning: %s: glyph %d cannot be drawn at %d pixels (%s): left blank\n",
               file_.c_str(), glyph, height, why);
}

int Font::lookup(char32_t cp) const {
  // The cmap may name any glyph id; only those check_truetype checked go to stb.
  const int g = stbtt_FindGlyphIndex(info_.get(), static_cast<int>(cp));
  return g > 0 && g < glyphs_ ? g : 0;
}

int Font::glyph(char32_t cp) const {
  if (cp < 0x20 || (cp >= 0x7f && cp < 0xa0)) return question_;
  const int g = lookup(cp);
  return g != 0 ? g : question_;
}

const Font::Box* Font::grown_box(int glyph) const {
  const auto it = grown_.find(glyph);
  return it == grown_.end() ? nullptr : &it->second;
}

bool Font::has(char32_t cp) const {
  return lookup(cp) != 0;
}

std::unique_ptr<Font> read_font(const std::string& path, const std::string& field) {
  const auto os_error = [&](const std::string& what) {
    const int err = errno;
    return InputError(path, 0, field, what + ": " + std::strerror(err));
  };
  // stat first: a FIFO or a device is refused without being opened.
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) throw os_error("cannot open");
  check_stat(st, path, field);
  // O_NONBLOCK: should the path have become a FIFO since, the open does not wait for a writer.
  const Fd fd(::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY));
  if (fd.get() < 0) throw os_error("cannot open");
  if (::fstat(fd.get(), &st) != 0) throw os_error("cannot read");
  check_stat(st, path, field);
  // One byte more than the size, to see a file that grew; never more than the cap.
  std::vector<unsigned char> bytes(static_cast<std::size_t>(st.st_size) + 1);
  std::size_t got = 0;
  while (got < bytes.size()) {
    const ssize_t n = ::read(fd.get(), bytes.data() + got, bytes.size() - got);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw os_error("read error");
    if (n == 0) break;
    got += static_cast<std::size_t>(n);
  }
  if (got != static_cast<std::size_t>(st.st_size))
    throw InputError(path, 0, field, "changed while it was read");
  bytes.resize(got);
  return std::make_unique<Font>(std::move(bytes), path, field);
}

const Font& text_font() {
  // A static local is initialised once even with threads; a throw leaves it for the next call.
  static const std::unique_ptr<Font> font = [] {
    const char* env = std::getenv("GLINT_FONT");
    const bool named = env != nullptr && *env != '\0';
    try {
      return read_font(named ? env : kDefaultFont, named ? "GLINT_FONT" : "font");
    } catch (const InputError& e) {
      throw InputError(e.file(), 0, e.field(),
                       e.message() +
                           " (GLINT_FONT=FILE.ttf names a TrueType font; the default, DejaVu "
                           "Sans, comes with the Debian package fonts-dejavu-core)");
    }
  }();
  return *font;
}

void load_text_font() {
  text_font();
}

}  // namespace glint
