#include "io/vcd_tally.h"

#include <algorithm>
#include <charconv>
#include <cstring>

namespace glint::rtl {

namespace {

// A line's first bytes decide what it is ("$var", "$enddefinitions", "#<time>"): a time stamp
// has at most 20 digits.
constexpr std::size_t kKeep = 32;

bool starts_with(const char* s, std::size_t n, const char* prefix) {
  const std::size_t k = std::strlen(prefix);
  return n >= k && std::memcmp(s, prefix, k) == 0;
}

}  // namespace

void VcdTally::line(const char* s, std::size_t n) {
  while (n > 0 && (s[n - 1] == '\r' || s[n - 1] == ' ' || s[n - 1] == '\t')) --n;
  while (n > 0 && (*s == ' ' || *s == '\t')) {
    ++s;
    --n;
  }
  if (n == 0) return;
  if (!counts_.definitions_ended) {
    if (starts_with(s, n, "$var")) ++counts_.variables;
    if (starts_with(s, n, "$enddefinitions")) counts_.definitions_ended = true;
    return;
  }
  if (*s == '#') {
    std::uint64_t t = 0;
    std::from_chars(s + 1, s + n, t);
    ++counts_.time_stamps;
    counts_.last_time = t;
  } else if (*s != '$') {
    ++counts_.value_changes;
  }
}

void VcdTally::feed(const char* data, std::size_t size) {
  const char* const end = data + size;
  while (data < end) {
    const char* nl = static_cast<const char*>(std::memchr(data, '\n', end - data));
    const char* stop = nl ? nl : end;
    if (partial_open_) {
      const std::size_t room = kKeep - partial_.size();
      partial_.append(data, std::min(room, static_cast<std::size_t>(stop - data)));
    }
    if (!nl) {
      if (!partial_open_) {
        partial_.assign(data, std::min(kKeep, static_cast<std::size_t>(end - data)));
        partial_open_ = true;
      }
      return;
    }
    if (partial_open_) {
      line(partial_.data(), partial_.size());
      partial_.clear();
      partial_open_ = false;
    } else {
      line(data, std::min(kKeep, static_cast<std::size_t>(nl - data)));
    }
    data = nl + 1;
  }
}

VcdCounts VcdTally::counts() const {
  if (!partial_open_) return counts_;
  VcdTally rest = *this;
  rest.line(partial_.data(), partial_.size());
  return rest.counts_;
}

std::string vcd_counts_difference(const VcdCounts& want, const VcdCounts& got) {
  std::string d;
  const auto add = [&d](const std::string& s) { d += (d.empty() ? "" : ", ") + s; };
  if (!got.definitions_ended) add("no $enddefinitions");
  if (got.variables != want.variables)
    add(std::to_string(got.variables) + " of " + std::to_string(want.variables) + " variables");
  if (got.value_changes != want.value_changes)
    add(std::to_string(got.value_changes) + " of " + std::to_string(want.value_changes) +
        " value changes");
  if (got.last_time != want.last_time)
    add("up to time " + std::to_string(got.last_time) + " of " + std::to_string(want.last_time));
  return d;
}

}  // namespace glint::rtl
