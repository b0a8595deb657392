#pragma once
// The granule criterion's flags, the same in run, analyze, sweep and render:
// --granule-criterion age|community|components, --granule-age T, --granule-resolution R
// (engine/analysis/granule_criterion.hpp).
#include <CLI/CLI.hpp>

#include "engine/analysis/granule_criterion.hpp"

namespace drumlab::cli {

struct GranuleFlags {
  GranuleCriterion criterion;
  bool age_given = false;
  bool resolution_given = false;
};

/// Declares the three flags on `cmd`; they fill `flags`, which must outlive the parse.
void add_granule_flags(CLI::App* cmd, GranuleFlags& flags);

/// Throws InputError (one line naming the flag) for a flag that does not apply to the chosen
/// criterion: --granule-age without age, --granule-resolution without community.
void check_granule_flags(const GranuleFlags& flags);

}  // namespace drumlab::cli
