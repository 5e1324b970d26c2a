#include "io/vector_blocks.h"

#include <algorithm>
#include <cstring>

#include "io/vector_rules.h"

namespace glint {
namespace {

// Bytes per piece below which another thread costs more than it brings.
constexpr std::size_t kMinPieceBytes = 1 << 16;

}  // namespace

BlockParser::BlockParser(const RowParser& rows, int threads)
    : rows_(rows), pool_(std::max(1, threads)) {}

void BlockParser::parse_piece(Piece& piece, std::uint64_t line) const {
  RowParser parser = rows_;
  piece.rows.clear();
  piece.error.reset();
  try {
    for (const char* p = piece.begin; p < piece.end; ++line) {
      const char* const nl = static_cast<const char*>(std::memchr(p, '\n', piece.end - p));
      std::size_t len = static_cast<std::size_t>(nl - p);
      if (len != 0 && p[len - 1] == '\r') --len;
      // LineReader's rule for every line, and its message.
      if (len > kVectorMaxLineBytes)
        throw InputError(parser.file(), line, "line", line_too_long_text());
      VectorRow row;
      if (parser.parse(std::string_view(p, len), line, row)) {
        row.line = line;
        piece.rows.push_back(row);
      }
      p = nl + 1;
    }
  } catch (const InputError& e) {
    piece.error = std::make_unique<InputError>(e);
  }
}

std::uint64_t BlockParser::parse(const char* begin, const char* end, std::uint64_t first_line,
                                 std::vector<VectorRow>& out, std::unique_ptr<InputError>& error) {
  const auto bytes = static_cast<std::size_t>(end - begin);
  const std::size_t count = std::max<std::size_t>(
      1,
      std::min<std::size_t>(4 * static_cast<std::size_t>(pool_.threads()), bytes / kMinPieceBytes));
  pieces_.resize(count);
  // Cut at line ends near equal shares.
  const char* at = begin;
  for (std::size_t k = 0; k < count; ++k) {
    Piece& piece = pieces_[k];
    piece.begin = at;
    const char* cut = k + 1 == count ? end : std::max(at, begin + bytes * (k + 1) / count);
    if (cut != end) {
      const char* nl = static_cast<const char*>(std::memchr(cut, '\n', end - cut));
      cut = nl + 1;  // the block ends with "\n": there is one
    }
    piece.end = at = cut;
  }
  pool_.run(count, [&](std::size_t k) {
    Piece& piece = pieces_[k];
    piece.lines = static_cast<std::uint64_t>(std::count(piece.begin, piece.end, '\n'));
  });
  std::vector<std::uint64_t> first(count);
  std::uint64_t lines = 0;
  for (std::size_t k = 0; k < count; ++k) {
    first[k] = first_line + lines;
    lines += pieces_[k].lines;
  }
  pool_.run(count, [&](std::size_t k) { parse_piece(pieces_[k], first[k]); });
  for (Piece& piece : pieces_) {
    out.insert(out.end(), piece.rows.begin(), piece.rows.end());
    if (piece.error) {
      error = std::move(piece.error);
      break;
    }
  }
  return lines;
}

}  // namespace glint
