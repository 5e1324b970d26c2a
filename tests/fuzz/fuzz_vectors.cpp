// Vector files (io/vectors.h, traces/README.md): the header and every row through VectorReader.
// Whatever the reader accepts, validate() accepts, and VectorWriter writes back into a file the
// reader reads to the same header and rows (bit-identical t: shortest round-trip form). The
// block parser (next_block, what glint eval reads through) gives the same rows, line numbers and
// error message as reading a line at a time.
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "fuzz.h"
#include "io/input_error.h"
#include "io/vectors.h"

namespace glint::fuzz {

namespace {

bool same_rows(const VectorRow& a, const VectorRow& b) {
  // Bits, not ==: -0 and 0 are distinct inputs to the units' front end.
  return std::memcmp(&a.t, &b.t, sizeof a.t) == 0 && a.material == b.material &&
         a.light == b.light && a.x == b.x && a.y == b.y;
}

bool same_headers(const VectorHeader& a, const VectorHeader& b) {
  return a.version == b.version && a.eps == b.eps && a.lights == b.lights &&
         a.light_intensity == b.light_intensity && a.materials == b.materials &&
         a.has_light == b.has_light && a.has_xy == b.has_xy;
}

// The rows next_block() gives, and the message of the error that ended them ("" if none).
std::string read_blocks(const std::string& text, std::vector<VectorRow>& rows) {
  std::istringstream in(text);
  try {
    VectorReader reader(in, "fuzz.vec");
    std::vector<VectorRow> block;
    while (reader.next_block(block, 1)) rows.insert(rows.end(), block.begin(), block.end());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

int vectors(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::istringstream in(text);
  VectorHeader header;
  std::vector<VectorRow> rows;
  std::string error;
  try {
    VectorReader reader(in, "fuzz.vec");
    header = reader.header();
    VectorRow row;
    while (reader.next(row)) rows.push_back(row);
    if (reader.rows_read() != rows.size()) fail("rows_read() disagrees with the rows read");
  } catch (const InputError& e) {
    error = e.what();  // refused with file, line and field: exit 2
  }
  std::vector<VectorRow> block_rows;
  if (read_blocks(text, block_rows) != error)
    fail("the block parser's error differs from next()'s");
  if (block_rows.size() != rows.size()) fail("the block parser's row count differs from next()'s");
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (!same_rows(rows[i], block_rows[i]) || rows[i].line != block_rows[i].line)
      fail("the block parser's rows differ from next()'s");
  if (!error.empty()) return 0;
  try {
    validate(header);
  } catch (const std::invalid_argument& e) {
    fail(std::string("the reader accepted a header validate() refuses: ") + e.what());
  }
  std::ostringstream out;
  try {
    VectorWriter writer(out, header);
    for (const VectorRow& r : rows) writer.write(r);
    writer.commit();
  } catch (const std::exception& e) {
    fail(std::string("the writer refused what the reader accepted: ") + e.what());
  }
  std::istringstream back(out.str());
  try {
    VectorReader again(back, "round-trip.vec");
    if (!same_headers(header, again.header())) fail("header changed in a write/read round trip");
    VectorRow row;
    std::size_t i = 0;
    while (again.next(row)) {
      if (i >= rows.size() || !same_rows(rows[i], row))
        fail("row changed in a write/read round trip");
      ++i;
    }
    if (i != rows.size()) fail("rows lost in a write/read round trip");
  } catch (const InputError& e) {
    fail(std::string("the reader refused what the writer wrote: ") + e.what());
  }
  return 0;
}

}  // namespace glint::fuzz

GLINT_FUZZ_TARGET(vectors)
