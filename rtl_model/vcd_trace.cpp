#include "rtl_model/vcd_trace.h"

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <systemc>

#include "io/output_set.h"
#include "io/signal_cleanup.h"
#include "rtl_model/clocked_sim.h"
#include "rtl_model/fst_read_back.h"
#include "rtl_model/rtl_common.h"
#include "rtl_model/tool_process.h"

namespace glint::rtl {

namespace fs = std::filesystem;

namespace {

// The root $scope, kept from SystemC's writer so the names (and GTKWave save files) stay the same.
const char* const kRootScope = "SystemC";

std::uint64_t now_ns() {
  return static_cast<std::uint64_t>(sc_core::sc_time_stamp().to_seconds() * 1e9 + 0.5);
}

}  // namespace

// vcd2fst reading the VCD from a pipe ("-v -": stdin) and writing <folder>/trace.fst, then fst2vcd
// reading that back for the check (fst_read_back.h), where
// <folder> is the output's private temporary folder (OutputSet::add_produced): vcd2fst's FST
// writer keeps a side file (<fst>.hier) next to its output while it runs, and the folder keeps all
// of it out of the user's. The process and every file it makes there are registered with
// signal_cleanup.h: a termination signal kills it before the files and the folder are removed.
class TraceControl::Vcd2Fst {
 public:
  Vcd2Fst(const std::string& target, const std::string& folder) : target_(target) {
    fst_ = (fs::path(folder) / "trace.fst").string();
    log_ = (fs::path(folder) / "vcd2fst.log").string();
    check_log_ = (fs::path(folder) / "fst2vcd.log").string();
    for (const std::string& f : {fst_, fst_ + ".hier", log_, check_log_})
      handles_.push_back(register_cleanup(CleanupKind::kFile, f));
    try {
      start();
    } catch (...) {
      // No destructor runs for a half-built object: undo here what it would.
      kill();
      release();
      throw;
    }
  }

  ~Vcd2Fst() {
    kill();
    if (pipe_) std::fclose(pipe_);  // only if never handed over (a constructor failure)
    release();
  }

  Vcd2Fst(const Vcd2Fst&) = delete;
  Vcd2Fst& operator=(const Vcd2Fst&) = delete;

  // The pipe's write end, for the VcdWriter (which closes it).
  std::FILE* take_pipe() {
    std::FILE* p = pipe_;
    pipe_ = nullptr;
    return p;
  }

  // Stops vcd2fst at once (a failed run: its partial output goes with the folder).
  void kill() {
    if (pid_ <= 0) return;
    ::kill(pid_, SIGKILL);
    wait();
  }

  // After the VCD's pipe was closed (`vcd_ok`: every write succeeded; `written`: what it held):
  // waits for vcd2fst, reads its FST back (fst_read_back.h) and returns it. Throws OutputError
  // naming vcd2fst and the output otherwise.
  std::string finish(bool vcd_ok, const VcdCounts& written) {
    if (pid_ <= 0) fail("vcd2fst is not running");
    const int status = wait();
    const bool exited_ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    std::error_code ec;
    if (!vcd_ok || !exited_ok || !fs::is_regular_file(fst_, ec) || fs::file_size(fst_, ec) == 0) {
      std::string why = WIFEXITED(status)     ? "exit status " + std::to_string(WEXITSTATUS(status))
                        : WIFSIGNALED(status) ? "signal " + std::to_string(WTERMSIG(status))
                                              : "status " + std::to_string(status);
      fail("vcd2fst failed (" + why + ")" + messages());
    }
    const std::string incomplete = check_fst(fst_, check_log_, target_, written);
    if (!incomplete.empty()) fail(incomplete);
    return fst_;
  }

 private:
  // vcd2fst reading a new pipe, whose write end becomes pipe_.
  void start() {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) fail(std::string("pipe: ") + std::strerror(errno));
    int err = 0;
    {
      // Signals held from the start to the registration: the process is never unregistered.
      SignalShield shield;
      err = spawn(fds[0]);
      if (err == 0) pid_handle_ = register_cleanup_process(pid_);
    }
    ::close(fds[0]);  // the child's copy is its stdin
    if (err != 0) {
      ::close(fds[1]);
      fail(std::string("cannot run vcd2fst (") + std::strerror(err) +
           "); it comes with the Debian package gtkwave");
    }
    pipe_ = ::fdopen(fds[1], "wb");
    if (!pipe_) {
      const int e = errno;
      ::close(fds[1]);
      fail(std::string("fdopen: ") + std::strerror(e));
    }
  }

  // vcd2fst reads the pipe, its stdout discarded, its stderr kept for the error message
  // (tool_process.h).
  int spawn(int read_fd) {
    ToolStart start;
    start.argv = {"vcd2fst", "-v", "-", "-f", fst_};
    start.stdin_fd = read_fd;
    start.log = log_;
    start.default_sigxfsz = true;  // vcd2fst writes the FST and may not check its writes
    return start_tool(start, pid_);
  }

  int wait() {  // pid_ > 0
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    release_cleanup(pid_handle_);
    pid_handle_ = -1;
    pid_ = -1;
    return status;
  }

  void release() noexcept {
    for (int h : handles_) release_cleanup(h);
    handles_.clear();
    release_cleanup(pid_handle_);
    pid_handle_ = -1;
  }

  // The start of vcd2fst's stderr, for the error message.
  std::string messages() const {
    const std::string text = log_start(log_, 500);
    return text.empty() ? "" : ": " + text;
  }

  [[noreturn]] void fail(const std::string& why) const { throw OutputError(target_ + ": " + why); }

  std::string target_, fst_, log_, check_log_;
  pid_t pid_ = -1;
  std::FILE* pipe_ = nullptr;
  std::vector<int> handles_;
  int pid_handle_ = -1;
};

bool is_fst_path(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".fst";
}

TraceControl::TraceControl(const TraceOutputs& outputs, AddTraces add_traces)
    : vcd_path_(outputs.path),
      fst_(outputs.fst),
      outputs_(outputs),
      add_traces_(std::move(add_traces)),
      writer_(kRootScope) {
  if (fst_) {
    vcd2fst_ = std::make_unique<Vcd2Fst>(what(), outputs.trace->work_folder());
    writer_.open(vcd2fst_->take_pipe(), /*pipe=*/true);
    writer_.tally();  // what the FST must hold when read back
    return;
  }
  // The writer buffers on its own: a descriptor of its own on the output's temporary (or on
  // standard output), closed by the writer; the OutputSet fsyncs and renames the file.
  const int fd = outputs.trace->dup_fd();
  std::FILE* f = ::fdopen(fd, "wb");
  if (!f) {
    const int err = errno;
    ::close(fd);
    throw OutputError(what() + ": " + std::strerror(err));
  }
  writer_.open(f);
}

TraceControl::~TraceControl() {
  if (!committed_) {
    if (vcd2fst_) vcd2fst_->kill();  // first: the writer's last words then go nowhere, at once
    writer_.close(0);                // the values it refers to may be gone: nothing is sampled
    vcd2fst_.reset();
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

std::string TraceControl::what() const {
  const std::string& option = outputs_.trace->option();
  return (option.empty() ? std::string(fst_ ? "FST" : "VCD") : option) + " " + vcd_path_;
}

std::string TraceControl::gtkw_path(const std::string& path) {
  fs::path p(path);
  if (p.extension() == ".vcd" || is_fst_path(path)) return p.replace_extension(".gtkw").string();
  return path + ".gtkw";
}

void TraceControl::commit() {
  open();  // a window no sample reached: the trace of the final state
  close();
  const bool written = writer_.close(writer_.last_time());
  if (fst_) {
    // Waits for vcd2fst; throws with its messages.
    outputs_.trace->set_produced(vcd2fst_->finish(written, writer_.counts()));
  } else if (!written) {
    const int err = writer_.error();
    throw OutputError(what() + ": write failed: " + (err != 0 ? std::strerror(err) : "I/O error"));
  }
  committed_ = true;
  if (outputs_.save)
    outputs_.save->stream() << gtkw_text(fs::absolute(vcd_path_).string(), start_ns_, signals());
}

namespace {

// GTKWave trace flags (analyzer.h: 1 << TR_*_B), written as "@<hex>" before the traces they apply
// to; GTKWave keeps the last one for every following trace.
constexpr std::uint64_t kDec = 0x4, kBin = 0x8, kRjustify = 0x20, kBlank = 0x200, kSigned = 0x400;
constexpr std::uint64_t kCollapsed = 0x1000, kAnalogStep = 0x8000;
constexpr std::uint64_t kAnalogExtend = 0x20000;  // TR_ANALOG_BLANK_STRETCH: one more row
constexpr std::uint64_t kClosed = 0x400000, kGroupBegin = 0x800000, kGroupEnd = 0x1000000;
constexpr std::uint64_t kFixedPoint = 0x40000000;  // TR_FPDECSHIFT: raw / 2^[fpshift_count]

// The window GTKWave opens ([size]) and its left panes: the tree of scopes ([sst_width]; collapsed,
// since expanded it takes ~280 pixels whatever [sst_width] asks) and the names with their values
// at the marker ([signals_width]: "hast/comparator/tau=0.870941162109375" fits). The wave pane gets
// the rest less ~24 pixels of pane handles, borders and the vertical scroll bar (measured under
// Xvfb with Debian's gtkwave 3.3.118, GTK 3).
constexpr int kWindowWidth = 1600, kWindowHeight = 1000, kSstWidth = 150, kSignalsWidth = 440;
constexpr int kWavePaneWidth = kWindowWidth - kSstWidth - kSignalsWidth - 24;
// Rows an analog wave spans (the trace's own plus kAnalogExtend rows).
constexpr int kAnalogRows = 4;
// GTKWave's rainbow colours ([color] N): 2 orange, 5 blue.
constexpr int kColourInput = 2, kColourResult = 5;

// GTKWave's zoom (the "*" line): a frame of 200 pixels spans zoombase^-zoom time units (calczoom;
// zoombase 2 by default); the VCD's unit is 1 ns.
double gtkw_zoom(double span_ns, int pixels) {
  return -std::log2(span_ns * 200.0 / pixels);
}

bool is_fixed_point(const TracedSignal& s) {
  // GTKWave's shift is 0..255 and its arithmetic 64-bit; a format outside (none of glint's: widths
  // are at most 62) shows raw.
  return s.width > 1 && s.frac_bits > 0 && s.frac_bits < 64;
}

std::uint64_t flags_of(const TracedSignal& s) {
  if (s.width == 1) return kRjustify | kBin;
  std::uint64_t f = kRjustify | kDec;
  if (s.is_signed) f |= kSigned;
  if (is_fixed_point(s)) f |= kFixedPoint;
  return f;
}

// The VCD name as GTKWave finds it: root scope, dotted path, vectors with their bit range.
std::string gtkw_name(const TracedSignal& s) {
  std::string n = std::string(kRootScope) + "." + s.name;
  if (s.width > 1) n += "[" + std::to_string(s.width - 1) + ":0]";
  return n;
}

// What the signal pane shows: the name below "top." with '/' between the levels, e.g.
// "hast/mul2/power". Not '.': GTKWave cuts aliases like names down to their last hier_max_level
// '.'-separated components (analyzer.c, hier_extract), and Debian's gtkwave defaults to 1, which
// would leave "power". '/' is also the hierarchy separator of synthesis and timing tools.
std::string alias_of(const TracedSignal& s) {
  const std::string top = "top.";
  std::string a = s.name.compare(0, top.size(), top) == 0 ? s.name.substr(top.size()) : s.name;
  std::replace(a.begin(), a.end(), '.', '/');
  return a;
}

// "uq1.15" / "sq2.14" (QFormat::name: integer bits include the sign bit). Its '.' survives
// hier_extract, which skips a trailing ".<digits>" component.
std::string format_name(const TracedSignal& s) {
  return std::string(s.is_signed ? "sq" : "uq") + std::to_string(s.width - s.frac_bits) + "." +
         std::to_string(s.frac_bits);
}

// "top.<unit>.<stage>.<signal>" -> "<unit>"; "" for top-level signals.
std::string group_of(const std::string& name) {
  const auto a = name.find('.');
  if (a == std::string::npos) return "";
  const auto b = name.find('.', a + 1);
  if (b == std::string::npos) return "";
  return name.substr(a + 1, b - a - 1);
}

// The save file's trace list, with the flags line written only when the flags change (as GTKWave
// writes its own save files).
class TraceList {
 public:
  explicit TraceList(std::ostream& o) : o_(o) {}

  void flags(std::uint64_t f) {
    if (f == last_) return;
    o_ << "@" << std::hex << f << std::dec << "\n";
    last_ = f;
  }
  // One trace shown under `alias`.
  void trace(const TracedSignal& s, std::uint64_t f, const std::string& alias, int colour = 0) {
    flags(f);
    if (colour > 0) o_ << "[color] " << colour << "\n";
    // The shift is GTKWave's current default for every trace added after it: written before each
    // fixed-point trace so a trace's line never depends on the ones above it.
    if (f & kFixedPoint) o_ << "[fpshift_count] " << s.frac_bits << "\n";
    o_ << "+{" << alias << "} " << gtkw_name(s) << "\n";
  }
  void analog(const TracedSignal& s, int colour) {
    trace(s, flags_of(s) | kAnalogStep, alias_of(s), colour);
    flags(kAnalogExtend);
    for (int r = 1; r < kAnalogRows; ++r) o_ << "-\n";
  }
  void group_begin(const std::string& name, bool closed = false) {
    flags(kGroupBegin | kBlank | (closed ? kClosed : 0));
    o_ << "-" << name << "\n";
  }
  void group_end(const std::string& name, bool closed = false) {
    flags(kGroupEnd | kBlank | (closed ? kClosed | kCollapsed : 0));
    o_ << "-" << name << "\n";
  }

 private:
  std::ostream& o_;
  std::uint64_t last_ = ~std::uint64_t{0};
};

// One unit's group: analog t and result, every signal, the raw bits of the fixed-point ones.
void write_group(TraceList& list, const std::string& unit,
                 const std::vector<const TracedSignal*>& sigs) {
  list.group_begin(unit);
  const std::string p = "top." + unit + ".";
  for (const TracedSignal* s : sigs) {
    if (s->name == p + "source.t") list.analog(*s, kColourInput);
  }
  for (const TracedSignal* s : sigs) {
    if (s->name == p + "sink.result") list.analog(*s, kColourResult);
  }
  for (const TracedSignal* s : sigs) list.trace(*s, flags_of(*s), alias_of(*s));
  bool any_raw = false;
  for (const TracedSignal* s : sigs) any_raw = any_raw || is_fixed_point(*s);
  if (any_raw) {
    const std::string raw = unit + " raw";
    list.group_begin(raw, /*closed=*/true);
    for (const TracedSignal* s : sigs) {
      if (!is_fixed_point(*s)) continue;
      list.trace(*s, flags_of(*s) & ~kFixedPoint,
                 alias_of(*s) + "[" + std::to_string(s->width - 1) + ":0] " + format_name(*s));
    }
    list.group_end(raw, /*closed=*/true);
  }
  list.group_end(unit);
}

}  // namespace

std::string gtkw_text(const std::string& dump_path, std::uint64_t start_ns,
                      const std::vector<TracedSignal>& signals) {
  // The view: kGtkwViewCycles periods from the window's start; the marker on its first rising
  // edge (the first cycle_time_ns at or after start_ns).
  const std::uint64_t period = cycle_time_ns(1) - cycle_time_ns(0);
  const std::uint64_t first_edge =
      start_ns <= cycle_time_ns(0)
          ? cycle_time_ns(0)
          : cycle_time_ns((start_ns - cycle_time_ns(0) + period - 1) / period);
  const double zoom = gtkw_zoom(static_cast<double>(kGtkwViewCycles * period), kWavePaneWidth);

  std::ostringstream o;
  o << "[*]\n[*] GTKWave save file written by glint (clocked SystemC model): " << kGtkwViewCycles
    << " clock periods from " << start_ns << " ns, marker on the first rising edge\n[*]\n";
  o << "[dumpfile] \"" << dump_path << "\"\n";
  o << "[timestart] " << start_ns << "\n";
  o << "[size] " << kWindowWidth << " " << kWindowHeight << "\n[pos] -1 -1\n";
  char zoom_line[64];
  std::snprintf(zoom_line, sizeof zoom_line, "*%.6f %llu", zoom,
                static_cast<unsigned long long>(first_edge));
  o << zoom_line << "\n";
  o << "[treeopen] " << kRootScope << ".\n[treeopen] " << kRootScope << ".top.\n";
  o << "[sst_width] " << kSstWidth << "\n[signals_width] " << kSignalsWidth << "\n";
  o << "[sst_expanded] 0\n[sst_vpaned_height] 300\n";

  TraceList list(o);
  // Signals in registration order; each unit's (contiguous) run becomes its group.
  for (std::size_t i = 0; i < signals.size();) {
    const std::string g = group_of(signals[i].name);
    if (g.empty()) {
      list.trace(signals[i], flags_of(signals[i]), alias_of(signals[i]));
      ++i;
      continue;
    }
    std::vector<const TracedSignal*> sigs;
    for (; i < signals.size() && group_of(signals[i].name) == g; ++i) sigs.push_back(&signals[i]);
    write_group(list, g, sigs);
  }
  return o.str();
}

}  // namespace glint::rtl
