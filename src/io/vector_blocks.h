// Rows of a vector file parsed a block of whole lines at a time on several threads, with the rows,
// line numbers and errors of parsing them one at a time (VectorReader::next_block).
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "io/input_error.h"
#include "io/thread_pool.h"
#include "io/vector_rows.h"
#include "io/vectors.h"

namespace glint {

class BlockParser {
 public:
  // Copies of `rows` parse the pieces of a block; it must outlive the parser.
  BlockParser(const RowParser& rows, int threads);

  // The whole lines [begin, end) (end just past a "\n"), the first of them line `first_line`:
  // their rows are appended to `out` in order. Returns the number of lines. A malformed line
  // (InputError, as RowParser or LineReader would throw it) ends the rows at the one before it
  // and is kept in `error`.
  std::uint64_t parse(const char* begin, const char* end, std::uint64_t first_line,
                      std::vector<VectorRow>& out, std::unique_ptr<InputError>& error);

 private:
  struct Piece {
    const char* begin = nullptr;
    const char* end = nullptr;
    std::uint64_t lines = 0;
    std::vector<VectorRow> rows;
    std::unique_ptr<InputError> error;
  };
  void parse_piece(Piece& piece, std::uint64_t first_line) const;
  // The rows of the lines [begin, end), the first of them `first_line`, appended to `out`; returns
  // the number of lines before a malformed one (kept in `error`) or of all.
  std::uint64_t parse_lines(const char* begin, const char* end, std::uint64_t first_line,
                            std::vector<VectorRow>& out, std::unique_ptr<InputError>& error) const;

  const RowParser& rows_;
  ThreadPool pool_;
  std::vector<Piece> pieces_;
};

}  // namespace glint
