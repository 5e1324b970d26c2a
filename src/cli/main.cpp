// glint command-line entry point; each subcommand lives in its own cmd_*.cpp.
#include <cstdio>
#include <string>

#include "cli/cli.h"
#include "io/signal_cleanup.h"
#include "rtl_model/sc_setup.h"

#ifndef GLINT_VERSION
#error "GLINT_VERSION must be defined by the build (CMakeLists.txt: the project version)"
#endif

// libsystemc's own main() would call sc_main; glint has a main of its own, which takes precedence,
// so sc_main only satisfies the linker.
extern "C" int sc_main(int, char**) {
  return 0;
}

namespace {

// The first word after `glint` names a subcommand unless it is an option. CLI11 would report an
// unknown one as "The following argument was not expected: WORD" (or only "A subcommand is
// required"), which does not say that WORD was taken for a subcommand; name it and the valid ones.
bool check_subcommand(CLI::App& app, int argc, char** argv) {
  if (argc < 2 || argv[1][0] == '-') return true;
  const std::string word = argv[1];
  std::string known;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
    if (sub->check_name(word)) return true;
    known += (known.empty() ? "" : ", ") + sub->get_name();
  }
  std::fprintf(stderr, "glint: unknown subcommand '%s' (expected one of: %s; see glint --help)\n",
               word.c_str(), known.c_str());
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  // SIGINT, SIGTERM and the like remove the run's temporary files before ending it; a file size
  // limit makes writes fail (an error reported, exit 2) instead of killing glint.
  glint::install_cleanup_handlers();
  glint::quiet_systemc_banner();
  CLI::App app{"glint: simulator of fixed-point specular shading units (max(0,t)^n)"};
  app.set_version_flag("--version", std::string("glint ") + GLINT_VERSION);
  app.require_subcommand(1);
  int status = glint::cli::kExitOk;
  glint::cli::add_tau_command(app, status);
  glint::cli::add_fit_command(app, status);
  glint::cli::add_eval_command(app, status);
  glint::cli::add_units_command(app, status);
  glint::cli::add_sim_command(app, status);
  glint::cli::add_regress_command(app, status);
  glint::cli::add_render_command(app, status);
  glint::cli::add_sweep_command(app, status);
  glint::cli::add_size_command(app, status);
  glint::cli::add_merge_command(app, status);
  if (!check_subcommand(app, argc, argv)) return glint::cli::kExitBadInput;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : glint::cli::kExitBadInput;
  }
  return status;
}
