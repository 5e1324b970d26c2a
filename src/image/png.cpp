// PNG through libspng (libspng-dev, zlib's deflate), chosen by measurement over stb_image_write,
// glint's encoder before, and libpng (tests/bench/png_speed.cpp, tests/bench/RESULTS.md "PNG
// encoders"): on a 1080p render's 20 images, stb at level 8 took 2.66 CPU-s for 3.02 MB, libspng
// with the Up filter at level 2 0.37 CPU-s for 2.51 MB; libpng the same way 0.28 CPU-s, but its
// errors are longjmps, which must not cross the C++ frames of our sinks. Each encoder is a context
// of its own, with no process-wide knobs, so images are encoded at once on any threads; rows can
// be fed as they are made (PngRowWriter), so a render never holds a whole image just to write it.
// The encoder writes IHDR, IDAT and IEND only (no time, text or gamma chunks), and neither the
// filter nor zlib's deflate has randomness: equal pixels give equal bytes.
#include <spng.h>

#include <climits>
#include <exception>
#include <stdexcept>
#include <string>

#include "image/image.h"
#include "io/atomic_file.h"

namespace glint {

namespace {

// One filter for every row, Up (each byte minus the one above): libspng's adaptive choice tries
// all five per row, which took 4x the CPU for 6 % smaller files. zlib's level 2 of 0-9: level 1
// costs the same for 3 % larger files, 6 and up several times more.
constexpr int kCompressionLevel = 2;
constexpr int kFilterChoice = SPNG_FILTER_CHOICE_UP;

void check_size(int width, int height) {
  if (width <= 0 || height <= 0) {
    throw std::invalid_argument("encode_png: a PNG needs at least one pixel, the image is " +
                                std::to_string(width) + "x" + std::to_string(height));
  }
}

}  // namespace

struct PngRowWriter::State {
  spng_ctx* ctx = nullptr;
  Sink sink;
  int width = 0, height = 0, rows = 0;
  std::exception_ptr error;  // thrown by the sink inside libspng's C frames, rethrown after

  ~State() { spng_ctx_free(ctx); }

  static int write(spng_ctx*, void* user, void* data, std::size_t size) {
    auto* s = static_cast<State*>(user);
    try {
      s->sink(static_cast<const std::uint8_t*>(data), size);
    } catch (...) {
      s->error = std::current_exception();
      return SPNG_IO_ERROR;
    }
    return 0;
  }

  void check(int code, const char* what) {
    if (error) std::rethrow_exception(error);
    if (code != 0 && code != SPNG_EOI)
      throw std::runtime_error(std::string("encode_png: ") + what + ": " + spng_strerror(code));
  }
};

PngRowWriter::PngRowWriter(int width, int height, Sink sink) : state_(std::make_unique<State>()) {
  check_size(width, height);
  State& s = *state_;
  s.sink = std::move(sink);
  s.width = width;
  s.height = height;
  s.ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  if (!s.ctx) throw std::runtime_error("encode_png: out of memory");
  spng_ihdr ihdr{};
  ihdr.width = static_cast<std::uint32_t>(width);
  ihdr.height = static_cast<std::uint32_t>(height);
  ihdr.bit_depth = 8;
  ihdr.color_type = SPNG_COLOR_TYPE_TRUECOLOR;
  s.check(spng_set_png_stream(s.ctx, &State::write, &s), "stream");
  s.check(spng_set_option(s.ctx, SPNG_IMG_COMPRESSION_LEVEL, kCompressionLevel), "level");
  s.check(spng_set_option(s.ctx, SPNG_FILTER_CHOICE, kFilterChoice), "filter");
  s.check(spng_set_ihdr(s.ctx, &ihdr), "header");
  s.check(spng_encode_image(s.ctx, nullptr, 0, SPNG_FMT_PNG,
                            SPNG_ENCODE_PROGRESSIVE | SPNG_ENCODE_FINALIZE),
          "start");
}

PngRowWriter::~PngRowWriter() = default;
PngRowWriter::PngRowWriter(PngRowWriter&&) noexcept = default;
PngRowWriter& PngRowWriter::operator=(PngRowWriter&&) noexcept = default;

void PngRowWriter::add_rows(const std::uint8_t* rgb, int rows) {
  State& s = *state_;
  if (rows < 0 || rows > s.height - s.rows)
    throw std::logic_error("PngRowWriter: more rows than the image has");
  const std::size_t row_bytes = 3 * static_cast<std::size_t>(s.width);
  for (int r = 0; r < rows; ++r, ++s.rows)
    s.check(spng_encode_row(s.ctx, rgb + static_cast<std::size_t>(r) * row_bytes, row_bytes),
            "row");
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
