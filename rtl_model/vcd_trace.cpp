#include "rtl_model/vcd_trace.h"

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <systemc>

#include "io/atomic_file.h"
#include "rtl_model/rtl_common.h"

namespace glint::rtl {

namespace fs = std::filesystem;

namespace {

// The root $scope, kept from SystemC's writer so the names (and GTKWave save files) stay the same.
const char* const kRootScope = "SystemC";

std::uint64_t now_ns() {
  return static_cast<std::uint64_t>(sc_core::sc_time_stamp().to_seconds() * 1e9 + 0.5);
}

}  // namespace

TraceControl::TraceControl(std::string vcd_path, AddTraces add_traces)
    : vcd_path_(std::move(vcd_path)), add_traces_(std::move(add_traces)), writer_(kRootScope) {
  check_output_path(vcd_path_);
  check_output_path(gtkw_path());
  temp_path_ = vcd_path_ + ".tmp." + std::to_string(::getpid()) + ".vcd";
  std::FILE* f = std::fopen(temp_path_.c_str(), "wb");
  if (!f) {
    throw OutputError("cannot write VCD '" + vcd_path_ + "': " + std::strerror(errno));
  }
  writer_.open(f);
}

TraceControl::~TraceControl() {
  if (!committed_) {
    writer_.close(0);  // the values it refers to may be gone: nothing is sampled
    std::error_code ec;
    fs::remove(temp_path_, ec);
  }
}

void TraceControl::open() {
  if (opened_) return;
  opened_ = true;
  start_ns_ = now_ns();
  add_traces_(writer_);
  writer_.header("ns", "glint clocked SystemC model (glint VcdWriter)");
  dump_pending_ = true;
}

void TraceControl::initial_dump(std::uint64_t t_ns) {
  dump_pending_ = false;
  writer_.dump_all(t_ns, clock_high_at_ns(t_ns));
}

void TraceControl::sample_reset() {
  if (tracing() && dump_pending_) initial_dump(start_ns_);
}

void TraceControl::sample_cycle(std::uint64_t rise_ns, std::uint64_t fall_ns) {
  if (!tracing()) return;
  if (dump_pending_) {
    initial_dump(start_ns_);
  } else {
    writer_.time(rise_ns);
    writer_.clock(true);
    writer_.changes();
  }
  writer_.time(fall_ns);
  writer_.clock(false);
}

void TraceControl::close() {
  if (!opened_ || closed_) return;
  // Closed before any sample (not in a normal run): the initial dump holds the values as they are.
  if (dump_pending_) initial_dump(start_ns_);
  closed_ = true;
  writer_.time(std::max(now_ns(), writer_.last_time()));  // where the trace ends
}

std::string TraceControl::gtkw_path() const {
  fs::path p(vcd_path_);
  if (p.extension() == ".vcd") return p.replace_extension(".gtkw").string();
  return vcd_path_ + ".gtkw";
}

void TraceControl::commit() {
  open();  // a window no sample reached: the VCD of the final state
  close();
  if (!writer_.close(writer_.last_time()))
    throw OutputError("cannot write VCD '" + vcd_path_ + "': " + std::strerror(errno));
  std::error_code ec;
  fs::rename(temp_path_, vcd_path_, ec);
  if (ec) {
    fs::remove(temp_path_, ec);
    throw OutputError("cannot rename VCD into '" + vcd_path_ + "': " + ec.message());
  }
  committed_ = true;
  AtomicOutputFile gtkw(gtkw_path());
  gtkw.stream() << gtkw_text(fs::absolute(vcd_path_).string(), start_ns_, signals());
  gtkw.commit(false);
}

namespace {

// GTKWave trace flags (analyzer.h): 0x20 right-justify, 0x04 decimal, 0x08 binary,
// 0x400 signed, 0x200 blank (comment/group rows), 0x800000 group begin, 0x1000000 group end.
const char* flags_of(const TracedSignal& s) {
  if (s.width == 1) return "@28";
  return s.is_signed ? "@424" : "@24";
}

std::string gtkw_name(const TracedSignal& s) {
  std::string n = std::string(kRootScope) + "." + s.name;
  if (s.width > 1) n += "[" + std::to_string(s.width - 1) + ":0]";
  return n;
}

// "top.<unit>.<stage>.<signal>" -> "<unit>"; "" for top-level signals.
std::string group_of(const std::string& name) {
  const auto a = name.find('.');
  if (a == std::string::npos) return "";
  const auto b = name.find('.', a + 1);
  if (b == std::string::npos) return "";
  return name.substr(a + 1, b - a - 1);
}

}  // namespace

std::string gtkw_text(const std::string& vcd_path, std::uint64_t start_ns,
                      const std::vector<TracedSignal>& signals) {
  std::ostringstream o;
  o << "[*]\n[*] GTKWave save file written by glint (clocked SystemC model)\n[*]\n";
  o << "[dumpfile] \"" << vcd_path << "\"\n";
  o << "[timestart] " << start_ns << "\n";
  o << "[size] 1600 1000\n[pos] -1 -1\n";
  o << "[sst_width] 260\n[signals_width] 360\n[sst_expanded] 1\n[sst_vpaned_height] 300\n";
  std::string group;
  std::string last_flags;
  for (const TracedSignal& s : signals) {
    const std::string g = group_of(s.name);
    if (g != group) {
      if (!group.empty()) o << "@1000200\n-" << group << "\n";
      if (!g.empty()) o << "@800200\n-" << g << "\n";
      group = g;
      last_flags.clear();
    }
    const std::string f = flags_of(s);
    if (f != last_flags) o << f << "\n";
    last_flags = f;
    o << gtkw_name(s) << "\n";
  }
  if (!group.empty()) o << "@1000200\n-" << group << "\n";
  return o.str();
}

}  // namespace glint::rtl
