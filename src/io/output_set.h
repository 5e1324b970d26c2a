// The output files of a run, made so that they cannot be turned against the user and committed all
// together or not at all.
//
// Every output is declared before the run does any work (OutputSet::add): the path is checked
// (lstat, so a symbolic link is seen, never followed: an existing target must be a regular file,
// its folder must exist), compared with every other output and input of the run (the same folder,
// resolved with realpath, and name; or the same existing file, by device and inode, which catches
// hard links), and its temporary is created at once, beside the target so that the final rename
// stays in one file system: "<target>.tmp.<12 random characters>", opened with
// O_CREAT | O_EXCL | O_NOFOLLOW (a name someone else made, file or link, is never opened: a fresh
// name is drawn) and mode 0600 while it is written when it replaces a file. Each temporary is
// registered with signal_cleanup.h, so SIGINT, SIGTERM and the like remove it.
//
// commit() first finishes every file: flushes, fsyncs, gives it the permission bits of the file it
// replaces (or 0666 & ~umask for a new one), and its owner and group where the process may (root;
// a group the user belongs to); any failure, e.g. a full disk, discards them all and leaves every
// target as it was. Then, with the termination signals held (SignalShield), it makes a hard link
// of each existing target ("<target>.tmp.<random>", a backup) and renames every temporary onto its
// target in a row. If one rename fails, the ones already done are undone: a replaced target gets
// its backup back (a rename), a new one is removed; so the targets are as before the run. The
// backups are removed at the end. Limits: a target on a file system without hard links gets no
// backup (such targets are renamed last, so one of them alone is still all-or-none); a crash or
// SIGKILL during those few renames can leave some targets new and some old, plus backup and
// temporary files; a target replaced keeps its name, not its inode (another hard link to it keeps
// the old content), and loses extended attributes and ACLs.
//
// "-" names standard output (for streams: add(..., allow_stdout)): written directly as the run
// goes, never renamed, so a failed run may have written part of it (its exit status says so).
// What commands print there otherwise (std::cout) is checked by io/standard_output.h.
// Two writers of standard output (two "-", or "-" and an option that prints there, claim_stdout)
// are refused.
#pragma once

#include <sys/types.h>

#include <memory>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

namespace glint {

// An output file that cannot be written: the user's path is wrong (missing folder, not a regular
// file, no permission, disk full), so the CLI reports it as bad input (exit 2).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// 12 characters from [0-9a-z] drawn from the kernel's random source (getrandom): the suffix of
// every temporary name, which another user cannot guess in advance.
std::string unpredictable_suffix();

// Throws OutputError unless `path` can be replaced by an output: it does not exist or is a regular
// file (lstat: a symbolic link, device, FIFO, socket or folder is refused), and its folder exists.
void check_output_path(const std::string& path);

// One output of an OutputSet.
class OutputFile {
 public:
  ~OutputFile();
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;

  // Where to write (binary, buffered). A write error (EFBIG, ENOSPC, EPIPE...) throws OutputError
  // naming the output from the write itself (the stream's exceptions include badbit). Not for
  // produced outputs.
  std::ostream& stream();
  // A new descriptor of the file being written (close-on-exec), for a writer with its own
  // buffering (the VCD writer's FILE*); the caller closes it, and flushes before commit().
  int dup_fd() const;

  const std::string& option() const { return option_; }
  const std::string& path() const { return path_; }  // as given; "-" for standard output
  bool is_stdout() const { return stdout_; }
  // The temporary written now (empty for standard output and produced outputs).
  const std::string& temp_path() const { return temp_path_; }

  // Produced outputs (OutputSet::add_produced): the private folder (0700) the other program writes
  // into, and the file in it that commit() fsyncs and renames onto path(); set it once the file
  // is complete: checked by whoever ran the program, since an exit status 0 does not prove it
  // (vcd2fst exits 0 with its FST cut short on a full disk; rtl_model/fst_read_back.h).
  const std::string& work_folder() const { return work_folder_; }
  void set_produced(const std::string& file) { produced_ = file; }

 private:
  friend class OutputSet;
  class Buf;
  OutputFile() = default;
  void finish(bool durable);  // flush, fsync, mode and owner, close (commit's first step)
  void discard() noexcept;    // close and remove the temporary
  std::string describe() const;

  std::string option_, path_;
  std::string target_;     // absolute: realpath of the folder + name ("" for standard output)
  std::string temp_path_;  // absolute
  std::string work_folder_, produced_;
  bool stdout_ = false;
  bool private_mode_ = false;  // temporary made 0600 (it replaces a file): needs its final mode
  int fd_ = -1;
  int temp_handle_ = -1, folder_handle_ = -1;  // signal_cleanup.h entries
  std::unique_ptr<Buf> buf_;
  std::unique_ptr<std::ostream> stream_;
};

class OutputSet {
 public:
  OutputSet();
  ~OutputSet();  // abort() unless committed: no temporary is left, no target touched
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // A file the run reads (`option` names it in messages, e.g. "VECTORS"): no output may be it.
  // "-" (standard input) is not a file and is ignored.
  void add_input(const std::string& option, const std::string& path);
  // `option` prints on standard output (e.g. "--json"): no output may be "-".
  void claim_stdout(const std::string& option);
  // An output written by this process, checked and its temporary created now (see above). "-" is
  // standard output when `allow_stdout` (a stream), else a file named "-". Throws OutputError (or
  // std::invalid_argument for two outputs on one file) naming the option.
  OutputFile& add(const std::string& option, const std::string& path, bool allow_stdout = false);
  // An output another program writes (vcd2fst): checked as add() does, with a private folder
  // "<target>.tmp.<random>" (mkdtemp: 0700, a fresh name) beside it for that program's files.
  // Files it will create there should be registered (register_cleanup) by whoever starts it.
  OutputFile& add_produced(const std::string& option, const std::string& path);
  // Creates the folder `dir` and its missing parents for outputs inside it; the ones created here
  // are removed again (when empty) if the run fails or is interrupted.
  void make_folder(const std::string& option, const std::string& dir);

  // Some output writes standard output ("-"): the caller prints its summary on stderr instead.
  bool writes_stdout() const;
  const std::vector<std::unique_ptr<OutputFile>>& files() const { return files_; }

  // Commits every output (see above): on return each target holds its new content; on an
  // OutputError every target is as it was (except as the limits above say) and no temporary is
  // left. Calling it twice is a std::logic_error.
  void commit(bool durable = true);
  // Discards every output now. Idempotent.
  void abort() noexcept;
  bool committed() const { return committed_; }

 private:
  struct Seen {  // an output or input, for the "same file" checks
    std::string option, path, key;
    bool input = false;
    bool exists = false;
    dev_t dev = 0;
    ino_t ino = 0;
  };
  OutputFile& declare(const std::string& option, const std::string& path, bool allow_stdout);
  void check_distinct(const Seen& s) const;

  std::vector<std::unique_ptr<OutputFile>> files_;
  std::vector<Seen> seen_;
  std::string stdout_claim_;  // the option that writes standard output, if any
  std::vector<std::pair<std::string, int>> created_folders_;  // path and cleanup handle
  bool committed_ = false, aborted_ = false;
};

}  // namespace glint
