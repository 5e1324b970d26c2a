#pragma once

namespace glint {

// Call before the first SystemC object is created.
void quiet_systemc_banner();

// Call when sc_start returns. SystemC runs processes on QuickThreads coroutines and tells
// AddressSanitizer of each switch (__sanitizer_start_switch_fiber), but the switch back to the
// main stack at the end of a simulation leaves ASan holding a coroutine's stack bounds as the
// thread's. The next exception thrown then finds its stack "out of bounds": ASan skips unpoisoning
// it (a warning, google/sanitizers#189) and reports a false stack-use-after-scope at the throw
// after. This tells ASan the thread is on its own stack again; without ASan it does nothing.
void resync_sanitizer_stack();

}  // namespace glint
