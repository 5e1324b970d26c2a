// Every option value of every subcommand validated (issue 11): out of range, NaN, infinities,
// overflow and values that would make a run endless exit 2 with the option named, before any
// input is read or output written; the limits are stated in --help. And `glint regress` cannot be
// fooled: a golden that lacks a field, has an extra one or a value of another type is refused
// naming the file and the field, a golden without its trace is refused, and a tampered trace fails.
// Runs the real binary, as tests/cli/test_cli.cpp does (its own small fixture).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kTraces = GLINT_SOURCE_DIR "/traces";
const std::string kPhong = kTraces + "/phong_basic.vec";

using glint::test::CliRun;

class CliOptions : public ::testing::Test {
 protected:
  CliRun glint(const std::string& args) { return glint::test::run_glint(dir_.path(), args); }
  // Exit 2, the option (or text) named on stderr, nothing on stdout, nothing left in the folder.
  void expect_refused(const std::string& args, const std::string& names) {
    SCOPED_TRACE(args);
    const CliRun r = glint(args);
    EXPECT_EQ(r.status, 2) << r.out << r.err;
    EXPECT_NE(r.err.find(names), std::string::npos) << r.err;
    EXPECT_EQ(r.out, "");
    EXPECT_EQ(dir_.entries(), std::vector<std::string>{}) << args;
  }
  glint::test::TempDir dir_;
};

struct Case {
  std::string args;
  std::string names;  // expected on stderr
};

TEST_F(CliOptions, Tau) {
  const std::string base = "tau --shininess 50 --eps 1e-3 ";
  for (const Case& c : std::vector<Case>{
           {"tau --shininess 0 --eps 1e-3", "--shininess"},
           {"tau --shininess -3 --eps 1e-3", "--shininess"},
           {"tau --shininess nan --eps 1e-3", "--shininess"},
           {"tau --shininess inf --eps 1e-3", "--shininess"},
           {"tau --shininess 1e999 --eps 1e-3", "--shininess"},
           {"tau --eps 1e-3", "--shininess"},
           {"tau --shininess 50 --eps 0", "--eps"},
           {"tau --shininess 50 --eps nan", "--eps"},
           {"tau --shininess 50 --eps inf", "--eps"},
           {"tau --shininess 50 --eps -1", "--eps"},
           {"tau --shininess 50", "--eps"},
           {base + "--lights 0", "--lights"},
           {base + "--lights 1048577", "--lights"},
           {base + "--lights 1e30", "--lights"},
           {base + "--lights 99999999999999999999", "--lights"},
           {base + "--color 1,1", "--color"},
           {base + "--color 1,nan,1", "--color"},
           {base + "--color 1,-1,1", "--color"},
           {base + "--light inf,1,1", "--light"},
           {base + "--color 1e200,1e200,1e200 --light 1e200,1e200,1e200", "overflows"},
           {base + "--lobe cosine", "--lobe"},
           {base + "--roughness 0.5", "--roughness"},
           {"tau --eps 1e-3 --lobe gaussian", "--roughness"},
           {"tau --eps 1e-3 --lobe gaussian --roughness 0", "--roughness"},
           {"tau --eps 1e-3 --lobe gaussian --roughness 1.5", "--roughness"},
           {"tau --eps 1e-3 --lobe gaussian --roughness nan", "--roughness"},
           {"tau --eps 1e-3 --lobe gaussian --roughness 0.3 --shininess 0", "--shininess"},
       })
    expect_refused(c.args, c.names);
  // In range: a Gaussian lobe without a shininess, the largest K.
  EXPECT_EQ(glint("tau --eps 1e-3 --lobe gaussian --roughness 0.3").status, 0);
  EXPECT_EQ(glint(base + "--lights 1048576").status, 0);
}

TEST_F(CliOptions, Fit) {
  for (const Case& c : std::vector<Case>{
           {"fit --shininess 0", "--shininess"},
           {"fit --shininess nan", "--shininess"},
           {"fit --shininess inf", "--shininess"},
           {"fit", "--shininess"},
           {"fit --shininess 50 --degree 0", "--degree"},
           {"fit --shininess 50 --degree 11", "--degree"},
           {"fit --shininess 50 --degree 1e9", "--degree"},
           {"fit --shininess 50 --method cubic", "--method"},
           {"fit --shininess 50 --domain half", "--domain"},
           {"fit --shininess 50 --eps nan --domain tau", "--eps"},
           {"fit --shininess 50 --eps 0", "--eps"},
           {"fit --shininess 50 --color 1,1,x", "--color"},
           {"fit --shininess 50 --samples 1", "--samples"},
           {"fit --shininess 50 --samples 1000001", "--samples"},
           {"fit --shininess 50 --samples 1e3", "--samples"},
           {"fit --shininess 50 --samples nan", "--samples"},
           {"fit --shininess 50 --degree 6 --samples 6", "--samples"},
           {"fit --shininess 50 --method minimax --samples 1000", "--samples"},
       })
    expect_refused(c.args, c.names);
}

// What the option parser itself refuses is one line in glint's form, naming the subcommand.
TEST_F(CliOptions, ParserRefusalsAreOneLineNamingTheSubcommand) {
  for (const auto& [args, line] : std::vector<std::pair<std::string, std::string>>{
           {"eval " + kPhong + " --display-bits 17",
            "glint eval: --display-bits: Value 17 not in range 1 to 16 (see glint eval --help)\n"},
           {"sim " + kPhong + " --unit lut --frob",
            "glint sim: The following argument was not expected: --frob (see glint sim --help)\n"},
           {"size " + kPhong, "glint size: --budget is required (see glint size --help)\n"},
           {"", "glint: A subcommand is required (see glint --help)\n"},
           // An unknown option is named before a missing argument, and the subcommand named
           // wherever it stands.
           {"render --frob",
            "glint render: The following argument was not expected: --frob (see glint render "
            "--help)\n"},
           {"--frob eval",
            "glint eval: The following argument was not expected: --frob (see glint eval "
            "--help)\n"},
           {"--frob",
            "glint: The following argument was not expected: --frob (see glint --help)\n"},
           {"size " + kPhong + " '--budgte=lsb8<=1'",
            "glint size: The following argument was not expected: --budgte=lsb8<=1 (see glint "
            "size --help)\n"},
           {"size --grid lut:bits=4 -q",
            "glint size: The following argument was not expected: -q (see glint size --help)\n"},
       }) {
    SCOPED_TRACE(args);
    const CliRun r = glint(args);
    EXPECT_EQ(r.status, 2);
    EXPECT_EQ(r.err.rfind(line, 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  }
}

TEST_F(CliOptions, Eval) {
  std::string many;
  for (int i = 0; i < 65; ++i) many += " --unit pow";
  for (const Case& c : std::vector<Case>{
           {"eval " + kPhong + " --display-bits 0", "--display-bits"},
           {"eval " + kPhong + " --display-bits 17", "--display-bits"},
           {"eval " + kPhong + " --display-bits nan", "--display-bits"},
           {"eval " + kPhong + " --chip ram:slots=0", "--chip"},
           {"eval " + kPhong + " --chip ram:slots=-1", "--chip"},
           {"eval " + kPhong + " --chip ram:slots=1048577", "--chip"},
           {"eval " + kPhong + " --chip ram:slots=18446744073709551617", "--chip"},
           {"eval " + kPhong + " --chip ram:slots=1e3", "--chip"},
           {"eval " + kPhong + " --chip flash", "--chip"},
           {"eval " + kPhong + " --chip rom:slots=4", "--chip"},
           {"eval " + kPhong + " --chip ram:colour=on", "--chip"},
           {"eval " + kPhong + " --chip ram:slots=4,slots=5", "--chip"},
           {"eval " + kPhong + " --chip ram --unit lut:tables=rom", "--chip"},
           {"eval " + kPhong + " --unit pow:", "pow:"},
           {"eval " + kPhong + " --unit pow:in=uq1.57", "pow"},
           {"eval " + kPhong + many, "--unit"},
       })
    expect_refused(c.args, c.names);
}

TEST_F(CliOptions, Sim) {
  const std::string base = "sim " + kPhong + " ";
  for (const Case& c : std::vector<Case>{
           // Near 0 a run takes ~vectors / P cycles: endless. The stated minimum is 0.01.
           {base + "--sink-ready 1e-9", "--sink-ready"},
           {base + "--sink-ready 0.00999", "--sink-ready"},
           {base + "--sink-ready 0", "--sink-ready"},
           {base + "--sink-ready 1.0001", "--sink-ready"},
           {base + "--sink-ready nan", "--sink-ready"},
           {base + "--sink-ready inf", "--sink-ready"},
           {base + "--seed -1", "--seed"},
           {base + "--seed 1e30", "--seed"},
           {base + "--seed 18446744073709551616", "--seed"},
           {base + "--seed 0x10", "--seed"},
           {base + "--seed ''", "--seed"},
           {base + "--vcd-window 5:4", "--vcd-window"},
           {base + "--vcd-window 0:18446744073709551616", "--vcd-window"},
           {base + "--vcd-window -1:3", "--vcd-window"},
           {base + "--vcd-window 3", "--vcd-window"},
           {base + "--batch 0", "--batch"},
           {base + "--batch 16777217", "--batch"},
           {base + "--batch -1", "--batch"},
           {base + "--batch 1e30", "--batch"},
           {base + "--mode turbo", "--mode"},
           {base + "--display-bits 99", "--display-bits"},
           {base + "--chip ram:materials=2000000", "--chip"},
           {base + "--mode fast --vcd t.vcd", "--vcd"},
           // An option that does nothing without another names both (issue 29, item 4).
           {base + "--vcd-window 1:2", "--vcd-window selects the vectors --vcd traces"},
           {base + "--mode clocked --vcd-window 1:2", "it needs --vcd"},
       })
    expect_refused(c.args, c.names);
  // The limits themselves are accepted.
  EXPECT_EQ(glint(base + "--sink-ready 0.01 --seed 18446744073709551615 --batch 16777216").status,
            0);
}

TEST_F(CliOptions, RegressAndRender) {
  std::string many;
  for (int i = 0; i < 65; ++i) many += " --unit pow";
  for (const Case& c : std::vector<Case>{
           {"regress --traces " + kTraces + " --tolerance nan", "--tolerance"},
           {"regress --traces " + kTraces + " --tolerance -1e-9", "--tolerance"},
           {"regress --traces " + kTraces + " --tolerance inf", "--tolerance"},
           {"regress --traces " + kTraces + " --tolerance 1e999", "--tolerance"},
           {"regress --traces " + kTraces + " --update" + many, "--unit"},
           {"regress --traces no_such_dir", "--traces"},
           {"render " + kTraces + "/scenes/small.json -o out --threads 0", "--threads"},
           {"render " + kTraces + "/scenes/small.json -o out --threads 257", "--threads"},
           {"render " + kTraces + "/scenes/small.json -o out --threads 1e9", "--threads"},
           {"render " + kTraces + "/scenes/small.json -o out --chip ram:slots=0", "--chip"},
           {"render " + kTraces + "/scenes/small.json -o out --unit lut:bits=99", "bits"},
           {"render " + kTraces + "/scenes/small.json", "--out"},
       })
    expect_refused(c.args, c.names);
}

// An option that has no effect without another is refused naming both (issue 29, item 4), before
// any input is read; with its partner it is accepted.
TEST_F(CliOptions, OptionWithoutItsPartnerIsRefused) {
  const std::string sim = "sim " + kPhong + " --unit pow ";
  const std::string sweep = "sweep " + kPhong + " --grid pow:in=uq1.12 ";
  const std::string scene = kTraces + "/scenes/small.json";
  for (const Case& c : std::vector<Case>{
           {sim + "--seed 5",
            "--seed sets the pattern of a sink that is not always ready: it "
            "needs --sink-ready below 1"},
           {sim + "--seed 5 --sink-ready 1", "needs --sink-ready below 1"},
           {sweep + "--seed 5", "needs --sink-ready below 1"},
           {"rtl pow --vectors " + kPhong + " -o out --seed 5", "needs --sink-ready below 1"},
           {sim + "--mode clocked --batch 64",
            "--batch sets fast mode's requests per time "
            "quantum: --mode clocked has none"},
           // The default value given explicitly is still a request the clocked mode ignores.
           {sim + "--mode clocked --batch 4096", "--batch"},
           {sim + "--vcd t.vcd --batch 64", "--vcd (clocked mode) has none"},
           {sim + "--mode clocked --threads 2",
            "--threads sets fast mode's threads: --mode "
            "clocked runs on one"},
           {sim + "--vcd t.vcd --threads 2", "--vcd (clocked mode) runs on one"},
           {sweep + "--no-image",
            "--no-image leaves out the image-level error of --scene: it "
            "needs --scene"},
           {"size " + kPhong + " --budget 'max_lsb<=1' --grid pow --no-image", "it needs --scene"},
           {"rtl pow --scene " + scene + " -o out --no-sweep",
            "--no-sweep leaves only the rows of --vectors in the testbench: it needs --vectors"},
       })
    expect_refused(c.args, c.names);
  for (const std::string& args :
       {sim + "--seed 5 --sink-ready 0.5", sim + "--mode fast --batch 64 --threads 2",
        sweep + "--seed 5 --sink-ready 0.5 -o out.csv"}) {
    const CliRun r = glint(args);
    EXPECT_EQ(r.status, 0) << args << ": " << r.err;
  }
}

// A stream beyond a run's resource limits (eval/evaluate.h) is refused against its file, naming the
// limit, before any unit is built, by every subcommand that reads a stream's slots: here 32769
// materials under two lights of different colours need 65538 slots (the limit is 65536), and 4097
// materials under 1024 white lights one slot each but 4195328 light x material pairs (the limit is
// 2^22).
TEST_F(CliOptions, StreamBeyondTheSlotLimitIsRefused) {
  const auto write = [&](const char* name, const char* lights, int materials) {
    std::ofstream out(dir_.path() / name);
    out << "glint-vectors 1\neps 1e-3\n" << lights;
    for (int m = 0; m < materials; ++m)
      out << "material m" << m << " specular=1,1,1 shininess=50 lobe=phong\n";
    out << "columns t material light\ndata\n0.5 m0 1\n";
  };
  write("big.vec", "lights 2\nlight 1 1,0.5,0.25\n", 32769);
  write("lit.vec", "lights 1024\n", 4097);
  for (const auto& [file, limit] :
       {std::pair<std::string, std::string>{"big.vec", "more than 65536 slots"},
        {"lit.vec", "4195328 light x material pairs, more than the limit of 4194304"}})
    for (const std::string& args :
         {"eval " + file + " --unit pow", "sim " + file + " --unit pow",
          "sweep " + file + " --grid pow -o out.csv", "rtl pow --vectors " + file + " -o out"}) {
      const CliRun r = glint(args);
      EXPECT_EQ(r.status, 2) << args << ": " << r.out << r.err;
      EXPECT_NE(r.err.find(file + ": field 'slots'"), std::string::npos) << args << ": " << r.err;
      EXPECT_NE(r.err.find(limit), std::string::npos) << args << ": " << r.err;
    }
  EXPECT_EQ(dir_.entries(), (std::vector<std::string>{"big.vec", "lit.vec"}));
}

// Each limit is stated in the subcommand's --help.
TEST_F(CliOptions, HelpStatesTheLimits) {
  struct Help {
    const char* sub;
    std::vector<std::string> texts;
  };
  for (const Help& h : std::vector<Help>{
           {"tau", {"finite, > 0", "1..1048576", "(0, 1]", "finite and >= 0"}},
           {"fit", {"finite, > 0", "1..10", "2..1000000"}},
           {"eval", {"1..16", "1..1048576", "at most 64"}},
           {"sim", {"[0.01, 1]", "0..2^64-1", "1..16777216", "1..16", "1..1048576", "at most 64"}},
           {"regress", {"finite number >= 0"}},
           {"render", {"1..256", "1..1048576", "at most 64"}},
       }) {
    const CliRun r = glint(std::string(h.sub) + " --help");
    EXPECT_EQ(r.status, 0) << h.sub;
    for (const auto& t : h.texts) EXPECT_NE(r.out.find(t), std::string::npos) << h.sub << ": " << t;
  }
}

// ---------------------------------------------------------------------------------------------
// glint regress: goldens against their schema.

class RegressSchema : public CliOptions {
 protected:
  void SetUp() override {
    fs::create_directories(dir_.path() / "t" / "golden");
    fs::copy_file(kPhong, dir_.path() / "t" / "phong_basic.vec");
    golden_ = json::parse(glint::test::read_file(kTraces + "/golden/phong_basic.json"));
  }
  void write_golden(const json& g) {
    std::ofstream(dir_.path() / "t" / "golden" / "phong_basic.json") << g.dump(2);
  }
  CliRun regress() { return glint("regress --traces t"); }
  json golden_;
};

TEST_F(RegressSchema, ShippedGoldenPasses) {
  write_golden(golden_);
  const CliRun r = regress();
  EXPECT_EQ(r.status, 0) << r.out << r.err;
}

// A stripped golden used to pass any trace: every missing, extra or retyped field is refused.
TEST_F(RegressSchema, StrippedExtendedOrRetypedGoldenIsRefused) {
  struct Edit {
    void (*apply)(json&);
    const char* field;
  };
  for (const Edit& e : std::vector<Edit>{
           {[](json& g) { g["report"]["units"][0].erase("digest"); }, "report.units[0].digest"},
           {[](json& g) { g["report"]["units"][0]["errors"].erase("max_abs"); },
            "report.units[0].errors.max_abs"},
           {[](json& g) { g["report"]["units"][3]["elaboration"].erase("slot_list"); },
            "report.units[3].elaboration.slot_list"},
           {[](json& g) { g["report"].erase("rows"); }, "report.rows"},
           {[](json& g) { g["report"]["units"][0]["extra"] = 1; }, "report.units[0].extra"},
           {[](json& g) { g["report"]["units"][1]["errors"]["parts"]["x"] = 1; },
            "report.units[1].errors.parts.x"},
           {[](json& g) { g["report"]["units"][0]["cycles"] = "1001"; }, "report.units[0].cycles"},
           {[](json& g) { g["report"]["units"][0]["config"]["in"] = 16; },
            "report.units[0].config.in"},
           {[](json& g) { g["seed"] = "7"; }, "seed"},
           {[](json& g) { g.erase("units"); }, "units"},
       }) {
    json g = golden_;
    e.apply(g);
    write_golden(g);
    const CliRun r = regress();
    EXPECT_EQ(r.status, 2) << e.field << ": " << r.out << r.err;
    EXPECT_NE(r.err.find("phong_basic.json"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(std::string("field '") + e.field + "'"), std::string::npos) << r.err;
  }
}

// With a complete golden, a tampered trace fails (exit 1), with the field that differs.
TEST_F(RegressSchema, TamperedTraceFails) {
  write_golden(golden_);
  std::string text = glint::test::read_file(kPhong);
  const auto pos = text.rfind("\n1.000 white\n");
  ASSERT_NE(pos, std::string::npos);
  text.replace(pos, 13, "\n0.999 white\n");
  std::ofstream(dir_.path() / "t" / "phong_basic.vec") << text;
  const CliRun r = regress();
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_NE(r.out.find("digest"), std::string::npos) << r.out;
}

TEST_F(RegressSchema, GoldenWithoutItsTraceOrForAnotherIsRefused) {
  write_golden(golden_);
  std::ofstream(dir_.path() / "t" / "golden" / "gone.json") << golden_.dump();
  CliRun r = regress();
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("gone.json"), std::string::npos) << r.err;
  fs::remove(dir_.path() / "t" / "golden" / "gone.json");
  json g = golden_;
  g["trace"] = "other.vec";
  g["report"]["vectors_file"] = "other.vec";
  write_golden(g);
  r = regress();
  EXPECT_EQ(r.status, 2) << r.out << r.err;
  EXPECT_NE(r.err.find("field 'trace'"), std::string::npos) << r.err;
}

}  // namespace
