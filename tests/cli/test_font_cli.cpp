// GLINT_FONT is an input (issue 29): every command that draws text refuses a bad font before any
// work, with exit 2 and a message naming GLINT_FONT, the file and what is wrong, leaving no
// output folder, no temporary and every old output as it was. Runs the real glint binary, under
// `timeout` so that a FIFO that blocked glint would fail the test instead of hanging it.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using test::shell_quote;
using test::TempDir;

const std::string kSource = GLINT_SOURCE_DIR;
const std::string kScene = kSource + "/traces/scenes/small.json";
const std::string kVectors = kSource + "/traces/blinn_colored.vec";
const std::string kDejaVu = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";

struct GlintRun {
  int status = -1;
  std::string err;
};

// `glint ARGS` in `dir` with GLINT_FONT=font, killed after 60 s (status -1 then).
GlintRun glint_with_font(const TempDir& dir, const std::string& font, const std::string& args) {
  const std::string err = dir.file("stderr.txt");
  const std::string cmd = "cd " + shell_quote(dir.path().string()) +
                          " && GLINT_FONT=" + shell_quote(font) + " timeout -s KILL 60 " +
                          shell_quote(GLINT_BINARY_DIR "/glint") + " " + args + " >/dev/null 2>" +
                          shell_quote(err) + " </dev/null";
  const int raw = std::system(cmd.c_str());
  GlintRun r;
  r.status = (raw != -1 && WIFEXITED(raw)) ? WEXITSTATUS(raw) : -1;
  r.err = test::read_file(err);
  fs::remove(err);
  return r;
}

void write(const std::string& path, const std::string& bytes) {
  std::ofstream(path, std::ios::binary) << bytes;
}

struct BadFont {
  const char* name;
  const char* message;  // what the refusal says is wrong
};

// Names the case in the test's ctest name instead of its bytes.
void PrintTo(const BadFont& f, std::ostream* os) {
  *os << f.name;
}

class BadFontRefused : public ::testing::TestWithParam<BadFont> {
 protected:
  // Makes the case's font in the scratch folder (or names a system file); returns its path.
  std::string make_font() {
    const std::string which = GetParam().name;
    const std::string path = dir_.file("font.ttf");
    if (which == "truncated") {
      write(path, test::read_file(kDejaVu).substr(0, 300000));
    } else if (which == "short_glyf") {
      // A whole file whose table directory says 'glyf' is 1000 bytes: the glyphs that 'loca'
      // places beyond them would be read outside the table.
      std::string font = test::read_file(kDejaVu);
      const std::size_t entry = font.find("glyf");
      EXPECT_LT(entry, 12 + 16 * 64u);
      font.replace(entry + 12, 4, std::string("\0\0\x03\xe8", 4));
      write(path, font);
    } else if (which == "zero") {
      return "/dev/zero";
    } else if (which == "fifo") {
      EXPECT_EQ(::mkfifo(path.c_str(), 0600), 0);
    } else if (which == "folder") {
      fs::create_directory(path);
    } else if (which == "empty") {
      write(path, "");
    } else if (which == "sparse") {
      // 10 GB that cost no disk: a hole.
      const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
      EXPECT_GE(fd, 0);
      EXPECT_EQ(::ftruncate(fd, off_t{10} << 30), 0);
      ::close(fd);
    } else if (which == "not_a_font") {
      write(path, test::read_file(kScene));
    } else if (which == "missing") {
      return dir_.file("no-such-font.ttf");
    }
    return path;
  }

  void expect_refused(const GlintRun& r, const std::string& font) {
    EXPECT_EQ(r.status, 2) << r.err;
    EXPECT_NE(r.err.find("glint: " + font + ": field 'GLINT_FONT': "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(GetParam().message), std::string::npos) << r.err;
  }

  TempDir dir_;
};

TEST_P(BadFontRefused, RenderLeavesNoFolder) {
  const std::string font = make_font();
  const GlintRun r =
      glint_with_font(dir_, font, "render " + shell_quote(kScene) + " -o out --unit lut");
  expect_refused(r, font);
  EXPECT_FALSE(fs::exists(dir_.file("out")));
}

TEST_P(BadFontRefused, RenderKeepsOldOutputs) {
  const std::string font = make_font();
  fs::create_directory(dir_.file("out"));
  write(dir_.file("out/report.json"), "old report");
  const GlintRun run =
      glint_with_font(dir_, font, "render " + shell_quote(kScene) + " -o out --unit lut");
  expect_refused(run, font);
  EXPECT_EQ(test::read_file(dir_.file("out/report.json")), "old report");
  std::vector<std::string> left;
  for (const auto& e : fs::directory_iterator(dir_.file("out")))
    left.push_back(e.path().filename());
  EXPECT_EQ(left, std::vector<std::string>{"report.json"});  // no temporary
}

TEST_P(BadFontRefused, SweepPlotLeavesNoFolder) {
  const std::string font = make_font();
  const GlintRun r = glint_with_font(
      dir_, font, "sweep " + shell_quote(kVectors) + " --grid 'pow:log_bits=5..6' --plot plots");
  expect_refused(r, font);
  EXPECT_FALSE(fs::exists(dir_.file("plots")));
}

// A scene sweep's renders make no images, so without --plot or --html it needs no font: the bad
// one is not read, and the report is written. With --html (its plots) it is refused.
TEST_P(BadFontRefused, SweepSceneNeedsTheFontOnlyForPlots) {
  const std::string font = make_font();
  const GlintRun ok = glint_with_font(
      dir_, font, "sweep --scene " + shell_quote(kScene) + " --grid 'lut:bits=4' -o sweep.json");
  EXPECT_EQ(ok.status, 0) << ok.err;
  EXPECT_TRUE(fs::exists(dir_.file("sweep.json")));
  const GlintRun r = glint_with_font(dir_, font,
                                     "sweep --scene " + shell_quote(kScene) +
                                         " --grid 'lut:bits=4' -o sweep2.json --html sweep.html");
  expect_refused(r, font);
  EXPECT_FALSE(fs::exists(dir_.file("sweep2.json")));
  EXPECT_FALSE(fs::exists(dir_.file("sweep.html")));
}

// size --html and merge --plot draw plots.
TEST_P(BadFontRefused, SizeAndMergeRefuseIt) {
  const std::string font = make_font();
  expect_refused(glint_with_font(dir_, font,
                                 "size --scene " + shell_quote(kScene) +
                                     " --no-image --grid 'lut:bits=4' --budget 'max_lsb<=4' "
                                     "--html size.html"),
                 font);
  EXPECT_FALSE(fs::exists(dir_.file("size.html")));
  expect_refused(glint_with_font(dir_, font, "merge no-shard.json --plot plots"), font);
  EXPECT_FALSE(fs::exists(dir_.file("plots")));
}

INSTANTIATE_TEST_SUITE_P(
    Cases, BadFontRefused,
    ::testing::Values(BadFont{"truncated", "runs past the end of the file"},
                      BadFont{"short_glyf", "is not inside table 'glyf' (1000 bytes)"},
                      BadFont{"zero", "not a regular file (a character device)"},
                      BadFont{"fifo", "not a regular file (a FIFO)"},
                      BadFont{"folder", "not a regular file (a folder)"}, BadFont{"empty", "empty"},
                      BadFont{"sparse", "10737418240 bytes, more than a font may have (32 MiB)"},
                      BadFont{"not_a_font", "not a TrueType font"},
                      BadFont{"missing", "cannot open: No such file or directory"}),
    [](const ::testing::TestParamInfo<BadFont>& info) { return std::string(info.param.name); });

// Commands that draw no text do not read the font at all.
TEST(FontCli, VectorSweepWithoutPlotIgnoresTheFont) {
  TempDir dir;
  const GlintRun r = glint_with_font(dir, "/dev/zero",
                                     "sweep " + shell_quote(kVectors) + " --grid 'pow:log_bits=5'");
  EXPECT_EQ(r.status, 0) << r.err;
}

// GLINT_FONT naming the default font draws exactly what the default does.
TEST(FontCli, NamedDefaultFontGivesTheSameSheet) {
  TempDir dir;
  const GlintRun named =
      glint_with_font(dir, kDejaVu, "render " + shell_quote(kScene) + " -o named --unit lut");
  ASSERT_EQ(named.status, 0) << named.err;
  const GlintRun unset =
      glint_with_font(dir, "", "render " + shell_quote(kScene) + " -o unset --unit lut");
  ASSERT_EQ(unset.status, 0) << unset.err;
  const std::string sheet = test::read_file(dir.file("named/contact_sheet.png"));
  EXPECT_GT(sheet.size(), 1000u);
  EXPECT_EQ(sheet, test::read_file(dir.file("unset/contact_sheet.png")));
}

}  // namespace
}  // namespace glint
