// AtomicOutputFile: write a file so that it either appears complete or not at all.
//
// The data goes to a temporary file beside the target (same directory, so the final rename stays
// on one file system): "<path>.tmp.<unique>", created with O_EXCL and the usual 0666 & ~umask
// permissions. commit() flushes, fsyncs (optional), closes and renames it over <path>, which
// atomically replaces any previous file. Destroying the object without commit() (an exception, an
// early return) removes the temporary, so a half-written output file never appears under <path>.
// Only a crash between creation and commit can leave a "<path>.tmp.*" file behind.
//
// All failures (cannot create, write error such as ENOSPC, rename failure) throw
// std::runtime_error naming the path and the system error. Write errors are remembered by the
// stream buffer and reported by commit(), since std::ostream swallows them into badbit.
#pragma once

#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>

namespace glint {

// An output file that cannot be written: the user's path is wrong (missing directory, not a
// regular file, no permission, disk full), so the CLI reports it as bad input (exit 2).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws OutputError when `path` exists and is not a regular file (a device such as /dev/null, a
// directory, a FIFO): the write-to-temporary-then-rename scheme would replace it.
void check_output_path(const std::string& path);

class AtomicOutputFile {
 public:
  explicit AtomicOutputFile(std::string path);
  ~AtomicOutputFile();  // removes the temporary unless committed; never throws

  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  // The stream to write to (binary: no newline translation). Valid until commit()/abort().
  std::ostream& stream();

  // Flush; fsync the data when `durable`; close; rename over path(). Throws std::runtime_error
  // (and removes the temporary) if any write failed or the rename fails. Calling it twice is an
  // error (std::logic_error).
  void commit(bool durable = true);

  // Discards the output now: closes and removes the temporary. Idempotent.
  void abort() noexcept;

  const std::string& path() const { return path_; }
  const std::string& temp_path() const { return temp_path_; }
  bool committed() const { return committed_; }

 private:
  class FdBuf;
  std::string path_;
  std::string temp_path_;
  std::unique_ptr<FdBuf> buf_;
  std::unique_ptr<std::ostream> stream_;
  bool committed_ = false;
};

}  // namespace glint
