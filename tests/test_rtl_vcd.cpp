// VCD output of the clocked mode: scopes and signals (parsed from the $scope/$var header), widths
// of the raw fixed-point values, the GTKWave save file, conversion by vcd2fst, the vector window,
// and that a failed run leaves no file behind. One elaboration per TEST.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "clocked_sim.h"
#include "evaluate.h"
#include "input_error.h"
#include "rtl_common.h"
#include "timing.h"
#include "unit_common.h"
#include "units.h"

namespace fs = std::filesystem;

namespace glint {
namespace {

class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::path(GLINT_BINARY_DIR) / "test_rtl_tmp" /
            (std::string(info->test_suite_name()) + "." + info->name() + "." +
             std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path_, ec);
  }
  std::string file(const std::string& name) const { return (path_ / name).string(); }
  std::set<std::string> entries() const {
    std::set<std::string> out;
    for (const auto& e : fs::directory_iterator(path_)) out.insert(e.path().filename());
    return out;
  }

 private:
  fs::path path_;
};

struct Stream {
  VectorHeader header;
  std::vector<VectorRow> rows;
};

Stream make_stream(std::size_t n, bool coloured) {
  Stream s;
  s.header.eps = 1e-3;
  s.header.lights = 1;
  VectorMaterial m;
  m.name = "gold";
  m.specular = coloured ? std::array<double, 3>{1, 0.766, 0.336} : std::array<double, 3>{1, 1, 1};
  m.shininess = 64;
  m.lobe = Lobe::kBlinn;
  s.header.materials.push_back(m);
  m.name = "plastic";
  m.specular = {0.5, 0.5, 0.5};
  m.shininess = 8;
  s.header.materials.push_back(m);
  std::mt19937_64 rng(42);
  std::uniform_real_distribution<double> t(-0.2, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    VectorRow r;
    r.t = t(rng);
    r.material = static_cast<std::uint32_t>(rng() % 2);
    r.line = i + 1;
    s.rows.push_back(r);
  }
  return s;
}

// $scope / $var of a VCD: full dotted name -> width, and the time stamps.
struct VcdInfo {
  std::map<std::string, int> vars;
  std::vector<std::uint64_t> times;
  std::uint64_t value_changes = 0;
};

VcdInfo parse_vcd(const std::string& path) {
  VcdInfo info;
  std::ifstream in(path);
  std::string line;
  std::vector<std::string> scope;
  bool header = true;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::string tok;
    ls >> tok;
    if (header) {
      if (tok == "$scope") {
        std::string kind, name;
        ls >> kind >> name;
        scope.push_back(name);
      } else if (tok == "$upscope") {
        scope.pop_back();
      } else if (tok == "$var") {
        std::string type, id, name;
        int width = 0;
        ls >> type >> width >> id >> name;
        std::string full;
        for (const std::string& s : scope) full += s + ".";
        info.vars[full + name] = width;
      } else if (tok == "$enddefinitions") {
        header = false;
      }
    } else if (!tok.empty() && tok[0] == '#') {
      info.times.push_back(std::stoull(tok.substr(1)));
    } else if (!tok.empty() && tok[0] != '$') {
      ++info.value_changes;
    }
  }
  return info;
}

const char* kVcd2Fst = "/usr/bin/vcd2fst";

TEST(RtlVcd, ScopesSignalsWidthsGtkwAndFst) {
  TempDir dir;
  const Stream s = make_stream(300, true);
  const SlotMap slots = make_slots(s.header);
  const std::vector<std::string> specs = {"hast",
                                          "hast:d=3",
                                          "horner:degree=3",
                                          "schlick:divider=iterative,out=uq1.11",
                                          "lut:in=uq1.11,out=sq2.14",
                                          "pow"};
  std::vector<std::unique_ptr<SpecularUnit>> owned;
  std::vector<const SpecularUnit*> units;
  for (const std::string& sp : specs) {
    owned.push_back(make_unit(parse_unit_spec(sp), slots.params));
    units.push_back(owned.back().get());
  }
  ClockedOptions options;
  options.vcd_path = dir.file("run.vcd");
  options.sink = SinkReady{0.8, 5};
  options.colour_stage = stream_is_coloured(s.header);
  ASSERT_TRUE(options.colour_stage);
  ClockedRunInfo info;
  std::vector<std::vector<ResultTiming>> timing(units.size());
  const auto stats = run_clocked(
      units, slots, [&] { return std::make_unique<MemoryRowStream>(s.rows); }, options,
      [&](const LaneOutput& o) { timing[o.lane].push_back(o.timing); }, &info);

  // Tracing changes nothing: the timing is still TimingEngine's.
  for (std::size_t u = 0; u < units.size(); ++u) {
    TimingEngine engine(clocked_timing(*units[u], true), options.sink);
    ASSERT_EQ(timing[u].size(), s.rows.size());
    for (std::size_t i = 0; i < s.rows.size(); ++i) {
      const std::int64_t t = quantize_input(s.rows[i].t, units[u]->in_format());
      const ResultTiming want = engine.next(units[u]->skip(slots.slot(s.rows[i]), t));
      ASSERT_EQ(timing[u][i].retire, want.retire) << specs[u] << " row " << i;
    }
    EXPECT_EQ(stats[u].cycles, engine.stats().cycles);
  }

  EXPECT_EQ(info.labels,
            (std::vector<std::string>{"hast_1", "hast_2", "horner", "schlick", "lut", "pow"}));
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"run.vcd", "run.gtkw"}));
  EXPECT_EQ(info.vcd_path, dir.file("run.vcd"));
  EXPECT_EQ(info.gtkw_path, dir.file("run.gtkw"));

  const VcdInfo vcd = parse_vcd(dir.file("run.vcd"));
  auto expect_var = [&](const std::string& name, int width) {
    const auto it = vcd.vars.find("SystemC.top." + name);
    if (it == vcd.vars.end()) {
      ADD_FAILURE() << "missing VCD variable top." << name;
    } else {
      EXPECT_EQ(it->second, width) << name;
    }
  };
  expect_var("clk", 1);
  expect_var("cycle", 32);
  const std::map<std::string, std::vector<std::string>> stages = {
      {"hast_1", {"in", "scale", "mul1", "mul2", "mul3"}},
      {"hast_2", {"in", "scale", "mul1", "mul2"}},
      {"horner", {"in", "scale", "mac1", "mac2", "mac3"}},
      {"schlick", {"in", "mac", "div", "round"}},
      {"lut", {"in", "lookup", "interp"}},
      {"pow", {"in", "log_table", "log_interp", "mul_n", "exp_table", "exp_interp"}},
  };
  for (std::size_t u = 0; u < units.size(); ++u) {
    const std::string l = info.labels[u];
    const int tw = units[u]->in_format().width(), rw = units[u]->out_format().width();
    SCOPED_TRACE(l);
    for (const char* hs : {"source", "merge", "sink"}) {
      expect_var(l + "." + hs + ".valid", 1);
      expect_var(l + "." + hs + ".ready", 1);
    }
    expect_var(l + ".source.t", tw);
    expect_var(l + ".comparator.tau", tw + 1);
    expect_var(l + ".comparator.compute_valid", 1);
    expect_var(l + ".comparator.compute_ready", 1);
    expect_var(l + ".bypass.valid", 1);
    expect_var(l + ".bypass.result", rw);
    expect_var(l + ".in.ready", 1);
    const auto& st = stages.at(l);
    for (const std::string& stage : st) {
      expect_var(l + "." + stage + ".valid", 1);
      expect_var(l + "." + stage + ".t", tw);
    }
    expect_var(l + "." + st.back() + ".result", rw);
    expect_var(l + ".colour.valid", 1);
    expect_var(l + ".colour.result", rw);
    expect_var(l + ".merge.result", rw);
    expect_var(l + ".sink.result", rw);
  }
  expect_var("schlick.div.bit", 4);  // out uq1.11: q = 13 iterations, 0..12
  EXPECT_EQ(vcd.vars.size(), info.traced.size());
  // Two time steps per cycle (rising and falling edge), from time 0 to the end of the run.
  ASSERT_FALSE(vcd.times.empty());
  std::uint64_t max_cycles = 0;
  for (const auto& st : stats) max_cycles = std::max(max_cycles, st.cycles);
  EXPECT_GE(vcd.times.back(), rtl::cycle_time_ns(max_cycles - 1));
  EXPECT_GT(vcd.value_changes, 10 * max_cycles);

  // GTKWave save file: the dump, one group per unit, every traced signal.
  std::ifstream g(dir.file("run.gtkw"));
  std::stringstream gs;
  gs << g.rdbuf();
  const std::string gtkw = gs.str();
  EXPECT_NE(gtkw.find("[dumpfile] \"" + fs::absolute(dir.file("run.vcd")).string() + "\""),
            std::string::npos);
  EXPECT_NE(gtkw.find("[timestart] 0\n"), std::string::npos);
  for (const std::string& l : info.labels) {
    EXPECT_NE(gtkw.find("@800200\n-" + l + "\n"), std::string::npos) << l;
    EXPECT_NE(gtkw.find("@1000200\n-" + l + "\n"), std::string::npos) << l;
  }
  EXPECT_NE(gtkw.find("SystemC.top.hast_1.in.t[15:0]\n"), std::string::npos);
  EXPECT_NE(gtkw.find("@424\nSystemC.top.lut.bypass.result[15:0]\n"), std::string::npos);
  EXPECT_NE(gtkw.find("@28\nSystemC.top.clk\n"), std::string::npos);

  if (::access(kVcd2Fst, X_OK) != 0) GTEST_SKIP() << kVcd2Fst << " not installed (gtkwave)";
  const std::string fst = dir.file("run.fst");
  const std::string cmd =
      std::string(kVcd2Fst) + " -v '" + dir.file("run.vcd") + "' -f '" + fst + "' > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(rc)) << cmd;
  EXPECT_EQ(WEXITSTATUS(rc), 0) << cmd;
  EXPECT_GT(fs::file_size(fst), 0u);
}

TEST(RtlVcd, WindowTracesFromFirstPresentedToLastRetired) {
  TempDir dir;
  const Stream s = make_stream(400, false);
  const SlotMap slots = make_slots(s.header);
  const auto unit = make_unit(parse_unit_spec("schlick:divider=iterative,buffer=4"), slots.params);
  ClockedOptions options;
  options.vcd_path = dir.file("w.vcd");
  options.vcd_first = 100;
  options.vcd_last = 120;
  options.sink = SinkReady{0.6, 9};
  ClockedRunInfo info;
  std::vector<ResultTiming> timing;
  run_clocked(
      {unit.get()}, slots, [&] { return std::make_unique<MemoryRowStream>(s.rows); }, options,
      [&](const LaneOutput& o) { timing.push_back(o.timing); }, &info);
  ASSERT_EQ(timing.size(), s.rows.size());
  // Vector 100 is presented at the issue edge of vector 99; the window closes one cycle after the
  // retire of vector 120.
  const std::uint64_t open_ns = rtl::cycle_time_ns(timing[99].issue);
  EXPECT_EQ(info.vcd_start_ns, open_ns);
  const VcdInfo vcd = parse_vcd(dir.file("w.vcd"));
  ASSERT_GE(vcd.times.size(), 2u);
  EXPECT_GT(vcd.times.front(), open_ns);  // the first change after the initial dump at open_ns
  EXPECT_LE(vcd.times.back(), rtl::cycle_time_ns(timing[120].retire + 1));
  EXPECT_GE(vcd.times.back(), rtl::cycle_time_ns(timing[120].retire));
  std::ifstream g(dir.file("w.gtkw"));
  std::stringstream gs;
  gs << g.rdbuf();
  EXPECT_NE(gs.str().find("[timestart] " + std::to_string(open_ns) + "\n"), std::string::npos);
}

TEST(RtlVcd, WindowBeyondTheStreamStillWritesTheFinalState) {
  TempDir dir;
  const Stream s = make_stream(30, false);
  const SlotMap slots = make_slots(s.header);
  const auto unit = make_unit(parse_unit_spec("lut"), slots.params);
  ClockedOptions options;
  options.vcd_path = dir.file("late.vcd");
  options.vcd_first = 1000;
  ClockedRunInfo info;
  const auto stats = run_clocked(
      {unit.get()}, slots, [&] { return std::make_unique<MemoryRowStream>(s.rows); }, options, {},
      &info);
  EXPECT_EQ(info.vcd_start_ns, rtl::cycle_time_ns(stats[0].cycles));
  const VcdInfo vcd = parse_vcd(dir.file("late.vcd"));
  EXPECT_EQ(vcd.vars.size(), info.traced.size());
  EXPECT_FALSE(vcd.times.empty());
  EXPECT_EQ(dir.entries(), (std::set<std::string>{"late.vcd", "late.gtkw"}));
}

// A stream that fails mid-way: the error surfaces from run_clocked unchanged and no VCD (nor
// temporary) is left behind.
class FailingStream : public RowStream {
 public:
  explicit FailingStream(const std::vector<VectorRow>& rows) : rows_(rows) {}
  bool next(VectorRow& row) override {
    if (i_ == 50) throw InputError("mem.vec", 51, "t", "bad row");
    row = rows_[i_++];
    return true;
  }

 private:
  const std::vector<VectorRow>& rows_;
  std::size_t i_ = 0;
};

TEST(RtlVcd, FailedRunLeavesNoFiles) {
  TempDir dir;
  const Stream s = make_stream(100, false);
  const SlotMap slots = make_slots(s.header);
  const auto unit = make_unit(parse_unit_spec("hast"), slots.params);
  ClockedOptions options;
  options.vcd_path = dir.file("f.vcd");
  EXPECT_THROW(run_clocked({unit.get()}, slots,
                           [&] { return std::make_unique<FailingStream>(s.rows); }, options, {}),
               InputError);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(RtlVcd, UnwritablePathAndSecondRunAreRejected) {
  const Stream s = make_stream(20, false);
  const SlotMap slots = make_slots(s.header);
  const auto unit = make_unit(parse_unit_spec("lut"), slots.params);
  auto open = [&] { return std::make_unique<MemoryRowStream>(s.rows); };
  ClockedOptions bad;
  bad.vcd_path = "/nonexistent-dir/x.vcd";
  EXPECT_THROW(run_clocked({unit.get()}, slots, open, bad, {}), std::runtime_error);
  ClockedOptions window;
  window.vcd_first = 5;
  window.vcd_last = 4;
  EXPECT_THROW(run_clocked({unit.get()}, slots, open, window, {}), std::invalid_argument);
  // The first real run elaborates; SystemC cannot elaborate again in this process.
  EXPECT_EQ(run_clocked({unit.get()}, slots, open, ClockedOptions{}, {})[0].results, 20u);
  EXPECT_THROW(run_clocked({unit.get()}, slots, open, ClockedOptions{}, {}), std::logic_error);
}

}  // namespace
}  // namespace glint
