// Vector files from standard input or a pipe, and one input read several times.
#pragma once

#include <sys/types.h>

#include <istream>
#include <memory>
#include <streambuf>
#include <string>
#include <vector>

#include "io/vectors.h"

namespace glint {

// The name standard input ("-" on the command line) has in messages.
inline constexpr const char* kStdinName = "<stdin>";

// An input stream over a file descriptor it does not own. `positional`: reads with pread from
// `offset`, so several streams share one descriptor with a position each; otherwise read() at the
// descriptor's own position (a pipe). A read error sets badbit with errno kept for the reader's
// message.
class FdInputStream : public std::istream {
 public:
  FdInputStream(int fd, bool positional, off_t offset = 0);
  ~FdInputStream() override;

 private:
  class Buf;
  std::unique_ptr<Buf> buf_;
};

// A vector file that several readers go through independently (the clocked model reads the stream
// once per lane). A regular file is opened again by path for each reader. Anything else, standard
// input ("-") or a path that names a pipe, a FIFO or a terminal (/dev/stdin of `cat x | glint`), is
// read once into an anonymous temporary file in $TMPDIR (else /tmp), which has no name from the
// start (O_TMPFILE; or a fresh name unlinked at once), so nothing can be left behind; the readers
// share it. Standard input redirected from a regular file is read in place. Costs disk space equal
// to the input; OutputError when the copy cannot be made (naming the folder and the error).
class RereadableInput {
 public:
  explicit RereadableInput(std::string path);
  ~RereadableInput();
  RereadableInput(const RereadableInput&) = delete;
  RereadableInput& operator=(const RereadableInput&) = delete;

  // A new reader at the start of the input (reads the header; throws InputError as VectorReader).
  std::unique_ptr<VectorReader> open() const;
  // The input was copied (standard input or a pipe).
  bool copied() const { return owned_; }

 private:
  std::string path_, name_;
  int fd_ = -1;  // shared descriptor: the copy, or standard input in place; -1: open by path
  bool owned_ = false;
  off_t base_ = 0;
};

}  // namespace glint
