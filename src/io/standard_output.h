// Standard output checked like any output file: a write that fails (a full disk behind
// `> file`, /dev/full, a pipe whose reader left while SIGPIPE is ignored) is an error the run
// reports, not a silent loss.
//
// std::cout, synced with C stdio by default, loses the reason of a failed write: stdio keeps only
// an error flag, and errno is long overwritten when the program looks. check_standard_output()
// gives std::cout a buffer of its own over descriptor 1 that keeps the errno of its first failed
// write (later writes are dropped: what follows a lost block would be misleading) and flushes at
// every newline on a terminal, fully buffered otherwise, as stdio does. finish_standard_output()
// flushes it and C stdio's stdout and throws OutputError("standard output: write failed: ...").
//
// The streams written to "-" (OutputSet::add with allow_stdout, the VCD writer) write descriptor
// 1 themselves and report their own errors; a run has one writer of standard output at a time
// (OutputSet::claim_stdout), so their bytes and std::cout's never interleave.
#pragma once

namespace glint {

// Installs the checked buffer on std::cout (idempotent; the buffer lives until the process ends,
// so the library's final flush at exit finds it). glint's main() calls it; a library user decides.
void check_standard_output();

// Flushes std::cout and stdout; throws OutputError naming standard output and the first error a
// write to it met since the last call, which clears it. Without check_standard_output(), only
// what stdio still knows (its error flag, the errno of this flush) is reported.
void finish_standard_output();

}  // namespace glint
