#pragma once
// Each subcommand of the `drumlab` CLI lives in its own file and registers itself here.
#include <CLI/CLI.hpp>

namespace drumlab::cli {

/// The whole command line of `drumlab` (app/cli/main.cpp): one subcommand required, and every
/// add_*_command below (render, teach and convert only with DRUMLAB_WITH_RENDER). Also what the
/// fuzz harness tests/fuzz/fuzz_cli_drumlab.cpp parses.
void add_commands(CLI::App& app);

void add_analyze_command(CLI::App& app);
void add_bench_command(CLI::App& app);
void add_contacts_command(CLI::App& app);
void add_decompose_command(CLI::App& app);
void add_paper_table_command(CLI::App& app);
void add_run_command(CLI::App& app);
void add_info_command(CLI::App& app);
void add_law_command(CLI::App& app);
void add_stress_command(CLI::App& app);
void add_sweep_command(CLI::App& app);
// Built only with DRUMLAB_WITH_RENDER:
void add_render_command(CLI::App& app);
void add_teach_command(CLI::App& app);
void add_convert_command(CLI::App& app);

}  // namespace drumlab::cli
