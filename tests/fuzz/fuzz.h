// libFuzzer harnesses of glint's parsers (tests/fuzz/README.md). Each harness is a function over
// one input; built with GLINT_FUZZ_ENTRY (the fuzz_* programs of GLINT_FUZZ=ON) it is also the
// program's LLVMFuzzerTestOneInput, and without it tests/fuzz/test_fuzz_replay.cpp calls it on
// every seed and every regression input in the normal suite.
//
// A harness returns 0 for any input that glint accepts or refuses the way the CLI would with exit
// 2 (InputError, std::invalid_argument); anything else is a finding and aborts through fail():
// another exception type (the CLI's "internal error", exit 3), a property the harness checks (a
// round trip, an idempotent spec), and of course a sanitizer report, a timeout or running out of
// memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace glint::fuzz {

int vectors(const std::uint8_t* data, std::size_t size);
int specs(const std::uint8_t* data, std::size_t size);
int units(const std::uint8_t* data, std::size_t size);
int scene(const std::uint8_t* data, std::size_t size);
int scene_render(const std::uint8_t* data, std::size_t size);
int golden(const std::uint8_t* data, std::size_t size);
int report(const std::uint8_t* data, std::size_t size);
int options(const std::uint8_t* data, std::size_t size);
int font(const std::uint8_t* data, std::size_t size);
int mesh(const std::uint8_t* data, std::size_t size);

// Reports a finding on stderr and aborts (libFuzzer then saves the input as a crash).
[[noreturn]] void fail(const std::string& what);

// A folder of this process for the files a harness writes per input, one per `name`
// (glint_fuzz_<name>.XXXXXX), made on first use and removed when the process exits normally
// (libFuzzer's -runs/-max_total_time, the replay test); a crash leaves it for the finding's replay
// to overwrite. In $TMPDIR if set, else in /dev/shm: on ext4 a truncated file is flushed when it
// is closed (auto_da_alloc), and rewriting three files per input held the scene harness to 363
// executions a second against 3122 in tmpfs (60 s runs from the same corpus, one after the other).
const std::filesystem::path& temp_folder(const std::string& name);

}  // namespace glint::fuzz

#ifdef GLINT_FUZZ_ENTRY
#define GLINT_FUZZ_TARGET(harness)                                                    \
  extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) { \
    return glint::fuzz::harness(data, size);                                          \
  }
#else
#define GLINT_FUZZ_TARGET(harness)
#endif
