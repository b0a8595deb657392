#pragma once
// `run`, `demo` and `render` on the command line: the printing around one RunSession
// (engine/session/run_session.hpp: fill, settle with the drum at rest, turn the drum, scheduled
// observers between steps). The options, the output schedule and the summary are
// app/run/'s, shared with drumlab-mpi.
#include <span>

#include "app/run/run_options.hpp"
#include "app/run/run_report.hpp"

namespace drumlab::cli {

/// Runs the scene as planned by `opt` and prints the summary of the turning phase. The output
/// writers requested in `opt` are added to `observers`.
void run_session(const RunOptions& opt, std::span<FrameObserver* const> observers = {});

}  // namespace drumlab::cli
