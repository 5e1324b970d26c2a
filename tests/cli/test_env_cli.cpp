// TMPDIR is an input too (issue 29): the commands that make files in it (a clocked `sim` copying a
// pipe, `synth`'s work folder) refuse one they cannot use with exit 2, naming it and the reason.
// GLINT_FONT has its own file, test_font_cli.cpp.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "test_support.h"

namespace glint {
namespace {

using test::shell_quote;
using test::TempDir;

struct EnvRun {
  int status = -1;
  std::string err;
};

// `PREFIX glint ARGS` run by /bin/sh in `dir`, killed after 120 s.
EnvRun run(const TempDir& dir, const std::string& prefix, const std::string& args) {
  const std::string err = dir.file("stderr.txt");
  const std::string cmd = "cd " + shell_quote(dir.path().string()) + " && " + prefix +
                          " timeout -s KILL 120 " + shell_quote(GLINT_BINARY_DIR "/glint") + " " +
                          args + " >/dev/null 2>" + shell_quote(err);
  const int raw = std::system(cmd.c_str());
  EnvRun r;
  r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  r.err = test::read_file(err);
  return r;
}

const std::string kVectors = std::string(GLINT_SOURCE_DIR) + "/traces/blinn_colored.vec";

TEST(TmpdirCli, SynthRefusesAMissingFolder) {
  TempDir dir;
  const std::string missing = dir.file("missing");
  const EnvRun r =
      run(dir, "TMPDIR=" + shell_quote(missing), "synth lut --vectors " + shell_quote(kVectors));
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("cannot make a work folder in '" + missing +
                       "' (TMPDIR): No such file or directory"),
            std::string::npos)
      << r.err;
}

TEST(TmpdirCli, ClockedSimFromAPipeRefusesAFileAsTmpdir) {
  TempDir dir;
  const EnvRun r = run(dir, "cat " + shell_quote(kVectors) + " | TMPDIR=/dev/null",
                       "sim - --mode clocked --unit lut");
  EXPECT_EQ(r.status, 2) << r.err;
  EXPECT_NE(r.err.find("in '/dev/null': Not a directory"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace glint
