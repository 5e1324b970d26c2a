// glint synth: the Verilog of `glint rtl` through Yosys, with a documented flow
// (src/cli/guide/synth.md), reported as JSON: cells by type, gate equivalents (CMOS transistors /
// 4, Yosys' `stat -tech cmos`) or a cell library's area (--liberty), flip-flops, and the logic
// depth (gates on the longest path) into each stage's registers, computed here from Yosys' JSON
// netlist.
#include <fmt/format.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <unordered_map>

#include "cli/cli.h"
#include "cli/external_tool.h"
#include "cli/rtl_input.h"
#include "cli/synth_sta.h"
#include "cost/liberty.h"
#include "cost/node.h"
#include "hdl/sdc.h"
#include "io/input_error.h"
#include "io/output_set.h"
#include "units/catalogue.h"
#include "units/lane_cost.h"

namespace glint::cli {
namespace {

struct SynthOptions {
  std::string spec;
  RtlInputOptions input;
  std::string liberty;
  std::string report;
  bool json = false;
  double clock_period_ns = hdl::kDefaultClockPeriodNs;
};

// The library `--liberty osu018` names: OSU's 0.18 um standard cells as Debian's
// qflow-tech-osu018 installs them (.ci/bootstrap).
constexpr const char* kBuiltinLibrary = "osu018";
constexpr const char* kBuiltinLibraryPath = "/usr/share/qflow/tech/osu018/osu018_stdcells.lib";

// Runs `yosys -q -l LOG -s SCRIPT` with its temporaries in `work`; throws with the log's last
// lines when it fails, and a clear message when yosys is not installed or its folder is full.
void run_yosys(const std::string& script, const std::string& log, const std::string& output,
               const std::string& work, bool user_library) {
  const int status = run_tool(
      "yosys", {"-q", "-l", log, "-s", script}, output, work,
      "synth needs Yosys: `yosys` is not on PATH (Debian package yosys; .ci/bootstrap installs "
      "it)");
  if (status != 0) {
    std::string text = read_text(log);
    if (text.size() > 2000) text = "..." + text.substr(text.size() - 2000);
    // Measured before the work folder goes: what Yosys wrote there still takes its room.
    const unsigned long long left = free_bytes(work);
    if (left < kFullDiskBytes)
      throw OutputError(fmt::format(
          "synth: yosys failed with {} KiB left on the file system of its work folder {} (a full "
          "disk: set TMPDIR to a folder with room); the end of its log:\n{}",
          left / 1024, work, text));
    // With --liberty the library is the likely cause (no buffer, no flip-flop ABC can use): bad
    // input. On the generic flow a failure is glint's own: an internal error.
    if (user_library)
      throw std::invalid_argument("--liberty: yosys could not map onto this library:\n" + text);
    throw std::runtime_error("synth: yosys failed:\n" + text);
  }
}

// A file Yosys wrote (exit status 0) that is missing or cut short: the disk of its work folder was
// full, since Yosys does not always report a failed write.
[[noreturn]] void incomplete(const std::string& file, const std::string& why) {
  throw OutputError(fmt::format(
      "synth: yosys exited 0 but its output {} is incomplete ({}); is the file system of $TMPDIR "
      "full?",
      file, why));
}

// The generic flow: Yosys' own `synth` (coarse and fine optimisation, techmap to its internal gate
// library, ABC on those gates), flattened so that depth is measured across the lane. With a
// liberty file: flip-flops mapped by dfflibmap and logic by ABC onto its cells, for the clock
// period as its delay target and, given the library's buffer (`constr`: a file naming it, the
// abc.constr below), buffered and sized: without it abc leaves a register driving a hundred
// loads unbuffered, a path no real flow keeps (schlick's merge-buffer read timed 13 ns
// unbuffered, 4.4 ns buffered). The calibration scripts map the same way
// (tests/calibration/node_flow.py, map_commands).
std::string yosys_script(const std::string& top, const std::vector<std::string>& sources,
                         const std::string& liberty, const std::string& stat,
                         const std::string& netlist, const std::string& sta_netlist,
                         long delay_target_ps, const std::string& constr) {
  std::string s;
  // The library's cells as blackboxes: the netlist then knows their ports' directions.
  if (!liberty.empty()) s += "read_liberty -lib " + liberty + "\n";
  for (const std::string& f : sources) s += "read_verilog " + f + "\n";
  s += "synth -flatten -top " + top + "\n";
  if (!liberty.empty()) {
    s += "dfflibmap -liberty " + liberty + "\n";
    s += fmt::format("abc -D {}{} -liberty {}\n", delay_target_ps,
                     constr.empty() ? "" : " -constr " + constr, liberty);
  }
  s += "opt_clean -purge\n";
  s += "tee -q -o " + stat + " stat " +
       (liberty.empty() ? std::string("-tech cmos") : "-liberty " + liberty) + "\n";
  s += "write_json " + netlist + "\n";
  if (!liberty.empty()) {
    // For OpenSTA, after the statistics: constants for undriven bits, one net per port bit,
    // registers named after the nets they drive (its paths then start and end at RTL names), and
    // assignments with a plain left-hand side (its Verilog reader takes no concatenation there).
    s += "setundef -zero\nsplitnets -ports\nopt_clean\nrename -wire\n";
    s += "write_verilog -noattr -noexpr -nohex -nodec -simple-lhs " + sta_netlist + "\n";
  }
  return s;
}

// Transistors of a flip-flop that Yosys' `stat -tech cmos` leaves unpriced (it counts $_DFF_P_ and
// $_DFF_N_ as 16 and every other flip-flop as 0, printing "N+"): the lane's pipeline registers
// hold their value under backpressure, so most are $_DFFE_ or $_SDFFE_ and would cost nothing.
// Priced as a $_DFF_P_ plus the gates folded into it: an enable is a 2:1 mux (12), a synchronous
// or asynchronous reset or set an AND (6) each. tests/calibration/yosys_flow.py prices the same.
int register_transistors(const std::string& type) {
  if (type.rfind("$_", 0) != 0) return 0;
  if (type.find("DFF") == std::string::npos && type.find("LATCH") == std::string::npos) return 0;
  if (type == "$_DFF_P_" || type == "$_DFF_N_") return 0;
  std::string name = type.substr(2);
  while (!name.empty() && name.back() == '_') name.pop_back();
  const std::size_t us = name.find('_');
  const std::string kind = name.substr(0, us);
  const std::string pins = us == std::string::npos ? "" : name.substr(us + 1);
  int t = 16;
  if (!kind.empty() && kind.back() == 'E') t += 12;
  if (kind.rfind("SDFF", 0) == 0 || kind.rfind("ALDFF", 0) == 0)
    t += 6;
  else if (kind.rfind("DFFSR", 0) == 0 || kind.rfind("DLATCHSR", 0) == 0)
    t += 12;
  else if (std::regex_match(pins, std::regex("[NP]{2}[01][NP]?")))
    t += 6;
  return t;
}

// Yosys' own flip-flops and latches ($_DFF_P_, $_SDFFE_PP0P_, $_DLATCH_P_, ...) or a library's.
bool is_register(const std::string& type, const std::set<std::string>& library_registers) {
  if (!type.empty() && type[0] == '$')
    return type.find("DFF") != std::string::npos || type.find("LATCH") != std::string::npos;
  return library_registers.count(type) > 0;
}

// The stage a register belongs to: `datapath.<stage>_<name>` (or in_t/in_group: "in") of the
// unit's layout; every other register is the lane's (comparator, credits, merge buffer).
std::string stage_of(const std::string& net, const StageLayout& layout) {
  const std::string prefix = "datapath.";
  if (net.compare(0, prefix.size(), prefix) != 0) return "lane";
  const std::string name = net.substr(prefix.size());
  std::string best = "datapath (carried)";
  std::size_t best_len = 0;
  for (const Stage& s : layout.stages())
    if (name.size() > s.name.size() && name.compare(0, s.name.size(), s.name) == 0 &&
        name[s.name.size()] == '_' && s.name.size() > best_len) {
      best = s.name;
      best_len = s.name.size();
    }
  return best;
}

struct DepthReport {
  nlohmann::json stages = nlohmann::json::array();
  int max_depth = 0;
  long flip_flops = 0;
  std::map<std::string, long> cell_types;
  long cells = 0;
};

// Logic depth from Yosys' JSON netlist: every combinational cell adds one level; register outputs,
// module inputs and constants are level 0. Per stage: the deepest input of its registers.
DepthReport analyse_netlist(const nlohmann::json& netlist, const std::string& top,
                            const StageLayout& layout,
                            const std::set<std::string>& library_registers) {
  const nlohmann::json& m = netlist.at("modules").at(top);
  struct Cell {
    std::vector<long> inputs, outputs;
    bool reg = false;
    std::string type;
  };
  std::vector<Cell> cells;
  std::unordered_map<long, std::size_t> driver;  // bit -> combinational cell
  DepthReport r;
  for (const auto& [name, c] : m.at("cells").items()) {
    Cell cell;
    cell.type = c.at("type").get<std::string>();
    cell.reg = is_register(cell.type, library_registers);
    if (!c.contains("port_directions"))
      throw std::runtime_error("synth: cell type " + cell.type + " has no port directions");
    const nlohmann::json& dirs = c.at("port_directions");
    for (const auto& [port, bits] : c.at("connections").items()) {
      const bool out = dirs.at(port) == "output";
      for (const auto& b : bits) {
        if (!b.is_number()) continue;  // a constant "0"/"1"/"x"
        (out ? cell.outputs : cell.inputs).push_back(b.get<long>());
      }
      // (A register's clock is an input of depth 0: it changes no depth.)
    }
    ++r.cell_types[cell.type];
    ++r.cells;
    if (cell.reg) ++r.flip_flops;
    if (!cell.reg)
      for (long b : cell.outputs) driver[b] = cells.size();
    cells.push_back(std::move(cell));
  }
  std::unordered_map<long, int> depth;
  // Iterative depth-first evaluation (a deep adder chain would overflow a recursive one).
  const auto depth_of = [&](long bit) {
    std::vector<std::pair<long, bool>> stack{{bit, false}};
    while (!stack.empty()) {
      auto [b, expanded] = stack.back();
      stack.pop_back();
      if (depth.count(b)) continue;
      const auto it = driver.find(b);
      if (it == driver.end()) {
        depth[b] = 0;
        continue;
      }
      const Cell& c = cells[it->second];
      if (!expanded) {
        stack.push_back({b, true});
        for (long in : c.inputs)
          if (!depth.count(in)) stack.push_back({in, false});
        continue;
      }
      int d = 0;
      for (long in : c.inputs) d = std::max(d, depth.count(in) ? depth[in] : 0);
      for (long out : c.outputs) depth[out] = d + 1;
    }
    return depth[bit];
  };
  // Register names: the public net names of their output bits.
  std::unordered_map<long, std::string> name_of;
  for (const auto& [name, n] : m.at("netnames").items()) {
    if (n.value("hide_name", 0) != 0) continue;
    for (const auto& b : n.at("bits"))
      if (b.is_number()) name_of.emplace(b.get<long>(), name);
  }
  std::map<std::string, std::pair<long, int>> per_stage;  // flip-flops, depth
  for (const Cell& c : cells) {
    if (!c.reg) continue;
    int d = 0;
    for (long in : c.inputs) d = std::max(d, depth_of(in));
    std::string stage = "lane";
    for (long out : c.outputs) {
      const auto it = name_of.find(out);
      if (it != name_of.end()) {
        stage = stage_of(it->second, layout);
        break;
      }
    }
    auto& e = per_stage[stage];
    ++e.first;
    e.second = std::max(e.second, d);
  }
  // The lane's outputs (the merge buffer's head is flow-through).
  int out_depth = 0;
  for (const auto& [name, port] : m.at("ports").items())
    if (port.at("direction") == "output")
      for (const auto& b : port.at("bits"))
        if (b.is_number()) out_depth = std::max(out_depth, depth_of(b.get<long>()));
  for (const Stage& s : layout.stages()) {
    const auto it = per_stage.find(s.name);
    if (it == per_stage.end()) continue;
    r.stages.push_back({{"stage", s.name},
                        {"positions", {s.first, s.last}},
                        {"flip_flops", it->second.first},
                        {"depth", it->second.second}});
    r.max_depth = std::max(r.max_depth, it->second.second);
    per_stage.erase(it);
  }
  for (const auto& [stage, e] : per_stage) {
    r.stages.push_back({{"stage", stage}, {"flip_flops", e.first}, {"depth", e.second}});
    r.max_depth = std::max(r.max_depth, e.second);
  }
  r.stages.push_back({{"stage", "lane outputs"}, {"flip_flops", 0}, {"depth", out_depth}});
  r.max_depth = std::max(r.max_depth, out_depth);
  return r;
}

int run_synth(const SynthOptions& o) {
  const UnitSpec spec = parse_unit_spec(o.spec);
  check_rtl_input(o.input);
  if (options_only()) return kExitOk;
  OutputSet out;
  if (!o.input.vectors.empty()) out.add_input("--vectors", o.input.vectors);
  if (!o.input.scene.empty()) out.add_input("--scene", o.input.scene);
  // --liberty osu018: the built-in library, unless a file of that name is there.
  const bool builtin = o.liberty == kBuiltinLibrary && ::access(o.liberty.c_str(), F_OK) != 0;
  const std::string library_file = builtin ? kBuiltinLibraryPath : o.liberty;
  if (builtin && ::access(library_file.c_str(), R_OK) != 0)
    throw std::invalid_argument(
        fmt::format("--liberty {}: the built-in library {} is not installed (Debian package "
                    "qflow-tech-osu018; .ci/bootstrap installs it)",
                    kBuiltinLibrary, library_file));
  if (!library_file.empty()) {
    out.add_input("--liberty", library_file);
    if (::access(library_file.c_str(), R_OK) != 0)
      throw InputError(library_file, 0, "file", "cannot be read");
  }
  if (o.json) out.claim_stdout("--json");
  OutputFile* report = o.report.empty() ? nullptr : &out.add("--report", o.report);
  const bool progress = isatty(STDERR_FILENO);

  const RtlDesign d =
      make_rtl_design(spec, rtl_header(o.input), rtl_input_name(o.input), o.input.chip);
  const std::string top = "glint_" + d.unit->name() + "_lane";
  WorkFolder work;
  const std::string lane = work.file(top + ".v");
  const std::string datapath = work.file("glint_" + d.unit->name() + "_datapath.v");
  const std::string script = work.file("synth.ys"), log = work.file("yosys.log");
  const std::string stat = work.file("stat.txt"), netlist = work.file("netlist.json");
  write_text(lane, d.lane_verilog);
  write_text(datapath, d.datapath_verilog);
  std::string liberty = library_file;
  if (!liberty.empty() && liberty.front() != '/') {
    char cwd[4096];
    if (::getcwd(cwd, sizeof cwd) != nullptr) liberty = std::string(cwd) + "/" + liberty;
  }
  const std::string sta_netlist = liberty.empty() ? "" : work.file("netlist.v");
  const std::string library_text = liberty.empty() ? "" : read_text(liberty);
  const std::string buffer = liberty_buffer(library_text);
  const long delay_target_ps = std::lround(o.clock_period_ns * 1000);
  std::string constr;
  if (!buffer.empty()) {
    // The buffer drives the lane's inputs; its outputs carry no load, as in the lane's SDC.
    constr = work.file("abc.constr");
    write_text(constr, "set_driving_cell " + buffer + "\nset_load 0\n");
  }
  write_text(script, yosys_script(top, {lane, datapath}, liberty, stat, netlist, sta_netlist,
                                  delay_target_ps, constr));
  if (progress)
    std::fprintf(stderr, "synth: yosys on %s (%s)...\n", d.unit->canonical_spec().c_str(),
                 liberty.empty() ? "generic gates" : liberty.c_str());
  const auto t0 = std::chrono::steady_clock::now();
  run_yosys(script, log, work.file("yosys.out"), work.path(), !liberty.empty());
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (progress) std::fprintf(stderr, "synth: done in %.1f s; reading the netlist\n", seconds);

  // Yosys's exit status does not prove its files whole: the netlist must parse and hold the top
  // module, and the statistics must count the cells the netlist holds.
  const std::string stat_text = read_text(stat);
  nlohmann::json parsed;
  try {
    parsed = nlohmann::json::parse(read_text(netlist));
  } catch (const nlohmann::json::parse_error& e) {
    incomplete(netlist, e.what());
  }
  if (!parsed.contains("modules") || !parsed["modules"].contains(top))
    incomplete(netlist, "no module " + top);
  const DepthReport dr = analyse_netlist(
      parsed, top, d.unit->stages(),
      liberty.empty() ? std::set<std::string>{} : liberty_registers(read_text(liberty)));
  {
    static const std::regex cells(R"(Number of cells:\s+([0-9]+))");
    std::smatch m;
    if (!std::regex_search(stat_text, m, cells)) incomplete(stat, "no cell count");
    if (std::stol(m[1]) != dr.cells)
      incomplete(stat, fmt::format("{} cells, the netlist has {}", m[1].str(), dr.cells));
  }
  nlohmann::json j{{"glint_synth_report", 2},
                   {"unit", d.unit->name()},
                   {"spec", d.unit->canonical_spec()},
                   {"flow", liberty.empty() ? "generic" : "liberty"},
                   {"yosys_seconds", seconds},
                   {"cells", dr.cells},
                   {"cell_types", dr.cell_types},
                   {"flip_flops", dr.flip_flops},
                   {"depth", dr.max_depth},
                   {"stages", dr.stages}};
  std::smatch match;
  if (liberty.empty()) {
    static const std::regex transistors(R"(Estimated number of transistors:\s+([0-9]+))");
    if (!std::regex_search(stat_text, match, transistors))
      incomplete(stat, "no transistor estimate");
    const double t = std::stod(match[1]);
    double added = 0;
    for (const auto& [type, n] : dr.cell_types)
      added += static_cast<double>(register_transistors(type)) * n;
    j["transistors"] = t + added;
    j["transistors_yosys"] = t;  // stat -tech cmos alone: flip-flops with enable or reset at 0
    j["ge"] = (t + added) / 4;
  } else {
    j["liberty"] = o.liberty;
    j["liberty_file"] = library_file;
    static const std::regex area(R"(Chip area for (?:top )?module '[^']*':\s+([0-9.eE+-]+))");
    if (!std::regex_search(stat_text, match, area)) incomplete(stat, "no chip area");
    const double um2 = std::stod(match[1]);
    j["area_um2"] = um2;
    j["delay_target_ps"] = delay_target_ps;
    j["buffer_cell"] = buffer.empty() ? nlohmann::json() : nlohmann::json(buffer);
    const Nand2 nand2 = liberty_nand2(library_text);
    if (!nand2.cell.empty()) {
      j["nand2_cell"] = nand2.cell;
      j["nand2_area_um2"] = nand2.area;
      j["nand2_equivalents"] = um2 / nand2.area;
    }
    if (progress) std::fprintf(stderr, "synth: OpenSTA on the mapped netlist...\n");
    StaPath path;
    try {
      path = run_sta(work, liberty, sta_netlist, top, hdl::lane_sdc(d.lane, o.clock_period_ns),
                     o.clock_period_ns);
    } catch (const std::runtime_error& e) {
      // A library OpenSTA cannot time (no delay tables, no thresholds: an area-only library such
      // as tests/rtl/tiny.lib) still gives the area: the report says why there is no timing. Any
      // other failure is glint's own.
      const std::string why = e.what();
      if (why.find(liberty) == std::string::npos) throw;
      j["timing"] = nullptr;
      j["timing_unavailable"] = why;
      path.period_ns = 0;
    }
    if (path.period_ns > 0) {
      const auto point = [&](const PathPoint& p) {
        std::string stage = p.kind == "register"     ? stage_of(p.name, d.unit->stages())
                            : p.kind == "input port" ? "lane inputs"
                                                     : "lane outputs";
        return nlohmann::json{{"name", p.name}, {"kind", p.kind}, {"stage", stage}};
      };
      j["timing"] = {{"clock_period_ns", path.period_ns},
                     {"slack_ns", path.slack_ns},
                     {"arrival_ns", path.arrival_ns},
                     {"setup_ns", path.setup_ns},
                     {"critical_path_ns", path.min_period_ns()},
                     {"max_clock_mhz", 1000.0 / path.min_period_ns()},
                     {"startpoint", point(path.start)},
                     {"endpoint", point(path.end)}};
    }
    // The built-in node: the cost proxy's own figures for it beside the measured ones, from the
    // constants calibrated on it (cost/node.h).
    if (const NodeConstants* node = find_node(o.liberty)) {
      const nlohmann::json n = unit_cost(*d.unit).node_json();
      if (n.at("node") == node->name)
        j["proxy"] = {{"node", n.at("node")},
                      {"area_um2", n.at("area_um2")},
                      {"critical_path_ns", n.at("critical_path_ns")},
                      {"critical_path", n.at("critical_path")},
                      {"max_clock_mhz", n.at("max_clock_mhz")}};
    }
  }
  if (report) report->stream() << j.dump(2) << "\n";
  out.commit();
  if (o.json) {
    print_json(j);
    return kExitOk;
  }
  std::string area = fmt::format("{:.0f} GE", j.value("ge", 0.0));
  if (!liberty.empty()) {
    area = fmt::format("{:.0f} um2", j["area_um2"].get<double>());
    if (j.contains("nand2_equivalents"))
      area += fmt::format(" = {:.0f} {} equivalents", j["nand2_equivalents"].get<double>(),
                          j["nand2_cell"].get<std::string>());
  }
  std::cout << fmt::format("{}: {} cells, {} flip-flops, {}, logic depth {} (yosys {:.1f} s)\n",
                           j["spec"].get<std::string>(), dr.cells, dr.flip_flops, area,
                           dr.max_depth, seconds);
  if (j.contains("delay_target_ps"))
    std::cout << fmt::format(
        "  mapped by abc for a {} ps delay target{}\n", j["delay_target_ps"].get<long>(),
        j["buffer_cell"].is_null()
            ? std::string(" (the library has no timed buffer: no buffering or sizing)")
            : ", high fan-out nets buffered with " + j["buffer_cell"].get<std::string>());
  if (j.contains("timing_unavailable"))
    std::cout << "  no timing: " << j["timing_unavailable"].get<std::string>() << "\n";
  if (j.contains("timing") && !j["timing"].is_null()) {
    const nlohmann::json& t = j["timing"];
    std::cout << fmt::format(
        "  critical path {:.3f} ns ({:.0f} MHz): {} ({}) -> {} ({}); slack {:.3f} ns at a {:g} ns "
        "clock\n",
        t["critical_path_ns"].get<double>(), t["max_clock_mhz"].get<double>(),
        t["startpoint"]["name"].get<std::string>(), t["startpoint"]["stage"].get<std::string>(),
        t["endpoint"]["name"].get<std::string>(), t["endpoint"]["stage"].get<std::string>(),
        t["slack_ns"].get<double>(), t["clock_period_ns"].get<double>());
  }
  if (j.contains("proxy"))
    std::cout << fmt::format("  the cost proxy at {}: {:.0f} um2, critical path {:.2f} ns ({})\n",
                             j["proxy"]["node"].get<std::string>(),
                             j["proxy"]["area_um2"].get<double>(),
                             j["proxy"]["critical_path_ns"].get<double>(),
                             j["proxy"]["critical_path"].get<std::string>());
  for (const auto& s : dr.stages)
    std::cout << fmt::format("  {:<20} {:>6} flip-flops  depth {:>4}\n",
                             s["stage"].get<std::string>(), s["flip_flops"].get<long>(),
                             s["depth"].get<int>());
  return kExitOk;
}

}  // namespace

void add_synth_command(CLI::App& app, int& status) {
  auto o = std::make_shared<SynthOptions>();
  CLI::App* sub = app.add_subcommand(
      "synth",
      "Synthesize one lane of a unit with Yosys: cells, gate equivalents, flip-flops and "
      "logic depth per stage");
  sub->add_option("SPEC", o->spec, "Unit SPEC NAME[:key=value,...] (keys: glint units)")
      ->required();
  add_rtl_input_options(sub, o->input);
  sub->add_option("--liberty", o->liberty,
                  "Map onto this cell library (dfflibmap, abc -liberty for the clock period, "
                  "buffered and sized by the library's smallest buffer; `osu018`: OSU's 0.18 um "
                  "cells, installed by .ci/bootstrap) and report its area in um2 and NAND2 "
                  "equivalents, and OpenSTA's critical path under the lane's SDC");
  add_clock_period_option(sub, o->clock_period_ns);
  sub->add_option("--report", o->report, "Also write the JSON report to this file");
  sub->add_flag("--json", o->json, "Print the report as one JSON document on stdout");
  sub->callback([o, &status] { status = guarded([&] { return run_synth(*o); }); });
}

}  // namespace glint::cli
