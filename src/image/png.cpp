// PNG through libpng (libpng-dev, zlib's deflate), chosen by measurement over stb_image_write,
// glint's encoder before, and libspng (tests/bench/png_speed.cpp, tests/bench/RESULTS.md "PNG
// encoders"): on a 1080p render's 20 images, stb at level 8 took 2.61 CPU-s for 3.02 MB, libspng
// with the Up filter at level 2 0.36 CPU-s, libpng the same way 0.28 CPU-s for 2.51 MB. Each
// encoder is a png_struct of its own, with no process-wide knobs, so images are encoded at once on
// any threads; rows are fed as they are made (PngRowWriter), so a render never holds a whole image
// just to write it. It writes IHDR, IDAT and IEND only (no time, text or gamma chunks), and
// neither the filter nor zlib's deflate has randomness: equal pixels give equal bytes.
//
// libpng reports errors by longjmp. The jumps land in the small functions below that call it
// (guarded), whose frames hold no C++ object, and the sink's exceptions never cross libpng's C
// frames: the write callback catches them, and raises a libpng error once out of its catch block.
#include <png.h>

#include <climits>
#include <csetjmp>
#include <cstdio>
#include <exception>
#include <stdexcept>
#include <string>

#include "image/image.h"
#include "io/atomic_file.h"

namespace glint {

namespace {

// One filter for every row, Up (each byte minus the one above): the adaptive choice tries all five
// per row, which took 3x the CPU for 6 % smaller files. zlib's level 2 of 0-9: level 1 costs the
// same for 3 % larger files, 6 and up several times more.
constexpr int kCompressionLevel = 2;
constexpr int kFilters = PNG_FILTER_UP;

void check_size(int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("encode_png: a PNG needs at least one pixel, the image is " +
                                std::to_string(width) + "x" + std::to_string(height));
  }
}

}  // namespace

struct PngRowWriter::State {
  png_structp png = nullptr;
  png_infop info = nullptr;
  Sink sink;
  int width = 0, height = 0, rows = 0;
  std::exception_ptr error;  // the sink's, rethrown once out of libpng
  char message[200] = {};    // libpng's own error

  ~State() { png_destroy_write_struct(&png, &info); }

  static void write(png_structp png, png_bytep data, png_size_t size) {
    auto* s = static_cast<State*>(png_get_io_ptr(png));
    bool failed = false;
    try {
      s->sink(data, size);
    } catch (...) {
      s->error = std::current_exception();
      failed = true;
    }
    if (failed) png_error(png, "sink");  // longjmps: nothing of this frame is live
  }
  static void flush(png_structp) {}
  static void on_error(png_structp png, png_const_charp text) {
    auto* s = static_cast<State*>(png_get_error_ptr(png));
    std::snprintf(s->message, sizeof s->message, "%s", text);
    std::longjmp(png_jmpbuf(png), 1);
  }
  static void on_warning(png_structp, png_const_charp) {}

  // Runs libpng's calls under its jump buffer; false if one failed. No C++ object lives here.
  bool start() {
    if (setjmp(png_jmpbuf(png))) return false;
    png_set_write_fn(png, this, &State::write, &State::flush);
    png_set_compression_level(png, kCompressionLevel);
    png_set_filter(png, PNG_FILTER_TYPE_BASE, kFilters);
    png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8,
                 PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_BASE,
                 PNG_FILTER_TYPE_BASE);
    png_write_info(png, info);
    return true;
  }
  bool write_rows(const std::uint8_t* rgb, int count) {
    if (setjmp(png_jmpbuf(png))) return false;
    const std::size_t row_bytes = 3 * static_cast<std::size_t>(width);
    for (int r = 0; r < count; ++r, ++rows)
      png_write_row(png, rgb + static_cast<std::size_t>(r) * row_bytes);
    if (rows == height) png_write_end(png, nullptr);
    return true;
  }

  [[noreturn]] void fail() {
    if (error) std::rethrow_exception(error);
    throw std::runtime_error(std::string("encode_png: ") + message);
  }
};

PngRowWriter::PngRowWriter(int width, int height, Sink sink) : state_(std::make_unique<State>()) {
  check_size(width, height);
  State& s = *state_;
  s.sink = std::move(sink);
  s.width = width;
  s.height = height;
  s.png = png_create_write_struct(PNG_LIBPNG_VER_STRING, &s, &State::on_error, &State::on_warning);
  if (s.png) s.info = png_create_info_struct(s.png);
  if (!s.png || !s.info) throw std::runtime_error("encode_png: out of memory");
  if (!s.start()) s.fail();
}

PngRowWriter::~PngRowWriter() = default;
PngRowWriter::PngRowWriter(PngRowWriter&&) noexcept = default;
PngRowWriter& PngRowWriter::operator=(PngRowWriter&&) noexcept = default;

void PngRowWriter::add_rows(const std::uint8_t* rgb, int rows) {
  State& s = *state_;
  if (rows < 0 || rows > s.height - s.rows)
    throw std::logic_error("PngRowWriter: more rows than the image has");
  if (!s.write_rows(rgb, rows)) s.fail();
}

bool PngRowWriter::done() const {
  return state_->rows == state_->height;
}

std::vector<std::uint8_t> encode_png(const Image8& image) {
  check_size(image.width, image.height);
  if (image.pixels.size() !=
      3 * static_cast<std::size_t>(image.width) * static_cast<std::size_t>(image.height)) {
    throw std::invalid_argument("encode_png: pixel buffer does not match " +
                                std::to_string(image.width) + "x" + std::to_string(image.height));
  }
  std::vector<std::uint8_t> out;
  PngRowWriter writer(image.width, image.height, [&](const std::uint8_t* data, std::size_t n) {
    out.insert(out.end(), data, data + n);
  });
  writer.add_rows(image.pixels.data(), image.height);
  return out;
}

void write_png(const std::string& path, const Image8& image) {
  // Encode first: a failure here leaves no temporary file behind either.
  const std::vector<std::uint8_t> bytes = encode_png(image);
  AtomicOutputFile file(path);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

}  // namespace glint
