// `glint sim` end to end: the fast mode (transaction-level, temporal decoupling) and the clocked
// mode (per-cycle SystemC processes) must give identical outputs and identical cycle stamps, and
// both must equal `glint eval`'s untimed datapaths bit for bit. Each run is its own `glint`
// process (SystemC elaborates once per process).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kGlint = GLINT_BINARY_DIR "/glint";
const fs::path kTraces = GLINT_SOURCE_DIR "/traces";

using glint::test::read_file;
const auto quote = glint::test::shell_quote;

std::vector<std::string> sorted_lines_without_header(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) lines.push_back(line);
  std::sort(lines.begin(), lines.end());
  return lines;
}

class SimModes : public ::testing::Test {
 protected:
  void SetUp() override {
    tmp_ = std::make_unique<glint::test::TempDir>();
    dir_ = tmp_->path();
  }
  void TearDown() override { tmp_.reset(); }

  // Runs glint; returns stdout, asserts exit status 0.
  std::string run(const std::string& args) {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string cmd =
        quote(kGlint) + " " + args + " >" + quote(out.string()) + " 2>" + quote(err.string());
    const int st = std::system(cmd.c_str());
    EXPECT_EQ(st, 0) << cmd << "\n" << read_file(err);
    return read_file(out);
  }

  // Runs both modes with the same units and sink, compares dumps (results and cycle stamps) and
  // the timing fields of the reports.
  void expect_modes_agree(const fs::path& vectors, const std::vector<std::string>& units,
                          double sink_ready, int seed) {
    std::string common = quote(vectors.string()) + " --json";
    for (const auto& u : units) common += " --unit " + quote(u);
    common += " --sink-ready " + std::to_string(sink_ready);
    // An always-ready sink has no pattern: glint refuses a --seed it would ignore.
    if (sink_ready < 1) common += " --seed " + std::to_string(seed);
    const fs::path fast_csv = dir_ / "fast.csv", clocked_csv = dir_ / "clocked.csv";
    const json fast =
        json::parse(run("sim " + common + " --mode fast --dump " + quote(fast_csv.string())));
    const json clocked =
        json::parse(run("sim " + common + " --mode clocked --dump " + quote(clocked_csv.string())));
    const auto a = sorted_lines_without_header(read_file(fast_csv));
    const auto b = sorted_lines_without_header(read_file(clocked_csv));
    ASSERT_EQ(a.size(), b.size()) << vectors;
    ASSERT_FALSE(a.empty());
    for (std::size_t i = 0; i < a.size(); ++i) ASSERT_EQ(a[i], b[i]) << vectors << " row " << i;
    ASSERT_EQ(fast["units"].size(), clocked["units"].size());
    for (std::size_t i = 0; i < fast["units"].size(); ++i) {
      const auto& f = fast["units"][i];
      const auto& c = clocked["units"][i];
      for (const char* k : {"vectors", "skipped", "computed", "cycles", "latency", "stall_cycles",
                            "stalls", "sink_wait", "digest", "operations"}) {
        EXPECT_EQ(f[k], c[k]) << vectors << " " << f["spec"] << " field " << k;
      }
    }
  }

  std::unique_ptr<glint::test::TempDir> tmp_;
  fs::path dir_;
};

const std::vector<std::string> kUnits = {"pow",    "schlick", "schlick:divider=iterative", "hast",
                                         "horner", "lut",     "lut:bits=4,buffer=2"};

std::vector<fs::path> shipped_traces() {
  std::vector<fs::path> out;
  for (const auto& e : fs::directory_iterator(kTraces))
    if (e.path().extension() == ".vec") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

TEST_F(SimModes, FastAndClockedAgreeOnEveryShippedTrace) {
  const auto traces = shipped_traces();
  ASSERT_GE(traces.size(), 6u);
  for (const auto& t : traces) expect_modes_agree(t, kUnits, 1.0, 1);
}

TEST_F(SimModes, FastAndClockedAgreeUnderBackpressure) {
  for (const auto& t : shipped_traces()) expect_modes_agree(t, kUnits, 0.6, 11);
}

TEST_F(SimModes, FastAndClockedAgreeOnRandomStreams) {
  std::mt19937_64 rng(20261121);
  for (int round = 0; round < 4; ++round) {
    const fs::path vec = dir_ / ("random" + std::to_string(round) + ".vec");
    std::ofstream out(vec);
    out << "glint-vectors 1\neps 1e-3\nlights 1\n"
        << "material a specular=1,1,1 shininess=" << (5 + round * 40) << " lobe=phong\n"
        << "material b specular=0.8,0.5,0.2 shininess=" << (200 - round * 30) << " lobe=blinn\n"
        << "columns t material\ndata\n";
    std::uniform_real_distribution<double> t(-1.0, 1.0), high(0.85, 1.0);
    std::bernoulli_distribution pick_high(0.2 + 0.2 * round);
    for (int i = 0; i < 1500; ++i)
      out << (pick_high(rng) ? high(rng) : t(rng)) << (i % 3 ? " a\n" : " b\n");
    out.close();
    const double ready = std::uniform_real_distribution<double>(0.2, 1.0)(rng);
    const int seed = static_cast<int>(rng() % 1000);
    expect_modes_agree(vec, kUnits, ready, seed);
  }
}

TEST_F(SimModes, SimOutputsEqualEvalBitForBit) {
  for (const auto& t : shipped_traces()) {
    const fs::path eval_csv = dir_ / "eval.csv", sim_csv = dir_ / "sim.csv";
    run("eval " + quote(t.string()) + " --dump " + quote(eval_csv.string()));
    run("sim " + quote(t.string()) + " --mode fast --dump " + quote(sim_csv.string()));
    // (line, unit) -> (fixed_raw, skipped) from both dumps.
    auto index = [](const std::string& text, int raw_col, int skip_col) {
      std::map<std::pair<std::string, std::string>, std::pair<std::string, std::string>> m;
      std::istringstream in(text);
      std::string line;
      std::getline(in, line);
      while (std::getline(in, line)) {
        std::vector<std::string> f;
        std::stringstream ss(line);
        for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
        const std::string unit = raw_col == 11 ? f[7] : f[1];
        m[{f[0], unit}] = {f[raw_col], f[skip_col]};
      }
      return m;
    };
    // eval: line,material,light,x,y,t,t_raw,unit,reference,model,fixed,fixed_raw,skipped
    // sim:  line,unit,t,t_raw,skipped,fixed_raw,fixed,issue,done,retire
    const auto e = index(read_file(eval_csv), 11, 12);
    const auto s = index(read_file(sim_csv), 5, 4);
    ASSERT_EQ(e.size(), s.size()) << t;
    ASSERT_FALSE(e.empty());
    EXPECT_TRUE(e == s) << t;
  }
}

TEST_F(SimModes, SkippingRaisesIterativeThroughputAndLowersPipelinedActivity) {
  const std::string vec = quote((kTraces / "phong_basic.vec").string());
  const json it = json::parse(run("sim " + vec + " --json --unit schlick:divider=iterative" +
                                  " --unit schlick:divider=iterative,skip=off"));
  const double with_skip = it["units"][0]["throughput"], without = it["units"][1]["throughput"];
  // Schlick skips below its own threshold (where S_n falls to eps: a lower t than t^n's tau),
  // ~88 % of phong_basic's rows; an II = q divider then finishes in proportion to the requests it
  // computes.
  EXPECT_GT(with_skip, 1.5 * without) << with_skip << " vs " << without;
  const double computed = it["units"][0]["computed"], vectors = it["units"][0]["vectors"];
  EXPECT_NEAR(with_skip / without, vectors / computed, 0.1 * vectors / computed);
  const json pl = json::parse(run("sim " + vec + " --json --unit schlick --unit schlick:skip=off"));
  EXPECT_LT(pl["units"][0]["computed"].get<double>(), pl["units"][1]["computed"].get<double>());
  // Pipelined: one result per cycle either way, so throughput barely moves.
  EXPECT_NEAR(pl["units"][0]["throughput"].get<double>(),
              pl["units"][1]["throughput"].get<double>(), 0.05);
}

TEST_F(SimModes, BadInputExitsTwoAndLeavesNoFiles) {
  const fs::path vec = dir_ / "bad.vec";
  std::ofstream(vec) << "glint-vectors 1\neps 1e-3\nlights 1\n"
                     << "material a specular=1,1,1 shininess=50 lobe=phong\n"
                     << "columns t material\ndata\n0.9 a\n0.95 a\nnot_a_number a\n";
  for (const char* mode : {"fast", "clocked"}) {
    const fs::path out = dir_ / "stdout.txt", err = dir_ / "stderr.txt";
    const std::string cmd =
        quote(kGlint) + " sim " + quote(vec.string()) + " --mode " + mode + " --dump " +
        quote((dir_ / "d.csv").string()) + " --report " + quote((dir_ / "r.json").string()) +
        (std::string(mode) == "clocked" ? " --vcd " + quote((dir_ / "t.vcd").string())
                                        : std::string()) +
        " >" + quote(out.string()) + " 2>" + quote(err.string());
    const int st = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(st)) << cmd;
    EXPECT_EQ(WEXITSTATUS(st), 2) << mode;
    const std::string msg = read_file(err);
    EXPECT_NE(msg.find("bad.vec:9:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'t'"), std::string::npos) << msg;
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string name = e.path().filename().string();
      EXPECT_TRUE(name == "bad.vec" || name == "stdout.txt" || name == "stderr.txt")
          << mode << " left " << name;
    }
  }
}

TEST_F(SimModes, BadWindowAndSinkAreUsageErrors) {
  const std::string vec = quote((kTraces / "phong_basic.vec").string());
  for (const char* args :
       {" --vcd-window 5", " --vcd-window 9:3", " --vcd-window a:b", " --sink-ready 0",
        " --sink-ready 1.5", " --sink-ready 1e-9", " --sink-ready 0.0099", " --sink-ready nan",
        " --mode fast --vcd x.vcd", " --seed -1", " --seed 18446744073709551616", " --seed 1x",
        " --vcd x.vcd --vcd-window 1:-1", " --vcd x.vcd --vcd-window +1:5",
        " --vcd x.vcd --vcd-window 0:18446744073709551616"}) {
    const std::string cmd = "cd " + quote(dir_.string()) + " && " + quote(kGlint) + " sim " + vec +
                            args + " >/dev/null 2>&1";
    const int st = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(st));
    EXPECT_EQ(WEXITSTATUS(st), 2) << args;
  }
  EXPECT_FALSE(fs::exists(dir_ / "x.vcd"));
}

// Two outputs on one path would overwrite each other: refused before anything is written.
TEST_F(SimModes, TwoOutputsOnOnePathAreRefused) {
  const std::string vec = quote((kTraces / "phong_basic.vec").string());
  for (const char* args : {" --dump o.txt --report o.txt", " --report ./o.txt --vcd o.txt",
                           " --vcd w.vcd --dump w.gtkw", " --dump sub/../o.txt --report o.txt"}) {
    fs::create_directories(dir_ / "sub");
    const std::string cmd = "cd " + quote(dir_.string()) + " && " + quote(kGlint) + " sim " + vec +
                            args + " >/dev/null 2>err.txt";
    const int st = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(st));
    EXPECT_EQ(WEXITSTATUS(st), 2) << args;
    std::ifstream err(dir_ / "err.txt");
    const std::string msg((std::istreambuf_iterator<char>(err)), std::istreambuf_iterator<char>());
    EXPECT_NE(msg.find("name the same file"), std::string::npos) << args << ": " << msg;
    EXPECT_FALSE(fs::exists(dir_ / "o.txt")) << args;
    EXPECT_FALSE(fs::exists(dir_ / "w.vcd")) << args;
  }
}

TEST_F(SimModes, OutputsThatAreNotRegularFilesAreRefused) {
  // Writing through a temporary file and a rename would replace a FIFO or device: refuse instead.
  const fs::path fifo = dir_ / "fifo";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  const std::string vec = quote((kTraces / "phong_basic.vec").string());
  for (const char* opt : {" --dump ", " --report ", " --vcd "}) {
    const std::string cmd =
        quote(kGlint) + " sim " + vec + opt + quote(fifo.string()) + " >/dev/null 2>&1";
    const int st = std::system(cmd.c_str());
    ASSERT_TRUE(WIFEXITED(st));
    EXPECT_EQ(WEXITSTATUS(st), 2) << opt;
    EXPECT_TRUE(fs::is_fifo(fifo)) << opt;
  }
}

TEST_F(SimModes, RegressReportsEveryDifferingField) {
  // A golden with a wrong cycle count and a float statistic beyond tolerance: exit 1 and one
  // readable line per field; the untouched golden passes.
  fs::create_directories(dir_ / "golden");
  fs::copy_file(kTraces / "phong_basic.vec", dir_ / "phong_basic.vec");
  fs::copy_file(kTraces / "golden" / "phong_basic.json", dir_ / "golden" / "phong_basic.json");
  EXPECT_NE(run("regress --traces " + quote(dir_.string())).find("1 traces checked, 0 failed"),
            std::string::npos);
  json g = json::parse(read_file(dir_ / "golden" / "phong_basic.json"));
  g["report"]["units"][0]["cycles"] = g["report"]["units"][0]["cycles"].get<int>() + 1;
  g["report"]["units"][1]["errors"]["rms"] =
      g["report"]["units"][1]["errors"]["rms"].get<double>() * 1.001;
  std::ofstream(dir_ / "golden" / "phong_basic.json") << g.dump(2);
  const std::string cmd = quote(kGlint) + " regress --traces " + quote(dir_.string()) + " >" +
                          quote((dir_ / "out.txt").string()) + " 2>&1";
  const int st = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(st));
  EXPECT_EQ(WEXITSTATUS(st), 1);
  const std::string out = read_file(dir_ / "out.txt");
  const std::string u0 = g["report"]["units"][0]["unit"], u1 = g["report"]["units"][1]["unit"];
  EXPECT_NE(out.find(u0 + ".cycles"), std::string::npos) << out;
  EXPECT_NE(out.find(u1 + ".errors.rms"), std::string::npos) << out;
  EXPECT_NE(out.find("2 differences"), std::string::npos) << out;
}

// The dump's material, light, x and y columns name the request each result belongs to: read from
// the vector file here, independently of glint's reader (light 0 and x = y = -1 when the file has
// no such column). Both modes write the same rows (FastAndClockedAgree*), so fast mode suffices.
TEST_F(SimModes, DumpNamesEachResultsMaterialLightAndPixel) {
  for (const auto& t : shipped_traces()) {
    SCOPED_TRACE(t.string());
    // source line -> {material, light, x, y}
    std::map<std::string, std::vector<std::string>> rows;
    std::vector<std::string> columns;
    bool data = false;
    std::ifstream in(t);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
      line = line.substr(0, line.find('#'));
      if (data) std::replace(line.begin(), line.end(), ',', ' ');  // fields: blanks or one comma
      std::istringstream words(line);
      std::vector<std::string> w;
      for (std::string x; words >> x;) w.push_back(x);
      if (w.empty()) continue;
      if (!data) {
        if (w[0] == "columns") columns.assign(w.begin() + 1, w.end());
        data = w[0] == "data";
        continue;
      }
      std::map<std::string, std::string> f = {{"light", "0"}, {"x", "-1"}, {"y", "-1"}};
      for (std::size_t i = 0; i < columns.size() && i < w.size(); ++i) f[columns[i]] = w[i];
      rows[std::to_string(n)] = {f["material"], f["light"], f["x"], f["y"]};
    }
    ASSERT_FALSE(rows.empty());
    const fs::path csv = dir_ / "sim.csv";
    run("sim " + quote(t.string()) + " --dump " + quote(csv.string()));
    std::istringstream dump(read_file(csv));
    std::getline(dump, line);
    std::vector<std::string> header;
    {
      std::stringstream ss(line);
      for (std::string x; std::getline(ss, x, ',');) header.push_back(x);
    }
    auto col = [&](const char* name) {
      return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) -
                                      header.begin());
    };
    const std::size_t c_line = col("line"), c_mat = col("material"), c_light = col("light"),
                      c_x = col("x"), c_y = col("y");
    ASSERT_LT(std::max({c_line, c_mat, c_light, c_x, c_y}), header.size()) << line;
    std::size_t checked = 0, bad = 0;
    while (std::getline(dump, line)) {
      std::vector<std::string> f;
      std::stringstream ss(line);
      for (std::string x; std::getline(ss, x, ',');) f.push_back(x);
      ASSERT_EQ(f.size(), header.size()) << line;
      const auto it = rows.find(f[c_line]);
      const bool ok = it != rows.end() &&
                      it->second == std::vector<std::string>{f[c_mat], f[c_light], f[c_x], f[c_y]};
      if (!ok && ++bad <= 5) ADD_FAILURE() << "dump row: " << line;
      ++checked;
    }
    EXPECT_EQ(bad, 0u);
    EXPECT_EQ(checked, rows.size() * 5);  // default: all five units
  }
}

}  // namespace
