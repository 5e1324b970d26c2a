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

void BlockParser::parse_piece(Piece& piece, std::uint64_t first_line) const {
  piece.rows.clear();
  piece.error.reset();
  piece.lines = parse_lines(piece.begin, piece.end, first_line, piece.rows, piece.error);
}

std::uint64_t BlockParser::parse_lines(const char* begin, const char* end, std::uint64_t first_line,
                                       std::vector<VectorRow>& out,
                                       std::unique_ptr<InputError>& error) const {
  RowParser parser = rows_;
  std::uint64_t line = first_line;
  try {
    for (const char* p = begin; p < end; ++line) {
      const char* const nl = static_cast<const char*>(std::memchr(p, '\n', end - p));
      std::size_t len = static_cast<std::size_t>(nl - p);
      if (len != 0 && p[len - 1] == '\r') --len;
      // LineReader's rule for every line, and its message.
      if (len > kVectorMaxLineBytes)
        throw InputError(parser.file(), line, "line", line_too_long_text());
      VectorRow row;
      if (parser.parse(std::string_view(p, len), line, row)) {
        row.line = line;
        out.push_back(row);
      }
      p = nl + 1;
    }
  } catch (const InputError& e) {
    error = std::make_unique<InputError>(e);
  }
  return line - first_line;  // with an error, the lines before it
}

std::uint64_t BlockParser::parse(const char* begin, const char* end, std::uint64_t first_line,
                                 std::vector<VectorRow>& out, std::unique_ptr<InputError>& error) {
  // On one thread, the lines go straight into `out`, numbered as they are parsed.
  if (pool_.threads() == 1) return parse_lines(begin, end, first_line, out, error);
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
  // Each piece numbered from 0 as it is parsed, which counts its lines; its rows are renumbered
  // as they are copied out. A pass counting every piece's lines first, so that each could be
  // parsed with its own numbers, took a fifth of the parsing's time (5 % of `glint eval`'s).
  pool_.run(count, [&](std::size_t k) { parse_piece(pieces_[k], 0); });
  std::size_t failed = count;  // the first piece with a malformed line
  for (std::size_t k = 0; k < count && failed == count; ++k)
    if (pieces_[k].error) failed = k;
  if (failed < count) {
    // Rare: every line counted, and the failing piece parsed again with its own numbers, for the
    // error's line.
    for (std::size_t k = failed; k < count; ++k)
      pieces_[k].lines =
          static_cast<std::uint64_t>(std::count(pieces_[k].begin, pieces_[k].end, '\n'));
  }
  std::vector<std::uint64_t> first(count);
  std::uint64_t lines = 0;
  for (std::size_t k = 0; k < count; ++k) {
    first[k] = first_line + lines;
    lines += pieces_[k].lines;
  }
  const std::size_t kept = std::min(count, failed + 1);
  pool_.run(kept, [&](std::size_t k) {
    if (k == failed) {
      parse_piece(pieces_[k], first[k]);  // numbered from its first line this time
    } else {
      for (VectorRow& row : pieces_[k].rows) row.line += first[k];
    }
  });
  for (std::size_t k = 0; k < kept; ++k) {
    Piece& piece = pieces_[k];
    out.insert(out.end(), piece.rows.begin(), piece.rows.end());
    if (piece.error) error = std::move(piece.error);
  }
  return lines;
}

}  // namespace glint
