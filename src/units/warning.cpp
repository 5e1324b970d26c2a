#include "units/warning.h"

#include <cstdio>
#include <mutex>
#include <set>
#include <utility>

namespace glint {
namespace {

struct Warnings {
  std::mutex mutex;
  WarningSink sink;
  std::set<std::string> seen;
};

Warnings& warnings() {
  static Warnings w;
  return w;
}

}  // namespace

void set_warning_sink(WarningSink sink) {
  Warnings& w = warnings();
  const std::lock_guard<std::mutex> lock(w.mutex);
  w.sink = std::move(sink);
}

void warn_once(const std::string& message) {
  Warnings& w = warnings();
  const std::lock_guard<std::mutex> lock(w.mutex);
  if (!w.seen.insert(message).second) return;
  if (w.sink)
    w.sink(message);
  else
    std::fprintf(stderr, "glint: warning: %s\n", message.c_str());
}

}  // namespace glint
