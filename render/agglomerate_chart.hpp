#pragma once
// The size distribution of agglomerates over time as a PNG (VTK charts, offscreen): left, the
// mass-weighted d10 / d50 / d90 of the volume-equivalent diameter (mm) against time; right, the
// number of agglomerates of size >= 2, the largest agglomerate (primaries) and the largest plain
// component's share of the bed (%), against time.
#include <filesystem>
#include <vector>

#include "engine/analysis/agglomerates.hpp"

namespace drumlab::render {

/// Writes the chart of `rows` to `file`. Throws InputError if it cannot be written or there are
/// no rows.
void write_agglomerate_chart(const std::vector<AgglomerateStats>& rows,
                             const std::filesystem::path& file);

}  // namespace drumlab::render
