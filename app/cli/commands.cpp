#include "app/cli/commands.hpp"

namespace drumlab::cli {

void add_commands(CLI::App& app) {
  app.require_subcommand(1);
  add_run_command(app);
  add_info_command(app);
  add_law_command(app);
  add_contacts_command(app);
  add_analyze_command(app);
  add_decompose_command(app);
  add_paper_table_command(app);
  add_bench_command(app);
  add_stress_command(app);
  add_sweep_command(app);
#ifdef DRUMLAB_WITH_RENDER
  add_render_command(app);
  add_teach_command(app);
  add_convert_command(app);
#endif
}

}  // namespace drumlab::cli
