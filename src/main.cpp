// glint command-line entry point; each subcommand lives in its own cmd_*.cpp.
#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"glint: fixed-point specular shading unit simulator"};
  app.require_subcommand(1);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
