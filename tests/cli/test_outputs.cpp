// Outputs that cannot be turned against the user (issue 11, item 2): temporaries made exclusively
// under unpredictable names beside the target; symbolic links, devices, FIFOs and folders refused
// (lstat); "-" for standard output on every stream, and two writers of standard output refused;
// a failed or interrupted (SIGINT, SIGTERM) run leaves no partial file, no temporary, and every
// existing output as it was (all outputs or none); permissions of a replaced file kept; two outputs
// on one file (under any spelling) refused; a full disk (RLIMIT_FSIZE) is exit 2 with nothing
// written; a clocked run reads standard input and pipes.
//
// The library (OutputSet) is tested in this process; the command line through the real glint
// binary, started with fork/exec so that the tests can signal it and limit its file size.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <thread>
#include <vector>

#include "io/atomic_file.h"
#include "io/output_set.h"
#include "test_support.h"

namespace glint {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;
using test::read_file;
using test::TempDir;

const std::string kGlint = GLINT_BINARY_DIR "/glint";
const std::string kTraces = GLINT_SOURCE_DIR "/traces";
const std::string kBasic = kTraces + "/phong_basic.vec";
const std::string kSmallScene = kTraces + "/scenes/small.json";

void write_text(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
  ASSERT_TRUE(out.good()) << p;
}

mode_t mode_of(const fs::path& p) {
  struct stat st {};
  EXPECT_EQ(::lstat(p.c_str(), &st), 0) << p;
  return st.st_mode & 07777;
}

// Every entry of a folder with its content (files) or kind, recursively: "what the run left".
std::map<std::string, std::string> snapshot(const fs::path& dir) {
  std::map<std::string, std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string rel = fs::relative(e.path(), dir).string();
    if (e.is_symlink()) {
      out[rel] = "link -> " + fs::read_symlink(e.path()).string();
    } else if (e.is_regular_file()) {
      out[rel] = read_file(e.path());
    } else {
      out[rel] = e.is_directory() ? "<folder>" : "<special>";
    }
  }
  return out;
}

std::vector<std::string> temporaries(const fs::path& dir) {
  std::vector<std::string> out;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos)
      out.push_back(e.path().string());
  return out;
}

// A vector header with one Phong material `m`; rows are "t m".
const char* const kHeader =
    "glint-vectors 1\neps 1e-3\nlights 1\nmaterial m specular=1,1,1 shininess=40 lobe=phong\n"
    "columns t material\ndata\n";

std::string rows(std::size_t n) {
  std::string s;
  s.reserve(n * 12);
  for (std::size_t i = 0; i < n; ++i)
    s += std::to_string(0.8 + 0.2 * double(i % 997) / 997) + " m\n";
  return s;
}

// ---- Running glint ----------------------------------------------------------------------------

struct GlintRun {
  int raw = -1;  // waitpid status
  std::string out, err;
  bool exited(int code) const { return WIFEXITED(raw) && WEXITSTATUS(raw) == code; }
};

struct Spawn {
  fs::path cwd;
  int stdin_fd = -1;               // -1: /dev/null
  std::function<void()> in_child;  // e.g. setrlimit; runs after fork, before exec
  std::string env_umask;           // octal, e.g. "027": the child's umask
};

// Starts glint ARGS with stdout and stderr to files in `out_dir`; returns the pid.
pid_t start(const std::vector<std::string>& args, const Spawn& s, const fs::path& out,
            const fs::path& err) {
  std::vector<std::string> argv{kGlint};
  argv.insert(argv.end(), args.begin(), args.end());
  std::vector<char*> cargv;
  for (auto& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  const mode_t child_umask = s.env_umask.empty()
                                 ? static_cast<mode_t>(-1)
                                 : static_cast<mode_t>(std::stoi(s.env_umask, nullptr, 8));
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (!s.cwd.empty() && ::chdir(s.cwd.c_str()) != 0) ::_exit(120);
    const int in = s.stdin_fd >= 0 ? s.stdin_fd : ::open("/dev/null", O_RDONLY);
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (in < 0 || o < 0 || e < 0) ::_exit(121);
    ::dup2(in, 0);
    ::dup2(o, 1);
    ::dup2(e, 2);
    if (child_umask != static_cast<mode_t>(-1)) ::umask(child_umask);
    if (s.in_child) s.in_child();
    ::execv(kGlint.c_str(), cargv.data());
    ::_exit(127);
  }
  return pid;
}

GlintRun finish(pid_t& pid, const fs::path& out, const fs::path& err) {
  GlintRun r;
  while (::waitpid(pid, &r.raw, 0) < 0 && errno == EINTR) {
  }
  pid = -1;
  r.out = read_file(out);
  r.err = read_file(err);
  fs::remove(out);
  fs::remove(err);
  return r;
}

// Kills and reaps a started glint unless finish() took it: a failed assertion must not leave a
// child blocked on a pipe.
struct Reaper {
  pid_t& pid;
  ~Reaper() {
    if (pid <= 0) return;
    ::kill(pid, SIGKILL);
    ::waitpid(pid, nullptr, 0);
  }
};

// A scratch folder for the runs (the cwd of glint) and one for its captured streams, so that the
// first holds exactly what glint left.
class CliOutputs : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_TRUE(fs::exists(kGlint)) << kGlint << " not built";
    work_ = tmp_.path() / "work";
    io_ = tmp_.path() / "io";
    fs::create_directories(work_);
    fs::create_directories(io_);
  }

  GlintRun glint(const std::vector<std::string>& args, Spawn s = {}) {
    if (s.cwd.empty()) s.cwd = work_;
    const fs::path out = io_ / "out", err = io_ / "err";
    pid_t pid = start(args, s, out, err);
    return finish(pid, out, err);
  }

  TempDir tmp_;
  fs::path work_, io_;
};

// ---- 1. Temporaries --------------------------------------------------------------------------

TEST(OutputSetTemporaries, ExclusiveUnpredictableBesideTheTargetPrivateWhenReplacing) {
  TempDir dir;
  write_text(dir.path() / "old.txt", "old\n");
  ::chmod((dir.path() / "old.txt").c_str(), 0644);
  OutputSet set;
  OutputFile& fresh = set.add("--a", dir.file("new.txt"));
  OutputFile& old = set.add("--b", dir.file("old.txt"));
  const std::regex name(R"((new|old)\.txt\.tmp\.[0-9a-z]{12})");
  for (const OutputFile* f : {&fresh, &old}) {
    const fs::path t = f->temp_path();
    EXPECT_TRUE(std::regex_match(t.filename().string(), name)) << t;
    EXPECT_EQ(fs::canonical(t.parent_path()), fs::canonical(dir.path())) << t;  // same folder
    EXPECT_TRUE(fs::is_regular_file(fs::symlink_status(t))) << t;
  }
  // The temporary of a file that replaces another is private while it is written.
  EXPECT_EQ(mode_of(old.temp_path()), 0600u);
  // Names are fresh every time (no pid, no counter an attacker could plant a link at).
  std::set<std::string> names;
  for (int i = 0; i < 200; ++i) {
    OutputSet s;
    names.insert(fs::path(s.add("", dir.file("x")).temp_path()).filename().string());
  }
  EXPECT_EQ(names.size(), 200u);
  EXPECT_FALSE(fs::exists(dir.path() / "x"));  // aborted sets leave nothing
  fresh.stream() << "new\n";
  old.stream() << "replaced\n";
  set.commit();
  EXPECT_EQ(read_file(dir.path() / "new.txt"), "new\n");
  EXPECT_EQ(read_file(dir.path() / "old.txt"), "replaced\n");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"new.txt", "old.txt"}));
}

// ---- 2. Refused targets ------------------------------------------------------------------------

TEST(OutputSetRefusals, LinksDevicesFifosSocketsAndFoldersAreRefusedUntouched) {
  TempDir dir;
  write_text(dir.path() / "victim", "precious\n");
  fs::create_symlink(dir.path() / "victim", dir.path() / "link");
  fs::create_symlink(dir.path() / "nowhere", dir.path() / "dangling");
  fs::create_symlink("/dev/null", dir.path() / "null_link");
  ASSERT_EQ(::mkfifo(dir.file("fifo").c_str(), 0600), 0);
  fs::create_directories(dir.path() / "folder");
  for (const std::string& p :
       {dir.file("link"), dir.file("dangling"), dir.file("null_link"), dir.file("fifo"),
        dir.file("folder"), std::string("/dev/null"), std::string("/dev/stdout"),
        dir.file("folder/."), dir.file("folder/")}) {
    OutputSet set;
    try {
      set.add("--x", p);
      ADD_FAILURE() << p << " accepted";
    } catch (const OutputError& e) {
      EXPECT_NE(std::string(e.what()).find("--x"), std::string::npos) << e.what();
    }
    EXPECT_THROW(check_output_path(p), OutputError) << p;
  }
  EXPECT_EQ(read_file(dir.path() / "victim"), "precious\n");
  EXPECT_TRUE(fs::is_symlink(dir.path() / "link"));
  EXPECT_TRUE(fs::is_symlink(dir.path() / "dangling"));
  EXPECT_FALSE(fs::exists(dir.path() / "nowhere"));
  EXPECT_TRUE(fs::is_fifo(dir.path() / "fifo"));
  EXPECT_TRUE(fs::is_symlink("/dev/stdout"));
  EXPECT_TRUE(temporaries(dir.path()).empty());
  // A missing folder is named.
  OutputSet set;
  try {
    set.add("--y", dir.file("no/such/x.csv"));
    ADD_FAILURE();
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("no/such"), std::string::npos) << e.what();
  }
}

// A target turned into a link or folder after it was declared is refused at commit, and then
// nothing is committed.
TEST(OutputSetRefusals, TargetReplacedByALinkBeforeCommitIsRefused) {
  TempDir dir;
  write_text(dir.path() / "a", "a0");
  write_text(dir.path() / "victim", "precious");
  OutputSet set;
  set.add("--a", dir.file("a")).stream() << "a1";
  set.add("--b", dir.file("b")).stream() << "b1";
  fs::create_symlink(dir.path() / "victim", dir.path() / "b");
  EXPECT_THROW(set.commit(), OutputError);
  EXPECT_EQ(read_file(dir.path() / "a"), "a0");
  EXPECT_EQ(read_file(dir.path() / "victim"), "precious");
  EXPECT_TRUE(fs::is_symlink(dir.path() / "b"));
  EXPECT_TRUE(temporaries(dir.path()).empty());
}

TEST_F(CliOutputs, ReportToDevStdoutIsRefusedAndTheLinkKept) {
  const std::string before = fs::read_symlink("/dev/stdout").string();
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"sim", kBasic, "--unit", "lut", "--report", "/dev/stdout"},
        std::vector<std::string>{"eval", kBasic, "--unit", "lut", "--dump", "/dev/stdout"},
        std::vector<std::string>{"sim", kBasic, "--unit", "lut", "--vcd", "/dev/stdout"},
        std::vector<std::string>{"sim", kBasic, "--unit", "lut", "--dump", "/dev/null"}}) {
    const GlintRun r = glint(args);
    EXPECT_TRUE(r.exited(2)) << args.back() << ": " << r.err;
    EXPECT_NE(r.err.find(args.back()), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("'-'"), std::string::npos) << r.err;  // points at '-'
    EXPECT_TRUE(r.out.empty()) << r.out;
  }
  EXPECT_TRUE(fs::is_symlink("/dev/stdout"));
  EXPECT_EQ(fs::read_symlink("/dev/stdout").string(), before);
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  EXPECT_TRUE(snapshot(work_).empty());
  // A link in the work folder to a file of the user's: refused, the file untouched.
  write_text(work_ / "mine.csv", "mine\n");
  fs::create_symlink(work_ / "mine.csv", work_ / "out.csv");
  const GlintRun r = glint({"eval", kBasic, "--unit", "lut", "--dump", "out.csv"});
  EXPECT_TRUE(r.exited(2)) << r.err;
  EXPECT_NE(r.err.find("symbolic link"), std::string::npos) << r.err;
  EXPECT_EQ(read_file(work_ / "mine.csv"), "mine\n");
  EXPECT_TRUE(fs::is_symlink(work_ / "out.csv"));
}

// ---- "-": standard output for every stream ------------------------------------------------------

TEST_F(CliOutputs, DashWritesEveryStreamToStandardOutput) {
  // eval --dump -: the CSV on stdout, the summary table on stderr.
  GlintRun r = glint({"eval", kBasic, "--unit", "lut", "--dump", "-"});
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_EQ(r.out.rfind("line,material,light,x,y,t,", 0), 0u) << r.out.substr(0, 200);
  EXPECT_NE(r.err.find("lut"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.out.begin(), r.out.end(), '\n'), 1002);  // header + 1001 vectors
  // sim --report -: the same document --json prints.
  const GlintRun j = glint({"sim", kBasic, "--unit", "lut", "--json"});
  r = glint({"sim", kBasic, "--unit", "lut", "--report", "-"});
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_EQ(json::parse(r.out), json::parse(j.out));
  // sim --dump -.
  r = glint({"sim", kBasic, "--unit", "lut", "--dump", "-"});
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_EQ(r.out.rfind("line,unit,t,", 0), 0u);
  // sim --vcd -: a VCD on stdout, no save file anywhere.
  r = glint({"sim", kBasic, "--unit", "lut", "--vcd", "-", "--json"});
  EXPECT_TRUE(r.exited(2)) << "--vcd - and --json both write stdout";
  r = glint({"sim", kBasic, "--unit", "lut", "--vcd", "-"});
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_EQ(r.out.rfind("$date", 0), 0u);
  EXPECT_NE(r.out.find("$enddefinitions $end"), std::string::npos);
  EXPECT_TRUE(snapshot(work_).empty());
  r = glint({"sim", kBasic, "--unit", "lut", "--vcd", "-", "--mode", "clocked", "--report",
             "r.json", "--vcd-window", "0:3"});
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_EQ((snapshot(work_).count("r.json")), 1u);
  fs::remove(work_ / "r.json");
  // render --write-vectors -: the requests on stdout, readable by eval from stdin.
  r = glint({"render", kSmallScene, "-o", "img", "--unit", "lut", "--write-vectors", "-"});
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_EQ(r.out.rfind("glint-vectors 1\n", 0), 0u);
  EXPECT_NE(r.err.find("images and report.json in img"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(work_ / "img" / "report.json"));
  write_text(io_ / "requests.vec", r.out);
  const int in = ::open((io_ / "requests.vec").c_str(), O_RDONLY);
  const GlintRun e = glint({"eval", "-", "--unit", "lut", "--json"}, Spawn{{}, in, {}, {}});
  ::close(in);
  ASSERT_TRUE(e.exited(0)) << e.err;
  EXPECT_EQ(json::parse(e.out).at("rows"),
            json::parse(read_file(work_ / "img" / "report.json")).at("requests"));
}

TEST_F(CliOutputs, TwoWritersOfStandardOutputAreRefusedNamingBoth) {
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"eval", kBasic, "--dump", "-", "--json"}, {"--dump", "--json"}},
      {{"sim", kBasic, "--dump", "-", "--report", "-"}, {"--dump", "--report"}},
      {{"sim", kBasic, "--report", "-", "--json"}, {"--report", "--json"}},
      {{"sim", kBasic, "--vcd", "-", "--dump", "-"}, {"--vcd", "--dump"}},
      {{"render", kSmallScene, "-o", "img", "--write-vectors", "-", "--json"},
       {"--write-vectors", "--json"}}};
  for (const auto& [args, options] : cases) {
    const GlintRun r = glint(args);
    EXPECT_TRUE(r.exited(2)) << args[3] << ": " << r.err;
    for (const std::string& o : options) EXPECT_NE(r.err.find(o), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("standard output"), std::string::npos) << r.err;
    EXPECT_TRUE(r.out.empty()) << r.out.substr(0, 200);
    EXPECT_TRUE(snapshot(work_).empty()) << args[3];  // not even render's folder
  }
}

// ---- 3. Interrupted runs
// --------------------------------------------------------------------------

// Waits until `ready` holds (polling), at most 30 s.
bool wait_for(const std::function<bool()>& ready) {
  for (int i = 0; i < 3000; ++i) {
    if (ready()) return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return false;
}

bool process_mentions(const std::string& text) {
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string cmd = read_file(e.path() / "cmdline");
    if (cmd.find(text) != std::string::npos) return true;
  }
  return false;
}

// SIGINT and SIGTERM while glint writes (its input a pipe this test holds open, its outputs growing
// temporaries): the process dies of the signal, no temporary is left and the outputs that existed
// are as they were.
TEST_F(CliOutputs, SignalDuringARunLeavesNoTemporaryAndKeepsOldOutputs) {
  for (const int sig : {SIGINT, SIGTERM}) {
    for (const bool clocked : {false, true}) {
      SCOPED_TRACE(std::to_string(sig) + (clocked ? " clocked" : " fast"));
      write_text(work_ / "d.csv", "old dump\n");
      write_text(work_ / "r.json", "{\"old\": 1}\n");
      const auto before = snapshot(work_);
      int fds[2];
      ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
      const fs::path out = io_ / "out", err = io_ / "err";
      std::vector<std::string> args{"sim", "-", "--dump", "d.csv", "--report", "r.json"};
      if (clocked) args.insert(args.end(), {"--vcd", "t.vcd", "--vcd-window", "0:10"});
      pid_t pid = start(args, Spawn{work_, fds[0], {}, {}}, out, err);
      Reaper reaper{pid};
      ::close(fds[0]);
      // Fast mode simulates as the rows come: its dump's temporary grows (past its 64 KiB buffer)
      // while the pipe stays open. The clocked mode copies its input first: its four temporaries
      // (--dump, --report, --vcd and the save file) exist from the start, empty.
      const std::string data = std::string(kHeader) + rows(200000);  // > the reader's 1 MiB
      ASSERT_EQ(::write(fds[1], data.data(), data.size()), static_cast<ssize_t>(data.size()));
      ASSERT_TRUE(wait_for([&] {
        const auto t = temporaries(work_);
        if (t.size() != (clocked ? 4u : 2u)) return false;
        for (const auto& f : t)
          if (!clocked && f.find("d.csv.tmp.") != std::string::npos) return fs::file_size(f) > 0;
        return clocked;
      })) << temporaries(work_).size();
      ASSERT_EQ(::kill(pid, sig), 0);
      const GlintRun r = finish(pid, out, err);
      ::close(fds[1]);
      EXPECT_TRUE(WIFSIGNALED(r.raw) && WTERMSIG(r.raw) == sig) << r.raw << " " << r.err;
      EXPECT_EQ(snapshot(work_), before);
    }
  }
}

// The same during a render's computation (a large image: the signal arrives while it is drawn).
TEST_F(CliOutputs, SignalDuringARenderLeavesNothing) {
  json scene = json::parse(read_file(kSmallScene));
  scene["camera"]["resolution"] = {2400, 1800};
  write_text(io_ / "big.json", scene.dump());
  fs::create_directories(work_ / "img");
  write_text(work_ / "img" / "report.json", "old report\n");
  write_text(work_ / "img" / "keep.txt", "not ours\n");
  const auto before = snapshot(work_);
  for (const int sig : {SIGTERM, SIGINT}) {
    SCOPED_TRACE(sig);
    const fs::path out = io_ / "out", err = io_ / "err";
    pid_t pid = start({"render", (io_ / "big.json").string(), "-o", "img/new/deeper", "--unit",
                       "lut", "--threads", "1", "--write-vectors", "req.vec"},
                      Spawn{work_, -1, {}, {}}, out, err);
    Reaper reaper{pid};
    // Every output declared first: the new folders and temporaries appear at once.
    ASSERT_TRUE(wait_for([&] { return temporaries(work_).size() == 13; }))
        << temporaries(work_).size();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));  // into the rendering
    ASSERT_EQ(::kill(pid, sig), 0);
    const GlintRun r = finish(pid, out, err);
    EXPECT_TRUE(WIFSIGNALED(r.raw) && WTERMSIG(r.raw) == sig) << r.raw << " " << r.err;
    EXPECT_EQ(snapshot(work_), before);  // img/new/deeper made by the run: removed too
  }
}

// FST: vcd2fst runs beside glint writing into a private folder; a signal stops it and removes the
// folder.
TEST_F(CliOutputs, SignalDuringAnFstRunStopsVcd2fstAndRemovesItsFolder) {
  if (::access("/usr/bin/vcd2fst", X_OK) != 0) GTEST_SKIP() << "vcd2fst not installed (gtkwave)";
  write_text(io_ / "big.vec", std::string(kHeader) + rows(3000000));
  const fs::path out = io_ / "out", err = io_ / "err";
  pid_t pid = start({"sim", (io_ / "big.vec").string(), "--unit", "lut", "--vcd", "t.fst"},
                    Spawn{work_, -1, {}, {}}, out, err);
  Reaper reaper{pid};
  // vcd2fst started: its FST appears in the private folder.
  fs::path folder;
  ASSERT_TRUE(wait_for([&] {
    for (const auto& e : fs::directory_iterator(work_))
      if (e.is_directory() && fs::exists(e.path() / "trace.fst")) folder = e.path();
    return !folder.empty();
  }));
  EXPECT_EQ(mode_of(folder), 0700u);
  EXPECT_TRUE(
      std::regex_match(folder.filename().string(), std::regex(R"(t\.fst\.tmp\.[0-9a-z]{12})")));
  ASSERT_EQ(::kill(pid, SIGTERM), 0);
  const GlintRun r = finish(pid, out, err);
  EXPECT_TRUE(WIFSIGNALED(r.raw) && WTERMSIG(r.raw) == SIGTERM) << r.raw << " " << r.err;
  EXPECT_TRUE(snapshot(work_).empty());
  EXPECT_FALSE(process_mentions(folder.string()));  // vcd2fst killed with it
}

// ---- 4. A failed run commits nothing
// ----------------------------------------------------------------

// The issue's example: `--dump d.csv --report nodir/r.json` exited 2 after replacing d.csv.
TEST_F(CliOutputs, AFailedRunKeepsEveryExistingOutput) {
  write_text(work_ / "d.csv", "old dump\n");
  write_text(work_ / "t.vcd", "old trace\n");
  const auto before = snapshot(work_);
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"sim", kBasic, "--dump", "d.csv", "--report", "nodir/r.json"},
        std::vector<std::string>{"sim", kBasic, "--dump", "d.csv", "--vcd", "t.vcd", "--report",
                                 "nodir/r.json"},
        std::vector<std::string>{"eval", kBasic, "--dump", "d.csv", "--unit", "nosuch"},
        std::vector<std::string>{"render", kSmallScene, "-o", "img", "--write-vectors",
                                 "nodir/x.vec"},
        std::vector<std::string>{"sim", kTraces + "/blinn_colored.vec", "--dump", "d.csv", "--vcd",
                                 "t.vcd", "--chip", "ram:slots=1"}}) {
    const GlintRun r = glint(args);
    EXPECT_TRUE(r.exited(2)) << args[3] << ": " << r.err;
    EXPECT_EQ(snapshot(work_), before) << r.err;
  }
}

TEST(OutputSetCommit, ARenameFailingMidwayUndoesTheOnesDone) {
  TempDir dir;
  write_text(dir.path() / "a", "a0");
  write_text(dir.path() / "c", "c0");
  OutputSet set;
  set.add("--a", dir.file("a")).stream() << "a1";
  set.add("--n", dir.file("n")).stream() << "n1";  // a new file
  OutputFile& c = set.add("--c", dir.file("c"));
  c.stream() << "c1";
  // c's temporary vanishes behind the set's back: its rename fails after a's and n's were done.
  ASSERT_EQ(::unlink(c.temp_path().c_str()), 0);
  try {
    set.commit(false);
    ADD_FAILURE() << "commit succeeded";
  } catch (const OutputError& e) {
    EXPECT_NE(std::string(e.what()).find("--c"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no output was changed"), std::string::npos) << e.what();
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a", "c"}));  // n removed, no backup left
  EXPECT_EQ(read_file(dir.path() / "a"), "a0");
  EXPECT_EQ(read_file(dir.path() / "c"), "c0");
}

TEST(OutputSetCommit, AllCommittedTogetherAndAnErrorBeforeAnyRenameChangesNothing) {
  TempDir dir;
  write_text(dir.path() / "a", "a0");
  {
    OutputSet set;
    set.add("--a", dir.file("a")).stream() << "a1";
    set.add("--b", dir.file("b")).stream() << "b1";
    EXPECT_EQ(read_file(dir.path() / "a"), "a0");  // nothing before commit
    set.commit();
    EXPECT_THROW(set.commit(), std::logic_error);
  }
  EXPECT_EQ(read_file(dir.path() / "a"), "a1");
  EXPECT_EQ(read_file(dir.path() / "b"), "b1");
  {
    OutputSet set;
    set.add("--a", dir.file("a")).stream() << "a2";
    set.add("--b", dir.file("b")).stream() << "b2";
    // An exception in the run: the set is destroyed uncommitted.
  }
  EXPECT_EQ(read_file(dir.path() / "a"), "a1");
  EXPECT_EQ(read_file(dir.path() / "b"), "b1");
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a", "b"}));
  // A folder made for the outputs goes with a failed run, not one that was there.
  {
    OutputSet set;
    set.make_folder("-o", dir.file("new/deeper"));
    set.add("-o", dir.file("new/deeper/x")).stream() << "x";
    EXPECT_TRUE(fs::is_directory(dir.path() / "new" / "deeper"));
  }
  EXPECT_EQ(dir.entries(), (std::vector<std::string>{"a", "b"}));
}

// ---- 5. Permissions ---------------------------------------------------------------------------

TEST(OutputSetPermissions, AReplacedFileKeepsItsModeAndOwnerANewOneFollowsTheUmask) {
  TempDir dir;
  write_text(dir.path() / "private", "secret");
  ::chmod(dir.file("private").c_str(), 0600);
  write_text(dir.path() / "shared", "x");
  ::chmod(dir.file("shared").c_str(), 0664);
  const bool root = ::geteuid() == 0;
  if (root) {
    ASSERT_EQ(::chown(dir.file("shared").c_str(), 12345, 23456), 0);
  }
  const mode_t old_mask = ::umask(027);
  {
    OutputSet set;
    set.add("", dir.file("private")).stream() << "new secret";
    set.add("", dir.file("shared")).stream() << "y";
    set.add("", dir.file("fresh")).stream() << "z";
    set.commit();
  }
  ::umask(old_mask);
  EXPECT_EQ(mode_of(dir.path() / "private"), 0600u);
  EXPECT_EQ(mode_of(dir.path() / "shared"), 0664u);
  EXPECT_EQ(mode_of(dir.path() / "fresh"), 0640u);  // 0666 & ~027
  EXPECT_EQ(read_file(dir.path() / "private"), "new secret");
  if (root) {
    struct stat st {};
    ASSERT_EQ(::stat(dir.file("shared").c_str(), &st), 0);
    EXPECT_EQ(st.st_uid, 12345u);
    EXPECT_EQ(st.st_gid, 23456u);
  }
}

TEST_F(CliOutputs, PermissionsOfReplacedOutputsAreKept) {
  write_text(work_ / "d.csv", "old\n");
  ::chmod((work_ / "d.csv").c_str(), 0600);
  write_text(work_ / "t.vcd", "old\n");
  ::chmod((work_ / "t.vcd").c_str(), 0640);
  Spawn s;
  s.env_umask = "077";
  const GlintRun r = glint(
      {"sim", kBasic, "--unit", "lut", "--dump", "d.csv", "--vcd", "t.vcd", "--report", "r.json"},
      s);
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_EQ(mode_of(work_ / "d.csv"), 0600u);
  EXPECT_EQ(mode_of(work_ / "t.vcd"), 0640u);
  EXPECT_EQ(mode_of(work_ / "r.json"), 0600u);  // new: 0666 & ~077
  EXPECT_EQ(mode_of(work_ / "t.gtkw"), 0600u);
  EXPECT_NE(read_file(work_ / "d.csv"), "old\n");
}

// ---- 6. Two outputs on one file
// --------------------------------------------------------------------

TEST(OutputSetSameFile, AnySpellingOfOneFileIsRefused) {
  TempDir dir;
  fs::create_directories(dir.path() / "sub");
  write_text(dir.path() / "a", "a");
  fs::create_hard_link(dir.path() / "a", dir.path() / "hard");
  fs::create_directory_symlink(dir.path() / "sub", dir.path() / "sublink");
  write_text(dir.path() / "in.vec", "input");
  const std::string d = dir.path().string();
  const std::vector<std::pair<std::string, std::string>> pairs = {
      {d + "/a", d + "/./a"},  {d + "/a", d + "/sub/../a"},      {d + "/a", d + "//a"},
      {d + "/a", d + "/hard"}, {d + "/sub/x", d + "/sublink/x"}, {d + "/new", d + "/sub/../new"}};
  for (const auto& [first, second] : pairs) {
    OutputSet set;
    set.add("--first", first);
    try {
      set.add("--second", second);
      ADD_FAILURE() << first << " and " << second << " accepted";
    } catch (const OutputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("--first"), std::string::npos) << what;
      EXPECT_NE(what.find("--second"), std::string::npos) << what;
      EXPECT_NE(what.find("name the same file"), std::string::npos) << what;
    }
  }
  // The input, by another name (a hard link), is not an output either.
  fs::create_hard_link(dir.path() / "in.vec", dir.path() / "in2.vec");
  OutputSet set;
  set.add_input("VECTORS", d + "/in.vec");
  EXPECT_THROW(set.add("--dump", d + "/in2.vec"), OutputError);
  EXPECT_THROW(set.add("--dump", d + "/sub/../in.vec"), OutputError);
  EXPECT_EQ(read_file(dir.path() / "in.vec"), "input");
  EXPECT_TRUE(temporaries(dir.path()).empty());
}

TEST_F(CliOutputs, TwoOutputsOnOneFileAreRefusedNamingBoth) {
  fs::create_directories(work_ / "sub");
  fs::create_directory_symlink(work_ / "sub", work_ / "link");
  fs::copy_file(kBasic, work_ / "in.vec");
  fs::create_hard_link(work_ / "in.vec", work_ / "same.vec");
  const auto before = snapshot(work_);
  const std::vector<std::pair<std::vector<std::string>, std::vector<std::string>>> cases = {
      {{"sim", kBasic, "--dump", "o.csv", "--report", "./o.csv"}, {"--dump", "--report"}},
      {{"sim", kBasic, "--dump", "sub/o", "--vcd", "link/o"}, {"--dump", "--vcd"}},
      {{"sim", kBasic, "--vcd", "w.vcd", "--report", "w.gtkw"}, {"--vcd's save file", "--report"}},
      {{"eval", "in.vec", "--dump", "same.vec"}, {"VECTORS", "--dump"}},
      {{"render", kSmallScene, "-o", "img", "--write-vectors", "img/report.json"},
       {"-o (report.json)", "--write-vectors"}}};
  for (const auto& [args, options] : cases) {
    const GlintRun r = glint(args);
    EXPECT_TRUE(r.exited(2)) << r.err;
    for (const std::string& o : options) EXPECT_NE(r.err.find(o), std::string::npos) << r.err;
    EXPECT_EQ(snapshot(work_), before);
  }
}

// ---- 7. Disk full
// ------------------------------------------------------------------------------------

// RLIMIT_FSIZE in the child stands for a full disk (no root, no mount needed): a write past the
// limit fails with EFBIG (glint ignores SIGXFSZ, which would otherwise kill it).
TEST_F(CliOutputs, AFullDiskIsExit2WithNoPartialOutput) {
  write_text(io_ / "many.vec", std::string(kHeader) + rows(50000));
  write_text(work_ / "d.csv", "old dump\n");
  fs::create_directories(work_ / "img");
  write_text(work_ / "img" / "report.json", "old report\n");
  const auto before = snapshot(work_);
  Spawn s;
  s.in_child = [] {
    const rlimit lim{64 * 1024, 64 * 1024};
    ::setrlimit(RLIMIT_FSIZE, &lim);
  };
  for (const std::vector<std::string>& args :
       {std::vector<std::string>{"eval", (io_ / "many.vec").string(), "--dump", "d.csv"},
        std::vector<std::string>{"sim", (io_ / "many.vec").string(), "--unit", "lut", "--dump",
                                 "d.csv"},
        std::vector<std::string>{"sim", (io_ / "many.vec").string(), "--unit", "lut", "--vcd",
                                 "t.vcd"},
        std::vector<std::string>{"render", kSmallScene, "-o", "img", "--write-vectors", "r.vec"}}) {
    const GlintRun r = glint(args, s);
    EXPECT_TRUE(r.exited(2)) << args[0] << " " << args.back() << ": " << r.raw << " " << r.err;
    EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
    EXPECT_EQ(r.err.find("internal error"), std::string::npos) << r.err;
    EXPECT_EQ(snapshot(work_), before) << args.back();
  }
  // And through the library: the error is thrown by the write, naming the output.
  const pid_t pid = ::fork();
  if (pid == 0) {
    const rlimit lim{4096, 4096};
    ::setrlimit(RLIMIT_FSIZE, &lim);
    ::signal(SIGXFSZ, SIG_IGN);
    int code = 1;
    try {
      AtomicOutputFile f((work_ / "lib.txt").string());
      f.stream() << std::string(100000, 'x');
      f.commit();
    } catch (const OutputError& e) {
      code = std::string(e.what()).find("lib.txt") != std::string::npos ? 0 : 2;
    } catch (...) {
      code = 3;
    }
    ::_exit(code);
  }
  int st = 0;
  ::waitpid(pid, &st, 0);
  EXPECT_TRUE(WIFEXITED(st) && WEXITSTATUS(st) == 0) << st;
  EXPECT_EQ(snapshot(work_), before);
}

// A real full disk, where this runs as root: a 256 KiB tmpfs mounted in a private mount namespace
// (unshare -m: it vanishes with the shell, nothing to unmount). Skipped otherwise; the RLIMIT_FSIZE
// test above covers every user.
TEST_F(CliOutputs, AFullTmpfsIsExit2WithNoPartialOutput) {
  if (::geteuid() != 0) GTEST_SKIP() << "mounting a tmpfs needs root";
  if (std::system("unshare -m true >/dev/null 2>&1") != 0) GTEST_SKIP() << "no unshare -m here";
  const auto q = test::shell_quote;
  write_text(io_ / "many.vec", std::string(kHeader) + rows(50000));
  const fs::path report = io_ / "report.txt";
  for (const std::string& args :
       {std::string(" eval ") + q((io_ / "many.vec").string()) + " --dump d.csv",
        std::string(" sim ") + q((io_ / "many.vec").string()) +
            " --unit lut --dump small.csv --vcd t.vcd --report r.json"}) {
    const std::string script =
        "mount -t tmpfs -o size=256k tmpfs " + q(work_.string()) + " && cd " + q(work_.string()) +
        " && printf 'old dump\\n' > d.csv && " + q(kGlint) + args + " >/dev/null 2>" +
        q((io_ / "err").string()) + "; echo status=$?; ls -A; cat d.csv";
    ASSERT_EQ(std::system(("unshare -m sh -c " + q(script) + " >" + q(report.string())).c_str()),
              0);
    const std::string err = read_file(io_ / "err");
    EXPECT_EQ(read_file(report), "status=2\nd.csv\nold dump\n") << err;
    EXPECT_NE(err.find("No space left on device"), std::string::npos) << err;
  }
  EXPECT_TRUE(snapshot(work_).empty());  // the mount was private to the shell
}

// ---- 8. Standard input and pipes
// -------------------------------------------------------------------

TEST_F(CliOutputs, ClockedAndFastRunsReadStandardInputAndPipes) {
  const GlintRun ref =
      glint({"sim", kBasic, "--unit", "hast", "--unit", "lut", "--mode", "clocked", "--json"});
  ASSERT_TRUE(ref.exited(0)) << ref.err;
  json expect = json::parse(ref.out);
  const auto same = [&](json got) {
    got.erase("vectors_file");
    json e = expect;
    e.erase("vectors_file");
    return got == e;
  };
  const std::string text = read_file(kBasic);
  for (const std::string& input : {std::string("-"), std::string("/dev/stdin")}) {
    for (const std::string mode : {"clocked", "fast"}) {
      SCOPED_TRACE(input + " " + mode);
      // From a pipe the test writes into (a thread, so a large input cannot block both sides).
      int fds[2];
      ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
      std::thread feeder([&] {
        (void)!::write(fds[1], text.data(), text.size());
        ::close(fds[1]);
      });
      const GlintRun r = glint({"sim", input, "--unit", "hast", "--unit", "lut", "--mode", mode,
                                "--json", "--sink-ready", "1"},
                               Spawn{{}, fds[0], {}, {}});
      feeder.join();
      ::close(fds[0]);
      ASSERT_TRUE(r.exited(0)) << r.err;
      json got = json::parse(r.out);
      if (mode == "fast") {
        // Fast and clocked agree on every statistic (test_sim_modes); compare the digests.
        for (std::size_t u = 0; u < 2; ++u)
          EXPECT_EQ(got["units"][u]["digest"], expect["units"][u]["digest"]);
      } else {
        EXPECT_TRUE(same(got)) << r.out.substr(0, 400);
      }
    }
  }
  // Standard input redirected from a file is read in place (no copy), and a FIFO by path.
  const int in = ::open(kBasic.c_str(), O_RDONLY);
  GlintRun r = glint({"sim", "-", "--unit", "hast", "--unit", "lut", "--mode", "clocked", "--json"},
                     Spawn{{}, in, {}, {}});
  ::close(in);
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_TRUE(same(json::parse(r.out)));
  const fs::path fifo = io_ / "fifo.vec";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::thread feeder([&] {
    std::ofstream f(fifo, std::ios::binary);
    f << text;
  });
  r = glint(
      {"sim", fifo.string(), "--unit", "hast", "--unit", "lut", "--mode", "clocked", "--json"});
  feeder.join();
  ASSERT_TRUE(r.exited(0)) << r.err;
  EXPECT_TRUE(same(json::parse(r.out)));
  // A malformed stream from standard input names "<stdin>" and its line.
  int fds[2];
  ASSERT_EQ(::pipe2(fds, O_CLOEXEC), 0);
  const std::string bad = std::string(kHeader) + "0.5 m\nnot_a_number m\n";
  ASSERT_EQ(::write(fds[1], bad.data(), bad.size()), static_cast<ssize_t>(bad.size()));
  ::close(fds[1]);
  r = glint({"eval", "-", "--dump", "d.csv"}, Spawn{{}, fds[0], {}, {}});
  ::close(fds[0]);
  EXPECT_TRUE(r.exited(2)) << r.err;
  EXPECT_NE(r.err.find("<stdin>:8:"), std::string::npos) << r.err;
  EXPECT_TRUE(snapshot(work_).empty());
}

}  // namespace
}  // namespace glint
