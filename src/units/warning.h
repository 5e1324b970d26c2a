// Warnings of a unit build: a spec that builds but is unlikely to be what its user wants (horner's
// method=robust on noise-free t^n, fit.h robust_rejects_samples). A build cannot return them
// beside the unit without every command carrying them, so they go to one process-wide sink, each
// distinct message once (a sweep builds the same spec many times).
#pragma once

#include <functional>
#include <string>

namespace glint {

// Receives each distinct warning once. The default writes "glint: warning: MESSAGE" to standard
// error; an empty sink restores it. Set it before building units (tests capture warnings so).
using WarningSink = std::function<void(const std::string& message)>;
void set_warning_sink(WarningSink sink);

// Passes `message` to the sink unless it was passed before in this process. Thread-safe.
void warn_once(const std::string& message);

}  // namespace glint
