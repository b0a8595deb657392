#include <CLI/CLI.hpp>

int main(int argc, char** argv) {
  CLI::App app{"drumlab: DEM of granular flow in rotating drums"};
  app.require_subcommand(1);
  CLI11_PARSE(app, argc, argv);
  return 0;
}
