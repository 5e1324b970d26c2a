// Process-wide SystemC setup shared by every entry point that elaborates modules.
#include "rtl_model/sc_setup.h"

#include <pthread.h>

#include <cstddef>
#include <cstdlib>

#if defined(__SANITIZE_ADDRESS__)
#define GLINT_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GLINT_ASAN 1
#endif
#endif

#ifdef GLINT_ASAN
extern "C" void __sanitizer_start_switch_fiber(void** fake_stack_save, const void* bottom,
                                               std::size_t size);
extern "C" void __sanitizer_finish_switch_fiber(void* fake_stack_save, const void** bottom_old,
                                                std::size_t* size_old);
#endif

namespace glint {

void quiet_systemc_banner() {
  // SystemC prints its banner on stdout when the first simulation context is created; glint's
  // stdout carries results (and JSON), so the banner is turned off before that happens.
  setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 0);
}

void resync_sanitizer_stack() {
#ifdef GLINT_ASAN
  pthread_attr_t attr;
  if (pthread_getattr_np(pthread_self(), &attr) != 0) return;
  void* bottom = nullptr;
  std::size_t size = 0;
  const int got = pthread_attr_getstack(&attr, &bottom, &size);
  pthread_attr_destroy(&attr);
  if (got != 0) return;
  // A "switch" from this stack to itself: ASan takes the bounds given as the current stack's.
  void* fake_stack = nullptr;
  __sanitizer_start_switch_fiber(&fake_stack, bottom, size);
  __sanitizer_finish_switch_fiber(fake_stack, nullptr, nullptr);
#endif
}

}  // namespace glint
