// What `glint synth` needs to run the open tools of the flow (Yosys, OpenSTA): a private work
// folder for their files, and a run of one tool with its output captured, both cleaned up by a
// termination signal's handler (io/signal_cleanup.h).
#pragma once

#include <string>
#include <vector>

namespace glint::cli {

// A private work folder (mkdtemp under $TMPDIR) and the files in it, removed at the end and by a
// termination signal's handler. The tools' own temporaries (ABC's folders) go in it too
// (run_tool sets TMPDIR to it), so the end removes them even where a tool left them.
class WorkFolder {
 public:
  WorkFolder();
  ~WorkFolder();
  const std::string& path() const { return dir_; }
  WorkFolder(const WorkFolder&) = delete;
  WorkFolder& operator=(const WorkFolder&) = delete;
  // A file in the folder, registered before it exists.
  std::string file(const std::string& name);

 private:
  std::string dir_;
  std::vector<std::string> files_;
  std::vector<int> handles_;
};

void write_text(const std::string& path, const std::string& text);  // OutputError on failure
std::string read_text(const std::string& path);                     // "" if unreadable

// Runs `program args...` with standard output and error into the file `output` and TMPDIR set to
// `work`, and waits for it. Returns its exit status, or -1 if a signal ended it. A program not on
// PATH throws std::invalid_argument(`missing`).
int run_tool(const std::string& program, const std::vector<std::string>& args,
             const std::string& output, const std::string& work, const std::string& missing);

// Bytes free to an unprivileged writer on the file system of `dir` (the maximum when unknown).
unsigned long long free_bytes(const std::string& dir);
// Below this, a tool that failed in a work folder is taken to have run out of space: its error
// (often a syntax error in a file it wrote itself, cut short) does not say so.
inline constexpr unsigned long long kFullDiskBytes = 1 << 20;

}  // namespace glint::cli
