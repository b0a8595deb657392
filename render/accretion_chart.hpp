#pragma once
// The chart of `drumlab analyze --accretion`: the primaries held in the seeds' granules against
// time, with the saturating exponential fitted to them (engine/analysis/accretion.hpp).
#include <filesystem>
#include <string>
#include <vector>

#include "engine/analysis/accretion.hpp"

namespace drumlab::render {

/// Draws the counts `n` at times `t` and `fit` as PNG `file`. Throws InputError if the file cannot
/// be written.
void write_accretion_chart(const std::vector<double>& t, const std::vector<double>& n,
                           const SaturatingFit& fit, const std::string& criterion,
                           const std::filesystem::path& file);

}  // namespace drumlab::render
