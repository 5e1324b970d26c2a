#include <stdlib.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <system_error>

#include "fuzz.h"

namespace glint::fuzz {

namespace fs = std::filesystem;

const fs::path& temp_folder(const std::string& name) {
  struct Folder {
    fs::path path;
    explicit Folder(const std::string& name) {
      std::error_code ec;
      const fs::path root = std::getenv("TMPDIR") == nullptr && fs::is_directory("/dev/shm", ec)
                                ? fs::path("/dev/shm")
                                : fs::temp_directory_path();
      std::string tmpl = (root / ("glint_fuzz_" + name + ".XXXXXX")).string();
      if (!mkdtemp(tmpl.data())) fail("cannot make a temporary folder");
      path = tmpl;
    }
    Folder(const Folder&) = delete;
    Folder& operator=(const Folder&) = delete;
    ~Folder() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static std::map<std::string, Folder> folders;  // harnesses run one input at a time
  return folders.try_emplace(name, name).first->second.path;
}

void fail(const std::string& what) {
  std::fprintf(stderr, "glint fuzz finding: %s\n", what.c_str());
  std::abort();
}

}  // namespace glint::fuzz
