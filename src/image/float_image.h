// Linear float RGB images, for researchers' own analysis (glint render --float): OpenEXR (Debian
// libopenexr-dev; 32-bit float R, G and B channels, ZIP compression, what image tools open) or
// PFM (Portable Float Map: a text header and raw little-endian floats, bottom row first; no
// library needed to read it). Written as their rows arrive, top row first, so a render never holds
// a whole float image; the same rows give the same bytes.
#pragma once

#include <memory>
#include <string>
#include <vector>

namespace glint {

enum class FloatFormat { kExr, kPfm };

// "exr" or "pfm": the option's value and the files' extension.
std::string to_string(FloatFormat f);
// The inverse; anything else throws std::invalid_argument naming the accepted values.
FloatFormat parse_float_format(const std::string& text);

class FloatRowWriter {
 public:
  // Writes into `fd`, a regular file open for writing (and seeking: EXR writes its table of rows
  // last, PFM places each row), which the writer closes. `what` names the file in errors. A size
  // without pixels throws std::invalid_argument.
  FloatRowWriter(FloatFormat format, int fd, int width, int height, std::string what);
  ~FloatRowWriter();
  FloatRowWriter(const FloatRowWriter&) = delete;
  FloatRowWriter& operator=(const FloatRowWriter&) = delete;

  // `rows` rows of 3 * width floats (linear R, G, B) each; more rows than the image has is a
  // std::logic_error. A failed write throws OutputError naming the file.
  void add_rows(const float* rgb, int rows);
  // After the last row: completes the file and closes it (OutputError if that fails, e.g. a
  // full disk); std::logic_error if rows are missing.
  void finish();

 private:
  struct State;
  std::unique_ptr<State> state_;
};

// A float image read back (tests and tools): 3 * width * height floats, top row first.
struct FloatImage {
  int width = 0, height = 0;
  std::vector<float> rgb;
};
// Reads an EXR (its R, G and B channels) or a PFM written as above, by the file's extension;
// std::runtime_error on anything else or a malformed file.
FloatImage read_float_image(const std::string& path);

}  // namespace glint
