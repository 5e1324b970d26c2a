// A vector file's rows, for the tests that link the io layer (test_support.h needs no glint
// library).
#pragma once

#include <string>
#include <vector>

#include "io/vectors.h"

namespace glint::test {

// Every row of a vector file, and its header.
inline std::vector<VectorRow> read_rows(const std::string& path, VectorHeader& header) {
  VectorReader reader(path);
  header = reader.header();
  std::vector<VectorRow> rows;
  VectorRow row;
  while (reader.next(row)) rows.push_back(row);
  return rows;
}

}  // namespace glint::test
