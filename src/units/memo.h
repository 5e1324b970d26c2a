// A bounded, thread-safe memo per process for the units' fits (horner: slots.cpp, fit_engine.cpp;
// pwp: fit_engine.cpp): each a pure function of its key that costs milliseconds to tens of
// milliseconds, which a sweep asks for again and again. A full memo starts afresh, so memory stays
// bounded (~1 MB for the fits) however long a sweep or fuzz run goes.
#pragma once

#include <cstddef>
#include <map>
#include <mutex>

namespace glint {

template <class Key, class Value>
class Memo {
 public:
  template <typename Run>
  Value get(const Key& key, Run&& run) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      if (const auto it = values_.find(key); it != values_.end()) return it->second;
    }
    Value v = run();  // outside the lock: two threads may compute alike, both equal
    const std::lock_guard<std::mutex> lock(mutex_);
    if (values_.size() >= kMaxEntries) values_.clear();
    values_.emplace(key, v);
    return v;
  }

 private:
  static constexpr std::size_t kMaxEntries = 4096;
  std::mutex mutex_;
  std::map<Key, Value> values_;
};

}  // namespace glint
