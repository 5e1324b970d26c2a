#include "vcd_trace.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "atomic_file.h"

namespace glint::rtl {

namespace fs = std::filesystem;

TraceControl::TraceControl(std::string vcd_path, AddTraces add_traces)
    : vcd_path_(std::move(vcd_path)), add_traces_(std::move(add_traces)) {
  temp_base_ = vcd_path_ + ".tmp." + std::to_string(::getpid());
  const std::string temp = temp_base_ + ".vcd";
  std::FILE* f = std::fopen(temp.c_str(), "w");
  if (!f) {
    throw std::runtime_error("cannot write VCD '" + vcd_path_ + "': " + std::strerror(errno));
  }
  std::fclose(f);
}

TraceControl::~TraceControl() {
  close();
  if (!committed_) {
    std::error_code ec;
    fs::remove(temp_base_ + ".vcd", ec);
  }
}

void TraceControl::open() {
  if (opened_) return;
  opened_ = true;
  tf_ = sc_core::sc_create_vcd_trace_file(temp_base_.c_str());
  tf_->set_time_unit(1, sc_core::SC_NS);
  start_ns_ = static_cast<std::uint64_t>(sc_core::sc_time_stamp().to_seconds() * 1e9 + 0.5);
  add_traces_(tf_, signals_);
}

void TraceControl::close() {
  if (!tf_) return;
  sc_core::sc_close_vcd_trace_file(tf_);
  tf_ = nullptr;
}

std::string TraceControl::gtkw_path() const {
  fs::path p(vcd_path_);
  if (p.extension() == ".vcd") return p.replace_extension(".gtkw").string();
  return vcd_path_ + ".gtkw";
}

void TraceControl::commit() {
  close();
  const std::string temp = temp_base_ + ".vcd";
  std::error_code ec;
  fs::rename(temp, vcd_path_, ec);
  if (ec) {
    fs::remove(temp, ec);
    throw std::runtime_error("cannot rename VCD into '" + vcd_path_ + "': " + ec.message());
  }
  committed_ = true;
  AtomicOutputFile gtkw(gtkw_path());
  gtkw.stream() << gtkw_text(fs::absolute(vcd_path_).string(), start_ns_, signals_);
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
  std::string n = "SystemC." + s.name;
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
