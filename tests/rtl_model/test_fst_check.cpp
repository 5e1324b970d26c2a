// The check an FST passes before it replaces a file (rtl_model/fst_read_back.h): the VCD counts
// (io/vcd_tally.h) of what glint's writer wrote and of fst2vcd's read-back agree for a whole FST,
// and an FST cut short, as vcd2fst leaves it on a full disk while exiting 0, is refused.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "io/output_set.h"
#include "io/vcd_tally.h"
#include "io/vcd_writer.h"
#include "rtl_model/fst_read_back.h"
#include "test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using rtl::VcdCounts;
using rtl::VcdTally;

const char* const kText =
    "$date\n  today\n$end\n$timescale\n  1 ns\n$end\n$scope module top $end\n"
    "$var wire 1 ! clk $end\n$var wire 8 \" x [7:0] $end\n$upscope $end\n"
    "$enddefinitions $end\n#0\n$dumpvars\n0!\nb0 \"\n$end\n#5\n1!\nb101 \"\n#10\n0!\n#15\n";

VcdCounts tally_of(const std::string& text, std::size_t chunk) {
  VcdTally t;
  for (std::size_t i = 0; i < text.size(); i += chunk)
    t.feed(text.data() + i, std::min(chunk, text.size() - i));
  return t.counts();
}

TEST(VcdTally, CountsVariablesChangesAndTheLastTime) {
  const VcdCounts c = tally_of(kText, 1 << 20);
  EXPECT_TRUE(c.definitions_ended);
  EXPECT_EQ(c.variables, 2u);
  EXPECT_EQ(c.value_changes, 5u);  // two initial values, three changes
  EXPECT_EQ(c.time_stamps, 4u);
  EXPECT_EQ(c.last_time, 15u);
}

TEST(VcdTally, AnySplitOfTheTextCountsTheSame) {
  const VcdCounts whole = tally_of(kText, 1 << 20);
  for (std::size_t chunk = 1; chunk < 40; ++chunk) {
    const VcdCounts c = tally_of(kText, chunk);
    EXPECT_EQ(c.variables, whole.variables) << chunk;
    EXPECT_EQ(c.value_changes, whole.value_changes) << chunk;
    EXPECT_EQ(c.time_stamps, whole.time_stamps) << chunk;
    EXPECT_EQ(c.last_time, whole.last_time) << chunk;
  }
  // A last line without its newline is counted.
  std::string cut = kText;
  cut += "1!";
  EXPECT_EQ(tally_of(cut, 7).value_changes, whole.value_changes + 1);
}

TEST(VcdTally, DifferenceNamesWhatIsMissing) {
  const VcdCounts want = tally_of(kText, 1 << 20);
  EXPECT_EQ(rtl::vcd_counts_difference(want, want), "");
  VcdCounts got = want;
  got.value_changes -= 2;
  got.last_time = 10;
  const std::string d = rtl::vcd_counts_difference(want, got);
  EXPECT_NE(d.find("3 of 5 value changes"), std::string::npos) << d;
  EXPECT_NE(d.find("up to time 10 of 15"), std::string::npos) << d;
  EXPECT_NE(rtl::vcd_counts_difference(want, VcdCounts{}).find("no $enddefinitions"),
            std::string::npos);
}

// A VCD of `cycles` cycles from glint's writer, its counts tallied as it was written.
VcdCounts write_vcd(const std::string& path, int cycles) {
  std::uint64_t a = 0, b = 0;
  bool flag = false;
  rtl::VcdWriter w("SystemC");
  w.add_clock("top.clk");
  w.add_bits(a, 16, false, "top.u.a");
  w.add_bits(b, 40, true, "top.u.b");
  w.add_bool(flag, "top.u.flag");
  std::FILE* f = std::fopen(path.c_str(), "wb");
  EXPECT_NE(f, nullptr);
  w.open(f);
  w.tally();
  w.header("ns", "test");
  w.dump_all(0, false);
  for (int c = 1; c <= cycles; ++c) {
    a = static_cast<std::uint64_t>(c * 7919) & 0xffff;
    b = static_cast<std::uint64_t>(c) * 0x10001;
    flag = c % 3 == 0;
    w.time(10 * c);
    w.clock(true);
    w.changes();
    w.time(10 * c + 5);
    w.clock(false);
  }
  EXPECT_TRUE(w.close(10 * cycles + 5));
  return w.counts();
}

bool have_gtkwave_tools() {
  return std::system("command -v vcd2fst >/dev/null && command -v fst2vcd >/dev/null") == 0;
}

void convert(const std::string& vcd, const std::string& fst) {
  const std::string cmd =
      "vcd2fst -v " + test::shell_quote(vcd) + " -f " + test::shell_quote(fst) + " >/dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 0) << cmd;
}

TEST(FstCheck, AWholeFstReadsBackWithEveryChange) {
  if (!have_gtkwave_tools()) GTEST_SKIP() << "vcd2fst/fst2vcd not installed (gtkwave)";
  test::TempDir dir;
  const VcdCounts written = write_vcd(dir.file("t.vcd"), 5000);
  EXPECT_EQ(written.variables, 4u);
  EXPECT_EQ(written.last_time, 50005u);
  EXPECT_GT(written.value_changes, 10000u);
  // The writer's tally is the text's.
  EXPECT_EQ(written.value_changes,
            tally_of(test::read_file(dir.file("t.vcd")), 4096).value_changes);
  convert(dir.file("t.vcd"), dir.file("t.fst"));
  const rtl::FstReadBack back = rtl::read_back_fst(dir.file("t.fst"), dir.file("log"), "t.fst");
  EXPECT_EQ(rtl::fst_incomplete(back, written), "");
  EXPECT_EQ(back.counts.value_changes, written.value_changes);
  EXPECT_EQ(back.counts.last_time, written.last_time);
  // One change more than the FST holds is caught: the comparison is not vacuous.
  VcdCounts more = written;
  ++more.value_changes;
  EXPECT_NE(rtl::fst_incomplete(back, more).find("value changes"), std::string::npos);
}

// What vcd2fst leaves on a full disk: the FST cut short (its later blocks and the hierarchy,
// written last, are missing).
TEST(FstCheck, AnFstCutShortIsRefused) {
  if (!have_gtkwave_tools()) GTEST_SKIP() << "vcd2fst/fst2vcd not installed (gtkwave)";
  test::TempDir dir;
  const VcdCounts written = write_vcd(dir.file("t.vcd"), 5000);
  convert(dir.file("t.vcd"), dir.file("t.fst"));
  const auto size = fs::file_size(dir.file("t.fst"));
  for (const std::uintmax_t keep : {size / 4, size / 2, size - 64, size - 1}) {
    const std::string cut = dir.file("cut" + std::to_string(keep) + ".fst");
    fs::copy_file(dir.file("t.fst"), cut);
    fs::resize_file(cut, keep);
    // The structure check refuses it before fst2vcd (which can spin on such a file) runs.
    EXPECT_NE(rtl::fst_structure_error(cut), "") << keep;
    const std::string why =
        rtl::check_fst(cut, dir.file("log" + std::to_string(keep)), "cut.fst", written);
    EXPECT_NE(why.find("vcd2fst wrote an incomplete FST"), std::string::npos)
        << keep << ": " << why;
  }
  EXPECT_EQ(rtl::fst_structure_error(dir.file("t.fst")), "");
  EXPECT_EQ(rtl::check_fst(dir.file("t.fst"), dir.file("log"), "t.fst", written), "");
}

TEST(FstCheck, WithoutFst2VcdTheRunFailsNamingIt) {
  test::TempDir dir;
  const char* old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", "/nonexistent", 1);
  try {
    rtl::read_back_fst(dir.file("t.fst"), dir.file("log"), "--vcd t.fst");
    ADD_FAILURE() << "no error without fst2vcd";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("--vcd t.fst: cannot run fst2vcd"), std::string::npos)
        << e.what();
  }
  ::setenv("PATH", saved.c_str(), 1);
}

}  // namespace
}  // namespace glint
