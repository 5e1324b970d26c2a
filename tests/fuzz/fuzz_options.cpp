// Command-line option values: the input's lines are the words after `glint` (at most 64, each at
// most 256 bytes), run through the real command line (cli::run) in its options-only mode: every
// subcommand parses and checks its options as in a real run and stops before it reads an input or
// writes anything (tau and fit, which read and write no file, run in full). Words with a '/' are
// dropped, so that any path an option names is a relative one.
//
// Exit statuses 0 (accepted, or --help) and 2 (refused, naming the option) are the expected ones;
// 3 (an internal error: an exception glint did not expect), anything else, or an exception escaping
// cli::run is a finding.
#include <stdexcept>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "fuzz.h"

namespace glint::fuzz {

namespace {

constexpr std::size_t kMaxWords = 64;
constexpr std::size_t kMaxWordBytes = 256;

}  // namespace

int options(const std::uint8_t* data, std::size_t size) {
  std::vector<std::string> words = {"glint"};
  std::string word;
  for (std::size_t i = 0; i <= size; ++i) {
    if (i == size || data[i] == '\n') {
      if (word.find('/') == std::string::npos && word.size() <= kMaxWordBytes)
        words.push_back(word);
      word.clear();
      if (words.size() > kMaxWords) break;
    } else {
      word += static_cast<char>(data[i]);
    }
  }
  std::vector<char*> argv;
  for (auto& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  cli::set_options_only(true);
  int status = -1;
  try {
    status = cli::run(static_cast<int>(words.size()), argv.data());
  } catch (const std::exception& e) {
    fail(std::string("an exception escaped the command line: ") + e.what());
  }
  if (status != 0 && status != 2) {
    std::string args;
    for (std::size_t i = 1; i < words.size(); ++i) args += " '" + words[i] + "'";
    fail("exit status " + std::to_string(status) + " for glint" + args);
  }
  return 0;
}

}  // namespace glint::fuzz

GLINT_FUZZ_TARGET(options)

#ifdef GLINT_FUZZ_ENTRY
// libsystemc (linked through the command line) calls sc_main from a main() of its own; libFuzzer's
// main takes precedence, so this only satisfies the linker, as in src/cli/main.cpp.
extern "C" int sc_main(int, char**) {
  return 0;
}
#endif
