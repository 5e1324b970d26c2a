// AtomicOutputFile: one output file that either appears complete or not at all, the one-file case
// of an OutputSet (output_set.h, which says what is guaranteed): the data goes to an exclusively
// created temporary beside the target ("<path>.tmp.<random>"), and commit() flushes, fsyncs
// (optional), gives it the replaced file's permissions and renames it over <path>. Destroying the
// object without commit() (an exception, an early return) removes the temporary.
//
// Every failure (cannot create, a target that is not a regular file, a write error such as ENOSPC
// or EFBIG, a failed rename) throws OutputError naming the path and the system error; write errors
// are thrown by the stream's write itself.
#pragma once

#include <memory>
#include <ostream>
#include <string>

#include "io/output_set.h"

namespace glint {

class AtomicOutputFile {
 public:
  explicit AtomicOutputFile(std::string path);
  ~AtomicOutputFile();  // removes the temporary unless committed; never throws

  AtomicOutputFile(const AtomicOutputFile&) = delete;
  AtomicOutputFile& operator=(const AtomicOutputFile&) = delete;

  // The stream to write to (binary: no newline translation). Valid until commit()/abort().
  std::ostream& stream();

  // Flush; fsync the data when `durable`; close; rename over path(). Throws OutputError (and
  // removes the temporary) if any write failed or the rename fails. Calling it twice, or after
  // abort(), is an error (std::logic_error).
  void commit(bool durable = true);

  // Discards the output now: closes and removes the temporary. Idempotent.
  void abort() noexcept;

  const std::string& path() const { return path_; }
  const std::string& temp_path() const { return temp_path_; }
  bool committed() const { return set_->committed(); }

 private:
  std::string path_, temp_path_;
  std::unique_ptr<OutputSet> set_;
  OutputFile* file_;
  bool aborted_ = false;
};

}  // namespace glint
