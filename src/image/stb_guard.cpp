// stb_truetype's implementation for glint (stb_guard.h says why it is compiled here): assertions
// throw, allocations are recorded per thread so that StbScope can free what a throw left behind.
#include "image/stb_guard.h"

#include <cstdlib>
#include <exception>
#include <iterator>
#include <string>
#include <vector>

namespace glint::stb_detail {
namespace {
thread_local std::vector<void*> live;  // stb's blocks not yet freed, in allocation order
}  // namespace

void* allocate(std::size_t n) {
  live.reserve(live.size() + 1);  // may throw before anything is allocated, never after
  void* p = std::malloc(n);
  if (p) live.push_back(p);
  return p;
}

void release(void* p) {
  if (!p) return;
  // stb frees in nearly the reverse order it allocates.
  for (auto it = live.rbegin(); it != live.rend(); ++it) {
    if (*it == p) {
      live.erase(std::next(it).base());
      break;
    }
  }
  std::free(p);
}

[[noreturn]] void assertion_failed(const char* condition) {
  throw StbAssertion(std::string("stb_truetype's assertion `") + condition + "` failed");
}

}  // namespace glint::stb_detail

#define STBTT_malloc(x, u) ((void)(u), glint::stb_detail::allocate(x))
#define STBTT_free(x, u) ((void)(u), glint::stb_detail::release(x))
#define STBTT_assert(x) ((x) ? (void)0 : glint::stb_detail::assertion_failed(#x))
#define STB_TRUETYPE_IMPLEMENTATION
#include <stb_truetype.h>

namespace glint {

StbScope::StbScope() : mark_(stb_detail::live.size()), uncaught_(std::uncaught_exceptions()) {}

StbScope::~StbScope() {
  if (std::uncaught_exceptions() <= uncaught_) return;
  while (stb_detail::live.size() > mark_) {
    std::free(stb_detail::live.back());
    stb_detail::live.pop_back();
  }
}

}  // namespace glint
