// drumlab paper-table --table 1|2 [--csv FILE]
// The paper's operation-count estimates beside what drumlab counts on the paper's packing
// (app/bench/paper_table.hpp).
#include <memory>
#include <string>

#include "app/bench/paper_table.hpp"
#include "app/cli/commands.hpp"

namespace drumlab::cli {

void add_paper_table_command(CLI::App& app) {
  auto table = std::make_shared<int>(1);
  auto csv = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand(
      "paper-table",
      "The paper's operation-count estimates beside drumlab's counts on its packing");
  cmd->add_option("--table", *table, "1: depth 0.15 m (193k particles), 2: depth 2 m (2.6M)")
      ->check(CLI::IsMember({1, 2}))
      ->capture_default_str();
  cmd->add_option("--csv", *csv, "also write the table as CSV (long format)");
  cmd->callback([table, csv] { bench::run_paper_table(*table, *csv); });
}

}  // namespace drumlab::cli
