// glint command-line entry point; the command line itself is cli::run (app.cpp), each subcommand
// in its own cmd_*.cpp.
#include "cli/cli.h"
#include "io/signal_cleanup.h"
#include "io/standard_output.h"
#include "rtl_model/sc_setup.h"

// libsystemc's own main() would call sc_main; glint has a main of its own, which takes precedence,
// so sc_main only satisfies the linker.
extern "C" int sc_main(int, char**) {
  return 0;
}

int main(int argc, char** argv) {
  // SIGINT, SIGTERM and the like remove the run's temporary files before ending it; a file size
  // limit makes writes fail (an error reported, exit 2) instead of killing glint.
  glint::install_cleanup_handlers();
  // std::cout keeps the reason of a failed write, which cli::run reports (exit 2).
  glint::check_standard_output();
  glint::quiet_systemc_banner();
  return glint::cli::run(argc, argv);
}
