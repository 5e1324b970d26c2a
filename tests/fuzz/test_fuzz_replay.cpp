// Replays the fuzz harnesses (tests/fuzz) in the normal suite, with every compiler: every seed of
// tests/fuzz/corpus/<harness>/ and every input a fuzzer once crashed on,
// tests/fuzz/regressions/<harness>/ (each named after what it found; see tests/fuzz/README.md). A
// finding aborts this program, which ctest reports as a failed test; the input's path is printed
// before each run.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "fuzz/fuzz.h"
#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using Harness = int (*)(const std::uint8_t*, std::size_t);

// Replays every file of tests/fuzz/<kind>/<name>/; returns how many.
int replay(const std::string& kind, const std::string& name, Harness harness) {
  const fs::path dir = fs::path(GLINT_SOURCE_DIR) / "tests" / "fuzz" / kind / name;
  if (!fs::is_directory(dir)) return 0;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    std::fprintf(stderr, "replaying %s\n", f.string().c_str());
    const std::string data = glint::test::read_file(f);
    EXPECT_EQ(harness(reinterpret_cast<const std::uint8_t*>(data.data()), data.size()), 0) << f;
  }
  return static_cast<int>(files.size());
}

// The harness `name` on the seeds and findings of `inputs` (scene_render takes scene's).
#define GLINT_REPLAY_ON(name, inputs)                                         \
  TEST(FuzzReplay, name##_seeds) {                                            \
    EXPECT_GT(replay("corpus", #inputs, glint::fuzz::name), 0) << "no seeds"; \
  }                                                                           \
  TEST(FuzzReplay, name##_findings) {                                         \
    replay("regressions", #inputs, glint::fuzz::name);                        \
  }
#define GLINT_REPLAY(name) GLINT_REPLAY_ON(name, name)

GLINT_REPLAY(vectors)
GLINT_REPLAY(specs)
GLINT_REPLAY(units)
GLINT_REPLAY(scene)
GLINT_REPLAY_ON(scene_render, scene)
GLINT_REPLAY(golden)
GLINT_REPLAY(report)
GLINT_REPLAY(options)
GLINT_REPLAY(font)
GLINT_REPLAY(mesh)

}  // namespace
