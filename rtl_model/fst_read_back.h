// The check an FST passes before it replaces anything: vcd2fst exits 0 and leaves a file even when
// its writes failed (a full disk: the FST is cut short and unreadable), so its status and the
// file's size prove nothing. Debian's fst2vcd (package gtkwave, with vcd2fst) reads the FST back as
// VCD text, which is counted as it streams (io/vcd_tally.h) and compared with what glint wrote.
#pragma once

#include <cstddef>
#include <string>

#include "io/vcd_tally.h"

namespace glint::rtl {

struct FstReadBack {
  int status = 0;        // fst2vcd's wait status
  VcdCounts counts;      // of the VCD text it printed
  std::string messages;  // the start of its standard error, one line
};

// Runs `fst2vcd -f FST` with its standard error in `log` (a new file, e.g. in the FST's private
// folder) and counts its output. The process is registered with signal_cleanup.h while it runs,
// and the caller registers `log`. Throws OutputError(`what` + ...) when fst2vcd cannot be started.
FstReadBack read_back_fst(const std::string& fst, const std::string& log, const std::string& what);

// "" when `fst` holds what `written` counts (fst2vcd exited 0 and read it all back), else why not,
// naming vcd2fst and fst2vcd.
std::string fst_incomplete(const FstReadBack& back, const VcdCounts& written);

// "" when the file at `fst` is a chain of whole FST blocks, else what is wrong. fst2vcd can spin
// forever on an FST cut short inside a block, so this runs first. An FST (gtkwave's fstapi.c) is a
// sequence of blocks, each a type byte and a big-endian 64-bit length (of the rest of the block,
// those 8 bytes included): the header (type 0) first, value changes, then the geometry (3) and
// the hierarchy (4, 6 or 7) last; a block still being written has type 255. A file cut short
// ends inside a block or lacks the last ones. Hand-written: no Debian package has the FST reader
// as a library, and this needs 8 bytes per block.
std::string fst_structure_error(const std::string& fst);

// The first `max` bytes of a tool's log on one line ("" if empty; " ..." marks a cut), for an
// error message.
std::string log_start(const std::string& path, std::size_t max);

// Both checks: "" when `fst` is whole, else why not (naming vcd2fst, and fst2vcd when it ran).
std::string check_fst(const std::string& fst, const std::string& log, const std::string& what,
                      const VcdCounts& written);

}  // namespace glint::rtl
