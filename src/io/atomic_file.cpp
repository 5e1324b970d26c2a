#include "io/atomic_file.h"

#include <stdexcept>

namespace glint {

AtomicOutputFile::AtomicOutputFile(std::string path)
    : path_(std::move(path)), set_(std::make_unique<OutputSet>()) {
  file_ = &set_->add("", path_);
  temp_path_ = file_->temp_path();
}

AtomicOutputFile::~AtomicOutputFile() {
  abort();
}

std::ostream& AtomicOutputFile::stream() {
  if (aborted_ || set_->committed())
    throw std::logic_error("AtomicOutputFile '" + path_ + "': already closed");
  return file_->stream();
}

void AtomicOutputFile::abort() noexcept {
  if (set_->committed()) return;
  set_->abort();
  aborted_ = true;
}

void AtomicOutputFile::commit(bool durable) {
  if (set_->committed())
    throw std::logic_error("AtomicOutputFile '" + path_ + "': committed twice");
  if (aborted_) throw std::logic_error("AtomicOutputFile '" + path_ + "': already aborted");
  try {
    set_->commit(durable);
  } catch (const OutputError&) {
    aborted_ = true;
    throw;
  }
}

}  // namespace glint
