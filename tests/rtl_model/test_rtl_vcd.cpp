// VCD output of the clocked mode: scopes and signals (parsed from the $scope/$var header), widths
// of the raw fixed-point values, the values cycle by cycle (clock, cycle counter, retired results),
// the GTKWave save file (view, stage-qualified aliases, fixed-point display, analog waves), FST
// output through vcd2fst (read back with fst2vcd), the vector window, and that a failed run leaves
// no file behind; and VcdWriter on its own (exact text, random values read back, a pipe whose
// reader is gone). One elaboration per TEST.
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <csignal>
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

#include "eval/evaluate.h"
#include "io/atomic_file.h"
#include "io/input_error.h"
#include "io/vcd_writer.h"
#include "rtl_model/clocked_sim.h"
#include "rtl_model/rtl_common.h"
#include "rtl_model/vcd_trace.h"
#include "test_support.h"
#include "timing/timing.h"
#include "units/catalogue.h"
#include "units/common.h"
#include "vcd_reader.h"

namespace fs = std::filesystem;

namespace glint {
namespace {

using glint::test::TempDir;

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

// One traced clocked run of `specs` over a stream: the units, the run's diagnostics, and per lane
// every result's timing and raw value in stream order.
struct TracedRun {
  std::vector<std::unique_ptr<SpecularUnit>> owned;
  std::vector<const SpecularUnit*> units;
  ClockedRunInfo info;
  std::vector<std::vector<ResultTiming>> timing;
  std::vector<std::vector<std::int64_t>> out_raw;
  std::vector<TimingStats> stats;

  TracedRun(const Stream& s, const SlotMap& slots, const std::vector<std::string>& specs,
            const ClockedOptions& options) {
    for (const std::string& sp : specs) {
      owned.push_back(make_unit(parse_unit_spec(sp), slots));
      units.push_back(owned.back().get());
    }
    timing.resize(units.size());
    out_raw.resize(units.size());
    stats = run_clocked(
        units, slots, [&] { return std::make_unique<MemoryRowStream>(s.rows); }, options,
        [&](const LaneOutput& o) {
          timing[o.lane].push_back(o.timing);
          out_raw[o.lane].push_back(o.out_raw);
        },
        &info);
  }
};

using VcdInfo = test::VcdReader;
VcdInfo parse_vcd(const std::string& path) {
  return VcdInfo(path);
}

const char* kVcd2Fst = "/usr/bin/vcd2fst";
const char* kFst2Vcd = "/usr/bin/fst2vcd";

// The traces of a GTKWave save file as GTKWave reads them: the flags ("@hex") and the fixed-point
// shift ("[fpshift_count] N") carry over to every following trace, a colour ("[color] N") applies
// to the next trace only; "+{alias} name" is a trace shown under `alias`, "-text" a blank row
// (group begin/end, comment, analog height extension).
struct GtkwTrace {
  std::uint64_t flags = 0;
  int fpshift = 0;
  int colour = 0;
  bool blank = false;
  std::string alias;  // or the blank row's text
  std::string name;   // the dump's signal, e.g. "SystemC.top.hast.in.t[15:0]"
};

struct Gtkw {
  std::map<std::string, std::string> directives;  // "[name] value" lines, and "*" -> zoom line
  std::vector<GtkwTrace> traces;

  const GtkwTrace* find(const std::string& alias, bool blank = false) const {
    for (const GtkwTrace& t : traces)
      if (t.alias == alias && t.blank == blank) return &t;
    return nullptr;
  }
  std::size_t index(const GtkwTrace* t) const { return static_cast<std::size_t>(t - &traces[0]); }
};

Gtkw parse_gtkw(const std::string& text) {
  Gtkw g;
  std::istringstream in(text);
  std::string line;
  std::uint64_t flags = 0;
  int fpshift = 0, colour = 0;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    if (line[0] == '@') {
      flags = std::stoull(line.substr(1), nullptr, 16);
    } else if (line[0] == '*') {
      g.directives["*"] = line.substr(1);
    } else if (line[0] == '[') {
      const auto close = line.find(']');
      const std::string key = line.substr(1, close - 1);
      const std::string value = close + 2 <= line.size() ? line.substr(close + 2) : "";
      if (key == "fpshift_count") {
        fpshift = std::stoi(value);
      } else if (key == "color") {
        colour = std::stoi(value);
      } else if (key != "*") {
        g.directives[key] = value;
      }
    } else if (line[0] == '-') {
      g.traces.push_back({flags, fpshift, 0, true, line.substr(1), ""});
    } else {
      GtkwTrace t{flags, fpshift, colour, false, "", line};
      if (line.rfind("+{", 0) == 0) {
        const auto close = line.find("} ");
        t.alias = line.substr(2, close - 2);
        t.name = line.substr(close + 2);
      }
      g.traces.push_back(t);
      colour = 0;
    }
  }
  return g;
}

// GTKWave trace flags (analyzer.h).
constexpr std::uint64_t kGtkwDec = 0x4, kGtkwBin = 0x8, kGtkwBlank = 0x200, kGtkwSigned = 0x400,
                        kGtkwAnalogStep = 0x8000, kGtkwAnalogExtend = 0x20000,
                        kGtkwClosed = 0x400000, kGtkwGroupBegin = 0x800000,
                        kGtkwGroupEnd = 0x1000000, kGtkwFixedPoint = 0x40000000;

// What GTKWave shows for a trace: the fixed-point shift applies only with its flag.
double shown_value(const GtkwTrace& t, std::int64_t raw) {
  const int shift = (t.flags & kGtkwFixedPoint) ? t.fpshift : 0;
  return std::ldexp(static_cast<double>(raw), -shift);
}

// A fixed-point signal as a stage-qualified trace: real values (decimal, shifted by its fraction
// bits, signed if its format is), and its raw bits in the unit's closed "raw" subgroup.
void expect_fixed_point(const Gtkw& g, const std::string& alias, const std::string& name,
                        const QFormat& format) {
  SCOPED_TRACE(alias);
  const GtkwTrace* t = g.find(alias);
  ASSERT_NE(t, nullptr);
  EXPECT_EQ(t->name, "SystemC.top." + name + "[" + std::to_string(format.width() - 1) + ":0]");
  EXPECT_TRUE(t->flags & kGtkwFixedPoint);
  EXPECT_TRUE(t->flags & kGtkwDec);
  EXPECT_EQ((t->flags & kGtkwSigned) != 0, format.is_signed);
  EXPECT_EQ(t->fpshift, format.frac_bits);
  const GtkwTrace* raw =
      g.find(alias + "[" + std::to_string(format.width() - 1) + ":0] " + format.name());
  ASSERT_NE(raw, nullptr);
  EXPECT_EQ(raw->name, t->name);
  EXPECT_FALSE(raw->flags & kGtkwFixedPoint);
  EXPECT_TRUE(raw->flags & kGtkwDec);
}

std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs `cmd` through the shell; true when it exited with status 0.
bool run_ok(const std::string& cmd) {
  const int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) && WEXITSTATUS(rc) == 0;
}

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
  ClockedOptions options;
  options.vcd_path = dir.file("run.vcd");
  options.sink = SinkReady{0.8, 5};
  const TracedRun run(s, slots, specs, options);
  const auto& [owned, units, info, timing, out_raw, stats] = run;

  // Tracing changes nothing: the timing is still TimingEngine's.
  for (std::size_t u = 0; u < units.size(); ++u) {
    TimingEngine engine(units[u]->timing(), options.sink);
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
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"run.gtkw", "run.vcd"}));
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
    // No colour stage: the lane the RTL writes.
    EXPECT_EQ(vcd.vars.count("SystemC.top." + l + ".colour.valid"), 0u);
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

  // The values are those of each cycle: the initial dump at time 0 (the reset state), the clock
  // rising at every cycle's time and falling halfway, the cycle counter counting the edges, and
  // each lane's sink showing exactly its retired results, at their retire cycles.
  EXPECT_FALSE(vcd.dumpvars_before_first_time);
  EXPECT_EQ(vcd.times.front(), 0u);
  EXPECT_EQ(vcd.value_at("SystemC.top.clk", 0), 0u);
  for (std::uint64_t c = 0; c < max_cycles; ++c) {
    ASSERT_EQ(vcd.value_at("SystemC.top.clk", rtl::cycle_time_ns(c)), 1u) << c;
    ASSERT_EQ(vcd.value_at("SystemC.top.clk", rtl::fall_time_ns(c)), 0u) << c;
    ASSERT_EQ(vcd.value_at("SystemC.top.cycle", rtl::cycle_time_ns(c)), c);
  }
  for (std::size_t u = 0; u < units.size(); ++u) {
    std::map<std::uint64_t, std::uint64_t> retired;  // retire cycle -> raw result bits
    const int rw = units[u]->out_format().width();
    for (std::size_t i = 0; i < timing[u].size(); ++i)
      retired[timing[u][i].retire] =
          static_cast<std::uint64_t>(out_raw[u][i]) & ((std::uint64_t{1} << rw) - 1);
    const std::string p = "SystemC.top." + info.labels[u] + ".sink.";
    for (std::uint64_t c = 0; c < max_cycles; ++c) {
      const auto it = retired.find(c);
      const std::uint64_t t = rtl::cycle_time_ns(c);
      ASSERT_EQ(vcd.value_at(p + "valid", t), it != retired.end() ? 1u : 0u)
          << info.labels[u] << " cycle " << c;
      if (it != retired.end()) {
        ASSERT_EQ(vcd.value_at(p + "result", t), it->second) << info.labels[u] << " cycle " << c;
      }
    }
  }

  // GTKWave save file: the dump, one group per unit, every traced signal.
  const std::string gtkw = read_text(dir.file("run.gtkw"));
  EXPECT_NE(gtkw.find("[dumpfile] \"" + fs::absolute(dir.file("run.vcd")).string() + "\""),
            std::string::npos);
  EXPECT_NE(gtkw.find("[timestart] 0\n"), std::string::npos);
  for (const std::string& l : info.labels) {
    EXPECT_NE(gtkw.find("@800200\n-" + l + "\n"), std::string::npos) << l;
    EXPECT_NE(gtkw.find("@1000200\n-" + l + "\n"), std::string::npos) << l;
  }
  EXPECT_NE(gtkw.find("SystemC.top.hast_1.in.t[15:0]\n"), std::string::npos);
  // Since the names became stage-qualified aliases and fixed-point values real numbers, the
  // traces read "@40000424 / [fpshift_count] 14 / +{lut/bypass/result} SystemC.top..." and
  // "+{clk} SystemC.top.clk" (were "@424 / SystemC.top.lut.bypass.result[15:0]", "@28 /
  // SystemC.top.clk"): checked on the parsed save file.
  const Gtkw g = parse_gtkw(gtkw);
  const GtkwTrace* clk = g.find("clk");
  ASSERT_NE(clk, nullptr);
  EXPECT_EQ(clk->name, "SystemC.top.clk");
  EXPECT_EQ(clk->flags, 0x28u);  // binary, right-justified
  expect_fixed_point(g, "lut/bypass/result", "lut.bypass.result", sq(2, 14));

  // Every traced signal is shown once under its stage-qualified alias: the name below "top." with
  // '/' for '.', which GTKWave's hier_max_level does not cut down.
  std::map<std::string, int> shown;
  for (const GtkwTrace& t : g.traces) {
    if (t.blank) continue;
    ASSERT_EQ(t.name.rfind("SystemC.top.", 0), 0u) << t.name;
    ASSERT_FALSE(t.alias.empty()) << t.name;
    if (t.alias.find(' ') != std::string::npos) continue;  // a raw twin: "<alias>[msb:0] <format>"
    std::string want = t.name.substr(std::string("SystemC.top.").size());
    want = want.substr(0, want.find('['));
    std::replace(want.begin(), want.end(), '.', '/');
    EXPECT_EQ(t.alias, want);
    if (!(t.flags & kGtkwAnalogStep)) ++shown[t.name.substr(8, t.name.find('[') - 8)];
  }
  for (const std::string& name : info.traced) EXPECT_EQ(shown[name], 1) << name;
  EXPECT_EQ(shown.size(), info.traced.size());

  // Fixed-point signals as real numbers, raw bits beside them; integers and flags as before.
  for (std::size_t u = 0; u < units.size(); ++u) {
    const std::string l = info.labels[u];
    const QFormat in = units[u]->in_format(), out = units[u]->out_format();
    const QFormat tau{in.int_bits + 1, in.frac_bits, true};  // input width + 1, signed
    expect_fixed_point(g, l + "/source/t", l + ".source.t", in);
    expect_fixed_point(g, l + "/comparator/tau", l + ".comparator.tau", tau);
    expect_fixed_point(g, l + "/bypass/t", l + ".bypass.t", in);
    for (const char* r : {"bypass", "merge", "sink"})
      expect_fixed_point(g, l + "/" + r + "/result", l + "." + r + ".result", out);
    for (const char* i : {"/source/seq", "/comparator/credits", "/merge/count"}) {
      const GtkwTrace* t = g.find(l + i);
      ASSERT_NE(t, nullptr) << l + i;
      EXPECT_EQ(t->flags & (kGtkwFixedPoint | kGtkwDec | kGtkwSigned), kGtkwDec) << l + i;
    }
    const GtkwTrace* v = g.find(l + "/source/valid");
    ASSERT_NE(v, nullptr);
    EXPECT_TRUE(v->flags & kGtkwBin);

    // The group: analog t and result first (step waves four rows high), then the signals, then
    // the closed raw subgroup.
    const GtkwTrace* begin = g.find(l, true);
    ASSERT_NE(begin, nullptr) << l;
    const std::size_t b = g.index(begin);
    EXPECT_EQ(begin->flags, kGtkwGroupBegin | kGtkwBlank);
    ASSERT_LT(b + 9, g.traces.size());
    for (std::size_t k : {b + 1, b + 5}) {
      const GtkwTrace& a = g.traces[k];
      EXPECT_EQ(a.alias, l + (k == b + 1 ? "/source/t" : "/sink/result"));
      EXPECT_TRUE(a.flags & kGtkwAnalogStep) << a.alias;
      EXPECT_TRUE(a.flags & kGtkwFixedPoint) << a.alias;
      EXPECT_GT(a.colour, 0) << a.alias;
      for (std::size_t e = k + 1; e < k + 4; ++e) {
        EXPECT_TRUE(g.traces[e].blank);
        EXPECT_EQ(g.traces[e].flags, kGtkwAnalogExtend);
      }
    }
    const GtkwTrace* raw = g.find(l + " raw", true);
    ASSERT_NE(raw, nullptr) << l;
    EXPECT_EQ(raw->flags, kGtkwGroupBegin | kGtkwBlank | kGtkwClosed);
    EXPECT_GT(g.index(raw), b);
  }

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
  const auto unit = make_unit(parse_unit_spec("schlick:divider=iterative,buffer=4"), slots);
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
  EXPECT_FALSE(vcd.dumpvars_before_first_time);
  EXPECT_EQ(vcd.times.front(), open_ns);  // the initial dump, at the opening time
  EXPECT_GT(vcd.times[1], open_ns);
  EXPECT_EQ(vcd.value_at("SystemC.top.schlick.source.seq", open_ns), 100u);
  EXPECT_EQ(vcd.value_at("SystemC.top.clk", open_ns), 1u);
  EXPECT_EQ(vcd.value_at("SystemC.top.schlick.sink.valid", rtl::cycle_time_ns(timing[120].retire)),
            1u);
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
  const auto unit = make_unit(parse_unit_spec("lut"), slots);
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
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"late.gtkw", "late.vcd"}));
}

// The save file's view and traces for a known set of signals (no elaboration): the view opens on
// about 40 clock periods from the window's start with the marker on its first rising edge, every
// name stage-qualified, fixed-point values shown as reals (t = 30032 in uq1.15 shows 0.9165), the
// unit's t and result as analog waves.
TEST(RtlVcdGtkw, ViewNamesFixedPointAndAnalog) {
  const std::vector<rtl::TracedSignal> signals = {
      {"top.clk", 1, false, 0},
      {"top.cycle", 32, false, 0},
      {"top.hast.source.valid", 1, false, 0},
      {"top.hast.source.t", 16, false, 15},
      {"top.hast.source.seq", 32, false, 0},
      {"top.hast.comparator.tau", 17, true, 15},
      {"top.hast.mul2.t", 16, false, 15},
      {"top.hast.mul2.power", 20, false, 19},
      {"top.hast.sink.result", 16, false, 15},
      {"top.horner.source.t", 12, false, 11},
      {"top.horner.mac1.acc", 27, true, 22},
      {"top.horner.mac1.u", 23, false, 22},
      {"top.horner.sink.result", 16, true, 14},
  };
  for (const std::uint64_t start : {std::uint64_t{0}, rtl::cycle_time_ns(934)}) {
    SCOPED_TRACE(start);
    const Gtkw g = parse_gtkw(rtl::gtkw_text("/x/run.fst", start, signals));
    EXPECT_EQ(g.directives.at("dumpfile"), "\"/x/run.fst\"");
    EXPECT_EQ(g.directives.at("timestart"), std::to_string(start));

    // "*zoom marker": GTKWave spans 2^-zoom ns with 200 pixels; the wave pane is the window
    // less the two left panes and ~24 pixels of borders (measured).
    std::istringstream zl(g.directives.at("*"));
    double zoom = 0;
    std::uint64_t marker = 0;
    zl >> zoom >> marker;
    ASSERT_TRUE(zl) << g.directives.at("*");
    std::istringstream size(g.directives.at("size"));
    int width = 0;
    size >> width;
    const int pane = width - std::stoi(g.directives.at("sst_width")) -
                     std::stoi(g.directives.at("signals_width")) - 24;
    const double span_ns = std::pow(2.0, -zoom) / 200.0 * pane;
    const double period = static_cast<double>(rtl::cycle_time_ns(1) - rtl::cycle_time_ns(0));
    EXPECT_NEAR(span_ns / period, rtl::kGtkwViewCycles, 1.0);
    EXPECT_EQ(rtl::kGtkwViewCycles, 40);
    EXPECT_EQ(marker, start == 0 ? rtl::cycle_time_ns(0) : start);  // the first rising edge

    // Qualified names and formats.
    const GtkwTrace* power = g.find("hast/mul2/power");
    ASSERT_NE(power, nullptr);
    EXPECT_EQ(power->name, "SystemC.top.hast.mul2.power[19:0]");
    EXPECT_EQ(power->flags & (kGtkwFixedPoint | kGtkwDec | kGtkwSigned | kGtkwAnalogStep),
              kGtkwFixedPoint | kGtkwDec);
    EXPECT_EQ(power->fpshift, 19);
    const GtkwTrace* t = g.find("hast/mul2/t");
    ASSERT_NE(t, nullptr);
    EXPECT_NEAR(shown_value(*t, 30032), 0.9165, 5e-5);
    EXPECT_EQ(shown_value(*t, 30032), 30032.0 / 32768);
    const GtkwTrace* acc = g.find("horner/mac1/acc");
    ASSERT_NE(acc, nullptr);
    EXPECT_TRUE(acc->flags & kGtkwSigned);
    EXPECT_EQ(shown_value(*acc, -(std::int64_t{3} << 21)), -1.5);
    const GtkwTrace* tau = g.find("hast/comparator/tau");
    ASSERT_NE(tau, nullptr);
    EXPECT_EQ(tau->flags & (kGtkwFixedPoint | kGtkwSigned), kGtkwFixedPoint | kGtkwSigned);
    EXPECT_EQ(tau->fpshift, 15);
    for (const char* integer : {"cycle", "hast/source/seq"}) {
      const GtkwTrace* i = g.find(integer);
      ASSERT_NE(i, nullptr) << integer;
      EXPECT_EQ(i->flags & (kGtkwFixedPoint | kGtkwDec), kGtkwDec) << integer;
      EXPECT_EQ(shown_value(*i, 30032), 30032.0) << integer;
    }
    const GtkwTrace* valid = g.find("hast/source/valid");
    ASSERT_NE(valid, nullptr);
    EXPECT_EQ(valid->flags & (kGtkwBin | kGtkwFixedPoint), kGtkwBin);
    // Raw bits beside the real values, in each unit's closed raw subgroup.
    const GtkwTrace* raw = g.find("hast/mul2/t[15:0] uq1.15");
    ASSERT_NE(raw, nullptr);
    EXPECT_EQ(shown_value(*raw, 30032), 30032.0);
    EXPECT_NE(g.find("horner/mac1/acc[26:0] sq5.22"), nullptr);
    EXPECT_NE(g.find("horner/sink/result[15:0] sq2.14"), nullptr);
    EXPECT_EQ(g.find("hast/source/seq[31:0] uq32.0"), nullptr);  // integers have no raw twin

    // One group per unit: analog t and result, the signals, the closed raw subgroup.
    for (const char* u : {"hast", "horner"}) {
      const std::string unit = u;
      SCOPED_TRACE(unit);
      const GtkwTrace* begin = g.find(unit, true);
      ASSERT_NE(begin, nullptr);
      const std::size_t b = g.index(begin);
      ASSERT_LT(b + 9, g.traces.size());
      EXPECT_EQ(g.traces[b + 1].alias, unit + "/source/t");
      EXPECT_EQ(g.traces[b + 5].alias, unit + "/sink/result");
      for (std::size_t k : {b + 1, b + 5}) {
        EXPECT_TRUE(g.traces[k].flags & kGtkwAnalogStep);
        EXPECT_TRUE(g.traces[k].flags & kGtkwFixedPoint);
        for (std::size_t e = k + 1; e < k + 4; ++e) {
          EXPECT_TRUE(g.traces[e].blank);
          EXPECT_EQ(g.traces[e].flags, kGtkwAnalogExtend);
        }
      }
      EXPECT_NE(g.traces[b + 1].colour, g.traces[b + 5].colour);
      const GtkwTrace* rb = g.find(unit + " raw", true);
      ASSERT_NE(rb, nullptr);
      EXPECT_EQ(rb->flags, kGtkwGroupBegin | kGtkwBlank | kGtkwClosed);
      // Closed group ends are collapsed (0x1000), as GTKWave writes them.
      std::size_t ends = 0;
      for (const GtkwTrace& x : g.traces) {
        if (x.blank && x.alias == unit + " raw" && (x.flags & kGtkwGroupEnd)) {
          EXPECT_EQ(x.flags, kGtkwGroupEnd | kGtkwBlank | kGtkwClosed | 0x1000);
          ++ends;
        }
        if (x.blank && x.alias == unit && (x.flags & kGtkwGroupEnd)) ++ends;
      }
      EXPECT_EQ(ends, 2u);
    }
  }
}

TEST(RtlVcdGtkw, FstByExtension) {
  EXPECT_TRUE(rtl::is_fst_path("run.fst"));
  EXPECT_TRUE(rtl::is_fst_path("/a.b/run.FST"));
  EXPECT_FALSE(rtl::is_fst_path("run.vcd"));
  EXPECT_FALSE(rtl::is_fst_path("run.fst.vcd"));
  EXPECT_FALSE(rtl::is_fst_path("fst"));
  EXPECT_FALSE(rtl::is_fst_path("/a.fst/run"));
}

// --vcd out.fst: the trace streamed through vcd2fst, the same scopes and values as the VCD (read
// back with fst2vcd), the save file beside it pointing at the FST.
TEST(RtlVcd, FstOutputReadsBackWithTheSameValues) {
  if (::access(kVcd2Fst, X_OK) != 0 || ::access(kFst2Vcd, X_OK) != 0)
    GTEST_SKIP() << "vcd2fst/fst2vcd not installed (gtkwave)";
  TempDir dir;
  const Stream s = make_stream(300, true);
  const SlotMap slots = make_slots(s.header);
  const std::vector<std::string> specs = {"hast", "schlick:divider=iterative,out=uq1.11"};
  ClockedOptions options;
  options.vcd_path = dir.file("run.fst");
  options.sink = SinkReady{0.8, 5};
  const TracedRun run(s, slots, specs, options);
  const auto& [owned, units, info, timing, out_raw, stats] = run;
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"run.fst", "run.gtkw"}));
  EXPECT_TRUE(info.fst);
  EXPECT_EQ(info.vcd_path, dir.file("run.fst"));
  EXPECT_EQ(info.gtkw_path, dir.file("run.gtkw"));
  // FST starts with its header block (type 0, then the block length); not VCD text.
  const std::string fst = read_text(dir.file("run.fst"));
  ASSERT_GT(fst.size(), 16u);
  EXPECT_EQ(fst[0], '\0');
  EXPECT_EQ(fst.find("$enddefinitions"), std::string::npos);

  ASSERT_TRUE(run_ok(std::string(kFst2Vcd) + " -f " + test::shell_quote(dir.file("run.fst")) +
                     " -o " + test::shell_quote(dir.file("back.vcd")) + " > /dev/null 2>&1"));
  const VcdInfo vcd = parse_vcd(dir.file("back.vcd"));
  // Every scope and signal at its width.
  EXPECT_EQ(vcd.vars.size(), info.traced.size());
  for (const std::string& name : info.traced)
    EXPECT_EQ(vcd.vars.count("SystemC." + name), 1u) << name;
  EXPECT_EQ(vcd.vars.at("SystemC.top.hast.source.t"), units[0]->in_format().width());
  EXPECT_EQ(vcd.vars.at("SystemC.top.schlick.div.bit"), 4);
  EXPECT_EQ(vcd.vars.at("SystemC.top.schlick.sink.result"), 12);
  // The values cycle by cycle: clock, cycle counter, each sink's retired results.
  std::uint64_t max_cycles = 0;
  for (const auto& st : stats) max_cycles = std::max(max_cycles, st.cycles);
  EXPECT_EQ(vcd.value_at("SystemC.top.clk", 0), 0u);
  for (std::uint64_t c = 0; c < max_cycles; ++c) {
    ASSERT_EQ(vcd.value_at("SystemC.top.clk", rtl::cycle_time_ns(c)), 1u) << c;
    ASSERT_EQ(vcd.value_at("SystemC.top.clk", rtl::fall_time_ns(c)), 0u) << c;
    ASSERT_EQ(vcd.value_at("SystemC.top.cycle", rtl::cycle_time_ns(c)), c);
  }
  for (std::size_t u = 0; u < units.size(); ++u) {
    const std::string p = "SystemC.top." + info.labels[u] + ".sink.";
    const std::uint64_t mask = (std::uint64_t{1} << units[u]->out_format().width()) - 1;
    std::set<std::uint64_t> retire_cycles;
    for (std::size_t i = 0; i < timing[u].size(); ++i) {
      const std::uint64_t t = rtl::cycle_time_ns(timing[u][i].retire);
      retire_cycles.insert(timing[u][i].retire);
      ASSERT_EQ(vcd.value_at(p + "valid", t), 1u) << info.labels[u] << " " << i;
      ASSERT_EQ(vcd.value_at(p + "result", t), static_cast<std::uint64_t>(out_raw[u][i]) & mask)
          << info.labels[u] << " " << i;
    }
    for (std::uint64_t c = 0; c < max_cycles; ++c) {
      if (!retire_cycles.count(c)) {
        ASSERT_EQ(vcd.value_at(p + "valid", rtl::cycle_time_ns(c)), 0u) << c;
      }
    }
  }
  // The save file opens the FST.
  const Gtkw g = parse_gtkw(read_text(dir.file("run.gtkw")));
  EXPECT_EQ(g.directives.at("dumpfile"), "\"" + fs::absolute(dir.file("run.fst")).string() + "\"");
  EXPECT_NE(g.find("hast/source/t"), nullptr);
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

// A run whose stream fails half-way throws its error and leaves no trace file named `file`.
void expect_failed_run_leaves_nothing(const std::string& file) {
  TempDir dir;
  const Stream s = make_stream(100, false);
  const SlotMap slots = make_slots(s.header);
  const auto unit = make_unit(parse_unit_spec("hast"), slots);
  ClockedOptions options;
  options.vcd_path = dir.file(file);
  EXPECT_THROW(run_clocked({unit.get()}, slots,
                           [&] { return std::make_unique<FailingStream>(s.rows); }, options, {}),
               InputError);
  EXPECT_TRUE(dir.entries().empty());
}

TEST(RtlVcd, FailedRunLeavesNoFiles) {
  expect_failed_run_leaves_nothing("f.vcd");
}

// The same for an FST: vcd2fst is stopped and its temporary directory (partial FST, side files)
// removed.
TEST(RtlVcd, FailedFstRunLeavesNoFiles) {
  if (::access(kVcd2Fst, X_OK) != 0) GTEST_SKIP() << kVcd2Fst << " not installed (gtkwave)";
  expect_failed_run_leaves_nothing("f.fst");
}

// Without vcd2fst an FST cannot be written: an OutputError (exit 2 in the CLI) naming the package,
// before anything is simulated, and nothing left behind. TraceFormat::kVcd writes a VCD whatever
// the name.
TEST(RtlVcd, FstWithoutVcd2fstIsAnOutputError) {
  TempDir dir;
  const Stream s = make_stream(20, false);
  const SlotMap slots = make_slots(s.header);
  const auto unit = make_unit(parse_unit_spec("lut"), slots);
  auto open = [&] { return std::make_unique<MemoryRowStream>(s.rows); };
  ClockedOptions fst;
  fst.vcd_path = dir.file("x.fst");
  const std::string path = std::getenv("PATH") ? std::getenv("PATH") : "";
  ::setenv("PATH", dir.path().c_str(), 1);  // no vcd2fst there
  try {
    run_clocked({unit.get()}, slots, open, fst, {});
    ADD_FAILURE() << "no OutputError";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("vcd2fst"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("gtkwave"), std::string::npos) << e.what();
  }
  ::setenv("PATH", path.c_str(), 1);
  EXPECT_TRUE(dir.entries().empty());

  ClockedOptions vcd;
  vcd.vcd_path = dir.file("y.fst");
  vcd.trace_format = TraceFormat::kVcd;
  ClockedRunInfo info;
  run_clocked({unit.get()}, slots, open, vcd, {}, &info);
  EXPECT_FALSE(info.fst);
  EXPECT_EQ(read_text(dir.file("y.fst")).rfind("$date", 0), 0u);
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"y.fst", "y.gtkw"}));
}

TEST(RtlVcd, UnwritablePathAndSecondRunAreRejected) {
  const Stream s = make_stream(20, false);
  const SlotMap slots = make_slots(s.header);
  const auto unit = make_unit(parse_unit_spec("lut"), slots);
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

// VcdWriter on its own (no elaboration): the exact text it writes.

TEST(RtlVcdWriter, WritesScopesValuesAndTimesExactly) {
  TempDir dir;
  bool a = false, b = true;
  std::uint64_t narrow = 0, neg = 0, wide = 0, one = 1;
  rtl::VcdWriter w("root");
  w.add_clock("top.clk");
  w.add_bool(a, "top.x.a");
  w.add_bits(narrow, 3, false, "top.x.n");
  w.add_bits(neg, 17, true, "top.y.s");
  w.add_bool(b, "top.x.b");  // joins the scope opened by top.x.a
  w.add_bits(wide, 64, false, "top.w");
  w.add_bits(one, 1, false, "top.one");
  EXPECT_THROW(w.add_bool(a, "top.x.a"), std::invalid_argument);
  EXPECT_THROW(w.add_bool(a, "top..c"), std::invalid_argument);
  EXPECT_THROW(w.add_bool(a, "top.c d"), std::invalid_argument);
  EXPECT_THROW(w.add_bits(wide, 65, false, "top.z"), std::invalid_argument);
  EXPECT_THROW(w.add_clock("top.clk2"), std::invalid_argument);
  ASSERT_EQ(w.signals().size(), 7u);
  EXPECT_EQ(w.signals()[3].name, "top.y.s");
  EXPECT_EQ(w.signals()[3].width, 17);
  EXPECT_TRUE(w.signals()[3].is_signed);

  const std::string path = dir.file("w.vcd");
  w.open(std::fopen(path.c_str(), "wb"));
  ASSERT_TRUE(w.is_open());
  w.header("ns", "test");
  EXPECT_THROW(w.add_bool(a, "top.late"), std::logic_error);
  w.dump_all(0, false);
  narrow = 0xff;                                       // 3 bits: 7
  neg = static_cast<std::uint64_t>(std::int64_t{-2});  // 17-bit two's complement
  w.time(5);
  w.clock(true);
  w.changes();
  a = true;
  wide = ~std::uint64_t{0};
  one = 0;
  w.time(10);
  w.clock(false);
  w.changes();
  w.time(15);
  w.clock(true);
  w.changes();  // only the clock changed
  EXPECT_THROW(w.time(12), std::logic_error);
  EXPECT_TRUE(w.close(20));

  const std::string text = read_text(path);
  const std::string defs =
      "$scope module root $end\n"
      "$scope module top $end\n"
      "$var wire 1 ! clk $end\n"
      "$var wire 64 ( w [63:0] $end\n"
      "$var wire 1 ) one $end\n"
      "$scope module x $end\n"
      "$var wire 1 \" a $end\n"
      "$var wire 3 % n [2:0] $end\n"
      "$var wire 1 ' b $end\n"
      "$upscope $end\n"
      "$scope module y $end\n"
      "$var wire 17 & s [16:0] $end\n"
      "$upscope $end\n"
      "$upscope $end\n"
      "$upscope $end\n"
      "$enddefinitions $end\n";
  const std::string body =
      "#0\n$dumpvars\n0!\n0\"\n1'\nb0 %\nb0 &\nb0 (\n1)\n$end\n"
      "#5\n1!\nb111 %\nb11111111111111110 &\n"
      "#10\n0!\n1\"\nb" +
      std::string(64, '1') +
      " (\n0)\n"
      "#15\n1!\n"
      "#20\n";
  EXPECT_EQ(text.rfind("$date\n", 0), 0u);
  EXPECT_NE(text.find("$timescale\n  1 ns\n$end\n"), std::string::npos);
  const auto d = text.find("$scope");
  ASSERT_NE(d, std::string::npos);
  EXPECT_EQ(text.substr(d), defs + body);
}

// The fixed-point format reaches the save file through add_bits (default: an integer).
TEST(RtlVcdWriter, FractionBitsOfTracedSignals) {
  std::uint64_t a = 0, b = 0;
  rtl::VcdWriter w("root");
  w.add_bits(a, 16, false, "top.t", 15);
  w.add_bits(b, 8, false, "top.count");
  ASSERT_EQ(w.signals().size(), 2u);
  EXPECT_EQ(w.signals()[0].frac_bits, 15);
  EXPECT_EQ(w.signals()[1].frac_bits, 0);
}

// Writing into a pipe whose reader is gone (vcd2fst died): close() reports the failure, and this
// process is not killed by SIGPIPE.
TEST(RtlVcdWriter, PipeWithoutReaderFailsInsteadOfKilling) {
  int fds[2];
  ASSERT_EQ(::pipe(fds), 0);
  ::close(fds[0]);
  std::uint64_t v = 0;
  rtl::VcdWriter w("root");
  w.add_clock("top.clk");
  w.add_bits(v, 8, false, "top.v");
  w.open(::fdopen(fds[1], "wb"), /*pipe=*/true);
  w.header("ns", "test");
  for (std::uint64_t t = 0; t < 100000; ++t) {  // several MiB: more than one buffer flush
    v = t;
    w.time(t);
    w.clock(t % 2 == 1);
    w.changes();
  }
  EXPECT_FALSE(w.close(100000));
  sigset_t pending;
  ASSERT_EQ(sigpending(&pending), 0);
  EXPECT_FALSE(sigismember(&pending, SIGPIPE));  // consumed, not left for someone else
}

// Many signals (two-character identifier codes) of every width with random values, read back
// change by change; vcd2fst accepts the file.
TEST(RtlVcdWriter, RandomValuesReadBack) {
  TempDir dir;
  constexpr int kSignals = 300, kSteps = 200;
  std::mt19937_64 rng(7);
  std::vector<std::uint64_t> bits(kSignals);
  std::unique_ptr<bool[]> flags(new bool[kSignals]());
  std::vector<int> width(kSignals);
  rtl::VcdWriter w("SystemC");
  w.add_clock("top.clk");
  for (int i = 0; i < kSignals; ++i) {
    width[i] = 1 + i % 64;
    const std::string name = "top.g" + std::to_string(i % 7) + ".s" + std::to_string(i);
    if (i % 5 == 0) {
      w.add_bool(flags[i], name);
    } else {
      w.add_bits(bits[i], width[i], i % 2 == 0, name);
    }
  }
  const std::string path = dir.file("r.vcd");
  w.open(std::fopen(path.c_str(), "wb"));
  w.header("ns", "test");
  auto mask = [](int wd) { return wd == 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << wd) - 1; };
  // expected[step][signal]
  std::vector<std::vector<std::uint64_t>> expected;
  auto snapshot = [&] {
    std::vector<std::uint64_t> v(kSignals);
    for (int i = 0; i < kSignals; ++i) v[i] = i % 5 == 0 ? flags[i] : bits[i] & mask(width[i]);
    expected.push_back(v);
  };
  w.dump_all(0, false);
  snapshot();
  for (int step = 1; step < kSteps; ++step) {
    for (int i = 0; i < kSignals; ++i) {
      if (rng() % 3 != 0) continue;  // a third of the values change
      if (i % 5 == 0) {
        flags[i] = rng() & 1;
      } else {
        bits[i] = rng() >> (rng() % 64);  // small and large values; upper bits ignored
      }
    }
    w.time(10 * static_cast<std::uint64_t>(step));
    w.clock(step % 2 == 1);
    w.changes();
    snapshot();
  }
  ASSERT_TRUE(w.close(10 * kSteps));

  const VcdInfo vcd = parse_vcd(path);
  ASSERT_EQ(vcd.vars.size(), static_cast<std::size_t>(kSignals + 1));
  std::set<std::string> ids;
  for (const auto& [name, id] : vcd.ids) ids.insert(id);
  EXPECT_EQ(ids.size(), vcd.vars.size());
  for (int i = 0; i < kSignals; ++i) {
    const std::string name = "SystemC.top.g" + std::to_string(i % 7) + ".s" + std::to_string(i);
    ASSERT_EQ(vcd.vars.at(name), i % 5 == 0 ? 1 : width[i]) << name;
    for (int step = 0; step < kSteps; ++step) {
      ASSERT_EQ(vcd.value_at(name, 10 * static_cast<std::uint64_t>(step)), expected[step][i])
          << name << " step " << step;
    }
  }
  EXPECT_EQ(vcd.times.back(), 10u * kSteps);

  if (::access(kVcd2Fst, X_OK) != 0) GTEST_SKIP() << kVcd2Fst << " not installed (gtkwave)";
  const std::string fst = dir.file("r.fst");
  const std::string cmd =
      std::string(kVcd2Fst) + " -v '" + path + "' -f '" + fst + "' > /dev/null 2>&1";
  const int rc = std::system(cmd.c_str());
  ASSERT_TRUE(WIFEXITED(rc)) << cmd;
  EXPECT_EQ(WEXITSTATUS(rc), 0) << cmd;
  EXPECT_GT(fs::file_size(fst), 0u);
}

}  // namespace
}  // namespace glint
