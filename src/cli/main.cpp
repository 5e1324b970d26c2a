// glint command-line entry point; each subcommand lives in its own cmd_*.cpp.
#include <cstdio>

#include "cli/cli.h"
#include "rtl_model/sc_setup.h"

// libsystemc's own main() would call sc_main; glint has a main of its own, which takes precedence,
// so sc_main only satisfies the linker.
extern "C" int sc_main(int, char**) {
  return 0;
}

int main(int argc, char** argv) {
  glint::quiet_systemc_banner();
  CLI::App app{"glint: simulator of fixed-point specular shading units (max(0,t)^n)"};
  app.require_subcommand(1);
  int status = glint::cli::kExitOk;
  glint::cli::add_tau_command(app, status);
  glint::cli::add_fit_command(app, status);
  glint::cli::add_eval_command(app, status);
  glint::cli::add_units_command(app, status);
  glint::cli::add_sim_command(app, status);
  glint::cli::add_regress_command(app, status);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : glint::cli::kExitBadInput;
  }
  return status;
}
