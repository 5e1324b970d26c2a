// Where a lane's requests come from: a tiny pull interface, with adapters over a vector file
// (VectorReader, constant memory) and over rows held in memory (tests, generated streams). Each
// lane gets its own stream, so lanes never wait for each other.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "io/vectors.h"

namespace glint {

class RowStream {
 public:
  virtual ~RowStream() = default;
  // The next row, or false at the end. May throw (e.g. InputError from a malformed vector file).
  virtual bool next(VectorRow& row) = 0;
};

// Reads rows from a VectorReader it owns (opened on a path) or borrows.
class VectorReaderStream final : public RowStream {
 public:
  explicit VectorReaderStream(const std::string& path)
      : owned_(std::make_unique<VectorReader>(path)), reader_(owned_.get()) {}
  explicit VectorReaderStream(VectorReader& reader) : reader_(&reader) {}
  explicit VectorReaderStream(std::unique_ptr<VectorReader> reader)
      : owned_(std::move(reader)), reader_(owned_.get()) {}

  bool next(VectorRow& row) override { return reader_->next(row); }
  const VectorHeader& header() const { return reader_->header(); }

 private:
  std::unique_ptr<VectorReader> owned_;
  VectorReader* reader_;
};

// Rows from memory. The vector must outlive the stream.
class MemoryRowStream final : public RowStream {
 public:
  explicit MemoryRowStream(const std::vector<VectorRow>& rows) : rows_(&rows) {}

  bool next(VectorRow& row) override {
    if (index_ >= rows_->size()) return false;
    row = (*rows_)[index_++];
    return true;
  }

 private:
  const std::vector<VectorRow>* rows_;
  std::size_t index_ = 0;
};

}  // namespace glint
