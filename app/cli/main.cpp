// drumlab: the headless command line. Exit codes: 0 success, 1 unexpected failure, 2 bad input
// (scene, CSV, option, output path), 3 the simulation became unstable.
#include <csignal>
#include <cstdio>
#include <exception>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "app/cli/commands.hpp"
#include "engine/openmp_waiting.hpp"
#include "engine/types.hpp"

int main(int argc, char** argv) {
  drumlab::choose_openmp_waiting(argc, argv);  // may execute the program again, see there
  // A file size limit (ulimit -f) then fails the write with a clear error instead of killing us.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"drumlab: DEM of granular flow in rotating drums, with switchable contact search"};
  drumlab::cli::add_commands(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help
    return app.exit(e);
  } catch (const CLI::ParseError& e) {  // a bad option or value: one line, exit 2 as bad input
    fmt::print(stderr, "drumlab: error: {}\n", e.what());
    return 2;
  } catch (const drumlab::InputError& e) {
    fmt::print(stderr, "drumlab: error: {}\n", e.what());
    return 2;
  } catch (const drumlab::UnstableError& e) {
    fmt::print(stderr, "drumlab: unstable: {}\n", e.what());
    return 3;
  } catch (const std::exception& e) {
    fmt::print(stderr, "drumlab: failed: {}\n", e.what());
    return 1;
  }
  return 0;
}
