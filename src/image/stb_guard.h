// stb_truetype, compiled into glint_image from Debian's header (libstb-dev) by stb_guard.cpp
// instead of linked from Debian's libstb. Debian builds libstb with assert() on, and some of the
// rasteriser's assertions are float checks, not memory guards (`sy1 > y_final-0.01f`): an outline
// that passes every check of truetype_check.h can still fail one at some subpixel shift, and
// libstb then aborts glint. Compiled here, a failed assertion throws StbAssertion before the access
// it guards, and what stb allocated inside the failed call is freed (StbScope), so a glyph stb
// cannot draw is a glyph left blank with a warning, never a crash.
#pragma once

#include <cstddef>
#include <stdexcept>

namespace glint {

class StbAssertion : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Around stb calls that may fail an assertion: when the scope is left by an exception, every
// block stb allocated on this thread since the scope began and has not freed is freed.
class StbScope {
 public:
  StbScope();
  ~StbScope();
  StbScope(const StbScope&) = delete;
  StbScope& operator=(const StbScope&) = delete;

 private:
  std::size_t mark_;
  int uncaught_;
};

}  // namespace glint
