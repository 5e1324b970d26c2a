#include "image/float_image.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "io/output_set.h"

namespace glint {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "PFM rows are written as the host's floats, declared little-endian");

std::string to_string(FloatFormat f) {
  return f == FloatFormat::kExr ? "exr" : "pfm";
}

FloatFormat parse_float_format(const std::string& text) {
  if (text == "exr") return FloatFormat::kExr;
  if (text == "pfm") return FloatFormat::kPfm;
  throw std::invalid_argument("'" + text + "': not a float format (exr or pfm)");
}

namespace {

// Writes `size` bytes at `offset` (pwrite: PFM places rows bottom first), or throws.
void write_at(int fd, const char* data, std::size_t size, off_t offset, const std::string& what) {
  while (size > 0) {
    const ssize_t n = ::pwrite(fd, data, size, offset);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) throw OutputError(what + ": " + std::strerror(n < 0 ? errno : ENOSPC));
    data += n;
    size -= static_cast<std::size_t>(n);
    offset += n;
  }
}

// OpenEXR's output stream on a descriptor. OpenEXR swallows exceptions while it completes a file
// in its destructor, so the first error is also kept for finish() to throw.
class FdStream : public Imf::OStream {
 public:
  FdStream(int fd, const std::string& what) : Imf::OStream(what.c_str()), fd_(fd), what_(what) {}
  void write(const char c[], int n) override {
    try {
      write_at(fd_, c, static_cast<std::size_t>(n), static_cast<off_t>(pos_), what_);
    } catch (const OutputError& e) {
      if (error_.empty()) error_ = e.what();
      throw;
    }
    pos_ += static_cast<std::uint64_t>(n);
  }
  std::uint64_t tellp() override { return pos_; }
  void seekp(std::uint64_t pos) override { pos_ = pos; }
  const std::string& error() const { return error_; }

 private:
  int fd_;
  std::string what_, error_;
  std::uint64_t pos_ = 0;
};

// Interleaved RGB floats as OpenEXR's R, G and B channels: row y at base + y * stride.
Imf::FrameBuffer rgb_frame_buffer(char* base, std::size_t stride) {
  Imf::FrameBuffer fb;
  for (int c = 0; c < 3; ++c)
    fb.insert(c == 0   ? "R"
              : c == 1 ? "G"
                       : "B",
              Imf::Slice(Imf::FLOAT, base + c * sizeof(float), 3 * sizeof(float), stride));
  return fb;
}

}  // namespace

struct FloatRowWriter::State {
  FloatFormat format = FloatFormat::kExr;
  int fd = -1, width = 0, height = 0, rows = 0;
  std::string what;
  std::unique_ptr<FdStream> stream;  // EXR
  std::unique_ptr<Imf::OutputFile> exr;
  std::size_t pfm_header = 0;

  ~State() {
    exr.reset();
    if (fd >= 0) ::close(fd);
  }
};

FloatRowWriter::FloatRowWriter(FloatFormat format, int fd, int width, int height, std::string what)
    : state_(std::make_unique<State>()) {
  State& s = *state_;
  s.fd = fd;
  s.format = format;
  s.what = std::move(what);
  if (width <= 0 || height <= 0)
    throw std::invalid_argument(s.what + ": a float image needs at least one pixel");
  s.width = width;
  s.height = height;
  if (format == FloatFormat::kPfm) {
    const std::string header =
        "PF\n" + std::to_string(width) + " " + std::to_string(height) + "\n-1.0\n";
    write_at(fd, header.data(), header.size(), 0, s.what);
    s.pfm_header = header.size();
    return;
  }
  Imf::Header header(width, height);
  header.compression() = Imf::ZIP_COMPRESSION;
  for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
  s.stream = std::make_unique<FdStream>(fd, s.what);
  s.exr = std::make_unique<Imf::OutputFile>(*s.stream, header, 0);  // 0: no threads of its own
}

FloatRowWriter::~FloatRowWriter() = default;

void FloatRowWriter::add_rows(const float* rgb, int rows) {
  State& s = *state_;
  if (rows < 0 || rows > s.height - s.rows)
    throw std::logic_error("FloatRowWriter: more rows than the image has");
  const std::size_t row_floats = 3 * static_cast<std::size_t>(s.width);
  if (s.format == FloatFormat::kPfm) {
    for (int r = 0; r < rows; ++r) {
      const std::size_t from_bottom = static_cast<std::size_t>(s.height - 1 - (s.rows + r));
      write_at(s.fd, reinterpret_cast<const char*>(rgb + r * row_floats),
               row_floats * sizeof(float),
               static_cast<off_t>(s.pfm_header + from_bottom * row_floats * sizeof(float)), s.what);
    }
    s.rows += rows;
    return;
  }
  // The frame buffer addresses row y at base + y * stride: shifted so that this batch's first
  // row is the file's next one.
  const std::size_t stride = row_floats * sizeof(float);
  char* base = const_cast<char*>(reinterpret_cast<const char*>(rgb)) -
               static_cast<std::ptrdiff_t>(s.rows) * static_cast<std::ptrdiff_t>(stride);
  s.exr->setFrameBuffer(rgb_frame_buffer(base, stride));
  s.exr->writePixels(rows);
  s.rows += rows;
}

void FloatRowWriter::finish() {
  State& s = *state_;
  if (s.rows != s.height) throw std::logic_error("FloatRowWriter: rows missing");
  s.exr.reset();  // writes the table of rows
  if (s.stream && !s.stream->error().empty()) throw OutputError(s.stream->error());
  const int fd = s.fd;
  s.fd = -1;
  if (::close(fd) != 0) throw OutputError(s.what + ": " + std::strerror(errno));
}

namespace {

FloatImage read_pfm(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string magic;
  FloatImage image;
  double scale = 0;
  in >> magic >> image.width >> image.height >> scale;
  in.get();
  if (!in || magic != "PF" || image.width <= 0 || image.height <= 0 || scale >= 0)
    throw std::runtime_error(path + ": not a little-endian RGB PFM");
  const std::size_t row = 3 * static_cast<std::size_t>(image.width);
  image.rgb.resize(row * static_cast<std::size_t>(image.height));
  for (int y = image.height - 1; y >= 0; --y)
    in.read(reinterpret_cast<char*>(image.rgb.data() + static_cast<std::size_t>(y) * row),
            static_cast<std::streamsize>(row * sizeof(float)));
  if (!in) throw std::runtime_error(path + ": PFM cut short");
  return image;
}

FloatImage read_exr(const std::string& path) {
  try {
    Imf::InputFile file(path.c_str());
    const Imath::Box2i window = file.header().dataWindow();
    FloatImage image;
    image.width = window.max.x - window.min.x + 1;
    image.height = window.max.y - window.min.y + 1;
    image.rgb.resize(3 * static_cast<std::size_t>(image.width) * image.height);
    const std::size_t stride = 3 * sizeof(float) * static_cast<std::size_t>(image.width);
    char* base = reinterpret_cast<char*>(image.rgb.data()) -
                 window.min.x * 3 * static_cast<std::ptrdiff_t>(sizeof(float)) -
                 window.min.y * static_cast<std::ptrdiff_t>(stride);
    file.setFrameBuffer(rgb_frame_buffer(base, stride));
    file.readPixels(window.min.y, window.max.y);
    return image;
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

}  // namespace

FloatImage read_float_image(const std::string& path) {
  const auto ends = [&](const char* ext) {
    return path.size() > 4 && path.compare(path.size() - 4, 4, ext) == 0;
  };
  if (ends(".pfm")) return read_pfm(path);
  if (ends(".exr")) return read_exr(path);
  throw std::runtime_error(path + ": not .exr or .pfm");
}

}  // namespace glint
