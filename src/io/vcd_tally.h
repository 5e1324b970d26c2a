// What a VCD holds, counted from its text as it streams by: variables declared, value changes,
// time stamps and the last time. Two VCDs of the same trace written by different programs (glint's
// VcdWriter, and fst2vcd reading back the FST vcd2fst made of it) format their header differently
// but agree on these counts, so they tell whether a conversion kept everything: an FST cut short
// (a full disk, which vcd2fst does not report) reads back with fewer changes, an earlier end, or
// not at all.
//
// A value change is any line after $enddefinitions that is neither a time stamp ('#') nor a
// keyword ('$dumpvars', '$end', ...); the initial values under $dumpvars count as changes.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace glint::rtl {

struct VcdCounts {
  std::uint64_t variables = 0;      // $var lines
  std::uint64_t value_changes = 0;  // see above
  std::uint64_t time_stamps = 0;    // '#' lines
  std::uint64_t last_time = 0;      // the last time stamp's value
  bool definitions_ended = false;   // $enddefinitions was seen
};

class VcdTally {
 public:
  // The next bytes of the file (any split: a line may span calls).
  void feed(const char* data, std::size_t size);
  // The counts so far; a last line without its newline is counted.
  VcdCounts counts() const;

 private:
  void line(const char* s, std::size_t n);

  VcdCounts counts_;
  std::string partial_;  // the first bytes of a line split between calls
  bool partial_open_ = false;
};

// "" when `got` (the read-back) holds what `want` (the VCD written) does, else what differs, e.g.
// "12 of 3400 value changes, up to 1200 ns of 9000 ns".
std::string vcd_counts_difference(const VcdCounts& want, const VcdCounts& got);

}  // namespace glint::rtl
