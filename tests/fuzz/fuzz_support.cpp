#include <cstdio>
#include <cstdlib>

#include "fuzz.h"

namespace glint::fuzz {

void fail(const std::string& what) {
  std::fprintf(stderr, "glint fuzz finding: %s\n", what.c_str());
  std::abort();
}

}  // namespace glint::fuzz
