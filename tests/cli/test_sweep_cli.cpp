// `glint sweep`, `glint size` and `glint merge` end to end: the real binary through the shell.
// Figures are checked against the other subcommands' own reports on the same input (eval, sim,
// render), shards against the unsharded run byte for byte, size against a brute force over the
// sweep's rows, plots against the rows they draw.
#include <gtest/gtest.h>
#include <stdlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "test_support.h"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

const std::string kTraces = GLINT_SOURCE_DIR "/traces";
const auto quote = glint::test::shell_quote;
const auto read_text = glint::test::read_file;

using glint::test::CliRun;

class SweepCli : public ::testing::Test {
 protected:
  CliRun glint(const std::string& args) { return glint::test::run_glint(tmp_.path(), args); }
  json glint_json(const std::string& args) {
    const CliRun r = glint(args);
    EXPECT_EQ(r.status, 0) << "glint " << args << "\n" << r.err;
    return json::accept(r.out) ? json::parse(r.out) : json();
  }
  std::string file(const std::string& name) const { return tmp_.file(name); }
  std::vector<std::string> entries() const { return tmp_.entries(); }

  glint::test::TempDir tmp_;
};

const std::string kGrids =
    "--grid 'horner:degree=2..5,in=uq1.11|uq1.15' --grid 'lut:bits=4..7' --grid pow "
    "--grid 'schlick:divider=pipelined|iterative' --grid 'hast:d=2..4'";

// One configuration: the sweep's errors are `glint eval`'s and its cost and timing `glint sim`'s
// for the same spec on the same file.
TEST_F(SweepCli, OneConfigurationEqualsEvalAndSim) {
  for (const char* f : {"/blinn_colored.vec", "/phong_basic.vec"}) {
    for (const char* spec : {"hast:d=3", "schlick:divider=iterative", "lut:bits=5,in=uq1.12"}) {
      const std::string vec = quote(kTraces + f);
      const json sweep = glint_json("sweep " + vec + " --grid " + quote(spec) + " --json");
      const json eval = glint_json("eval " + vec + " --unit " + quote(spec) + " --json");
      const json sim = glint_json("sim " + vec + " --unit " + quote(spec) + " --json");
      ASSERT_EQ(sweep.at("results").size(), 1u);
      const json& row = sweep["results"][0];
      const json& e = eval.at("units")[0];
      const json& s = sim.at("units")[0];
      EXPECT_EQ(row.at("errors"), e.at("errors")) << f << " " << spec;
      EXPECT_EQ(row.at("errors"), s.at("errors")) << f << " " << spec;
      EXPECT_EQ(row.at("canonical_spec"), s.at("spec"));
      EXPECT_EQ(row.at("spec"), spec);
      EXPECT_EQ(row.at("vectors"), e.at("vectors"));
      EXPECT_EQ(row.at("skipped"), e.at("skipped"));
      EXPECT_EQ(row.at("digest"), s.at("digest"));
      for (const char* k : {"cycles", "throughput", "computed", "stall_cycles"})
        EXPECT_EQ(row.at(k), s.at(k)) << k;
      EXPECT_EQ(row.at("latency_cycles"), s.at("latency"));
      EXPECT_EQ(row.at("area_ge"), s.at("area").at("ge"));
      EXPECT_EQ(row.at("critical_path"), s.at("critical_path").at("delay"));
      EXPECT_EQ(row.at("latency"), s.at("timing").at("latency"));
      for (const auto& [kind, n] : s.at("operations").items())
        EXPECT_EQ(row.at("operations").at("total").at(kind), n) << kind;
      EXPECT_EQ(row.at("error"), row.at("errors").at("max_lsb"));
      // One configuration is on every front.
      for (const char* o : {"area", "throughput", "area_latency"})
        EXPECT_TRUE(row.at("pareto").at(o).get<bool>());
    }
  }
}

TEST_F(SweepCli, JobsGiveTheSameBytes) {
  const std::string vec = quote(kTraces + "/multi_light.vec");
  const CliRun one = glint("sweep " + vec + " " + kGrids + " --jobs 1 -o one.json --csv one.csv");
  ASSERT_EQ(one.status, 0) << one.err;
  const CliRun three =
      glint("sweep " + vec + " " + kGrids + " --jobs 3 -o three.json --csv three.csv");
  ASSERT_EQ(three.status, 0) << three.err;
  EXPECT_EQ(read_text(file("one.json")), read_text(file("three.json")));
  EXPECT_EQ(read_text(file("one.csv")), read_text(file("three.csv")));
  EXPECT_EQ(one.out, three.out);
}

// The printed fronts list a configuration tied in both objectives with the one above it only as
// a count; with the counts, they account for every configuration the report flags.
TEST_F(SweepCli, PrintedFrontsCountTiedConfigurations) {
  const std::string args =
      "sweep " + quote(kTraces + "/phong_basic.vec") + " --grid 'pow:buffer=1..40'";
  const CliRun text = glint(args);
  ASSERT_EQ(text.status, 0) << text.err;
  const json report = glint_json(args + " --json");
  std::size_t tied_lines = 0;
  for (const char* name : {"area", "throughput", "area_latency"}) {
    SCOPED_TRACE(name);
    std::size_t flagged = 0;
    for (const json& r : report.at("results")) flagged += r.at("pareto").at(name).get<bool>();
    const std::string head = std::string("Pareto front, error vs ") + name + " (";
    const auto at = text.out.find(head);
    ASSERT_NE(at, std::string::npos) << text.out;
    std::istringstream section(text.out.substr(at));
    std::string line;
    std::getline(section, line);  // the title
    std::getline(section, line);  // the column names
    std::size_t listed = 0, counted = 0;
    while (std::getline(section, line) && line.rfind("Pareto", 0) != 0) {
      std::size_t more = 0;
      if (std::sscanf(line.c_str(), " and %zu more tied", &more) == 1) {
        counted += more;
        ++tied_lines;
      } else {
        ++listed;
      }
    }
    EXPECT_EQ(listed + counted, flagged) << text.out;
  }
  // pow's buffer changes timing only: past full throughput every size ties there.
  EXPECT_GT(tied_lines, 0u) << text.out;
}

// Shards merged equal the unsharded run, byte for byte (JSON and CSV), whatever order the shard
// files come in; Pareto flags are recomputed over the union.
TEST_F(SweepCli, ShardsMergeToTheUnshardedRun) {
  const std::string vec = quote(kTraces + "/eight_lights.vec");
  ASSERT_EQ(glint("sweep " + vec + " " + kGrids + " -o all.json --csv all.csv").status, 0);
  for (int k = 0; k < 3; ++k) {
    const CliRun r = glint("sweep " + vec + " " + kGrids + " --shard " + std::to_string(k) +
                           "/3 -o shard" + std::to_string(k) + ".json");
    ASSERT_EQ(r.status, 0) << r.err;
  }
  const CliRun m =
      glint("merge shard2.json shard0.json shard1.json -o merged.json --csv merged.csv");
  ASSERT_EQ(m.status, 0) << m.err;
  EXPECT_EQ(read_text(file("merged.json")), read_text(file("all.json")));
  EXPECT_EQ(read_text(file("merged.csv")), read_text(file("all.csv")));
  // A shard's own fronts are over its configurations only, so they differ somewhere.
  const json s0 = json::parse(read_text(file("shard0.json")));
  EXPECT_EQ(s0.at("shard"), (json{{"index", 0}, {"count", 3}}));

  // A shard nested deeper than a report can be (it once crashed merge's dump(): SIGSEGV) and one
  // that is not JSON are refused naming the file and the line.
  {
    std::ofstream deep(file("deep.json"));
    deep << "{\"glint_sweep_report\": 1, \"input\":\n"
         << std::string(100000, '[') << std::string(100000, ']') << "}\n";
    std::ofstream(file("garbage.json")) << "{\"glint_sweep_report\": 1,\n  oops\n}\n";
  }
  // Shards whose numbers would size merge's tables, or whose fields have other types than glint
  // writes (they once made merge allocate until bad_alloc, or throw nlohmann's errors: exit 3).
  const auto write_tampered = [&](const std::string& name, const std::string& pointer,
                                  const json& value) {
    json t = s0;
    t[json::json_pointer(pointer)] = value;
    std::ofstream(file(name)) << t.dump();
  };
  write_tampered("huge_count.json", "/shard/count", std::uint64_t{1} << 60);
  write_tampered("huge_configurations.json", "/configurations", std::uint64_t{1} << 60);
  write_tampered("text_area.json", "/results/0/area_ge", "big");
  write_tampered("no_path.json", "/input", json{{"kind", "vectors"}});
  write_tampered("bits_text.json", "/display_bits", "8");
  // Missing, repeated and foreign shards are refused, and nothing is written.
  const struct {
    const char* args;
    const char* mention;
  } bad[] = {
      {"shard0.json shard1.json", "shard 2/3 is missing"},
      {"shard0.json shard0.json shard1.json", "both shard 0/3"},
      {"all.json", "not a shard"},
      {"shard0.json shard1.json nosuch.json", "nosuch.json"},
      {"shard0.json shard1.json deep.json", "deep.json:2: field 'json': nested deeper than 32"},
      {"shard0.json garbage.json shard2.json", "garbage.json:2: field 'json'"},
      {"huge_count.json shard1.json shard2.json", "huge_count.json: field 'shard'"},
      {"huge_configurations.json shard1.json shard2.json",
       "huge_configurations.json: field 'configurations': not a count in 0..100000"},
      {"text_area.json shard1.json shard2.json",
       "text_area.json: field 'results[0]/area_ge': wrong type: string"},
      {"no_path.json shard1.json shard2.json", "no_path.json: field 'input'"},
      {"bits_text.json shard1.json shard2.json", "bits_text.json: field 'display_bits'"}};
  for (const auto& b : bad) {
    const CliRun r = glint(std::string("merge ") + b.args + " -o bad.json");
    EXPECT_EQ(r.status, 2) << b.args;
    EXPECT_NE(r.err.find(b.mention), std::string::npos) << b.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(file("bad.json")));
  }
  const CliRun other = glint("sweep " + vec + " --grid pow --shard 1/3 -o other.json");
  ASSERT_EQ(other.status, 0);
  const CliRun r = glint("merge shard0.json other.json shard2.json -o bad.json");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("another sweep"), std::string::npos) << r.err;
}

TEST_F(SweepCli, BadInputExitsTwoAndWritesNothing) {
  const std::string vec = quote(kTraces + "/phong_basic.vec");
  const struct {
    std::string args;
    const char* mention;
  } bad[] = {
      {"sweep " + vec + " --grid 'horner:degre=2'", "--grid 'horner:degre=2'"},
      {"sweep " + vec + " --grid 'horner:degree=0..3'", "key 'degree'"},
      {"sweep " + vec + " --grid 'hast:buffer=1..1000,d=1..16,guard=0..7'",
       "128000 configurations exceed the limit of 100000"},
      {"sweep --grid pow", "VECTORS"},
      {"sweep " + vec + " --scene x.json --grid pow", "one input"},
      {"sweep " + vec + " --grid pow --error-measure frobs", "--error-measure"},
      {"sweep " + vec + " --grid pow --error-measure throughput", "not an error measure"},
      {"sweep " + vec + " --grid pow --error-measure image.max_lsb", "need --scene"},
      {"sweep " + vec + " --grid pow --shard 3/3", "--shard"},
      {"sweep " + vec + " --grid pow -o out.txt", "-o out.txt"},
      {"sweep " + vec + " --grid pow --csv " + vec, "would overwrite the input"},
      {"sweep " + vec + " --grid pow -o a.csv --csv a.csv", "a.csv"},
      {"sweep " + vec + " --grid pow -o nodir/a.json", "folder 'nodir'"},
      {"sweep " + vec + " --grid pow --chip ram:slots=0", "--chip"},
      {"sweep nosuch.vec --grid pow -o out.json", "nosuch.vec"},
      {"size --budget 'frobs<=1' " + vec, "unknown measure 'frobs'"},
      {"size --budget 'lsb8<=1' --objective speed " + vec, "--objective"},
      {"size --budget 'lsb8<=1'", "VECTORS"},
      {"size --budget 'lsb8<=1' --no-widen --widen-rounds 2 " + vec, "--no-widen"},
      {"size --budget 'lsb8<=1' --widen-rounds 65 " + vec, "--widen-rounds"},
      {"merge -o out.json", "SHARD"},
  };
  for (const auto& b : bad) {
    const bool plots = b.args.rfind("size", 0) != 0;  // size writes no plots
    const CliRun r = glint(b.args + (plots ? " --plot plots" : ""));
    EXPECT_EQ(r.status, 2) << b.args << "\n" << r.err;
    EXPECT_NE(r.err.find(b.mention), std::string::npos) << b.args << ": " << r.err;
    EXPECT_TRUE(entries().empty()) << b.args << " left files";
  }
}

// size against a brute force over `glint sweep`'s rows of the same grids on the same inputs.
TEST_F(SweepCli, SizePicksTheCheapestAndExitsOneWhenNoneMeets) {
  const std::string grids =
      "--grid 'lut:bits=4..8,in=uq1.11|uq1.15' --grid 'horner:degree=2..5' "
      "--grid 'pow:out=uq1.10|uq1.15'";
  const std::vector<std::string> files = {kTraces + "/phong_basic.vec",
                                          kTraces + "/multi_light.vec"};
  std::vector<json> sweeps;
  std::string inputs;
  for (const std::string& f : files) {
    sweeps.push_back(glint_json("sweep " + quote(f) + " " + grids + " --json"));
    inputs += " " + quote(f);
  }
  // --no-widen: the grids as given, as the sweeps ran them (widening: the tests below).
  const json size =
      glint_json("size --no-widen --budget 'max_lsb8<=2' " + grids + inputs + " --top 4 --json");
  // Brute force: the largest area over the inputs among configurations within 2 LSB on both.
  std::optional<std::size_t> best;
  double best_area = 0;
  std::map<std::string, std::pair<std::size_t, double>> per_family;
  std::vector<std::pair<double, std::size_t>> meeting;  // (area, index)
  // Per family: the configuration nearest the budget (least worst error; ties to less area).
  std::map<std::string, std::tuple<double, double, std::size_t>> nearest;
  for (std::size_t i = 0; i < sweeps[0]["results"].size(); ++i) {
    bool ok = true;
    double area = 0, lsb = 0;
    for (const json& s : sweeps) {
      const json& row = s["results"][i];
      lsb = std::max(lsb, row["errors"]["max_abs"].get<double>() * 255);
      ok = ok && row["errors"]["max_abs"].get<double>() * 255 <= 2;
      area = std::max(area, row["area_ge"].get<double>());
    }
    const std::string family = sweeps[0]["results"][i]["unit"];
    if (!nearest.count(family) || std::make_tuple(lsb, area, i) < nearest[family])
      nearest[family] = {lsb, area, i};
    if (!ok) continue;
    meeting.emplace_back(area, i);
    if (!best || area < best_area) {
      best = i;
      best_area = area;
    }
    const std::string unit = sweeps[0]["results"][i]["unit"];
    if (!per_family.count(unit) || area < per_family[unit].second) per_family[unit] = {i, area};
  }
  ASSERT_TRUE(best);
  EXPECT_EQ(size.at("best").at("index"), *best);
  EXPECT_EQ(size.at("best").at("spec"), sweeps[0]["results"][*best]["spec"]);
  EXPECT_DOUBLE_EQ(size.at("best").at("value").get<double>(), best_area);
  for (const json& f : size.at("families")) {
    const std::string unit = f.at("unit");
    const auto [lsb, area, index] = nearest.at(unit);
    EXPECT_DOUBLE_EQ(f.at("reached").at(0).at("best").get<double>(), lsb) << unit;
    if (per_family.count(unit)) {
      EXPECT_EQ(f.at("index"), per_family[unit].first) << unit;
      EXPECT_FALSE(f.contains("closest")) << unit;
    } else {
      EXPECT_TRUE(f.at("spec").is_null()) << unit;
      EXPECT_EQ(f.at("closest").at("index"), index) << unit;
      EXPECT_DOUBLE_EQ(f.at("closest").at("miss").get<double>(), lsb / 2 - 1) << unit;
      EXPECT_TRUE(f.at("closest").at("part").contains("name")) << unit;
    }
  }
  EXPECT_LT(per_family.size(), 3u) << "the test wants a family that misses the budget";
  // --top 4: the four cheapest meeting the budget, over every family, ties to the lower index.
  std::sort(meeting.begin(), meeting.end());
  ASSERT_EQ(size.at("top").size(), std::min<std::size_t>(4, meeting.size()));
  for (std::size_t k = 0; k < size.at("top").size(); ++k)
    EXPECT_EQ(size.at("top")[k].at("index"), meeting[k].second) << k;
  // The text ends with the spec alone, ready to paste.
  const CliRun text = glint("size --no-widen --budget 'max_lsb8<=2' " + grids + inputs);
  ASSERT_EQ(text.status, 0) << text.err;
  const std::string last = text.out.substr(text.out.rfind('\n', text.out.size() - 2) + 1);
  EXPECT_EQ(last, sweeps[0]["results"][*best]["spec"].get<std::string>() + "\n");

  const CliRun none = glint("size --no-widen --budget 'max_abs<0' " + grids + inputs);
  EXPECT_EQ(none.status, 1) << none.err;
  EXPECT_NE(none.out.find("no configuration meets the budget"), std::string::npos) << none.out;
}

// The default grids run on every shipped trace (src/cli/guide/size.md lists them).
// Without --chip, size answers on both chips and says whether the winner differs; each answer is
// the one --chip gives on its own. On these traces a ROM lut wins while loaded tables make lut's
// table a register file and pow wins (issue 25's finding).
TEST_F(SweepCli, SizeAnswersOnBothChipsUnlessOneIsGiven) {
  const std::string args =
      "size --no-widen --budget 'max_lsb8<=1' --grid 'lut:in=uq1.16,out=uq1.8,bits=6..8' "
      "--grid 'pow:in=uq1.16,out=uq1.8,log_bits=6,exp_bits=4' " +
      quote(kTraces + "/phong_basic.vec") + " " + quote(kTraces + "/multi_light.vec");
  const json both = glint_json(args + " --json");
  const json rom = glint_json(args + " --json --chip rom");
  const json ram = glint_json(args + " --json --chip ram");
  ASSERT_TRUE(both.is_object() && rom.is_object() && ram.is_object());
  EXPECT_EQ(both.at("chip"), "rom");
  EXPECT_EQ(both.at("loadable").at("chip"), "ram");
  EXPECT_EQ(both.at("best"), rom.at("best"));
  EXPECT_EQ(both.at("loadable").at("best"), ram.at("best"));
  EXPECT_FALSE(rom.contains("loadable"));
  EXPECT_FALSE(rom.contains("winner_differs"));
  const std::string rom_spec = rom.at("best").at("spec"), ram_spec = ram.at("best").at("spec");
  EXPECT_EQ(rom_spec.rfind("lut:", 0), 0u) << rom_spec;
  EXPECT_EQ(ram_spec.rfind("pow:", 0), 0u) << ram_spec;
  EXPECT_EQ(both.at("winner_differs"), true);
  const CliRun text = glint(args);
  ASSERT_EQ(text.status, 0) << text.err;
  // After the pixel measure's line, the chips' line.
  const std::string second = text.out.substr(text.out.find('\n') + 1);
  EXPECT_EQ(second.rfind("chips: the winner differs: rom " + rom_spec + ", ram " + ram_spec, 0), 0u)
      << text.out;
  // The default chip's answer last, ready to paste.
  EXPECT_EQ(text.out.substr(text.out.rfind('\n', text.out.size() - 2) + 1), rom_spec + "\n");
  const CliRun given = glint(args + " --chip ram");
  EXPECT_EQ(given.out.substr(given.out.find('\n') + 1).rfind("chip: ram\n", 0), 0u) << given.out;
  EXPECT_EQ(given.out.find("chips:"), std::string::npos) << given.out;
}

TEST_F(SweepCli, SizeDefaultGridsOnTheTraces) {
  std::string inputs;
  for (const char* f : {"/phong_basic.vec", "/multi_light.vec", "/eight_lights.vec"})
    inputs += " " + quote(kTraces + f);
  const json size = glint_json("size --budget 'lsb8<=1'" + inputs + " --json");
  EXPECT_GT(size.at("configurations").get<std::size_t>(), 100u);
  ASSERT_TRUE(size.at("best").is_object());
  for (const json& v : size.at("best").at("measures").at("lsb8")) EXPECT_LE(v.get<double>(), 1.0);
}

const json* family(const json& size, const std::string& unit) {
  for (const json& f : size.at("families"))
    if (f.at("unit") == unit) return &f;
  return nullptr;
}

// The value of `key` in a spec "unit:key=value,...".
std::string spec_value(const std::string& spec, const std::string& key) {
  const std::smatch m = [&] {
    std::smatch r;
    std::regex_search(spec, r, std::regex("[:,]" + key + "=([^,]+)"));
    return r;
  }();
  return m.empty() ? std::string() : m[1].str();
}

int frac_bits(const std::string& format) {
  return std::stoi(format.substr(format.find('.') + 1));
}

// A budget the fixed grid misses and the widened one meets: the winner's key lies beyond the old
// edge, the report says how the grid grew, and its final grid swept as given gives the same answer.
TEST_F(SweepCli, SizeWidensAGridUntilTheBudgetIsMet) {
  const std::string vec = quote(kTraces + "/phong_basic.vec");
  const std::string args = "size --budget 'lsb8<=1' --grid 'lut:bits=4..5' " + vec;
  const CliRun fixed = glint(args + " --no-widen");
  EXPECT_EQ(fixed.status, 1) << fixed.err;
  const json size = glint_json(args + " --json");
  ASSERT_TRUE(size.at("best").is_object());
  const std::string spec = size.at("best").at("spec");
  EXPECT_GT(std::stoi(spec_value(spec, "bits")), 5) << spec;
  for (const json& v : size.at("best").at("measures").at("lsb8")) EXPECT_LE(v.get<double>(), 1.0);
  EXPECT_EQ(size.at("grids_given"), json::array({"lut:bits=4..5"}));
  const json& search = family(size, "lut")->at("search").at(0);
  EXPECT_EQ(search.at("stopped"), "met");
  EXPECT_GE(search.at("rounds").get<int>(), 1);
  EXPECT_EQ(search.at("steps").at(0).at("key"), "bits");
  EXPECT_EQ(search.at("steps").at(0).at("value"), "6");
  EXPECT_EQ(size.at("grids").at(0), search.at("grid"));
  EXPECT_EQ(size.at("configurations"), search.at("configurations"));
  EXPECT_EQ(size.at("widen").at("rounds"), search.at("rounds"));

  const json again = glint_json("size --no-widen --budget 'lsb8<=1' --grid " +
                                quote(search.at("grid")) + " " + vec + " --json");
  EXPECT_EQ(again.at("best").at("spec"), spec);
  EXPECT_EQ(again.at("best").at("index"), size.at("best").at("index"));
  EXPECT_EQ(again.at("best").at("value"), size.at("best").at("value"));
}

// A budget the fixed grid meets, with its winner at the narrowest output: a narrower output,
// beyond the grid, is cheaper and still meets it.
TEST_F(SweepCli, SizeWidensTowardsACheaperConfiguration) {
  const std::string args =
      "size --budget 'lsb8<=1' --grid 'lut:in=uq1.16,out=uq1.10|uq1.12,"
      "bits=6..8' " +
      quote(kTraces + "/phong_basic.vec") + " " + quote(kTraces + "/multi_light.vec") + " --json";
  const json fixed = glint_json(args + " --no-widen");
  const json wide = glint_json(args);
  ASSERT_TRUE(fixed.at("best").is_object());
  ASSERT_TRUE(wide.at("best").is_object());
  EXPECT_EQ(spec_value(fixed.at("best").at("spec"), "out"), "uq1.10");
  EXPECT_LT(frac_bits(spec_value(wide.at("best").at("spec"), "out")), 10) << wide.at("best");
  EXPECT_LT(wide.at("best").at("value").get<double>(), fixed.at("best").at("value").get<double>());
  EXPECT_EQ(family(fixed, "lut")->at("search").at(0).at("stopped"), "fixed");
  EXPECT_FALSE(fixed.at("widen").at("enabled").get<bool>());
}

// Budgets nothing reaches: the search ends within its caps and says why.
TEST_F(SweepCli, SizeStopsWideningWithinItsCaps) {
  const std::string vec = quote(kTraces + "/phong_basic.vec");
  // max_abs < 0: every step improves, so the rounds run out.
  CliRun r =
      glint("size --budget 'max_abs<0' --grid 'lut:bits=4..5' --widen-rounds 2 --json " + vec);
  EXPECT_EQ(r.status, 1) << r.err;
  json size = json::parse(r.out);
  json search = family(size, "lut")->at("search").at(0);
  EXPECT_EQ(search.at("stopped"), "round_cap");
  EXPECT_EQ(search.at("rounds"), 2);
  EXPECT_EQ(size.at("configurations"), 4);
  EXPECT_EQ(size.at("widen").at("max_rounds"), 2);
  // ... or the configurations.
  r = glint("size --budget 'max_abs<0' --grid 'lut:bits=4..5' --widen-configurations 3 --json " +
            vec);
  EXPECT_EQ(r.status, 1) << r.err;
  size = json::parse(r.out);
  search = family(size, "lut")->at("search").at(0);
  EXPECT_EQ(search.at("stopped"), "configuration_cap");
  EXPECT_LE(size.at("configurations").get<int>(), 3);
  // Schlick misses 1 LSB by a factor of ~50, its approximation's: wider formats close too little.
  r = glint("size --budget 'lsb8<=1' --grid 'schlick:in=uq1.12|uq1.14,out=uq1.10|uq1.12' --json " +
            vec);
  EXPECT_EQ(r.status, 1) << r.err;
  size = json::parse(r.out);
  search = family(size, "schlick")->at("search").at(0);
  EXPECT_EQ(search.at("stopped"), "too_slow");
  EXPECT_EQ(search.at("rounds"), 0);
  // The key table's end: lut's bits takes 1..16, and a budget of more area than bits=16 has
  // improves towards it.
  const std::string bits = "--grid 'lut:bits=15..16' " + vec;
  r = glint("size --no-widen --budget 'area_ge>=1e12' --json " + bits);
  EXPECT_EQ(r.status, 1) << r.err;
  const double largest = json::parse(r.out).at("families")[0].at("reached")[0].at("best");
  std::ostringstream limit;
  limit.precision(17);
  limit << largest * 1.01;
  r = glint("size --budget 'area_ge>=" + limit.str() + "' --json " + bits);
  EXPECT_EQ(r.status, 1) << r.err;
  size = json::parse(r.out);
  search = family(size, "lut")->at("search").at(0);
  EXPECT_EQ(search.at("stopped"), "range_end");
  EXPECT_EQ(search.at("grid"), "lut:bits=15..16");
  EXPECT_NE(search.at("why").get<std::string>().find("1..16"), std::string::npos) << search;
}

// --plot: both plots as SVG and PNG; the SVG holds one point per configuration with an error
// value, those on the front marked.
TEST_F(SweepCli, PlotsHoldEveryConfiguration) {
  const std::string vec = quote(kTraces + "/multi_light.vec");
  const CliRun r = glint("sweep " + vec + " " + kGrids + " -o r.json --plot plots");
  ASSERT_EQ(r.status, 0) << r.err;
  const json report = json::parse(read_text(file("r.json")));
  for (const auto& [name, flag] : {std::pair<std::string, std::string>{"error_vs_area", "area"},
                                   {"error_vs_throughput", "throughput"}}) {
    const std::string svg = read_text(file("plots/" + name + ".svg"));
    ASSERT_EQ(svg.rfind("<?xml version=\"1.0\"", 0), 0u) << name;
    EXPECT_NE(svg.find("</svg>\n"), std::string::npos);
    // Well formed enough: every element opened is closed or self-closing.
    EXPECT_EQ(std::count(svg.begin(), svg.end(), '<'), std::count(svg.begin(), svg.end(), '>'));
    const auto count = [&](const std::string& what) {
      std::size_t n = 0;
      for (std::size_t at = svg.find(what); at != std::string::npos; at = svg.find(what, at + 1))
        ++n;
      return n;
    };
    std::size_t points = 0, front = 0;
    for (const json& row : report["results"]) {
      if (!row["error"].is_number()) continue;
      ++points;
      front += row["pareto"][flag].get<bool>();
    }
    EXPECT_EQ(count("class=\"point "), points) << name;
    EXPECT_EQ(count("class=\"point front\""), front) << name;
    EXPECT_GT(front, 0u);
    const std::string png = read_text(file("plots/" + name + ".png"));
    ASSERT_GT(png.size(), 1000u) << name;
    EXPECT_EQ(png.substr(1, 3), "PNG");
  }
  // The same bytes on a second run.
  const std::string svg = read_text(file("plots/error_vs_area.svg"));
  const std::string png = read_text(file("plots/error_vs_area.png"));
  ASSERT_EQ(glint("sweep " + vec + " " + kGrids + " --plot plots").status, 0);
  EXPECT_EQ(read_text(file("plots/error_vs_area.svg")), svg);
  EXPECT_EQ(read_text(file("plots/error_vs_area.png")), png);
}

// A scene: request-level figures equal eval's on the scene's own requests (--write-vectors), and
// the image-level error equals glint render's.
TEST_F(SweepCli, SceneEqualsRenderAndEvalOnItsRequests) {
  const std::string scene = quote(kTraces + "/scenes/small.json");
  const std::string grid = "--grid 'lut:bits=4..6' --grid 'hast:d=2|4'";
  const json sweep = glint_json("sweep --scene " + scene + " " + grid + " --json");
  ASSERT_EQ(sweep.at("results").size(), 5u);
  EXPECT_EQ(sweep.at("input").at("kind"), "scene");
  EXPECT_TRUE(sweep.at("image_error").get<bool>());
  for (const json& row : sweep["results"]) {
    const std::string spec = row.at("spec");
    const json render = glint_json("render " + scene + " --unit " + quote(spec) +
                                   " -o r --write-vectors r.vec --json");
    const json eval = glint_json("eval r.vec --unit " + quote(spec) + " --json");
    EXPECT_EQ(row.at("image"), render.at("units")[0].at("image_error")) << spec;
    EXPECT_EQ(row.at("errors"), eval.at("units")[0].at("errors")) << spec;
    EXPECT_EQ(row.at("vectors"), render.at("requests"));
  }
  const CliRun csv = glint("sweep --scene " + scene + " " + grid + " --csv s.csv");
  ASSERT_EQ(csv.status, 0) << csv.err;
  EXPECT_NE(read_text(file("s.csv")).find(",image.max_lsb,"), std::string::npos);
  // Image-level error measures for the fronts and budgets.
  const json by_image =
      glint_json("sweep --scene " + scene + " " + grid + " --error-measure image.max_lsb --json");
  for (const json& row : by_image["results"])
    EXPECT_EQ(row.at("error"), row.at("image").at("max_lsb"));
  // --no-image: request-level only.
  const json no_image = glint_json("sweep --scene " + scene + " " + grid + " --no-image --json");
  EXPECT_FALSE(no_image.at("image_error").get<bool>());
  for (const json& row : no_image["results"]) EXPECT_FALSE(row.contains("image"));
}

// A CSV as the sweep writes it (RFC 4180: a cell with a comma or a quote is quoted): its lines'
// cells.
std::vector<std::vector<std::string>> read_csv(const std::string& text) {
  std::vector<std::vector<std::string>> rows(1);
  std::string cell;
  bool quoted = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quoted && c == '"' && i + 1 < text.size() && text[i + 1] == '"') {
      cell += '"';
      ++i;
    } else if (c == '"') {
      quoted = !quoted;
    } else if (!quoted && (c == ',' || c == '\n')) {
      rows.back().push_back(cell);
      cell.clear();
      if (c == '\n') rows.emplace_back();
    } else {
      cell += c;
    }
  }
  rows.pop_back();  // after the last newline
  return rows;
}

std::size_t column_of(const std::vector<std::string>& header, const std::string& name) {
  return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
}

const std::vector<std::string> kNodeColumns = {"area_um2", "critical_path_ns", "max_clock_mhz"};

// sweep --node: the CSV and every front's table state each lane's area, critical path and clock at
// the node, sim --node's figures for the same spec; without --node the CSV and the tables are
// those of the same sweep with the node's columns left out.
TEST_F(SweepCli, NodeColumnsStateSimsLaneAtTheNode) {
  const std::string vec = quote(kTraces + "/phong_basic.vec");
  const std::string args = "sweep " + vec + " --grid 'lut:bits=4..6' --grid 'hast:d=2..3'";
  const CliRun node = glint(args + " --node osu018 --csv node.csv");
  ASSERT_EQ(node.status, 0) << node.err;
  const CliRun plain = glint(args + " --csv plain.csv");
  ASSERT_EQ(plain.status, 0) << plain.err;
  const auto with = read_csv(read_text(file("node.csv")));
  const auto without = read_csv(read_text(file("plain.csv")));
  ASSERT_EQ(with.size(), 6u);  // the header and 5 configurations
  ASSERT_EQ(without.size(), with.size());
  const std::vector<std::string>& header = with[0];
  std::string units;
  for (std::size_t i = 1; i < with.size(); ++i)
    units += " --unit " + quote(with[i][column_of(header, "spec")]);
  const json sim = glint_json("sim " + vec + units + " --node osu018 --json");
  ASSERT_EQ(sim.at("units").size(), with.size() - 1);
  for (const std::string& c : kNodeColumns) {
    ASSERT_LT(column_of(header, c), header.size()) << c;
    EXPECT_EQ(column_of(without[0], c), without[0].size()) << c;
    for (std::size_t i = 1; i < with.size(); ++i) {
      const double v = std::stod(with[i][column_of(header, c)]);
      EXPECT_GT(v, 0) << c;
      // The CSV's number reads back as the double sim's JSON holds.
      EXPECT_EQ(v, sim["units"][i - 1].at("node").at(c).get<double>()) << c << " " << i;
    }
  }
  // Without --node: every other column, cell for cell.
  std::vector<std::string> kept;
  for (const std::string& c : header)
    if (std::find(kNodeColumns.begin(), kNodeColumns.end(), c) == kNodeColumns.end() &&
        c != "energy_pj_per_request" && c != "pareto_energy")
      kept.push_back(c);
  EXPECT_EQ(without[0], kept);
  for (std::size_t i = 1; i < with.size(); ++i)
    for (const std::string& c : kept)
      EXPECT_EQ(without[i][column_of(without[0], c)], with[i][column_of(header, c)]) << c;
  // The tables: each front's heading names the columns, and the area front's first line states
  // its configuration's area at the node; without --node they are absent.
  const std::string heading = "   area_um2 critical_path_ns max_clock_mhz";
  std::size_t headings = 0;
  for (std::size_t at = node.out.find(heading); at != std::string::npos;
       at = node.out.find(heading, at + 1))
    ++headings;
  EXPECT_EQ(headings, 4u) << node.out;  // area, throughput, area_latency, energy
  EXPECT_EQ(plain.out.find("area_um2"), std::string::npos) << plain.out;
  EXPECT_EQ(plain.out.find("max_clock_mhz"), std::string::npos) << plain.out;
  const std::size_t first = node.out.find('\n', node.out.find(heading)) + 1;
  std::istringstream line(node.out.substr(first, node.out.find('\n', first) - first));
  std::size_t index = 0;
  std::string skip, area;
  line >> index >> skip >> skip >> skip >> skip >> skip >> area;
  ASSERT_LT(index + 1, with.size());
  EXPECT_EQ(std::stod(area), std::round(std::stod(with[index + 1][column_of(header, "area_um2")])))
      << node.out;
}

// size --node: the tables state the chosen lanes' area in GE and um2 and their clock, the JSON the
// lane at the node of each choice; --objective area_um2 picks the least area at the node among the
// configurations meeting the budget (a brute force over sweep --node's rows); it needs --node.
TEST_F(SweepCli, SizeAtANodeStatesTheLaneAndMinimisesItsArea) {
  const std::string vec = quote(kTraces + "/phong_basic.vec");
  const std::string grids = " --grid 'lut:bits=4..7' --grid 'hast:d=2..3' ";
  const std::string args = "size --no-widen --chip rom --budget 'max_lsb8<=2'" + grids + vec;
  const json sweep = glint_json("sweep " + vec + grids + "--node osu018 --json");
  std::optional<std::size_t> least;
  for (std::size_t i = 0; i < sweep.at("results").size(); ++i) {
    const json& row = sweep["results"][i];
    if (row["errors"]["max_abs"].get<double>() * 255 > 2) continue;
    const double um2 = row["node"]["area_um2"].get<double>();
    if (!least || um2 < sweep["results"][*least]["node"]["area_um2"].get<double>()) least = i;
  }
  ASSERT_TRUE(least) << "the test wants a configuration meeting the budget";
  const json doc = glint_json(args + " --node osu018 --objective area_um2 --top 3 --json");
  EXPECT_EQ(doc.at("objective"), "area_um2");
  const json& best = doc.at("best");
  ASSERT_TRUE(best.is_object());
  EXPECT_EQ(best.at("index"), *least);
  EXPECT_EQ(best.at("value"), sweep["results"][*least]["node"]["area_um2"]);
  for (const json& c : doc.at("top")) {
    EXPECT_GE(c.at("value").get<double>(), best.at("value").get<double>());
    EXPECT_EQ(c.at("value"), c.at("node").at("area_um2"));
  }
  const json sim = glint_json("sim " + vec + " --unit " +
                              quote(best.at("spec").get<std::string>()) + " --node osu018 --json");
  for (const char* k : {"area_um2", "critical_path_ns", "max_clock_mhz"})
    EXPECT_EQ(best.at("node").at(k), sim.at("units")[0].at("node").at(k)) << k;

  // The text (objective area_ge): area_um2 and max_clock_mhz beside it, in the family table and
  // on the overall line, as the JSON states them.
  const CliRun text = glint(args + " --node osu018");
  ASSERT_EQ(text.status, 0) << text.err;
  EXPECT_NE(text.out.find("family          area_ge       area_um2  max_clock_mhz"),
            std::string::npos)
      << text.out;
  const json area = glint_json(args + " --node osu018 --json");
  std::smatch m;
  const std::regex overall(
      R"(cheapest overall \(area_ge \S+; area_um2 (\S+), max_clock_mhz (\S+);)");
  ASSERT_TRUE(std::regex_search(text.out, m, overall)) << text.out;
  const json& node = area.at("best").at("node");
  EXPECT_NEAR(std::stod(m[1]), node.at("area_um2").get<double>(),
              1e-5 * node.at("area_um2").get<double>());
  EXPECT_NEAR(std::stod(m[2]), node.at("max_clock_mhz").get<double>(), 0.05);
  // Without --node: neither column.
  const CliRun plain = glint(args);
  ASSERT_EQ(plain.status, 0) << plain.err;
  EXPECT_EQ(plain.out.find("area_um2"), std::string::npos) << plain.out;
  EXPECT_EQ(plain.out.find("max_clock_mhz"), std::string::npos) << plain.out;
  const CliRun refused = glint(args + " --objective area_um2");
  EXPECT_EQ(refused.status, 2) << refused.err;
  EXPECT_NE(refused.err.find("--objective area_um2"), std::string::npos) << refused.err;
  EXPECT_NE(refused.err.find("--node"), std::string::npos) << refused.err;
}

}  // namespace
